"""Which pairs and particles each interaction acts on, and when: exclusions (nonExcluded), intra- and
inter-model lists, groups, batches, the per-type (and per-batch) tables of the Surface walls and
startStep/endStep. Each test compares the engine with the
energy of the pairs that must interact, summed here independently, so ignoring the rule fails it."""

import itertools
import json
import math

import numpy as np
import pytest

import structmd


def lj(r, epsilon=1.0, sigma=1.0):
    return 4.0 * epsilon * ((sigma / r) ** 12 - (sigma / r) ** 6)


def minimum_image(d, box):
    return d - box * np.round(d / box)


def document(positions, types=None, model=None, batch=None, force_field=None, steps=20, box=12.0):
    n = len(positions)
    types = types or ["A"] * n
    structure_labels = ["id", "type"] + (["modelId"] if model else []) + (["batchId"] if batch else [])
    rows = []
    for i in range(n):
        row = [i, types[i]]
        if model:
            row.append(model[i])
        if batch:
            row.append(batch[i])
        rows.append(row)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "scope"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0], ["B", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 0.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(p), [0.0, 0.0, 0.0]] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": structure_labels, "data": rows}, "forceField": force_field or {}},
    }


def lj_entry(condition="all", pairs=(("A", "A", 1.0, 1.0), ("A", "B", 1.0, 1.0), ("B", "B", 1.0, 1.0)), **extra):
    parameters = {"cutOffFactor": 2.5, "condition": condition}
    parameters.update(extra)
    return {"type": ["NonBonded", "LennardJonesType1"], "parameters": parameters,
            "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [list(p) for p in pairs]}


def pair_energy(positions, accept, box=12.0, epsilon=1.0):
    positions = np.asarray(positions)
    total = 0.0
    for i, j in itertools.combinations(range(len(positions)), 2):
        r = np.linalg.norm(minimum_image(positions[j] - positions[i], box))
        if r < 2.5 and accept(i, j):
            total += lj(r, epsilon)
    return total


# A small cluster: every pair within the cutoff, some across the boundary, none overlapping.
CLUSTER = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.0, 1.2, 0.1], [1.0, 1.1, 0.9], [-1.0, 0.2, 0.5],
           [5.6, 0.1, 0.0]]


@pytest.fixture
def sim(options):
    with structmd.Simulation(options) as s:
        yield s


def test_non_excluded_list_skips_the_excluded_pairs(sim):
    excluded = {0: [1, 2], 1: [0], 2: [0], 3: [4], 4: [3]}
    doc = document(CLUSTER, force_field={
        "nl": {"type": ["VerletConditionalListSet", "nonExcluded"], "parameters": {"cutOffVerletFactor": 1.2},
               "labels": ["id", "id_list"], "data": [[i, ids] for i, ids in excluded.items()]},
        "lj": lj_entry("nonExcluded")})
    sim.load(doc)
    expected = pair_energy(CLUSTER, lambda i, j: j not in excluded.get(i, []))
    assert sim.energy("lj") == pytest.approx(expected, rel=1e-12)
    assert expected != pytest.approx(pair_energy(CLUSTER, lambda i, j: True), rel=1e-3)


def test_exclusions_must_be_symmetric(sim):
    doc = document(CLUSTER, force_field={
        "nl": {"type": ["VerletConditionalListSet", "nonExcluded"], "labels": ["id", "id_list"],
               "data": [[0, [1]]]},
        "lj": lj_entry("nonExcluded")})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.nl\.data.*symmetric"):
        sim.load(doc)


