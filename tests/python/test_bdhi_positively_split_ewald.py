"""["BDHITriplyPeriodic","PositivelySplitEwald"]: Brownian dynamics with hydrodynamic interactions in
a triply periodic box by the positively split Ewald method (docs/input-format.md).

The method computes the periodic RPY mobility, overlapping pairs included, split in two by psi: its
references (periodic_rpy.py, independent of the engine) are Beenakker's Ewald sum of the periodic RPY
tensor with the overlapping form for pairs closer than 2a, and Hasimoto's self-mobility. The result
must not depend on psi beyond the tolerance.

The mobility is read column by column from the integrator's own deterministic step at temperature 0:
a force F on one particle along one axis moves every particle by dt M F.
"""

import numpy as np
import pytest

import structmd
from set_parameter_checks import assert_refused_and_kept
from periodic_rpy import (ETA, assert_refused_at_load, MU0, RADIUS, covariance_standard_error, document, hasimoto, measured_mobility,
                          minimum_image, noise_samples, rpy_ewald, rpy_overlap_correction, trapped_particle_energy,
                          windowed_msd)


def pse(time_step=0.01, viscosity=ETA, radius=RADIUS, tolerance=1e-4, psi=1.0, cls="BDHITriplyPeriodic", **extra):
    parameters = {"timeStep": time_step, "viscosity": viscosity, "hydrodynamicRadius": radius,
                  "tolerance": tolerance, "psi": psi, **extra}
    return {"type": [cls, "PositivelySplitEwald"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


def fcm(time_step=0.01, tolerance=1e-4):
    return {"type": ["BDHITriplyPeriodic", "ForceCouplingMethod"],
            "parameters": {"timeStep": time_step, "viscosity": ETA, "hydrodynamicRadius": RADIUS,
                           "tolerance": tolerance}}


def pse_mobility(options, positions, box, time_step=0.01, **parameters):
    return measured_mobility(options, positions, box, pse(time_step=time_step, **parameters), time_step)


def periodic_rpy(positions, box):
    box = np.asarray(box if np.ndim(box) else [box] * 3, float)
    return rpy_ewald(positions, RADIUS, ETA, box, xi=0.5) + rpy_overlap_correction(positions, RADIUS, ETA, box)


# Three particles in an orthorhombic box: 0-1 overlap (1.5 a), 0-2 are 2.6 a apart, 1-2 4.0 a.
BOX = [13.0, 14.0, 15.0]
POSITIONS = [[0.3, -0.2, 0.1], [1.8, -0.2, 0.1], [0.3, 2.2, -0.9]]


def test_the_overlap_correction_is_continuous_at_contact():
    """The reference's overlapping form meets the far one at r = 2a (Wajnryb et al. 2013)."""
    for d in (2.0 - 1e-9, 2.0 + 1e-9):
        assert np.max(np.abs(rpy_overlap_correction([[0, 0, 0], [d, 0, 0]], RADIUS, ETA, [10.0] * 3))) < 1e-8 * MU0
    assert np.max(np.abs(rpy_overlap_correction([[0, 0, 0], [1.0, 0, 0]], RADIUS, ETA, [10.0] * 3))) > 0.1 * MU0


@pytest.mark.parametrize("psi", [0.7, 1.2])
def test_pair_mobilities_match_the_periodic_rpy_tensor_overlap_included(options, psi):
    """Every block of M, self and pairs (overlapping, near contact and apart), against the Ewald sum
    of the periodic RPY tensor, to the tolerance (1e-4) for either splitting."""
    mobility = pse_mobility(options, POSITIONS, BOX, psi=psi)
    reference = periodic_rpy(POSITIONS, BOX)
    assert np.max(np.abs(mobility - reference)) < 1e-4 * MU0, np.max(np.abs(mobility - reference)) / MU0
    # The overlapping pair's coupling is no small part of it, and differs from the far RPY form.
    assert abs(reference[0, 3]) > 0.5 * MU0
    assert np.allclose(mobility, mobility.T, atol=1e-7 * MU0), "M must be symmetric"
    assert np.linalg.eigvalsh(0.5 * (mobility + mobility.T)).min() > 0.0


def test_the_mobility_does_not_depend_on_psi(options):
    """psi only moves work between the near and far parts: between two splittings that put most of
    the mobility on one side or the other, M must agree to the tolerance."""
    coarse = pse_mobility(options, POSITIONS, BOX, psi=0.8, tolerance=1e-5)
    fine = pse_mobility(options, POSITIONS, BOX, psi=1.6, tolerance=1e-5)
    assert np.max(np.abs(coarse - fine)) < 1e-5 * MU0, np.max(np.abs(coarse - fine)) / MU0


@pytest.mark.parametrize("length", [8.0, 12.0, 20.0])
def test_one_pushed_particle_moves_with_hasimotos_periodic_mobility(options, length):
    """Hasimoto's expansion leaves out O((a/L)^6), below 1e-5 here; the method's error is the
    tolerance (1e-4). (psi = 2: the near field must reach at most L / 2.)"""
    position = [[0.37, -1.21, 2.05]]
    mobility = pse_mobility(options, position, length, psi=2.0)
    expected = hasimoto(RADIUS, length)
    for axis in range(3):
        assert mobility[axis, axis] == pytest.approx(expected, rel=1e-4)
    off_diagonal = mobility - np.diag(np.diag(mobility))
    assert np.max(np.abs(off_diagonal)) < 1e-5 * MU0


def test_a_larger_tolerance_is_less_accurate_but_within_itself(options):
    reference = periodic_rpy(POSITIONS, BOX)
    for tolerance in (1e-2, 1e-3, 1e-6):
        mobility = pse_mobility(options, POSITIONS, BOX, tolerance=tolerance)
        assert np.max(np.abs(mobility - reference)) < tolerance * MU0, (tolerance, np.max(np.abs(mobility - reference)))


def test_the_force_coupling_method_and_pse_agree(options):
    """The same three particles, 4 to 7.5 radii apart, by both triply periodic methods: FCM's
    Gaussian differs from RPY's sphere by up to 6e-4 mu0 at 4 radii (Keaveny 2014), the grids add
    1e-4 each, so 1e-3 mu0 bounds the difference; a coupling of 0.1 mu0 and more must show in both."""
    box = [11.0, 12.5, 14.0]
    positions = [[0.3, -0.2, 0.1], [4.1, 0.6, -0.8], [-1.5, 4.5, 2.2]]
    by_pse = pse_mobility(options, positions, box)
    by_fcm = measured_mobility(options, positions, box, fcm(), 0.01)
    assert np.max(np.abs(by_pse - by_fcm)) < 1e-3 * MU0
    assert np.max(np.abs(by_pse[0:3, 3:9])) > 0.1 * MU0


def test_the_default_radius_is_the_particles_and_uammds_spelling_is_the_same(options):
    reference = pse_mobility(options, POSITIONS, BOX)
    assert np.array_equal(pse_mobility(options, POSITIONS, BOX, radius=None), reference)
    assert np.array_equal(pse_mobility(options, POSITIONS, BOX, cls="BDHITriplePeriodic"), reference)


def test_single_and_mixed_precision_give_the_same_mobility(options):
    # A long step, so that single-precision positions resolve the displacement to 1e-5 of it.
    reference = pse_mobility(options, POSITIONS, BOX, time_step=1.0)
    for precision in ("single", "mixed"):
        other = pse_mobility(dict(options, precision=precision), POSITIONS, BOX, time_step=1.0)
        assert np.max(np.abs(other - reference)) < 1e-4 * MU0, (precision, np.max(np.abs(other - reference)) / MU0)


@pytest.mark.parametrize("psi, length", [(0.3, 22.0), (1.5, 12.0)])
def test_the_noise_has_covariance_2_kT_dt_M(options, psi, length):
    """Many zero-force steps from the same configuration (reset before each): the sample covariance
    of the displacements against 2 kT dt M, M from the same integrator's deterministic response. An
    element of the sample covariance of n Gaussian vectors has standard error
    sqrt((C_aa C_bb + C_ab^2) / n); every element must be within 4 of them. psi = 0.3 puts half of
    the self-mobility in the near field (Lanczos), 1.5 nine tenths in the far field (Fourier); each
    runs in a box its near field fits."""
    box = [length] * 3
    positions = np.array([[0.2, 0.1, -0.3], [1.9, 0.4, 0.2], [0.1, 3.0, 0.5]])
    time_step, kT, samples = 0.01, 1.7, 3000
    entry = pse(time_step=time_step, tolerance=1e-3, psi=psi)
    mobility = measured_mobility(options, positions, box, entry, time_step)
    expected = 2.0 * kT * time_step * mobility
    moves = noise_samples(options, positions, box, entry, kT, samples)
    assert np.all(np.abs(moves.mean(0)) < 4 * np.sqrt(np.diag(expected) / samples))
    sampled = moves.T @ moves / samples
    standard_error = covariance_standard_error(expected, samples)
    assert np.all(np.abs(sampled - expected) < 4 * standard_error), np.max(np.abs(sampled - expected) / standard_error)
    # The overlapping pair's coupling is resolved: the covariance between them is many errors from 0.
    assert abs(sampled[0, 3]) > 10 * standard_error[0, 3]


def test_a_dilute_suspension_diffuses_with_hasimotos_coefficient(options):
    """64 particles in a box of side 24 a (volume fraction 2 %): the mean square displacement over a
    lag of 20 steps, from non-overlapping windows of the unwrapped trajectories, against
    6 D t with D = kT mu(L), mu(L) Hasimoto's (each particle's self-mobility, whatever the others do;
    the RPY mobility has no divergence). The standard error comes from the spread of the window means
    (the windows of one time are averaged over particles first); 4 of them are allowed, and the
    Hasimoto correction (12 %) is more than 10 of them."""
    length, kT, time_step, lag, windows = 24.0, 1.0, 0.05, 20, 150
    cells = 4
    grid = (np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)], float) + 0.5)
    positions = grid * length / cells - 0.5 * length + np.random.default_rng(5).uniform(-1, 1, (cells ** 3, 3))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, length, pse(time_step=time_step, tolerance=1e-3, psi=0.5), steps=10 ** 7,
                          temperature=kT))
        measured, standard_error = windowed_msd(sim, windows, lag, length)
    expected = 6.0 * kT * hasimoto(RADIUS, length) * lag * time_step
    assert abs(measured - expected) < 4 * standard_error, (measured, expected, standard_error)
    free = 6.0 * kT * MU0 * lag * time_step
    assert abs(measured - free) > 10 * standard_error


