"""Brownian dynamics with hydrodynamic interactions in an unbounded fluid: ["BDHIOpenBoundary","Cholesky"]
and ["BDHIOpenBoundary","Lanczos"],
    x(t + dt) = x + dt M F + sqrt(2 kT dt) M^{1/2} W,
M the Rotne-Prager-Yamakawa mobility. The mobility is written here independently (rpy_block, from
Zuk, Wajnryb, Mizerski & Szymczak 2014 for unequal radii; Rotne-Prager and Wajnryb et al. 2013 for
equal ones) and checked at temperature 0 through the drift; the noise through its covariance over
many steps from one configuration, which must be 2 kT dt M; free diffusion against kT / (6 pi eta a).

Statistical checks allow a number of standard errors computed from the sample size; every run has a
fixed seed, so the outcome is repeatable."""

import math

import numpy as np
import pytest

import structmd

METHODS = ["Cholesky", "Lanczos"]
TYPES = [["small", 1.0, 0.5, 0.0], ["large", 1.0, 1.0, 0.0], ["flat", 1.0, 0.0, 0.0]]  # name, mass, radius, charge
RADIUS = {row[0]: row[2] for row in TYPES}
VISCOSITY = 0.7
DIRECTION = np.array([0.48, -0.6, 0.64])  # unit vector, no component zero


def rpy_block(d, a_i, a_j, viscosity=VISCOSITY):
    """M_ij for the separation d = r_j - r_i (3 x 3)."""
    r = float(np.linalg.norm(d))
    if r <= abs(a_i - a_j):
        return np.eye(3) / (6.0 * math.pi * viscosity * max(a_i, a_j))
    rr = np.outer(d, d) / r ** 2
    if r > a_i + a_j:
        s = (a_i ** 2 + a_j ** 2) / r ** 2
        return ((1.0 + s / 3.0) * np.eye(3) + (1.0 - s) * rr) / (8.0 * math.pi * viscosity * r)
    f = (16.0 * r ** 3 * (a_i + a_j) - ((a_i - a_j) ** 2 + 3.0 * r ** 2) ** 2) / (32.0 * r ** 3)
    g = 3.0 * ((a_i - a_j) ** 2 - r ** 2) ** 2 / (32.0 * r ** 3)
    return (f * np.eye(3) + g * rr) / (6.0 * math.pi * viscosity * a_i * a_j)


def rpy_matrix(positions, radii):
    n = len(positions)
    m = np.zeros((3 * n, 3 * n))
    for i in range(n):
        for j in range(n):
            m[3 * i:3 * i + 3, 3 * j:3 * j + 3] = rpy_block(positions[j] - positions[i], radii[i], radii[j])
    return m


def test_the_reference_mobility_is_continuous_and_reduces_to_the_equal_radii_forms():
    # The test's own formula: continuous at r = a_i + a_j and r = |a_i - a_j|, and for equal radii the
    # overlapping form is (1 - 9r/32a) I + (3r/32a) r^ r^ over 6 pi eta a (Wajnryb et al. 2013).
    for a_i, a_j in ((0.5, 0.5), (0.5, 1.0), (1.3, 0.4)):
        for r in (a_i + a_j, abs(a_i - a_j)):
            if r == 0.0:
                continue
            below, above = rpy_block(DIRECTION * r * (1 - 1e-9), a_i, a_j), rpy_block(DIRECTION * r * (1 + 1e-9), a_i, a_j)
            assert np.allclose(below, above, rtol=1e-7, atol=1e-12)
    a, r = 0.5, 0.7
    rr = np.outer(DIRECTION, DIRECTION)
    expected = ((1 - 9 * r / (32 * a)) * np.eye(3) + 3 * r / (32 * a) * rr) / (6 * math.pi * VISCOSITY * a)
    assert np.allclose(rpy_block(DIRECTION * r, a, a), expected, rtol=1e-14, atol=0.0)


