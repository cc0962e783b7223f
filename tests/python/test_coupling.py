"""Coupling calls through the Python package: subsets by id (structmd_get_positions_of, ...), the
host's external field energy (structmd_set_external_energy) and run-time parameters
(structmd_set_parameter / structmd_get_parameter). Each result is compared with what the whole-array
calls, or a freshly loaded input, give for the same state."""


import numpy as np
import pytest

import structmd
import systems

SPACING = 1.12


def lattice(side=10, bond_k=20.0, steps=1000, thermo=None, integrator=None):
    """side^3 particles on a simple cubic lattice: LJ between all of them, a HarmonicCommon_K_r0 bond
    between particles 2k and 2k+1, velocity Verlet (or the integrator given)."""
    box = side * SPACING
    positions = [[(i + 0.5) * SPACING - box / 2, (j + 0.5) * SPACING - box / 2, (k + 0.5) * SPACING - box / 2]
                 for i in range(side) for j in range(side) for k in range(side)]
    n = len(positions)
    rng = np.random.default_rng(3)
    velocities = (0.3 * rng.standard_normal((n, 3))).tolist()
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "coupling", "seed": 5}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
        },
        "integrator": {
            "vv": integrator or {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, p, v] for i, (p, v) in enumerate(zip(positions, velocities))]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"],
                       "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]},
                "bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": bond_k, "r0": SPACING},
                          "labels": ["id_i", "id_j"], "data": [[i, i + 1] for i in range(0, n - 1, 2)]},
            },
        },
    }
    if thermo:
        doc["simulationStep"] = {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                                            "parameters": {"intervalStep": thermo[1], "outputFilePath": thermo[0]}}}
    return doc


@pytest.fixture
def handles(options):
    made = []

    def make(doc):
        sim = structmd.Simulation(options)
        made.append(sim)
        sim.load(doc)
        return sim

    yield make
    for sim in made:
        sim.close()


IDS = [417, 3, 999, 0, 512, 58, 7, 731, 260, 88]  # unsorted on purpose


def moved(counters_before, counters_after):
    return (counters_after["host_to_device_bytes"] - counters_before["host_to_device_bytes"],
            counters_after["device_to_host_bytes"] - counters_before["device_to_host_bytes"])


# ---- subsets: values ---------------------------------------------------------------------------

def test_subset_getters_give_the_rows_of_the_whole_arrays_in_the_order_of_the_ids(handles):
    sim = handles(lattice())
    sim.step(25)
    np.testing.assert_array_equal(sim.positions_of(IDS), sim.positions[IDS])
    np.testing.assert_array_equal(sim.velocities_of(IDS), sim.velocities[IDS])
    np.testing.assert_array_equal(sim.forces_of(IDS), sim.forces[IDS])
    assert sim.positions_of([]).shape == (0, 3)


def test_subset_setters_equal_the_whole_array_setters_with_those_rows_changed(handles):
    a, b = handles(lattice()), handles(lattice())
    a.step(10)
    b.step(10)
    box = a.box
    rng = np.random.default_rng(11)
    new_positions = a.positions[IDS] + rng.uniform(-0.05, 0.05, (len(IDS), 3))
    new_positions[0, 0] += 3 * box[0]  # far outside the box: wrapped like set_positions does
    new_positions[1, 2] -= 2 * box[2]
    new_velocities = rng.standard_normal((len(IDS), 3))
    forces_before = a.forces  # current, so the subset setter must make them stale
    a.set_positions_of(IDS, new_positions)
    a.set_velocities_of(IDS, new_velocities)
    whole = b.positions
    whole[IDS] = new_positions
    b.positions = whole
    whole = b.velocities
    whole[IDS] = new_velocities
    b.velocities = whole

    np.testing.assert_array_equal(a.positions, b.positions)
    assert np.all(np.abs(a.positions) <= box / 2)
    np.testing.assert_array_equal(a.velocities, b.velocities)
    assert not np.array_equal(a.forces, forces_before)
    np.testing.assert_array_equal(a.forces, b.forces)
    assert a.energy("total") == b.energy("total")
    a.step(50)
    b.step(50)
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.velocities, b.velocities)


