"""["Magnetic","ForceCouplingMethod"]: magnetic particles that move and turn through a triply periodic
Stokes fluid by the force coupling method with rotation (docs/input-format.md).

References, written here independently of the engine: the lattice sums over wave vectors of the
method's two Gaussians (forces: width sigma = a / sqrt(pi); torques: sigma_t = a / (6 sqrt(pi))^(1/3)),
  rotation by a torque:         (1/(4 eta V)) sum_{k != 0} exp(-k^2 sigma_t^2) (I - k k^T/k^2) T
  translation by a torque at r: -(1/(2 eta V)) sum_{k != 0} exp(-k^2 (sigma^2 + sigma_t^2)/2) sin(k.r) (k x T)/k^2
and their continuum limits: the Stokes rotational mobility 1/(8 pi eta a^3) less its k = 0 term,
(1 - (4 pi / 3) (a/L)^3) / (8 pi eta a^3) in a cubic box of side L, and the rotlet T x r / (8 pi eta r^3).
Torques come from a constant magnetic field on a moment, T = mu x B; forces from the external forces.
"""

import math

import numpy as np
import pytest

import structmd
from periodic_rpy import ETA, RADIUS, document, hasimoto, minimum_image
from periodic_rpy import measured_mobility as measured_entry_mobility

SIGMA = RADIUS / math.sqrt(math.pi)
SIGMA_T = RADIUS / (6.0 * math.sqrt(math.pi)) ** (1.0 / 3.0)
ROTATIONAL_MU0 = 1.0 / (8.0 * math.pi * ETA * RADIUS ** 3)


def fcm(time_step=0.01, tolerance=1e-4, algorithm="none", **extra):
    parameters = {"timeStep": time_step, "viscosity": ETA, "hydrodynamicRadius": RADIUS, "tolerance": tolerance,
                  "msat": 1.0, "magneticIntegrationAlgorithm": algorithm, **extra}
    return {"type": ["Magnetic", "ForceCouplingMethod"], "parameters": parameters}


def magnetic_document(positions, box, entry, moments, field, temperature=0.0, steps=10 ** 6, directions=None):
    """periodic_rpy's document with a body-frame moment [mx, my, mz, M] per particle (all at the
    identity unless `directions`) in a constant field `field` (a vector)."""
    doc = document(positions, box, entry, steps=steps, temperature=temperature)
    labels = ["id", "position", "direction", "magnetization"]
    quaternions = directions if directions is not None else [[1.0, 0.0, 0.0, 0.0]] * len(positions)
    doc["state"] = {"labels": labels,
                    "data": [[i, [float(c) for c in p], [float(c) for c in q], [float(c) for c in m]]
                             for i, (p, q, m) in enumerate(zip(positions, quaternions, moments))]}
    strength = float(np.linalg.norm(field))
    if strength > 0:
        doc["topology"]["forceField"]["field"] = {
            "type": ["External", "ConstantMagneticField"],
            "parameters": {"b0": strength, "direction": [float(c) / strength for c in field]}}
    return doc


def rotation_vectors(before, after):
    """The lab-frame rotation vectors theta with after = exp(theta / 2) before (quaternions scalar first)."""
    out = []
    for q, p in zip(before, after):
        a, b, c, d = p
        w, x, y, z = q[0], -q[1], -q[2], -q[3]  # q^-1
        r = np.array([a * w - b * x - c * y - d * z, a * x + b * w + c * z - d * y,
                      a * y - b * z + c * w + d * x, a * z + b * y - c * x + d * w])
        if r[0] < 0:
            r = -r
        norm = np.linalg.norm(r[1:])
        angle = 2.0 * math.atan2(norm, r[0])
        out.append(r[1:] * (angle / norm) if norm > 0 else np.zeros(3))
    return np.array(out)


def one_step(options, doc, time_step, external_forces=None):
    """(velocities, angular velocities, torques) of one deterministic step."""
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        start, turned_from = sim.positions, sim.orientations
        torques = sim.torques
        if external_forces is not None:
            sim.external_forces = external_forces
        sim.step(1)
        box = np.asarray(doc["global"]["ensemble"]["data"][0][0], float)
        velocities = minimum_image(sim.positions - start, box) / time_step
        angular = rotation_vectors(turned_from, sim.orientations) / time_step
    return velocities, angular, torques