def integrator(method, time_step, temperature=None, **extra):
    parameters = {"timeStep": time_step, "viscosity": VISCOSITY, **extra}
    if temperature is not None:
        parameters["temperature"] = temperature
    if method == "Lanczos":
        parameters.setdefault("tolerance", 1e-10)
    return {"type": ["BDHIOpenBoundary", method], "parameters": parameters}


def document(positions, types, entry, steps, force_field=None, temperature=1.0, box=40.0, seed=5):
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "bdhi", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], temperature]]},
        },
        "integrator": {"bdhi": entry,
                       "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                    "data": [[1, "bdhi", steps]]}},
        "state": {"labels": ["id", "position"], "data": [[i, [float(c) for c in p]] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": force_field or {}},
    }


def constant_forces(forces):
    """{id: force} as a ["Bond1","ConstantForce"] entry."""
    return {"pull": {"type": ["Bond1", "ConstantForce"], "labels": ["id_i", "force"],
                     "data": [[i, [float(c) for c in f]] for i, f in forces.items()]}}


# (types, separation, hydrodynamicRadius or None): far apart, overlapping, one inside the other
PAIRS = {
    "equal far": (["small", "small"], 1.7, None),
    "equal overlapping": (["small", "small"], 0.6, None),
    "hydrodynamicRadius far": (["small", "large"], 3.1, 1.2),
    "hydrodynamicRadius overlapping": (["small", "large"], 1.9, 1.2),
    "unequal far": (["small", "large"], 2.0, None),
    "unequal overlapping": (["small", "large"], 1.0, None),
    "unequal inside": (["small", "large"], 0.3, None),
}


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("pair", PAIRS)
def test_at_zero_temperature_each_particle_moves_by_the_rpy_mobility_times_the_force(options, method, pair):
    types, separation, hydrodynamic_radius = PAIRS[pair]
    positions = np.array([[0.3, -0.2, 0.1], [0.3, -0.2, 0.1] + separation * DIRECTION])
    force = np.array([0.4, 0.9, -0.3])
    extra = {} if hydrodynamic_radius is None else {"hydrodynamicRadius": hydrodynamic_radius}
    dt = 1e-3
    doc = document(positions, types, integrator(method, dt, temperature=0.0, **extra), 1,
                   force_field=constant_forces({0: force}))
    radii = [hydrodynamic_radius or RADIUS[t] for t in types]
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)
        velocity = (sim.positions - positions) / dt
    mobility = rpy_matrix(positions, radii)
    assert np.allclose(velocity[0], mobility[0:3, 0:3] @ force, rtol=1e-8, atol=0.0), "self mobility"
    assert np.allclose(velocity[1], mobility[3:6, 0:3] @ force, rtol=1e-8, atol=0.0), "pair mobility"


@pytest.mark.parametrize("method", METHODS)
def test_particles_outside_the_group_stay_and_take_no_part_in_the_flow(options, method):
    # Particle 2 (not in the group, and of radius 0) is pushed and sits beside particle 1: it does not
    # move, and the drift of 0 and 1 is that of the pair alone.
    positions = np.array([[0.0, 0.0, 0.0], 1.4 * DIRECTION, 1.4 * DIRECTION + [0.0, 0.0, 0.8]])
    forces = {0: [0.4, 0.9, -0.3], 2: [1.0, 1.0, 1.0]}
    entry = integrator(method, 1e-3, temperature=0.0, group="mobile")
    force_field = constant_forces(forces)
    force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                             "data": [["mobile", "Ids", [0, 1]]]}
    doc = document(positions, ["small", "small", "flat"], entry, 1, force_field=force_field)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)
        velocity = (sim.positions - positions) / 1e-3
    assert np.array_equal(velocity[2], np.zeros(3))
    mobility = rpy_matrix(positions[:2], [0.5, 0.5])
    expected = mobility @ np.concatenate([forces[0], [0.0, 0.0, 0.0]])
    assert np.allclose(velocity[:2].ravel(), expected, rtol=1e-8, atol=0.0)


