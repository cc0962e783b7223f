"""["FluctuatingHydrodynamics","CompressibleInertialCoupling"]: the inertial coupling method
(docs/input-format.md) for neutrally buoyant particles in a compressible fluctuating fluid.

The independent reference, written here with numpy's FFT: the method's linearised equations with its
discrete operators, in a triply periodic box of n^3 cells of side h (density on the cell centres,
velocities on the faces, D_d = (1 - exp(-2 pi i m_d / n)) / h the divergence's symbol, G = -D^* the
gradient's, -|D|^2 the Laplacian's, Peskin's three-point kernel phi between particle and faces),
solved exactly in time mode by mode for a constant force density f = S F:
- transverse:    rho v_T' = -eta |D|^2 v_T + f_T,
- longitudinal:  drho' = -rho |D| v_L,   rho v_L' = c^2 |D| drho - (4 eta / 3 + zeta) |D|^2 v_L + f_L
  (a damped sound wave: the force is finally held by a density gradient, so v_L -> 0),
- the mean:      rho v_0' = F / V (the total momentum grows by the impulse; nothing removes it),
the particle's velocity u = J v = (1/N) sum_k conj(w_a(k)) v_a(k), w_a the transform of its kernel
weights on the faces of component a. At equilibrium every face velocity has variance kT / (rho dV)
(less the mean, fixed by momentum conservation), so <u_a^2> = (kT / (rho dV)) (sum_faces w^2 - 1/N)
= (kT / (rho dV)) (1/8 - 1/N) wherever the particle is (sum_j phi^2 = 1/2 per axis).
"""

import math

import numpy as np
import pytest

import structmd
from periodic_rpy import (assert_checkpoint_carries_the_fluid, assert_refused_at_load, diffusion_from_msd_slopes, document,
                          minimum_image, with_open_z)
from test_fluctuating_hydrodynamics import face_weights, grid_mobility