def wave_vectors(length, width):
    cut = math.sqrt(36.0 * math.log(10.0)) / width
    m = int(math.ceil(cut * length / (2 * math.pi)))
    axis = 2 * math.pi * np.arange(-m, m + 1) / length
    waves = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), -1).reshape(-1, 3)
    k2 = (waves * waves).sum(1)
    keep = (k2 > 0) & (k2 < cut * cut)
    return waves[keep], k2[keep]


def rotational_lattice_sum(torque, length):
    waves, k2 = wave_vectors(length, SIGMA_T)
    weight = np.exp(-k2 * SIGMA_T ** 2) / (4.0 * ETA * length ** 3)
    along = waves @ torque / k2
    return (weight[:, None] * (torque[None, :] - along[:, None] * waves)).sum(0)


def torque_flow_lattice_sum(torque, r, length):
    waves, k2 = wave_vectors(length, SIGMA_T)
    weight = -np.exp(-k2 * (SIGMA ** 2 + SIGMA_T ** 2) / 2) * np.sin(waves @ r) / k2 / (2.0 * ETA * length ** 3)
    return (weight[:, None] * np.cross(waves, torque)).sum(0)


# ---- deterministic mobilities ---------------------------------------------------------------------

@pytest.mark.parametrize("length", [8.0, 12.0, 20.0])
def test_a_torque_turns_one_particle_at_the_periodic_stokes_rate(options, length):
    """T = mu x B on one particle. The Gaussian's lattice sum differs from (1 - (4 pi/3)(a/L)^3) mu_r0
    by terms of order exp(-(2 pi sigma_t / L)^2 ...) from the k = 0 gap only, below 1e-12 here; the grid
    adds an error of the order of the tolerance (1e-4): 5e-4 bounds it. The torque does not move the
    particle it turns."""
    time_step = 0.01
    doc = magnetic_document([[0.37, -1.21, 2.05]], length, fcm(time_step), [[1.0, 0.0, 0.0, 2.0]], [0.0, 0.6, 0.9])
    velocities, angular, torques = one_step(options, doc, time_step)
    torque = torques[0]
    assert torque[0] == pytest.approx(0.0, abs=1e-12) and np.linalg.norm(torque) > 1.0
    expected = (1.0 - 4.0 * math.pi / 3.0 * (RADIUS / length) ** 3) * ROTATIONAL_MU0 * torque
    np.testing.assert_allclose(rotational_lattice_sum(torque, length), expected, rtol=1e-9, atol=1e-12)
    assert np.linalg.norm(angular[0] - expected) < 5e-4 * np.linalg.norm(expected)
    assert np.linalg.norm(velocities[0]) < 1e-4 * ROTATIONAL_MU0 * RADIUS * np.linalg.norm(torque)


def test_the_rotational_mobility_tends_to_stokes_as_the_box_grows(options):
    """(omega / T) (8 pi eta a^3) - 1 against -(4 pi / 3)(a/L)^3: the periodic correction shrinks as L^-3."""
    time_step = 0.01
    deficits = []
    for length in (6.0, 10.0, 16.0):
        doc = magnetic_document([[0.0, 0.0, 0.0]], length, fcm(time_step), [[0.0, 0.0, 1.0, 1.0]], [1.0, 0.0, 0.0])
        _, angular, torques = one_step(options, doc, time_step)
        deficits.append(angular[0] @ torques[0] / (torques[0] @ torques[0]) / ROTATIONAL_MU0 - 1.0)
    for length, deficit in zip((6.0, 10.0, 16.0), deficits):
        assert deficit == pytest.approx(-4.0 * math.pi / 3.0 * (RADIUS / length) ** 3, abs=3e-4)
    assert abs(deficits[0]) > abs(deficits[1]) > abs(deficits[2])


