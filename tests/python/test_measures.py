"""The simulation steps that measure and report: ["GeometricalMeasure","MeanSquareDisplacement"],
["GeometricalMeasure","GyrationRadius"], ["MechanicalMeasure","StressMeasure"], ["UtilsStep","InfoStep"]
and the columns of ["ThermodynamicMeasure","ThermodynamicQuantityMeasure"]. Each file the engine writes
is read back and compared with the quantity computed here from the particles' positions, forces or
the API's getters, so a wrong formula, a lost box crossing or a column out of place fails."""

import math
import re

import numpy as np
import pytest

import structmd

BOX = 10.0
KB_KCAL_MOL = 1.987191e-3  # k_B of ["Units","KcalMol_A"], as docs/input-format.md gives it


def document(positions, velocities=None, types=None, force_field=None, steps=10, time_step=0.01, box=BOX,
             simulation_steps=None, units=None, current_step=None):
    n = len(positions)
    velocities = velocities if velocities is not None else [[0.0, 0.0, 0.0]] * n
    types = types or ["A"] * n
    fundamental = {"timeStep": time_step}
    if current_step is not None:
        fundamental["currentStep"] = current_step
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "measures"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0], ["B", 2.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
            "fundamental": {"type": ["Fundamental", "Time"], "parameters": fundamental},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"]},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(map(float, p)), list(map(float, v))]
                           for i, (p, v) in enumerate(zip(positions, velocities))]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": force_field or {}},
        "simulationStep": simulation_steps or {},
    }
    if units:
        doc["global"]["units"] = {"type": ["Units", units]}
    return doc


def measure(cls, subclass, interval=1, **parameters):
    return {"type": [cls, subclass], "parameters": {"intervalStep": interval, **parameters}}


def lj_entry(cutoff_factor=2.5, **extra):
    return {"type": ["NonBonded", "LennardJonesType1"],
            "parameters": {"cutOffFactor": cutoff_factor, "condition": "all", **extra},
            "labels": ["name_i", "name_j", "epsilon", "sigma"],
            "data": [["A", "A", 1.0, 1.0], ["A", "B", 1.5, 1.1], ["B", "B", 0.8, 1.0]]}


NEIGHBOUR_LIST = {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}}


def read_rows(path):
    """The numeric rows of a measure file (comment lines dropped)."""
    return np.array([[float(x) for x in line.split()] for line in path.read_text().splitlines()
                     if line and not line.startswith("#")])


def read_stress_blocks(path):
    """{step: array of rows `id volume sxx ... szz`} of a stress file."""
    blocks = {}
    current = None
    lines = path.read_text().splitlines()
    assert lines[0].split() == ["#id", "volume", "sxx", "sxy", "sxz", "syx", "syy", "syz", "szx", "szy", "szz"]
    for line in lines[1:]:
        if line.startswith("#step"):
            current = int(line.split()[1])
            blocks[current] = []
        else:
            blocks[current].append([float(x) for x in line.split()])
    return {step: np.array(rows) for step, rows in blocks.items()}


def minimum_image(d, box=BOX):
    return d - box * np.round(d / box)


@pytest.fixture
def sim(options):
    with structmd.Simulation(options) as s:
        yield s


# ---- mean square displacement --------------------------------------------------------------------

def test_msd_of_free_particles_is_ballistic_across_the_boundary(sim, tmp_path):
    rng = np.random.default_rng(11)
    positions = rng.uniform(-BOX / 2, BOX / 2, size=(6, 3))
    velocities = rng.uniform(-5.0, 5.0, size=(6, 3))
    output = tmp_path / "msd.dat"
    dt, steps = 0.01, 300
    sim.load(document(positions, velocities, steps=steps, time_step=dt, simulation_steps={
        "msd": measure("GeometricalMeasure", "MeanSquareDisplacement", interval=20, outputFilePath=str(output))}))
    sim.run()
    assert output.read_text().splitlines()[0] == "#step time msd"
    rows = read_rows(output)
    np.testing.assert_array_equal(rows[:, 0], np.arange(0, steps + 1, 20))
    t = rows[:, 0] * dt
    np.testing.assert_allclose(rows[:, 1], t, rtol=1e-12, atol=1e-12)
    expected = np.mean(np.sum(velocities ** 2, axis=1)) * t ** 2
    np.testing.assert_allclose(rows[:, 2], expected, rtol=1e-9, atol=1e-12)
    # The fastest particle travels more than a box length: only image tracking gives the MSD above.
    assert np.max(np.abs(velocities)) * steps * dt > BOX


def test_msd_of_a_group_averages_over_its_members(sim, tmp_path):
    velocities = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 4.0], [8.0, 0.0, 0.0]]
    positions = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [-2.0, 0.0, 1.0], [3.0, -3.0, 0.0]]
    output = tmp_path / "msd.dat"
    doc = document(positions, velocities, steps=10, time_step=0.1, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["pair", "Ids", [1, 2]]]}}, simulation_steps={
        "msd": measure("GeometricalMeasure", "MeanSquareDisplacement", interval=5, outputFilePath=str(output),
                       group="pair")})
    sim.load(doc)
    sim.run()
    rows = read_rows(output)
    t = rows[:, 1]
    np.testing.assert_allclose(rows[:, 2], (2.0 ** 2 + 4.0 ** 2) / 2 * t ** 2, rtol=1e-9)


