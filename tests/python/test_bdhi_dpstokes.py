"""["BDHIDoublyPeriodic","DPStokes"]: Brownian dynamics with hydrodynamic interactions in a fluid
periodic along x and y, open along z ("none"), above a no-slip wall at z = -H/2 ("bottom") or
between walls at z = -H/2 and H/2 ("slit") (docs/input-format.md).

References written here, independent of the engine:
- Open ("none"): the doubly periodic Stokes mobility of Gaussian blobs (sigma = a / sqrt(pi)) from
  the 3D Oseen tensor in Fourier space, the sum over the plane's wave vectors k != 0 (k = 0 left
  out: no net flow, UAMMD's convention) of the integral over q_z done numerically,
    M_ab(r) = 1/(eta A) sum_k int dq_z/(2 pi) exp(i q.r) exp(-q^2 sigma^2) (delta_ab - q_a q_b / q^2) / q^2.
- Bottom wall: the Rotne-Prager-Blake self mobility of Swan & Brady (Phys. Fluids 19, 113306
  (2007)) at height h (lambda = a / h),
    mu_par / mu0 = 1 - 9/16 lambda + 1/8 lambda^3 - 1/16 lambda^5,
    mu_perp / mu0 = 1 - 9/8 lambda + 1/2 lambda^3 - 1/8 lambda^5,
  in an infinite plane: the periodic images' effect falls as 1/L^3 (the plane's mean flow, a plug
  above the forces, is cancelled at leading order by the missing small-k part of the plane's
  integral), so two box sizes extrapolate it away.
- Slit: Faxen's mobility of a sphere midway between two walls a distance 2l apart (Happel & Brenner,
  section 7-4), mu / mu0 = 1 - 1.004 lambda + 0.418 lambda^3 + 0.21 lambda^4 - 0.169 lambda^5,
  lambda = a / l; the slit's images fall as 1/L^2, extrapolated likewise.

The mobility is read column by column from the integrator's own deterministic step at temperature 0
(periodic_rpy.measured_mobility): a force F on one particle along one axis moves every particle by
dt M F.
"""

import math

import numpy as np
import pytest

import periodic_rpy
import structmd

SAMPLES = 1200  # of the Boltzmann test, 5 steps apart

ETA = periodic_rpy.ETA
RADIUS = periodic_rpy.RADIUS
MU0 = periodic_rpy.MU0
SIGMA = RADIUS / math.sqrt(math.pi)


@pytest.fixture
def options(options):
    """One thread on the CPU: these systems are far too small to share out, and on a busy machine
    the threads' barriers (a dozen loops a step for the Lanczos iteration) cost 30 times the work."""
    return dict(options, threads=1) if options["backend"] == "cpu" else options


# ---- input documents ------------------------------------------------------------------------------

