"""["FluctuatingHydrodynamics","IncompressibleInertialCoupling"]: the inertial coupling method
(docs/input-format.md) for neutrally buoyant particles in an incompressible fluctuating fluid.

The independent reference, written here with numpy's FFT: the method's discrete operators in a
triply periodic box of n^3 cells of side h (velocities on the cell faces, Peskin's three-point kernel
phi, the projection P = I - conj(D) D^T / |D|^2 with D_d = (1 - exp(-2 pi i m_d / n)) / h):
- the steady mobility  mu = (1 / (eta V)) sum_{k != 0} conj(w_a(k)) P_ab(k) w_b(k) / |D(k)|^2,
- the particles' velocity covariance  <u u^T> = (kT / (rho dV N)) sum_{k != 0} conj(w_a) P_ab w_b,
w_a the transform of the particle's kernel weights on the faces of component a. The Crank-Nicolson
step holds every fluid mode at kT / (rho dV) exactly, so the velocity covariance does not depend on
the time step. With sum_j phi^2 = 1/2 per axis the fluid mass a particle drags is m_f = rho (2h)^3
and <u_a^2> is close to (2/3) kT / m_f (the incompressible fluid's share of the three directions).
"""

import math

import numpy as np
import pytest

import structmd
from periodic_rpy import (assert_checkpoint_carries_the_fluid, assert_refused_at_load, diffusion_from_msd_slopes, document,
                          minimum_image, with_open_z)

HASIMOTO = 2.837297


def icm(time_step=0.5, viscosity=1.0, density=1.0, radius=0.91, **extra):
    parameters = {"timeStep": time_step, "viscosity": viscosity, "density": density, "hydrodynamicRadius": radius,
                  **extra}
    return {"type": ["FluctuatingHydrodynamics", "IncompressibleInertialCoupling"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


# ---- the independent reference --------------------------------------------------------------------

def peskin(r):
    a = np.abs(r)
    out = np.zeros_like(a)
    near, far = a <= 0.5, (a > 0.5) & (a < 1.5)
    out[near] = (1 + np.sqrt(1 - 3 * a[near] ** 2)) / 3
    b = 1 - a[far]
    out[far] = (5 - 3 * a[far] - np.sqrt(np.maximum(1 - 3 * b * b, 0))) / 6
    return out


def face_weights(q, n, length):
    """The kernel's weight on every face of each component, arrays indexed [z, y, x]."""
    h = length / n
    weights = []
    for component in range(3):
        axes = []
        for d in range(3):
            node = (np.arange(n) + 0.5 + (0.5 if component == d else 0.0)) * h - length / 2
            axes.append(peskin(minimum_image(node - q[d], length) / h))
        weights.append(np.einsum("z,y,x->zyx", axes[2], axes[1], axes[0]))
    return weights


def spectral_form(q, n, length, multiplier):
    """(1/N) sum_{k != 0} conj(w_a) P_ab w_b multiplier(|D|^2), 3 x 3."""
    h = length / n
    w = [np.fft.fftn(x) for x in face_weights(np.asarray(q, float), n, length)]
    d1 = (1 - np.exp(-2j * np.pi * np.arange(n) / n)) / h
    d = [np.broadcast_to(d1[None, None, :], (n,) * 3), np.broadcast_to(d1[None, :, None], (n,) * 3),
         np.broadcast_to(d1[:, None, None], (n,) * 3)]
    norm2 = sum(np.abs(x) ** 2 for x in d)
    norm2[0, 0, 0] = 1.0
    form = np.zeros((3, 3))
    for a in range(3):
        for b in range(3):
            term = np.conj(w[a]) * ((a == b) - np.conj(d[a]) * d[b] / norm2) * w[b] * multiplier(norm2)
            term[0, 0, 0] = 0.0
            form[a, b] = term.sum().real / n ** 3
    return form


def grid_mobility(q, n, length, eta):
    return spectral_form(q, n, length, lambda k2: 1.0 / (eta * k2)) / (length / n) ** 3


def velocity_covariance(q, n, length, density, kT):
    return spectral_form(q, n, length, np.ones_like) * kT / (density * (length / n) ** 3)


def hasimoto(a, eta, length):
    return (1 - HASIMOTO * a / length + (4 * math.pi / 3) * (a / length) ** 3) / (6 * math.pi * eta * a)


# ---- the reference itself -------------------------------------------------------------------------

def test_the_reference_kernel_sums_to_one_and_its_squares_to_one_half():
    r = np.linspace(-0.5, 0.5, 11)
    offsets = np.arange(-3, 4)
    sums = peskin(r[:, None] - offsets[None, :]).sum(1)
    squares = (peskin(r[:, None] - offsets[None, :]) ** 2).sum(1)
    assert np.allclose(sums, 1.0, atol=1e-14) and np.allclose(squares, 0.5, atol=1e-14)


# ---- input ----------------------------------------------------------------------------------------

def test_the_thermal_drift_is_small_but_there(options):
    """sumThermalDrift adds the random finite difference's forcing: the same seed with and without it
    gives trajectories that differ, by little (the kernel's mobility hardly changes along a step)."""
    runs = []
    for drift in (False, True):
        with structmd.Simulation(options) as sim:
            sim.load(document([[0.3, 0.1, -0.2]], 8.0, icm(sumThermalDrift=drift), steps=50, temperature=0.01))
            sim.run()
            runs.append(sim.positions.copy())
    difference = np.abs(runs[1] - runs[0]).max()
    assert 0.0 < difference < 1e-3


def test_loads_with_uammd_structureds_parameters_and_defaults(options):
    """Only viscosity, density and hydrodynamicRadius (and the time step) are needed. (The grid the radius
    chooses, n = floor(0.91 L / a) made FFT-friendly, is checked by the next test: 16 cells for L = 16,
    a = 0.91, the grid of its reference.)"""
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], 24.0, icm(radius=0.91), steps=3))
        sim.run()
        assert np.all(np.isfinite(sim.positions))