def test_msd_is_relative_to_its_first_firing(sim, tmp_path):
    output = tmp_path / "msd.dat"
    sim.load(document([[0.0, 0.0, 0.0]], [[1.0, 0.0, 0.0]], steps=20, time_step=0.1, simulation_steps={
        "msd": measure("GeometricalMeasure", "MeanSquareDisplacement", interval=5, startStep=10,
                       outputFilePath=str(output))}))
    sim.run()
    rows = read_rows(output)
    np.testing.assert_array_equal(rows[:, 0], [10, 15, 20])
    np.testing.assert_allclose(rows[:, 2], [0.0, 0.25, 1.0], rtol=1e-9, atol=1e-12)


# ---- gyration radius -----------------------------------------------------------------------------

def gyration_radius(positions):
    positions = np.asarray(positions)
    return math.sqrt(np.mean(np.sum((positions - positions.mean(axis=0)) ** 2, axis=1)))


def gyration_file_after_setting(sim, tmp_path, positions, **parameters):
    output = tmp_path / "rg.dat"
    sim.load(document(np.zeros((len(positions), 3)) + [[0.1 * i, 0.0, 0.0] for i in range(len(positions))],
                      steps=1, simulation_steps={
                          "rg": measure("GeometricalMeasure", "GyrationRadius", outputFilePath=str(output),
                                        **parameters)}))
    sim.positions = positions
    sim.step(1)
    assert output.read_text().splitlines()[0] == "#step time Rg"
    return read_rows(output)


def test_gyration_radius_of_a_known_configuration(sim, tmp_path):
    rng = np.random.default_rng(3)
    positions = rng.uniform(-3.0, 3.0, size=(7, 3))
    rows = gyration_file_after_setting(sim, tmp_path, positions)
    assert rows[0, 0] == 0
    assert rows[0, 2] == pytest.approx(gyration_radius(positions), rel=1e-12)
    # The particles stay put (no forces, no velocities): the final firing gives the same value.
    assert rows[-1, 2] == pytest.approx(rows[0, 2], rel=1e-12)


def test_gyration_radius_of_a_chain_split_across_the_boundary_uses_unwrapped_positions(sim, tmp_path):
    # A straight chain from x = 3.5 to 6.5 in a box spanning [-5, 5): half of it wraps to the far side.
    positions = np.array([[3.5 + 0.5 * k, 0.2 * k, 0.0] for k in range(7)])
    rows = gyration_file_after_setting(sim, tmp_path, positions)
    expected = gyration_radius(positions)
    assert rows[0, 2] == pytest.approx(expected, rel=1e-12)
    wrapped = minimum_image(positions)
    assert gyration_radius(wrapped) > 3 * expected  # what ignoring the images would give


def test_gyration_radius_of_a_group(sim, tmp_path):
    positions = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0], [4.0, 4.0, 4.0]])
    output = tmp_path / "rg.dat"
    sim.load(document(positions, types=["A", "B", "B", "A"], steps=1, force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["bees", "Types", ["B"]]]}}, simulation_steps={
        "rg": measure("GeometricalMeasure", "GyrationRadius", outputFilePath=str(output), group="bees")}))
    sim.run()
    assert read_rows(output)[0, 2] == pytest.approx(gyration_radius(positions[1:3]), rel=1e-12)


# ---- centre of mass and mean radius --------------------------------------------------------------