def displacement_samples(options, method, positions, types, samples, dt, kt, extra=None):
    """One-step displacements from the same configuration, `samples` times (the noise of each step is
    independent of the others')."""
    doc = document(positions, types, integrator(method, dt, temperature=kt, **(extra or {})), samples)
    out = np.empty((samples, 3 * len(positions)))
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        for k in range(samples):
            sim.step(1)
            out[k] = (sim.positions - positions).ravel()
            sim.positions = positions
    return out


@pytest.mark.parametrize("method", METHODS)
def test_the_noise_has_the_covariance_2_kt_dt_m(options, method):
    # Three particles close enough to couple strongly (one pair overlapping), zero force: each step's
    # displacement is N(0, 2 kT dt M). For S samples the sample covariance C_ab has standard error
    # sqrt((C_aa C_bb + C_ab^2) / S); every entry must be within 4.5 of them, and the mean within 4.5
    # standard errors of 0. A wrong factor sqrt(2) in the noise moves the diagonal by 100 standard errors.
    positions = np.array([[0.0, 0.0, 0.0], 0.9 * DIRECTION, [1.2, 0.4, -0.5]])
    types = ["small", "small", "large"]
    samples, dt, kt = 20000, 1e-3, 1.5
    x = displacement_samples(options, method, positions, types, samples, dt, kt)
    expected = 2.0 * kt * dt * rpy_matrix(positions, [RADIUS[t] for t in types])
    covariance = x.T @ x / samples
    diagonal = np.diag(expected)
    error = np.sqrt((np.outer(diagonal, diagonal) + expected ** 2) / samples)
    worst = np.max(np.abs(covariance - expected) / error)
    assert worst < 4.5, f"covariance off by {worst:.1f} standard errors"
    assert np.max(np.abs(x.mean(axis=0)) / np.sqrt(diagonal / samples)) < 4.5
    # The coupling is strong: the off-diagonal blocks are far from zero in the sample too.
    assert abs(covariance[0, 3]) > 20 * error[0, 3]


@pytest.mark.parametrize("method", METHODS)
def test_a_lone_particle_diffuses_with_the_stokes_einstein_coefficient(options, method):
    # D = kT / (6 pi eta a); over windows of t = 20 dt the displacement along each axis is N(0, 2 D t).
    # 4000 windows x 3 axes: 4.5 standard errors of <dx^2 / (2 D t)> are 4.5 sqrt(2 / 12000) = 5.8%.
    dt, window, windows, kt, a = 1e-3, 20, 4000, 1.5, 0.5
    doc = document([[0.0, 0.0, 0.0]], ["small"], integrator(method, dt, temperature=kt), window * windows)
    diffusion = kt / (6.0 * math.pi * VISCOSITY * a)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        trajectory = [sim.positions[0].copy()]
        for _ in range(windows):
            sim.step(window)
            trajectory.append(sim.positions[0].copy())
    steps = np.diff(np.array(trajectory), axis=0) / math.sqrt(2.0 * diffusion * window * dt)
    ratio = np.mean(steps ** 2)
    assert abs(ratio - 1.0) < 4.5 * math.sqrt(2.0 / steps.size), f"<dx^2>/(2 D t) = {ratio}"


@pytest.mark.parametrize("method", METHODS)
def test_a_particle_pushed_through_the_box_edge_keeps_its_unwrapped_separation(options, method):
    # The fluid has no periodic images: the pair's mobility uses the unwrapped separation, so after
    # particle 1 crosses the box edge its partner still feels it 1.5 away, not a box length away.
    box, dt = 6.0, 1e-3
    positions = np.array([[2.2, 0.0, 0.0], [2.99, 0.0, 0.0]])
    push = np.array([200.0, 0.0, 0.0])
    doc = document(positions, ["small", "small"], integrator(method, dt, temperature=0.0), 10,
                   force_field=constant_forces({1: push, 0: push}), box=box)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)
        assert sim.positions[1, 0] < 0.0, "particle 1 must have crossed the edge"
        before = sim.positions.copy()
        sim.step(1)
        velocity = (sim.positions - before) / dt
    unwrapped = before.copy()
    unwrapped[1, 0] += box
    expected = rpy_matrix(unwrapped, [0.5, 0.5]) @ np.concatenate([push, push])
    assert np.allclose(velocity.ravel(), expected, rtol=1e-8, atol=0.0)


