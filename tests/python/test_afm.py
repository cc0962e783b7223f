"""["AFM","SphericalTip"]: the tip-sample energy and the chip spring against the formulas written here
in numpy, force = -grad U by central differences across the periodic boundary, the chip's motion
(start, indentation, withdrawal) step by step, and the input errors."""

import numpy as np
import pytest

import structmd

BOX = 12.0
TIP_RADIUS = 1.5
DT = 0.002


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def configuration(seed):
    """A tip on the x = L/2 face and a sample of 7 particles 0.6..1.6 from its surface, some across the
    boundary, plus a bystander the term does not touch."""
    rng = np.random.default_rng(seed)
    tip = np.array([BOX / 2 - 0.2, 0.3, 0.5])
    positions = [tip]
    for _ in range(7):
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        positions.append(tip + (TIP_RADIUS + rng.uniform(0.6, 1.6)) * direction)
    positions.append([-1.0, -3.0, -3.0])
    return minimum_image(np.array(positions))


def document(positions, epsilon, chip=(5.8, 0.0, 3.0), velocity=-0.5, start=0, backward=None, steps=10):
    labels = ["idSet_i", "idSet_j", "epsilon", "sigma", "K", "Kxy", "tipVelocity", "startChipPosition",
              "indentationStartStep"]
    row = [[0], list(range(1, 8)), epsilon, 0.9, 2.0, 5.0, velocity, list(chip), start]
    if backward is not None:
        labels.append("indentationBackwardStep")
        row.append(backward)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "afm"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["TIP", 5.0, TIP_RADIUS, 0.0], ["S", 1.0, 0.3, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": DT}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(p), [0.0, 0.0, 0.0]] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": ["id", "type"],
                                   "data": [[i, "TIP" if i == 0 else "S"] for i in range(len(positions))]},
                     "forceField": {"AFM": {"type": ["AFM", "SphericalTip"], "labels": labels, "data": [row]}}},
    }


def chip_at(step, chip, velocity, start, backward):
    z = chip[2]
    if start <= step < backward:
        z += velocity * DT * (step - start)
    elif step >= backward:
        z += velocity * DT * (backward - start) - velocity * DT * (step - backward)
    return np.array([chip[0], chip[1], z])


def expected_energy(positions, epsilon, step=0, chip=(5.8, 0.0, 3.0), velocity=-0.5, start=0, backward=10**18):
    eps, A, B = (-epsilon, 1.0, -2.0) if epsilon < 0 else (epsilon, 0.0, 1.0)
    g = np.linalg.norm(minimum_image(positions[1:8] - positions[0]), axis=1) - TIP_RADIUS
    sample = np.sum(eps * (A * (0.9 / g) ** 12 + B * (0.9 / g) ** 6))
    d = minimum_image(chip_at(step, chip, velocity, start, backward) - positions[0])
    spring = 0.5 * (5.0 * d[0] ** 2 + 5.0 * d[1] ** 2 + 2.0 * d[2] ** 2)
    return sample + spring


@pytest.mark.parametrize("epsilon", [-1.2, 0.8])
def test_energy_is_the_formula_and_force_is_minus_its_gradient(options, epsilon):
    positions = configuration(seed=1)
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(positions, epsilon))
        assert sim.energy("AFM") == pytest.approx(expected_energy(positions, epsilon), rel=1e-12)
        forces = sim.forces
        assert np.all(forces[8] == 0.0)
        h = 1e-6
        numerical = np.zeros_like(forces)
        for i in range(len(positions)):
            for a in range(3):
                moved = positions.copy()
                moved[i, a] += h
                sim.positions = moved
                up = sim.energy("AFM")
                moved[i, a] -= 2 * h
                sim.positions = moved
                numerical[i, a] = -(up - sim.energy("AFM")) / (2 * h)
    error = np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical))
    assert error < 1e-6, error
    # The tip feels the reactions of its sample plus the chip: the sample's forces and the tip's
    # balance the chip spring.
    d = minimum_image(np.array([5.8, 0.0, 3.0]) - positions[0])
    np.testing.assert_allclose(forces[:8].sum(axis=0), [5.0 * d[0], 5.0 * d[1], 2.0 * d[2]], atol=1e-9)


def test_the_chip_waits_indents_and_withdraws(options):
    positions = configuration(seed=2)
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(positions, -1.0, velocity=-3.0, start=4, backward=9, steps=14))
        for _ in range(14):
            step = sim.step_number
            expected = expected_energy(sim.positions, -1.0, step, velocity=-3.0, start=4, backward=9)
            assert sim.energy("AFM") == pytest.approx(expected, rel=1e-10), step
            sim.step(1)


