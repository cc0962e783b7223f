"""structmd.Input, the input builder: the document it makes has the format's sections and tables,
the engine's reader judges it through check() (a bad parameter is named by its JSON path), wrong
shapes are refused before that, an input made from ASE atoms gives ASE's Lennard-Jones energies, and
the examples of docs/python.md that use it run as written. (That it writes the bundled examples
byte for byte is host_bundled_inputs_regenerate.)"""

import re
from pathlib import Path

import numpy as np
import pytest

import structmd
from structmd import Input
from systems import CUTOFF_FACTOR, EPSILON, SIGMA, rattled_argon

PYTHON_DOC = Path(__file__).resolve().parents[2] / "docs" / "python.md"
LJ_LABELS = ["name_i", "name_j", "epsilon", "sigma"]


def small_liquid(cut_off_key="cutOffFactor"):
    system = Input("small", seed=3)
    system.add_type("A", mass=2.0)
    system.add_type("B", mass=1.0, charge=-1.0)
    system.set_ensemble(6.0, 1.5)
    grid = np.array([[x, y, z] for x in (-2.0, 0.0, 2.0) for y in (-2.0, 0.0, 2.0) for z in (-2.0, 0.0)])
    ids_a = system.add_particles(grid[:9], "A", structure_columns={"chainId": np.zeros(9, dtype=int)})
    ids_b = system.add_particles(grid[9:], ["B"] * 9, structure_columns={"chainId": np.ones(9, dtype=int)})
    system.add_interaction("nl", ["VerletConditionalListSet", "all"], {"cutOffVerletFactor": 1.1})
    system.add_interaction("lj", ["NonBonded", "LennardJonesType1"], {cut_off_key: 1.2, "condition": "all"},
                           labels=LJ_LABELS, data=[["A", "A", 1.0, 1.0], ["A", "B", 1.0, 1.0], ["B", "B", 1.0, 1.0]])
    system.add_integrator("vv", ["Verlet", "VelocityVerlet"], {"timeStep": 0.001}, steps=5)
    system.add_integrator("bbk", ["Langevin", "BBK"], {"timeStep": 0.001, "frictionConstant": 1.0}, steps=7)
    return system, ids_a, ids_b, grid


def test_the_document_has_the_formats_sections_and_tables():
    system, ids_a, ids_b, grid = small_liquid()
    document = system.document()
    assert list(document) == ["system", "global", "integrator", "state", "topology"]
    assert document["system"]["info"]["parameters"] == {"name": "small", "seed": 3}
    assert document["global"]["types"]["data"] == [["A", 2.0, 0.5, 0.0], ["B", 1.0, 0.5, -1.0]]
    assert document["global"]["ensemble"]["data"] == [[[6.0, 6.0, 6.0], 1.5]]
    assert ids_a == list(range(9)) and ids_b == list(range(9, 18))
    assert document["state"]["labels"] == ["id", "position"]
    assert [row[1] for row in document["state"]["data"]] == grid.tolist()
    assert document["topology"]["structure"]["labels"] == ["id", "type", "chainId"]
    assert document["topology"]["structure"]["data"][10] == [10, "B", 1]
    assert list(document["integrator"]) == ["vv", "bbk", "schedule"]
    assert document["integrator"]["schedule"]["data"] == [[1, "vv", 5], [2, "bbk", 7]]


def test_a_built_input_loads_and_runs_its_schedule(options):
    system, _, _, grid = small_liquid()
    system.check()
    with structmd.Simulation(options) as sim:
        sim.load(system.document())
        np.testing.assert_allclose(sim.positions, grid, rtol=0, atol=1e-12)
        sim.run()
        assert sim.step_number == 12


def test_check_names_a_wrong_parameter_by_its_path():
    system, _, _, _ = small_liquid(cut_off_key="cutoffFactor")
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.lj\.parameters"):
        system.check()


