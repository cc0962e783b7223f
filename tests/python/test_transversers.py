"""The expression transverser: ["TransverserMeasure","Expression"] writes each particle's sum of an
expression over its pairs every N steps. Coordination numbers ("r < 1.5"), a local density and a sum
of the pair's per-particle columns are computed here with numpy from the positions the API gives at
the same step, over a neighbour list (a cutoff), over all pairs (none) and over a group."""

import numpy as np
import pytest

import structmd
from conftest import BACKEND
from measure_files import read_step_blocks
from test_measures import BOX, document, measure, minimum_image


@pytest.fixture
def sim(options):
    with structmd.Simulation(options) as s:
        yield s


def read_blocks(path):
    """{step: array of rows `id value`} of a transverser measure's file."""
    header, blocks = read_step_blocks(path)
    assert header == "# id value"
    return blocks


def separations(positions):
    p = np.asarray(positions)
    d = minimum_image(p[None, :, :] - p[:, None, :])  # d[i, j] = r_j - r_i
    r = np.linalg.norm(d, axis=2)
    np.fill_diagonal(r, np.inf)
    return d, r


def liquid(n=300, seed=3):
    rng = np.random.default_rng(seed)
    positions = rng.uniform(-BOX / 2, BOX / 2, size=(n, 3))
    velocities = rng.normal(0.0, 1.0, size=(n, 3))
    return positions, velocities


def lattice(edge=7, seed=3):
    """edge^3 particles on a cubic lattice filling the box, each moved by up to 0.1: no pair closer
    than 1.2, so a Lennard-Jones liquid of them steps calmly."""
    rng = np.random.default_rng(seed)
    sites = (np.arange(edge) + 0.5) * BOX / edge - BOX / 2
    grid = np.stack(np.meshgrid(sites, sites, sites, indexing="ij"), axis=-1).reshape(-1, 3)
    return grid + rng.uniform(-0.1, 0.1, grid.shape), rng.normal(0.0, 1.0, grid.shape)


def test_coordination_numbers_every_n_steps_against_numpy(sim, tmp_path):
    positions, velocities = liquid()
    output = tmp_path / "coordination.dat"
    sim.load(document(positions, velocities, steps=20, time_step=0.002, simulation_steps={
        "coordination": measure("TransverserMeasure", "Expression", interval=10, outputFilePath=str(output),
                                compute="r < 1.5", cutOff=1.5)}))
    expected = {}
    for step in (0, 10, 20):
        if step:
            sim.step(10)
        _, r = separations(sim.positions)
        expected[step] = np.sum(r < 1.5, axis=1)
    blocks = read_blocks(output)
    assert sorted(blocks) == [0, 10, 20]
    for step, rows in blocks.items():
        np.testing.assert_array_equal(rows[:, 0], np.arange(len(positions)))
        np.testing.assert_array_equal(rows[:, 1], expected[step])
    assert expected[0].sum() > 2 * len(positions)  # dense enough to mean something


def test_local_density_over_a_list_and_over_all_pairs_agree_with_numpy(sim, tmp_path):
    positions, _ = liquid(200, seed=5)
    h = 2.0
    weight = f"(r < {h}) * (1 - r / {h})^2"
    listed, everything = tmp_path / "listed.dat", tmp_path / "all.dat"
    sim.load(document(positions, steps=1, simulation_steps={
        "listed": measure("TransverserMeasure", "Expression", outputFilePath=str(listed), compute=weight, cutOff=h),
        "all": measure("TransverserMeasure", "Expression", outputFilePath=str(everything), compute=weight)}))
    sim.step(1)
    _, r = separations(sim.positions)
    w = np.where(r < h, (1 - r / h) ** 2, 0.0)
    expected = w.sum(axis=1)
    for path in (listed, everything):
        rows = read_blocks(path)[1]
        np.testing.assert_allclose(rows[:, 1], expected, rtol=1e-12, atol=1e-12)


def test_all_pairs_read_types_masses_and_separations(sim, tmp_path):
    """No cutoff: every other particle by minimum image; type_j and mass_j are the partner's
    (document(): type B has mass 2), dx its separation along x."""
    positions, _ = liquid(60, seed=7)
    types = ["A" if i % 3 else "B" for i in range(len(positions))]
    output = tmp_path / "sum.dat"
    sim.load(document(positions, types=types, steps=1, simulation_steps={
        "sum": measure("TransverserMeasure", "Expression", outputFilePath=str(output),
                       compute="mass_j * exp(-r) + dx * type_j - type_i / 100")}))
    sim.step(1)
    d, r = separations(sim.positions)
    type_index = np.array([0.0 if t == "A" else 1.0 for t in types])
    mass = np.array([1.0 if t == "A" else 2.0 for t in types])
    terms = mass[None, :] * np.exp(-r) + d[:, :, 0] * type_index[None, :] - type_index[:, None] / 100
    np.fill_diagonal(terms, 0.0)
    rows = read_blocks(output)[1]
    np.testing.assert_allclose(rows[:, 1], terms.sum(axis=1), rtol=1e-12, atol=1e-12)


