"""docs/input-format.md is the user's reference for every component: each `### ["Class","SubClass"]`
heading there opens with a JSON example. These tests load every example into a small system, so the
page cannot promise a component the engine rejects; that every component the engine knows has its
section is tests/registry/test_docs.cpp's part, which walks the registries themselves."""

import copy
import json
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

import structmd

DOC = Path(__file__).resolve().parents[2] / "docs" / "input-format.md"
HEADING = re.compile(r'^### \["([^"]+)","([^"]+)"\]\s*$')
SECTION = re.compile(r"^Section: `([A-Za-z.]+)`")
FORCE_FIELD = "topology.forceField"


def documented_components():
    """{(class, subclass): (example entry name, entry, section)} for every component heading."""
    lines = DOC.read_text(encoding="utf-8").splitlines()
    components = {}
    for number, line in enumerate(lines):
        match = HEADING.match(line)
        if not match:
            continue
        key = (match.group(1), match.group(2))
        where = f"{DOC.name}:{number + 1} {line}"
        assert key not in components, f"{where}: documented twice"
        k = number + 1
        while k < len(lines) and not lines[k].strip():
            k += 1
        assert k < len(lines) and lines[k].strip() == "```json", f"{where}: no ```json example right below"
        end = lines.index("```", k + 1)
        example = json.loads("\n".join(lines[k + 1:end]))
        assert len(example) == 1, f"{where}: the example must hold one named entry"
        (name, entry), = example.items()
        assert entry.get("type") == list(key), f"{where}: the example's type is {entry.get('type')}"
        k = end + 1
        while k < len(lines) and not lines[k].strip():
            k += 1
        section = SECTION.match(lines[k]) if k < len(lines) else None
        assert section, f"{where}: the example must be followed by a 'Section: `...`' line"
        components[key] = (name, entry, section.group(1))
    return components


COMPONENTS = documented_components()
FORCE_FIELD_COMPONENTS = sorted(k for k, v in COMPONENTS.items() if v[2] == FORCE_FIELD)
DOCUMENT_COMPONENTS = sorted(k for k, v in COMPONENTS.items() if v[2] != FORCE_FIELD)

# The system every example is written for (docs/input-format.md, "Examples on this page"): ids 0..3
# in a bent, non-planar chain (every angle and dihedral is defined), types A and B with charges,
# models 0 and 1, magnetic moments, all well inside a 10-wide box and within 2 of the origin.
POSITIONS = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [1.5, 1.0, 0.0], [2.6, 1.1, 0.5]]
TYPES = ["A", "B", "A", "B"]
MODELS = [0, 0, 1, 1]
MAGNETIZATIONS = [[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.2], [0.0, 0.0, 1.0, 0.8], [0.6, 0.0, 0.8, 1.1]]
BOX = 10.0
# The conditions each neighbour list subclass offers (docs: "Neighbour lists").
LIST_CONDITIONS = {"all": ["all"], "nonExcluded": ["nonExcluded"], "intra_inter": ["intra", "inter"],
                   "nonExclIntra_nonExclInter": ["intra", "inter"],
                   "nonExclIntra_nonExclInter_nonExclCharged": ["intra", "inter", "charged"],
                   "nonExclIntra_nonExclInter_nonExclInterCharged": ["intra", "inter", "charged"],
                   "nonExcIntra_nonExcInter_nonExcInterCharged": ["intra", "inter", "charged"],
                   "interDifferentType": ["inter"],
                   "nonExclTypeGroup1Intra_nonExclTypeGroup2Intra_nonExclInter_nonExclNoGroup":
                       ["typeGroup1Intra", "typeGroup2Intra", "inter", "noGroup"]}