def test_centre_of_mass_and_mean_radius_of_a_group_split_by_the_boundary(sim, tmp_path):
    """Types A (mass 1) and B (mass 2); the group of B particles straddles the x faces of the box
    ([-5, 5)): the centre is mass-weighted over its unwrapped positions, numpy gives both."""
    positions = np.array([[4.2, 0.0, 0.0], [5.3, 0.5, 0.0], [5.9, -0.4, 0.3], [0.0, 1.0, 1.0], [4.6, 1.0, -1.0]])
    types = ["B", "B", "A", "A", "B"]
    masses = np.array([2.0 if t == "B" else 1.0 for t in types])
    members = np.array([t == "B" for t in types])
    files = {"com": tmp_path / "com.dat", "radius": tmp_path / "radius.dat"}
    doc = document(np.zeros((5, 3)) + [[0.5 * i - 1.0, 0.0, 0.0] for i in range(5)], types=types, steps=1,
                   force_field={"groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                           "data": [["bees", "Types", ["B"]]]}},
                   simulation_steps={
                       "com": measure("GeometricalMeasure", "CenterOfMassPosition", outputFilePath=str(files["com"]),
                                      group="bees"),
                       "radius": measure("GeometricalMeasure", "MeanRadius", outputFilePath=str(files["radius"]),
                                         group="bees")})
    sim.load(doc)
    sim.positions = positions
    sim.step(1)
    chosen, weights = positions[members], masses[members]
    centre = np.sum(weights[:, None] * chosen, axis=0) / weights.sum()
    radius = np.mean(np.linalg.norm(chosen - centre, axis=1))
    assert files["com"].read_text().splitlines()[0] == "#step time X Y Z"
    assert files["radius"].read_text().splitlines()[0] == "#step time Rmean"
    com_rows, radius_rows = read_rows(files["com"]), read_rows(files["radius"])
    np.testing.assert_allclose(com_rows[0, 2:5], centre, rtol=1e-12)
    assert radius_rows[0, 2] == pytest.approx(radius, rel=1e-12)
    assert centre[0] > BOX / 2 - 0.5, "the unwrapped centre lies past the face, where the group is"


# ---- energies of listed interaction entries ------------------------------------------------------

def test_interactors_list_energy_measure_writes_each_listed_entry_as_the_api_gives_it(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.1, 1.2, 0.2], [1.2, 1.1, 0.9]]
    bonds = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 20.0, "r0": 1.0},
             "labels": ["id_i", "id_j"], "data": [[0, 1], [2, 3]]}
    listed, every = tmp_path / "listed.dat", tmp_path / "every.dat"
    sim.load(document(positions, rng_velocities(len(positions)), steps=4, time_step=0.002,
                      force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry(), "bonds": bonds},
                      simulation_steps={
                          "listed": measure("ThermodynamicMeasure", "InteractorsListEnergyMeasure", interval=2,
                                            outputFilePath=str(listed), interactorsList=["bonds"]),
                          "every": measure("ThermodynamicMeasure", "InteractorsListEnergyMeasure", interval=2,
                                           outputFilePath=str(every))}))
    expected = []
    for _ in range(3):
        expected.append([sim.step_number, sim.time, sim.energy("lj"), sim.energy("bonds")])
        if sim.step_number < 4:
            sim.step(2)
    expected = np.array(expected)
    assert listed.read_text().splitlines()[0] == "#step time bonds"
    assert every.read_text().splitlines()[0] == "#step time lj bonds"
    np.testing.assert_allclose(read_rows(listed), expected[:, [0, 1, 3]], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(read_rows(every), expected, rtol=1e-12, atol=1e-14)


def rng_velocities(n):
    return np.random.default_rng(8).normal(0.0, 0.5, size=(n, 3))


def test_an_unknown_interactor_names_the_list(sim, tmp_path):
    entry = measure("ThermodynamicMeasure", "InteractorsListEnergyMeasure", outputFilePath=str(tmp_path / "e.dat"),
                    interactorsList=["lj", "nl"])
    with pytest.raises(structmd.InputError,
                       match=r"simulationStep\.e\.parameters\.interactorsList: no interaction entry named 'nl'"):
        sim.load(document([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]], force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()},
                          simulation_steps={"e": entry}))


# ---- distances, angles and dihedrals of listed particles ------------------------------------------

def dihedral(r0, r1, r2, r3):
    """IUPAC dihedral of r0-r1-r2-r3 (0 cis, pi trans), written here from the definition."""
    b1, b2, b3 = r1 - r0, r2 - r1, r3 - r2
    m, n = np.cross(b1, b2), np.cross(b2, b3)
    return math.atan2(np.linalg.norm(b2) * np.dot(b1, n), np.dot(m, n))


def test_distances_angles_and_dihedrals_of_listed_particles_across_the_boundary(sim, tmp_path):
    """A chain that leaves the box through its +x face: every value uses minimum images, and the
    numbers match numpy on the unwrapped chain, row by row."""
    chain = np.array([[4.0, 0.0, 0.0], [4.9, 0.6, 0.1], [5.6, 0.2, 0.9], [6.3, 1.0, 1.2], [-3.0, -2.0, 0.5]])
    rows = {"distances": ("DistancesMeasure", ["id_i", "id_j"], [[0, 1], [1, 3], [0, 4]]),
            "angles": ("AnglesMeasure", ["id_i", "id_j", "id_k"], [[0, 1, 2], [1, 2, 3]]),
            "dihedrals": ("DihedralsMeasure", ["id_i", "id_j", "id_k", "id_l"], [[0, 1, 2, 3], [3, 2, 1, 0]])}
    steps = {}
    for name, (subclass, labels, data) in rows.items():
        entry = measure("ParticlesListMeasure", subclass, outputFilePath=str(tmp_path / f"{name}.dat"))
        entry.update(labels=labels, data=data)
        steps[name] = entry
    sim.load(document(np.zeros((5, 3)) + [[0.5 * i - 1.0, 0.0, 0.0] for i in range(5)], steps=1,
                      simulation_steps=steps))
    sim.positions = chain
    sim.step(1)
    minimum = lambda d: d - BOX * np.round(d / BOX)
    expected = {
        "distances": [np.linalg.norm(minimum(chain[j] - chain[i])) for i, j in rows["distances"][2]],
        "angles": [math.acos(np.dot(chain[i] - chain[j], chain[k] - chain[j]) /
                             (np.linalg.norm(chain[i] - chain[j]) * np.linalg.norm(chain[k] - chain[j])))
                   for i, j, k in rows["angles"][2]],
        "dihedrals": [dihedral(*chain[list(ids)]) for ids in rows["dihedrals"][2]],
    }
    for name, values in expected.items():
        path = tmp_path / f"{name}.dat"
        header = path.read_text().splitlines()[0]
        assert header.startswith("#step time ") and len(header.split()) == 2 + len(values)
        written = read_rows(path)
        np.testing.assert_allclose(written[0, 2:], values, rtol=1e-10, atol=1e-12)
    assert expected["distances"][2] < 8.0 and abs(expected["dihedrals"][0]) > 0.1