def test_a_group_takes_part_alone(sim, tmp_path):
    positions, _ = liquid(150, seed=9)
    members = [i for i in range(len(positions)) if i % 4 != 1]
    output = tmp_path / "group.dat"
    doc = document(positions, steps=1, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["some", "Ids", members]]}}, simulation_steps={
        "count": measure("TransverserMeasure", "Expression", outputFilePath=str(output), compute="r < 2",
                         cutOff=2.0, group="some")})
    sim.load(doc)
    sim.step(1)
    _, r = separations(sim.positions)
    inside = r[np.ix_(members, members)] < 2.0
    rows = read_blocks(output)[1]
    np.testing.assert_array_equal(rows[:, 0], members)
    np.testing.assert_array_equal(rows[:, 1], inside.sum(axis=1))


@pytest.mark.parametrize("compute, cut_off, message", [
    ("r < ", 1.0, "parameters.compute"),
    ("r < sigma", 1.0, "unknown variable"),
    ("r < 1", -1.0, "parameters.cutOff"),
])
def test_bad_entries_name_their_path(sim, tmp_path, compute, cut_off, message):
    doc = document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], steps=1, simulation_steps={
        "bad": measure("TransverserMeasure", "Expression", outputFilePath=str(tmp_path / "x.dat"),
                       compute=compute, cutOff=cut_off)})
    with pytest.raises(structmd.InputError, match=message):
        sim.load(doc)


def test_traverse_expression_from_the_api_follows_the_state(sim):
    """structmd_traverse_expression through Simulation.traverse_expression: the same sums as numpy,
    over a list and over all pairs, again after the particles moved (the prepared list follows)."""
    positions, velocities = liquid(250, seed=13)
    sim.load(document(positions, velocities, steps=50, time_step=0.005))
    for _ in range(2):
        d, r = separations(sim.positions)
        np.testing.assert_array_equal(sim.traverse_expression("r < 1.5", 1.5), np.sum(r < 1.5, axis=1))
        np.testing.assert_array_equal(sim.traverse_expression("r <= 1.2", 0.0), np.sum(r <= 1.2, axis=1))
        dens = sim.traverse_expression("mass_j * (r < 2) * (1 - r / 2)^2", 2.0)
        np.testing.assert_allclose(dens, np.where(r < 2, (1 - r / 2) ** 2, 0).sum(axis=1), rtol=1e-12, atol=1e-12)
        sim.step(50)
    assert not np.allclose(sim.positions, positions)


@pytest.mark.parametrize("compute, cutoff, error, message", [
    ("r <", 1.0, structmd.InputError, "compute: at column 4"),
    ("r < rc", 1.0, structmd.InputError, "unknown variable 'rc'"),
    ("r < 1", -2.0, structmd.InputError, "cutoff"),
    ("r < 1", float("nan"), structmd.InputError, "cutoff"),
])
def test_traverse_expression_refuses_bad_arguments(sim, compute, cutoff, error, message):
    positions, _ = liquid(20)
    sim.load(document(positions, steps=1))
    with pytest.raises(error, match=message):
        sim.traverse_expression(compute, cutoff)


def test_traverse_expression_needs_a_load(sim):
    with pytest.raises(structmd.StateError):
        sim.traverse_expression("r < 1", 1.0)


def test_batches_stay_apart_over_a_list_and_over_all_pairs(sim):
    """Two batches overlaid in one box (batchId 0 and 1) are independent systems: a particle's pairs
    are those of its own batch, with a neighbour list and without."""
    positions, _ = liquid(300, seed=17)  # more than one tile of 128 on the GPU
    doc = document(positions, steps=1)
    batch = [i % 2 for i in range(len(positions))]
    doc["topology"]["structure"] = {"labels": ["id", "type", "batchId"],
                                    "data": [[i, "A", b] for i, b in enumerate(batch)]}
    sim.load(doc)
    _, r = separations(sim.positions)
    same = np.equal.outer(batch, batch)
    np.testing.assert_array_equal(sim.traverse_expression("r < 2", 2.0), np.sum((r < 2) & same, axis=1))
    np.testing.assert_array_equal(sim.traverse_expression("1"), np.sum(same, axis=1) - 1)


def stepped_lattice_under_lj(sim, seed):
    """Loads the lattice under the LJ term over its list of every pair and takes 5 steps; returns the
    starting positions."""
    from test_measures import NEIGHBOUR_LIST, lj_entry
    positions, velocities = lattice(seed=seed)
    sim.load(document(positions, velocities, steps=100, time_step=0.002,
                      force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()}))
    sim.step(5)
    return positions