def base_document():
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "docs"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.5], ["B", 1.0, 0.5, -0.5]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 10]]},
        },
        "state": {"labels": ["id", "position", "velocity", "magnetization"],
                  "data": [[i, p, [0.0, 0.0, 0.0], MAGNETIZATIONS[i]] for i, p in enumerate(POSITIONS)]},
        "topology": {
            "structure": {"labels": ["id", "type", "modelId"],
                          "data": [[i, TYPES[i], MODELS[i]] for i in range(len(POSITIONS))]},
            "forceField": {"nl": {"type": ["VerletConditionalListSet", "all"]}},
        },
    }


def lennard_jones(condition, neighbour_list):
    return {"type": ["NonBonded", "LennardJonesType1"],
            "parameters": {"cutOffFactor": 2.5, "condition": condition, "neighbourList": neighbour_list},
            "labels": ["name_i", "name_j", "epsilon", "sigma"],
            "data": [["A", "A", 1.0, 1.0], ["A", "B", 1.0, 1.0], ["B", "B", 1.0, 1.0]]}


# Components defined in one unit system only (their docs say so), and that system.
UNITS_OF = {("Bond3", "BestChenHummerAngular"): "KcalMol_A"}

# Terms of no cutoff (their docs say so): over an ["NBody","all"] list, in a box open along every axis.
OPEN_BOX = {("NonBonded", "Coulomb"), ("NonBonded", "Gravity")}

# Components that read a state column the base document lacks (their docs say so), and its values.
DIRECTIONS = [[1.0, 0.0, 0.0, 0.0], [0.8, 0.6, 0.0, 0.0], [0.6, 0.0, 0.8, 0.0], [0.0, 0.0, 0.6, 0.8]]
STATE_COLUMN_OF = {("Bond2", "RAP"): ("direction", DIRECTIONS), ("Bond2", "HarmonicRAP"): ("direction", DIRECTIONS),
                   ("External", "PolarizationTabulated"): ("polarizability", [1.0, 0.5, 2.0, 1.5]),
                   ("NonBonded", "StericInner6"): ("innerRadius", [0.4, 0.3, 0.5, 0.35]),
                   ("NonBonded", "StericInner12"): ("innerRadius", [0.4, 0.3, 0.5, 0.35]),
                   ("NonBonded", "Zhang"): ("direction", DIRECTIONS)}


def with_force_field_example(key):
    """The base document with the example added; lists and groups get entries that use them."""
    name, entry, _ = COMPONENTS[key]
    doc = base_document()
    if key in UNITS_OF:
        doc["global"]["units"] = {"type": ["Units", UNITS_OF[key]]}
    if key in STATE_COLUMN_OF:
        label, values = STATE_COLUMN_OF[key]
        doc["state"]["labels"].append(label)
        for row, value in zip(doc["state"]["data"], values):
            row.append(value)
    force_field = doc["topology"]["forceField"]
    cls, subclass = key
    if key in OPEN_BOX:
        doc["global"]["ensemble"]["data"][0][0] = ["inf", "inf", "inf"]
        force_field["nl"] = {"type": ["NBody", "all"]}
    if cls in ("VerletConditionalListSet", "NBody"):
        del force_field["nl"]  # the example is the list
    assert name not in force_field, f"example name '{name}' clashes with the test's base system"
    force_field[name] = copy.deepcopy(entry)
    if cls in ("VerletConditionalListSet", "NBody"):
        for condition in LIST_CONDITIONS[subclass]:
            force_field[f"lj_{condition}"] = lennard_jones(condition, name)
    if cls == "Groups":
        for group in entry["data"]:
            force_field[f"bonds_{group[0]}"] = {
                "type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 10.0, "r0": 1.0, "group": group[0]},
                "labels": ["id_i", "id_j"], "data": [[0, 1], [1, 2], [2, 3]]}
    return doc


# The in-tree NeighbourCount transverser plugin (tests/plugins), which ctest names: every handle here
# loads it, so that the example of ["TransverserMeasure","Plugin"] finds the transverser it names.
TRANSVERSER_PLUGIN = os.environ.get("STRUCTMD_TEST_TRANSVERSER_PLUGIN")
NEEDS_TRANSVERSER_PLUGIN = {("TransverserMeasure", "Plugin")}


