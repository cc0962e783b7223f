"""Steps that end a step call early: ["GeometricalMeasure","EscapeSphereTime"] and
["GeometricalMeasure","EscapePolygonTime"] (the escape steps written here from the particles' straight
flights, the region tested in numpy) and ["FlowControl","AFMMaxForce"] (the step where the cantilever
force first reaches maxForce, read from an AFMMeasure of the same trajectory). A stopped call returns
normally, structmd_get_info's stopped_by names the step, and the next call steps on."""

import numpy as np
import pytest

import structmd
from test_afm import configuration as afm_configuration
from test_afm import document as afm_document

BOX = 20.0
DT = 0.01


def free_flight(positions, velocities, steps, simulation_steps):
    """Particles without forces under velocity Verlet: r(s) = r0 + v s dt."""
    n = len(positions)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "escape"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": DT}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(map(float, positions[i])), list(map(float, velocities[i]))] for i in range(n)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
                     "forceField": {}},
        "simulationStep": simulation_steps,
    }


def first_step_outside(positions, velocities, inside, steps, interval=1):
    """For each particle, the first firing step at which `inside` is false, or None."""
    out = []
    for r0, v in zip(positions, velocities):
        found = None
        for s in range(0, steps + 1, interval):
            if not inside(np.asarray(r0) + np.asarray(v) * s * DT):
                found = s
                break
        out.append(found)
    return out


def read_escapes(path):
    lines = path.read_text().splitlines()
    assert lines[0] == "#step id"
    return {int(i): int(s) for s, i in (line.split() for line in lines[1:])}


# Five particles leaving the origin at different speeds; one starts outside, one never leaves.
POSITIONS = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, -1.0, 0.5], [0.0, 0.0, 4.5], [0.1, 0.1, 0.1]]
VELOCITIES = [[1.37, 0.0, 0.0], [0.0, 2.11, 0.0], [0.0, -0.83, 0.31], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
SPHERES = [([0.0, 0.0, 0.0], 3.0), ([1.0, 0.0, 0.0], 3.5)]


def inside_spheres(logical_sum):
    def inside(r):
        d = [np.linalg.norm(r - np.array(c)) for c, _ in SPHERES]
        if logical_sum == "all":
            return all(di <= radius for di, (_, radius) in zip(d, SPHERES))
        return any(di < radius for di, (_, radius) in zip(d, SPHERES))
    return inside


@pytest.mark.parametrize("logical_sum", ["all", "any"])
def test_escape_sphere_time_writes_each_particles_first_step_outside(options, tmp_path, logical_sum):
    steps, interval = 600, 7
    entry = {"type": ["GeometricalMeasure", "EscapeSphereTime"],
             "parameters": {"intervalStep": interval, "outputFilePath": str(tmp_path / "escape.dat"),
                            "logicalSum": logical_sum},
             "labels": ["center", "radius"], "data": [[c, r] for c, r in SPHERES]}
    with structmd.Simulation(options) as sim:
        sim.load(free_flight(POSITIONS, VELOCITIES, steps, {"escape": entry}))
        sim.run()
        assert sim.step_number == steps and sim.info["stopped_by"] is None
    expected = first_step_outside(POSITIONS, VELOCITIES, inside_spheres(logical_sum), steps, interval)
    assert read_escapes(tmp_path / "escape.dat") == {i: s for i, s in enumerate(expected) if s is not None}
    assert expected[3] == 0 and expected[4] is None, "one particle starts outside, one never leaves"


def test_escape_polygon_time_uses_half_spaces_whose_normals_point_inwards(options, tmp_path):
    steps = 500
    planes = [([0.0, 0.0, 1.0], [0.0, 0.0, -2.0]), ([0.0, 0.0, -1.0], [0.0, 0.0, 2.0]),
              ([1.0, 1.0, 0.0], [-2.5, 0.0, 0.0])]
    entry = {"type": ["GeometricalMeasure", "EscapePolygonTime"],
             "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "escape.dat")},
             "labels": ["normalVector", "independentVector"], "data": [[n, p] for n, p in planes]}
    velocities = [[-1.3, -0.2, 0.0], [0.0, 0.0, 0.9], [0.0, 0.3, -0.7], [0.0, 0.0, 0.0], [0.2, 0.2, 0.0]]
    with structmd.Simulation(options) as sim:
        sim.load(free_flight(POSITIONS, velocities, steps, {"escape": entry}))
        sim.run()

    def inside(r):
        return all(np.dot(n, r - np.array(p)) >= 0.0 for n, p in planes)
    expected = first_step_outside(POSITIONS, velocities, inside, steps)
    assert read_escapes(tmp_path / "escape.dat") == {i: s for i, s in enumerate(expected) if s is not None}
    assert sum(s is not None for s in expected) >= 3


# run(progress=True) steps in chunks: it too ends where the flow-control step ends the run.
@pytest.mark.parametrize("progress", [False, True])
def test_stop_simulation_ends_the_call_at_the_escape_that_completes_the_count_and_the_next_call_steps_on(
        options, tmp_path, progress):
    steps = 600
    entry = {"type": ["GeometricalMeasure", "EscapeSphereTime"],
             "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "escape.dat"),
                            "stopSimulation": "true", "particlesToEscape": 3},
             "labels": ["center", "radius"], "data": [[c, r] for c, r in SPHERES]}
    expected = first_step_outside(POSITIONS, VELOCITIES, inside_spheres("all"), steps)
    third = sorted(s for s in expected if s is not None)[2]
    with structmd.Simulation(options) as sim:
        sim.load(free_flight(POSITIONS, VELOCITIES, steps, {"escape": entry}))
        sim.run(progress=progress)
        assert sim.step_number == third and sim.info["stopped_by"] == "escape"
        np.testing.assert_allclose(sim.positions, np.array(POSITIONS) + np.array(VELOCITIES) * third * DT, atol=1e-12)
        sim.step(5)
        assert sim.step_number == third + 5 and sim.info["stopped_by"] is None
    assert sorted(read_escapes(tmp_path / "escape.dat").values())[:3] == sorted(s for s in expected if s is not None)[:3]


