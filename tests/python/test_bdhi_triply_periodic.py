"""["BDHITriplyPeriodic","ForceCouplingMethod"]: Brownian dynamics with hydrodynamic interactions in
a triply periodic box by the force coupling method (docs/input-format.md).

References, independent of the engine: Hasimoto's self-mobility and Beenakker's Ewald sum of the
periodic RPY mobility (periodic_rpy.py, checked here to be independent of its splitting), and
- the force coupling method's own mobility, the lattice sum over wave vectors of its Gaussian kernels
  (1/(eta V)) sum_{k != 0} exp(-k^2 sigma^2) (I - k k^T/k^2) cos(k.r) / k^2, sigma = a / sqrt(pi),
  which the grid approximates to the method's tolerance.

The mobility is read column by column from the integrator's own deterministic step at temperature 0:
a force F on one particle along one axis moves every particle by dt M F.
"""

import math

import numpy as np
import pytest

import structmd
from set_parameter_checks import assert_refused_and_kept
from periodic_rpy import (ETA, assert_refused_at_load, MU0, RADIUS, add_wave_sum, covariance_standard_error, document, hasimoto,
                          minimum_image, noise_samples, rpy_ewald, trapped_particle_energy, wave_vectors, windowed_msd)
from periodic_rpy import measured_mobility as measured_entry_mobility


# ---- input documents ------------------------------------------------------------------------------

def fcm(time_step=0.01, viscosity=ETA, radius=RADIUS, tolerance=1e-4, cls="BDHITriplyPeriodic", **extra):
    parameters = {"timeStep": time_step, "viscosity": viscosity, "hydrodynamicRadius": radius,
                  "tolerance": tolerance, **extra}
    return {"type": [cls, "ForceCouplingMethod"], "parameters": {k: v for k, v in parameters.items() if v is not None}}


def measured_mobility(options, positions, box, time_step=0.01, **fcm_parameters):
    return measured_entry_mobility(options, positions, box, fcm(time_step=time_step, **fcm_parameters), time_step)


# ---- independent references -----------------------------------------------------------------------

def fcm_lattice_sum(positions, a, eta, box):
    """The force coupling method's mobility without a grid: Gaussian kernels of width a / sqrt(pi)."""
    pos = np.asarray(positions, float)
    box = np.asarray(box, float)
    sigma = a / math.sqrt(math.pi)
    waves, k2 = wave_vectors(box, math.sqrt(36.0 * math.log(10.0)) / sigma)
    mobility = np.zeros((3 * len(pos), 3 * len(pos)))
    add_wave_sum(mobility, pos, waves, k2, np.exp(-k2 * sigma * sigma) / k2 / (eta * box.prod()))
    return mobility


# ---- tests ----------------------------------------------------------------------------------------

def test_the_ewald_reference_does_not_depend_on_its_splitting_and_gives_hasimoto():
    """The reference itself: two splittings agree to rounding, and the self term is Hasimoto's."""
    positions = [[0.0, 0.0, 0.0], [3.0, 0.5, -0.4], [-2.0, 2.5, 1.0]]
    coarse = rpy_ewald(positions, RADIUS, ETA, [10.0] * 3, xi=0.3)
    fine = rpy_ewald(positions, RADIUS, ETA, [10.0] * 3, xi=0.8)
    assert np.max(np.abs(coarse - fine)) < 1e-10 * MU0
    assert coarse[0, 0] == pytest.approx(hasimoto(RADIUS, 10.0), rel=1e-6)


@pytest.mark.parametrize("length", [8.0, 12.0, 20.0])
def test_one_pushed_particle_moves_with_hasimotos_periodic_mobility(options, length):
    """FCM's Gaussian differs from a rigid sphere only from the (a/L)^3 term on (its coefficient is 4
    against 4 pi / 3, a difference of 3.7e-4 mu0 at a/L = 1/8, measured exactly by the lattice sum)
    and the grid adds an error of the order of the tolerance (1e-4): 1e-3 bounds both."""
    position = [[0.37, -1.21, 2.05]]
    mobility = measured_mobility(options, position, length)
    expected = hasimoto(RADIUS, length)
    lattice = fcm_lattice_sum(position, RADIUS, ETA, [length] * 3)
    for axis in range(3):
        assert mobility[axis, axis] == pytest.approx(expected, rel=1e-3)
        assert mobility[axis, axis] == pytest.approx(lattice[axis, axis], rel=3e-4)
    off_diagonal = mobility - np.diag(np.diag(mobility))
    assert np.max(np.abs(off_diagonal)) < 1e-4 * MU0


def test_a_larger_tolerance_is_less_accurate_but_within_itself(options):
    position = [[0.1, 0.2, 0.3]]
    lattice = fcm_lattice_sum(position, RADIUS, ETA, [10.0] * 3)[0, 0]
    for tolerance in (1e-2, 1e-3, 1e-5):
        mobility = measured_mobility(options, position, 10.0, tolerance=tolerance)[0, 0]
        assert mobility == pytest.approx(lattice, rel=3 * tolerance)