def test_intra_and_inter_lists_split_pairs_by_model(sim):
    model = [0, 0, 0, 1, 1, 1]
    doc = document(CLUSTER, model=model, force_field={
        "nl": {"type": ["VerletConditionalListSet", "intra_inter"]},
        "intra": lj_entry("intra", neighbourList="nl"),
        "inter": lj_entry("inter", pairs=(("A", "A", 2.0, 1.0),), neighbourList="nl")})
    sim.load(doc)
    intra = pair_energy(CLUSTER, lambda i, j: model[i] == model[j])
    inter = pair_energy(CLUSTER, lambda i, j: model[i] != model[j], epsilon=2.0)
    assert sim.energy("intra") == pytest.approx(intra, rel=1e-12)
    assert sim.energy("inter") == pytest.approx(inter, rel=1e-12)
    assert sim.energy("potential") == pytest.approx(intra + inter, rel=1e-12)


def test_unknown_condition_names_the_path(sim):
    doc = document(CLUSTER, force_field={"nl": {"type": ["VerletConditionalListSet", "intra_inter"]},
                                         "lj": lj_entry("all")})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.lj\.parameters\.condition.*intra, inter"):
        sim.load(doc)


@pytest.mark.parametrize("selection, members", [
    (["Types", ["A"]], {0, 1, 3, 5}),
    (["notTypes", ["A"]], {2, 4}),
    (["Ids", [0, 1, 2]], {0, 1, 2}),
    (["notIds", [0]], {1, 2, 3, 4, 5}),
    (["ModelIds", [1]], {3, 4, 5}),
    (["notModelIds", [1]], {0, 1, 2}),
    # [modelId, batchId] pairs, matched as pairs: model 0 has no particle in batch 1.
    (["ModelIdsBatchIds", [[1, 0], [0, 1]]], {3, 4, 5}),
    (["notModelIdsBatchIds", [[1, 0]]], {0, 1, 2}),
])
def test_a_pair_term_acts_only_inside_its_group(sim, selection, members):
    types = ["A", "A", "B", "A", "B", "A"]
    doc = document(CLUSTER, types=types, model=[0, 0, 0, 1, 1, 1], force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["chosen"] + selection]},
        "nl": {"type": ["VerletConditionalListSet", "all"]},
        "lj": lj_entry(group="chosen")})
    sim.load(doc)
    expected = pair_energy(CLUSTER, lambda i, j: i in members and j in members)
    assert sim.energy("lj") == pytest.approx(expected, rel=1e-12)
    forces = sim.forces
    for i in set(range(len(CLUSTER))) - members:
        assert np.all(forces[i] == 0.0), f"particle {i} is outside the group but feels a force"


def test_a_group_selecting_nothing_is_an_input_error(sim):
    doc = document(CLUSTER, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["empty", "Types", ["B"]]]},
        "nl": {"type": ["VerletConditionalListSet", "all"]},
        "lj": lj_entry(group="empty")})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.groups\.data\[0\].*selects no particle"):
        sim.load(doc)


def test_bonds_act_only_when_all_their_particles_are_in_the_group(sim):
    doc = document(CLUSTER, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["first", "Ids", [0, 1, 2]]]},
        "bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 10.0, "r0": 1.0, "group": "first"},
                  "labels": ["id_i", "id_j"], "data": [[0, 1], [1, 2], [2, 3]]}})
    sim.load(doc)
    p = np.asarray(CLUSTER)
    expected = sum(0.5 * 10.0 * (np.linalg.norm(p[j] - p[i]) - 1.0) ** 2 for i, j in [(0, 1), (1, 2)])
    assert sim.energy("bonds") == pytest.approx(expected, rel=1e-12)


# Each of UAMMD-structured's conditional lists, condition by condition: which pairs of the cluster
# (models 0 and 1, types A and B, some charged, some excluded) the condition's LJ term sums.
CONDITION_MODELS = [0, 0, 1, 1, 1, 1]
CONDITION_TYPES = ["A", "A", "B", "B", "C", "B"]
CONDITION_CHARGES = [1.0, 0.0, -1.0, 0.5, 0.0, -0.5]
CONDITION_EXCLUDED = {1: [3], 3: [1], 2: [4], 4: [2]}  # each within the cutoff
TYPE_GROUP = {"A": 1, "B": 2}  # C is in neither


