"""["BDHITriplyPeriodic","FluctuatingImmersedBoundary"]: Brownian dynamics with hydrodynamic
interactions in a triply periodic box by the fluctuating immersed boundary method (Delong et al.,
J. Chem. Phys. 140, 134110 (2014); docs/input-format.md).

References, independent of the engine:
- the method's own mobility M = J L^{-1} S written here in numpy (full complex FFTs over the whole
  grid, the kernel evaluated at every node): Peskin's 3-point kernel on the staggered faces and the
  staggered grid's discrete projection and Laplacian, which the engine must give to rounding;
- Hasimoto's self-mobility of a sphere of radius a_h = 0.91 h (h the grid spacing, the radius the
  3-point kernel gives) and Beenakker's Ewald sum of the periodic RPY tensor (periodic_rpy.py), which
  the method approximates to its translational-invariance error;
- fluctuation-dissipation: the covariance of the random displacements is 2 kT dt M, and free particles
  diffuse with kT times the self-mobility, without drift.

The mobility is read column by column from the integrator's own deterministic step at temperature 0
(a force F on one particle along one axis moves every particle by dt M F, the midpoint's shift of J
being of order dt M F / h, 1e-6 here).
"""

import math

import numpy as np
import pytest

import structmd
from periodic_rpy import (ETA, assert_refused_at_load, covariance_standard_error, document, measured_mobility, minimum_image, noise_samples,
                          rpy_ewald, windowed_msd)

HASIMOTO = 2.837297
# The 3-point kernel's translational-invariance error (measured with this file's references, double
# precision): the self-mobility of one particle, against Hasimoto's for a_h = 0.91 h, changes by up to
# 2.2 % with its place in the cell (8 random places, L = 16 h and 30 h), and its mean over those places
# is 0.3-0.4 % above; a pair's mobility differs from the periodic RPY one by 0.9 % of mu0 at 3.2 a_h
# (the kernel is no sphere that close) and by 0.05-0.2 % from 5.4 a_h on.
SPREAD_WITHIN_CELL = 0.03
MEAN_ERROR = 0.01
PAIR_ERROR = 0.015