def test_afm_max_force_stops_where_the_measured_cantilever_force_first_reaches_it(options, tmp_path):
    steps, interval = 3000, 10
    positions = afm_configuration(3)
    measure = {"type": ["ExperimentMeasures", "AFMMeasure"],
               "parameters": {"intervalStep": interval, "outputFilePath": str(tmp_path / "afm.dat")}}
    traced = afm_document(positions, 0.8, steps=steps)
    traced["simulationStep"] = {"afm": measure}
    with structmd.Simulation(options) as sim:
        sim.load(traced)
        sim.run()
    rows = np.loadtxt(tmp_path / "afm.dat")
    force = rows[:, 3]
    max_force = 0.5 * (force.min() + force.max())
    first = int(rows[np.argmax(force >= max_force), 0])
    assert 0 < first < steps

    stopping = afm_document(positions, 0.8, steps=steps)
    stopping["simulationStep"] = {"stop": {"type": ["FlowControl", "AFMMaxForce"],
                                           "parameters": {"intervalStep": interval, "maxForce": max_force}}}
    with structmd.Simulation(options) as sim:
        sim.load(stopping)
        sim.run()
        assert sim.step_number == first and sim.info["stopped_by"] == "stop"
        sim.run()
        assert sim.step_number == steps, "the tip has reached the force: the next call runs to the end"


@pytest.mark.parametrize("entry, path, message", [
    ({"type": ["GeometricalMeasure", "EscapeSphereTime"],
      "parameters": {"intervalStep": 1, "outputFilePath": "e.dat", "stopSimulation": "yes"},
      "labels": ["center", "radius"], "data": [[[0, 0, 0], 1.0]]},
     "simulationStep.s.parameters.stopSimulation", '"true" or "false"'),
    ({"type": ["GeometricalMeasure", "EscapeSphereTime"],
      "parameters": {"intervalStep": 1, "outputFilePath": "e.dat", "logicalSum": "some"},
      "labels": ["center", "radius"], "data": [[[0, 0, 0], 1.0]]},
     "simulationStep.s.parameters.logicalSum", '"all" or "any"'),
    ({"type": ["GeometricalMeasure", "EscapeSphereTime"],
      "parameters": {"intervalStep": 1, "outputFilePath": "e.dat"},
      "labels": ["center", "radius"], "data": [[[0, 0, 0], -1.0]]},
     "simulationStep.s.data[0][1]", "positive radius"),
    ({"type": ["GeometricalMeasure", "EscapePolygonTime"],
      "parameters": {"intervalStep": 1, "outputFilePath": "e.dat", "particlesToEscape": 9},
      "labels": ["normalVector", "independentVector"], "data": [[[0, 0, 1], [0, 0, 0]]]},
     "simulationStep.s.parameters.particlesToEscape", "at most the 5 particles"),
    ({"type": ["GeometricalMeasure", "EscapePolygonTime"],
      "parameters": {"intervalStep": 1, "outputFilePath": "e.dat"},
      "labels": ["normalVector", "independentVector"], "data": [[[0, 1], [0, 0, 0]]]},
     "simulationStep.s.data[0][0]", "vector"),
    ({"type": ["FlowControl", "AFMMaxForce"], "parameters": {"intervalStep": 1, "maxForce": 1.0}},
     "simulationStep.s.type", "AFM"),
])
def test_bad_flow_control_entries_name_their_path(options, entry, path, message):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError) as error:
            sim.load(free_flight(POSITIONS, VELOCITIES, 10, {"s": entry}))
        assert path in str(error.value) and message in str(error.value)
        sim.load(free_flight(POSITIONS, VELOCITIES, 10, {}))
        sim.run()
