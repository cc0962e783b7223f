"""Magnetism: the state's magnetization and anisotropy, ["External","ConstantMagneticField"] and
["External","ACMagneticField"] (Zeeman energy and torque), ["NonBonded","DipolarMagnetic"] (energy,
forces, torques), the magnetic integrators ["Magnetic","Fixed"] and ["Magnetic","Brownian"] against
the relaxation laws and the Langevin function, the magnetization measures, and the write formats
magnet, xyzm, spm, svvm and svvma read back. Every expected value is computed here from the formulas,
independently of structmd."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import structmd

BOX = 12.0
TYPES = [["A", 1.0, 0.5, 0.0], ["B", 1.0, 0.75, 0.0]]  # name, mass, radius, charge
RADIUS = {row[0]: row[2] for row in TYPES}


def document(positions, types, magnetizations=None, directions=None, anisotropy=None, force_field=None,
             integrators=None, schedule=(), temperature=0.0, steps_section=None, seed=11, box=BOX):
    """magnetizations: [[mx, my, mz, M], ...] (body-frame direction, magnitude)."""
    labels = ["id", "position"]
    columns = []
    for label, values in (("direction", directions), ("magnetization", magnetizations), ("anisotropy", anisotropy)):
        if values is not None:
            labels.append(label)
            columns.append(values)
    rows = []
    for i, position in enumerate(positions):
        row = [i, [float(c) for c in position]]
        for values in columns:
            value = values[i]
            row.append(float(value) if np.ndim(value) == 0 else [float(c) for c in value])
        rows.append(row)
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "magnetism", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], temperature]]},
        },
        "state": {"labels": labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": dict(force_field or {})},
    }
    if integrators:
        doc["integrator"] = dict(integrators, schedule={
            "type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
            "data": [[k + 1, name, steps] for k, (name, steps) in enumerate(schedule)]})
    if steps_section:
        doc["simulationStep"] = steps_section
    return doc


def constant_field(b0, direction):
    return {"type": ["External", "ConstantMagneticField"], "parameters": {"b0": b0, "direction": list(direction)}}


def dipolar(permeability, cutoff):
    return {"type": ["NonBonded", "DipolarMagnetic"],
            "parameters": {"permeability": permeability, "cutOff": cutoff, "condition": "all"}}


NEIGHBOUR_LIST = {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}}


def fixed(time_step, algorithm="LLG_Heun", msat=1.0, damping=0.5, gyro_ratio=2.0):
    return {"type": ["Magnetic", "Fixed"],
            "parameters": {"timeStep": time_step, "msat": msat, "damping": damping, "gyroRatio": gyro_ratio,
                           "magneticIntegrationAlgorithm": algorithm}}


def rotation_matrix(q):
    """R(q), q = [q0, q1, q2, q3] scalar first: the body axes in the lab frame are its columns."""
    a, b, c, d = q
    return np.array([[a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
                     [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
                     [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d]])


def turned(q, theta):
    """q after the lab-frame rotation by the vector theta: exp(theta / 2) q (Hamilton product)."""
    angle = np.linalg.norm(theta)
    w = math.cos(angle / 2)
    v = np.sin(angle / 2) / angle * np.asarray(theta) if angle > 0 else np.zeros(3)
    a, b, c, d = q
    return np.array([w * a - v[0] * b - v[1] * c - v[2] * d, w * b + v[0] * a + v[1] * d - v[2] * c,
                     w * c - v[0] * d + v[1] * a + v[2] * b, w * d + v[0] * c - v[1] * b + v[2] * a])


def random_quaternions(n, rng):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def random_magnetizations(n, rng):
    m = rng.normal(size=(n, 3))
    m /= np.linalg.norm(m, axis=1)[:, None]
    return np.hstack([m, rng.uniform(0.5, 2.0, size=(n, 1))])


def lab_moments(magnetizations, directions):
    return np.array([m[3] * rotation_matrix(q) @ m[:3] for m, q in zip(magnetizations, directions)])


def minimum_image(d, box=BOX):
    return d - box * np.round(d / box)


def dipolar_reference(positions, moments, permeability, cutoff, box=BOX):
    """Energy, forces, torques of point dipoles, each pair once, in numpy."""
    k = permeability / (4 * math.pi)
    n = len(positions)
    energy, forces, torques = 0.0, np.zeros((n, 3)), np.zeros((n, 3))
    for i in range(n):
        for j in range(n):
            if i == j:
                continue
            r = minimum_image(np.asarray(positions[j]) - positions[i], box)
            d = np.linalg.norm(r)
            if d >= cutoff:
                continue
            mi, mj = moments[i], moments[j]
            field_j = k * (3 * r * (mj @ r) / d ** 5 - mj / d ** 3)
            if i < j:
                energy += k * ((mi @ mj) / d ** 3 - 3 * (mi @ r) * (mj @ r) / d ** 5)
            forces[i] += -3 * k / d ** 5 * ((mi @ mj) * r + (mj @ r) * mi + (mi @ r) * mj
                                            - 5 * (mi @ r) * (mj @ r) * r / d ** 2)
            torques[i] += np.cross(mi, field_j)
    return energy, forces, torques


def langevin(x):
    return 1 / math.tanh(x) - 1 / x


# ---- the state's magnetization --------------------------------------------------------------------

def test_moments_are_the_magnitude_times_the_body_direction_turned_by_the_orientation(options):
    rng = np.random.default_rng(1)
    n = 5
    q = random_quaternions(n, rng)
    m = random_magnetizations(n, rng)
    m[:, :3] *= 3.0  # a direction of any length reads as its unit vector
    with structmd.Simulation(options) as sim:
        sim.load(document(rng.uniform(-5, 5, (n, 3)), ["A"] * n, magnetizations=m, directions=q))
        unit = m.copy()
        unit[:, :3] /= np.linalg.norm(m[:, :3], axis=1)[:, None]
        np.testing.assert_allclose(sim.magnetic_moments, lab_moments(unit, q), atol=1e-12)
    with structmd.Simulation(options) as sim:
        sim.load(document([[0, 0, 0]], ["A"]))
        np.testing.assert_array_equal(sim.magnetic_moments, [[0.0, 0.0, 0.0]])


def test_bad_magnetizations_and_terms_without_them_are_input_errors(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"state\.data\[0\]\[2\]\[3\]: the moment's magnitude must be >= 0"):
            sim.load(document([[0, 0, 0]], ["A"], magnetizations=[[0, 0, 1, -1.0]]))
        with pytest.raises(structmd.InputError, match=r"state\.data\[0\]\[2\]: expected a magnetization"):
            sim.load(document([[0, 0, 0]], ["A"], magnetizations=[[0, 0, 1]]))
        with pytest.raises(structmd.InputError,
                           match=r"topology\.forceField\.field\.type: .*the state needs a 'magnetization' column"):
            sim.load(document([[0, 0, 0]], ["A"], force_field={"field": constant_field(1.0, [0, 0, 1])}))
        with pytest.raises(structmd.InputError, match=r"integrator\.llg\.type: .*'magnetization' column"):
            sim.load(document([[0, 0, 0]], ["A"], integrators={"llg": fixed(0.01)}, schedule=[("llg", 1)]))


def test_coincident_dipoles_are_numerical_errors_not_a_dropped_pair(options):
    """Two dipoles on one point have no finite energy; the pair used to be skipped (energy 0, OK)."""
    positions = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
    magnetizations = [[0.0, 0.0, 1.0, 1.0]] * 3
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, ["A"] * 3, magnetizations=magnetizations,
                          force_field={"nl": NEIGHBOUR_LIST, "dipoles": dipolar(1.0, 4.0)}))
        with pytest.raises(structmd.NumericalError):
            sim.energy("dipoles")
        with pytest.raises(structmd.NumericalError):
            sim.forces
        sim.positions = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 1.5], [2.0, 0.0, 0.0]])
        assert np.isfinite(sim.energy("dipoles"))  # the handle lives on once the particles are apart


# ---- the external fields -----------------------------------------------------------------------

def test_zeeman_energy_and_torque_of_a_constant_field(options):
    rng = np.random.default_rng(2)
    n = 6
    q = random_quaternions(n, rng)
    m = random_magnetizations(n, rng)
    b0, direction = 1.7, np.array([0.3, -0.5, 0.8])
    field = b0 * direction  # UAMMD-structured's b0 direction, the direction as given
    with structmd.Simulation(options) as sim:
        sim.load(document(rng.uniform(-5, 5, (n, 3)), ["A"] * n, magnetizations=m, directions=q,
                          force_field={"field": constant_field(b0, direction)}))
        mu = lab_moments(m, q)
        assert sim.energy("field") == pytest.approx(-np.sum(mu @ field), rel=1e-12)
        np.testing.assert_allclose(sim.particle_energies, -(mu @ field), rtol=1e-12)
        np.testing.assert_allclose(sim.torques, np.cross(mu, field), atol=1e-12)
        np.testing.assert_array_equal(sim.forces, np.zeros((n, 3)))
        check_torques_by_rotations(sim, q, "field")


def check_torques_by_rotations(sim, q, term, h=1e-5, rtol=1e-7):
    """The torque is minus the derivative of the energy with respect to a lab-frame rotation of each
    particle: T_a = -(U(exp(h e_a) q) - U(exp(-h e_a) q)) / 2h."""
    torques = sim.torques
    numerical = np.zeros_like(torques)
    for i in range(len(q)):
        for a in range(3):
            energies = []
            for sign in (1, -1):
                moved = q.copy()
                moved[i] = turned(q[i], sign * h * np.eye(3)[a])
                sim.orientations = moved
                energies.append(sim.energy(term))
            numerical[i, a] = -(energies[0] - energies[1]) / (2 * h)
    sim.orientations = q
    scale = np.max(np.abs(torques))
    np.testing.assert_allclose(numerical, torques, rtol=0, atol=rtol * scale)


def test_an_alternating_field_follows_b0_sin_2pi_f_t_plus_phase(options):
    m = [[0.0, 0.6, 0.8, 1.5]]
    b0, frequency, phase, dt = 2.0, 0.7, 0.4, 0.05
    entry = {"type": ["External", "ACMagneticField"],
             "parameters": {"b0": b0, "direction": [0, 0, 1], "frequency": frequency, "phase": phase}}
    with structmd.Simulation(options) as sim:
        # "none": the moment stays as given, only time goes on.
        sim.load(document([[0, 0, 0]], ["A"], magnetizations=m, force_field={"ac": entry},
                          integrators={"still": fixed(dt, algorithm="none")}, schedule=[("still", 20)]))
        for k in range(6):
            t = k * 3 * dt
            b = b0 * math.sin(2 * math.pi * frequency * t + phase)
            assert sim.energy("ac") == pytest.approx(-1.5 * 0.8 * b, rel=1e-12, abs=1e-14)
            np.testing.assert_allclose(sim.torques, [[1.5 * 0.6 * b, 0.0, 0.0]], atol=1e-12)
            sim.step(3)


# ---- dipoles -------------------------------------------------------------------------------------

def dipole_system(rng, n=8):
    """Particles spread over the box, some across its faces, none closer than 1."""
    positions = []
    while len(positions) < n:
        p = rng.uniform(-BOX / 2, BOX / 2, 3)
        p[0] = rng.choice([-BOX / 2 + 0.3, BOX / 2 - 0.3]) if len(positions) < 3 else p[0]
        if all(np.linalg.norm(minimum_image(p - other)) > 1.0 for other in positions):
            positions.append(p)
    return np.array(positions), random_quaternions(n, rng), random_magnetizations(n, rng)


def test_dipolar_energy_forces_and_torques_against_the_point_dipole_formulas(options):
    rng = np.random.default_rng(3)
    positions, q, m = dipole_system(rng)
    permeability, cutoff = 3.0, 4.5
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, ["A"] * len(positions), magnetizations=m, directions=q,
                          force_field={"nl": NEIGHBOUR_LIST, "dipoles": dipolar(permeability, cutoff)}))
        energy, forces, torques = dipolar_reference(positions, lab_moments(m, q), permeability, cutoff)
        # Pairs within the cutoff, some only through a face of the box.
        near = [(i, j) for i in range(len(positions)) for j in range(i)
                if np.linalg.norm(minimum_image(positions[i] - positions[j])) < cutoff]
        assert any(np.linalg.norm(positions[i] - positions[j]) > cutoff for i, j in near)
        assert sim.energy("dipoles") == pytest.approx(energy, rel=1e-12)
        np.testing.assert_allclose(sim.forces, forces, rtol=1e-11, atol=1e-12 * np.max(np.abs(forces)))
        np.testing.assert_allclose(sim.torques, torques, rtol=1e-11, atol=1e-12 * np.max(np.abs(torques)))
        # Newton's third law, and the torques and moments of forces of each pair balance.
        np.testing.assert_allclose(forces.sum(axis=0), 0.0, atol=1e-12 * np.max(np.abs(forces)))


REFERENCE = Path(__file__).resolve().parents[1] / "reference" / "data"


def test_dipolar_terms_match_lammps_lj_cut_dipole_cut(options):
    """tests/reference/make_lammps_reference_dipoles.py: LAMMPS's pair_style lj/cut/dipole/cut with
    epsilon 0 (the dipole-dipole term alone) on 40 dipoles in a periodic box, permeability 4 pi."""
    reference = json.loads((REFERENCE / "dipoles.lammps.json").read_text())
    with structmd.Simulation(options) as sim:
        sim.load(json.loads((REFERENCE / "dipoles.json").read_text()))
        assert sim.energy("dipoles") == pytest.approx(reference["energy"], rel=1e-11)
        np.testing.assert_allclose(sim.particle_energies, reference["particle_energies"], rtol=1e-10, atol=1e-12)
        forces, torques = np.array(reference["forces"]), np.array(reference["torques"])
        np.testing.assert_allclose(sim.forces, forces, rtol=1e-10, atol=1e-11 * np.max(np.abs(forces)))
        np.testing.assert_allclose(sim.torques, torques, rtol=1e-10, atol=1e-11 * np.max(np.abs(torques)))


def test_dipoles_have_no_shifted_form(options):
    entry = dipolar(1.0, 3.0)
    entry["parameters"]["shift"] = True
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"topology\.forceField\.dipoles\.parameters\.shift: .*no shifted form"):
            sim.load(document([[0, 0, 0], [1.5, 0, 0]], ["A", "A"], magnetizations=[[0, 0, 1, 1.0]] * 2,
                              force_field={"nl": NEIGHBOUR_LIST, "dipoles": entry}))


def test_dipolar_forces_and_torques_are_the_energys_derivatives(options):
    rng = np.random.default_rng(4)
    positions, q, m = dipole_system(rng, n=6)
    h = 1e-6
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, ["A"] * len(positions), magnetizations=m, directions=q,
                          force_field={"nl": NEIGHBOUR_LIST, "dipoles": dipolar(2.0, 5.0)}))
        forces = sim.forces
        start = sim.positions
        numerical = np.zeros_like(forces)
        for i in range(len(positions)):
            for a in range(3):
                energies = []
                for sign in (1, -1):
                    moved = start.copy()
                    moved[i, a] += sign * h
                    sim.positions = moved
                    energies.append(sim.energy("dipoles"))
                numerical[i, a] = -(energies[0] - energies[1]) / (2 * h)
        sim.positions = start
        np.testing.assert_allclose(numerical, forces, rtol=0, atol=1e-6 * np.max(np.abs(forces)))
        check_torques_by_rotations(sim, q, "dipoles")


# ---- the magnetic integrators ----------------------------------------------------------------------

def test_llg_relaxation_at_zero_temperature_follows_the_analytic_solution(options):
    """A moment at theta0 from B (along z), no noise, no anisotropy: theta(t) from
    tan(theta/2) = tan(theta0/2) exp(-gamma alpha B t / (1 + alpha^2)), and a precession about B at
    gamma B / (1 + alpha^2)."""
    theta0, phi0 = 2.0, 0.3
    b, gamma, alpha, dt, steps = 1.5, 2.0, 0.5, 1e-3, 1500
    m = [[math.sin(theta0) * math.cos(phi0), math.sin(theta0) * math.sin(phi0), math.cos(theta0), 1.3]]
    with structmd.Simulation(options) as sim:
        sim.load(document([[0, 0, 0]], ["A"], magnetizations=m, force_field={"field": constant_field(b, [0, 0, 1])},
                          integrators={"llg": fixed(dt, damping=alpha, gyro_ratio=gamma)}, schedule=[("llg", steps)]))
        for k in range(1, 4):
            sim.step(steps // 3)
            t = k * (steps // 3) * dt
            rate = gamma * b / (1 + alpha ** 2)
            theta = 2 * math.atan(math.tan(theta0 / 2) * math.exp(-alpha * rate * t))
            phi = phi0 + rate * t
            expected = 1.3 * np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)])
            # Heun's error here is about 2e-5; an Euler step would be off by about 3e-3.
            np.testing.assert_allclose(sim.magnetic_moments[0], expected, atol=1e-4)


def test_llg_euler_converges_at_first_order(options):
    """LLG_Euler is first order in dt: halving dt halves its error at a fixed time."""
    b, gamma, alpha, t_end = 1.0, 1.0, 0.3, 1.0
    m = [[1.0, 0.0, 0.0, 1.0]]
    errors = []
    for dt in (0.01, 0.005):
        with structmd.Simulation(options) as sim:
            steps = round(t_end / dt)
            sim.load(document([[0, 0, 0]], ["A"], magnetizations=m,
                              force_field={"field": constant_field(b, [0, 0, 1])},
                              integrators={"llg": fixed(dt, algorithm="LLG_Euler", damping=alpha, gyro_ratio=gamma)},
                              schedule=[("llg", steps)]))
            sim.step(steps)
            rate = gamma * b / (1 + alpha ** 2)
            theta = 2 * math.atan(math.exp(-alpha * rate * t_end))
            expected = [math.sin(theta) * math.cos(rate * t_end), math.sin(theta) * math.sin(rate * t_end),
                        math.cos(theta)]
            errors.append(np.linalg.norm(sim.magnetic_moments[0] - expected))
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.1)


def test_a_rigid_dipole_turns_into_the_field_as_brownian_rotation_predicts(options):
    """Magnetization fixed in the body ("none"): the particle turns by its torque mu x B with the
    rotational mobility M_r = 1 / (8 pi eta a^3): tan(theta/2) = tan(theta0/2) exp(-M_r mu B t)."""
    theta0, mu, b, eta, dt, steps = 2.5, 1.2, 0.8, 0.2, 5e-4, 6000
    a = RADIUS["B"]
    # The body's x axis carries the moment; the body is turned so that it starts at theta0 from z.
    q0 = turned([1.0, 0.0, 0.0, 0.0], [0.0, theta0 - math.pi / 2, 0.0])
    brownian = {"type": ["Magnetic", "Brownian"],
                "parameters": {"timeStep": dt, "viscosity": eta, "msat": 1.0, "magneticIntegrationAlgorithm": "none"}}
    with structmd.Simulation(options) as sim:
        sim.load(document([[0, 0, 0]], ["B"], magnetizations=[[1, 0, 0, mu]], directions=[q0],
                          force_field={"field": constant_field(b, [0, 0, 1])}, integrators={"rigid": brownian},
                          schedule=[("rigid", steps)]))
        start = sim.magnetic_moments[0]
        assert math.acos(start[2] / mu) == pytest.approx(theta0, rel=1e-12)
        mobility = 1 / (8 * math.pi * eta * a ** 3)
        for k in range(1, 4):
            sim.step(steps // 3)
            t = k * (steps // 3) * dt
            theta = 2 * math.atan(math.tan(theta0 / 2) * math.exp(-mobility * mu * b * t))
            moment = sim.magnetic_moments[0]
            assert math.acos(moment[2] / mu) == pytest.approx(theta, abs=1e-3)
            # The moment turns in its plane with z: the turn is about the y axis.
            assert moment[1] == pytest.approx(0.0, abs=1e-12)


def sample_alignment(sim, equilibration, samples, interval):
    """Mean of m . z over particles for each sample, after the equilibration steps."""
    sim.step(equilibration)
    means = []
    for _ in range(samples):
        sim.step(interval)
        moments = sim.magnetic_moments
        means.append(np.mean(moments[:, 2] / np.linalg.norm(moments, axis=1)))
    return np.array(means)


@pytest.mark.parametrize("integrator", ["Fixed", "Brownian"])
def test_the_mean_alignment_in_a_field_is_the_langevin_function(options, integrator):
    """At temperature T, moments of magnitude M in B have <cos theta> = L(M B / kT), whether they turn
    inside the particles (Neel, stochastic LLG in Stratonovich's sense by Heun) or with them (Brownian
    rotation). The tolerance is four standard errors of the sample means (samples 2 relaxation times
    apart), plus the time-step bias allowance 0.01."""
    n, kT, mu, b = 400, 1.0, 1.0, 2.0
    rng = np.random.default_rng(5)
    m = random_magnetizations(n, rng)
    m[:, 3] = mu
    if integrator == "Fixed":
        entry = fixed(0.005, damping=1.0, gyro_ratio=1.0)  # relaxation rate gamma alpha kT / ((1 + alpha^2) M) = 1/2
        steps = dict(equilibration=2000, samples=25, interval=800)
    else:
        a = RADIUS["A"]
        eta = 1 / (8 * math.pi * a ** 3)  # rotational mobility 1: D_r = kT
        entry = {"type": ["Magnetic", "Brownian"],
                 "parameters": {"timeStep": 0.002, "viscosity": eta, "msat": 1.0,
                                "magneticIntegrationAlgorithm": "none"}}
        steps = dict(equilibration=2000, samples=25, interval=500)
    with structmd.Simulation(options) as sim:
        sim.load(document(np.zeros((n, 3)), ["A"] * n, magnetizations=m, temperature=kT,
                          force_field={"field": constant_field(b, [0, 0, 1])}, integrators={"run": entry},
                          schedule=[("run", 100000)]))
        means = sample_alignment(sim, **steps)
    expected = langevin(mu * b / kT)
    error = np.std(means, ddof=1) / math.sqrt(len(means))
    assert abs(np.mean(means) - expected) < 4 * error + 0.01, (np.mean(means), expected, error)
    assert abs(np.mean(means) - langevin(2 * mu * b / kT)) > 4 * error + 0.01  # the test can tell another x


def test_anisotropy_holds_a_moment_along_the_easy_axis(options):
    """With anisotropy K and no field, a moment starting near the body's z axis relaxes onto it: the
    anisotropy field 2 K / M_s (m . z) z has the moment's z axis as its stable equilibrium."""
    m = [[0.3, 0.0, math.sqrt(1 - 0.09), 1.0], [0.0, -0.4, -math.sqrt(1 - 0.16), 1.0]]
    with structmd.Simulation(options) as sim:
        sim.load(document([[0, 0, 0], [3, 0, 0]], ["A", "A"], magnetizations=m, anisotropy=[2.0, 2.0],
                          integrators={"llg": fixed(0.002, msat=0.5, damping=1.0, gyro_ratio=1.0)},
                          schedule=[("llg", 5000)]))
        sim.step(5000)
        np.testing.assert_allclose(sim.magnetic_moments, [[0, 0, 1], [0, 0, -1]], atol=1e-6)