@pytest.mark.parametrize("length", [8.0, 16.0])
def test_a_force_moves_one_particle_with_hasimotos_mobility_and_does_not_turn_it(options, length):
    """The translation is ["BDHITriplyPeriodic","ForceCouplingMethod"]'s (Hasimoto's mobility to 1e-3:
    the Gaussian's (a/L)^3 coefficient is 4, a sphere's 4 pi/3, and the grid adds 1e-4)."""
    position = [[0.1, -0.7, 1.3]]
    mobility = measured_entry_mobility(options, position, length, fcm(), 0.01)
    for axis in range(3):
        assert mobility[axis, axis] == pytest.approx(hasimoto(RADIUS, length), rel=1e-3)
    assert np.max(np.abs(mobility - np.diag(np.diag(mobility)))) < 1e-4 * mobility[0, 0]
    doc = magnetic_document(position, length, fcm(), [[1.0, 0.0, 0.0, 0.0]], [0.0, 0.0, 0.0])
    force = np.array([[0.3, -1.0, 0.6]])
    _, angular, _ = one_step(options, doc, 0.01, external_forces=force)
    assert np.linalg.norm(angular[0]) < 1e-4 * ROTATIONAL_MU0 * RADIUS * np.linalg.norm(force)


def test_a_torque_on_one_particle_moves_another_with_the_rotlet_flow(options):
    """Particle 0 carries the moment and turns; particle 1 (no moment) 4.2 radii away is carried by the
    flow: the lattice sum of the two Gaussians to the grid's 1e-4 (relative to the flow), and the
    free-space rotlet T x r / (8 pi eta r^3) to 2.5% (the periodic images at L = 32 and the Gaussians'
    size, measured by the lattice sum itself: 1.5%). Conversely a force F on particle 1 turns particle 0
    by the transposed coupling: omega_0 . T = u_1 . F (the mobility is symmetric)."""
    length, time_step = 32.0, 0.01
    positions = [[0.5, 0.3, -0.2], [4.5, 1.3, -0.7]]
    r = np.subtract(positions[1], positions[0])
    doc = magnetic_document(positions, length, fcm(time_step, tolerance=1e-3),
                            [[1.0, 0.0, 0.0, 3.0], [1.0, 0.0, 0.0, 0.0]], [0.1, 0.5, 0.8])
    velocities, angular, torques = one_step(options, doc, time_step)
    torque = torques[0]
    assert np.linalg.norm(torques[1]) == 0.0
    lattice = torque_flow_lattice_sum(torque, r, length)
    rotlet = np.cross(torque, r) / (8.0 * math.pi * ETA * np.linalg.norm(r) ** 3)
    assert np.linalg.norm(velocities[1] - lattice) < 1e-3 * np.linalg.norm(lattice)
    assert np.linalg.norm(velocities[1] - rotlet) < 0.025 * np.linalg.norm(rotlet)
    assert np.linalg.norm(angular[1]) > 0.0  # the flow turns it as well

    force = np.array([[0.0, 0.0, 0.0], [0.4, -0.8, 0.5]])
    doc = magnetic_document(positions, length, fcm(time_step, tolerance=1e-3),
                            [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]], [0.0, 0.0, 0.0])
    _, turned, _ = one_step(options, doc, time_step, external_forces=force)
    assert turned[0] @ torque == pytest.approx(velocities[1] @ force[1], rel=1e-6)


# ---- thermal ---------------------------------------------------------------------------------------

