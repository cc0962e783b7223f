"""Terms on centres of mass of sets of particles (Set1, Set2) and the DistanceBetweenCentersOfMass
measure, against the formulas written here in numpy: each centre mass-weighted over its members
unwrapped next to the set's first member, forces spread by mass, torques with zero net force. The
force = -grad U checks and the Hessian checks are the shared ones (test_component_gradients CASES)."""

import numpy as np
import pytest

import structmd
from test_component_gradients import BOX, CASES, N, SET_CASES, SETS1, SETS2, configuration, document
from test_hessian import hessian_step

MASS = np.array([2.0 if i % 3 == 0 else 1.0 for i in range(N)])  # types B and A, as document() assigns


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def centre(positions, ids):
    first = positions[ids[0]]
    unwrapped = first + minimum_image(positions[ids] - first)
    return (MASS[ids, None] * unwrapped).sum(axis=0) / MASS[ids].sum(), unwrapped


def load(doc, options):
    sim = structmd.Simulation(dict(options, precision="double"))
    sim.load(doc)
    return sim


def expected_energy(name, positions):
    term = CASES[name]["term"]
    total = 0.0
    for row in term["data"]:
        cells = dict(zip(term["labels"], row))
        cells.update(term.get("parameters", {}))
        if name.startswith("Set1"):
            c, _ = centre(positions, cells["idSet_i"])
            d = minimum_image(np.array(cells["position"]) - c)
            K = np.broadcast_to(cells["K"], 3)
            r0 = np.broadcast_to(cells["r0"], 3)
            total += np.sum(0.5 * K * (np.abs(d) - r0) ** 2)
        else:
            r = np.linalg.norm(minimum_image(centre(positions, cells["idSet_j"])[0] -
                                             centre(positions, cells["idSet_i"])[0]))
            if "Harmonic" in name:
                total += 0.5 * cells["K"] * (r - cells["r0"]) ** 2
            else:
                total += -cells["force"] * r
    return total


@pytest.mark.parametrize("name", [case[0] for case in SET_CASES])
def test_energy_is_the_centre_of_mass_formula_and_each_centre_feels_its_force(options, name):
    positions = configuration(seed=5)
    with load(document(positions, CASES[name]), options) as sim:
        energy = sim.energy("term")
        forces = sim.forces
    expected = expected_energy(name, positions)
    assert abs(expected) > 1e-3
    assert energy == pytest.approx(expected, rel=1e-12, abs=1e-12)
    term = CASES[name]["term"]
    for row in term["data"]:
        ids = [row[0]] if name.startswith("Set1") else [row[0], row[1]]
        shares = [forces[s] / MASS[s, None] for s in ids]
        # Every member of a set gets the same force per unit mass: the centre's force over the set's mass.
        for share in shares:
            np.testing.assert_allclose(share, np.broadcast_to(share[0], share.shape), rtol=0, atol=1e-12)
        if len(ids) == 2:  # the two centres feel opposite forces
            np.testing.assert_allclose(forces[ids[0]].sum(axis=0), -forces[ids[1]].sum(axis=0), atol=1e-12)


def test_a_constant_force_on_a_centre_reaches_its_members_by_mass(options):
    positions = configuration(seed=1)
    F = np.array([0.3, -1.2, 0.7])
    term = {"type": ["Set1", "ConstantForceOverCenterOfMass"], "labels": ["idSet_i", "force"],
            "data": [[SETS1[0], list(F)], [SETS1[2], list(2 * F)]]}
    with load(document(positions, {"term": term}), options) as sim:
        forces = sim.forces
        assert sim.energy("term") == 0.0
    expected = np.zeros((N, 3))
    for ids, f in ((SETS1[0], F), (SETS1[2], 2 * F)):
        expected[ids] = MASS[ids, None] / MASS[ids].sum() * f
    np.testing.assert_allclose(forces, expected, rtol=0, atol=1e-14)


def torque_forces(positions, ids, T):
    """UAMMD-structured's construction: f_k = m_k T x u_k / sum m |u|^2, u_k the offset from the axis."""
    c, unwrapped = centre(positions, ids)
    d = unwrapped - c
    u = d - np.outer(d @ T, T) / (T @ T)
    return MASS[ids, None] * np.cross(T, u) / np.sum(MASS[ids] * np.sum(u * u, axis=1)), d