@pytest.mark.parametrize("parameters, path, message", [
    ({"viscosity": None}, "integrator.bd.parameters.viscosity", "missing"),
    ({"density": None}, "integrator.bd.parameters.density", "missing"),
    ({"radius": None}, "integrator.bd.parameters.hydrodynamicRadius", "missing"),
    ({"density": -1.0}, "integrator.bd.parameters.density", "positive"),
    ({"cellDimX": 8}, "integrator.bd.parameters.cellDimY", "go together"),
    ({"cellDimX": 3, "cellDimY": 8, "cellDimZ": 8}, "integrator.bd.parameters.cellDimX", "at least 4"),
    ({"cellDimX": 8.5, "cellDimY": 8, "cellDimZ": 8}, "integrator.bd.parameters.cellDimX", "whole number"),
])
def test_bad_input_names_its_path(options, parameters, path, message):
    assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 8.0, icm(**parameters)), path, message)


def test_an_open_box_is_refused(options):
    assert_refused_at_load(options, with_open_z(document([[0.0, 0.0, 0.0]], 8.0, icm())), "integrator.bd.type",
                           "periodic")


# ---- deterministic --------------------------------------------------------------------------------

def terminal_velocity(options, position, length, force, steps, **parameters):
    with structmd.Simulation(options) as sim:
        sim.load(document([position], length, icm(**parameters), steps=10 ** 6))
        sim.external_forces = np.array([force])
        sim.step(steps)
        return sim.velocities[0].copy(), sim.positions[0].copy()


def test_a_pulled_particle_reaches_the_grids_mobility_and_hasimotos_to_the_kernels_accuracy(options):
    """A force of 1e-4 (Reynolds number ~1e-5: advection is negligible) along x on a particle in a box of
    16^3 cells, 400 steps of 0.5 (the slowest mode, k = 2 pi / L, decays by 1e-13): the velocity is the
    grid's mobility (numpy reference above) to 2e-4 (the particle moves 1e-3 h meanwhile), and Hasimoto's
    periodic mobility with the kernel's radius a_h = 0.91 h to 3% (the three-point kernel's mobility
    depends on where the particle stands in its cell: from 0.837 to 0.859 mu0 here)."""
    length, n, force = 16.0, 16, 1e-4
    q = np.array([0.3, 0.1, -0.2])
    velocity, _ = terminal_velocity(options, q, length, [force, 0.0, 0.0], 400)
    mobility = grid_mobility(q, n, length, 1.0)
    assert velocity[0] / force == pytest.approx(mobility[0, 0], rel=2e-4)
    assert np.allclose(velocity[1:] / force, mobility[1:, 0], atol=2e-4 * mobility[0, 0])
    assert velocity[0] / force == pytest.approx(hasimoto(0.91 * length / n, 1.0, length), rel=0.03)