def cicm(time_step=0.05, shear=0.5, bulk=0.3, sound=1.0, density=1.0, radius=None, cells=8, **extra):
    parameters = {"timeStep": time_step, "shearViscosity": shear, "bulkViscosity": bulk, "speedOfSound": sound,
                  "density": density, "hydrodynamicRadius": radius,
                  **({"cellDimX": cells, "cellDimY": cells, "cellDimZ": cells} if cells else {}), **extra}
    return {"type": ["FluctuatingHydrodynamics", "CompressibleInertialCoupling"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


# ---- the independent reference --------------------------------------------------------------------

def pulled_velocity(q, n, length, force, times, eta, zeta, c, rho):
    """u(t) (len(times) x 3) of a particle at q under a constant force switched on at t = 0, the fluid
    at rest before, from the linearised equations above."""
    h, points = length / n, n ** 3
    dV = h ** 3
    w = [np.fft.fftn(x) for x in face_weights(np.asarray(q, float), n, length)]
    f = [w[a] * force[a] / dV for a in range(3)]
    d1 = (1 - np.exp(-2j * np.pi * np.arange(n) / n)) / h
    d = [np.broadcast_to(d1[None, None, :], (n,) * 3), np.broadcast_to(d1[None, :, None], (n,) * 3),
         np.broadcast_to(d1[:, None, None], (n,) * 3)]
    norm2 = sum(np.abs(x) ** 2 for x in d)
    norm2[0, 0, 0] = 1.0
    norm = np.sqrt(norm2)
    e = [np.conj(x) / norm for x in d]  # the longitudinal direction
    f_l = sum(d[a] * f[a] for a in range(3)) / norm
    f_t = [f[a] - f_l * e[a] for a in range(3)]
    # The longitudinal pair y = (drho, v_L): y' = A y + (0, f_L / rho), A = [[0, -rho k], [c^2 k / rho, -nu_l k^2]].
    nu_l = (4 * eta / 3 + zeta) / rho
    a_mat = np.zeros(norm.shape + (2, 2), complex)
    a_mat[..., 0, 1] = -rho * norm
    a_mat[..., 1, 0] = c * c * norm / rho
    a_mat[..., 1, 1] = -nu_l * norm2
    values, vectors = np.linalg.eig(a_mat)
    source = np.stack([np.zeros_like(f_l), f_l / rho], axis=-1)
    coefficients = np.linalg.solve(vectors, source[..., None])[..., 0]
    out = []
    for t in times:
        # y(t) = V diag((e^{lambda t} - 1) / lambda) V^{-1} b
        growth = np.expm1(values * t) / values
        v_l = np.einsum("...j,...j->...", vectors[..., 1, :], growth * coefficients)
        decay = -np.expm1(-eta / rho * norm2 * t) / (eta * norm2)
        u = np.zeros(3)
        for a in range(3):
            v = f_t[a] * decay + v_l * e[a]
            v[0, 0, 0] = f[a][0, 0, 0] * t / rho
            u[a] = (np.conj(w[a]) * v).sum().real / points
        out.append(u)
    return np.array(out)


def test_the_references_steady_state_is_the_incompressible_mobility_plus_the_growing_mean():
    """Long after the force is switched on the sound has died away: the particle moves with the
    incompressible fluid's grid mobility (the other module's reference, which projects the force) on top
    of the mean velocity F t / (rho V)."""
    q, n, length, eta, rho = np.array([0.3, 0.1, -0.2]), 8, 8.0, 0.5, 1.3
    t = 400.0
    u = pulled_velocity(q, n, length, [1.0, 0.0, 0.0], [t], eta, 0.3, 1.0, rho)[0]
    expected = grid_mobility(q, n, length, eta)[:, 0] + np.array([t / (rho * length ** 3), 0.0, 0.0])
    assert np.allclose(u, expected, rtol=1e-9, atol=1e-12)


# ---- input ----------------------------------------------------------------------------------------

def test_loads_with_uammd_structureds_example_and_either_way_of_giving_the_grid(options):
    """UAMMD-structured's documented example (radius and cells both: the cells count), the radius alone
    (n = floor(0.91 L / a): 8 cells for L = 8, a = 0.91) and the cells with a radius of -1 (UAMMD's
    "not given")."""
    example = {"type": ["FluctuatingHydrodynamics", "CompressibleInertialCoupling"],
               "parameters": {"timeStep": 0.01, "temperature": 1.0, "shearViscosity": 1.0, "bulkViscosity": 1.0,
                              "speedOfSound": 10.0, "density": 1.0, "hydrodynamicRadius": 0.5,
                              "cellDimX": 32, "cellDimY": 32, "cellDimZ": 32, "initialCondition": "none"}}
    for entry in (example, cicm(radius=0.91, cells=None), cicm(radius=-1.0)):
        with structmd.Simulation(options) as sim:
            sim.load(document([[0.0, 0.0, 0.0]], 8.0, entry, steps=3))
            sim.run()
            assert np.all(np.isfinite(sim.positions))


@pytest.mark.parametrize("parameters, path, message", [
    ({"shear": None}, "integrator.bd.parameters.shearViscosity", "missing"),
    ({"bulk": None}, "integrator.bd.parameters.bulkViscosity", "missing"),
    ({"sound": None}, "integrator.bd.parameters.speedOfSound", "missing"),
    ({"density": None}, "integrator.bd.parameters.density", "missing"),
    ({"bulk": -1.0}, "integrator.bd.parameters.bulkViscosity", ""),
    ({"sound": 0.0}, "integrator.bd.parameters.speedOfSound", "positive"),
    ({"cells": None}, "integrator.bd.parameters.hydrodynamicRadius", "cellDimX"),
    ({"cells": None, "cellDimX": 8}, "integrator.bd.parameters.cellDimY", "go together"),
    ({"cells": 3}, "integrator.bd.parameters.cellDimX", "at least 4"),
    ({"cells": 8.5}, "integrator.bd.parameters.cellDimX", ""),
    ({"initialCondition": "random"}, "integrator.bd.parameters.initialCondition", "none"),
])
def test_bad_input_names_its_path(options, parameters, path, message):
    assert_refused_at_load(options, document([[0.0, 0.0, 0.0]], 8.0, cicm(**parameters)), path, message)


def test_an_open_box_is_refused(options):
    assert_refused_at_load(options, with_open_z(document([[0.0, 0.0, 0.0]], 8.0, cicm())), "integrator.bd.type",
                           "periodic")


# ---- deterministic --------------------------------------------------------------------------------

def test_a_pulled_particle_follows_the_linearised_compressible_fluid(options):
    """A force of 1e-4 along (1, 0.5, -0.3) switched on at t = 0 on a particle in a box of 8^3 cells at
    rest: its velocity over 20 time units (sound crosses the box 2.5 times; c dt / h = 0.05) against the
    reference, sampled every 10 steps, to 3e-5 of the largest velocity (it agrees to 5e-6: RK3's error
    at the start, and the particle's 2e-4 h of motion later)."""
    length, n, dt, force = 8.0, 8, 0.05, 1e-4 * np.array([1.0, 0.5, -0.3])
    q = np.array([0.3, 0.1, -0.2])
    eta, zeta, c, rho = 0.5, 0.3, 1.0, 1.3
    measured = []
    with structmd.Simulation(options) as sim:
        sim.load(document([q], length, cicm(time_step=dt, shear=eta, bulk=zeta, sound=c, density=rho), steps=10 ** 6))
        sim.external_forces = np.array([force])
        for _ in range(40):
            sim.step(10)
            measured.append(sim.velocities[0].copy())
    times = dt * 10 * np.arange(1, 41)
    expected = pulled_velocity(q, n, length, force, times, eta, zeta, c, rho)
    scale = np.abs(expected).max()
    assert np.abs(np.array(measured) - expected).max() < 3e-5 * scale, np.abs(np.array(measured) - expected).max() / scale


def test_particles_outside_the_group_neither_move_nor_push(options):
    """A group of particle 0 alone: particle 1, pulled too, stays where it is, and particle 0 moves as if
    particle 1 were not there."""
    length = 8.0
    q = [[0.3, 0.1, -0.2], [2.0, -1.0, 1.5]]
    forces = np.array([[1e-3, 0.0, 0.0], [0.0, 2e-3, 0.0]])
    groups = {"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                         "data": [["first", "Ids", [0]]]}}
    doc = document(q, length, cicm(group="first"), steps=10 ** 6, force_field=groups)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.external_forces = forces
        sim.step(40)
        both = sim.positions.copy()
    with structmd.Simulation(options) as sim:
        sim.load(document(q[:1], length, cicm(), steps=10 ** 6))
        sim.external_forces = forces[:1]
        sim.step(40)
        alone = sim.positions.copy()
    assert np.array_equal(both[1], np.array(q[1]))
    assert np.allclose(both[0], alone[0], rtol=0, atol=1e-14)
    assert np.abs(alone[0] - q[0]).max() > 1e-4


def test_a_checkpoint_carries_the_fluid(options, tmp_path):
    """The pulled particle's velocity depends on the flow and the sound built up so far."""
    assert_checkpoint_carries_the_fluid(options, cicm(), tmp_path / "cicm.chk")


# ---- thermal --------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def thermal_run():
    """16 particles in 8^3 cells, kT = 1e-4 (density and velocity fluctuations of 1%: linear), eta 0.5,
    zeta 0.2, c 1, dt 0.05: 600 steps from rest (the slowest modes' variances relax by e^-15), then
    16000 steps."""
    from conftest import engine_options
    length, n, kT, dt, count = 8.0, 8, 1e-4, 0.05, 16
    start = np.random.default_rng(3).uniform(-length / 2, length / 2, (count, 3))
    velocities, trajectory = [], []
    with structmd.Simulation(engine_options()) as sim:
        sim.load(document(start, length, cicm(time_step=dt, shear=0.5, bulk=0.2), steps=10 ** 8, temperature=kT, seed=5))
        sim.step(600)
        previous = sim.positions
        unwrapped = previous.copy()
        for _ in range(16000):
            sim.step(1)
            now = sim.positions
            unwrapped += minimum_image(now - previous, length)
            previous = now
            velocities.append(sim.velocities.copy())
            trajectory.append(unwrapped.copy())
    return dict(length=length, n=n, kT=kT, dt=dt, start=start, velocities=np.array(velocities),
                trajectory=np.array(trajectory))


def test_particle_velocities_have_the_compressible_fluids_equipartition(thermal_run):
    """<u_a^2> against (kT / (rho dV)) (1/8 - 1/N) (the same wherever the particle is); 20 blocks of 800
    steps give the standard error, 4 of them allowed, and it must be below 1% (precise enough that a
    wrong noise amplitude would show)."""
    r = thermal_run
    blocks = (r["velocities"] ** 2).reshape(20, -1, 16, 3).mean(axis=(1, 2, 3))
    measured, error = blocks.mean(), blocks.std(ddof=1) / math.sqrt(len(blocks))
    expected = r["kT"] * (1 / 8 - 1 / r["n"] ** 3)
    assert abs(measured - expected) < 4 * error + 2e-3 * expected, (measured, expected, error)
    assert error < 0.01 * expected


def test_long_time_diffusion_is_kT_times_the_incompressible_mobility(thermal_run):
    """The longitudinal modes' velocity correlations integrate to 0 (a steady force on them is held by
    a density gradient, as the reference's steady state shows) and the total momentum stays 0, so the
    long-time diffusion coefficient is kT times the incompressible fluid's grid mobility (the other
    module's reference) at the particles' places (they move 0.1 h meanwhile). D from the slope of the
    mean square displacement between lags of 300 and 600 steps (15 and 30 time units; the slowest
    transverse mode decays in 3.4 and the slowest sound wave in 4), its standard error from 8
    consecutive windows' slopes; 4 allowed."""
    r = thermal_run
    traj, dt = r["trajectory"], r["dt"]
    expected = r["kT"] * np.mean([np.trace(grid_mobility(q, r["n"], r["length"], 0.5)) / 3 for q in r["start"]])
    measured, error = diffusion_from_msd_slopes(traj, dt, 300)
    assert abs(measured - expected) < 4 * error, (measured, expected, error)
    assert error < 0.1 * expected
