"""["BDHIDoublyPeriodic","Quasi2D"]: Brownian dynamics with hydrodynamic interactions of particles
moving in a plane periodic along x and y (docs/input-format.md).

References written here, independent of the engine:
- The kernels from their definition (Pelaez et al., J. Stat. Mech. 063207 (2018)): quasi-2D is the 3D
  Oseen tensor between Gaussian blobs (sigma = a / sqrt(pi)) integrated over the out-of-plane wave
  number numerically, k_z = k tan(theta), by Gauss-Legendre quadrature,
    T(k) = 1/(2 pi k) int exp(-k^2 sigma^2 / cos^2) dtheta,  L(k) = 1/(2 pi k) int sin^2 exp(...) dtheta,
  M(k) = (T k^perp k^perp^T + L k^ k^T) / eta; true 2D is exp(-k^2 sigma^2) (I - k^ k^T) / (eta k^2),
  sigma = 0.66556976637 a. The periodic mobility is the lattice sum (1/A) sum_{k != 0} M(k) cos(k.r)
  and the thermal drift kT sum_b d/dq_b . M(q_a - q_b) = (kT/A) sum_b sum_k sin(k.r_ab) L(k) k / eta.
- Quasi-2D's analytic self mobility in a square periodic box of side L,
    mu(L) = mu0 (1 - 4.3877980 a/L + 6 (a/L)^2 + O((a/L)^3)),  mu0 = 1/(6 pi eta a),
  the first correction from the small-k limit (T + L)/2 -> 3/(8k) and the square lattice's Epstein
  zeta Z(1/2) = 4 zeta(1/2) beta(1/2) = -3.90026492, the second from the constant -sigma/sqrt(pi) of
  the next order (the k = 0 term the sum leaves out). True 2D's,
    mu(L) = (ln(L/a) - 1.3079605 + 2 pi (sigma/L)^2 + O((sigma/L)^4)) / (4 pi eta),
  from the theta-function form of sum_{n != 0} exp(-eps n^2) / n^2 = -pi ln(eps) + 0.7716053 + eps + ...
  (UAMMD's test has 1.3105329 in place of 1.3079605, the constant of a Gaussian 0.2 % wider).

The mobility is read column by column from the integrator's own deterministic step at temperature 0:
a force F on one particle along one axis moves every particle by dt M F.
"""

import math

import numpy as np
import pytest

import periodic_rpy
import structmd
from set_parameter_checks import assert_refused_and_kept

ETA = 1.3
RADIUS = 1.0
MU0 = 1.0 / (6.0 * math.pi * ETA * RADIUS)
EPSTEIN_TERM = 4.3877980350022
TRUE2D_CONSTANT = 1.307960460395468
TRUE2D_SIGMA = 0.66556976637237890625 * RADIUS
Z_BOX = 30.0


# ---- input documents ------------------------------------------------------------------------------

def q2d(time_step=0.01, viscosity=ETA, radius=RADIUS, tolerance=1e-4, kernel=None, **extra):
    parameters = {"timeStep": time_step, "viscosity": viscosity, "hydrodynamicRadius": radius,
                  "tolerance": tolerance, "hydrodynamicKernel": kernel, **extra}
    return {"type": ["BDHIDoublyPeriodic", "Quasi2D"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


def planar_box(box):
    box = [float(b) for b in (box if np.ndim(box) else [box] * 2)]
    return np.array(box[:2])


def document(positions, box, entry, **rest):
    """periodic_rpy's document in the box of `box`'s plane, Z_BOX high."""
    return periodic_rpy.document(positions, list(planar_box(box)) + [Z_BOX], entry, **rest)


def planar_moves(after, before, box):
    """The in-plane displacements (N x 2), z's must not have moved at all."""
    assert np.array_equal(after[:, 2], before[:, 2]), "z must be untouched"
    return periodic_rpy.minimum_image(after[:, :2] - before[:, :2], planar_box(box))


def measured_mobility(options, positions, box, time_step=0.01, **parameters):
    """M (2N x 2N, x and y of each particle) from the integrator's step at temperature 0: column
    (j, axis) is the in-plane displacement of every particle under a unit force on j along that axis,
    over dt."""
    positions = np.asarray(positions, float)
    n = len(positions)
    mobility = np.zeros((2 * n, 2 * n))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, q2d(time_step=time_step, **parameters), steps=10 ** 6))
        start = sim.positions
        for column in range(2 * n):
            force = np.zeros((n, 3))
            force[column // 2, column % 2] = 1.0
            sim.positions = start
            sim.external_forces = force
            sim.step(1)
            mobility[:, column] = planar_moves(sim.positions, start, box).ravel() / time_step
    return mobility


# ---- independent references -----------------------------------------------------------------------

NODES, WEIGHTS = np.polynomial.legendre.leggauss(96)
THETA, D_THETA = 0.5 * math.pi * NODES, 0.5 * math.pi * WEIGHTS


def q2d_kernel(k, a):
    """T(k), L(k) with the Gaussians' exp(-k^2 sigma^2), by quadrature of the 3D Oseen tensor over k_z."""
    sigma = a / math.sqrt(math.pi)
    k = np.asarray(k, float)
    gauss = np.exp(-np.square(k * sigma)[:, None] / np.cos(THETA) ** 2)
    transverse = (D_THETA * gauss).sum(1) / (2 * math.pi * k)
    longitudinal = (D_THETA * np.sin(THETA) ** 2 * gauss).sum(1) / (2 * math.pi * k)
    return transverse, longitudinal


def true2d_kernel(k, a):
    sigma = TRUE2D_SIGMA * a / RADIUS
    return np.exp(-np.square(k * sigma)) / (k * k), np.zeros_like(k)


def wave_vectors(box, cut):
    axes = [2 * math.pi * np.arange(-m, m + 1) / length
            for m, length in ((int(math.ceil(cut * length / (2 * math.pi))), length) for length in box)]
    waves = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 2)
    k2 = (waves * waves).sum(1)
    keep = (k2 > 0) & (k2 < cut * cut)
    return waves[keep], np.sqrt(k2[keep])


