"""["MechanicalMeasure","PairwiseForceMeasure"] on every force-field component through the whole
engine, on the configurations of test_component_gradients: the forces the particles exert on each
other sum, for each receiver, to its whole force (UAMMD-structured's own check); each is central
(along the line between the two, but for direction-dependent springs) and opposite to its reverse (Newton's third law); the Lennard-Jones
pair forces match the formula written here; and "Total_force" writes the forces the API returns."""

import numpy as np
import pytest

import structmd
from test_component_gradients import BOX, CASES, N, TABLE, case_document, configuration, document

ONE_PARTICLE = ("Bond1", "External", "Surface")  # terms that exert no force from another particle


def force_step(path, mode, group=None):
    parameters = {"intervalStep": 1, "outputFilePath": str(path), "mode": mode}
    if group:
        parameters["group"] = group
    return {"type": ["MechanicalMeasure", "PairwiseForceMeasure"], "parameters": parameters}


def first_firing(path, header):
    lines = path.read_text().splitlines()
    assert lines[0].split() == header
    assert lines[1].startswith("# step 0 time ")
    rows = []
    for line in lines[2:]:
        if line.startswith("#"):
            break
        rows.append([float(x) for x in line.split()])
    return np.array(rows).reshape(-1, len(header))


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def run(name, tmp_path):
    positions, doc = case_document(name)
    doc["simulationStep"] = {"pairs": force_step(tmp_path / "pairs.dat", "Pairwise_force"),
                             "total": force_step(tmp_path / "total.dat", "Total_force")}
    with structmd.Simulation(dict(OPTIONS, precision="double")) as sim:
        sim.load(doc)
        forces = sim.forces
        sim.step(1)
    pairs = first_firing(tmp_path / "pairs.dat", ["#From", "To", "Fx", "Fy", "Fz"])
    total = first_firing(tmp_path / "total.dat", ["#Id", "Fx", "Fy", "Fz"])
    return positions, forces, pairs, total


@pytest.fixture(autouse=True)
def engine(options):
    global OPTIONS
    OPTIONS = options


# Terms on centres of mass (Set1, Set2) act between sets, not pairs: they have no pair split.
@pytest.mark.parametrize("name", sorted(name for name in CASES if not name.startswith("Set")))
def test_pair_forces_are_central_opposite_and_sum_to_each_particles_force(tmp_path, name):
    positions, forces, pairs, total = run(name, tmp_path)
    np.testing.assert_array_equal(total[:, 0], np.arange(N))
    np.testing.assert_allclose(total[:, 1:], forces, rtol=0, atol=1e-12 * np.max(np.abs(forces)))
    if name.startswith(ONE_PARTICLE):
        assert len(pairs) == 0
        return
    assert len(pairs) > 0
    scale = np.max(np.abs(forces))
    summed = np.zeros((N, 3))
    by_pair = {}
    for source, receiver, *f in pairs:
        i, j = int(receiver), int(source)
        summed[i] += f
        by_pair[(j, i)] = np.array(f)
        separation = minimum_image(positions[i] - positions[j])
        if "Anisotropic" not in name:  # a spring per axis pulls off the line between the two
            assert np.linalg.norm(np.cross(f, separation)) <= 1e-8 * scale * np.linalg.norm(separation)
    np.testing.assert_allclose(summed, forces, rtol=0, atol=1e-8 * scale)
    for (j, i), f in by_pair.items():
        np.testing.assert_allclose(by_pair[(i, j)], -f, rtol=0, atol=1e-8 * scale)


def test_lennard_jones_pair_forces_follow_the_formula(tmp_path):
    positions, _, pairs, _ = run("LennardJonesType1", tmp_path)
    types = ["A" if i % 3 else "B" for i in range(N)]
    parameters = {frozenset((a, b)): (eps, sigma) for a, b, eps, sigma in TABLE}
    written = {(int(s), int(r)): np.array(f) for s, r, *f in pairs}
    expected = {}
    for i in range(N):
        for j in range(N):
            eps, sigma = parameters[frozenset((types[i], types[j]))]
            d = minimum_image(positions[i] - positions[j])
            r = np.linalg.norm(d)
            if i == j or r >= 2.4 * sigma:
                continue
            dudr = 4 * eps * (-12 * sigma ** 12 / r ** 13 + 6 * sigma ** 6 / r ** 7)
            expected[(j, i)] = -dudr * d / r  # the force j exerts on i
    assert sorted(written) == sorted(expected)
    for key, f in expected.items():
        np.testing.assert_allclose(written[key], f, rtol=1e-10, atol=1e-12)