def dpstokes(length, height, n, mode, time_step=0.01, nz=None, **extra):
    parameters = {"timeStep": time_step, "viscosity": ETA, "hydrodynamicRadius": RADIUS, "nx": n, "ny": n,
                  "Lx": length, "Ly": length, "H": height, "w": 6, "mode": mode, "nz": nz, **extra}
    return {"type": ["BDHIDoublyPeriodic", "DPStokes"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


def box_of(length, height):
    """The simulation box: the slab's plane, and z periodic far beyond the slab."""
    return [length, length, 2.0 * height]


def mobility(options, positions, length, height, n, mode, **extra):
    time_step = extra.pop("time_step", 0.01)
    return periodic_rpy.measured_mobility(options, positions, box_of(length, height),
                                          dpstokes(length, height, n, mode, time_step=time_step, **extra), time_step)


def document(positions, length, height, entry, **rest):
    return periodic_rpy.document(positions, box_of(length, height), entry, **rest)


# ---- independent references -----------------------------------------------------------------------

def open_mobility(positions, length, a=RADIUS, eta=ETA):
    """The doubly periodic open mobility (3N x 3N) by the Fourier sum over k and quadrature over q_z."""
    sigma = a / math.sqrt(math.pi)
    pos = np.asarray(positions, float)
    cut = 7.0 / sigma
    m = int(math.ceil(cut * length / (2 * math.pi)))
    axis = 2 * math.pi * np.arange(-m, m + 1) / length
    kx, ky = [c.ravel() for c in np.meshgrid(axis, axis, indexing="ij")]
    keep = (kx * kx + ky * ky > 0) & (kx * kx + ky * ky < cut * cut)
    kx, ky = kx[keep], ky[keep]
    qz, dq = np.linspace(-cut, cut, 2801, retstep=True)
    q = [kx[:, None] + 0 * qz, ky[:, None] + 0 * qz, qz[None, :] + 0 * kx[:, None]]
    q2 = q[0] ** 2 + q[1] ** 2 + q[2] ** 2
    weight = np.exp(-q2 * sigma * sigma) / q2 * dq / (2 * math.pi) / (eta * length * length)
    n = len(pos)
    result = np.zeros((3 * n, 3 * n))
    for i in range(n):
        for j in range(n):
            d = pos[i] - pos[j]
            phase = np.exp(1j * (q[0] * d[0] + q[1] * d[1] + q[2] * d[2])) * weight
            for a_ in range(3):
                for b in range(3):
                    projector = (1.0 if a_ == b else 0.0) - q[a_] * q[b] / q2
                    result[3 * i + a_, 3 * j + b] = np.sum(phase * projector).real
    return result


def swan_brady(h, a=RADIUS):
    lam = a / h
    return (1 - 9 / 16 * lam + lam ** 3 / 8 - lam ** 5 / 16), (1 - 9 / 8 * lam + lam ** 3 / 2 - lam ** 5 / 8)


def faxen_midplane(half_gap, a=RADIUS):
    lam = a / half_gap
    return 1 - 1.004 * lam + 0.418 * lam ** 3 + 0.21 * lam ** 4 - 0.169 * lam ** 5


def extrapolated(values, lengths):
    """The L -> infinity limit of v(L) = v + c / L^3 from two box sizes."""
    (v1, v2), (l1, l2) = values, lengths
    return (l2 ** 3 * v2 - l1 ** 3 * v1) / (l2 ** 3 - l1 ** 3)


# ---- the deterministic mobility -------------------------------------------------------------------

def test_the_open_mobility_matches_the_fourier_sum(options):
    """Two particles at different heights in the open slab: every element of M (self, pair, x-z
    coupling across heights) against the Fourier sum, to 1e-4 mu0 at a grid spacing of a/2."""
    positions = [[0.0, 0.0, 0.0], [1.5, 0.7, 1.1]]
    measured = mobility(options, positions, 16.0, 12.0, 32, "none")
    reference = open_mobility(positions, 16.0)
    assert np.max(np.abs(measured - reference)) < 1e-4 * MU0, np.round((measured - reference) / MU0, 6)


def test_the_tolerance_cuts_the_gaussian_within_it(options):
    """The Gaussian is cut where it falls to the tolerance of its peak: four particles (one 0.5 a
    from the bottom wall, one across the box's seam) above a wall and in a slit, every element of M
    at tolerances 1e-2 and 1e-3 within the tolerance (times mu0) of M at 1e-9 on the same grid (at
    most 0.3 of it measured, at grid spacings from 0.8 to 1.9 sigma), and the looser cut more than
    ten times farther from it than the tighter (the tolerance reaches the kernel)."""
    positions = [[0.4, 0.3, -2.2], [2.6, -1.1, -0.9], [-5.9, 5.95, 1.1], [1.0, 1.0, -3.5]]
    for mode in ("bottom", "slit"):
        exact = mobility(options, positions, 12.0, 8.0, 24, mode, tolerance=1e-9)
        errors = {tolerance: np.max(np.abs(mobility(options, positions, 12.0, 8.0, 24, mode, tolerance=tolerance)
                                           - exact)) / MU0 for tolerance in (1e-2, 1e-3)}
        for tolerance, error in errors.items():
            assert error < tolerance, (mode, errors)
        assert errors[1e-2] > 10 * errors[1e-3], (mode, errors)


def test_the_open_mobility_converges_as_the_grid_is_refined(options):
    """The error against the Fourier sum falls from the coarsest grid allowed (spacing 1.8 sigma)
    through 1.2 sigma to 0.9 sigma, by at least 10 at each refinement."""
    positions = [[0.0, 0.0, 0.0], [1.5, 0.7, 1.1]]
    reference = open_mobility(positions, 16.0)
    errors = [np.max(np.abs(mobility(options, positions, 16.0, 12.0, n, "none") - reference)) / MU0
              for n in (16, 24, 32)]
    assert errors[0] > 10 * errors[1] > 100 * errors[2], errors
    assert errors[1] < 1e-3


def test_a_finer_z_grid_changes_little(options):
    """nz given: twice the z nodes of the default moves the mobility by less than 1e-4 mu0 (the z
    kernel is band-limited to the nodes, so the default spacing already resolves the Gaussian)."""
    positions = [[0.0, 0.0, -2.0], [1.5, 0.7, -0.9]]
    default = mobility(options, positions, 12.0, 8.0, 24, "bottom")
    finer = mobility(options, positions, 12.0, 8.0, 24, "bottom", nz=2 * 17 - 1)
    assert np.max(np.abs(finer - default)) < 1e-4 * MU0


@pytest.mark.parametrize("height", [1.5, 2.5, 4.0])
def test_the_self_mobility_above_a_wall_is_rotne_prager_blake(options, height):
    """A particle at height h above the bottom wall (z = -H/2): M_xx, M_yy and M_zz, extrapolated to
    an infinite plane from boxes of 24 and 32 (images fall as 1/L^3), within 1e-2 mu0 of Swan and
    Brady's wall-corrected RPY (the Gaussian blob is not the RPY sphere: 0.6 % apart at h = 1.5 a).
    Without the wall (or with the image of the wrong sign) M_zz would be off by 30 % or more."""
    lengths = (24.0, 32.0)
    blocks = [mobility(options, [[0.3, -0.2, -6.0 + height]], length, 12.0, int(2 * length), "bottom")
              for length in lengths]
    parallel, perpendicular = swan_brady(height)
    measured = {axis: extrapolated([b[axis, axis] for b in blocks], lengths) / MU0 for axis in range(3)}
    assert measured[0] == pytest.approx(parallel, abs=1e-2)
    assert measured[1] == pytest.approx(parallel, abs=1e-2)
    assert measured[2] == pytest.approx(perpendicular, abs=1e-2)
    assert np.max(np.abs(blocks[1] - np.diag(np.diag(blocks[1])))) < 1e-9 * MU0, "x, y, z decouple for one particle"


def test_the_slit_is_symmetric_about_its_midplane(options):
    """A pair and its mirror image through z = 0: M of the one is the reflection (z -> -z) of M of
    the other, and M is symmetric."""
    positions = np.array([[0.3, 0.2, 1.3], [2.0, -1.0, -0.9]])
    mirrored = positions * [1, 1, -1]
    upper = mobility(options, positions, 12.0, 8.0, 24, "slit")
    lower = mobility(options, mirrored, 12.0, 8.0, 24, "slit")
    reflect = np.diag([1.0, 1.0, -1.0, 1.0, 1.0, -1.0])
    assert np.max(np.abs(reflect @ upper @ reflect - lower)) < 1e-9 * MU0
    assert np.max(np.abs(upper - upper.T)) < 1e-9 * MU0
    assert abs(upper[2, 5]) > 0.05 * MU0, "the pair is coupled along z"


def test_the_slit_mobility_is_continuous_across_the_midplane(options):
    """A slit 2.5 a high and a pair, one of them at z = +-1e-6: M agrees on either side to 1e-5 mu0
    (its slope there is about 0.1 mu0 / a). Subtracting only the image through the nearer wall made
    the kernel jump at z = 0 and M with it (by 3e-4 mu0 here: 1 / 1000 of M's largest element)."""
    eps = 1e-6
    sides = [mobility(options, [[0.0, 0.0, sign * eps], [1.5, 0.5, 0.5]], 8.0, 2.5, 16, "slit") for sign in (1, -1)]
    assert np.max(np.abs(sides[0] - sides[1])) < 1e-5 * MU0, np.max(np.abs(sides[0] - sides[1])) / MU0


def test_the_slit_midplane_mobility_is_faxens(options):
    """A particle midway between walls 8 a apart: M_xx extrapolated from boxes of 24 and 32 (the
    slit's images fall as 1/L^2) within 3e-3 mu0 of Faxen's 1 - 1.004 l + 0.418 l^3 + 0.21 l^4 -
    0.169 l^5, l = a / 4 (0.756; the bottom wall alone would give 0.86, no wall 1)."""
    lengths = (24.0, 32.0)
    values = [mobility(options, [[0.0, 0.0, 0.0]], length, 8.0, int(2 * length), "slit")[0, 0] for length in lengths]
    (v1, v2), (l1, l2) = values, lengths
    measured = (l2 ** 2 * v2 - l1 ** 2 * v1) / (l2 ** 2 - l1 ** 2) / MU0
    assert measured == pytest.approx(faxen_midplane(4.0), abs=3e-3)


# ---- noise and thermal drift ----------------------------------------------------------------------

def test_the_noise_has_covariance_2_kT_dt_M(options):
    """Many zero-force steps of a pair near the bottom wall from the same configuration (reset before
    each): the sample covariance of the displacements about their mean against 2 kT dt M, M from the
    same integrator's deterministic response; every element within 4 standard errors
    (periodic_rpy.covariance_standard_error), and the pair's coupling resolved."""
    length, height, n = 12.0, 6.0, 12
    positions = np.array([[0.2, 0.1, -1.2], [1.9, 0.4, -0.6]])
    time_step, kT, samples = 0.01, 1.7, 400
    measured = mobility(options, positions, length, height, n, "bottom", time_step=time_step, tolerance=1e-4)
    expected = 2.0 * kT * time_step * measured
    moves = periodic_rpy.noise_samples(options, positions, box_of(length, height),
                                       dpstokes(length, height, n, "bottom", time_step=time_step, tolerance=1e-4),
                                       kT, samples)
    centred = moves - moves.mean(0)
    sampled = centred.T @ centred / (samples - 1)
    standard_error = periodic_rpy.covariance_standard_error(expected, samples)
    assert np.all(np.abs(sampled - expected) < 4 * standard_error), np.max(np.abs(sampled - expected) / standard_error)
    assert abs(sampled[0, 3]) > 6 * standard_error[0, 3], "the pair's coupling is resolved"


def test_the_thermal_drift_is_kT_times_the_slope_of_the_mobility(options):
    """One particle 2 a above the bottom wall, no force, one long step from the same place many
    times: the mean displacement is dt kT div M, whose only component is dM_zz/dz (measured here by
    central differences of the deterministic M_zz at z +- 0.05), within 4 standard errors of the
    sample mean, and many errors from 0 (a step without the drift fails); x and y have none."""
    length, height, n = 12.0, 8.0, 12
    z = -height / 2 + 2.0
    time_step, kT, samples = 100.0, 1.0, 400
    slope = (mobility(options, [[0.0, 0.0, z + 0.05]], length, height, n, "bottom")[2, 2]
             - mobility(options, [[0.0, 0.0, z - 0.05]], length, height, n, "bottom")[2, 2]) / 0.1
    moves = periodic_rpy.noise_samples(options, [[0.0, 0.0, z]], box_of(length, height),
                                       dpstokes(length, height, n, "bottom", time_step=time_step, tolerance=1e-4),
                                       kT, samples)
    mean, error = moves.mean(0), moves.std(0, ddof=1) / math.sqrt(samples)
    expected = time_step * kT * slope
    assert abs(mean[2] - expected) < 4 * error[2], (mean, expected, error)
    assert expected > 5 * error[2]
    assert np.all(np.abs(mean[:2]) < 4 * error[:2])


def test_trapped_particles_above_a_wall_sample_boltzmann(options):
    """Nine particles in harmonic traps 1.5 a above the bottom wall (K = 4 kT/a^2), where the
    mobility normal to the wall falls steeply towards it: their heights sample exp(-U/kT), mean at
    the trap and variance kT/K, within 4 standard errors (from 10 blocks). Without the thermal drift
    the heights would sample exp(-U/kT) / M_zz(z) instead (Ito), whose mean lies below the trap by
    more than 8 of those errors (to first order, from Swan and Brady's M_zz)."""
    length, height, n = 16.0, 8.0, 16
    trap_height, stiffness, kT, time_step = 1.5, 4.0, 1.0, 0.4
    z0 = -height / 2 + trap_height
    side = 3
    positions = [[-length / 2 + length / side * (i + 0.5), -length / 2 + length / side * (j + 0.5), z0]
                 for i in range(side) for j in range(side)]
    trap = {"trap": {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
                     "data": [[i, stiffness, 0.0, p] for i, p in enumerate(positions)]}}
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, length, height,
                          dpstokes(length, height, n, "bottom", time_step=time_step, tolerance=1e-3),
                          steps=10 ** 7, temperature=kT, force_field=trap))
        sim.step(50)
        heights = []
        for _ in range(SAMPLES):
            sim.step(5)
            heights.append(sim.positions[:, 2] - z0)
    heights = np.array(heights)
    blocks = heights.reshape(10, -1).mean(1)
    mean, error = blocks.mean(), blocks.std(ddof=1) / math.sqrt(len(blocks))
    variances = (heights ** 2).reshape(10, -1).mean(1)
    assert abs(mean) < 4 * error, (mean, error)
    assert abs(variances.mean() - kT / stiffness) < 4 * variances.std(ddof=1) / math.sqrt(10) + 0.02 * kT / stiffness
    # exp(-U/kT) / M_zz to first order: the mean moves by -(kT/K) d ln M_zz / dz.
    slope = (swan_brady(trap_height + 1e-4)[1] - swan_brady(trap_height - 1e-4)[1]) / 2e-4
    shift = -kT / stiffness * slope / swan_brady(trap_height)[1]
    assert shift < -8 * error, (shift, error)