def fib(time_step=1e-4, viscosity=ETA, radius=1.0, tolerance=None, cls="BDHITriplyPeriodic", **extra):
    parameters = {"timeStep": time_step, "viscosity": viscosity, "hydrodynamicRadius": radius,
                  "tolerance": tolerance, **extra}
    return {"type": [cls, "FluctuatingImmersedBoundary"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


def fib_mobility(options, positions, box, time_step=1e-4, **parameters):
    return measured_mobility(options, positions, box, fib(time_step=time_step, **parameters), time_step)


# ---- independent references -----------------------------------------------------------------------

def grid_cells(box, radius):
    """The even size with factors 2, 3 and 5 closest in ratio to 0.91 L / a along each axis."""
    def friendly(m):
        rest = m
        for p in (2, 3, 5):
            while rest % p == 0:
                rest //= p
        return m % 2 == 0 and rest == 1
    cells = []
    for length in box:
        wanted = 0.91 * length / radius
        candidates = [m for m in range(2, 2 * int(wanted) + 8) if friendly(m)]
        cells.append(min(candidates, key=lambda m: abs(wanted / m - 1)))
    return cells


def peskin3(r):
    r = np.abs(r)
    inner = (1 + np.sqrt(np.clip(1 - 3 * r * r, 0, None))) / 3
    outer = (5 - 3 * r - np.sqrt(np.clip(1 - 3 * (1 - r) ** 2, 0, None))) / 6
    return np.where(r <= 0.5, inner, np.where(r < 1.5, outer, 0.0))


def face_weights(position, component, box, cells):
    """The weights of the component's faces (nodes x_i = -L/2 + i h, shifted by h/2 along that
    component's axis) for a particle at `position`: one array per axis, nearest images."""
    weights = []
    for axis in range(3):
        u = cells[axis] * (position[axis] / box[axis] + 0.5)
        nodes = np.arange(cells[axis]) + (0.5 if axis == component else 0.0)
        distance = nodes - u
        distance -= cells[axis] * np.round(distance / cells[axis])
        weights.append(peskin3(distance))
    return weights


def fib_reference_mobility(positions, box, eta, cells):
    """M = J L^{-1} S on the staggered grid, column by column: S spreads with weight phi phi phi / dV,
    L^{-1} is (I - conj(d) d^T / |d|^2) / (eta |d|^2) with d_a = (1 - exp(-i k_a h_a)) / h_a, k = 0
    removed, and J sums phi phi phi v."""
    pos = np.asarray(positions, float)
    box = np.asarray(box, float)
    spacing = box / np.asarray(cells)
    volume = spacing.prod()
    d = []
    for axis in range(3):
        theta = 2 * np.pi * np.arange(cells[axis]) / cells[axis]
        shape = [1, 1, 1]
        shape[axis] = cells[axis]
        d.append(((1 - np.exp(-1j * theta)) / spacing[axis]).reshape(shape))
    d = np.broadcast_arrays(*d)
    d2 = sum(np.abs(da) ** 2 for da in d)
    d2[0, 0, 0] = 1.0
    mobility = np.zeros((3 * len(pos), 3 * len(pos)))
    for j in range(len(pos)):
        for c in range(3):
            wx, wy, wz = face_weights(pos[j], c, box, cells)
            field = [np.zeros(cells), np.zeros(cells), np.zeros(cells)]
            field[c] = np.einsum("i,j,k->ijk", wx, wy, wz) / volume
            g = [np.fft.fftn(f) for f in field]
            dot = sum(da * ga for da, ga in zip(d, g))
            v = [(ga - np.conj(da) * dot / d2) / (eta * d2) for da, ga in zip(d, g)]
            for va in v:
                va[0, 0, 0] = 0.0
            v = [np.fft.ifftn(va).real for va in v]
            for i in range(len(pos)):
                for a in range(3):
                    wx, wy, wz = face_weights(pos[i], a, box, cells)
                    mobility[3 * i + a, 3 * j + c] = np.einsum("i,j,k,ijk->", wx, wy, wz, v[a])
    return mobility


def hasimoto(a, length, eta=ETA):
    return (1 - HASIMOTO * a / length + (4 * math.pi / 3) * (a / length) ** 3) / (6 * math.pi * eta * a)


# ---- tests ----------------------------------------------------------------------------------------

def test_the_reference_kernel_is_peskins():
    """Its weights on the nodes sum to 1, have first moment 0 and squares summing to 1/2 anywhere."""
    for u in np.linspace(0.0, 1.0, 11):
        nodes = np.arange(-3, 4) - u
        w = peskin3(nodes)
        assert w.sum() == pytest.approx(1.0, abs=1e-14)
        assert (w * nodes).sum() == pytest.approx(0.0, abs=1e-14)
        assert (w * w).sum() == pytest.approx(0.5, abs=1e-14)


def test_the_mobility_is_the_staggered_grids_to_rounding(options):
    """Three particles in an orthorhombic box whose spacings differ (12 x 12 x 16 cells, spacings 1,
    1.17 and 1.03): the engine's M against the numpy one, entry by entry."""
    box = [12.0, 14.0, 16.5]
    positions = [[0.3, -0.2, 0.1], [3.4, 0.9, -0.8], [-1.5, 3.7, 2.6]]
    cells = grid_cells(box, 1.0)
    assert cells == [12, 12, 16]
    mobility = fib_mobility(options, positions, box)
    reference = fib_reference_mobility(positions, box, ETA, cells)
    scale = np.max(np.abs(reference))
    assert np.max(np.abs(mobility - reference)) < 1e-6 * scale, np.max(np.abs(mobility - reference)) / scale
    assert np.allclose(mobility, mobility.T, atol=1e-6 * scale), "M must be symmetric"
    assert np.linalg.eigvalsh(0.5 * (mobility + mobility.T)).min() > 0.0


@pytest.mark.parametrize("length, cells", [(16.0, 16), (32.0, 30)])
def test_one_pushed_particle_moves_with_hasimotos_mobility_of_radius_0_91_h(options, length, cells):
    """A radius of 1 asks for cells of 1 / 0.91: L = 16 gets 16 cells (h = 1), L = 32 gets 30. The
    3-point kernel's self-mobility is that of a sphere of radius 0.91 h, Hasimoto-corrected, to
    within its translational-invariance error: it changes by up to SPREAD_WITHIN_CELL (relative) with
    the particle's place in the cell, and its average over the cell is within MEAN_ERROR of Hasimoto's."""
    assert grid_cells([length] * 3, 1.0) == [cells] * 3
    radius = 0.91 * length / cells
    expected = hasimoto(radius, length)
    rng = np.random.default_rng(3)
    places = rng.uniform(-0.5, 0.5, (8, 3)) * (length / cells) + 0.25
    diagonal = []
    for place in places:
        mobility = fib_mobility(options, [place], length)
        diagonal.extend(np.diag(mobility))
        off_diagonal = mobility - np.diag(np.diag(mobility))
        assert np.max(np.abs(off_diagonal)) < 0.01 * expected
    diagonal = np.array(diagonal)
    assert np.max(np.abs(diagonal / expected - 1)) < SPREAD_WITHIN_CELL, diagonal / expected - 1
    assert abs(diagonal.mean() / expected - 1) < MEAN_ERROR, diagonal.mean() / expected - 1


def test_pair_mobilities_match_the_periodic_rpy_tensor_a_few_radii_apart(options):
    """Particles 3 to 6 radii a_h = 0.91 h apart in a cubic box of 16 cells: the pair blocks against
    Beenakker's Ewald sum of the periodic RPY tensor of spheres of radius a_h. The immersed boundary
    kernel's far field is Oseen's, with a finite-size correction close to RPY's; what differs is the
    kernel's translational invariance (its pair mobility changes with where the particles are in their
    cells), PAIR_ERROR of the Stokes mobility mu0 = 1 / (6 pi eta a_h) at most."""
    length = 16.0
    radius = 0.91
    mu0 = 1.0 / (6 * math.pi * ETA * radius)
    positions = [[0.3, -0.2, 0.1], [3.1, 0.4, -0.3], [-1.4, 4.3, 1.2], [0.8, -1.1, -5.2]]
    mobility = fib_mobility(options, positions, length)
    rpy = rpy_ewald(positions, radius, ETA, [length] * 3, xi=0.5)
    pair = np.ones_like(mobility, bool)
    for i in range(len(positions)):
        pair[3 * i:3 * i + 3, 3 * i:3 * i + 3] = False
    assert np.max(np.abs(mobility - rpy)[pair]) < PAIR_ERROR * mu0, np.max(np.abs(mobility - rpy)[pair]) / mu0
    # The pair terms are no small part of it: a wrong coupling would show.
    assert np.max(np.abs(rpy[pair])) > 0.1 * mu0


def test_the_noise_has_covariance_2_kT_dt_M_and_no_mean(options):
    """Many zero-force steps from the same configuration (reset before each): the sample covariance
    of the displacements against 2 kT dt M, M from the numpy reference. The midpoint moves J by
    about sqrt(2 kT mu dt) / h = 0.03 cells, which changes the covariance by well under its
    statistical error. An element of the sample covariance of n Gaussian vectors has standard error
    sqrt((C_aa C_bb + C_ab^2) / n); every element must be within 4 of them, and so must the mean
    (the drift kT div M of a translation-invariant periodic mobility is 0)."""
    box = 10.0
    positions = np.array([[0.2, 0.1, -0.3], [2.9, 0.4, 0.2]])
    time_step, kT, samples = 0.01, 1.7, 3000
    cells = grid_cells([box] * 3, 1.0)
    expected = 2.0 * kT * time_step * fib_reference_mobility(positions, [box] * 3, ETA, cells)
    moves = noise_samples(options, positions, box, fib(time_step=time_step), kT, samples)
    assert np.all(np.abs(moves.mean(0)) < 4 * np.sqrt(np.diag(expected) / samples))
    sampled = moves.T @ moves / samples
    standard_error = covariance_standard_error(expected, samples)
    assert np.all(np.abs(sampled - expected) < 4 * standard_error), np.max(np.abs(sampled - expected) / standard_error)
    # The pair's coupling is resolved: the covariance between the particles is many errors from 0.
    assert abs(sampled[0, 3]) > 10 * standard_error[0, 3]


def test_free_particles_diffuse_with_kT_times_the_self_mobility_and_do_not_drift(options):
    """27 particles in a box of 24 cells (radius 0.91 h = 0.91): the mean square displacement over a
    lag of 20 steps, from non-overlapping windows of the unwrapped trajectories, against 6 D t with
    D = kT mu, mu Hasimoto's for a_h (allowing MEAN_ERROR for the kernel); the mean displacement of
    every window against 0. Standard errors from the spread of the window means (the fluid correlates
    the particles of one window); 4 of them allowed. The Hasimoto correction (11 %) is about 10 of them."""
    length, kT, time_step, lag, windows = 24.0, 1.0, 0.05, 20, 200
    assert grid_cells([length] * 3, 1.0) == [24] * 3
    radius = 0.91
    cells = 3
    grid = (np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)], float) + 0.5)
    positions = grid * length / cells - 0.5 * length + np.random.default_rng(5).uniform(-1, 1, (cells ** 3, 3))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, length, fib(time_step=time_step), steps=10 ** 7, temperature=kT))
        start = sim.positions
        measured, standard_error = windowed_msd(sim, windows, lag, length)
        # The net displacement of the suspension: the fluid has no net flow, and no drift may appear.
        travelled = minimum_image(sim.positions - start, length)
    expected = 6.0 * kT * hasimoto(radius, length) * lag * time_step
    assert abs(measured - expected) < 4 * standard_error + MEAN_ERROR * expected, (measured, expected, standard_error)
    free = 6.0 * kT * lag * time_step / (6 * math.pi * ETA * radius)
    assert abs(measured - free) > 6 * standard_error
    # Over all 4000 steps each particle has spread by sqrt(2 kT mu t) per axis; their mean, correlated
    # through the fluid, by at most that. The centre of mass moves 4 of them at most.
    spread = math.sqrt(2 * kT * hasimoto(radius, length) * windows * lag * time_step)
    assert np.all(np.abs(travelled.mean(0)) < 4 * spread)