def test_orientations_decorrelate_at_the_rotational_diffusion_rate(options):
    """27 particles 4 radii apart (box 12), no torque, kT = 1: each step turns every particle by a
    Gaussian rotation vector of variance s^2 = 2 D_r dt per axis, D_r = kT mu_r(L), whose body axes then
    keep on average e(0) . e(n dt) = r^n, r = (1 + 2 (1 - s^2) exp(-s^2/2)) / 3 (= exp(-2 D_r dt) to
    O(dt^2)). Measured at n = 15 and 30 over 40 windows each started from the last one's end; the
    windows' means (over particles, which the fluid correlates) give the standard error, and the mean
    must be within 4 of them, while a rate off by a third (the translational mobility's 4/3 in place of
    the rotational one's) must be outside them."""
    length, time_step, kT = 12.0, 0.2, 1.0
    grid = np.arange(3) * 4.0 - 4.0
    positions = [[x, y, z] for x in grid for y in grid for z in grid]
    n = len(positions)
    doc = magnetic_document(positions, length, fcm(time_step, tolerance=1e-3), [[1.0, 0.0, 0.0, 0.0]] * n,
                            [0.0, 0.0, 0.0], temperature=kT, steps=10 ** 7)
    diffusion = kT * (1.0 - 4.0 * math.pi / 3.0 * (RADIUS / length) ** 3) * ROTATIONAL_MU0
    s2 = 2.0 * diffusion * time_step
    per_step = (1.0 + 2.0 * (1.0 - s2) * math.exp(-s2 / 2.0)) / 3.0
    windows, lags = 40, (15, 30)
    correlations = {lag: [] for lag in lags}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        for _ in range(windows):
            start = body_axes(sim.orientations)
            done = 0
            for lag in lags:
                sim.step(lag - done)
                done = lag
                correlations[lag].append(np.mean(np.sum(start * body_axes(sim.orientations), axis=1)))
    for lag in lags:
        samples = np.array(correlations[lag])
        mean, error = samples.mean(), samples.std(ddof=1) / math.sqrt(windows)
        expected = per_step ** lag
        assert abs(mean - expected) < 4.0 * error, (lag, mean, expected, error)
        assert abs(mean - math.exp(-2.0 * (4.0 / 3.0) * diffusion * lag * time_step)) > 4.0 * error


def body_axes(quaternions):
    """The body z axis of each orientation in the lab frame."""
    a, b, c, d = np.asarray(quaternions).T
    return np.stack([2 * (b * d + a * c), 2 * (c * d - a * b), a * a - b * b - c * c + d * d], axis=1)


def test_the_rotational_noise_has_covariance_2_kT_dt_mu_r(options):
    """Many single steps from the same state (reset before each), no torque: the sample covariance of the
    rotation vectors against 2 kT dt mu_r(L) I, each element within 4 standard errors
    sqrt((C_aa C_bb + C_ab^2) / n); and the rotations are uncorrelated with the displacements (a single
    particle's translation-rotation coupling is zero by symmetry)."""
    length, time_step, kT, samples = 8.0, 0.01, 1.5, 2000
    doc = magnetic_document([[0.2, 0.1, -0.3]], length, fcm(time_step, tolerance=1e-3), [[1.0, 0.0, 0.0, 0.0]],
                            [0.0, 0.0, 0.0], temperature=kT, steps=10 ** 7)
    moves = np.empty((samples, 6))
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        start, orientation = sim.positions, sim.orientations
        for s in range(samples):
            sim.positions, sim.orientations = start, orientation
            sim.step(1)
            moves[s, :3] = minimum_image(sim.positions - start, length)[0]
            moves[s, 3:] = rotation_vectors(orientation, sim.orientations)[0]
    variance = 2.0 * kT * time_step * (1.0 - 4.0 * math.pi / 3.0 * (RADIUS / length) ** 3) * ROTATIONAL_MU0
    translation = 2.0 * kT * time_step * hasimoto(RADIUS, length)
    expected = np.diag([translation] * 3 + [variance] * 3)
    sampled = moves.T @ moves / samples
    error = np.sqrt((np.outer(np.diag(expected), np.diag(expected)) + expected ** 2) / samples)
    assert np.all(np.abs(sampled - expected) < 4.0 * error + 2e-3 * expected), (sampled, expected)


# ---- inputs ------------------------------------------------------------------------------------------

