"""Parallel tempering (["ReplicaExchange","ParallelTempering"]) in one process, every replica here, on
a system whose answer is known: N particles tethered by harmonic springs (["Bond1","FixedHarmonic"],
r0 = 0), 3N quadratic degrees of freedom, under Langevin dynamics at four temperatures. Detailed
balance is checked through what it implies: each temperature's potential (and kinetic) energy
averages 3N/2 kT, and the acceptance of each neighbouring pair is the Metropolis expectation
E[min(1, exp((b_k - b_k+1)(U_k - U_k+1)))] over independent U ~ Gamma(3N/2, kT) at each temperature,
computed here by sampling. Tolerances come from the run's own sample: block averages for the means,
the binomial spread (doubled for the correlation of successive attempts) for the acceptance. Also:
the acceptance file and structmd_get_info agree, the run is deterministic, and bad entries are refused
with their path. MPI runs (replicas over ranks, the same exchanges) are in tests/mpi."""

import json
import math

import numpy as np
import pytest

import structmd

N = 16
K_SPRING = 10.0
TEMPERATURES = [1.0, 1.25, 1.5625, 1.953125]
INTERVAL = 20
STEPS = 40000
DOF = 3 * N


def oscillators(steps=STEPS, temperatures=TEMPERATURES, interval=INTERVAL):
    rng = np.random.default_rng(3)
    anchors = rng.uniform(-6.0, 6.0, size=(N, 3))
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "pt", "seed": 17}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[20.0] * 3, 1.0]]},
        },
        "integrator": {
            "langevin": {"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.01, "frictionConstant": 1.0}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "langevin", steps]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, list(a)] for i, a in enumerate(anchors.tolist())]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(N)]},
            "forceField": {"tethers": {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
                                       "data": [[i, K_SPRING, 0.0, list(a)] for i, a in enumerate(anchors.tolist())]}},
        },
        "simulationStep": {
            "exchange": {"type": ["ReplicaExchange", "ParallelTempering"],
                         "parameters": {"intervalStep": interval, "temperatures": temperatures,
                                        "outputFilePath": "exchanges.dat"}},
            "thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                       "parameters": {"intervalStep": interval, "outputFilePath": "thermo.dat"}},
        },
    }


def expected_acceptance(t_low, t_high, samples=2_000_000):
    rng = np.random.default_rng(11)
    u_low = rng.gamma(DOF / 2, t_low, samples)
    u_high = rng.gamma(DOF / 2, t_high, samples)
    exponent = (1.0 / t_low - 1.0 / t_high) * (u_low - u_high)
    return float(np.mean(np.minimum(1.0, np.exp(np.minimum(exponent, 0.0)))))


def thermo_columns(path):
    with open(path) as f:
        header = f.readline().lstrip("#").split()
        rows = np.array([[float(x) for x in line.split()] for line in f if not line.startswith("#")])
    return {name: rows[:, k] for k, name in enumerate(header)}


def block_error(series, blocks=20):
    means = np.array([b.mean() for b in np.array_split(series, blocks)])
    return means.std(ddof=1) / math.sqrt(blocks)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pt")
    import os
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        with structmd.Simulation({"backend": "cpu", "precision": "double", "threads": 1}) as sim:
            sim.load(oscillators())
            sim.run()
            info = sim.info
    finally:
        os.chdir(cwd)
    return folder, info


def test_each_temperature_has_equipartition(run):
    folder, _ = run
    for k, temperature in enumerate(TEMPERATURES):
        columns = thermo_columns(folder / f"temperature{k}_thermo.dat")
        equilibrated = columns["step"] >= 2000
        for quantity in ("potential", "kinetic"):
            series = columns[quantity][equilibrated]
            expected = DOF / 2 * temperature
            tolerance = 5 * block_error(series) + 1e-3 * expected
            assert abs(series.mean() - expected) < tolerance, (k, quantity, series.mean(), expected, tolerance)


