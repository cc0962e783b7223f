"""["MechanicalMeasure","HessianMeasure"] on every force-field component through the whole engine:
the file's blocks d2U/dx_i dx_j, in both modes, against central differences of the forces the API
returns (positions set, forces read), on the configurations of test_component_gradients. The
Analytical mode differentiates each term's functor in dual numbers, so a wrong seed, a block put
under the wrong particle or a transposed block fails here; the Numerical mode differentiates the
engine's forces itself, so it is checked against the same reference."""

import numpy as np
import pytest

import structmd
from test_component_gradients import CASES, N, case_document, configuration, document


def hessian_step(path, mode, group=None):
    parameters = {"intervalStep": 1, "outputFilePath": str(path), "mode": mode, "outputPrecision": 14}
    if group:
        parameters["group"] = group
    return {"type": ["MechanicalMeasure", "HessianMeasure"], "parameters": parameters}


def read_hessian(path, ids):
    """{(i, j): 3x3 block} of the first firing of a Hessian file."""
    lines = path.read_text().splitlines()
    assert lines[0].split() == ["#", "Id_i", "Id_j", "Hxx", "Hxy", "Hxz", "Hyx", "Hyy", "Hyz", "Hzx", "Hzy", "Hzz"]
    assert lines[1].startswith("# step 0 time ")
    blocks = {}
    for line in lines[2:]:
        if line.startswith("#"):
            break
        values = line.split()
        blocks[(int(values[0]), int(values[1]))] = np.array([float(x) for x in values[2:]]).reshape(3, 3)
    assert sorted(blocks) == sorted((i, j) for i in ids for j in ids)
    return blocks


def reference_hessian(sim, positions, h=1e-5):
    """H[3i + a, 3j + b] = -(F_j^b(x_i^a + h) - F_j^b(x_i^a - h)) / 2h, forces read through the API."""
    hessian = np.zeros((3 * N, 3 * N))
    for i in range(N):
        for a in range(3):
            moved = positions.copy()
            moved[i, a] += h
            sim.positions = moved
            forward = sim.forces.reshape(-1)
            moved[i, a] -= 2 * h
            sim.positions = moved
            backward = sim.forces.reshape(-1)
            hessian[3 * i + a] = -(forward - backward) / (2 * h)
    return hessian


def as_matrix(blocks):
    hessian = np.zeros((3 * N, 3 * N))
    for (i, j), block in blocks.items():
        hessian[3 * i:3 * i + 3, 3 * j:3 * j + 3] = block
    return hessian


@pytest.mark.parametrize("name", sorted(CASES))
def test_both_modes_match_central_differences_of_the_forces(options, tmp_path, name):
    _, doc = case_document(name)
    doc["simulationStep"] = {"analytical": hessian_step(tmp_path / "analytical.dat", "Analytical"),
                             "numerical": hessian_step(tmp_path / "numerical.dat", "Numerical")}
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        before = sim.positions
        sim.step(1)
        analytical = as_matrix(read_hessian(tmp_path / "analytical.dat", range(N)))
        numerical = as_matrix(read_hessian(tmp_path / "numerical.dat", range(N)))
        sim.positions = before
        reference = reference_hessian(sim, before)
    scale = np.max(np.abs(reference))
    assert scale > 0.0, "the term must curve the energy on this configuration"
    np.testing.assert_allclose(reference, reference.T, atol=1e-6 * scale)
    assert np.max(np.abs(analytical - reference)) < 1e-6 * scale, name
    assert np.max(np.abs(numerical - reference)) < 1e-6 * scale, name


def test_a_group_limits_the_blocks_and_the_measure_leaves_the_trajectory_alone(options, tmp_path):
    """Blocks only between the group's particles; and measuring (which moves particles to and fro in
    the Numerical mode) changes nothing the integrator sees."""
    positions = configuration(seed=3)
    force_field = dict(CASES["LennardJonesType1"])
    force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                             "data": [["some", "Ids", [1, 4, 7]]]}
    plain = document(positions, force_field)
    measured = document(positions, force_field)
    measured["simulationStep"] = {"h": hessian_step(tmp_path / "h.dat", "Numerical", group="some"),
                                  "a": hessian_step(tmp_path / "a.dat", "Analytical", group="some")}
    trajectories = []
    for doc in (plain, measured):
        with structmd.Simulation(dict(options, precision="double")) as sim:
            sim.load(doc)
            sim.step(10)
            trajectories.append(sim.positions)
    np.testing.assert_array_equal(trajectories[0], trajectories[1])
    numerical = read_hessian(tmp_path / "h.dat", [1, 4, 7])
    analytical = read_hessian(tmp_path / "a.dat", [1, 4, 7])
    for key, block in analytical.items():
        np.testing.assert_allclose(numerical[key], block, atol=1e-6 * np.max(np.abs(block)) + 1e-9)


def test_analytical_mode_refuses_a_term_without_second_derivatives(options, tmp_path):
    positions = configuration(seed=0)
    expression = {"term": {"type": ["External", "Expression"],
                           "parameters": {"energy": "0.5 * k * (x^2 + y^2 + z^2)", "k": 2.0}}}
    doc = document(positions, expression)
    doc["simulationStep"] = {"hessian": hessian_step(tmp_path / "h.dat", "Analytical")}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"simulationStep\.hessian\.parameters\.mode.*'term'"):
            sim.load(doc)
        doc["simulationStep"]["hessian"]["parameters"]["mode"] = "Numerical"
        sim.load(doc)
        sim.step(1)
        blocks = read_hessian(tmp_path / "h.dat", range(N))
    for (i, j), block in blocks.items():
        expected = 2.0 * np.eye(3) if i == j else np.zeros((3, 3))
        np.testing.assert_allclose(block, expected, atol=1e-6)


def test_an_unknown_mode_names_its_path(options, tmp_path):
    doc = document(configuration(seed=0), CASES["LennardJonesType1"])
    doc["simulationStep"] = {"hessian": hessian_step(tmp_path / "h.dat", "Exact")}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"simulationStep\.hessian\.parameters\.mode.*Analytical"):
            sim.load(doc)