def charged(i):
    return CONDITION_CHARGES[i] != 0.0


def same_model(i, j):
    return CONDITION_MODELS[i] == CONDITION_MODELS[j]


def group(i):
    return TYPE_GROUP.get(CONDITION_TYPES[i], 0)


CONDITIONAL_LISTS = {
    "nonExclIntra_nonExclInter": {"intra": same_model, "inter": lambda i, j: not same_model(i, j)},
    "nonExclIntra_nonExclInter_nonExclCharged": {
        "intra": same_model, "inter": lambda i, j: not same_model(i, j),
        "charged": lambda i, j: charged(i) and charged(j)},
    "nonExclIntra_nonExclInter_nonExclInterCharged": {
        "charged": lambda i, j: not same_model(i, j) and charged(i) and charged(j)},
    "nonExcIntra_nonExcInter_nonExcInterCharged": {
        "charged": lambda i, j: not same_model(i, j) and charged(i) and charged(j)},
    "interDifferentType": {"inter": lambda i, j: not same_model(i, j) and CONDITION_TYPES[i] != CONDITION_TYPES[j]},
    "nonExclTypeGroup1Intra_nonExclTypeGroup2Intra_nonExclInter_nonExclNoGroup": {
        "typeGroup1Intra": lambda i, j: same_model(i, j) and group(i) == group(j) == 1,
        "typeGroup2Intra": lambda i, j: same_model(i, j) and group(i) == group(j) == 2,
        "inter": lambda i, j: group(i) and group(j) and (not same_model(i, j) or group(i) != group(j)),
        "noGroup": lambda i, j: not group(i) or not group(j)},
}


def conditional_document(list_type, conditions, type_groups=None):
    excludes = list_type != "interDifferentType"
    nl = {"type": ["VerletConditionalListSet", list_type]}
    if excludes:
        nl.update(labels=["id", "id_list"], data=[[i, ids] for i, ids in CONDITION_EXCLUDED.items()])
    if type_groups:
        nl["parameters"] = type_groups
    force_field = {"nl": nl}
    every_pair = [(a, b, 1.0, 1.0) for a, b in itertools.combinations_with_replacement("ABC", 2)]
    for condition in conditions:
        force_field[condition] = lj_entry(condition, pairs=every_pair)
    doc = document(CLUSTER, types=CONDITION_TYPES, model=CONDITION_MODELS, force_field=force_field)
    doc["global"]["types"]["data"].append(["C", 1.0, 0.5, 0.0])
    doc["state"]["labels"].append("charge")
    for row, q in zip(doc["state"]["data"], CONDITION_CHARGES):
        row.append(q)
    return doc


@pytest.mark.parametrize("list_type", sorted(CONDITIONAL_LISTS))
def test_each_condition_of_a_conditional_list_sums_its_own_pairs(sim, list_type):
    conditions = CONDITIONAL_LISTS[list_type]
    groups = {"typeGroup1": ["A"], "typeGroup2": ["B"]} if "TypeGroup" in list_type else None
    sim.load(conditional_document(list_type, conditions, groups))
    excludes = list_type != "interDifferentType"
    for condition, accept in conditions.items():
        expected = pair_energy(CLUSTER, lambda i, j: bool(accept(i, j)) and
                               not (excludes and j in CONDITION_EXCLUDED.get(i, [])))
        assert sim.energy(condition) == pytest.approx(expected, rel=1e-12), condition
        assert expected != 0.0, f"{condition} must hold some pair here"


def test_a_type_group_list_names_a_missing_or_repeated_type_group(sim):
    groups = {"typeGroup1": ["A"]}
    list_type = "nonExclTypeGroup1Intra_nonExclTypeGroup2Intra_nonExclInter_nonExclNoGroup"
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.nl\.parameters\.typeGroup2: missing"):
        sim.load(conditional_document(list_type, ["inter"], groups))
    with pytest.raises(structmd.InputError, match=r"typeGroup2\[0\]: a type can be in one type group only"):
        sim.load(conditional_document(list_type, ["inter"], {"typeGroup1": ["A"], "typeGroup2": ["A"]}))