def test_magnetic_state_continues_from_a_checkpoint_as_without_it(options, tmp_path):
    rng = np.random.default_rng(6)
    n = 10
    m = random_magnetizations(n, rng)
    doc = document(rng.uniform(-5, 5, (n, 3)), ["A"] * n, magnetizations=m, temperature=1.0,
                   force_field={"nl": NEIGHBOUR_LIST, "dipoles": dipolar(1.0, 3.0),
                                "field": constant_field(1.0, [1, 0, 0])},
                   integrators={"llg": fixed(0.01)}, schedule=[("llg", 100)])
    path = str(tmp_path / "state.chk")
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(10)
        sim.save_checkpoint(path)
        sim.step(10)
        continued = sim.magnetic_moments
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.load_checkpoint(path)
        sim.step(10)
        np.testing.assert_array_equal(sim.magnetic_moments, continued)
        assert not np.allclose(continued, lab_moments(m, [[1, 0, 0, 0]] * n))


def test_unknown_algorithms_are_refused_by_name(options):
    m = [[0, 0, 1, 1.0]]
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError,
                           match=r"magneticIntegrationAlgorithm: expected one of none, LLG_Euler, LLG_Heun"):
            sim.load(document([[0, 0, 0]], ["A"], magnetizations=m, integrators={"llg": fixed(0.01, algorithm="RK4")},
                              schedule=[("llg", 1)]))
        without_damping = fixed(0.01)
        del without_damping["parameters"]["damping"]
        with pytest.raises(structmd.InputError, match=r"integrator\.llg\.parameters\.damping: .*damping > 0"):
            sim.load(document([[0, 0, 0]], ["A"], magnetizations=m, integrators={"llg": without_damping},
                              schedule=[("llg", 1)]))