def test_an_expression_bond_splits_on_the_cpu_and_is_refused_where_it_is_compiled(tmp_path):
    """The CPU backend interprets an expression with the built-in bond kernels, so its forces split
    like any bond's; CUDA compiles it into a kernel of its own that cannot split them, and says so
    (ERR_UNSUPPORTED names the entry) while "Total_force" works."""
    positions = configuration(seed=0)
    expression = {"term": {"type": ["Bond2", "Expression"], "parameters": {"energy": "0.5 * k * r^2", "k": 2.0},
                           "labels": ["id_i", "id_j"], "data": [[0, 1]]}}
    doc = document(positions, expression)
    doc["simulationStep"] = {"pairs": force_step(tmp_path / "p.dat", "Pairwise_force")}
    with structmd.Simulation(OPTIONS) as sim:
        if OPTIONS["backend"] == "cuda":
            with pytest.raises(structmd.UnsupportedError, match=r"simulationStep\.pairs\.parameters\.mode.*'term'"):
                sim.load(doc)
            doc["simulationStep"]["pairs"]["parameters"]["mode"] = "Total_force"
            sim.load(doc)
            sim.step(1)
            total = first_firing(tmp_path / "p.dat", ["#Id", "Fx", "Fy", "Fz"])
            np.testing.assert_allclose(total[1, 1:], -2.0 * minimum_image(positions[1] - positions[0]), rtol=1e-10)
            return
        sim.load(doc)
        sim.step(1)
    pairs = first_firing(tmp_path / "p.dat", ["#From", "To", "Fx", "Fy", "Fz"])
    assert sorted((int(s), int(r)) for s, r, *_ in pairs) == [(0, 1), (1, 0)]
    for source, receiver, *f in pairs:
        i, j = int(receiver), int(source)
        np.testing.assert_allclose(f, -2.0 * minimum_image(positions[i] - positions[j]), rtol=1e-10)


def test_an_unknown_mode_names_its_path(tmp_path):
    doc = document(configuration(seed=0), CASES["LennardJonesType1"])
    doc["simulationStep"] = {"pairs": force_step(tmp_path / "p.dat", "Both")}
    with structmd.Simulation(OPTIONS) as sim:
        with pytest.raises(structmd.InputError, match=r"simulationStep\.pairs\.parameters\.mode.*Pairwise_force"):
            sim.load(doc)


def test_force_between_sets_sums_the_pair_forces_from_one_set_on_the_other(tmp_path):
    """Three sets over a bonded chain with Lennard-Jones between all pairs: each line is the sum of the
    pair forces from its first set's particles on its second set's, as PairwiseForceMeasure writes
    them in the same firing; and the reverse line is its opposite."""
    force_field = dict(CASES["Bond3 HarmonicAngular"], nl=CASES["LennardJonesType1"]["nl"],
                       lj=CASES["LennardJonesType1"]["term"])
    doc = document(configuration(seed=5), force_field)
    sets = {"head": [0, 1, 2, 3], "middle": [4, 5, 6, 7], "tail": [8, 9, 10]}
    doc["simulationStep"] = {
        "pairs": force_step(tmp_path / "pairs.dat", "Pairwise_force"),
        "sets": {"type": ["MechanicalMeasure", "ForceBetweenSetsMeasure"],
                 "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "sets.dat")},
                 "labels": ["name", "id_list"], "data": [[name, ids] for name, ids in sets.items()]}}
    with structmd.Simulation(dict(OPTIONS, precision="double")) as sim:
        sim.load(doc)
        sim.step(1)
    pairs = {(int(s), int(r)): np.array(f) for s, r, *f in first_firing(tmp_path / "pairs.dat",
                                                                        ["#From", "To", "Fx", "Fy", "Fz"])}
    lines = (tmp_path / "sets.dat").read_text().splitlines()
    assert lines[0].split() == ["#From", "To", "Fx", "Fy", "Fz"] and lines[1].startswith("# step 0 ")
    written = {(line.split()[0], line.split()[1]): np.array([float(x) for x in line.split()[2:]])
               for line in lines[2:8]}
    assert sorted(written) == sorted((a, b) for a in sets for b in sets if a != b)
    for (source, receiver), f in written.items():
        expected = sum((pairs.get((j, i), np.zeros(3)) for i in sets[receiver] for j in sets[source]), np.zeros(3))
        np.testing.assert_allclose(f, expected, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(written[(receiver, source)], -f, rtol=1e-9, atol=1e-9)
    assert np.linalg.norm(written[("head", "middle")]) > 0.0