def test_a_torque_on_a_set_has_no_net_force_and_its_component_along_the_axis(options):
    positions = configuration(seed=2)
    T = np.array([0.4, -0.9, 1.3])
    ids = SETS1[2]
    term = {"type": ["Set1", "ConstantTorqueOverCenterOfMass"], "labels": ["idSet_i", "torque"],
            "data": [[ids, list(T)]]}
    with load(document(positions, {"term": term}), options) as sim:
        forces = sim.forces
        assert sim.energy("term") == 0.0
    expected, d = torque_forces(positions, ids, T)
    np.testing.assert_allclose(forces[ids], expected, rtol=0, atol=1e-12)
    others = [i for i in range(N) if i not in ids]
    assert np.all(forces[others] == 0.0)
    np.testing.assert_allclose(forces.sum(axis=0), 0.0, atol=1e-12)
    torque = np.cross(d, forces[ids]).sum(axis=0)
    assert torque @ T / np.linalg.norm(T) == pytest.approx(np.linalg.norm(T), rel=1e-12)


def test_a_torque_on_a_set_symmetric_about_its_axis_is_exactly_the_given_torque(options):
    """Six equal masses on a ring about an axis through a point on the box face: the products of
    inertia about the axis vanish, so the torque about the centre is T itself."""
    T = np.array([0.0, 0.0, 2.5])
    ring = [1, 2, 4, 5, 7, 8]  # type A: equal masses
    positions = configuration(seed=0) * 0.0
    for k in range(N):
        positions[k] = [0.0, -3.0 + 0.5 * k, 2.0]
    axis_point = np.array([BOX / 2 - 0.1, 0.5, -1.0])
    for k, i in enumerate(ring):
        angle = 2 * np.pi * k / len(ring)
        positions[i] = axis_point + [np.cos(angle), np.sin(angle), 0.3 * (-1) ** k]
    positions = minimum_image(positions)
    term = {"type": ["Set1", "ConstantTorqueOverCenterOfMass"], "labels": ["idSet_i", "torque"],
            "data": [[ring, list(T)]]}
    with load(document(positions, {"term": term}), options) as sim:
        forces = sim.forces
    c, unwrapped = centre(positions, ring)
    np.testing.assert_allclose(minimum_image(c - axis_point), 0.0, atol=1e-12)  # the ring straddles x = L/2
    np.testing.assert_allclose(np.cross(unwrapped - c, forces[ring]).sum(axis=0), T, rtol=0, atol=1e-12)
    np.testing.assert_allclose(forces.sum(axis=0), 0.0, atol=1e-12)


def test_torques_between_sets_twist_them_oppositely_about_their_axis(options):
    positions = configuration(seed=4)
    (first, second) = SETS2[1]
    term = {"type": ["Set2", "ConstantTorqueBetweenCentersOfMass"], "labels": ["idSet_i", "idSet_j", "torque"],
            "data": [[first, second, 1.7]]}
    with load(document(positions, {"term": term}), options) as sim:
        forces = sim.forces
    axis = minimum_image(centre(positions, second)[0] - centre(positions, first)[0])
    axis /= np.linalg.norm(axis)
    for ids, sign in ((first, 1.0), (second, -1.0)):
        expected, d = torque_forces(positions, ids, sign * 1.7 * axis)
        np.testing.assert_allclose(forces[ids], expected, rtol=0, atol=1e-12)
        np.testing.assert_allclose(forces[ids].sum(axis=0), 0.0, atol=1e-12)
        assert np.cross(d, forces[ids]).sum(axis=0) @ axis == pytest.approx(sign * 1.7, rel=1e-12)