# ---- the rest of the scene ------------------------------------------------------------------------

def test_particles_outside_the_group_neither_move_nor_push_the_fluid(options):
    """Particle 1, outside the group, is pushed hard: it must not move, and the group's members must
    move as the two of them alone do under the push on particle 0."""
    length, height, n = 12.0, 8.0, 24
    positions = np.array([[0.0, 0.0, -2.0], [0.0, -3.0, -2.0], [0.0, 3.5, -1.0]])
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["mobile", "Ids", [0, 2]]]}}
    time_step = 0.01
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, length, height,
                          dpstokes(length, height, n, "bottom", time_step=time_step, group="mobile"),
                          steps=100, force_field=groups))
        sim.external_forces = [[1.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 0.0]]
        sim.step(1)
        moved = sim.positions - positions
    assert np.array_equal(moved[1], [0.0, 0.0, 0.0])
    pair = mobility(options, positions[[0, 2]], length, height, n, "bottom", time_step=time_step)
    assert moved[0] / time_step == pytest.approx(pair[0:3, 0], abs=1e-9)
    assert moved[2] / time_step == pytest.approx(pair[3:6, 0], abs=1e-9)
    assert abs(moved[2, 0]) > 0.01 * MU0 * time_step, "the group's other member must be carried"


def test_the_precisions_give_the_same_mobility(options):
    positions = [[0.4, 0.3, -2.2], [2.6, -1.1, -0.9]]
    # A long step, so that single-precision positions resolve the displacement to 1e-5 of it.
    reference = mobility(options, positions, 12.0, 8.0, 24, "slit", time_step=1.0)
    for precision in ("single", "mixed"):
        other = mobility(dict(options, precision=precision), positions, 12.0, 8.0, 24, "slit", time_step=1.0)
        assert np.max(np.abs(other - reference)) < 1e-4 * MU0