def test_contacts_measure_writes_a_block_of_pair_distances_per_firing(sim, tmp_path):
    """UAMMD-structured's layout: `# step N time T`, then `id_i id_j r` per row, by minimum image."""
    chain = np.array([[4.0, 0.0, 0.0], [4.9, 0.6, 0.1], [-4.6, 0.2, 0.9], [1.0, 1.0, 1.2]])
    pairs = [[0, 2], [1, 3], [2, 1]]
    entry = measure("ParticlesListMeasure", "ContactsMeasure", interval=2, outputFilePath=str(tmp_path / "c.dat"))
    entry.update(labels=["id_i", "id_j"], data=pairs)
    sim.load(document(chain, steps=4, simulation_steps={"contacts": entry}))
    sim.step(4)
    lines = (tmp_path / "c.dat").read_text().splitlines()
    assert lines[0] == "# Id_i Id_j distance"
    firings = [k for k, line in enumerate(lines) if line.startswith("# step ")]
    assert [int(lines[k].split()[2]) for k in firings] == [0, 2, 4]
    first = np.array([[float(x) for x in line.split()] for line in lines[firings[0] + 1:firings[1]]])
    np.testing.assert_array_equal(first[:, :2], pairs)
    expected = [np.linalg.norm(minimum_image(chain[j] - chain[i])) for i, j in pairs]
    np.testing.assert_allclose(first[:, 2], expected, rtol=1e-12)
    assert expected[0] < 2.0  # across the boundary


def test_height_averages_the_highest_particles_of_the_group_over_unwrapped_positions(sim, tmp_path):
    positions = np.array([[0.0, 0.0, 4.8], [1.0, 0.0, 2.0], [2.0, 0.0, -3.0], [3.0, 0.0, 1.0], [0.0, 2.0, 4.5]])
    velocities = [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    groups = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
              "data": [["notLast", "Ids", [0, 1, 2, 3]]]}
    steps = {"groups": groups,
             "top2": measure("GeometricalMeasure", "Height", interval=10, particleNumberAverage=2,
                             outputFilePath=str(tmp_path / "top2.dat"), group="notLast"),
             "top": measure("GeometricalMeasure", "Height", interval=10, outputFilePath=str(tmp_path / "top.dat"))}
    sim.load(document(positions, velocities=velocities, steps=50, time_step=0.01, simulation_steps=steps))
    sim.step(50)  # particle 0 rises by 0.5 and crosses the top face (z = 5)
    top2, top = read_rows(tmp_path / "top2.dat"), read_rows(tmp_path / "top.dat")
    z0 = 4.8 + 0.01 * top2[:, 0]
    np.testing.assert_allclose(top2[:, 2], (z0 + 2.0) / 2.0, rtol=1e-12)
    np.testing.assert_allclose(top[:, 2], np.maximum(z0, 4.5), rtol=1e-12)
    assert top2[-1, 2] > 3.6  # 5.3 unwrapped, not -4.7


def test_height_of_more_particles_than_the_group_holds_names_the_parameter(sim, tmp_path):
    steps = {"h": measure("GeometricalMeasure", "Height", particleNumberAverage=6, outputFilePath=str(tmp_path / "h"))}
    with pytest.raises(structmd.InputError, match=r"simulationStep\.h\.parameters\.particleNumberAverage: "
                                                  r"expected at most the 5 particles measured, got 6"):
        sim.load(document(np.zeros((5, 3)) + np.arange(5)[:, None], simulation_steps=steps))


def test_sort_step_loads_and_leaves_the_trajectory_alone(options):
    positions = np.array([[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.0, 1.2, 0.0], [1.0, 1.0, 1.0]])
    force_field = {"nl": NEIGHBOUR_LIST, "lj": lj_entry()}
    runs = []
    for steps in ({}, {"sort": measure("UtilsStep", "SortStep", interval=3)}):
        with structmd.Simulation(options) as sim:
            sim.load(document(positions, force_field=force_field, steps=20, time_step=0.002, simulation_steps=steps))
            sim.step(20)
            runs.append(sim.positions)
    np.testing.assert_array_equal(runs[0], runs[1])
    assert not np.array_equal(runs[0], positions)


def test_potential_measure_splits_energy_and_force_by_entry_for_listed_particles(sim, tmp_path):
    """A Lennard-Jones liquid with a harmonic bond: per listed particle, each entry's energy and force
    (with its magnitude) against the LJ and harmonic formulas written here; torques are zero."""
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.4, 1.0, 0.2], [4.7, -0.3, 0.1], [-4.8, 0.2, -0.4]]
    force_field = {"nl": NEIGHBOUR_LIST, "lj": lj_entry(),
                   "spring": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"],
                              "data": [[0, 2, 30.0, 1.2]]}}
    entry = measure("ParticlesListMeasure", "PotentialMeasure", outputFilePath=str(tmp_path / "p.dat"))
    entry.update(labels=["id"], data=[[3], [0], [2]])
    sim.load(document(positions, force_field=force_field, steps=1, simulation_steps={"potential": entry}))
    sim.step(1)
    lines = (tmp_path / "p.dat").read_text().splitlines()
    columns = ["Energy", "ForceX", "ForceY", "ForceZ", "ForceMod", "TorqueX", "TorqueY", "TorqueZ", "TorqueMod"]
    assert lines[0].split() == ["#", "id"] + [t + c for t in ("lj", "spring") for c in columns]
    assert lines[1] == "# 0"
    rows = {int(line.split()[0]): np.array([float(x) for x in line.split()[1:]]) for line in lines[2:5]}
    assert sorted(rows) == [0, 2, 3]
    p = np.array(positions)
    for i, values in rows.items():
        lj_energy, lj_force = 0.0, np.zeros(3)
        for j in range(len(p)):
            d = minimum_image(p[i] - p[j])
            r = np.linalg.norm(d)
            if j == i or r >= 2.5:
                continue
            lj_energy += 0.5 * 4 * (r ** -12 - r ** -6)  # half of each pair's energy
            lj_force += -4 * (-12 * r ** -13 + 6 * r ** -7) * d / r
        spring_energy, spring_force = 0.0, np.zeros(3)
        if i in (0, 2):
            d = minimum_image(p[i] - p[2 - i])
            r = np.linalg.norm(d)
            spring_energy = 0.5 * 0.5 * 30.0 * (r - 1.2) ** 2
            spring_force = -30.0 * (r - 1.2) * d / r
        for offset, energy, force in ((0, lj_energy, lj_force), (9, spring_energy, spring_force)):
            block = values[offset:offset + 9]
            np.testing.assert_allclose(block[:4], [energy, *force], rtol=1e-10, atol=1e-12)
            assert block[4] == pytest.approx(np.linalg.norm(force), rel=1e-10, abs=1e-12)
            assert np.all(block[5:] == 0.0)
    assert np.linalg.norm(rows[3][1:4]) > 0.1 and rows[3][9] == 0.0