def test_batches_never_interact_and_their_energies_are_read_separately(sim, options):
    # Two copies of the cluster in one box, shifted by a little: across batches they would overlap.
    shifted = [[x + 0.3, y + 0.2, z + 0.1] for x, y, z in CLUSTER]
    positions = CLUSTER + shifted
    batch = [0] * len(CLUSTER) + [1] * len(shifted)
    doc = document(positions, batch=batch, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]},
                                                        "lj": lj_entry()})
    sim.load(doc)
    single = pair_energy(CLUSTER, lambda i, j: True)
    assert sim.energy("lj@batch:0") == pytest.approx(single, rel=1e-12)
    assert sim.energy("potential@batch:1") == pytest.approx(single, rel=1e-12)
    assert sim.energy("lj") == pytest.approx(2.0 * single, rel=1e-12)
    with structmd.Simulation(options) as alone:
        alone.load(document(CLUSTER, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]},
                                                  "lj": lj_entry()}))
        np.testing.assert_allclose(sim.forces[:len(CLUSTER)], alone.forces, rtol=1e-12, atol=1e-12)
    with pytest.raises(structmd.ArgumentError, match="batchId '7'"):
        sim.energy("lj@batch:7")


def test_a_batched_pair_table_gives_each_batch_its_own_type_pairs(sim, options, tmp_path):
    # Two copies of the cluster (types A and B) with batchIds 5 and 2 (numbered 1 and 0 inside the
    # engine), each with its own parameters; batch 2 lists no (B, B) row, so its B particles never meet.
    types = ["A", "B", "A", "B", "A", "B"]
    shifted = [[x + 0.3, y + 0.2, z + 0.1] for x, y, z in CLUSTER]
    batch = [5] * len(CLUSTER) + [2] * len(shifted)
    rows = {5: {("A", "A"): (1.0, 1.0), ("A", "B"): (0.6, 0.9), ("B", "B"): (1.4, 1.05)},
            2: {("A", "A"): (0.8, 1.1), ("A", "B"): (1.2, 0.95)}}
    table = [[a, b, eps, sigma, batchId] for batchId, pairs in rows.items() for (a, b), (eps, sigma) in pairs.items()]
    entry = {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.5, "condition": "all"},
             "labels": ["name_i", "name_j", "epsilon", "sigma", "batchId"], "data": table}
    positions = CLUSTER + shifted
    doc = document(positions, types=types * 2, batch=batch,
                   force_field={"nl": {"type": ["VerletConditionalListSet", "all"]}, "lj": entry})
    # The Hessian reads the table around one particle at a time: exact against central differences.
    doc["simulationStep"] = {mode: {"type": ["MechanicalMeasure", "HessianMeasure"],
                                    "parameters": {"intervalStep": 1000, "mode": mode, "outputPrecision": 12,
                                                   "outputFilePath": str(tmp_path / f"{mode}.dat")}}
                             for mode in ("Analytical", "Numerical")}
    sim.load(doc)
    sim.step(1)
    hessians = [np.loadtxt(tmp_path / f"{mode}.dat")[:, 2:] for mode in ("Analytical", "Numerical")]
    scale = np.max(np.abs(hessians[0]))
    assert scale > 1.0 and np.max(np.abs(hessians[0] - hessians[1])) < 1e-6 * scale
    sim.positions = positions

    def batch_energy(members, pairs):
        total = 0.0
        for i, j in itertools.combinations(members, 2):
            key = tuple(sorted((types[i % 6], types[j % 6])))
            if key not in pairs:
                continue
            epsilon, sigma = pairs[key]
            r = np.linalg.norm(minimum_image(np.subtract(positions[j], positions[i]), 12.0))
            if r < 2.5 * sigma:
                total += lj(r, epsilon, sigma)
        return total

    first, second = range(6), range(6, 12)
    assert sim.energy("lj@batch:5") == pytest.approx(batch_energy(first, rows[5]), rel=1e-12)
    assert sim.energy("lj@batch:2") == pytest.approx(batch_energy(second, rows[2]), rel=1e-12)
    # Each batch alone, unbatched, with its rows: the same forces.
    for members, batchId in ((first, 5), (second, 2)):
        alone_table = [[a, b, eps, sigma] for (a, b), (eps, sigma) in rows[batchId].items()]
        alone_entry = dict(entry, labels=entry["labels"][:4], data=alone_table)
        with structmd.Simulation(options) as alone:
            alone.load(document([positions[i] for i in members], types=types,
                                force_field={"nl": {"type": ["VerletConditionalListSet", "all"]}, "lj": alone_entry}))
            np.testing.assert_allclose(sim.forces[list(members)], alone.forces, rtol=1e-12, atol=1e-12)