def test_a_trapped_particle_stays_in_its_trap_at_temperature(options):
    """A force-field term with the thermal step in single precision too: a particle in a harmonic
    trap 2.5 a above the wall keeps finite positions near the trap (the Lanczos tolerance is floored
    at what single precision can reach)."""
    trap = {"trap": {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
                     "data": [[0, 5.0, 0.0, [0.0, 0.0, -1.5]]]}}
    for precision in ("double", "single"):
        with structmd.Simulation(dict(options, precision=precision)) as sim:
            sim.load(document([[0.0, 0.0, -1.5]], 12.0, 8.0, dpstokes(12.0, 8.0, 16, "bottom", time_step=0.1),
                              steps=10 ** 6, temperature=1.0, force_field=trap))
            sim.step(50)
            position = sim.positions[0]
        assert np.all(np.isfinite(position)) and np.linalg.norm(position - [0.0, 0.0, -1.5]) < 2.5, position


def test_several_batches_are_refused_by_name(options):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.bd\.type: .*batches"):
            sim.load(document([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]], 12.0, 8.0, dpstokes(12.0, 8.0, 24, "none"),
                              batches=[0, 1]))


@pytest.mark.parametrize("change, path, message", [
    ({"mode": "top"}, "mode", "none"),
    ({"H": -1.0}, "H", "positive"),
    ({"nx": 0}, "nx", "integer >= 1"),
    ({"ny": 2.5}, "ny", "integer"),
    ({"nz": 2}, "nz", "integer >= 3"),
    ({"nx": 8}, "nx", "wider than twice"),
    ({"alpha": 3.5}, "alpha", "at most w/2"),
    ({"w_d": 4, "alpha_d": 2.5}, "alpha_d", "at most w_d/2"),
    ({"tolerance": 0.5}, "tolerance", "0.1"),
    ({"viscosity": None}, "viscosity", "missing"),
    ({"w": None}, "w", "missing"),
    ({"Lx": 13.0}, "Lx", "box's x length"),
    ({"H": 30.0}, "H", "does not fit"),
    ({"mode": "slit", "H": 1.5}, "H", "one diameter"),
    # nx = 2^31 became a negative grid blamed on the radius (issue 37).
    ({"nx": 2 ** 31}, "nx", r"at most 2\^30 grid points, got 2147483648"),
    ({"nx": 2 ** 12, "ny": 2 ** 12, "nz": 2 ** 12}, "nx", r"4096 x 4096 x 4096 points, more than 2\^30"),
])
def test_bad_input_names_its_path(options, change, path, message):
    entry = dpstokes(12.0, 8.0, 24, "none")
    for key, value in change.items():
        if value is None:
            del entry["parameters"][key]
        else:
            entry["parameters"][key] = value
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"integrator\.bd\.parameters\." + path + ".*" + message):
            sim.load(document([[0.0, 0.0, 0.0]], 12.0, 8.0, entry))  # the load alone refuses (Lx, H: issue 37)


@pytest.mark.parametrize("mode, wall", [("bottom", -4.0), ("slit", -4.0), ("slit", 4.0)])
def test_a_particle_on_a_wall_is_named_with_its_step(options, mode, wall):
    """A particle on a wall has a zero row of M: alone it failed the Lanczos square root as "not
    positive definite" with neither step nor particle (issue 37), among others the noise moved it
    across the wall. Refused, named; just inside the wall the step runs."""
    positions = [[0.0, 0.0, 0.0], [1.5, 0.0, 2.0], [3.0, 1.0, wall]]
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, 12.0, 8.0, dpstokes(12.0, 8.0, 24, mode), temperature=1.0))
        with pytest.raises(structmd.NumericalError, match=f"step 1, particle id 2: it lies on the wall at z = {wall:g}"):
            sim.step(1)
        positions[2][2] = 0.999 * wall
        sim.positions = np.array(positions)
        sim.step(1)