def test_uammd_structureds_documented_example_loads_and_steps(options):
    """The entry of UAMMD-structured's documentation, its registered spelling, at temperature 1: a
    box of 10 with radius 0.5 gets 18 cells (a_h = 0.506); the particles move, stay finite, and a
    particle outside the group does not."""
    entry = {"type": ["BDHITriplePeriodic", "FluctuatingImmersedBoundary"],
             "parameters": {"timeStep": 0.01, "temperature": 1.0, "viscosity": 1.0, "hydrodynamicRadius": 0.5,
                            "tolerance": 1e-4, "group": "mobile"}}
    positions = np.random.default_rng(2).uniform(-5, 5, (20, 3))
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["mobile", "Ids", list(range(19))]]}}
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, 10.0, entry, steps=50, force_field=groups))
        sim.run()
        moved = minimum_image(sim.positions - positions, 10.0)
    assert np.all(np.isfinite(moved))
    assert np.all(np.abs(moved[:19]).max(axis=1) > 0)
    assert np.array_equal(moved[19], [0.0, 0.0, 0.0])
    # 50 steps of diffusion with D = kT mu0 ~ 0.1 move a particle by about 0.5 per axis: not 5.
    assert np.sqrt(np.mean(moved[:19] ** 2)) < 2.0


def test_both_spellings_and_the_precisions_give_the_same_mobility(options):
    positions = [[0.4, 0.3, -0.2], [2.6, -1.1, 0.9]]
    # A long step, so that single-precision positions resolve the displacement to 1e-5 of it.
    reference = fib_mobility(options, positions, 9.0, time_step=1.0)
    assert np.array_equal(fib_mobility(options, positions, 9.0, time_step=1.0, cls="BDHITriplePeriodic"), reference)
    for precision in ("single", "mixed"):
        other = fib_mobility(dict(options, precision=precision), positions, 9.0, time_step=1.0)
        assert np.max(np.abs(other - reference)) < 1e-4 * np.max(np.abs(reference))