def test_pair_mobilities_match_the_periodic_rpy_tensor_a_few_radii_apart(options):
    """Three particles 4 to 7.5 radii apart in an orthorhombic box. Beyond overlap the Gaussian's pair
    mobility is Oseen + (a^2/pi) Laplacian Oseen plus terms falling as exp(-r^2 pi / (4 a^2)), RPY's
    Oseen + (a^2/3) Laplacian Oseen (Maxey & Patel 2001; Keaveny 2014 compares the two): they differ
    by 6e-4 mu0 at 4 radii (the two lattice sums here), which 1e-3 mu0 bounds with the grid's 1e-4. The
    lattice sum of the Gaussians, which the grid approximates, must agree to the tolerance."""
    box = [11.0, 12.5, 14.0]
    positions = [[0.3, -0.2, 0.1], [4.1, 0.6, -0.8], [-1.5, 4.5, 2.2]]
    mobility = measured_mobility(options, positions, box)
    rpy = rpy_ewald(positions, RADIUS, ETA, box, xi=0.5)
    lattice = fcm_lattice_sum(positions, RADIUS, ETA, box)
    assert np.max(np.abs(mobility - lattice)) < 3e-4 * MU0
    pair = np.ones_like(mobility, bool)
    for i in range(3):
        pair[3 * i:3 * i + 3, 3 * i:3 * i + 3] = False
    assert np.max(np.abs(mobility - rpy)[pair]) < 1e-3 * MU0
    # The pair terms are no small part of it: a wrong coupling would show.
    assert np.max(np.abs(rpy[pair])) > 0.1 * MU0
    assert np.allclose(mobility, mobility.T, atol=1e-6 * MU0), "M must be symmetric"
    assert np.linalg.eigvalsh(0.5 * (mobility + mobility.T)).min() > 0.0


def test_the_noise_has_covariance_2_kT_dt_M(options):
    """Many zero-force steps from the same configuration (reset before each): the sample covariance
    of the displacements against 2 kT dt M, M from the same integrator's deterministic response. An
    element of the sample covariance of n Gaussian vectors has standard error
    sqrt((C_aa C_bb + C_ab^2) / n); every element must be within 4 of them."""
    box = 9.0
    positions = np.array([[0.2, 0.1, -0.3], [2.9, 0.4, 0.2]])
    time_step, kT, samples = 0.01, 1.7, 3000
    mobility = measured_mobility(options, positions, box, time_step=time_step, tolerance=1e-3)
    expected = 2.0 * kT * time_step * mobility
    moves = noise_samples(options, positions, box, fcm(time_step=time_step, tolerance=1e-3), kT, samples)
    assert np.all(np.abs(moves.mean(0)) < 4 * np.sqrt(np.diag(expected) / samples))
    sampled = moves.T @ moves / samples
    standard_error = covariance_standard_error(expected, samples)
    assert np.all(np.abs(sampled - expected) < 4 * standard_error), np.max(np.abs(sampled - expected) / standard_error)
    # The pair's coupling is resolved: the covariance between the particles is many errors from 0.
    assert abs(sampled[0, 3]) > 10 * standard_error[0, 3]


def test_a_dilute_suspension_diffuses_with_hasimotos_coefficient(options):
    """27 particles in a box of side 24 a (volume fraction 0.8 %): the mean square displacement over a
    lag of 20 steps, from non-overlapping windows of the unwrapped trajectories, against
    6 D t with D = kT mu(L), mu(L) Hasimoto's (FCM's mobility has no divergence, and each particle's
    self-mobility does not depend on the others). The standard error comes from the spread of the
    window means (particles' windows are correlated through the fluid, so the windows of one time
    are averaged first); 4 of them are allowed, and the Hasimoto correction (12 %) is 20 of them."""
    length, kT, time_step, lag, windows = 24.0, 1.0, 0.05, 20, 100
    cells = 3
    grid = (np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)], float) + 0.5)
    positions = grid * length / cells - 0.5 * length + np.random.default_rng(5).uniform(-1, 1, (cells ** 3, 3))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, length, fcm(time_step=time_step, tolerance=1e-3), steps=10 ** 7, temperature=kT))
        measured, standard_error = windowed_msd(sim, windows, lag, length)
    expected = 6.0 * kT * hasimoto(RADIUS, length) * lag * time_step
    assert abs(measured - expected) < 4 * standard_error, (measured, expected, standard_error)
    free = 6.0 * kT * MU0 * lag * time_step
    assert abs(measured - free) > 10 * standard_error


