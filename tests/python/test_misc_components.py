"""Single components of UAMMD-structured without a family of their own: the rotational alignment bonds
["Bond2","RAP"] and ["Bond2","HarmonicRAP"] (energies against the formula written here from rotation
matrices, forces by central differences across the periodic boundary, torques by small rotations,
tau = -dU/dtheta), and the tabulated fields ["External","ExternalTabulated"] and
["External","PolarizationTabulated"] (an analytic field sampled on the grid comes back, the force is
minus the gradient of the interpolated energy, the interpolation against Peskin's three-point kernel
written here)."""

import json
import math
import os

import numpy as np
import pytest

import structmd

BOX = 8.0


def document(positions, force_field, directions=None, extra_columns=None, units="None", types=None):
    """extra_columns: {label: [value per particle]} appended to the state."""
    extra_columns = extra_columns or {}
    labels = ["id", "position"] + (["direction"] if directions is not None else []) + list(extra_columns)
    rows = []
    for i, p in enumerate(positions):
        row = [i, [float(c) for c in p]]
        if directions is not None:
            row.append([float(c) for c in directions[i]])
        row += [float(column[i]) for column in extra_columns.values()]
        rows.append(row)
    types = types or ["A"] * len(positions)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "misc"}}},
        "global": {
            "units": {"type": ["Units", units]},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 1.0]]},
        },
        "state": {"labels": labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": force_field},
    }


def random_quaternions(n, rng):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def rotation_matrix(q):
    """R(q), q = [q0, q1, q2, q3] scalar first (UAMMD-structured's State documentation): columns are
    the body axes in the lab frame."""
    q0, q1, q2, q3 = q
    return np.array([[1 - 2 * q2 * q2 - 2 * q3 * q3, 2 * q1 * q2 - 2 * q0 * q3, 2 * q1 * q3 + 2 * q0 * q2],
                     [2 * q1 * q2 + 2 * q0 * q3, 1 - 2 * q1 * q1 - 2 * q3 * q3, 2 * q2 * q3 - 2 * q0 * q1],
                     [2 * q1 * q3 - 2 * q0 * q2, 2 * q2 * q3 + 2 * q0 * q1, 1 - 2 * q1 * q1 - 2 * q2 * q2]])


def turned(q, axis, angle):
    """q after a lab-frame rotation by `angle` about unit axis `axis`: (cos a/2; sin a/2 axis) * q."""
    a = np.array([math.cos(angle / 2), *(math.sin(angle / 2) * np.asarray(axis, dtype=float))])
    w0, w = a[0], a[1:]
    p0, p = q[0], np.asarray(q[1:])
    return np.array([w0 * p0 - w @ p, *(w0 * p + p0 * w + np.cross(w, p))])


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


# ---- ["Bond2","RAP"] and ["Bond2","HarmonicRAP"] -------------------------------------------------

N_CHAIN = 6


def chain_positions(rng):
    """A chain whose bonds cross the box face at x = +-L/2."""
    start = np.array([BOX / 2 - 2.0, 0.3, -0.2])
    steps = rng.uniform(-0.3, 0.3, size=(N_CHAIN, 3)) + np.array([0.9, 0.0, 0.0])
    positions = start + np.cumsum(steps, axis=0)
    return minimum_image(positions)


def rap_entry(K, R):
    return {"type": ["Bond2", "RAP"], "labels": ["id_i", "id_j", "K", "R"],
            "data": [[k, k + 1, K[k], list(R[k])] for k in range(N_CHAIN - 1)]}


def harmonic_rap_entry(Khrm, r0, left, right, Krap, R):
    return {"type": ["Bond2", "HarmonicRAP"],
            "labels": ["id_i", "id_j", "Khrm", "r0", "leftConnection", "rightConnection", "Krap", "R"],
            "data": [[k, k + 1, Khrm[k], r0[k], list(left[k]), list(right[k]), Krap[k], list(R[k])]
                     for k in range(N_CHAIN - 1)]}


def rap_energy(q, K, R):
    """sum over bonds of K/4 (3 - tr(A R0 B^T)), as UAMMD-structured writes it: K (3 - Frob(A^T B, R0))/4."""
    total = 0.0
    for k in range(N_CHAIN - 1):
        A, B, R0 = rotation_matrix(q[k]), rotation_matrix(q[k + 1]), rotation_matrix(R[k])
        total += K[k] * (3.0 - np.sum((A.T @ B) * R0)) / 4.0
    return total


