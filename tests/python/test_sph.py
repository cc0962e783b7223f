"""["SPH","Verlet"] (docs/input-format.md): smoothed particle hydrodynamics by velocity Verlet.

The reference here is numpy: the cubic spline kernel (checked to integrate to 1), the density
rho_i = sum_j m_j W_ij and the pressure P_i = K (rho_i - rho_0) it gives, and the force from them;
the engine's force is read from the displacement of one short step (x1 = x0 + dt v0 + dt^2/2 F0/m).
Over longer runs: the momentum, conserved by the antisymmetric pair forces with viscosity, and,
without viscosity, the energy H = sum 1/2 m v^2 + sum m_i u(rho_i) with du/drho = P / rho^2, that is
u = K (ln rho + rho_0 / rho), conserved to O(dt^2).
"""

import numpy as np
import pytest

import structmd

TYPES = [["A", 1.0, 0.5, 0.0], ["B", 1.5, 0.5, 0.0]]  # name, mass, radius, charge
MASS = {row[0]: row[1] for row in TYPES}
H = 0.8             # smoothing length; the support is 2 H
STIFFNESS = 10.0    # K
REST_DENSITY = 0.5  # rho_0, below the fluid's density so the pressure is positive
SOFTENING = 0.001   # of the artificial viscosity, times H^2


def kernel(r, h=H):
    q = r / h
    inner = 1.0 - 1.5 * q ** 2 + 0.75 * q ** 3
    outer = 0.25 * np.clip(2.0 - q, 0.0, None) ** 3
    return np.where(q < 1.0, inner, outer) / (np.pi * h ** 3)


def kernel_derivative(r, h=H):
    q = r / h
    inner = -3.0 * q + 2.25 * q ** 2
    outer = -0.75 * np.clip(2.0 - q, 0.0, None) ** 2
    return np.where(q < 1.0, inner, outer) / (np.pi * h ** 4)


def test_reference_kernel_is_normalised_and_its_derivative_is_its_slope():
    r = np.linspace(0.0, 2.0 * H, 200001)
    integrand = 4.0 * np.pi * r ** 2 * kernel(r)
    assert np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(r)) == pytest.approx(1.0, rel=1e-8)
    mid = 0.5 * (r[1:] + r[:-1])
    np.testing.assert_allclose(np.diff(kernel(r)) / np.diff(r), kernel_derivative(mid), atol=1e-6 / H ** 4)


def document(positions, velocities, types, box, parameters, steps, seed=9):
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "sph", "seed": seed}}},
        "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
                   "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                                "data": [[[box, box, box], 0.1]]}},
        "integrator": {"sph": {"type": ["SPH", "Verlet"], "parameters": parameters},
                       "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                    "data": [[1, "sph", steps]]}},
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, [float(c) for c in p], [float(c) for c in v]]
                           for i, (p, v) in enumerate(zip(positions, velocities))]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": {}},
    }


def sph(time_step, viscosity):
    return {"timeStep": time_step, "support": H, "viscosity": viscosity, "gasStiffness": STIFFNESS,
            "restDensity": REST_DENSITY, "resetVelocities": False}


def fluid(cells=6, spacing=1.0, seed=1, speed=0.3):
    """A perturbed cubic lattice filling a periodic box, types alternating, random velocities of zero
    total momentum."""
    rng = np.random.default_rng(seed)
    grid = np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)], dtype=float)
    box = cells * spacing
    x = (grid + 0.5) * spacing - 0.5 * box + rng.uniform(-0.25, 0.25, grid.shape) * spacing
    types = ["A" if k % 2 else "B" for k in range(len(x))]
    mass = np.array([MASS[t] for t in types])
    v = rng.normal(size=x.shape) * speed
    v -= np.sum(mass[:, None] * v, axis=0) / np.sum(mass)
    return x, v, types, mass, box


def separations(x, box):
    d = x[:, None, :] - x[None, :, :]
    d -= box * np.round(d / box)
    return d, np.sqrt(np.sum(d * d, axis=-1))


def densities(x, mass, box):
    _, r = separations(x, box)
    return np.sum(mass[None, :] * kernel(r), axis=1)  # the self term W(0) included (r_ii = 0)