@pytest.mark.parametrize("call, message", [
    (lambda s: s.add_particles(np.zeros((4, 2)), "A"), r"shape \(n, 3\)"),
    (lambda s: s.add_particles(np.zeros((4, 3)), ["A", "A"]), "2 types for 4 particles"),
    (lambda s: s.add_particles(np.zeros((4, 3)), "A", velocities=np.zeros((3, 3))), "'velocity' has 3 values"),
    (lambda s: s.add_particles(np.zeros((4, 3)), "A", velocities=np.zeros((4, 3))), "the earlier ones"),
    (lambda s: s.add_type("A"), "added twice"),
    (lambda s: s.add_interaction("lj", ["NonBonded", "WCAType1"]), r"topology\.forceField\.lj is added twice"),
    (lambda s: s.add_integrator("schedule", ["Verlet", "VelocityVerlet"]), "steps="),
    (lambda s: s.add_step("x", ["WriteStep"]), r"\[Class, SubClass\]"),
    (lambda s: s.add_step("x", ["WriteStep", "WriteStep"], labels=["a"]), "both labels and data"),
    (lambda s: s.set_ensemble([1.0, 2.0], 1.0), "one edge or three"),
])
def test_what_python_can_see_is_refused_at_once(call, message):
    system, _, _, _ = small_liquid()
    before = system.document()
    with pytest.raises(ValueError, match=message):
        call(system)
    assert system.document() == before


def test_open_axes_are_written_as_inf_and_run_over_all_pairs(options):
    """An edge of math.inf or 0 is an open axis: JSON has no infinity, so the builder writes "inf",
    which the engine reads back as infinity; gravity over an NBody entry then runs in that box."""
    system = Input("open", seed=1)
    system.add_type("A", mass=1.0)
    system.set_ensemble([np.inf, 0.0, float("inf")], 1.0)
    system.add_particles(np.array([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, 2.0, 0.0]]), "A",
                         velocities=np.zeros((3, 3)))
    system.add_interaction("all", ["NBody", "all"])
    system.add_interaction("gravity", ["NonBonded", "Gravity"], {"G": 1.0, "condition": "all"})
    system.add_integrator("vv", ["Verlet", "VelocityVerlet"], {"timeStep": 0.001}, steps=5)
    assert system.document()["global"]["ensemble"]["data"][0][0] == ["inf", 0.0, "inf"]
    with structmd.Simulation(options) as sim:
        sim.load(system.document())
        assert all(np.isinf(edge) for edge in sim.box)
        expected = -1.0 / 1.5 - 1.0 / 2.0 - 1.0 / 2.5
        assert sim.energy("potential") == pytest.approx(expected, rel=1e-12)


def test_an_input_from_ase_atoms_gives_ases_lennard_jones(options):
    from ase.calculators.lj import LennardJones
    from structmd.ase import Calculator

    atoms = rattled_argon(seed=4)
    system = Input.from_atoms(atoms, name="argon")
    document = system.document()
    assert document["global"]["types"]["data"] == [["Ar", pytest.approx(39.948), 0.5, 0.0]]
    assert "units" not in document["global"]
    system.add_interaction("nl", ["VerletConditionalListSet", "all"], {"cutOffVerletFactor": 1.02})
    system.add_interaction("lj", ["NonBonded", "LennardJonesType1"],
                           {"cutOffFactor": CUTOFF_FACTOR, "condition": "all", "shift": True},
                           labels=LJ_LABELS, data=[["Ar", "Ar", EPSILON, SIGMA]])
    reference = atoms.copy()
    reference.calc = LennardJones(sigma=SIGMA, epsilon=EPSILON, rc=CUTOFF_FACTOR * SIGMA)
    with Calculator(system.document(), options=options) as calc:
        atoms.calc = calc
        assert atoms.get_potential_energy() == pytest.approx(reference.get_potential_energy(), rel=1e-11)


def test_atoms_a_box_cannot_hold_are_refused():
    atoms = rattled_argon(seed=5)
    atoms.set_cell(atoms.cell + np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]))
    with pytest.raises(ValueError, match="orthorhombic"):
        Input.from_atoms(atoms)
    atoms = rattled_argon(seed=5)
    charges = np.zeros(len(atoms))
    charges[0] = 1.0
    atoms.set_initial_charges(charges)
    with pytest.raises(ValueError, match="different charges"):
        Input.from_atoms(atoms)


def test_the_examples_of_docs_python_md_that_build_inputs_run_as_written(tmp_path, monkeypatch):
    from ase.io import write
    blocks = re.findall(r"```python\n(.*?)```", PYTHON_DOC.read_text(encoding="utf-8"), re.S)
    building = [block for block in blocks if "Input" in block]
    assert len(building) >= 2, "docs/python.md no longer shows the input builder"
    monkeypatch.chdir(tmp_path)
    write("argon.xyz", rattled_argon(seed=6))
    for block in building:
        exec(compile(block, str(PYTHON_DOC), "exec"), {})
    assert Path("argon.json").is_file() and Path("lj.json").is_file()