def harmonic_rap_energy(x, q, Khrm, r0, left, right, Krap, R):
    total = rap_energy(q, Krap, R)
    for k in range(N_CHAIN - 1):
        a = x[k] + rotation_matrix(q[k]) @ left[k]
        b = x[k + 1] + rotation_matrix(q[k + 1]) @ right[k]
        total += 0.5 * Khrm[k] * (np.linalg.norm(minimum_image(b - a)) - r0[k]) ** 2
    return total


@pytest.fixture
def rap_system():
    rng = np.random.default_rng(11)
    x = chain_positions(rng)
    q = random_quaternions(N_CHAIN, rng)
    K = rng.uniform(5.0, 25.0, N_CHAIN - 1)
    R = random_quaternions(N_CHAIN - 1, rng)
    return x, q, K, R


def numerical_torques(sim, q, name, h=1e-5):
    """tau_i = -dU/dtheta for lab-frame rotations of particle i about each axis, by central differences."""
    torques = np.zeros((len(q), 3))
    for i in range(len(q)):
        for d in range(3):
            axis = np.eye(3)[d]
            energies = []
            for angle in (h, -h):
                moved = q.copy()
                moved[i] = turned(q[i], axis, angle)
                sim.orientations = moved
                energies.append(sim.energy(name))
            torques[i, d] = -(energies[0] - energies[1]) / (2 * h)
    sim.orientations = q
    return torques


def numerical_forces(sim, x, name, h=1e-5):
    forces = np.zeros_like(x)
    for i in range(len(x)):
        for d in range(3):
            energies = []
            for step in (h, -h):
                moved = x.copy()
                moved[i, d] += step
                sim.positions = moved
                energies.append(sim.energy(name))
            forces[i, d] = -(energies[0] - energies[1]) / (2 * h)
    sim.positions = x
    return forces


def test_rap_energy_is_the_alignment_formula_and_it_exerts_no_force(options, rap_system):
    x, q, K, R = rap_system
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"rap": rap_entry(K, R)}, directions=q))
        expected = rap_energy(q, K, R)
        assert expected > 1.0
        assert sim.energy("rap") == pytest.approx(expected, rel=1e-12)
        np.testing.assert_array_equal(sim.forces, 0.0)


def test_rap_torques_are_minus_the_energy_derivative_by_small_rotations(options, rap_system):
    x, q, K, R = rap_system
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"rap": rap_entry(K, R)}, directions=q))
        torques = sim.torques
        numerical = numerical_torques(sim, q, "rap")
        assert np.max(np.abs(numerical)) > 1.0
        error = np.max(np.abs(torques - numerical)) / np.max(np.abs(numerical))
        assert error < 1e-6, error
        # A rotation of the whole system changes nothing: the torques of each bond cancel.
        np.testing.assert_allclose(torques.sum(axis=0), 0.0, atol=1e-12)


def test_rap_is_zero_with_no_torque_at_the_target_relative_rotation(options):
    """B = A R0: every body turned by its bond's target from the one before it."""
    rng = np.random.default_rng(5)
    R = random_quaternions(N_CHAIN - 1, rng)
    q = [random_quaternions(1, rng)[0]]
    for k in range(N_CHAIN - 1):
        # R(q_{k+1}) = R(q_k) R(R_k): the quaternion product q_k * R_k.
        a0, a = q[k][0], q[k][1:]
        b0, b = R[k][0], R[k][1:]
        q.append(np.array([a0 * b0 - a @ b, *(a0 * b + b0 * a + np.cross(a, b))]))
    q = np.array(q)
    with structmd.Simulation(options) as sim:
        sim.load(document(chain_positions(rng), {"rap": rap_entry(np.full(N_CHAIN - 1, 7.0), R)}, directions=q))
        assert abs(sim.energy("rap")) < 1e-12
        np.testing.assert_allclose(sim.torques, 0.0, atol=1e-12)


@pytest.fixture
def harmonic_rap_system(rap_system):
    x, q, K, R = rap_system
    rng = np.random.default_rng(12)
    n = N_CHAIN - 1
    return dict(Khrm=rng.uniform(20.0, 40.0, n), r0=rng.uniform(0.3, 0.6, n), left=rng.uniform(-0.4, 0.4, (n, 3)),
                right=rng.uniform(-0.4, 0.4, (n, 3)), Krap=K, R=R), x, q


def test_harmonic_rap_energy_forces_and_torques(options, harmonic_rap_system):
    p, x, q = harmonic_rap_system
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"hrap": harmonic_rap_entry(**p)}, directions=q))
        expected = harmonic_rap_energy(x, q, **p)
        assert sim.energy("hrap") == pytest.approx(expected, rel=1e-12)
        forces, torques = sim.forces, sim.torques
        numerical = numerical_forces(sim, x, "hrap")
        assert np.max(np.abs(numerical)) > 1.0
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6
        numerical = numerical_torques(sim, q, "hrap")
        assert np.max(np.abs(torques - numerical)) / np.max(np.abs(numerical)) < 1e-6
        np.testing.assert_allclose(forces.sum(axis=0), 0.0, atol=1e-10)


