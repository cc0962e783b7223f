"""["DPD","Verlet"] (docs/input-format.md): dissipative particle dynamics by velocity Verlet.

Its pair force, each part alone, against numpy from the displacement of one short step (x1 = x0 +
dt v0 + dt^2/2 F0/m, so F0 = 2 m (x1 - x0 - dt v0) / dt^2); the conservation of momentum that the
pair-symmetric noise gives; and the fluid it makes, at Groot and Warren's (1997) standard state
(rho = 3, a = 25, gamma = 4.5, k_B T = 1, r_c = 1) and one more: its equation of state
p = rho k_B T + alpha a rho^2, and its temperature at their time step 0.04.

The equation of state's reference values are Allen and Tildesley's DPD example (the examples of
"Computer Simulation of Liquids", 2nd ed., wiki page "Fortran Simulation DPD"), simulated with two
other thermostats (Lowe and Shardlow) to +-0.003: p = 23.637 at rho = 3, a = 25 and p = 32.622 at
rho = 4, a = 18.75 (a rho = 75 k_B T for both), k_B T = 1. Groot and Warren's fit alpha = 0.101 is
rough there: those pressures give alpha = 0.0917 and 0.0954.
"""

import numpy as np
import pytest

import structmd

CUTOFF = 1.0
TYPES = [["A", 1.0, 0.5, 0.0], ["B", 2.0, 0.5, 0.0]]  # name, mass, radius, charge
MASS = {row[0]: row[1] for row in TYPES}


def document(positions, types, box, parameters, steps, temperature=1.0, velocities=None, seed=5):
    labels = ["id", "position"] + (["velocity"] if velocities is not None else [])
    rows = [[i, [float(c) for c in p]] + ([[float(c) for c in velocities[i]]] if velocities is not None else [])
            for i, p in enumerate(positions)]
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "dpd", "seed": seed}}},
        "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
                   "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                                "data": [[[box, box, box], temperature]]}},
        "integrator": {"dpd": {"type": ["DPD", "Verlet"], "parameters": parameters},
                       "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                    "data": [[1, "dpd", steps]]}},
        "state": {"labels": labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": {}},
    }


def dpd(time_step, gamma, alpha, **extra):
    return {"timeStep": time_step, "cutOff": CUTOFF, "gamma": gamma, "alpha": alpha, **extra}


def separations(x, box):
    """r_i - r_j for every pair (n x n x 3), by the minimum image, and their lengths."""
    d = x[:, None, :] - x[None, :, :]
    d -= box * np.round(d / box)
    return d, np.sqrt(np.sum(d * d, axis=-1))


def random_fluid(n, box, seed):
    rng = np.random.default_rng(seed)
    types = ["A" if k % 2 else "B" for k in range(n)]
    return rng.uniform(-box / 2, box / 2, (n, 3)), types, np.array([MASS[t] for t in types])


def force_from_one_step(options, doc, x0, v0, mass, dt, box):
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)
        x1 = sim.positions
    move = x1 - x0
    move -= box * np.round(move / box)
    return 2.0 * mass[:, None] * (move - dt * v0) / dt ** 2


def test_conservative_force_is_a_soft_repulsion(options):
    # gamma = 0: no friction and no noise, so F_i = sum_j a (1 - r/r_c) e_ij alone.
    n, box, dt, a = 60, 4.0, 1e-3, 25.0
    x0, types, mass = random_fluid(n, box, seed=1)
    v0 = np.zeros((n, 3))
    doc = document(x0, types, box, dpd(dt, 0.0, a, resetVelocities=False), 1, velocities=v0)
    d, r = separations(x0, box)
    inside = (r < CUTOFF) & (r > 0)
    weight = np.where(inside, a * (1.0 - r / CUTOFF) / np.where(inside, r, 1.0), 0.0)
    expected = np.sum(weight[:, :, None] * d, axis=1)
    measured = force_from_one_step(options, doc, x0, v0, mass, dt, box)
    assert np.abs(expected).max() > 10.0, "the configuration should have overlapping pairs"
    np.testing.assert_allclose(measured, expected, rtol=0, atol=1e-6 * np.abs(expected).max())