def test_torques_have_no_analytical_hessian_and_the_numerical_mode_measures_them(options, tmp_path):
    term = {"type": ["Set1", "ConstantTorqueOverCenterOfMass"], "labels": ["idSet_i", "torque"],
            "data": [[SETS1[2], [0.0, 0.0, 1.0]]]}
    doc = document(configuration(seed=0), {"term": term})
    doc["simulationStep"] = {"hessian": hessian_step(tmp_path / "h.dat", "Analytical")}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.UnsupportedError, match=r"simulationStep\.hessian\.parameters\.mode.*'term'"):
            sim.load(doc)
        doc["simulationStep"]["hessian"]["parameters"]["mode"] = "Numerical"
        sim.load(doc)
        sim.step(1)
    assert "# step 0" in (tmp_path / "h.dat").read_text()


@pytest.mark.parametrize("cells, path, message", [
    ([[0, 1, 99], [3, 4]], r"term\.data\[0\]\[0\]\[2\]", "particle id 99 does not exist"),
    ([[], [3, 4]], r"term\.data\[0\]\[0\]", "non-empty list"),
    ([[0, 1, 2], [2, 3]], r"term\.data\[0\]\[1\]\[0\]", "already in a set"),
    ([5, [3, 4]], r"term\.data\[0\]\[0\]", "non-empty list of particle ids"),
])
def test_bad_sets_are_input_errors_naming_the_cell(options, cells, path, message):
    term = {"type": ["Set2", "HarmonicBondBetweenCentersOfMass"], "labels": ["idSet_i", "idSet_j", "K", "r0"],
            "data": [cells + [1.0, 1.0]]}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=path + ".*" + message):
            sim.load(document(configuration(seed=0), {"term": term}))


def test_a_negative_r0_and_a_missing_column_are_input_errors(options):
    term = {"type": ["Set1", "FixedHarmonicAnisotropicCommon_K_r0CenterOfMass"], "labels": ["idSet_i", "position"],
            "parameters": {"K": 1.0, "r0": -1.0}, "data": [[[0, 1], [0.0, 0.0, 0.0]]]}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"term\.parameters\.r0"):
            sim.load(document(configuration(seed=0), {"term": term}))
        term["parameters"]["r0"] = 0.5
        term["labels"] = ["idSet_i"]
        term["data"] = [[[0, 1]]]
        with pytest.raises(structmd.InputError, match=r"term.*position"):
            sim.load(document(configuration(seed=0), {"term": term}))


def test_distance_between_centres_of_mass_matches_numpy_on_the_same_frames(options, tmp_path):
    positions = configuration(seed=3)
    doc = document(positions, CASES["Set2 HarmonicBondBetweenCentersOfMass"])
    doc["simulationStep"] = {"dist": {"type": ["GeometricalMeasure", "DistanceBetweenCentersOfMass"],
                                      "parameters": {"intervalStep": 10, "outputFilePath": str(tmp_path / "d.dat")},
                                      "labels": ["idSet_i", "idSet_j"], "data": SETS2}}
    frames = []
    with load(doc, options) as sim:
        frames.append(sim.positions)
        sim.step(10)
        frames.append(sim.positions)
        sim.step(1)
    lines = (tmp_path / "d.dat").read_text().splitlines()
    assert lines[0].split() == ["#step", "time", "distance_0", "distance_1"]
    rows = [np.array([float(x) for x in line.split()]) for line in lines[1:]]
    assert [int(r[0]) for r in rows] == [0, 10]
    for row, frame in zip(rows, frames):
        expected = [np.linalg.norm(minimum_image(centre(frame, a)[0] - centre(frame, b)[0])) for a, b in SETS2]
        np.testing.assert_allclose(row[2:], expected, rtol=1e-12)
    assert not np.allclose(rows[0][2:], rows[1][2:])  # the frames differ


def test_distance_measure_refuses_an_unknown_particle(options, tmp_path):
    doc = document(configuration(seed=0), CASES["Set2 HarmonicBondBetweenCentersOfMass"])
    doc["simulationStep"] = {"dist": {"type": ["GeometricalMeasure", "DistanceBetweenCentersOfMass"],
                                      "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "d.dat")},
                                      "labels": ["idSet_i", "idSet_j"], "data": [[[0, 1], [2, 40]]]}}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"simulationStep\.dist\.data\[0\]\[1\]\[1\].*40"):
            sim.load(doc)