def test_a_listed_id_that_does_not_exist_names_its_cell(sim, tmp_path):
    entry = measure("ParticlesListMeasure", "AnglesMeasure", outputFilePath=str(tmp_path / "a.dat"))
    entry.update(labels=["id_i", "id_j", "id_k"], data=[[0, 1, 2], [0, 1, 9]])
    with pytest.raises(structmd.InputError, match=r"simulationStep\.angles\.data\[1\]\[2\].*particle id 9"):
        sim.load(document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], simulation_steps={"angles": entry}))


# ---- stress --------------------------------------------------------------------------------------

def lj_derivative(r, epsilon=1.0, sigma=1.0):
    """dU/dr of U = 4 eps ((s/r)^12 - (s/r)^6)."""
    return 4.0 * epsilon * (-12.0 * sigma ** 12 / r ** 13 + 6.0 * sigma ** 6 / r ** 7)


def neighbour_volumes(positions, radius_cutoff, box=BOX):
    """The volume estimate docs/input-format.md gives, by brute force over all pairs."""
    positions = np.asarray(positions)
    volumes = np.zeros(len(positions))
    for i in range(len(positions)):
        r = np.linalg.norm(minimum_image(np.delete(positions, i, axis=0) - positions[i], box), axis=1)
        r = r[r < radius_cutoff]
        if len(r):
            radius = 0.5 * np.sum(1.0 / r) / np.sum(1.0 / r ** 2)
            volumes[i] = 4.0 / 3.0 * math.pi * radius ** 3
    return volumes


def stress_blocks(sim, tmp_path, positions, radius_cutoff=3.0, force_field=None, types=None, box=BOX,
                  **parameters):
    """The stress file of one step from the positions: blocks 0 (those positions) and 1 (the handle's
    state when this returns)."""
    output = tmp_path / "stress.dat"
    sim.load(document(positions, types=types, steps=1, force_field=force_field, box=box, simulation_steps={
        "stress": measure("MechanicalMeasure", "StressMeasure", outputFilePath=str(output),
                          radiusCutOff=radius_cutoff, **parameters)}))
    sim.step(1)
    return read_stress_blocks(output)


def test_stress_of_a_lennard_jones_pair_follows_the_formula(sim, tmp_path):
    r = 1.05
    direction = np.array([1.0, 2.0, 2.0]) / 3.0
    # The pair straddles the boundary: the minimum image is what counts.
    positions = [[4.8, 0.0, 0.0], (np.array([4.8, 0.0, 0.0]) + r * direction - [BOX, 0.0, 0.0]).tolist()]
    blocks = stress_blocks(sim, tmp_path, positions,
                           force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()})
    rows = blocks[0]
    np.testing.assert_array_equal(rows[:, 0], [0, 1])
    volume = 4.0 / 3.0 * math.pi * (r / 2) ** 3  # one neighbour at r: R = r/2
    np.testing.assert_allclose(rows[:, 1], volume, rtol=1e-9)
    # S_i = 1/2 (r_i - r_j) (x) F_ij with F_ij = U'(r) (r_j - r_i)/r, the same for both particles.
    r_ij = r * direction
    virial = -0.5 * lj_derivative(r) / r * np.outer(r_ij, r_ij)
    for row in rows:
        np.testing.assert_allclose(row[2:].reshape(3, 3), virial / volume, rtol=1e-9, atol=1e-9)
    assert virial[0, 0] > 0  # repulsive at r < 2^(1/6): positive, like a pressure


def test_stress_times_volume_sums_to_the_pair_virial(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.0, 1.2, 0.1], [1.0, 1.1, 0.9], [-1.0, 0.2, 0.5],
                 [4.6, 0.1, 0.0], [-4.5, 1.0, -0.8]]
    types = ["A", "B", "A", "B", "A", "A", "B"]
    rows = stress_blocks(sim, tmp_path, positions, types=types, radius_cutoff=2.9,
                         force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()})[1]
    summed = np.sum(rows[:, 1, None] * rows[:, 2:], axis=0).reshape(3, 3)
    w = sim.virial
    np.testing.assert_allclose(summed, w, rtol=1e-8, atol=1e-8 * np.max(np.abs(w)))