def test_a_group_moves_alone_and_feels_its_own_members_only(options):
    # Group "typeA": the B particles stay exactly where they are, and the A particles feel only one
    # another (gamma = 0: the conservative force alone).
    n, box, dt, a = 60, 4.0, 1e-3, 25.0
    x0, types, mass = random_fluid(n, box, seed=9)
    v0 = np.zeros((n, 3))
    doc = document(x0, types, box, dpd(dt, 0.0, a, resetVelocities=False, group="typeA"), 1, velocities=v0)
    doc["integrator"]["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                   "data": [["typeA", "Types", ["A"]]]}
    member = np.array([t == "A" for t in types])
    d, r = separations(x0, box)
    inside = (r < CUTOFF) & (r > 0) & member[:, None] & member[None, :]
    weight = np.where(inside, a * (1.0 - r / CUTOFF) / np.where(inside, r, 1.0), 0.0)
    expected = np.sum(weight[:, :, None] * d, axis=1)
    measured = force_from_one_step(options, doc, x0, v0, mass, dt, box)
    assert np.all(measured[~member] == 0.0), "a particle outside the group moved"
    np.testing.assert_allclose(measured[member], expected[member], rtol=0, atol=1e-6 * np.abs(expected).max())


def test_dissipative_force_damps_relative_velocity_along_the_line(options):
    # Temperature 0 and a = 0: the noise is 0 and F_i = -gamma sum_j w^2 (e_ij . v_ij) e_ij.
    n, box, dt, gamma = 60, 4.0, 1e-3, 4.5
    x0, types, mass = random_fluid(n, box, seed=2)
    v0 = np.random.default_rng(3).normal(size=(n, 3))
    doc = document(x0, types, box, dpd(dt, gamma, 0.0, resetVelocities=False, temperature=0.0), 1, velocities=v0)
    d, r = separations(x0, box)
    inside = (r < CUTOFF) & (r > 0)
    safe = np.where(inside, r, 1.0)
    e = d / safe[:, :, None]
    w = np.where(inside, 1.0 - r / CUTOFF, 0.0)
    along = np.sum(e * (v0[:, None, :] - v0[None, :, :]), axis=-1)
    expected = np.sum((-gamma * w ** 2 * along)[:, :, None] * e, axis=1)
    measured = force_from_one_step(options, doc, x0, v0, mass, dt, box)
    assert np.abs(expected).max() > 1.0
    np.testing.assert_allclose(measured, expected, rtol=0, atol=1e-6 * np.abs(expected).max())


def test_momentum_is_conserved_with_noise(options):
    # The random force of a pair is one number for both particles, so it cancels in the total: the
    # momentum stays what it was to rounding, while the velocities themselves change completely.
    n, box = 200, 4.0
    x0, types, mass = random_fluid(n, box, seed=4)
    v0 = np.random.default_rng(5).normal(size=(n, 3)) / np.sqrt(mass)[:, None]
    doc = document(x0, types, box, dpd(0.02, 4.5, 25.0, resetVelocities=False), 300, velocities=v0)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(300)
        v = sim.velocities
    before, after = np.sum(mass[:, None] * v0, axis=0), np.sum(mass[:, None] * v, axis=0)
    assert np.abs(v - v0).max() > 1.0, "the thermostat should have changed the velocities"
    np.testing.assert_allclose(after, before, rtol=0, atol=1e-9 * np.sum(mass))


def fluid_averages(options, density, a, time_step, equilibration, samples, every, box=5.0, pressure=True):
    """Mean kinetic k_B T and (where `pressure`) mean excess pressure (1/3V) sum_{i<j} r_ij . F^C_ij of
    a one-type fluid (mass 1, k_B T = 1, gamma = 4.5) started at random positions, the velocities
    drawn by the integrator."""
    n = int(round(density * box ** 3))
    x0 = np.random.default_rng(11).uniform(-box / 2, box / 2, (n, 3))
    doc = document(x0, ["A"] * n, box, dpd(time_step, 4.5, a), equilibration + samples * every)
    kinetic, excess = [], []
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(equilibration)
        for _ in range(samples):
            sim.step(every)
            kinetic.append(np.sum(sim.velocities ** 2) / (3 * n))
            if not pressure:
                continue
            _, r = separations(sim.positions, box)
            inside = (r < CUTOFF) & (r > 0)
            excess.append(np.sum(a * (1.0 - r[inside] / CUTOFF) * r[inside]) / 2 / (3 * box ** 3))
    return float(np.mean(kinetic)), float(np.mean(excess)) if pressure else None


@pytest.mark.parametrize("density, a, reference", [(3.0, 25.0, 23.637), (4.0, 18.75, 32.622)])
def test_equation_of_state(options, density, a, reference):
    # At dt = 0.04 (Groot and Warren's step): the excess pressure p - rho k_B T against the reference
    # to 1% (its statistical error here is about 0.2%), and Groot and Warren's form alpha a rho^2
    # with alpha about 0.1 (their 0.101 within 10%).
    kt, excess = fluid_averages(options, density, a, 0.04, 500, 100, 10)
    assert excess == pytest.approx(reference - density, rel=0.01)
    assert excess / (a * density ** 2) == pytest.approx(0.101, rel=0.1)
    assert density * kt + excess == pytest.approx(reference, rel=0.02)


def test_temperature_at_the_standard_time_step(options):
    # Velocity Verlet with the dissipative force at the half-step velocities (Groot and Warren's
    # lambda = 1/2) runs about 3% hot at dt = 0.04 and converges to k_B T as dt^2. The kinetic
    # temperature of this fluid is correlated over about one time unit (a long run's block averages),
    # so a mean over 100 time units has a standard error of about 0.0045 k_B T, and over 50, 0.0065. A
    # noise amplitude off by sqrt(2) would miss by a factor 2, one off by 10% by 20%.
    hot, _ = fluid_averages(options, 3.0, 25.0, 0.04, 300, 500, 5, pressure=False)
    assert 1.01 < hot < 1.05
    fine, _ = fluid_averages(options, 3.0, 25.0, 0.01, 600, 500, 10, pressure=False)
    assert fine == pytest.approx(1.0, abs=0.02)
    assert fine < hot


def test_checkpoint_restart_continues_the_same_trajectory(options, tmp_path):
    # The pair forces kept for the next step's first half kick are saved with the state: without them
    # the restart would compute them from the full-step velocities and leave the trajectory.
    n, box = 120, 4.0
    x0, types, _ = random_fluid(n, box, seed=6)
    doc = document(x0, types, box, dpd(0.04, 4.5, 25.0), 40)
    with structmd.Simulation(options) as whole:
        whole.load(doc)
        whole.step(40)
        uninterrupted = whole.positions, whole.velocities
    path = tmp_path / "dpd.chk"
    with structmd.Simulation(options) as first:
        first.load(doc)
        first.step(17)
        first.save_checkpoint(path)
    with structmd.Simulation(options) as second:
        second.load(doc)
        second.load_checkpoint(path)
        second.step(23)
        restarted = second.positions, second.velocities
        exact = second.info["backend"] == "cpu"
    for a, b in zip(restarted, uninterrupted):
        if exact:
            assert np.array_equal(a, b), "the restarted run left the trajectory"
        else:
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-9)