def test_rap_refuses_a_state_without_directions_and_targets_of_other_norms(options, rap_system):
    x, q, K, R = rap_system
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"topology\.forceField\.rap\.type: .*direction"):
            sim.load(document(x, {"rap": rap_entry(K, R)}))
    bad = R.copy()
    bad[2] *= 1.1
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"topology\.forceField\.rap\.data\[2\]\[3\]: .*unit quaternion"):
            sim.load(document(x, {"rap": rap_entry(K, bad)}, directions=q))


def test_rap_bonds_turn_bodies_into_their_target_alignment(options):
    """At zero temperature the rigid-body integrator relaxes a RAP pair to B = A R0 (zero energy)."""
    rng = np.random.default_rng(3)
    R = random_quaternions(1, rng)
    q = random_quaternions(2, rng)
    doc = document([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]],
                   {"rap": {"type": ["Bond2", "RAP"], "labels": ["id_i", "id_j", "K", "R"],
                            "data": [[0, 1, 10.0, list(R[0])]]}}, directions=q)
    doc["global"]["ensemble"]["data"][0][1] = 0.0
    doc["integrator"] = {
        "rigid": {"type": ["Brownian", "EulerMaruyamaRigidBody"], "parameters": {"timeStep": 0.01, "viscosity": 0.1}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "rigid", 1000]]}}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        start = sim.energy("rap")
        sim.run()
        assert start > 1.0
        assert sim.energy("rap") < 1e-8 * start
        A, B = rotation_matrix(sim.orientations[0]), rotation_matrix(sim.orientations[1])
        np.testing.assert_allclose(A.T @ B, rotation_matrix(R[0]), atol=1e-4)


# ---- ["External","ExternalTabulated"], ["External","PolarizationTabulated"] ----------------------

def cell_centres(n):
    h = BOX / n
    return -BOX / 2 + (np.arange(n) + 0.5) * h


def field_entry(function, n, subclass="ExternalTabulated", scale=None, with_force=True, extra=None):
    nx, ny, nz = n
    X, Y, Z = np.meshgrid(cell_centres(nx), cell_centres(ny), cell_centres(nz), indexing="ij")
    E = function(X, Y, Z)
    parameters = {"nx": nx, "ny": ny, "nz": nz, **(extra or {})}
    if scale is not None:
        parameters["scale"] = scale
    labels = ["i", "j", "k", "energy"] + (["force"] if with_force else [])
    data = []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                row = [i, j, k, float(E[i, j, k])]
                if with_force:
                    row.append([0.0, 0.0, 0.0])  # checked, not used: the force is the energy's gradient
                data.append(row)
    return {"type": ["External", subclass], "parameters": parameters, "labels": labels, "data": data}


def peskin(s):
    """Peskin's three-point kernel, written from Roma, Peskin and Berger (1999)."""
    a = np.abs(s)
    inner = (1 + np.sqrt(np.clip(1 - 3 * a * a, 0, None))) / 3
    outer = (5 - 3 * a - np.sqrt(np.clip(1 - 3 * (1 - a) ** 2, 0, None))) / 6
    return np.where(a <= 0.5, inner, np.where(a <= 1.5, outer, 0.0))


def interpolated(function, n, x):
    """The sum over every cell (all images of the periodic grid) of E_c phi phi phi."""
    centres = [cell_centres(m) for m in n]
    weights = []
    for a in range(3):
        h = BOX / n[a]
        s = minimum_image(x[a] - centres[a]) / h
        weights.append(peskin(s))
    X, Y, Z = np.meshgrid(*centres, indexing="ij")
    return float(np.einsum("i,j,k,ijk->", *weights, function(X, Y, Z)))


def periodic_field(X, Y, Z):
    k = 2 * math.pi / BOX
    return np.sin(k * X + 0.3) * np.cos(2 * k * Y) + 0.5 * np.cos(k * Z - 0.7) + 0.2 * np.sin(k * (X + Z))


def random_positions(count, rng, margin=0.0):
    return rng.uniform(-BOX / 2 + margin, BOX / 2 - margin, size=(count, 3))