@pytest.mark.parametrize("other_time_step", ["global", "unscheduled integrator first"])
def test_the_chip_moves_by_the_time_step_the_integrator_steps_with(options, other_time_step):
    """A time step the integrator does not step with must not move the chip: global.fundamental's when
    the integrator gives its own, or that of an integrator scheduled first for no steps."""
    positions = configuration(seed=2)
    doc = document(positions, -1.0, velocity=-3.0, start=1, steps=6)
    if other_time_step == "global":
        doc["global"]["fundamental"] = {"type": ["Fundamental", "Time"], "parameters": {"timeStep": 5 * DT}}
    else:
        doc["integrator"]["idle"] = {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 5 * DT}}
        doc["integrator"]["schedule"]["data"] = [[1, "idle", 0], [2, "vv", 6]]
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        for _ in range(6):
            sim.step(1)
            assert sim.time == pytest.approx(sim.step_number * DT, rel=1e-12)
            expected = expected_energy(sim.positions, -1.0, sim.step_number, velocity=-3.0, start=1)
            assert sim.energy("AFM") == pytest.approx(expected, rel=1e-10), sim.step_number


@pytest.mark.parametrize("change, path, message", [
    (lambda row: row.__setitem__(0, [0, 8]), r"AFM\.data\[0\]", "one particle"),
    (lambda row: row.__setitem__(1, [1, 2, 0]), r"AFM\.data\[0\]\[1\]\[2\]", "already in a set"),
    (lambda row: row.__setitem__(1, [1, 20]), r"AFM\.data\[0\]\[1\]\[1\]", "does not exist"),
    (lambda row: row.__setitem__(9, 2), r"AFM\.data\[0\]", "before indentationStartStep"),
])
def test_bad_rows_are_input_errors(options, change, path, message):
    doc = document(configuration(seed=0), -1.0, start=5, backward=7)
    change(doc["topology"]["forceField"]["AFM"]["data"][0])
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=path + ".*" + message):
            sim.load(doc)


@pytest.mark.parametrize("verbose", [False, True])
def test_afm_measure_writes_indentation_and_cantilever_force(options, tmp_path, verbose):
    positions = configuration(seed=3)
    doc = document(positions, -1.0, velocity=-3.0, start=2, backward=6, steps=20)
    doc["simulationStep"] = {"afm": {"type": ["ExperimentMeasures", "AFMMeasure"],
                                     "parameters": {"intervalStep": 4, "outputFilePath": str(tmp_path / "afm.dat"),
                                                    "verbose": verbose}}}
    frames = []
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        for _ in range(3):  # the measure fires at steps 0, 4, 8 and 12, the last where the last call ends
            frames.append((sim.step_number, sim.positions, sim.forces))
            sim.step(4)
        frames.append((sim.step_number, sim.positions, sim.forces))
    lines = (tmp_path / "afm.dat").read_text().splitlines()
    expected_header = (["#step", "time", "chip_0", "tip_0", "deflection_0", "tipForce_0", "sampleForce_0", "F_0"]
                       if verbose else ["#step", "time", "X_0", "F_0"])
    assert lines[0].split() == expected_header
    for line, (step, frame, forces) in zip(lines[1:], frames):
        values = [float(x) for x in line.split()]
        assert int(values[0]) == step
        chip = chip_at(step, (5.8, 0.0, 3.0), -3.0, 2, 6)[2]
        F = 2.0 * (frame[0, 2] - chip)
        if verbose:
            np.testing.assert_allclose(values[2:], [chip, frame[0, 2], frame[0, 2] - chip, forces[0, 2],
                                                    forces[1:8, 2].sum(), F], rtol=1e-9, atol=1e-12)
        else:
            np.testing.assert_allclose(values[2:], [frame[0, 2] - TIP_RADIUS, F], rtol=1e-12)
    assert len(lines) == 1 + len(frames)


def test_afm_measure_needs_an_afm_entry(options, tmp_path):
    doc = document(configuration(seed=0), -1.0)
    doc["topology"]["forceField"] = {}
    doc["simulationStep"] = {"afm": {"type": ["ExperimentMeasures", "AFMMeasure"],
                                     "parameters": {"intervalStep": 1, "outputFilePath": str(tmp_path / "a.dat")}}}
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"simulationStep\.afm\.type.*AFM"):
            sim.load(doc)