def test_stress_leaves_out_bonds(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.1, 0.3, 0.0], [0.2, 1.2, 0.4], [3.0, 3.0, 3.0]]
    k, r0 = 50.0, 1.5
    bonds = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": k, "r0": r0},
             "labels": ["id_i", "id_j"], "data": [[0, 1], [1, 2]]}
    rows = stress_blocks(sim, tmp_path, positions, radius_cutoff=2.9,
                         force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry(), "bonds": bonds})[1]
    p = np.asarray(sim.positions)
    bond_virial = np.zeros((3, 3))
    for i, j in [(0, 1), (1, 2)]:
        d = minimum_image(p[i] - p[j])
        r = np.linalg.norm(d)
        force_on_i = -k * (r - r0) * d / r
        bond_virial += np.outer(d, force_on_i)
    summed = np.sum(rows[:, 1, None] * rows[:, 2:], axis=0).reshape(3, 3)
    w = sim.virial
    np.testing.assert_allclose(summed, w - bond_virial, rtol=1e-8, atol=1e-8 * np.max(np.abs(w)))
    assert np.max(np.abs(bond_virial)) > 1.0  # the bonds are stretched: leaving them in would show


def test_stress_volumes_match_a_brute_force_search(sim, tmp_path):
    # Many particles, no forces: the volumes exercise the cell search (5 cells a side for 2.0, 2 for
    # 4.0, where the cells on either side are the same cell) against all pairs.
    rng = np.random.default_rng(5)
    positions = rng.uniform(-BOX / 2, BOX / 2, size=(150, 3))
    for radius_cutoff in (2.0, 4.0):
        rows = stress_blocks(sim, tmp_path, positions, radius_cutoff=radius_cutoff)[0]
        np.testing.assert_allclose(rows[:, 1], neighbour_volumes(positions, radius_cutoff), rtol=1e-9)
        assert np.all(rows[:, 2:] == 0.0)


def test_stress_volumes_in_a_large_sparse_box(sim, tmp_path):
    # A cell per radiusCutOff would make 10^8 cells for a handful of particles.
    box = 500.0
    positions = [[0.0, 0.0, 0.0], [1.0, 0.5, 0.0], [0.3, 1.1, 0.2], [249.5, 0.0, 0.0], [-249.8, 0.5, 0.0],
                 [100.0, -100.0, 30.0]]
    rows = stress_blocks(sim, tmp_path, positions, radius_cutoff=1.2, box=box)[0]
    np.testing.assert_allclose(rows[:, 1], neighbour_volumes(positions, 1.2, box), rtol=1e-9)
    assert rows[3, 1] > 0.0 and rows[5, 1] == 0.0  # neighbours across the boundary; none at all


def test_a_particle_alone_within_the_radius_has_no_volume_and_no_stress(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.2, 0.0, 0.0], [4.0, 4.0, 4.0]]
    rows = stress_blocks(sim, tmp_path, positions, radius_cutoff=2.6,
                         force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()})[0]
    assert rows[2, 1] == 0.0 and np.all(rows[2, 2:] == 0.0)
    assert rows[0, 1] > 0.0 and rows[0, 2] != 0.0


def test_stress_of_a_group_writes_its_members_only(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.0, 1.2, 0.1], [1.0, 1.1, 0.9]]
    full = stress_blocks(sim, tmp_path, positions, force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()})[0]
    groups = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
              "data": [["some", "Ids", [1, 3]]]}
    part = stress_blocks(sim, tmp_path, positions, group="some",
                         force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry(), "groups": groups})[0]
    np.testing.assert_array_equal(part, full[[1, 3]])


def test_stress_writes_a_block_per_firing(sim, tmp_path):
    output = tmp_path / "stress.dat"
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0]]
    sim.load(document(positions, [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]], steps=10, time_step=0.001,
                      force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()}, simulation_steps={
                          "stress": measure("MechanicalMeasure", "StressMeasure", interval=4,
                                            outputFilePath=str(output), radiusCutOff=2.5)}))
    sim.run()
    blocks = read_stress_blocks(output)
    assert sorted(blocks) == [0, 4, 8, 10]
    assert all(block.shape == (2, 11) for block in blocks.values())


@pytest.mark.parametrize("radius, what", [(5.0, "not shorter than half the box"), (0.0, "positive"),
                                          (-1.0, "positive")])
def test_a_bad_radius_cutoff_names_its_path(sim, tmp_path, radius, what):
    doc = document([[0.0, 0.0, 0.0]], simulation_steps={
        "stress": measure("MechanicalMeasure", "StressMeasure", outputFilePath=str(tmp_path / "s.dat"),
                          radiusCutOff=radius)})
    with pytest.raises(structmd.InputError, match=r"simulationStep\.stress\.parameters\.radiusCutOff.*" + what):
        sim.load(doc)


# ---- info ----------------------------------------------------------------------------------------