def test_tabulated_field_is_peskins_three_point_interpolation_with_an_exact_gradient(options):
    rng = np.random.default_rng(2)
    n = (10, 12, 9)
    x = random_positions(12, rng)
    x[:4, 0] = BOX / 2 - rng.uniform(0.0, 0.4, 4)  # within a cell of the x face: the grid wraps
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"field": field_entry(periodic_field, n)}))
        energies = [interpolated(periodic_field, n, p) for p in x]
        assert sim.energy("field") == pytest.approx(sum(energies), rel=1e-12)
        forces = sim.forces
        numerical = numerical_forces(sim, x, "field")
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6


def test_a_linear_and_a_product_field_come_back_exactly_away_from_the_box_faces(options):
    """The three-point kernel reproduces linear functions (its weights sum to one with zero first
    moment), hence x + y + z and x y z, as UAMMD-structured's test fields; more than a cell and a half from
    the faces no cell of the other side contributes."""
    rng = np.random.default_rng(4)
    n = (16, 16, 16)
    x = random_positions(20, rng, margin=1.6 * BOX / 16)
    for function, gradient in [(lambda X, Y, Z: X + Y + Z, lambda p: np.array([1.0, 1.0, 1.0])),
                               (lambda X, Y, Z: X * Y * Z, lambda p: np.array([p[1] * p[2], p[0] * p[2], p[0] * p[1]]))]:
        with structmd.Simulation(options) as sim:
            sim.load(document(x, {"field": field_entry(function, n, scale=1.5)}))
            assert sim.energy("field") == pytest.approx(1.5 * sum(function(*p) for p in x), abs=1e-10)
            np.testing.assert_allclose(sim.forces, [-1.5 * gradient(p) for p in x], atol=1e-10)


def test_a_smooth_field_comes_back_to_the_interpolation_accuracy(options):
    """Second order: the error falls about fourfold as the cells halve."""
    rng = np.random.default_rng(6)
    x = random_positions(30, rng)
    errors = []
    for cells in (16, 32):
        with structmd.Simulation(options) as sim:
            sim.load(document(x, {"field": field_entry(periodic_field, (cells,) * 3, with_force=False)}))
            errors.append(abs(sim.energy("field") - sum(periodic_field(*p) for p in x)) / len(x))
    assert errors[1] < 0.02
    assert errors[0] / errors[1] > 3.0


def test_polarization_field_is_scaled_by_eps_times_each_polarizability(options):
    rng = np.random.default_rng(8)
    n = (8, 8, 8)
    x = random_positions(6, rng)
    alpha = rng.uniform(0.5, 2.0, len(x))
    eps_r = 78.0
    f = 332.0716  # kcal A / (mol e^2), UAMMD-structured's KcalMol_A electric conversion factor
    entry = field_entry(periodic_field, n, subclass="PolarizationTabulated", scale=2.0,
                        extra={"dielectricConstant": eps_r})
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"pol": entry}, extra_columns={"polarizability": alpha}, units="KcalMol_A"))
        per_particle = [2.0 * eps_r / (4 * math.pi * f) * a * interpolated(periodic_field, n, p)
                        for a, p in zip(alpha, x)]
        assert sim.energy("pol") == pytest.approx(sum(per_particle), rel=1e-12)
        forces = sim.forces
        numerical = numerical_forces(sim, x, "pol")
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6


def test_polarization_field_without_a_dielectric_constant_is_scaled_by_the_polarizability_alone(options):
    """UAMMD-structured's current source and generators: no dielectricConstant, U_i = alpha_i U_tab."""
    rng = np.random.default_rng(9)
    n = (8, 8, 8)
    x = random_positions(5, rng)
    alpha = rng.uniform(0.5, 2.0, len(x))
    entry = field_entry(periodic_field, n, subclass="PolarizationTabulated", scale=3.0)
    assert "dielectricConstant" not in entry["parameters"]
    with structmd.Simulation(options) as sim:
        sim.load(document(x, {"pol": entry}, extra_columns={"polarizability": alpha}, units="KcalMol_A"))
        expected = sum(3.0 * a * interpolated(periodic_field, n, p) for a, p in zip(alpha, x))
        assert sim.energy("pol") == pytest.approx(expected, rel=1e-12)


def test_polarization_field_takes_the_polarizability_of_polarizable_types(options):
    """["Types","Polarizable"]: without a state column, each particle's alpha is its type's."""
    rng = np.random.default_rng(10)
    n = (8, 8, 8)
    x = random_positions(4, rng)
    type_alpha = {"A": 1.5, "B": 0.25}
    types = ["A", "B", "B", "A"]
    doc = document(x, {"pol": field_entry(periodic_field, n, subclass="PolarizationTabulated")}, types=types)
    doc["global"]["types"] = {"type": ["Types", "Polarizable"],
                              "labels": ["name", "mass", "radius", "charge", "polarizability"],
                              "data": [[name, 1.0, 0.5, 0.0, alpha] for name, alpha in type_alpha.items()]}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        expected = sum(type_alpha[t] * interpolated(periodic_field, n, p) for t, p in zip(types, x))
        assert sim.energy("pol") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name, polarizability_column", [("External-ExternalTabulated.json", None),
                                                          ("External-PolarizationTabulated.json", 2)])