BAD = [
    ({"timeStep": 0.01}, r"integrator\.bdhi\.parameters\.viscosity"),
    ({"timeStep": 0.01, "viscosity": -1.0}, r"integrator\.bdhi\.parameters\.viscosity"),
    ({"timeStep": 0.01, "viscosity": 1.0, "hydrodynamicRadius": -0.5}, r"integrator\.bdhi\.parameters\.hydrodynamicRadius"),
    ({"timeStep": 0.01, "viscosity": 1.0, "hydrodynamicRadius": 0.0}, r"integrator\.bdhi\.parameters\.hydrodynamicRadius"),
]


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("parameters,message", BAD)
def test_bad_parameters_name_their_path(options, method, parameters, message):
    doc = document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["small", "small"],
                   {"type": ["BDHIOpenBoundary", method], "parameters": parameters}, 10)
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=message):
            sim.load(doc)


@pytest.mark.parametrize("method", METHODS)
def test_a_particle_without_radius_needs_the_hydrodynamic_radius(options, method):
    entry = {"type": ["BDHIOpenBoundary", method], "parameters": {"timeStep": 0.01, "viscosity": 1.0}}
    doc = document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["small", "flat"], entry, 10)
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"(?s)integrator\.bdhi.*particle id 1.*hydrodynamicRadius"):
            sim.load(doc)
    entry["parameters"]["hydrodynamicRadius"] = 0.5
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["small", "flat"], entry, 10))
        sim.run()


@pytest.mark.parametrize("tolerance", [0.0, -1e-3])
def test_lanczos_needs_a_positive_tolerance(options, tolerance):
    entry = integrator("Lanczos", 0.01, tolerance=tolerance)
    doc = document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["small", "small"], entry, 10)
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"integrator\.bdhi\.parameters\.tolerance"):
            sim.load(doc)


def test_lanczos_with_a_loose_tolerance_still_has_the_covariance_of_m_to_that_tolerance(options):
    # The default tolerance 1e-3 on 12 strongly coupled particles (fewer iterations than 3N = 36): the
    # covariance of the noise is that of M to the statistical error (2% on the diagonal here), which a
    # truncation missing the coupling would exceed.
    rng = np.random.default_rng(4)
    positions = rng.uniform(-1.2, 1.2, (12, 3))
    types = ["small"] * 12
    samples, dt, kt = 6000, 1e-3, 1.0
    x = displacement_samples(options, "Lanczos", positions, types, samples, dt, kt, extra={"tolerance": 1e-3})
    expected = 2.0 * kt * dt * rpy_matrix(positions, [0.5] * 12)
    covariance = x.T @ x / samples
    diagonal = np.diag(expected)
    error = np.sqrt((np.outer(diagonal, diagonal) + expected ** 2) / samples)
    worst = np.max(np.abs(covariance - expected) / error)
    assert worst < 5.0, f"covariance off by {worst:.1f} standard errors"


@pytest.mark.parametrize("method", METHODS)
def test_several_batches_are_refused_since_they_would_share_one_fluid(options, method):
    doc = document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["small", "small"], integrator(method, 0.01), 10)
    doc["topology"]["structure"] = {"labels": ["id", "type", "batchId"], "data": [[0, "small", 0], [1, "small", 1]]}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bdhi\.type: .*batch"):
            sim.load(doc)
    doc["topology"]["structure"]["data"][1][2] = 0
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.run()
