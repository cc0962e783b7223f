"""The engine skips what a scene does not need, proved with structmd_get_counters: a bonded-only
scene builds no neighbour list; steps between measures evaluate no energy or virial; asking for the
forces twice evaluates them once; stepping moves no particle data to the host."""

import numpy as np
import pytest

import structmd

SIDE = 5  # 125 particles on a simple cubic lattice


def document(bonds_only=False, thermo_interval=None, steps=200, side=SIDE):
    spacing = 1.12
    box = side * spacing
    positions = [[(i + 0.5) * spacing - box / 2, (j + 0.5) * spacing - box / 2, (k + 0.5) * spacing - box / 2]
                 for i in range(side) for j in range(side) for k in range(side)]
    n = len(positions)
    force_field = {"bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 20.0, "r0": 1.12},
                             "labels": ["id_i", "id_j"], "data": [[i, i + 1] for i in range(0, n - 1, 2)]}}
    if not bonds_only:
        force_field["nl"] = {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}}
        force_field["lj"] = {"type": ["NonBonded", "LennardJonesType1"],
                             "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                             "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]}
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "counters"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, p] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
                     "forceField": force_field},
    }
    if thermo_interval:
        doc["simulationStep"] = {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                                            "parameters": {"intervalStep": thermo_interval,
                                                           "outputFilePath": "thermo.dat"}}}
    return doc