def test_several_batches_are_refused_since_they_would_share_one_fluid(options):
    x0, types, _ = random_fluid(4, 4.0, seed=7)
    doc = document(x0, types, 4.0, dpd(0.01, 4.5, 25.0), 5)
    doc["topology"]["structure"] = {"labels": ["id", "type", "batchId"],
                                    "data": [[i, t, i % 2] for i, t in enumerate(types)]}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"integrator\.dpd\.type: .*batch"):
            sim.load(doc)


def final_state(options, seed, steps):
    n, box = 150, 4.0
    x0, types, _ = random_fluid(n, box, seed=8)
    with structmd.Simulation(options) as sim:
        sim.load(document(x0, types, box, dpd(0.04, 4.5, 25.0), steps, seed=seed))
        sim.step(steps)
        return sim.positions, sim.velocities


def test_the_same_seed_repeats_the_trajectory_bit_for_bit_on_any_thread_count(options):
    if options["backend"] != "cpu":
        pytest.skip("thread counts are a CPU matter; the CPU run of this suite covers them")
    cpu = {"backend": "cpu", "precision": "double", "log": "quiet"}
    one = final_state(dict(cpu, threads=1), 21, 100)
    two = final_state(dict(cpu, threads=2), 21, 100)
    other = final_state(dict(cpu, threads=2), 22, 100)
    assert np.array_equal(one[0], two[0]) and np.array_equal(one[1], two[1])
    assert np.abs(other[1] - one[1]).max() > 0.1, "another seed, another trajectory"


def test_the_backend_repeats_the_cpu_trajectory_to_rounding(options):
    if options["backend"] == "cpu":
        pytest.skip("compares another backend with the CPU: run with STRUCTMD_TEST_BACKEND=cuda")
    # The same pair noise on both; 20 steps, before chaos amplifies rounding (1e-16) past 1e-9.
    cpu = {"backend": "cpu", "precision": "double", "log": "quiet"}
    expected = final_state(cpu, 21, 20)
    measured = final_state(options, 21, 20)
    np.testing.assert_allclose(measured[0], expected[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(measured[1], expected[1], rtol=0, atol=1e-9)