def test_a_batched_pair_table_names_the_row_of_a_missing_batch_or_a_repeated_pair(sim):
    entry = lj_entry()
    entry["labels"] = entry["labels"] + ["batchId"]
    doc = document(CLUSTER, batch=[0, 0, 0, 1, 1, 1], force_field={
        "nl": {"type": ["VerletConditionalListSet", "all"]},
        "lj": dict(entry, data=[["A", "A", 1.0, 1.0, 0], ["A", "A", 1.0, 1.0, 3]])})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.lj\.data\[1\]\[4\].*no particle has batchId 3"):
        sim.load(doc)
    doc["topology"]["forceField"]["lj"]["data"] = [["A", "A", 1.0, 1.0, 1], ["A", "A", 0.5, 1.0, 1]]
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.lj\.data\[1\].*listed twice for this batchId"):
        sim.load(doc)


def kim_hummer_document(**parameters):
    entry = {"type": ["NonBonded", "KimHummer"],
             "parameters": {"cutOffNPFactor": 2.0, "cutOffDHFactor": 2.0, "dielectricConstant": 80.0,
                            "debyeLength": 1.0, "condition": "all", **parameters},
             "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", -0.5, 1.0]]}
    return document(CLUSTER, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]}, "kh": entry})


def test_kim_hummer_takes_sasa_model_a_and_refuses_the_models_that_need_surface_areas(sim):
    sim.load(kim_hummer_document())
    default = sim.energy("kh")
    sim.load(kim_hummer_document(sasaModel="A"))
    assert default != 0.0 and sim.energy("kh") == default
    with pytest.raises(structmd.UnsupportedError, match=r"topology\.forceField\.kh\.parameters\.sasaModel: "
                                                        r"\"C\" is not supported: SASA models B-F"):
        sim.load(kim_hummer_document(sasaModel="C"))
    with pytest.raises(structmd.InputError, match=r"parameters\.sasaModel: expected one of A, B, C, D, E, F, got \"Z\""):
        sim.load(kim_hummer_document(sasaModel="Z"))


def surface_lj2(z, plane, epsilon, sigma):
    """SurfaceLennardJonesType2 of a particle at height z."""
    x = sigma / abs(z - plane)
    return epsilon * (x**12 - 2.0 * x**6)


SURFACE_POSITIONS = [[0.0, 0.0, 1.0], [1.0, 2.0, -1.4], [-2.0, 1.0, 2.2], [3.0, -1.0, 0.8], [0.5, 0.5, -0.9],
                     [-3.0, 3.0, 1.7]]


def surface_entry(rows, labels=("name", "epsilon", "sigma")):
    return {"type": ["Surface", "SurfaceLennardJonesType2"], "parameters": {"surfacePosition": 0.2},
            "labels": list(labels), "data": rows}