def info_lines(options, tmp_path, doc, steps_per_call=None):
    log = tmp_path / "structmd.log"
    with structmd.Simulation({**options, "log": "info", "log_file": str(log)}) as s:
        s.load(doc)
        if steps_per_call:
            for _ in range(doc["integrator"]["schedule"]["data"][0][2] // steps_per_call):
                s.step(steps_per_call)
        else:
            s.run()
    pattern = re.compile(r"^structmd info: simulationStep\.info: step (\d+) of (\d+) \(([\d.]+) %\)(.*)$")
    found = []
    for line in log.read_text().splitlines():
        match = pattern.match(line)
        if match:
            found.append((int(match[1]), int(match[2]), float(match[3]), match[4]))
    return found


def test_info_lines_come_at_the_interval_with_progress_and_speed(options, tmp_path):
    doc = document([[0.0, 0.0, 0.0], [1.2, 0.0, 0.0]], steps=50, simulation_steps={
        "info": measure("UtilsStep", "InfoStep", interval=10)}, force_field={"nl": NEIGHBOUR_LIST,
                                                                             "lj": lj_entry()})
    lines = info_lines(options, tmp_path, doc, steps_per_call=5)
    assert [line[0] for line in lines] == [0, 10, 20, 30, 40, 50]
    assert all(line[1] == 50 for line in lines)
    assert [line[2] for line in lines] == pytest.approx([0.0, 20.0, 40.0, 60.0, 80.0, 100.0])
    assert lines[0][3] == ""  # no speed before a second firing
    for _, _, _, rest in lines[1:]:
        match = re.fullmatch(r", ([\d.e+-]+) steps/s, ETA (\d+):(\d\d):(\d\d)", rest)
        assert match, rest
        assert float(match[1]) > 0
    assert lines[-1][3].endswith("ETA 0:00:00")


def test_info_progress_counts_from_the_starting_step(options, tmp_path):
    doc = document([[0.0, 0.0, 0.0]], steps=40, current_step=100, simulation_steps={
        "info": measure("UtilsStep", "InfoStep", interval=20, startStep=120)})
    lines = info_lines(options, tmp_path, doc)
    assert [(line[0], line[1]) for line in lines] == [(120, 140), (140, 140)]
    assert [line[2] for line in lines] == pytest.approx([50.0, 100.0])


def test_info_is_silent_below_the_info_level(tmp_path, options):
    log = tmp_path / "structmd.log"
    with structmd.Simulation({**options, "log": "warning", "log_file": str(log)}) as s:
        s.load(document([[0.0, 0.0, 0.0]], steps=10, simulation_steps={
            "info": measure("UtilsStep", "InfoStep", interval=2)}))
        s.run()
    assert "simulationStep.info" not in log.read_text()


# ---- thermodynamic columns -----------------------------------------------------------------------

def test_thermodynamic_columns_match_the_api(sim, tmp_path):
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.1, 1.2, 0.2], [1.2, 1.1, 0.9], [4.5, 0.1, 0.3],
                 [-4.4, 0.4, -0.2]]
    rng = np.random.default_rng(2)
    velocities = rng.normal(0.0, 0.3, size=(len(positions), 3))
    bonds = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 20.0, "r0": 1.0},
             "labels": ["id_i", "id_j"], "data": [[0, 1], [4, 5]]}
    output = tmp_path / "thermo.dat"
    interval, steps = 5, 40
    # kcal/mol units, so that k_B is not 1 and the temperature column shows it.
    sim.load(document(positions, velocities, types=["A", "B", "A", "A", "B", "A"], steps=steps, time_step=0.002,
                      units="KcalMol_A", force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry(), "bonds": bonds},
                      simulation_steps={"thermo": measure("ThermodynamicMeasure", "ThermodynamicQuantityMeasure",
                                                          interval=interval, outputFilePath=str(output))}))
    n = len(positions)
    expected = []
    for _ in range(steps // interval + 1):
        kinetic = sim.energy("kinetic")
        w = sim.virial
        volume = float(np.prod(sim.box))
        expected.append([sim.step_number, n, volume, sim.energy("bonds"), sim.energy("lj"), kinetic,
                         sim.energy("potential"), sim.energy("total"), 2.0 * kinetic / (3.0 * n * KB_KCAL_MOL),
                         np.trace(w), (2.0 * kinetic + np.trace(w)) / (3.0 * volume), sim.energy("external")])
        if sim.step_number < steps:
            sim.step(interval)
    header = output.read_text().splitlines()[0].split()
    assert header == ["#step", "particles", "volume", "bonds", "lj", "kinetic", "potential", "total",
                      "temperature", "virial", "pressure", "external"]
    rows = read_rows(output)
    expected = np.array(expected)
    assert rows.shape == expected.shape
    np.testing.assert_allclose(rows, expected, rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(rows[:, 6], rows[:, 3] + rows[:, 4], rtol=1e-8)  # potential = sum of entries
    np.testing.assert_allclose(rows[-1, 10], sim.pressure, rtol=1e-8)


@pytest.mark.parametrize("mass", [0.0, 2.0])
def test_brownian_dynamics_has_no_kinetic_energy_in_the_thermodynamic_columns(sim, tmp_path, mass):
    """UAMMD-structured's Brownian inputs give types mass 0. Overdamped particles have no velocities:
    the columns say kinetic 0, the bath's temperature and P = (N k_B T + tr W / 3) / V, never NaN,
    from the first row on; a comment line says so, and another where a Verlet stage follows."""
    positions = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [0.1, 1.2, 0.2], [3.0, 1.1, 0.9]]
    n, bath = len(positions), 1.7
    doc = document(positions, types=["A"] * n, force_field={"nl": NEIGHBOUR_LIST, "lj": lj_entry()},
                   simulation_steps={"thermo": measure("ThermodynamicMeasure", "ThermodynamicQuantityMeasure",
                                                       outputFilePath=str(tmp_path / "thermo.dat"))})
    del doc["state"]["labels"][2]  # no velocities given: the engine draws them (or not)
    doc["state"]["data"] = [row[:2] for row in doc["state"]["data"]]
    doc["global"]["types"]["data"][0][1] = mass
    doc["global"]["types"]["data"][1][1] = 1.0
    doc["integrator"] = {
        "bd": {"type": ["Brownian", "EulerMaruyama"], "parameters": {"viscosity": 1.0, "temperature": bath}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "bd", 3]]}}
    if mass > 0:
        doc["integrator"]["vv"] = {"type": ["Verlet", "VelocityVerlet"]}
        doc["integrator"]["schedule"]["data"].append([2, "vv", 2])
    sim.load(doc)
    assert np.array_equal(sim.velocities, np.zeros((n, 3))), "overdamped particles start at rest"
    expected = []
    for step in range(4):
        trace = np.trace(sim.virial)
        expected.append([0.0, bath, trace, (n * bath + trace / 3.0) / BOX ** 3])
        assert sim.energy("kinetic") == 0.0
        if step < 3:
            sim.step(1)
    sim.run()
    lines = (tmp_path / "thermo.dat").read_text().splitlines()
    assert lines[1].startswith("# from step 0: overdamped")
    rows = read_rows(tmp_path / "thermo.dat")
    assert np.all(np.isfinite(rows))
    columns = [4, 7, 8, 9]  # kinetic, temperature, virial, pressure (after the one LJ entry, column 3)
    # A row describes the dynamics of the step that follows it: with a Verlet stage next, step 3's row
    # is inertial (the particles are at rest, so K = T = 0).
    overdamped_rows = 3 if mass > 0 else 4
    np.testing.assert_allclose(rows[:overdamped_rows][:, columns], np.array(expected[:overdamped_rows]), rtol=1e-8,
                               atol=1e-12)
    if mass > 0:
        assert "# from step 3: inertial dynamics: kinetic and temperature from the velocities" in lines
        np.testing.assert_allclose(rows[3, columns], [0.0, 0.0, expected[3][2], expected[3][2] / (3 * BOX ** 3)],
                                   rtol=1e-8, atol=1e-12)
        assert rows.shape[0] == 6 and rows[5, 4] > 0.0, "Verlet particles move: kinetic energy"