def test_particles_outside_the_group_neither_move_nor_push_the_fluid(options):
    """Particle 1, outside the group, is pushed hard along y: it must not move, and the group's
    members must move as the two of them alone would under the push on particle 0 along x."""
    box = 12.0
    positions = np.array([[0.0, 0.0, 0.0], [0.0, -3.0, 0.0], [0.0, 1.5, 0.0]])
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["mobile", "Ids", [0, 2]]]}}
    time_step = 0.01
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, pse(time_step=time_step, group="mobile"), steps=100, force_field=groups))
        sim.external_forces = [[1.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 0.0]]
        sim.step(1)
        moved = minimum_image(sim.positions - positions, box)
    assert np.array_equal(moved[1], [0.0, 0.0, 0.0])
    pair = periodic_rpy(positions[[0, 2]], box)
    assert moved[0] / time_step == pytest.approx(pair[0:3, 0], abs=1e-4 * MU0)
    assert moved[2] / time_step == pytest.approx(pair[3:6, 0], abs=1e-4 * MU0)
    assert abs(moved[2, 0]) > 0.2 * MU0 * time_step, "the group's other member (overlapping) must be carried"
    everyone = periodic_rpy(positions, box)
    assert min(abs(5.0 * everyone[1, 4]), abs(5.0 * everyone[7, 4])) > 0.5 * MU0