def test_uammd_structured_inputs_give_the_energies_their_analysis_expects(options, name, polarizability_column):
    """UAMMD-structured's own generators tabulate x y z (its tests' analysis.py expects each particle's
    energy to be x y z scale, times its polarizability for the polarization field, within 1e-4)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference", "uammd_inputs", name)
    with open(path) as f:
        doc = json.load(f)
    scale = doc["topology"]["forceField"]["ExTab"]["parameters"]["scale"]
    rows = doc["state"]["data"]
    x = np.array([row[1] for row in rows])
    factor = np.array([row[polarizability_column] for row in rows]) if polarizability_column else 1.0
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.compute(forces=True, energy=True)
        np.testing.assert_allclose(sim.particle_energies, x[:, 0] * x[:, 1] * x[:, 2] * scale * factor,
                                   rtol=0, atol=1e-10)


@pytest.mark.parametrize("change, path, message", [
    (lambda e: e["data"].pop(), r"field\.data", "one row per cell"),
    (lambda e: e["data"][3].__setitem__(2, 0), r"field\.data\[3\]", "listed twice"),
    (lambda e: e["data"][5].__setitem__(2, 4), r"field\.data\[5\]\[2\]", "outside 0..3"),
    (lambda e: e["parameters"].__setitem__("nx", 0), r"field\.parameters\.nx", ""),
])
def test_tabulated_field_input_errors_name_the_culprit(options, change, path, message):
    entry = field_entry(periodic_field, (4, 4, 4))
    change(entry)
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=path + ".*" + message):
            sim.load(document([[0.0, 0.0, 0.0]], {"field": entry}))


def test_polarization_field_needs_the_polarizability_column(options):
    entry = field_entry(periodic_field, (4, 4, 4), subclass="PolarizationTabulated", extra={"dielectricConstant": 2.0})
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"forceField\.pol\.type: .*polarizability"):
            sim.load(document([[0.0, 0.0, 0.0]], {"pol": entry}))


# ---- ["AFM","SphericallyBluntedConicTip"] --------------------------------------------------------

TIP_RADIUS = 0.5


def conic_document(positions, epsilon, sigma, angle, K=3.0, Kxy=2.0, chip=(0.3, -0.2, 3.0)):
    """Particle 0 is the tip (radius TIP_RADIUS), near the x face; the others its sample."""
    n = len(positions)
    doc = document(positions, {"AFM": {
        "type": ["AFM", "SphericallyBluntedConicTip"],
        "labels": ["idSet_i", "idSet_j", "epsilon", "sigma", "tipAngle", "K", "Kxy", "tipVelocity",
                   "startChipPosition", "indentationStartStep"],
        "data": [[[0], list(range(1, n)), epsilon, sigma, angle, K, Kxy, -0.1, list(chip), 0]]}})
    doc["global"]["types"]["data"][0][2] = TIP_RADIUS
    doc["integrator"] = {
        "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "vv", 10]]}}
    return doc


def distance_to_blunted_cone(d, angle):
    """The distance from d (relative to the sphere's centre) to the tip's surface, by densely sampling
    its profile in the (rho, z) half-plane: the arc of the sphere below the circle where the cone
    touches it, then the cone's side."""
    rho, z = math.hypot(d[0], d[1]), d[2]
    phi = np.linspace(0.0, math.pi / 2 - angle, 200001)  # from the bottom of the sphere up to the circle
    arc = np.stack([TIP_RADIUS * np.sin(phi), -TIP_RADIUS * np.cos(phi)], axis=1)
    touch = arc[-1]
    u = np.linspace(0.0, 20.0, 400001)
    side = touch + u[:, None] * np.array([math.sin(angle), math.cos(angle)])
    profile = np.concatenate([arc, side])
    return float(np.min(np.hypot(profile[:, 0] - rho, profile[:, 1] - z)))


def conic_positions():
    tip = np.array([BOX / 2 - 0.2, 0.1, 0.4])
    sample = [tip + np.array(offset) for offset in
              [[0.1, 0.2, -1.3], [0.6, -0.3, -0.9], [-1.2, 0.4, 0.3], [1.2, 1.1, 1.5], [-0.3, -1.4, 0.2]]]
    return minimum_image(np.array([tip] + sample))


def test_conic_tip_energy_is_the_wall_at_the_distance_to_the_surface(options):
    x = conic_positions()
    epsilon, sigma, angle = 0.7, 0.6, 0.4
    K, Kxy, chip = 3.0, 2.0, np.array([0.3, -0.2, 3.0])
    with structmd.Simulation(options) as sim:
        sim.load(conic_document(x, epsilon, sigma, angle, K, Kxy, chip))
        expected = 0.0
        for p in x[1:]:
            g = distance_to_blunted_cone(minimum_image(p - x[0]), angle)
            expected += epsilon * (sigma / g) ** 12
        spring = minimum_image(chip - x[0])
        expected += 0.5 * (Kxy * (spring[0] ** 2 + spring[1] ** 2) + K * spring[2] ** 2)
        assert sim.energy("AFM") == pytest.approx(expected, rel=1e-7)


def test_conic_tip_force_is_minus_the_energy_gradient_on_the_cap_and_the_side(options):
    x = conic_positions()
    angle = 0.4
    regions = {"cap": 0, "side": 0}
    for p in x[1:]:
        d = minimum_image(p - x[0])
        regions["side" if math.hypot(d[0], d[1]) * math.sin(angle) + d[2] * math.cos(angle) > 0 else "cap"] += 1
    assert regions["cap"] >= 2 and regions["side"] >= 2, regions
    with structmd.Simulation(options) as sim:
        sim.load(conic_document(x, 0.7, 0.6, angle))
        forces = sim.forces
        numerical = numerical_forces(sim, x, "AFM")
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6


def test_conic_tip_angle_must_be_below_a_right_angle(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"AFM\.data\[0\].*tipAngle"):
            sim.load(conic_document(conic_positions(), 0.7, 0.6, 1.6))


# ---- ["NonBonded","StericInner6"], ["NonBonded","StericInner12"] ---------------------------------

def steric_inner_entry(n, epsilon, factor, shift=False):
    return {"nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
            "inner": {"type": ["NonBonded", f"StericInner{n}"],
                      "parameters": {"epsilon": epsilon, "cutOffFactor": factor, "condition": "all", "shift": shift}}}


def inner_configuration(rng, count=14):
    """Particles around the x face, no two closer than 0.6 (minimum image)."""
    positions = []
    while len(positions) < count:
        p = rng.uniform(-1.5, 1.5, 3)
        p[0] += BOX / 2
        p = minimum_image(p)
        if all(np.linalg.norm(minimum_image(p - q)) > 0.6 for q in positions):
            positions.append(p)
    return np.array(positions)


def steric_inner_energy(x, a, n, epsilon, factor, shift):
    total = 0.0
    for i in range(len(x)):
        for j in range(i + 1, len(x)):
            r = np.linalg.norm(minimum_image(x[j] - x[i]))
            s = a[i] + a[j]
            if r < factor * s:
                total += epsilon * ((s / r) ** n - (factor ** -n if shift else 0.0))
    return total


@pytest.mark.parametrize("n", [6, 12])
@pytest.mark.parametrize("shift", [False, True])
def test_steric_inner_energy_and_forces(options, n, shift):
    rng = np.random.default_rng(20 + n)
    x = inner_configuration(rng)
    a = rng.uniform(0.2, 0.45, len(x))
    epsilon, factor = 0.8, 2.0
    with structmd.Simulation(options) as sim:
        sim.load(document(x, steric_inner_entry(n, epsilon, factor, shift), extra_columns={"innerRadius": a}))
        expected = steric_inner_energy(x, a, n, epsilon, factor, shift)
        assert sim.energy("inner") == pytest.approx(expected, rel=1e-12)
        # Some pairs are inside their own cutoff and others only inside the list's (the two largest radii).
        forces = sim.forces
        numerical = numerical_forces(sim, x, "inner")
        assert np.max(np.abs(numerical)) > 0.0
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6


def test_steric_inner_sizes_pairs_by_inner_radii_not_type_radii(options):
    """Two particles 1.5 apart, inner radii 0.5 and 0.25 (s = 0.75), type radius 0.5: U = eps (0.75/1.5)^6."""
    x = [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]]
    with structmd.Simulation(options) as sim:
        sim.load(document(x, steric_inner_entry(6, 2.0, 2.5), extra_columns={"innerRadius": [0.5, 0.25]}))
        assert sim.energy("inner") == pytest.approx(2.0 * 0.5 ** 6, rel=1e-14)