def test_uammd_structureds_own_test_input_loads_and_drifts_at_the_periodic_mobility(options):
    """The input Tests/Magnetism/ForceCouplingMethod/scripts/generateMagneticIntegratorsTest.py writes
    (its parameters.json: one particle of radius 0.928337 in a box of 20, viscosity 0.1, tolerance
    1e-5, a constant force 1 along z, 100 steps of 0.001; orientations but no moments; algorithm
    "none"): it loads, steps, drifts along z at Hasimoto's mobility (1e-3, as above) and does not turn."""
    radius, length, viscosity, time_step, steps = 0.928337, 20.0, 0.1, 0.001, 100
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "FCM"}}},
        "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "radius", "mass", "charge"],
                             "data": [["A", radius, 0, 0]]},
                   "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                                "data": [[[length] * 3, 0]]}},
        "integrator": {"FCM": {"type": ["Magnetic", "ForceCouplingMethod"],
                               "parameters": {"timeStep": time_step, "msat": 1, "viscosity": viscosity,
                                              "tolerance": 1e-5, "magneticIntegrationAlgorithm": "none",
                                              "hydrodynamicRadius": radius}},
                       "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                    "data": [[1, "FCM", steps]]}},
        "state": {"labels": ["id", "position", "direction"], "data": [[0, [0, 0, 0], [1.0, 0, 0, 0]]]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"]]},
                     "forceField": {"External": {"type": ["External", "ConstantForce"],
                                                 "parameters": {"constantForce": [0, 0, 1]}}}},
    }
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.run()
        a = radius / length
        mobility = (1 - 2.837297 * a + 4 * math.pi / 3 * a ** 3) / (6 * math.pi * viscosity * radius)
        assert sim.positions[0][2] == pytest.approx(mobility * steps * time_step, rel=1e-3)
        assert np.linalg.norm(sim.positions[0][:2]) < 1e-6
        np.testing.assert_allclose(sim.orientations[0], [1, 0, 0, 0], atol=1e-9)


def test_bad_inputs_are_refused_by_path(options):
    doc = magnetic_document([[0, 0, 0]], 10.0, fcm(algorithm="LLG_Heun"), [[1.0, 0.0, 0.0, 1.0]], [0, 0, 0])
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"integrator\.bd\.parameters\.damping: .*damping > 0"):
            sim.load(doc)
        no_moments = document([[0, 0, 0]], 10.0, fcm(algorithm="LLG_Euler", damping=0.1, gyroRatio=1.0))
        with pytest.raises(structmd.InputError, match=r"integrator\.bd\.type: .*'magnetization' column"):
            sim.load(no_moments)
        small = document([[0, 0, 0]], 10.0, fcm(tolerance=1e-12))
        with pytest.raises(structmd.InputError, match=r"integrator\.bd\.parameters\.tolerance"):
            sim.load(small)
        two_batches = document([[0, 0, 0], [3, 0, 0]], 10.0, fcm(), batches=[0, 1])
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bd\.type: hydrodynamics couples"):
            sim.load(two_batches)
        sim.load(document([[0, 0, 0]], 10.0, fcm()))
        sim.step(1)
        sim.box = [11.0, 11.0, 11.0]
        with pytest.raises(structmd.UnsupportedError, match=r"bd: the box changed.*Magnetic.*ForceCouplingMethod"):
            sim.step(1)


def test_the_moments_turn_with_the_particles_and_by_llg(options):
    """A moment at 90 degrees from the field, no damping torque inside (algorithm "none"): the particle
    turns towards the field and the moment with it, the Brownian relaxation of a rigid dipole at zero
    temperature, tan(theta/2) = tan(theta_0/2) exp(-mu_r M B t) to first order in dt. With LLG_Heun
    and a large damping, the moment turns inside the particle as well, so it aligns faster."""
    length, time_step, steps, b0, moment = 10.0, 0.01, 200, 2.0, 3.0
    mu_r = (1.0 - 4.0 * math.pi / 3.0 * (RADIUS / length) ** 3) * ROTATIONAL_MU0
    doc = magnetic_document([[0, 0, 0]], length, fcm(time_step, tolerance=1e-3), [[1.0, 0.0, 0.0, moment]],
                            [0.0, 0.0, b0], steps=steps)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(steps)
        rigid = sim.magnetic_moments[0] / moment
    theta = 2.0 * math.atan(math.exp(-mu_r * moment * b0 * steps * time_step))
    assert math.acos(rigid[2]) == pytest.approx(theta, rel=3e-3)
    llg = fcm(time_step, tolerance=1e-3, algorithm="LLG_Heun", damping=1.0, gyroRatio=0.5)
    doc = magnetic_document([[0, 0, 0]], length, llg, [[1.0, 0.0, 0.0, moment]], [0.0, 0.0, b0], steps=steps)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(steps)
        both = sim.magnetic_moments[0] / moment
    assert both[2] > rigid[2] + 0.05