# ---- reading ---------------------------------------------------------------------------------------

def test_a_group_on_the_thermodynamic_measure_is_unsupported(sim, tmp_path):
    doc = document([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], force_field={
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["one", "Ids", [0]]]}}, simulation_steps={
        "thermo": measure("ThermodynamicMeasure", "ThermodynamicQuantityMeasure",
                          outputFilePath=str(tmp_path / "t.dat"), group="one")})
    with pytest.raises(structmd.UnsupportedError, match=r"simulationStep\.thermo\.parameters\.group"):
        sim.load(doc)


def test_an_unknown_group_names_its_path(sim, tmp_path):
    doc = document([[0.0, 0.0, 0.0]], simulation_steps={
        "msd": measure("GeometricalMeasure", "MeanSquareDisplacement", outputFilePath=str(tmp_path / "m.dat"),
                       group="nobody")})
    with pytest.raises(structmd.InputError, match=r"simulationStep\.msd\.parameters\.group.*'nobody'"):
        sim.load(doc)


def test_an_unknown_step_names_the_nearest_known_ones(sim):
    doc = document([[0.0, 0.0, 0.0]], simulation_steps={"x": measure("GeometricalMeasure", "GyrationRadiu")})
    with pytest.raises(structmd.InputError) as error:
        sim.load(doc)
    message = str(error.value)
    assert message.startswith("simulationStep.x.type: unknown simulation step")
    assert 'nearest known simulation steps: ["GeometricalMeasure", "GyrationRadius"]' in message
    assert "\n" not in message


@pytest.mark.parametrize("subclass, extra", [("MeanSquareDisplacement", {}), ("GyrationRadius", {}),
                                             ("StressMeasure", {"radiusCutOff": 2.0})])
def test_an_unwritable_output_is_an_io_error_at_the_first_firing(sim, tmp_path, subclass, extra):
    cls = "MechanicalMeasure" if subclass == "StressMeasure" else "GeometricalMeasure"
    folder = tmp_path / "removed"
    folder.mkdir()
    doc = document([[0.0, 0.0, 0.0]], simulation_steps={
        "m": measure(cls, subclass, outputFilePath=str(folder / "out.dat"), **extra)})
    sim.load(doc)  # the folder is there at load; the file is opened at the first firing
    folder.rmdir()
    with pytest.raises(structmd.StructmdIOError, match=r"simulationStep\.m: cannot open"):
        sim.step(1)
    with pytest.raises(structmd.StructmdIOError) as refused:  # and a new load refuses the folder gone
        sim.load(doc)
    assert str(refused.value).startswith("simulationStep.m.parameters.outputFilePath: the folder")


def test_a_misspelt_parameter_is_rejected(sim, tmp_path):
    doc = document([[0.0, 0.0, 0.0]], simulation_steps={
        "rg": measure("GeometricalMeasure", "GyrationRadius", outputFilePath=str(tmp_path / "r.dat"),
                      radiusCutOf=1.0)})
    with pytest.raises(structmd.InputError, match=r"simulationStep\.rg\.parameters\.radiusCutOf"):
        sim.load(doc)