def lattice_sums(positions, box, kernel=q2d_kernel, a=RADIUS, eta=ETA):
    """The periodic mobility (2N x 2N) and the thermal drift per kT (N x 2) without a grid."""
    pos = np.asarray(positions, float)[:, :2]
    box = planar_box(box)
    waves, k = wave_vectors(box, 7.0 / (0.66 * a))
    transverse, longitudinal = kernel(k, a)
    unit = waves / k[:, None]
    across = np.stack([-unit[:, 1], unit[:, 0]], 1)
    tensor = (transverse[:, None, None] * across[:, :, None] * across[:, None, :]
              + longitudinal[:, None, None] * unit[:, :, None] * unit[:, None, :]) / (eta * box.prod())
    n = len(pos)
    mobility = np.zeros((2 * n, 2 * n))
    drift = np.zeros((n, 2))
    for i in range(n):
        for j in range(n):
            phase = waves @ (pos[i] - pos[j])
            mobility[2 * i:2 * i + 2, 2 * j:2 * j + 2] = np.einsum("k,kab->ab", np.cos(phase), tensor)
            drift[i] += (np.sin(phase) * longitudinal) @ waves / (eta * box.prod())
    return mobility, drift


def q2d_self_mobility(length):
    return MU0 * (1 - EPSTEIN_TERM * RADIUS / length + 6 * (RADIUS / length) ** 2)


def true2d_self_mobility(length):
    return (math.log(length / RADIUS) - TRUE2D_CONSTANT + 2 * math.pi * (TRUE2D_SIGMA / length) ** 2) / (4 * math.pi * ETA)


def off_block_diagonal(n):
    pair = np.ones((2 * n, 2 * n), bool)
    for i in range(n):
        pair[2 * i:2 * i + 2, 2 * i:2 * i + 2] = False
    return pair


# ---- tests ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("length", [32.0, 64.0])
def test_the_references_give_the_analytic_periodic_self_mobilities(length):
    """The lattice sums themselves against the analytic self mobilities (what is left of quasi-2D's is
    its O((a/L)^3) term, 2.2 (a/L)^3 mu0)."""
    position = [[0.0, 0.0, 0.0]]
    quasi, _ = lattice_sums(position, length)
    assert quasi[0, 0] == pytest.approx(q2d_self_mobility(length), rel=1e-4)
    true2d, _ = lattice_sums(position, length, kernel=true2d_kernel)
    assert true2d[0, 0] == pytest.approx(true2d_self_mobility(length), rel=1e-6)


@pytest.mark.parametrize("length", [16.0, 32.0, 64.0])
def test_one_pushed_particle_moves_with_the_periodic_quasi2d_self_mobility(options, length):
    """The grid adds an error of the order of the tolerance (1e-4) to the lattice sum; the analytic
    form misses O((a/L)^3), 5e-4 mu0 at L = 16 a."""
    position = [[0.37, -1.21, 2.05]]
    mobility = measured_mobility(options, position, length)
    lattice, _ = lattice_sums(position, length)
    for axis in range(2):
        assert mobility[axis, axis] == pytest.approx(lattice[axis, axis], rel=3e-4)
        assert mobility[axis, axis] == pytest.approx(q2d_self_mobility(length), rel=1e-3)
    assert abs(mobility[0, 1]) < 1e-4 * MU0
    # The periodic correction is no small part of it.
    assert abs(mobility[0, 0] - MU0) > 0.05 * MU0