@pytest.fixture
def sim(options):
    with structmd.Simulation({**options, **({"plugins": [TRANSVERSER_PLUGIN]} if TRANSVERSER_PLUGIN else {})}) as s:
        yield s


@pytest.mark.parametrize("key", FORCE_FIELD_COMPONENTS, ids=lambda k: f"{k[0]}-{k[1]}")
def test_force_field_example_loads_and_computes(sim, key):
    name = COMPONENTS[key][0]
    sim.load(with_force_field_example(key))
    sim.compute(forces=True, energy=True, virial=True)
    forces = np.asarray(sim.forces)
    assert forces.shape == (len(POSITIONS), 3)
    assert np.all(np.isfinite(forces)), forces
    assert math.isfinite(sim.energy("potential"))
    assert np.all(np.isfinite(sim.particle_energies))
    assert np.all(np.isfinite(sim.virial))
    if key[0] not in ("VerletConditionalListSet", "NBody", "Groups"):
        assert math.isfinite(sim.energy(name))
    sim.step(2)
    assert np.all(np.isfinite(np.asarray(sim.positions)))


# Steps that measure what one force-field component does, and that component.
MEASURED_COMPONENT = {("ExperimentMeasures", "AFMMeasure"): ("AFM", "SphericalTip"),
                      ("FlowControl", "AFMMaxForce"): ("AFM", "SphericalTip"),
                      ("TopologicalMeasures", "PatchPolymers"): ("PatchyParticles", "DynamicallyBondedPatchyParticles")}


def full_document_with(key):
    """The base document with the example put in its section, replacing the entry of its class (an
    integrator replaces every integrator and becomes the whole schedule)."""
    name, entry, section = COMPONENTS[key]
    doc = base_document()
    entries = doc.setdefault(section, {})
    if section == "integrator" and key[0] != "Schedule":
        same = lambda t: t[0] != "Schedule"
    elif key[0] == "Simulation":  # Information and Backup stand side by side in system
        same = lambda t: t == list(key)
    else:
        same = lambda t: t[0] == key[0]
    for other in [n for n, e in entries.items() if same(e["type"])]:
        del entries[other]
    entries[name] = copy.deepcopy(entry)
    if key in MEASURED_COMPONENT:  # a measure of one component's experiment needs that component
        needed_name, needed, _ = COMPONENTS[MEASURED_COMPONENT[key]]
        doc["topology"]["forceField"][needed_name] = copy.deepcopy(needed)
    if section == "integrator" and key[0] != "Schedule":
        doc["integrator"]["schedule"]["data"] = [[1, name, 10]]
    return doc


@pytest.mark.parametrize("key", DOCUMENT_COMPONENTS, ids=lambda k: f"{k[0]}-{k[1]}")
def test_document_example_loads_and_steps(sim, key, tmp_path, monkeypatch):
    if key in NEEDS_TRANSVERSER_PLUGIN and not TRANSVERSER_PLUGIN:
        pytest.skip("STRUCTMD_TEST_TRANSVERSER_PLUGIN not set (ctest sets it)")
    monkeypatch.chdir(tmp_path)  # measures write their files here
    sim.load(full_document_with(key))
    sim.step(2)
    assert sim.step_number >= 2
    assert np.all(np.isfinite(np.asarray(sim.forces)))


def test_the_sections_of_the_examples_are_known():
    known = {"system", "global", "integrator", "simulationStep", FORCE_FIELD}
    assert {section for _, _, section in COMPONENTS.values()} <= known


def test_the_complete_document_of_the_page_runs(sim, tmp_path, monkeypatch):
    text = DOC.read_text(encoding="utf-8")
    start = text.index("```json", text.index("## Document shape")) + len("```json")
    doc = json.loads(text[start:text.index("```", start)])
    monkeypatch.chdir(tmp_path)
    sim.load(doc)
    sim.run()
    assert (tmp_path / "thermo.dat").read_text().startswith("#step")