def test_steric_inner_needs_the_inner_radius_column(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"forceField\.inner\.type: .*innerRadius"):
            sim.load(document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], steric_inner_entry(6, 1.0, 2.0)))


# ---- ["Surface","Absorbed"] ----------------------------------------------------------------------

def test_absorbed_ties_the_particles_starting_below_the_threshold_to_where_they_started(options):
    rng = np.random.default_rng(30)
    start = random_positions(10, rng)
    start[:3, 0] = BOX / 2 - 0.05  # springs that cross the x face once the particles move
    K, threshold = 4.0, 0.5
    absorbed = start[:, 2] < threshold
    assert 2 <= absorbed.sum() <= 8
    entry = {"absorbed": {"type": ["Surface", "Absorbed"], "parameters": {"K": K, "heightThreshold": threshold}}}
    with structmd.Simulation(options) as sim:
        sim.load(document(start, entry))
        moved = minimum_image(start + rng.uniform(-0.3, 0.3, start.shape))
        sim.positions = moved
        d = minimum_image(start - moved)
        assert sim.energy("absorbed") == pytest.approx(0.5 * K * np.sum(d[absorbed] ** 2), rel=1e-12)
        forces = sim.forces
        np.testing.assert_allclose(forces[absorbed], K * d[absorbed], rtol=1e-12, atol=1e-14)
        np.testing.assert_array_equal(forces[~absorbed], 0.0)
        numerical = numerical_forces(sim, moved, "absorbed")
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6