@pytest.mark.parametrize("length", [16.0, 64.0])
def test_one_pushed_particle_moves_with_the_periodic_true2d_self_mobility(options, length):
    position = [[1.1, 0.4, -3.0]]
    mobility = measured_mobility(options, position, length, kernel="True2D")
    lattice, _ = lattice_sums(position, length, kernel=true2d_kernel)
    for axis in range(2):
        assert mobility[axis, axis] == pytest.approx(lattice[axis, axis], rel=3e-4)
        assert mobility[axis, axis] == pytest.approx(true2d_self_mobility(length), rel=1e-3)


def test_a_larger_tolerance_is_less_accurate_but_within_itself(options):
    position = [[0.1, 0.2, 0.3]]
    lattice = lattice_sums(position, 12.0)[0][0, 0]
    for tolerance in (1e-2, 1e-3, 1e-5):
        mobility = measured_mobility(options, position, 12.0, tolerance=tolerance)[0, 0]
        assert mobility == pytest.approx(lattice, rel=3 * tolerance)


@pytest.mark.parametrize("kernel, reference", [(None, q2d_kernel), ("Quasi2D", q2d_kernel), ("True2D", true2d_kernel)])
def test_pair_mobilities_match_the_lattice_sum(options, kernel, reference):
    """Three particles 2.5 to 6 radii apart, at different heights (z does not count), in a
    rectangular box: every element of M to the tolerance, M symmetric and positive."""
    box = [11.0, 13.5]
    positions = [[0.3, -0.2, 0.1], [4.1, 0.6, -5.8], [-1.5, 2.2, 7.2]]
    mobility = measured_mobility(options, positions, box, kernel=kernel)
    lattice, _ = lattice_sums(positions, box, kernel=reference)
    assert np.max(np.abs(mobility - lattice)) < 3e-4 * MU0
    assert np.max(np.abs(lattice[off_block_diagonal(3)])) > 0.1 * MU0, "the pairs must be coupled"
    assert np.allclose(mobility, mobility.T, atol=1e-6 * MU0), "M must be symmetric"
    assert np.linalg.eigvalsh(0.5 * (mobility + mobility.T)).min() > 0.0


def test_the_two_kernels_differ(options):
    """Quasi-2D's in-plane flow is compressible (L != 0), true 2D's is not: the responses differ."""
    positions = [[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]]
    quasi = measured_mobility(options, positions, 12.0)
    true2d = measured_mobility(options, positions, 12.0, kernel="True2D")
    assert np.max(np.abs(quasi - true2d)) > 0.1 * MU0


def test_z_is_untouched_and_forces_along_z_do_nothing(options):
    """Forces along z only, at temperature 0: no particle moves at all. At temperature > 0 the z of
    every particle stays bit for bit over many steps, and the same in-plane positions at other heights
    move exactly as they do (the particles all count as in the plane)."""
    box = 10.0
    positions = np.array([[0.0, 0.0, 0.0], [2.5, 0.5, 3.0], [-1.0, 3.0, -7.5]])
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, q2d(), steps=100))
        sim.external_forces = [[0.0, 0.0, 5.0], [0.0, 0.0, -3.0], [0.0, 0.0, 1.0]]
        sim.step(3)
        assert np.array_equal(sim.positions, positions)
    runs = []
    for heights in ([0.0, 3.0, -7.5], [1.0, -12.0, 4.0]):
        moved = positions.copy()
        moved[:, 2] = heights
        with structmd.Simulation(options) as sim:
            sim.load(document(moved, box, q2d(), steps=100, temperature=1.0))
            sim.external_forces = [[0.3, 0.0, 5.0], [0.0, -0.2, -3.0], [0.0, 0.0, 1.0]]
            sim.step(20)
            after = sim.positions
        assert np.array_equal(after[:, 2], moved[:, 2])
        runs.append(after[:, :2])
    assert np.array_equal(runs[0], runs[1])
    assert np.min(np.abs(runs[0] - positions[:, :2])) > 0.0


def one_step(options, positions, box, kT, time_step, seed=11, kernel=None):
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, q2d(time_step=time_step, kernel=kernel), steps=100, temperature=kT,
                          seed=seed))
        sim.step(1)
        return planar_moves(sim.positions, np.asarray(positions, float), box)