def test_setting_positions_of_a_subset_invalidates_forces_and_the_list(handles):
    sim = handles(lattice())
    sim.compute()
    before = sim.counters
    sim.forces_of(IDS)
    assert sim.counters["force_evaluations"] == before["force_evaluations"]  # current: nothing to do
    sim.set_positions_of([IDS[0]], sim.positions_of([IDS[0]]) + 0.01)
    sim.forces_of(IDS)
    after = sim.counters
    assert after["force_evaluations"] == before["force_evaluations"] + 1
    assert after["neighbour_list_builds"] == before["neighbour_list_builds"] + 1


def test_external_forces_of_a_subset_start_from_zero_and_compose_with_the_whole_array(handles):
    sim = handles(lattice())
    internal = sim.forces
    n = len(internal)
    f = np.arange(3 * len(IDS), dtype=float).reshape(-1, 3) - 7.5
    sim.set_external_forces_of(IDS, f)
    expected = np.zeros((n, 3))
    expected[IDS] = f
    np.testing.assert_allclose(sim.forces, internal + expected, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(sim.external_forces, expected)

    whole = np.full((n, 3), 0.25)
    sim.external_forces = whole  # the whole array replaces everything
    np.testing.assert_allclose(sim.forces, internal + 0.25, rtol=0, atol=1e-12)
    sim.set_external_forces_of([5, 6], [[1.0, 2.0, 3.0], [-1.0, 0.0, 0.5]])  # changes only these two
    whole[5], whole[6] = [1.0, 2.0, 3.0], [-1.0, 0.0, 0.5]
    np.testing.assert_allclose(sim.forces, internal + whole, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(sim.external_forces, whole)
    sim.external_forces = None
    np.testing.assert_allclose(sim.forces, internal, rtol=0, atol=1e-12)


def test_changing_the_field_updates_current_forces_without_evaluating_them_again(handles):
    # A coupling loop sets its field every step: the forces of the present positions change by the
    # field's difference in place (structmd_set_external_forces[_of]), with no new force evaluation.
    sim = handles(lattice())
    internal = sim.forces
    n = len(internal)
    evaluations = sim.counters["force_evaluations"]
    f = np.random.default_rng(4).standard_normal((len(IDS), 3))
    sim.set_external_forces_of(IDS, f)
    whole = np.zeros((n, 3))
    whole[IDS] = f
    np.testing.assert_allclose(sim.forces, internal + whole, rtol=0, atol=1e-12)
    sim.external_forces = 2 * whole
    np.testing.assert_allclose(sim.forces, internal + 2 * whole, rtol=0, atol=1e-12)
    sim.external_forces = None
    np.testing.assert_allclose(sim.forces, internal, rtol=0, atol=1e-12)
    assert sim.counters["force_evaluations"] == evaluations
    sim.set_external_forces_of(IDS, f)
    sim.step(1)  # new positions: the next forces are evaluated afresh, field included
    fresh = handles(lattice())
    fresh.positions = sim.positions
    fresh.external_forces = whole
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=0, atol=1e-10)


def test_external_forces_of_a_subset_act_during_steps(handles):
    a, b = handles(lattice()), handles(lattice())
    n = a.num_particles
    f = np.random.default_rng(2).standard_normal((len(IDS), 3))
    a.set_external_forces_of(IDS, f)
    whole = np.zeros((n, 3))
    whole[IDS] = f
    b.external_forces = whole
    a.step(30)
    b.step(30)
    np.testing.assert_array_equal(a.positions, b.positions)


# ---- subsets: bytes moved ----------------------------------------------------------------------

def test_subset_transfers_are_proportional_to_m_not_n(handles):
    sim = handles(lattice())  # 1000 particles
    n, m = sim.num_particles, len(IDS)
    sim.compute()
    baseline = sim.counters
    overhead = moved(baseline, sim.counters)  # what a counters call itself moves
    slack = 64 + max(overhead)

    c0 = sim.counters
    sim.positions_of(IDS)
    c1 = sim.counters
    to_device, to_host = moved(c0, c1)
    assert to_device <= 8 * m + slack  # the ids
    assert 24 * m <= to_host <= 32 * m + slack  # m values (x, y, z in a 4-wide record)

    sim.forces_of(IDS)
    c2 = sim.counters
    to_device, to_host = moved(c1, c2)
    assert to_device <= 8 * m + slack and 24 * m <= to_host <= 32 * m + slack

    sim.set_external_forces_of(IDS, np.ones((m, 3)))
    c3 = sim.counters
    to_device, to_host = moved(c2, c3)
    assert 8 * m + 24 * m <= to_device <= (8 + 32) * m + slack and to_host <= slack

    sim.set_positions_of(IDS, sim.positions_of(IDS))
    c4 = sim.counters
    to_device, _ = moved(c3, c4)
    assert to_device <= (8 + 8 + 32 + 12) * m + slack  # ids twice (get and set), values, images

    # The whole-array getter, for scale: n values.
    sim.positions
    to_device, to_host = moved(c4, sim.counters)
    assert to_host >= 24 * n > 20 * (32 * m + slack)


def test_a_region_read_after_every_step_call_is_gathered_by_the_call_itself(handles):
    # The watched region: the step call gathers the positions a host read after the last call, so
    # the read costs nothing of its own; whatever moved the particles since, the values stay exact.
    sim = handles(lattice())
    m = len(IDS)
    overhead = moved(sim.counters, sim.counters)
    slack = 64 + max(overhead)
    np.testing.assert_array_equal(sim.positions_of(IDS), sim.positions[IDS])
    for _ in range(3):
        before = sim.counters
        sim.step(2)
        during = sim.counters
        read = sim.positions_of(IDS)
        after = sim.counters
        assert moved(before, during)[1] >= 24 * m  # the call gathered them
        assert max(moved(during, after)) <= slack  # the read moved nothing
        np.testing.assert_array_equal(read, sim.positions[IDS])

    # Positions changed by the host after the step: read from the engine again, not the gather.
    sim.step(1)
    sim.set_positions_of(IDS[:1], sim.positions[IDS[:1]] + 0.01)
    np.testing.assert_array_equal(sim.positions_of(IDS), sim.positions[IDS])
    # Another region read in between takes the watch over; the first is still exact.
    sim.step(1)
    others = [5, 6, 900]
    np.testing.assert_array_equal(sim.positions_of(others), sim.positions[others])
    sim.step(1)
    np.testing.assert_array_equal(sim.positions_of(IDS), sim.positions[IDS])
    np.testing.assert_array_equal(sim.positions_of(IDS), sim.positions[IDS])

    # A region no longer read stops being gathered after one call.
    sim.step(1)  # gathers: the region was read before it
    before = sim.counters
    sim.step(1)
    sim.step(1)
    assert moved(before, sim.counters)[1] < 24 * m


def test_a_blow_up_is_reported_while_a_region_is_watched(handles):
    # The watched gather brings the step call's fault flag back with it: a blow-up must still stop
    # the call and roll it back, and the region then reads the rolled-back positions.
    sim = handles(lattice())
    sim.positions_of(IDS)
    sim.step(1)
    sim.positions_of(IDS)  # read after the call: the next call gathers it
    neighbour = sim.positions[1]
    sim.set_positions_of([0], [neighbour + 0.01])  # almost on top of particle 1
    sim.positions_of(IDS)
    before = sim.positions
    with pytest.raises(structmd.NumericalError):
        sim.step(5)
    np.testing.assert_array_equal(sim.positions, before)
    np.testing.assert_array_equal(sim.positions_of(IDS), before[IDS])


# ---- subsets: bad arguments --------------------------------------------------------------------

@pytest.mark.parametrize("ids, culprit", [([3, 1000], "ids[1]: particle id 1000 does not exist"),
                                          ([-1], "ids[0]: particle id -1 does not exist"),
                                          ([4, 9, 4], "particle id 4 is given twice")])
def test_bad_ids_change_nothing(handles, ids, culprit):
    sim = handles(lattice())
    sim.step(3)
    positions, velocities, forces = sim.positions, sim.velocities, sim.forces
    values = np.ones((len(ids), 3))
    for call in (sim.set_positions_of, sim.set_velocities_of, sim.set_external_forces_of):
        with pytest.raises(structmd.ArgumentError, match=culprit.replace("[", r"\[").replace("]", r"\]")):
            call(ids, values)
    for call in (sim.positions_of, sim.velocities_of, sim.forces_of):
        with pytest.raises(structmd.ArgumentError):
            call(ids)
    np.testing.assert_array_equal(sim.positions, positions)
    np.testing.assert_array_equal(sim.velocities, velocities)
    np.testing.assert_array_equal(sim.forces, forces)
    assert sim.external_forces is None


def test_non_finite_values_change_nothing_and_name_the_particle(handles):
    sim = handles(lattice())
    positions, forces = sim.positions, sim.forces
    values = np.ones((3, 3))
    values[2, 1] = np.nan
    for call in (sim.set_positions_of, sim.set_velocities_of, sim.set_external_forces_of):
        with pytest.raises(structmd.ArgumentError, match=r"particle id 30\b"):
            call([10, 20, 30], values)
    np.testing.assert_array_equal(sim.positions, positions)
    np.testing.assert_array_equal(sim.forces, forces)


def test_wrong_value_shapes_are_refused_before_the_call(handles):
    sim = handles(lattice())
    with pytest.raises(structmd.ArgumentError, match="expected shape"):
        sim.set_positions_of([1, 2], np.zeros((3, 3)))


# ---- the host's external energy ----------------------------------------------------------------

def test_external_energy_is_its_own_term_and_part_of_total(handles):
    sim = handles(lattice())
    sim.step(5)
    potential, kinetic = sim.energy("potential"), sim.energy("kinetic")
    assert sim.energy("external") == 0.0
    assert sim.energy("total") == pytest.approx(potential + kinetic, rel=1e-14)
    sim.set_external_energy(-12.375)
    assert sim.energy("external") == -12.375
    assert sim.energy("potential") == potential  # the force field's alone
    assert sim.energy("total") == pytest.approx(potential + kinetic - 12.375, rel=1e-14)
    assert sim.particle_energies.sum() == pytest.approx(potential, rel=1e-12)
    # One batch: "@batch:0" is the whole system.
    assert sim.energy("total@batch:0") == sim.energy("total")
    assert sim.energy("external@batch:0") == -12.375
    with pytest.raises(structmd.ArgumentError, match="not a finite"):
        sim.set_external_energy(float("inf"))
    assert sim.energy("external") == -12.375
    sim.external_forces = None  # clearing the field clears its energy
    assert sim.energy("external") == 0.0
    sim.set_external_energy(4.0)
    sim.load(lattice())
    assert sim.energy("external") == 0.0


def test_thermodynamic_measure_writes_the_external_energy_and_adds_it_to_total(handles, tmp_path):
    path = tmp_path / "thermo.dat"
    sim = handles(lattice(side=6, thermo=(str(path), 10)))
    sim.set_external_energy(100.5)
    sim.step(11)  # fires at steps 0 and 10
    rows = path.read_text().splitlines()
    header = rows[0].split()
    assert header[-1] == "external"
    last = dict(zip(header, map(float, rows[-1].split())))
    assert last["external"] == 100.5
    assert last["total"] == pytest.approx(last["kinetic"] + last["potential"] + 100.5, rel=1e-9)


def test_external_energy_of_one_batch_of_several_is_refused(options):
    doc = systems.lj_bond_system()
    doc["topology"]["structure"]["labels"].append("batchId")
    for row, batch in zip(doc["topology"]["structure"]["data"], [0, 0, 1, 1]):
        row.append(batch)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.set_external_energy(2.0)
        with pytest.raises(structmd.ArgumentError, match="belongs to no batch"):
            sim.energy("external@batch:1")
        assert sim.energy("total@batch:0") + sim.energy("total@batch:1") + 2.0 == pytest.approx(sim.energy("total"))


# ---- run-time parameters -----------------------------------------------------------------------

def same_state(source, target):
    """Puts the positions and velocities of source into target (a freshly loaded handle)."""
    target.positions = source.positions
    target.velocities = source.velocities


def test_get_parameter_returns_what_the_input_gives(handles):
    sim = handles(lattice(bond_k=20.0))
    assert sim.get_parameter("topology.forceField.bonds.parameters.K") == 20.0
    assert sim.get_parameter("topology.forceField.bonds.parameters.r0") == SPACING
    assert sim.get_parameter("topology.forceField.lj.parameters.cutOffFactor") == 2.5
    assert sim.get_parameter("topology.forceField.nl.parameters.cutOffVerletFactor") == 1.2
    assert sim.get_parameter("integrator.vv.parameters.timeStep") == 0.002
    assert sim.get_parameter("global.ensemble.temperature") == 1.0
    with pytest.raises(structmd.ArgumentError, match="does not give it"):
        sim.get_parameter("integrator.vv.parameters.temperature")


def test_a_common_bond_constant_changes_force_and_energy_as_a_fresh_load_would(handles):
    sim = handles(lattice(bond_k=20.0))
    sim.step(20)
    bonds_before = sim.energy("bonds")
    sim.set_parameter("topology.forceField.bonds.parameters.K", 35.0)
    assert sim.get_parameter("topology.forceField.bonds.parameters.K") == 35.0
    assert sim.energy("bonds") == pytest.approx(bonds_before * 35.0 / 20.0, rel=1e-12)

    fresh = handles(lattice(bond_k=35.0))
    same_state(sim, fresh)
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=1e-12, atol=1e-12)
    assert sim.energy("bonds") == pytest.approx(fresh.energy("bonds"), rel=1e-12)
    assert sim.energy("potential") == pytest.approx(fresh.energy("potential"), rel=1e-12)
    np.testing.assert_allclose(sim.virial, fresh.virial, rtol=1e-12, atol=1e-12)
    sim.step(30)
    fresh.step(30)
    np.testing.assert_allclose(sim.positions, fresh.positions, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sim.velocities, fresh.velocities, rtol=1e-12, atol=1e-12)