# ---- ["NonBonded","Zhang"] -----------------------------------------------------------------------

ZHANG_RADIUS = 0.5


def zhang_entry(epsilon=1.2, mu=3.0, chi=2.0, theta=0.3, axis=None):
    parameters = {"condition": "all"}
    if axis is not None:
        parameters["axis"] = axis
    return {"nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
            "zhang": {"type": ["NonBonded", "Zhang"], "parameters": parameters,
                      "labels": ["name_i", "name_j", "radius", "epsilon", "mu", "chi", "theta"],
                      "data": [["A", "A", ZHANG_RADIUS, epsilon, mu, chi, theta]]}}


def zhang_energy(x, q, epsilon, mu, chi, theta, axis=(0.0, 0.0, 1.0)):
    """Yuan et al. (2010) as UAMMD-structured writes it, r = r_j - r_i."""
    rb, rc = 2 ** (7 / 6) * ZHANG_RADIUS, 5.2 * ZHANG_RADIUS
    n = [rotation_matrix(qi) @ np.asarray(axis) for qi in q]
    s = math.sin(theta)
    total = 0.0
    for i in range(len(x)):
        for j in range(i + 1, len(x)):
            r = minimum_image(x[j] - x[i])
            d = np.linalg.norm(r)
            if d >= rc:
                continue
            u = r / d
            a = np.cross(n[i], u) @ np.cross(n[j], u) - s * (n[j] - n[i]) @ u - s * s
            phi = 1 + mu * (a - 1)
            if d < rb:
                total += epsilon * ((rb / d) ** 4 - 2 * (rb / d) ** 2) + (1 - phi) * epsilon
            else:
                total += -epsilon * math.cos(math.pi / 2 * (d - rb) / (rc - rb)) ** (2 * chi) * phi
    return total


def zhang_configuration(rng, count=12):
    """A patch of membrane across the x face: neighbours both inside r_b (1.12) and beyond it."""
    positions = []
    while len(positions) < count:
        p = np.array([BOX / 2 + rng.uniform(-1.8, 1.8), rng.uniform(-1.8, 1.8), rng.uniform(-0.4, 0.4)])
        p = minimum_image(p)
        if all(np.linalg.norm(minimum_image(p - other)) > 0.8 for other in positions):
            positions.append(p)
    return np.array(positions)


def test_zhang_energy_forces_and_torques(options):
    rng = np.random.default_rng(40)
    x = zhang_configuration(rng)
    q = random_quaternions(len(x), rng)
    axis = np.array([0.3, -0.4, 0.0])
    axis[2] = math.sqrt(1 - axis @ axis)
    with structmd.Simulation(options) as sim:
        sim.load(document(x, zhang_entry(axis=list(axis)), directions=q))
        expected = zhang_energy(x, q, 1.2, 3.0, 2.0, 0.3, axis)
        assert sim.energy("zhang") == pytest.approx(expected, rel=1e-12)
        forces, torques = sim.forces, sim.torques
        numerical = numerical_forces(sim, x, "zhang")
        assert np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical)) < 1e-6
        numerical = numerical_torques(sim, q, "zhang")
        assert np.max(np.abs(numerical)) > 0.1
        assert np.max(np.abs(torques - numerical)) / np.max(np.abs(numerical)) < 1e-6