def test_the_thermal_drift_is_kT_times_the_divergence_of_the_mobility(options):
    """The same step (seed and step number) at kT and 4 kT draws the same noise field: the displacement
    is dt kT D + sqrt(kT) N, so d(4 kT) - 2 d(kT) = 2 dt kT D exactly, the drift D = sum_b d/dq_b . M
    against the lattice sum. The drift pushes the particles apart (quasi-2D's flow is compressible);
    a lone particle has none, nor has true 2D."""
    box = [12.0, 10.0]
    positions = [[0.0, 0.0, 0.0], [2.6, 0.8, 1.0], [-1.2, 2.4, -2.0]]
    kT, time_step = 0.8, 0.05
    drift = (one_step(options, positions, box, 4 * kT, time_step)
             - 2 * one_step(options, positions, box, kT, time_step)) / (2 * time_step * kT)
    _, expected = lattice_sums(positions, box)
    assert np.max(np.abs(drift - expected)) < 3e-4 * MU0, (drift, expected)
    assert np.max(np.abs(expected)) > 0.01 * MU0, "the drift must be resolved"
    separation = np.asarray(positions)[1, :2] - np.asarray(positions)[0, :2]
    assert np.dot(drift[1] - drift[0], separation) > 0.0, "the drift is repulsive"
    # A particle's own term vanishes (the grid's divergence of the kernel is odd), wherever it is.
    for alone in ([[0.0, 0.0, 0.0]], [[0.41, -0.22, 3.0]]):
        own = one_step(options, alone, box, 4 * kT, time_step) - 2 * one_step(options, alone, box, kT, time_step)
        assert np.max(np.abs(own)) < 1e-12
    true2d = (one_step(options, positions, box, 4 * kT, time_step, kernel="True2D")
              - 2 * one_step(options, positions, box, kT, time_step, kernel="True2D"))
    assert np.max(np.abs(true2d)) < 1e-12


def test_the_noise_has_covariance_2_kT_dt_M(options):
    """Many zero-force steps from the same configuration (reset before each): the sample covariance
    of the displacements about their mean against 2 kT dt M, M from the same integrator's
    deterministic response. An element of the sample covariance of n Gaussian vectors has standard
    error sqrt((C_aa C_bb + C_ab^2) / n); every element must be within 4 of them. The mean is the drift
    dt kT D within 4 standard errors."""
    box = 9.0
    positions = np.array([[0.2, 0.1, -0.3], [2.9, 0.4, 0.2]])
    time_step, kT, samples = 0.01, 1.7, 3000
    mobility = measured_mobility(options, positions, box, time_step=time_step, tolerance=1e-3)
    expected = 2.0 * kT * time_step * mobility
    moves = np.empty((samples, 4))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, q2d(time_step=time_step, tolerance=1e-3), steps=10 ** 7, temperature=kT))
        start = sim.positions
        for s in range(samples):
            sim.positions = start
            sim.step(1)
            moves[s] = planar_moves(sim.positions, start, box).ravel()
    _, drift = lattice_sums(positions, box)
    mean_error = np.sqrt(np.diag(expected) / samples)
    assert np.all(np.abs(moves.mean(0) - time_step * kT * drift.ravel()) < 4 * mean_error)
    centred = moves - moves.mean(0)
    sampled = centred.T @ centred / (samples - 1)
    standard_error = periodic_rpy.covariance_standard_error(expected, samples)
    assert np.all(np.abs(sampled - expected) < 4 * standard_error), np.max(np.abs(sampled - expected) / standard_error)
    # The pair's coupling is resolved: the covariance between the particles is many errors from 0.
    assert abs(sampled[0, 2]) > 10 * standard_error[0, 2]


def test_particles_outside_the_group_neither_move_nor_push_the_fluid(options):
    """Particle 1, outside the group, is pushed hard along y: it must not move, and the group's
    members must move as the two of them alone would under the push on particle 0 along x."""
    box = 10.0
    positions = np.array([[0.0, 0.0, 0.0], [0.0, -3.0, 0.0], [0.0, 3.5, 0.0]])
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["mobile", "Ids", [0, 2]]]}}
    time_step = 0.01
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, q2d(time_step=time_step, group="mobile"), steps=100, force_field=groups))
        sim.external_forces = [[1.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 0.0]]
        sim.step(1)
        moved = planar_moves(sim.positions, positions, box)
    assert np.array_equal(moved[1], [0.0, 0.0])
    pair, _ = lattice_sums(positions[[0, 2]], box)
    assert moved[0] / time_step == pytest.approx(pair[0:2, 0], abs=3e-4 * MU0)
    assert moved[2] / time_step == pytest.approx(pair[2:4, 0], abs=3e-4 * MU0)
    assert abs(moved[2, 0]) > 0.02 * MU0 * time_step, "the group's other member must be carried"
    everyone, _ = lattice_sums(positions, box)
    assert min(abs(5.0 * everyone[1, 3]), abs(5.0 * everyone[5, 3])) > 0.3 * MU0