def test_a_trapped_particle_samples_boltzmann(options):
    """A force-field term with hydrodynamics: a particle in a harmonic trap of stiffness K. With its
    self-mobility mu (Hasimoto's), Euler-Maruyama samples <K x^2> = kT / (1 - mu K dt / 2) per axis
    exactly; samples one relaxation time apart in 20 blocks give the standard error (4 allowed)."""
    box, kT, stiffness, time_step = 10.0, 1.0, 50.0, 0.05
    measured, error, expected = trapped_particle_energy(options, pse(time_step=time_step, tolerance=1e-3), box, kT,
                                                        stiffness, time_step)
    assert abs(measured - expected) < 4 * error, (measured, expected, error)
    assert error < 0.1 * kT


def test_a_schedule_of_stages_and_brownian_dynamics_between_them(options):
    """PSE, free Brownian dynamics, the same PSE again (its list and mesh kept from its first stage)
    and a PSE at temperature 0: every stage moves the particles, and the last, under a push on
    particle 0, moves particle 1 (overlapping it) as the periodic RPY coupling says."""
    box, time_step = 12.0, 0.01
    positions = np.array([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]])
    doc = document(positions, box, pse(time_step=time_step), temperature=1.0)
    doc["integrator"]["free"] = {"type": ["Brownian", "EulerMaruyama"],
                                 "parameters": {"timeStep": time_step, "viscosity": ETA}}
    doc["integrator"]["cold"] = pse(time_step=time_step, temperature=0.0)
    doc["integrator"]["schedule"]["data"] = [[1, "bd", 3], [2, "free", 3], [3, "bd", 3], [4, "cold", 10]]
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        for _ in range(3):
            before = sim.positions
            sim.step(3)
            assert np.all(np.abs(minimum_image(sim.positions - before, box)) > 0.0)
        before = sim.positions
        sim.external_forces = [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
        sim.step(1)
        moved = minimum_image(sim.positions - before, box) / time_step
    coupling = periodic_rpy(before, box)
    assert moved[1] == pytest.approx(coupling[3:6, 0], abs=1e-4 * MU0)
    assert moved[1, 0] > 0.3 * MU0


def test_a_box_changed_by_the_host_is_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 8.0, pse(psi=2.0), steps=10))
        sim.step(1)
        sim.box = [9.0, 9.0, 9.0]
        with pytest.raises(structmd.UnsupportedError, match=r"bd: the box changed.*PositivelySplitEwald"):
            sim.step(1)