def test_without_the_mean_removed_the_total_momentum_grows_by_the_impulse(options):
    """removeTotalMomentum false (its default, true, is the test above: the mean does not grow there): nothing removes the momentum the force puts in, so the fluid's mean
    velocity (all of the momentum: the particles carry no mass of their own) is F t / (rho V) exactly,
    and the particle moves with it on top of its steady velocity relative to the fluid."""
    length, n, force, steps, dt, density = 16.0, 16, 1e-4, 400, 0.5, 1.3
    q = np.array([0.3, 0.1, -0.2])
    # The cells given take precedence over the radius (which alone would give the smallest grid, 4 cells).
    velocity, _ = terminal_velocity(options, q, length, [force, 0.0, 0.0], steps, removeTotalMomentum=False,
                                    density=density, time_step=dt, radius=8.0, cellDimX=n, cellDimY=n, cellDimZ=n)
    mean_fluid = force * steps * dt / (density * length ** 3)
    relative = grid_mobility(q, n, length, 1.0)[0, 0] * force
    assert velocity[0] == pytest.approx(mean_fluid + relative, rel=2e-4)
    assert mean_fluid > 0.5 * relative  # the mean is no small part of it


# ---- thermal --------------------------------------------------------------------------------------

def sample(options, length, count, steps, kT, dt, seed=3):
    rng = np.random.default_rng(seed)
    start = rng.uniform(-length / 2, length / 2, (count, 3))
    velocities, trajectory = [], []
    with structmd.Simulation(options) as sim:
        sim.load(document(start, length, icm(time_step=dt), steps=10 ** 8, temperature=kT, seed=seed))
        previous = sim.positions
        unwrapped = previous.copy()
        for s in range(steps):
            sim.step(1)
            now = sim.positions
            unwrapped += minimum_image(now - previous, length)
            previous = now
            velocities.append(sim.velocities.copy())
            trajectory.append(unwrapped.copy())
    return start, np.array(velocities), np.array(trajectory)


@pytest.fixture(scope="module")
def thermal_run():
    """16 particles in a box of 8^3 cells, kT = 0.01 (fluctuations of 0.1 per cell: advection stays
    small), 8000 steps of 0.5."""
    from conftest import engine_options
    length, n, kT, dt = 8.0, 8, 0.01, 0.5
    start, velocities, trajectory = sample(engine_options(), length, 16, 8000, kT, dt)
    return dict(length=length, n=n, kT=kT, dt=dt, start=start, velocities=velocities, trajectory=trajectory)


def test_particle_velocities_have_the_incompressible_fluids_equipartition(thermal_run):
    """<u_a^2> against the reference covariance averaged over random positions (it varies by 0.5% with
    the position in the cell); 20 blocks of 400 steps, each far longer than the velocity's correlation
    time, give the standard error; 4 of them allowed. And (2/3) kT / m_f, m_f = rho (2h)^3, to 3%."""
    r = thermal_run
    rng = np.random.default_rng(11)
    positions = rng.uniform(-r["length"] / 2, r["length"] / 2, (40, 3))
    expected = np.mean([np.trace(velocity_covariance(q, r["n"], r["length"], 1.0, r["kT"])) / 3 for q in positions])
    blocks = (r["velocities"] ** 2).reshape(20, -1, 16, 3).mean(axis=(1, 2, 3))
    measured, error = blocks.mean(), blocks.std(ddof=1) / math.sqrt(len(blocks))
    assert abs(measured - expected) < 4 * error + 2e-3 * expected, (measured, expected, error)
    assert error < 0.01 * expected  # precise enough that a wrong noise amplitude would show
    fluid_mass = 8.0 * (r["length"] / r["n"]) ** 3
    assert measured == pytest.approx(2.0 / 3.0 * r["kT"] / fluid_mass, rel=0.03)


def test_long_time_diffusion_is_kT_times_the_periodic_mobility(thermal_run):
    """D from the slope of the mean square displacement between lags of 100 and 200 steps (50 and 100
    time units, far beyond the slowest fluid mode's 1 / (nu k_min^2) = 1.6), its standard error from 8
    consecutive windows' slopes (the 16 particles averaged in each); 4 allowed, against kT times the
    reference mobility averaged over positions."""
    r = thermal_run
    traj, dt = r["trajectory"], r["dt"]
    rng = np.random.default_rng(12)
    positions = rng.uniform(-r["length"] / 2, r["length"] / 2, (40, 3))
    expected = r["kT"] * np.mean([np.trace(grid_mobility(q, r["n"], r["length"], 1.0)) / 3 for q in positions])
    measured, error = diffusion_from_msd_slopes(traj, dt, 100)
    assert abs(measured - expected) < 4 * error, (measured, expected, error)
    assert error < 0.1 * expected


def test_a_checkpoint_carries_the_fluid(options, tmp_path):
    """The pulled particle's velocity depends on the flow built up so far."""
    assert_checkpoint_carries_the_fluid(options, icm(), tmp_path / "icm.chk")