def check_a_pair_terms_list_is_shared(sim, counts, within, beyond, seed):
    """counts(cutoff): a transverser's neighbour counts. Within the cutoff of the LJ term's list (of
    every pair) it goes over that list, which the steps keep up to date: its calls add only their
    output to the engine's memory, where one with a cutoff beyond makes a list of its own (at least
    20 bytes a particle); both count as numpy does, as the particles move."""
    positions = stepped_lattice_under_lj(sim, seed)
    held = sim.counters["device_memory_bytes"]
    for _ in range(2):
        _, r = separations(sim.positions)
        np.testing.assert_array_equal(counts(within), np.sum(r < within, axis=1))
        sim.step(20)
    shared = sim.counters["device_memory_bytes"] - held
    assert 0 < shared <= 8 * len(positions) + 4096, shared
    _, r = separations(sim.positions)
    np.testing.assert_array_equal(counts(beyond), np.sum(r < beyond, axis=1))
    assert sim.counters["device_memory_bytes"] - held - shared > 20 * len(positions)


def test_a_pair_terms_list_is_used_where_it_offers_every_pair(sim):
    check_a_pair_terms_list_is_shared(sim, lambda cutoff: sim.traverse_expression(f"r < {cutoff}", cutoff), 2.0, 3.0, 5)


def test_an_expression_transverser_goes_over_the_list_of_a_force_field_made_again(sim):
    """structmd_set_parameter makes the force field and its lists again. A prepared expression
    transverser then goes over the new LJ list, and the list it went over before is freed: the
    engine's memory is back to what it held before the first call, plus that call's output."""
    positions = stepped_lattice_under_lj(sim, 11)
    held = sim.counters["device_memory_bytes"]
    sim.traverse_expression("r < 2", 2.0)
    sim.set_parameter("topology.forceField.lj.parameters.cutOffFactor", 2.5)
    sim.step(20)
    _, r = separations(sim.positions)
    np.testing.assert_array_equal(sim.traverse_expression("r < 2", 2.0), np.sum(r < 2, axis=1))
    assert sim.counters["device_memory_bytes"] - held <= 8 * len(positions) + 4096


def test_a_list_that_leaves_pairs_out_is_not_used(sim):
    """A pair term over the pairs that are not excluded (a bond excludes 0-1, lattice neighbours): a
    transverser still counts every pair, the bonded one too."""
    positions, _ = lattice(seed=7)
    bonds = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 20.0, "r0": BOX / 7},
             "labels": ["id_i", "id_j"], "data": [[0, 1]]}
    from test_measures import lj_entry
    excluding = {"type": ["VerletConditionalListSet", "nonExcluded"], "parameters": {"cutOffVerletFactor": 1.2}}
    sim.load(document(positions, steps=10, force_field={"nl": excluding, "lj": lj_entry(condition="nonExcluded"),
                                                         "bonds": bonds}))
    sim.step(1)
    _, r = separations(sim.positions)
    assert r[0, 1] < 2
    np.testing.assert_array_equal(sim.traverse_expression("r < 2", 2.0), np.sum(r < 2, axis=1))


@pytest.mark.skipif(BACKEND != "cuda", reason="1.6e9 pairs: a test of the GPU's all-pairs tiles")
def test_all_pairs_of_a_large_system_in_an_open_box(sim):
    """40,000 particles: on the GPU each has a lane of its own, so all pairs run in shared-memory tiles
    (all_pairs_traversal.hpp). In an open box the sum over partners of dx is X - n x_i (X the sum of
    the x's), and "1" counts the rest of a particle's batch."""
    n = 40000
    rng = np.random.default_rng(29)
    positions = rng.uniform(-50.0, 50.0, size=(n, 3))
    doc = document(positions, steps=1)
    doc["global"]["ensemble"]["data"][0][0] = ["inf", "inf", "inf"]
    batch = [i % 3 for i in range(n)]
    doc["topology"]["structure"] = {"labels": ["id", "type", "batchId"],
                                    "data": [[i, "A", b] for i, b in enumerate(batch)]}
    sim.load(doc)
    x = np.asarray(sim.positions)[:, 0]
    batch = np.asarray(batch)
    expected = np.zeros(n)
    for b in range(3):
        mine = batch == b
        expected[mine] = x[mine].sum() - mine.sum() * x[mine]
    np.testing.assert_allclose(sim.traverse_expression("dx", 0.0), expected, rtol=1e-9, atol=1e-7)
    np.testing.assert_array_equal(sim.traverse_expression("1", 0.0), np.bincount(batch)[batch] - 1)