def test_the_precisions_give_the_same_mobility(options):
    position = [[0.4, 0.3, -0.2], [2.6, -1.1, 0.9]]
    # A long step, so that single-precision positions resolve the displacement to 1e-5 of it.
    reference = measured_mobility(options, position, 9.0, time_step=1.0)
    for precision in ("single", "mixed"):
        other = measured_mobility(dict(options, precision=precision), position, 9.0, time_step=1.0)
        assert np.max(np.abs(other - reference)) < 1e-4 * MU0


def test_a_trapped_particle_samples_boltzmann(options):
    """A force-field term with hydrodynamics: a particle in a harmonic trap of stiffness K. With its
    self-mobility mu (the lattice sum's), Euler-Maruyama samples <K x^2> = kT / (1 - mu K dt / 2) per
    in-plane axis exactly (one particle has no drift); samples one relaxation time apart in 20 blocks
    give the standard error (4 allowed). Its z never moves."""
    box, kT, stiffness, time_step = 10.0, 1.0, 50.0, 0.05
    trap = {"trap": {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
                     "data": [[0, stiffness, 0.0, [0.0, 0.0, 1.5]]]}}
    mobility = lattice_sums([[0.0, 0.0, 0.0]], box)[0][0, 0]
    stride = int(math.ceil(1.0 / (mobility * stiffness * time_step)))
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 1.5]], box, q2d(time_step=time_step, tolerance=1e-3), steps=10 ** 7,
                          temperature=kT, force_field=trap))
        samples = []
        for _ in range(400):
            sim.step(stride)
            samples.append(sim.positions[0].copy())
    samples = np.array(samples)
    assert np.all(samples[:, 2] == 1.5)
    energy = stiffness * samples[:, :2] ** 2
    blocks = energy.reshape(20, -1, 2).mean(axis=(1, 2))
    measured, error = blocks.mean(), blocks.std(ddof=1) / math.sqrt(len(blocks))
    expected = kT / (1.0 - 0.5 * mobility * stiffness * time_step)
    assert abs(measured - expected) < 4 * error, (measured, expected, error)
    assert error < 0.1 * kT  # a noise amplitude off by sqrt(2) would miss by 10 errors


def test_a_box_changed_by_the_host_is_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 8.0, q2d(), steps=10))
        sim.step(1)
        sim.box = [9.0, 8.0, Z_BOX]
        with pytest.raises(structmd.UnsupportedError, match=r"bd: the box changed.*Quasi2D"):
            sim.step(1)


def test_several_batches_are_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bd\.type: .*batches"):
            sim.load(document([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]], 8.0, q2d(), batches=[0, 1]))


@pytest.mark.parametrize("parameters, path, message", [
    ({"viscosity": 0.0}, "integrator.bd.parameters.viscosity", "positive"),
    ({"viscosity": None}, "integrator.bd.parameters.viscosity", "missing"),
    ({"radius": None}, "integrator.bd.parameters.hydrodynamicRadius", "missing"),
    ({"radius": -0.5}, "integrator.bd.parameters.hydrodynamicRadius", "positive"),
    ({"tolerance": 0.5}, "integrator.bd.parameters.tolerance", r"\[1e-10, 0.1\]"),
    ({"tolerance": -1e-3}, "integrator.bd.parameters.tolerance", "positive"),
    ({"kernel": "Saffman"}, "integrator.bd.parameters.hydrodynamicKernel", "Quasi2D"),
    ({"radius": 2.5}, "integrator.bd.parameters.hydrodynamicRadius", "too small"),
    ({"radius": 1e-7}, "integrator.bd.parameters.hydrodynamicRadius", r"more than 2\^30"),  # not SIGFPE (issue 37)
])
def test_bad_input_names_its_path(options, parameters, path, message):
    periodic_rpy.assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 6.0, q2d(**parameters)), path, message)


def test_set_parameter_refuses_a_radius_whose_grid_cannot_be(options):
    path = "integrator.bd.parameters.hydrodynamicRadius"
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 12.0, q2d()))
        sim.step(1)
        assert sim.get_parameter(path) == RADIUS
        assert_refused_and_kept(sim, path, 1e-7, r"more than 2\^30")