def reference_forces(x, v, mass, box, viscosity):
    d, r = separations(x, box)
    rho = densities(x, mass, box)
    p_over_rho2 = STIFFNESS * (rho - REST_DENSITY) / rho ** 2
    inside = (r < 2.0 * H) & (r > 0)
    safe = np.where(inside, r, 1.0)
    along = np.sum(d * (v[:, None, :] - v[None, :, :]), axis=-1)
    artificial = -viscosity * along / (r ** 2 + SOFTENING * H ** 2)
    strength = mass[:, None] * mass[None, :] * (p_over_rho2[:, None] + p_over_rho2[None, :] + artificial)
    gradient = np.where(inside, kernel_derivative(r) / safe, 0.0)[:, :, None] * d  # grad_i W(|r_i - r_j|)
    return -np.sum(strength[:, :, None] * gradient, axis=1)


@pytest.mark.parametrize("viscosity", [0.0, 2.0])
def test_force_from_density_and_pressure(options, viscosity):
    x0, v0, types, mass, box = fluid()
    dt = 1e-4
    with structmd.Simulation(options) as sim:
        sim.load(document(x0, v0, types, box, sph(dt, viscosity), 1))
        sim.step(1)
        x1 = sim.positions
    move = x1 - x0
    move -= box * np.round(move / box)
    measured = 2.0 * mass[:, None] * (move - dt * v0) / dt ** 2
    expected = reference_forces(x0, v0, mass, box, viscosity)
    assert np.abs(expected).max() > 1.0
    np.testing.assert_allclose(measured, expected, rtol=0, atol=1e-5 * np.abs(expected).max())


def test_momentum_is_conserved_with_viscosity(options):
    x0, v0, types, mass, box = fluid(seed=2, speed=1.0)
    v0 += np.array([0.3, -0.2, 0.1])  # a net flow, kept
    with structmd.Simulation(options) as sim:
        sim.load(document(x0, v0, types, box, sph(0.01, 2.0), 400))
        sim.step(400)
        v = sim.velocities
    kinetic = lambda u: 0.5 * np.sum(mass[:, None] * u * u)
    assert kinetic(v) < 0.9 * kinetic(v0), "the viscosity should have dissipated energy"
    np.testing.assert_allclose(np.sum(mass[:, None] * v, axis=0), np.sum(mass[:, None] * v0, axis=0),
                               rtol=0, atol=1e-10 * np.sum(mass))


def energy_error(options, time_step, duration):
    """Largest |H(t) - H(0)| over a run without viscosity, sampled 40 times, relative to the kinetic
    energy at the start."""
    x0, v0, types, mass, box = fluid(seed=3, speed=1.0)
    steps = int(round(duration / time_step))

    def energy(x, v):
        rho = densities(x, mass, box)
        internal = STIFFNESS * (np.log(rho) + REST_DENSITY / rho)
        return 0.5 * np.sum(mass[:, None] * v * v) + np.sum(mass * internal)

    start = energy(x0, v0)
    errors = []
    with structmd.Simulation(options) as sim:
        sim.load(document(x0, v0, types, box, sph(time_step, 0.0), steps))
        for _ in range(40):
            sim.step(steps // 40)
            errors.append(abs(energy(sim.positions, sim.velocities) - start))
    return max(errors) / (0.5 * np.sum(mass[:, None] * v0 * v0))


def test_energy_is_conserved_without_viscosity(options):
    coarse = energy_error(options, 0.01, 4.0)
    fine = energy_error(options, 0.005, 4.0)
    assert coarse < 1e-3
    # Velocity Verlet's error is O(dt^2): half the step, a quarter of the error.
    assert 2.5 < coarse / fine < 6.0


def test_the_backend_repeats_the_cpu_trajectory_to_rounding(options):
    if options["backend"] == "cpu":
        pytest.skip("compares another backend with the CPU: run with STRUCTMD_TEST_BACKEND=cuda")
    x0, v0, types, _, box = fluid(seed=4, speed=1.0)
    doc = document(x0, v0, types, box, sph(0.005, 2.0), 50)
    states = []
    for backend_options in ({"backend": "cpu", "precision": "double", "log": "quiet"}, options):
        with structmd.Simulation(backend_options) as sim:
            sim.load(doc)
            sim.step(50)
            states.append((sim.positions, sim.velocities))
    np.testing.assert_allclose(states[1][0], states[0][0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(states[1][1], states[0][1], rtol=0, atol=1e-9)