def test_a_surface_acts_on_each_particle_by_its_type_and_not_on_unlisted_types(sim):
    types = ["A", "B", "A", "B", "A", "B"]
    sim.load(document(SURFACE_POSITIONS, types=types, force_field={"wall": surface_entry([["A", 0.7, 0.9]])}))
    expected = [surface_lj2(p[2], 0.2, 0.7, 0.9) if t == "A" else 0.0 for p, t in zip(SURFACE_POSITIONS, types)]
    np.testing.assert_allclose(sim.particle_energies, expected, rtol=1e-12, atol=0.0)
    assert np.all(np.asarray(sim.forces)[1::2] == 0.0)


def test_a_batched_surface_table_gives_each_batch_its_own_rows(sim):
    # batchIds 3 and 7 (numbered 0 and 1 inside the engine); type B of batch 7 is not listed.
    types = ["A", "B", "A", "B", "A", "B"]
    batch = [3, 3, 7, 7, 7, 3]
    rows = {(3, "A"): (0.7, 0.9), (3, "B"): (1.3, 0.8), (7, "A"): (0.4, 1.1)}
    table = [[t, eps, sigma, b] for (b, t), (eps, sigma) in rows.items()]
    sim.load(document(SURFACE_POSITIONS, types=types, batch=batch,
                      force_field={"wall": surface_entry(table, ("name", "epsilon", "sigma", "batchId"))}))
    expected = [surface_lj2(p[2], 0.2, *rows[(b, t)]) if (b, t) in rows else 0.0
                for p, t, b in zip(SURFACE_POSITIONS, types, batch)]
    np.testing.assert_allclose(sim.particle_energies, expected, rtol=1e-12, atol=0.0)
    assert sim.energy("wall@batch:7") == pytest.approx(expected[2] + expected[4], rel=1e-12)


def test_a_batched_surface_row_of_a_batch_no_particle_has_names_its_cell(sim):
    doc = document(SURFACE_POSITIONS, batch=[0, 0, 0, 1, 1, 1], force_field={
        "wall": surface_entry([["A", 0.7, 0.9, 0], ["A", 0.7, 0.9, 2]], ("name", "epsilon", "sigma", "batchId"))})
    with pytest.raises(structmd.InputError,
                       match=r"topology\.forceField\.wall\.data\[1\]\[3\].*no particle has batchId 2"):
        sim.load(doc)


def test_start_and_end_step_switch_a_term_on_and_off(sim):
    doc = document([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]], steps=30, force_field={
        "late": {"type": ["Bond2", "HarmonicCommon_K_r0"],
                 "parameters": {"K": 10.0, "r0": 1.0, "startStep": 5, "endStep": 12},
                 "labels": ["id_i", "id_j"], "data": [[0, 1]]}})
    sim.load(doc)
    for step in range(20):
        active = 5 <= sim.step_number < 12
        energy = sim.energy("late")
        if active:
            assert energy > 0.0, f"the bond must act at step {sim.step_number}"
        else:
            assert energy == 0.0 and np.all(sim.forces == 0.0), f"the bond must not act at step {sim.step_number}"
        sim.step(1)
    # Before step 5 nothing moved; the bond then pulled the particles together.
    assert sim.positions[1][0] - sim.positions[0][0] < 1.5