def test_acceptance_matches_the_metropolis_expectation(run):
    folder, info = run
    exchange = info["replica_exchange"]
    assert exchange["temperatures"] == TEMPERATURES
    attempts = STEPS // INTERVAL // 2
    for k in range(len(TEMPERATURES) - 1):
        assert exchange["attempts"][k] == attempts
        observed = exchange["accepted"][k] / attempts
        expected = expected_acceptance(TEMPERATURES[k], TEMPERATURES[k + 1])
        spread = 2 * math.sqrt(expected * (1 - expected) / attempts)
        assert abs(observed - expected) < 5 * spread, (k, observed, expected, spread)
        assert exchange["acceptance"][k] == pytest.approx(observed)
    # The file's last row holds the same running acceptance, after one outcome per pair and attempt.
    rows = [line.split() for line in (folder / "exchanges.dat").read_text().splitlines() if not line.startswith("#")]
    assert len(rows) == STEPS // INTERVAL
    pairs = len(TEMPERATURES) - 1
    for k in range(pairs):
        outcomes = [row[1 + k] for row in rows]
        assert outcomes.count("-") == len(rows) // 2
        assert outcomes.count("1") == exchange["accepted"][k]
        assert float(rows[-1][1 + pairs + k]) == pytest.approx(exchange["acceptance"][k], rel=1e-9)


def test_runs_are_deterministic(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    results = []
    for _ in range(2):
        with structmd.Simulation({"backend": "cpu", "precision": "double", "threads": 1}) as sim:
            sim.load(oscillators(steps=2000))
            sim.run()
            results.append((np.asarray(sim.positions).copy(), sim.info["replica_exchange"]["accepted"]))
    assert np.array_equal(results[0][0], results[1][0]) and results[0][1] == results[1][1]


def test_outputs_at_an_exchange_step_record_the_configuration_before_the_exchange(tmp_path, monkeypatch):
    """As LAMMPS's temper dumps step N before its swap: the thermo row of temperature 0 at an attempt
    holds the potential energy the replica had before it, which the handle (replica 0) still shows
    after the call unless the pair (0, 1) exchanged there."""
    monkeypatch.chdir(tmp_path)
    with structmd.Simulation({"backend": "cpu", "precision": "double", "threads": 1}) as sim:
        sim.load(oscillators(steps=100 * INTERVAL))
        after = {}
        while sim.step_number < 100 * INTERVAL:
            sim.step(INTERVAL)
            after[sim.step_number] = sim.energy("potential")
    thermo = thermo_columns(tmp_path / "temperature0_thermo.dat")
    before = dict(zip(thermo["step"].astype(int), thermo["potential"]))
    exchanged = {int(row[0]): row[1] == "1" for row in
                 (line.split() for line in (tmp_path / "exchanges.dat").read_text().splitlines())
                 if row and not row[0].startswith("#")}
    assert sum(exchanged.values()) >= 3, "the check needs exchanges of the pair (0, 1)"
    for step, energy in after.items():
        assert (before[step] == pytest.approx(energy, rel=1e-7)) == (not exchanged[step]), step  # 8 digits written


@pytest.mark.parametrize("change, path", [
    (lambda p: p.update(temperatures=[1.0]), "simulationStep.exchange.parameters.temperatures"),
    (lambda p: p.update(temperatures=[1.0, -2.0]), "simulationStep.exchange.parameters.temperatures[1]"),
    (lambda p: p.update(intervalStep=0), "simulationStep.exchange.parameters.intervalStep"),
    (lambda p: p.update(swapEvery=3), "simulationStep.exchange.parameters.swapEvery"),
])
def test_bad_entries_are_refused_with_their_path(change, path):
    doc = oscillators(steps=10)
    change(doc["simulationStep"]["exchange"]["parameters"])
    with structmd.Simulation({"backend": "cpu"}) as sim:
        with pytest.raises(structmd.InputError, match=path.replace("[", r"\[").replace("]", r"\]")):
            sim.load(doc)


def test_an_integrator_temperature_is_refused(tmp_path):
    doc = oscillators(steps=10)
    doc["integrator"]["langevin"]["parameters"]["temperature"] = 2.0
    with structmd.Simulation({"backend": "cpu"}) as sim:
        with pytest.raises(structmd.UnsupportedError, match="integrator.langevin.parameters.temperature"):
            sim.load(doc)