@pytest.fixture
def sim(options, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with structmd.Simulation(options) as s:
        yield s


def difference(after, before):
    return {key: after[key] - before[key] for key in after}


def test_counters_are_json_with_every_field(sim):
    sim.load(document())
    assert set(sim.counters) == {"force_evaluations", "energy_evaluations", "virial_evaluations",
                                 "neighbour_list_builds", "host_to_device_bytes", "device_to_host_bytes",
                                 "device_memory_bytes", "step_graphs_captured", "step_graphs_replayed",
                                 "domain_rebuilds", "steps_joined"}
    assert all(isinstance(value, int) and value >= 0 for value in sim.counters.values())
    sim.step(100)
    assert sim.counters["domain_rebuilds"] == 0  # one process: no spatial domains


def test_a_bonded_only_scene_builds_no_neighbour_list(sim):
    sim.load(document(bonds_only=True))
    sim.step(100)
    sim.energy("potential")
    assert sim.counters["neighbour_list_builds"] == 0
    sim.load(document())
    sim.step(100)
    assert sim.counters["neighbour_list_builds"] >= 1


def test_steps_without_measures_evaluate_no_energy_or_virial(sim):
    sim.load(document())
    sim.step(100)
    counters = sim.counters
    assert counters["energy_evaluations"] == 0
    assert counters["virial_evaluations"] == 0
    # Velocity Verlet: one force evaluation per step, plus the first at the initial positions.
    assert counters["force_evaluations"] == 101


def test_measures_evaluate_energies_only_at_their_steps(sim):
    sim.load(document(thermo_interval=50))
    sim.step(100)  # the measure fires at steps 0, 50 and 100, where the call ends
    counters = sim.counters
    terms = 2  # one energy pass per forceField entry (bonds, lj) per firing
    assert counters["energy_evaluations"] == 3 * terms
    assert counters["virial_evaluations"] == 3


def test_reading_forces_twice_evaluates_them_once(sim):
    sim.load(document())
    before = sim.counters
    first = sim.forces
    middle = sim.counters
    second = sim.forces
    after = sim.counters
    assert difference(middle, before)["force_evaluations"] == 1
    assert difference(after, middle)["force_evaluations"] == 0
    assert (first == second).all()
    sim.positions = first * 0.0 + sim.positions  # the same values, but set: forces are stale now
    sim.forces
    assert difference(sim.counters, after)["force_evaluations"] == 1


def test_energy_is_evaluated_once_per_state(sim):
    sim.load(document())
    sim.energy("potential")
    once = sim.counters
    sim.energy("potential")
    sim.particle_energies
    assert difference(sim.counters, once)["energy_evaluations"] == 0


def test_device_memory_is_linear_in_the_particle_count(sim):
    held = {}
    for side in (6, 12):
        sim.load(document(side=side))
        sim.step(10)
        held[side] = sim.counters["device_memory_bytes"]
    # positions, velocities and forces alone take 48 bytes a particle in single precision
    assert held[6] >= 48 * 6**3
    assert 6.0 < held[12] / held[6] < 10.0  # 8 times the particles


def test_a_scene_without_pair_terms_holds_no_list_memory(sim):
    sim.load(document(bonds_only=True))
    without_list = sim.counters["device_memory_bytes"]
    sim.load(document())
    sim.step(1)
    # a Verlet list of a liquid takes tens of bytes per particle at least
    assert sim.counters["device_memory_bytes"] - without_list > 20 * SIDE**3


def test_stepping_moves_no_particle_data_to_the_host(sim):
    sim.load(document(steps=1000))
    sim.step(1)
    before = sim.counters
    sim.step(500)
    moved = difference(sim.counters, before)
    assert moved["host_to_device_bytes"] == 0
    # One fault word and one neighbour-list control record per call: a few dozen bytes, whatever N.
    assert moved["device_to_host_bytes"] <= 64, moved
    n = SIDE ** 3
    sim.positions
    assert difference(sim.counters, before)["device_to_host_bytes"] >= moved["device_to_host_bytes"] + 3 * 4 * n


def test_cuda_replays_steps_as_graphs(sim, options):
    sim.load(document(steps=2000))
    sim.step(1000)
    counters = sim.counters
    if options["backend"] == "cuda":
        # 1000 steps in batches of 16: one graph for the full batches, one for the last, shorter one
        assert counters["step_graphs_captured"] <= 4
        assert counters["step_graphs_replayed"] >= 1000 // 16 - 4
    else:
        assert counters["step_graphs_captured"] == counters["step_graphs_replayed"] == 0


def test_steps_without_graphs_repeat_the_run_bit_for_bit(options, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    runs = {}
    for graphs in (True, False):
        with structmd.Simulation({**options, "step_graphs": graphs}) as s:
            s.load(document(steps=2000))
            s.step(300)
            runs[graphs] = (np.array(s.positions), np.array(s.velocities), s.counters)
    (positions, velocities, with_graphs), (positions_issued, velocities_issued, issued) = runs[True], runs[False]
    # the lists were rebuilt during the steps, so the build's conditional kernels ran both ways
    assert issued["neighbour_list_builds"] == with_graphs["neighbour_list_builds"] > 2
    assert np.array_equal(positions_issued, positions)
    assert np.array_equal(velocities_issued, velocities)
    assert issued["step_graphs_captured"] == issued["step_graphs_replayed"] == 0
    if options["backend"] == "cuda":
        assert with_graphs["step_graphs_replayed"] >= 300 // 16 - 4


def run_thermo_steps(options, calls, steps):
    """Positions, velocities, steps_joined and the thermodynamic output after `steps` steps of
    velocity Verlet taken in `calls` equal calls, a measure every 10 steps."""
    with structmd.Simulation(options) as s:
        s.load(document(thermo_interval=10, steps=2000))
        # a lattice at rest feels no force: random velocities make the kicks matter
        s.velocities = np.random.default_rng(7).normal(0.0, 1.0, (SIDE**3, 3))
        for _ in range(calls):
            s.step(steps // calls)
        return np.array(s.positions), np.array(s.velocities), s.counters["steps_joined"]


def test_joined_steps_repeat_the_unjoined_run_bit_for_bit(options, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    positions, velocities, joined = run_thermo_steps(options, 1, 120)
    thermo = (tmp_path / "thermo.dat").read_text()
    (tmp_path / "thermo.dat").unlink()
    positions_apart, velocities_apart, joined_apart = run_thermo_steps(options, 120, 120)
    # Steps 0 .. 119 in one call: each joined to the next, but the last of the call and the 11 before
    # the steps the measure fires at (10 .. 110), which must see full-step velocities.
    assert joined == 119 - 11
    assert joined_apart == 0  # a call of one step ends on its closing kick
    assert np.array_equal(positions, positions_apart)
    assert np.array_equal(velocities, velocities_apart)
    # what the measure saw: the kinetic energy of full-step velocities, as the unjoined run's
    assert (tmp_path / "thermo.dat").read_text() == thermo
    assert not np.allclose(velocities, run_thermo_steps(options, 120, 0)[1])  # the kicks moved them


def test_no_step_joined_while_a_force_callback_is_set(sim):
    sim.load(document(steps=2000))
    sim.set_force_callback(lambda positions, forces, step: 0.0)
    sim.step(50)
    assert sim.counters["steps_joined"] == 0