@pytest.mark.parametrize("entry, path, what", [
    ({"type": ["Bond3", "HarmonicAngular"], "labels": ["id_i", "id_j", "id_k", "K", "theta0"],
      "data": [[0, 1, 1, 1.0, 2.0]]}, r"data\[0\]\[2\]", "appears twice"),
    ({"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 99, 1.0, 1.0]]},
     r"data\[0\]\[1\]", "does not exist"),
    ({"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, 1.0]]},
     r"data\[0\]", "cells"),
    ({"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K"], "data": [[0, 1, 1.0]]},
     r"labels", "r0"),
    ({"type": ["Bond4", "Dihedral4"], "labels": ["id_i", "id_j", "id_k", "id_l", "K", "phi0"],
      "data": [[0, 1, 2, 3, [1.0, 2.0], [0.0, 0.0, 0.0, 0.0]]]}, r"data\[0\]\[4\]", "4 numbers"),
    ({"type": ["External", "Plates"], "parameters": {"platesEpsilon": 1.0}}, r"parameters\.platesSeparation",
     "missing"),
])
def test_malformed_bonded_entries_name_their_path(sim, entry, path, what):
    doc = document(CLUSTER, force_field={"term": entry})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.term\." + path + ".*" + what):
        sim.load(doc)


def test_unknown_type_name_in_a_pair_table(sim):
    doc = document(CLUSTER, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]},
                                         "lj": lj_entry(pairs=(("A", "C", 1.0, 1.0),))})
    with pytest.raises(structmd.InputError, match=r"topology\.forceField\.lj\.data\[0\]\[1\].*unknown type 'C'"):
        sim.load(doc)


def test_reading_after_the_neighbour_list_grew(sim):
    # A cluster much denser than the box's mean density: the first list capacity, guessed from the
    # mean, is too small, and stepping enlarges it. Reading at the same positions afterwards must use
    # buffers sized for the new capacity (this once read past their end).
    cluster = [[0.95 * i, 0.95 * j, 0.95 * k] for i in range(3) for j in range(3) for k in range(3)][:20]
    doc = document(cluster, steps=10, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]},
                                                   "lj": lj_entry()})
    sim.load(doc)
    sim.step(2)
    energy = sim.energy("lj")
    forces = sim.forces
    positions = sim.positions
    expected = pair_energy(positions, lambda i, j: True)
    assert energy == pytest.approx(expected, rel=1e-9)
    assert np.all(np.isfinite(forces))


def test_groups_of_the_integrator_and_simulation_step_sections_are_known_everywhere(sim, tmp_path):
    """UAMMD-structured's inputs put GroupsList entries (with an empty parameters object) in the
    integrator and simulationStep sections too: the integrator moves its group, the step writes its
    group, and a group repeated with the same selection is one group."""
    groups = {"type": ["Groups", "GroupsList"], "parameters": {}, "labels": ["name", "type", "selection"],
              "data": [["moving", "Ids", [0, 1, 2]]]}
    doc = document(CLUSTER, force_field={"nl": {"type": ["VerletConditionalListSet", "all"]}, "lj": lj_entry()},
                   steps=5)
    doc["integrator"]["groups"] = groups
    doc["integrator"]["vv"]["parameters"]["group"] = "moving"
    doc["simulationStep"] = {
        "groups": dict(groups, data=[["moving", "Ids", [0, 1, 2]], ["written", "notIds", [0]]]),
        "write": {"type": ["WriteStep", "WriteStep"],
                  "parameters": {"intervalStep": 5, "outputFilePath": str(tmp_path / "out"), "outputFormat": "xyz",
                                 "group": "written"}}}
    sim.load(doc)
    start = sim.positions
    sim.run()
    assert np.array_equal(sim.positions[3:], start[3:]), "particles outside the integrator's group stay"
    assert np.all(np.any(sim.positions[:3] != start[:3], axis=1))
    first_frame = (tmp_path / "out.xyz").read_text().splitlines()
    assert first_frame[0].strip() == str(len(CLUSTER) - 1)


def test_a_group_redefined_with_another_selection_names_its_path(sim):
    doc = document(CLUSTER, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["g", "Ids", [0, 1]]]},
        "nl": {"type": ["VerletConditionalListSet", "all"]}, "lj": lj_entry()})
    doc["integrator"]["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                   "data": [["g", "Ids", [0, 2]]]}
    with pytest.raises(structmd.InputError, match=r"integrator\.groups\.data\[0\]\[0\].*different selections"):
        sim.load(doc)