def test_several_batches_are_refused(options):
    doc = document([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]], 8.0, pse(psi=2.0), steps=10, batches=[0, 1])
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match="batches"):
            sim.load(doc)


def test_unequal_radii_need_a_hydrodynamic_radius(options):
    doc = document([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]], 12.0, pse(radius=None), steps=10)
    doc["global"]["types"]["data"].append(["B", 1.0, 0.5, 0.0])
    doc["topology"]["structure"]["data"][1][1] = "B"
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"integrator\.bd\.parameters\.hydrodynamicRadius.*one radius"):
            sim.load(doc)
            sim.step(1)
    doc["integrator"]["bd"]["parameters"]["hydrodynamicRadius"] = 1.0
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)


@pytest.mark.parametrize("parameters, path, message", [
    ({"viscosity": 0.0}, "viscosity", "positive"),
    ({"viscosity": -1.0}, "viscosity", "positive"),
    ({"viscosity": None}, "viscosity", "missing"),
    ({"radius": -0.5}, "hydrodynamicRadius", "positive"),
    ({"psi": 0.0}, "psi", "positive"),
    ({"psi": -0.5}, "psi", "positive"),
    ({"psi": 0.3}, "psi", "more than half the box"),
    ({"psi": 1e6}, "psi", r"more than 2\^30: psi is too large"),  # not SIGFPE (issue 37)
    ({"psi": 1e4}, "psi", r"more than 2\^30"),
    ({"tolerance": 0.5}, "tolerance", r"\[1e-10, 0.1\]"),
    ({"tolerance": 1e-12}, "tolerance", r"\[1e-10, 0.1\]"),
    ({"tolerance": -1e-3}, "tolerance", "positive"),
])
def test_bad_input_names_its_path(options, parameters, path, message):
    assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 12.0, pse(**parameters)),
                           "integrator.bd.parameters." + path, message)


@pytest.mark.parametrize("psi, message", [(1e6, r"more than 2\^30"), (0.3, "more than half the box")])
def test_set_parameter_refuses_a_psi_the_box_cannot_hold(options, psi, message):
    """psi 1e6 by set_parameter stopped the process at the next step (issue 37)."""
    path = "integrator.bd.parameters.psi"
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]], 12.0, pse()))
        sim.step(1)
        assert sim.get_parameter(path) == 1.0
        assert_refused_and_kept(sim, path, psi, message)