def test_an_expression_constant_changes_as_a_fresh_load_would(handles):
    def with_expression(k):
        doc = lattice(side=6)
        doc["topology"]["forceField"]["spring"] = {
            "type": ["Bond2", "Expression"],
            "parameters": {"energy": "0.5 * k * (r - r0)^2", "k": k, "r0": 1.0},
            "labels": ["id_i", "id_j"], "data": [[i, i + 6] for i in range(0, 200, 7)]}
        return doc

    sim = handles(with_expression(4.0))
    sim.step(10)
    sim.set_parameter("topology.forceField.spring.parameters.k", 9.5)
    fresh = handles(with_expression(9.5))
    same_state(sim, fresh)
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=1e-12, atol=1e-12)
    assert sim.energy("spring") == pytest.approx(fresh.energy("spring"), rel=1e-12)


def test_a_term_in_units_of_kT_follows_the_ensemble_temperature(handles):
    """["Bond4","IDP_Fourier"] is k_B T times a fixed series: a new temperature rescales it, as a fresh
    load at that temperature would have it, and a temperature the reader refuses changes nothing."""
    def with_dihedrals(temperature):
        doc = lattice(side=5)
        doc["global"]["ensemble"]["data"][0][1] = temperature
        doc["topology"]["forceField"]["idp"] = {
            "type": ["Bond4", "IDP_Fourier"], "labels": ["id_i", "id_j", "id_k", "id_l"],
            "data": [[i, i + 1, i + 6, i + 31] for i in range(0, 90, 3)]}
        return doc

    sim = handles(with_dihedrals(1.0))
    sim.step(10)
    before = sim.energy("idp")
    assert before != 0.0
    sim.set_parameter("global.ensemble.temperature", 2.5)
    assert sim.energy("idp") == pytest.approx(2.5 * before, rel=1e-12)
    fresh = handles(with_dihedrals(2.5))
    same_state(sim, fresh)
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=1e-12, atol=1e-12)
    with pytest.raises(structmd.ArgumentError):
        sim.set_parameter("global.ensemble.temperature", -1.0)
    assert sim.energy("idp") == pytest.approx(2.5 * before, rel=1e-12)