def test_the_radius_defaults_to_1(options):
    positions = [[0.4, 0.3, -0.2]]
    given = fib_mobility(options, positions, 12.0)
    entry = fib()
    del entry["parameters"]["hydrodynamicRadius"]
    assert np.array_equal(measured_mobility(options, positions, 12.0, entry, 1e-4), given)


def test_a_box_changed_by_the_host_is_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 8.0, fib(), steps=10))
        sim.step(1)
        sim.box = [9.0, 9.0, 9.0]
        with pytest.raises(structmd.UnsupportedError, match=r"bd: the box changed.*FluctuatingImmersedBoundary"):
            sim.step(1)


def test_several_batches_are_refused(options):
    doc = document([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]], 8.0, fib(), steps=10, batches=[0, 1])
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bd\.type: .*one fluid"):
            sim.load(doc)


@pytest.mark.parametrize("parameters, path, message", [
    ({"viscosity": 0.0}, "integrator.bd.parameters.viscosity", "positive"),
    ({"viscosity": None}, "integrator.bd.parameters.viscosity", "missing"),
    ({"radius": -0.5}, "integrator.bd.parameters.hydrodynamicRadius", "positive"),
    ({"tolerance": -1e-3}, "integrator.bd.parameters.tolerance", "positive"),
    ({"radius": 3.0}, "integrator.bd.parameters.hydrodynamicRadius", "box is too small"),
    ({"radius": 1e-7}, "integrator.bd.parameters.hydrodynamicRadius", r"more than 2\^30"),
])
def test_bad_input_names_its_path(options, parameters, path, message):
    assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 6.0, fib(**parameters)), path, message)