# ---- measures and formats --------------------------------------------------------------------------

def magnetic_run(options, tmp_path, steps_section, steps=6, interval=3, n=5):
    """A rigid-dipole Brownian run in a field at finite temperature; returns, at each firing, the
    API's (positions, radii, types, orientations, moments)."""
    rng = np.random.default_rng(7)
    types = ["A", "B", "A", "B", "A"][:n]
    brownian = {"type": ["Magnetic", "Brownian"],
                "parameters": {"timeStep": 0.01, "viscosity": 0.5, "msat": 1.0, "magneticIntegrationAlgorithm": "none"}}
    doc = document(rng.uniform(-4, 4, (n, 3)), types, magnetizations=random_magnetizations(n, rng),
                   directions=random_quaternions(n, rng), temperature=1.0,
                   force_field={"field": constant_field(1.0, [0, 1, 1])}, integrators={"rigid": brownian},
                   schedule=[("rigid", steps)], steps_section=steps_section)
    frames = []
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        for k in range(steps // interval + 1):
            frames.append((sim.positions, np.array([RADIUS[t] for t in types]),
                           [0 if t == "A" else 1 for t in types], sim.orientations, sim.magnetic_moments))
            if k < steps // interval:
                sim.step(interval)
    return frames


def test_the_magnetization_measures_sum_the_moments(options, tmp_path):
    total, mean = str(tmp_path / "total.dat"), str(tmp_path / "mean.dat")
    steps_section = {
        "total": {"type": ["MagneticMeasure", "MeasureTotalMagnetization"],
                  "parameters": {"intervalStep": 3, "outputFilePath": total}},
        "mean": {"type": ["MagneticMeasure", "MeasureMeanMagnetization"],
                 "parameters": {"intervalStep": 3, "outputFilePath": mean}}}
    frames = magnetic_run(options, tmp_path, steps_section)
    for path, normalise in ((total, False), (mean, True)):
        lines = open(path).read().splitlines()
        assert lines[0] == "#step time Mx My Mz"
        rows = np.array([[float(v) for v in line.split()] for line in lines[1:]])
        assert len(rows) == len(frames)
        for k, (*_, moments) in enumerate(frames):
            expected = moments.sum(axis=0)
            if normalise:
                expected /= np.linalg.norm(moments, axis=1).sum()
            assert rows[k, 0] == 3 * k
            assert rows[k, 1] == pytest.approx(3 * k * 0.01)
            np.testing.assert_allclose(rows[k, 2:], expected, rtol=1e-12, atol=1e-14)


def write_frames(options, tmp_path, output_format):
    base = str(tmp_path / "out")
    steps_section = {"write": {"type": ["WriteStep", "WriteStep"],
                               "parameters": {"intervalStep": 3, "outputFilePath": base,
                                              "outputFormat": output_format}}}
    frames = magnetic_run(options, tmp_path, steps_section)
    return frames, open(f"{base}.{output_format}").read()


def numbers(line):
    return [float(v) for v in line.split()]


def sp_frames(lines):
    frames = []
    for line in lines:
        if line.startswith("#L"):
            frames.append([])
        elif not line.startswith("#"):
            frames[-1].append(numbers(line))
    return frames


def test_magnet_and_xyzm_write_each_moment(options, tmp_path):
    frames, text = write_frames(options, tmp_path, "magnet")
    rows = np.array([numbers(line) for line in text.splitlines()])
    np.testing.assert_allclose(rows, np.vstack([f[4] for f in frames]), rtol=1e-7, atol=1e-7)
    frames, text = write_frames(options, tmp_path, "xyzm")
    rows = np.array([numbers(line) for line in text.splitlines()])
    np.testing.assert_allclose(rows, np.vstack([np.hstack([f[0], f[4]]) for f in frames]), rtol=1e-7, atol=1e-7)


def unit(v):
    return v / np.linalg.norm(v)


def test_spm_marks_each_moment_with_a_small_sphere(options, tmp_path):
    frames, text = write_frames(options, tmp_path, "spm")
    written = sp_frames(text.splitlines())
    assert len(written) == len(frames)
    for (positions, radii, types, _, moments), lines in zip(frames, written):
        assert len(lines) == 2 * len(positions)
        for i, (r, a, t) in enumerate(zip(positions, radii, types)):
            np.testing.assert_allclose(lines[2 * i], [*r, a, t], rtol=1e-7, atol=1e-7)
            np.testing.assert_allclose(lines[2 * i + 1], [*(r + a * unit(moments[i])), a / 5, t + 1],
                                       rtol=1e-7, atol=1e-7)


def test_svvm_draws_an_arrow_through_each_particle_along_its_moment(options, tmp_path):
    frames, text = write_frames(options, tmp_path, "svvm")
    lines = text.splitlines()
    assert lines[0] == "# SPHERE OPACITY 0.6" and sum(line.startswith("# SPHERE") for line in lines) == 1
    written = sp_frames(lines[1:])
    assert len(written) == len(frames)
    for (positions, radii, types, _, moments), block in zip(frames, written):
        for i, (r, a, t) in enumerate(zip(positions, radii, types)):
            u = unit(moments[i])
            np.testing.assert_allclose(block[2 * i], [*r, a, t], rtol=1e-7, atol=1e-7)
            np.testing.assert_allclose(block[2 * i + 1], [*(r - 0.9 * a * u), *(1.8 * a * u), 7 if t == 1 else 1],
                                       rtol=1e-7, atol=1e-7)


def test_svvma_draws_the_moment_and_the_easy_axis(options, tmp_path):
    frames, text = write_frames(options, tmp_path, "svvma")
    written = sp_frames(text.splitlines())
    assert len(written) == len(frames)
    for (positions, radii, types, q, moments), block in zip(frames, written):
        for i, (r, a, t) in enumerate(zip(positions, radii, types)):
            z = rotation_matrix(q[i])[:, 2]
            np.testing.assert_allclose(block[4 * i], [*r, a, t], rtol=1e-7, atol=1e-7)
            np.testing.assert_allclose(block[4 * i + 1], [*r, *(2 * a * unit(moments[i])), 1], rtol=1e-7, atol=1e-7)
            np.testing.assert_allclose(block[4 * i + 2], [*r, *(2 * a * z), 39], rtol=1e-7, atol=1e-7)
            np.testing.assert_allclose(block[4 * i + 3], [*r, *(-2 * a * z), 39], rtol=1e-7, atol=1e-7)


def test_a_magnetic_format_without_magnetization_is_an_input_error(options, tmp_path):
    steps_section = {"write": {"type": ["WriteStep", "WriteStep"],
                               "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "x"),
                                              "outputFormat": "magnet"}}}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"simulationStep\.write\.parameters\.outputFormat: .*magnetization"):
            sim.load(document([[0, 0, 0]], ["A"], steps_section=steps_section))
