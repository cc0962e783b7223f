"""Transversers that a plugin registered, beyond the host's one-off structmd_traverse: the simulation
step ["TransverserMeasure","Plugin"] writes each particle's values every N steps, and
Simulation.traverse_view (structmd_traverse_view) lends them as a DLPack tensor where the engine
computed them. The in-tree NeighbourCount plugin (tests/plugins, examples/plugins/neighbour_count.cu)
is checked against numpy neighbour counts by minimum image, over a neighbour list, over all pairs and
over a group; then the refusals at load (an unknown name, a parameter it does not take), after which
the handle still loads and runs."""

import os

import numpy as np
import pytest

import structmd
from conftest import BACKEND
from structmd.dlpack import K_DL_CPU, K_DL_CUDA
from test_measures import document, measure
from test_transversers import check_a_pair_terms_list_is_shared, liquid, read_blocks, separations

PLUGIN = os.environ.get("STRUCTMD_TEST_TRANSVERSER_PLUGIN")
pytestmark = pytest.mark.skipif(not PLUGIN, reason="STRUCTMD_TEST_TRANSVERSER_PLUGIN not set (ctest sets it)")


@pytest.fixture
def sim(options):
    with structmd.Simulation({**options, "plugins": [PLUGIN]}) as s:
        yield s


def with_group(doc, name, members):
    doc["topology"]["forceField"]["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                              "data": [[name, "Ids", members]]}
    return doc


def test_the_step_writes_neighbour_counts_every_n_steps_against_numpy(sim, tmp_path):
    positions, velocities = liquid(300, seed=21)
    members = [i for i in range(len(positions)) if i % 3 != 2]
    listed, everything, grouped = tmp_path / "listed.dat", tmp_path / "all.dat", tmp_path / "group.dat"
    sim.load(with_group(document(positions, velocities, steps=20, time_step=0.002, simulation_steps={
        "listed": measure("TransverserMeasure", "Plugin", interval=10, outputFilePath=str(listed),
                          transverser="NeighbourCount", cutOff=1.5),
        "all": measure("TransverserMeasure", "Plugin", interval=20, outputFilePath=str(everything),
                       transverser="NeighbourCount", transverserParameters={}),
        "grouped": measure("TransverserMeasure", "Plugin", interval=10, outputFilePath=str(grouped),
                           transverser="NeighbourCount", cutOff=2.0, group="some")}), "some", members))
    expected, expected_group = {}, {}
    for step in (0, 10, 20):
        if step:
            sim.step(10)
        _, r = separations(sim.positions)
        expected[step] = np.sum(r < 1.5, axis=1)
        expected_group[step] = np.sum(r[np.ix_(members, members)] < 2.0, axis=1)
    assert expected[0].sum() > 2 * len(positions)  # dense enough to mean something
    assert not np.array_equal(expected[0], expected[20])  # the particles moved: each firing is its own

    blocks = read_blocks(listed)
    assert sorted(blocks) == [0, 10, 20]
    for step, rows in blocks.items():
        np.testing.assert_array_equal(rows[:, 0], np.arange(len(positions)))
        np.testing.assert_array_equal(rows[:, 1], expected[step])
    blocks = read_blocks(everything)
    assert sorted(blocks) == [0, 20]
    for rows in blocks.values():
        np.testing.assert_array_equal(rows[:, 1], np.full(len(positions), len(positions) - 1))
    blocks = read_blocks(grouped)
    for step, rows in blocks.items():
        np.testing.assert_array_equal(rows[:, 0], members)
        np.testing.assert_array_equal(rows[:, 1], expected_group[step])


def plugin_step_document(tmp_path, **parameters):
    positions, _ = liquid(40, seed=23)
    return document(positions, steps=2, simulation_steps={
        "counts": measure("TransverserMeasure", "Plugin", outputFilePath=str(tmp_path / "counts.dat"), **parameters)})


@pytest.mark.parametrize("parameters, message", [
    ({"transverser": "NeighbourCont"},
     r"simulationStep\.counts\.parameters\.transverser: no transverser named 'NeighbourCont' "
     r"\(the loaded plugins register 'NeighbourCount'"),
    ({"transverser": "NeighbourCount", "transverserParameters": {"radius": 1.0}},
     r"simulationStep\.counts\.parameters\.transverserParameters\.radius: unknown parameter"),
    ({"transverser": "NeighbourCount", "transverserParameters": [1.0]},
     r"simulationStep\.counts\.parameters\.transverserParameters: expected an object"),
    ({"transverser": "NeighbourCount", "cutOff": -1.0}, r"simulationStep\.counts\.parameters\.cutOff"),
])
def test_a_bad_entry_is_refused_at_load_by_its_path_and_the_handle_stays_usable(sim, tmp_path, parameters, message):
    with pytest.raises(structmd.InputError, match=message):
        sim.load(plugin_step_document(tmp_path, **parameters))
    assert not (tmp_path / "counts.dat").exists()
    sim.load(plugin_step_document(tmp_path, transverser="NeighbourCount", cutOff=1.5))
    sim.run()
    assert sorted(read_blocks(tmp_path / "counts.dat")) == [0, 1, 2]


def test_a_handle_without_the_plugin_says_that_none_registers_one(options, tmp_path):
    with structmd.Simulation(options) as bare:
        with pytest.raises(structmd.InputError, match="no loaded plugin registers one"):
            bare.load(plugin_step_document(tmp_path, transverser="NeighbourCount"))


def test_traverse_view_lends_the_counts_without_a_copy(sim):
    positions, velocities = liquid(200, seed=25)
    sim.load(document(positions, velocities, steps=30, time_step=0.002))
    for _ in range(2):
        _, r = separations(sim.positions)
        view = sim.traverse_view("NeighbourCount", 1.5)
        assert view.shape == (len(positions),)
        assert view.bits == 64
        if BACKEND == "cuda":
            assert view.device[0] == K_DL_CUDA
        else:
            assert view.device == (K_DL_CPU, 0)
            np.testing.assert_array_equal(view.numpy(), np.sum(r < 1.5, axis=1))
            np.testing.assert_array_equal(np.from_dlpack(sim.traverse_view("NeighbourCount", 0.0)),
                                          np.full(len(positions), len(positions) - 1))
            np.testing.assert_array_equal(np.from_dlpack(sim.traverse_view("NeighbourCount", 1.5)),
                                          sim.traverse("NeighbourCount", 1.5))
        sim.step(30)


def test_a_registered_transverser_goes_over_a_pair_terms_list_of_every_pair(sim):
    check_a_pair_terms_list_is_shared(sim, lambda cutoff: sim.traverse("NeighbourCount", cutoff), 2.5, 3.0, 27)


def test_traverse_view_refuses_as_traverse_does(sim, options):
    positions, _ = liquid(20)
    with pytest.raises(structmd.StateError):
        sim.traverse_view("NeighbourCount", 1.0)
    sim.load(document(positions, steps=1))
    with pytest.raises(structmd.ArgumentError, match="no transverser named 'Nope'"):
        sim.traverse_view("Nope")
    with pytest.raises(structmd.InputError, match="NeighbourCount.parameters.radius"):
        sim.traverse_view("NeighbourCount", 1.0, {"radius": 2.0})
    with pytest.raises(structmd.InputError, match="cutoff"):
        sim.traverse_view("NeighbourCount", -1.0)