def test_particles_outside_the_group_neither_move_nor_push_the_fluid(options):
    """Particle 1, outside the group, is pushed hard along y: it must not move, and the group's
    members must move as the two of them alone would under the push on particle 0 along x (the
    lattice sum of the pair), with nothing along y."""
    box = 10.0
    positions = np.array([[0.0, 0.0, 0.0], [0.0, -3.0, 0.0], [0.0, 3.5, 0.0]])
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["mobile", "Ids", [0, 2]]]}}
    time_step = 0.01
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, fcm(time_step=time_step, group="mobile"), steps=100, force_field=groups))
        sim.external_forces = [[1.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 0.0]]
        sim.step(1)
        moved = minimum_image(sim.positions - positions, box)
    assert np.array_equal(moved[1], [0.0, 0.0, 0.0])
    pair = fcm_lattice_sum(positions[[0, 2]], RADIUS, ETA, [box] * 3)
    assert moved[0] / time_step == pytest.approx(pair[0:3, 0], abs=3e-4 * MU0)
    assert moved[2] / time_step == pytest.approx(pair[3:6, 0], abs=3e-4 * MU0)
    assert abs(moved[2, 0]) > 0.02 * MU0 * time_step, "the group's other member must be carried"
    # Had particle 1 pushed the fluid, the group would have moved along y by about 1 mu0 F dt.
    everyone = fcm_lattice_sum(positions, RADIUS, ETA, [box] * 3)
    assert min(abs(5.0 * everyone[1, 4]), abs(5.0 * everyone[7, 4])) > 0.5 * MU0


def test_uammds_spelling_and_the_precisions_give_the_same_mobility(options):
    position = [[0.4, 0.3, -0.2], [2.6, -1.1, 0.9]]
    # A long step, so that single-precision positions resolve the displacement to 1e-5 of it.
    reference = measured_mobility(options, position, 9.0, time_step=1.0)
    assert np.array_equal(measured_mobility(options, position, 9.0, time_step=1.0, cls="BDHITriplePeriodic"),
                          reference)
    for precision in ("single", "mixed"):
        other = measured_mobility(dict(options, precision=precision), position, 9.0, time_step=1.0)
        assert np.max(np.abs(other - reference)) < 1e-4 * MU0


def test_a_trapped_particle_samples_boltzmann(options):
    """A force-field term with hydrodynamics: a particle in a harmonic trap of stiffness K. With its
    self-mobility mu (Hasimoto's), Euler-Maruyama samples <K x^2> = kT / (1 - mu K dt / 2) per axis
    exactly; samples one relaxation time apart in 20 blocks give the standard error (4 allowed)."""
    box, kT, stiffness, time_step = 10.0, 1.0, 50.0, 0.05
    measured, error, expected = trapped_particle_energy(options, fcm(time_step=time_step, tolerance=1e-3), box, kT,
                                                        stiffness, time_step)
    assert abs(measured - expected) < 4 * error, (measured, expected, error)
    assert error < 0.1 * kT  # a noise amplitude off by sqrt(2) would miss by 10 errors


def test_a_box_changed_by_the_host_is_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 8.0, fcm(), steps=10))
        sim.step(1)
        sim.box = [9.0, 9.0, 9.0]
        with pytest.raises(structmd.UnsupportedError, match=r"bd: the box changed.*ForceCouplingMethod"):
            sim.step(1)


def test_several_batches_are_refused(options):
    doc = document([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]], 8.0, fcm(), steps=10, batches=[0, 1])
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bd\.type: .*one fluid"):
            sim.load(doc)
    # One batch is one system: the same input without the split loads.
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]], 8.0, fcm(), steps=10, batches=[0, 0]))


@pytest.mark.parametrize("parameters, path, message", [
    ({"viscosity": 0.0}, "integrator.bd.parameters.viscosity", "positive"),
    ({"viscosity": -1.0}, "integrator.bd.parameters.viscosity", "positive"),
    ({"viscosity": None}, "integrator.bd.parameters.viscosity", "missing"),
    ({"radius": None}, "integrator.bd.parameters.hydrodynamicRadius", "missing"),
    ({"radius": -0.5}, "integrator.bd.parameters.hydrodynamicRadius", "positive"),
    ({"tolerance": 0.5}, "integrator.bd.parameters.tolerance", r"\[1e-10, 0.1\]"),
    ({"tolerance": 1e-12}, "integrator.bd.parameters.tolerance", r"\[1e-10, 0.1\]"),
    ({"tolerance": -1e-3}, "integrator.bd.parameters.tolerance", "positive"),
    ({"radius": 2.5}, "integrator.bd.parameters.hydrodynamicRadius", "too small"),
    # A grid that could never be held: refused by name, not SIGFPE or an 8 GB allocation (issue 37).
    ({"radius": 1e-7}, "integrator.bd.parameters.hydrodynamicRadius", r"more than 2\^30: the radius is too small"),
    ({"radius": 1e-5}, "integrator.bd.parameters.hydrodynamicRadius", r"more than 2\^30"),
])
def test_bad_input_names_its_path(options, parameters, path, message):
    """Refused by the load itself: the grid is judged against the input's box (issue 37 refused some
    only at the first step)."""
    assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 6.0, fcm(**parameters)), path, message)


@pytest.mark.parametrize("radius, message", [(1e-7, r"more than 2\^30"), (6.0, "too small")])
def test_set_parameter_refuses_a_radius_whose_grid_cannot_be(options, radius, message):
    """Once SIGFPE at the next step (issue 37): now refused by set_parameter (ARGUMENT, as every value
    the input's rules refuse, naming the path), which keeps the old value."""
    path = "integrator.bd.parameters.hydrodynamicRadius"
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], 12.0, fcm()))
        sim.step(1)
        assert sim.get_parameter(path) == RADIUS
        assert_refused_and_kept(sim, path, radius, message)