def test_a_larger_cutoff_remakes_the_neighbour_list(handles):
    sim = handles(lattice())
    sim.step(10)
    builds = sim.counters["neighbour_list_builds"]
    sim.set_parameter("topology.forceField.lj.parameters.cutOffFactor", 3.5)
    fresh_doc = lattice()
    fresh_doc["topology"]["forceField"]["lj"]["parameters"]["cutOffFactor"] = 3.5
    fresh = handles(fresh_doc)
    same_state(sim, fresh)
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=1e-12, atol=1e-12)
    assert sim.energy("lj") == pytest.approx(fresh.energy("lj"), rel=1e-12)
    assert sim.counters["neighbour_list_builds"] > builds  # counted on, not reset
    sim.step(20)
    fresh.step(20)
    np.testing.assert_allclose(sim.positions, fresh.positions, rtol=1e-12, atol=1e-12)


def test_the_time_step_of_an_integrator_changes(handles):
    sim = handles(lattice(side=5))
    sim.step(5)
    sim.set_parameter("integrator.vv.parameters.timeStep", 0.004)
    t = sim.time
    sim.step(10)
    assert sim.time == pytest.approx(t + 10 * 0.004, rel=1e-12)


def test_the_thermostat_follows_the_ensemble_temperature(handles):
    langevin = {"type": ["Langevin", "GJF"], "parameters": {"timeStep": 0.005, "frictionConstant": 2.0}}
    sim = handles(lattice(side=6, integrator=langevin, steps=10000))
    n = sim.num_particles

    def mean_temperature(steps, every=10):
        samples = []
        for _ in range(steps // every):
            sim.step(every)
            samples.append(2.0 * sim.energy("kinetic") / (3.0 * n))
        return float(np.mean(samples))

    mean_temperature(300)
    assert mean_temperature(600) == pytest.approx(1.0, abs=0.08)
    sim.set_parameter("global.ensemble.temperature", 2.5)
    assert sim.get_parameter("global.ensemble.temperature") == 2.5
    mean_temperature(400)  # relaxation: 1 / friction = 100 steps
    assert mean_temperature(800) == pytest.approx(2.5, abs=0.2)


@pytest.mark.parametrize("path, value, why", [
    ("topology.forceField.nothing.parameters.K", 1.0, "no entry named 'nothing'"),
    ("topology.forceField.bonds.parameters.Kay", 1.0, "Kay"),
    ("topology.forceField.lj.parameters.condition", 1.0, "not a number"),
    ("topology.forceField.lj.parameters.cutOffFactor", 6.0, "half the box"),
    ("integrator.vv.parameters.timeStep", -0.1, "integrator.vv.parameters.timeStep"),
    ("integrator.schedule.parameters.steps", 5.0, "schedule cannot change"),
    ("global.ensemble.box", 20.0, "structmd_set_box"),
    ("global.units", 1.0, "not a run-time parameter"),
    ("topology.forceField.bonds.K", 1.0, "parameters"),
    ("topology.forceField.bonds.parameters.K", float("nan"), "not a finite number"),
])
def test_a_parameter_that_cannot_change_is_refused_and_changes_nothing(handles, path, value, why):
    sim = handles(lattice())
    sim.step(5)
    forces, energy = sim.forces, sim.energy("total")
    with pytest.raises(structmd.ArgumentError) as failure:
        sim.set_parameter(path, value)
    assert path in failure.value.message and why in failure.value.message
    np.testing.assert_array_equal(sim.forces, forces)
    assert sim.energy("total") == energy
    assert sim.get_parameter("topology.forceField.bonds.parameters.K") == 20.0
    assert sim.get_parameter("integrator.vv.parameters.timeStep") == 0.002
    t = sim.time
    sim.step(1)
    assert sim.time == pytest.approx(t + 0.002)


def test_a_refused_parameter_is_taken_back_so_later_changes_work(handles):
    # The kept document must not hold a refused value or key: the next change is read with it.
    sim = handles(lattice())
    with pytest.raises(structmd.ArgumentError, match="Kay"):
        sim.set_parameter("topology.forceField.bonds.parameters.Kay", 1.0)
    with pytest.raises(structmd.ArgumentError, match="does not give it"):
        sim.get_parameter("topology.forceField.bonds.parameters.Kay")
    with pytest.raises(structmd.ArgumentError):
        sim.set_parameter("global.ensemble.temperature", -1.0)
    assert sim.get_parameter("global.ensemble.temperature") == 1.0
    sim.set_parameter("topology.forceField.bonds.parameters.K", 30.0)
    sim.set_parameter("global.ensemble.temperature", 1.5)
    assert sim.get_parameter("topology.forceField.bonds.parameters.K") == 30.0
    assert sim.get_parameter("global.ensemble.temperature") == 1.5
    fresh = handles(lattice(bond_k=30.0))
    fresh.positions = sim.positions
    np.testing.assert_allclose(sim.forces, fresh.forces, rtol=1e-12, atol=1e-12)


def test_a_parameter_the_input_left_to_its_default_can_be_set(handles):
    langevin = {"type": ["Langevin", "GJF"], "parameters": {"timeStep": 0.002, "frictionConstant": 1.0}}
    sim = handles(lattice(side=5, integrator=langevin))
    sim.set_parameter("integrator.vv.parameters.temperature", 3.0)
    assert sim.get_parameter("integrator.vv.parameters.temperature") == 3.0
    sim.load(lattice(side=5, integrator=langevin))  # a new load forgets the change
    with pytest.raises(structmd.ArgumentError, match="does not give it"):
        sim.get_parameter("integrator.vv.parameters.temperature")