def test_zhang_pairs_reach_both_branches(options):
    """Two parallel directors along z, side by side along x, theta = 0: a = 1 and phi = 1, so the
    energy is the Lennard-Jones-like well inside r_b and -eps cos^(2 chi) beyond."""
    rb, rc = 2 ** (7 / 6) * ZHANG_RADIUS, 5.2 * ZHANG_RADIUS
    for d, expected in [(1.0, 1.5 * ((rb / 1.0) ** 4 - 2 * (rb / 1.0) ** 2)),
                        (2.0, -1.5 * math.cos(math.pi / 2 * (2.0 - rb) / (rc - rb)) ** 4)]:
        with structmd.Simulation(options) as sim:
            sim.load(document([[0.0, 0.0, 0.0], [d, 0.0, 0.0]], zhang_entry(epsilon=1.5, theta=0.0),
                              directions=[[1.0, 0.0, 0.0, 0.0]] * 2))
            assert sim.energy("zhang") == pytest.approx(expected, rel=1e-12)


def test_zhang_needs_directions_and_a_unit_axis(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"forceField\.zhang\.type: .*direction"):
            sim.load(document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], zhang_entry()))
        with pytest.raises(structmd.InputError, match=r"forceField\.zhang\.parameters\.axis: .*unit"):
            sim.load(document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], zhang_entry(axis=[0.0, 0.0, 2.0]),
                              directions=[[1.0, 0.0, 0.0, 0.0]] * 2))


# ---- second derivatives --------------------------------------------------------------------------

def analytical_hessian(sim_options, doc, path, n):
    """The Analytical HessianMeasure's first firing, as a 3n x 3n matrix, and the positions it was at."""
    doc["integrator"] = {
        "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "vv", 1]]}}
    doc["simulationStep"] = {"h": {"type": ["MechanicalMeasure", "HessianMeasure"],
                                   "parameters": {"intervalStep": 1, "outputFilePath": str(path),
                                                  "mode": "Analytical", "outputPrecision": 14}}}
    hessian = np.zeros((3 * n, 3 * n))
    with structmd.Simulation(sim_options) as sim:
        sim.load(doc)
        sim.step(1)
    for line in path.read_text().splitlines()[2:]:
        if line.startswith("#"):
            break
        values = line.split()
        i, j = int(values[0]), int(values[1])
        hessian[3 * i:3 * i + 3, 3 * j:3 * j + 3] = np.array([float(v) for v in values[2:]]).reshape(3, 3)
    return hessian


def force_differences(sim_options, doc, x, h=1e-5):
    n = len(x)
    hessian = np.zeros((3 * n, 3 * n))
    with structmd.Simulation(sim_options) as sim:
        sim.load(doc)
        for i in range(n):
            for a in range(3):
                moved = x.copy()
                moved[i, a] += h
                sim.positions = moved
                forward = sim.forces.reshape(-1)
                moved[i, a] -= 2 * h
                sim.positions = moved
                hessian[3 * i + a] = -(forward - sim.forces.reshape(-1)) / (2 * h)
    return hessian


def test_steric_inner_and_absorbed_have_exact_second_derivatives(options, tmp_path):
    rng = np.random.default_rng(50)
    x = inner_configuration(rng, count=8)
    a = rng.uniform(0.25, 0.45, len(x))
    force_field = dict(steric_inner_entry(12, 0.8, 2.0),
                       absorbed={"type": ["Surface", "Absorbed"], "parameters": {"K": 3.0, "heightThreshold": 0.0}})
    doc = document(x, force_field, extra_columns={"innerRadius": a})
    reference = force_differences(options, json.loads(json.dumps(doc)), x)
    analytical = analytical_hessian(options, doc, tmp_path / "h.dat", len(x))
    scale = np.max(np.abs(reference))
    assert scale > 0.0
    assert np.max(np.abs(analytical - reference)) < 1e-6 * scale


@pytest.mark.parametrize("entry", ["rap", "field", "zhang"])
def test_terms_without_second_derivatives_are_refused_by_name_in_the_analytical_mode(options, tmp_path, entry):
    rng = np.random.default_rng(51)
    x = chain_positions(rng)
    q = random_quaternions(N_CHAIN, rng)
    force_field = {"rap": {"rap": rap_entry(np.full(N_CHAIN - 1, 5.0), random_quaternions(N_CHAIN - 1, rng))},
                   "field": {"field": field_entry(periodic_field, (4, 4, 4))},
                   "zhang": zhang_entry()}[entry]
    with pytest.raises(structmd.StructmdError, match=f"'{'zhang' if entry == 'zhang' else entry}'"):
        analytical_hessian(options, document(x, force_field, directions=q), tmp_path / "h.dat", len(x))
