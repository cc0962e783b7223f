"""The ensemble's lambda (["Ensemble","NVTlambda"]) and the terms, steps and measure built on it.

Each term of lambda: its energy against the formula written out here (numpy, minimum image), and its
dU/dlambda, as ["ThermodynamicMeasure","ThermodynamicIntegration"] writes it, against a central
finite difference of the engine's energy between two inputs whose ensembles differ in lambda alone.
(Forces against -grad U, and the Hessian, run in test_component_gradients / test_hessian, whose CASES
hold these terms at lambda = 0.6.) The schedules of LambdaActivation and LambdaCycle are checked step
by step through the energy of a LambdaHarmonic bond with n = 1 between particles that cannot move
(mass 0), whose energy is lambda times the spring's. LennardJonesSoftCoreType1 is also checked against
LAMMPS's lj/cut/soft (tests/reference/make_lammps_reference_soft_core.py)."""

import copy
import json
import math
from pathlib import Path

import numpy as np
import pytest

import structmd

BOX = 6.0
# Four particles, the pairs (0, 1) and (2, 3) across the x boundary; every pair is within 1.3 s of
# the soft-core cutoff 2.5 s (s = 1).
POSITIONS = np.array([[2.6, 0.1, 0.0], [-2.55, 0.3, 0.2], [0.0, 0.0, 0.0], [1.1, 0.4, -0.3]])
EPSILON, SIGMA, ALPHA, POWER = 1.3, 1.0, 0.7, 3


def separation(i, j, positions=POSITIONS):
    d = positions[j] - positions[i]
    return d - BOX * np.round(d / BOX)


def document(force_field, lam=0.6, steps=None, mass=1.0, ensemble="NVTlambda"):
    labels, row = (["box", "temperature", "lambda"], [[BOX, BOX, BOX], 1.0, lam])
    if ensemble == "NVT":
        labels, row = labels[:2], row[:2]
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "lambda"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", mass, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", ensemble], "labels": labels, "data": [row]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 100]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(p), [0.0, 0.0, 0.0]] for i, p in enumerate(POSITIONS)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(POSITIONS))]},
                     "forceField": copy.deepcopy(force_field)},
        "simulationStep": copy.deepcopy(steps or {}),
    }


NL = {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}}

# (c12, c6) of U = lambda^n eps (c12 / D^2 + c6 / D), D = alpha (1 - lambda)^2 + (r/s)^6
SOFT_SHAPES = {"Steric6SoftCore": (0, 1), "Steric12SoftCore": (1, 0),
               "LennardJonesSoftCoreType1": (4, -4), "LennardJonesSoftCoreType2": (1, -2)}


def soft_core(r, lam, shape, cutoff=math.inf, shifted=False):
    c12, c6 = shape
    if r >= cutoff:
        return 0.0

    def u(x):
        D = ALPHA * (1 - lam) ** 2 + (x / SIGMA) ** 6
        return lam ** POWER * EPSILON * (c12 / D ** 2 + c6 / D)
    return u(r) - (u(cutoff) if shifted else 0.0)


def pair_entry(name, shift=False):
    return {"nl": NL, "term": {"type": ["NonBonded", name],
                               "parameters": {"cutOffFactor": 2.5, "condition": "all", "alpha": ALPHA, "n": POWER,
                                              "shift": shift},
                               "labels": ["name_i", "name_j", "epsilon", "sigma"],
                               "data": [["A", "A", EPSILON, SIGMA]]}}


def pair_energy(name, lam, shift=False):
    return sum(soft_core(np.linalg.norm(separation(i, j)), lam, SOFT_SHAPES[name], 2.5 * SIGMA, shift)
               for i in range(4) for j in range(i + 1, 4))


BONDS = [(0, 1), (1, 2), (2, 3)]
K, R0 = 7.0, 1.2


def harmonic_bonds(lam):
    return sum(lam ** POWER * 0.5 * K * (np.linalg.norm(separation(i, j)) - R0) ** 2 for i, j in BONDS)


SPRING_K, SPRING_R0, POINT = [3.0, 5.0, 2.0], [0.4, 0.1, 0.3], [2.9, -0.5, 0.5]


def anisotropic_tethers(lam):
    total = 0.0
    for i in range(4):
        d = np.asarray(POINT) - POSITIONS[i]
        d -= BOX * np.round(d / BOX)
        total += lam ** POWER * sum(0.5 * k * (abs(x) - r0) ** 2 for k, x, r0 in zip(SPRING_K, d, SPRING_R0))
    return total


def soft_bonds(k, common):
    params = {"alpha": ALPHA, "n": POWER}
    labels, row = ["epsilon", "sigma"], [EPSILON, SIGMA]
    if common:
        params["epsilon"] = EPSILON
        labels, row = ["sigma"], [SIGMA]
    name = f"LennardJonesSoftCoreType{k}" + ("Common_epsilon" if common else "")
    return {"term": {"type": ["Bond2", name], "parameters": params, "labels": ["id_i", "id_j"] + labels,
                     "data": [[i, j] + row for i, j in BONDS]}}


# name: (force field, U(lambda) written out here)
TERMS = {
    **{f"NonBonded {name}": (pair_entry(name), lambda lam, name=name: pair_energy(name, lam))
       for name in SOFT_SHAPES},
    "NonBonded LennardJonesSoftCoreType1 shifted": (
        pair_entry("LennardJonesSoftCoreType1", shift=True),
        lambda lam: pair_energy("LennardJonesSoftCoreType1", lam, shift=True)),
    "Bond2 LambdaHarmonic": ({"term": {"type": ["Bond2", "LambdaHarmonic"], "parameters": {"n": POWER},
                                       "labels": ["id_i", "id_j", "K", "r0"],
                                       "data": [[i, j, K, R0] for i, j in BONDS]}}, harmonic_bonds),
    "Bond1 LambdaFixedHarmonicAnisotropic": (
        {"term": {"type": ["Bond1", "LambdaFixedHarmonicAnisotropic"], "parameters": {"n": POWER},
                  "labels": ["id_i", "K", "r0", "position"],
                  "data": [[i, SPRING_K, SPRING_R0, POINT] for i in range(4)]}}, anisotropic_tethers),
    **{f"Bond2 LennardJonesSoftCoreType{k}{'Common_epsilon' if c else ''}": (
        soft_bonds(k, c),
        lambda lam, k=k: sum(soft_core(np.linalg.norm(separation(i, j)), lam, SOFT_SHAPES[
            f"LennardJonesSoftCoreType{k}"]) for i, j in BONDS)) for k in (1, 2) for c in (False, True)},
}


def energy_at(options, force_field, lam, term="term"):
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(force_field, lam))
        return sim.energy(term)


def ti_output(options, tmp_path, force_field, values, step_lambda, nsteps, mass=0.0, interval=1):
    """The blocks of a ThermodynamicIntegration run: [(lambda, [dU/dlambda, ...]), ...]."""
    path = tmp_path / "ti.dat"
    steps = {"ti": {"type": ["ThermodynamicMeasure", "ThermodynamicIntegration"],
                    "parameters": {"intervalStep": interval, "stepLambda": step_lambda, "lambdaValues": values,
                                   "outputFilePath": str(path)}}}
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(force_field, values[0], steps, mass=mass))
        sim.step(nsteps)
    lines = path.read_text().splitlines()
    assert lines[0] == "# dU/dlambda"
    blocks = []
    for line in lines[1:]:
        if line.startswith("#"):
            blocks.append((float(line[1:]), []))
        else:
            blocks[-1][1].append(float(line))
    return blocks


@pytest.mark.parametrize("name", sorted(TERMS))
@pytest.mark.parametrize("lam", [0.0, 0.35, 1.0])
def test_energy_is_the_formula(options, name, lam):
    force_field, formula = TERMS[name]
    expected = formula(lam)
    got = energy_at(options, force_field, lam)
    if lam > 0:
        assert abs(expected) > 1e-3, "the term must act on this configuration"
    assert got == pytest.approx(expected, rel=1e-12, abs=1e-14)


@pytest.mark.parametrize("name", sorted(TERMS))
@pytest.mark.parametrize("lam", [0.0, 0.35, 0.8, 1.0])
def test_lambda_derivative_is_the_finite_difference_of_the_energy(options, tmp_path, name, lam):
    force_field, _ = TERMS[name]
    (written_lambda, values), = ti_output(options, tmp_path, force_field, [lam], 10, 2)
    assert written_lambda == lam
    assert len(values) == 3 and values[0] == values[1] == values[2]  # steps 0, 1 and 2 (where the call ends); nothing moves
    h = 1e-6
    # One-sided at the ends of [0, 1] (second order), central inside.
    if lam == 0.0:
        e0, e1, e2 = (energy_at(options, force_field, lam + k * h) for k in range(3))
        numerical = (-3 * e0 + 4 * e1 - e2) / (2 * h)
    elif lam == 1.0:
        e0, e1, e2 = (energy_at(options, force_field, lam - k * h) for k in range(3))
        numerical = (3 * e0 - 4 * e1 + e2) / (2 * h)
    else:
        numerical = (energy_at(options, force_field, lam + h) - energy_at(options, force_field, lam - h)) / (2 * h)
    scale = max(abs(numerical), 1e-3)
    assert abs(values[0] - numerical) / scale < 1e-6, (values[0], numerical)
    if lam > 0.0:
        assert abs(values[0]) > 1e-3, "dU/dlambda must not vanish here"


def test_thermodynamic_integration_walks_lambda_and_sums_every_term(options, tmp_path):
    force_field = {**TERMS["Bond2 LambdaHarmonic"][0],
                   **{"nl": NL, "pair": pair_entry("LennardJonesSoftCoreType2")["term"]}}
    blocks = ti_output(options, tmp_path, force_field, [0.9, 0.5, 0.2], step_lambda=4, nsteps=20, interval=2)
    # Blocks start at steps 0, 4, 8; dU/dlambda is written at the even steps of each; after step 11
    # nothing more.
    assert [b[0] for b in blocks] == [0.9, 0.5, 0.2]
    assert [len(b[1]) for b in blocks] == [2, 2, 2]
    h = 1e-6
    for lam, values in blocks:
        numerical = (energy_at(options, force_field, lam + h, "potential") -
                     energy_at(options, force_field, lam - h, "potential")) / (2 * h)
        for value in values:
            assert value == pytest.approx(numerical, rel=1e-6)
    bonds_only = ti_output(options, tmp_path, TERMS["Bond2 LambdaHarmonic"][0], [0.5], 4, 1)
    assert bonds_only[0][1][0] == pytest.approx(POWER * 0.5 ** (POWER - 1) * harmonic_bonds(1.0), rel=1e-12)


def lambda_energy_trace(options, tmp_path, schedule, nsteps, lam=0.3):
    """lambda at each step 0 .. nsteps - 1 as the schedule sets it, read from the energy of a
    LambdaHarmonic bond with n = 1 between two particles that cannot move."""
    path = tmp_path / "energies.dat"
    bond = {"term": {"type": ["Bond2", "LambdaHarmonic"], "parameters": {"n": 1},
                     "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, K, R0]]}}
    steps = {"schedule": schedule,
             "energy": {"type": ["ThermodynamicMeasure", "InteractorsListEnergyMeasure"],
                        "parameters": {"intervalStep": 1, "outputFilePath": str(path)}}}
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(bond, lam, steps, mass=0.0))
        sim.step(nsteps)
    rows = [line.split() for line in path.read_text().splitlines()[1:]]
    full = 0.5 * K * (np.linalg.norm(separation(0, 1)) - R0) ** 2
    return {int(r[0]): float(r[2]) / full for r in rows if int(r[0]) < nsteps}


def test_lambda_activation_schedule(options, tmp_path):
    values = [0.1, 0.4, 0.8]
    schedule = {"type": ["FlowControl", "LambdaActivation"],
                "parameters": {"intervalStep": 1, "startStep": 5, "lambdaValueStep": 3, "lambdaValues": values}}
    trace = lambda_energy_trace(options, tmp_path, schedule, 30)

    def expected(step):
        if step < 5:
            return 0.3  # the ensemble's until the schedule starts
        s = step - 5
        return values[s // 3] if s < 9 else 1.0
    assert sorted(trace) == list(range(30))
    for step, lam in trace.items():
        assert lam == pytest.approx(expected(step), rel=1e-12), step


def test_a_schedule_firing_every_few_steps_holds_lambda_in_between(options, tmp_path):
    values = [0.1, 0.4, 0.8]
    schedule = {"type": ["FlowControl", "LambdaActivation"],
                "parameters": {"intervalStep": 4, "lambdaValueStep": 3, "lambdaValues": values}}
    trace = lambda_energy_trace(options, tmp_path, schedule, 16)
    exact = lambda s: values[s // 3] if s < 9 else 1.0
    for step, lam in trace.items():
        assert lam == pytest.approx(exact(step - step % 4), rel=1e-12), step


def test_lambda_cycle_schedule(options, tmp_path):
    values = [0.2, 0.5, 0.7]
    schedule = {"type": ["FlowControl", "LambdaCycle"],
                "parameters": {"intervalStep": 1, "startStep": 3, "activationStep": 2, "measureStep": 4,
                               "pauseStep": 3, "lambdaValues": values}}
    trace = lambda_energy_trace(options, tmp_path, schedule, 45)

    def expected(step):
        if step < 3:
            return 0.3
        c = (step - 3) % (6 + 4 + 3)
        return values[c // 2] if c < 6 else (1.0 if c < 10 else 0.0)
    assert sorted(trace) == list(range(45))
    for step, lam in trace.items():
        assert lam == pytest.approx(expected(step), rel=1e-12, abs=1e-15), step


def test_lambda_survives_a_checkpoint(options, tmp_path):
    bond = TERMS["Bond2 LambdaHarmonic"][0]
    steps = {"schedule": {"type": ["FlowControl", "LambdaActivation"],
                          "parameters": {"intervalStep": 1, "lambdaValueStep": 100, "lambdaValues": [0.45]}}}
    path = str(tmp_path / "state.chk")
    with structmd.Simulation(dict(options, precision="double")) as first:
        first.load(document(bond, 0.9, steps, mass=0.0))
        first.step(3)
        first.save_checkpoint(path)
        saved = first.energy("term")
    assert saved == pytest.approx(harmonic_bonds(0.45), rel=1e-12)
    with structmd.Simulation(dict(options, precision="double")) as second:
        second.load(document(bond, 0.9, mass=0.0))
        assert second.energy("term") == pytest.approx(harmonic_bonds(0.9), rel=1e-12)
        second.load_checkpoint(path)
        assert second.energy("term") == pytest.approx(saved, rel=1e-12)


def test_a_step_call_undone_puts_back_its_lambda(options):
    bond = TERMS["Bond2 LambdaHarmonic"][0]
    steps = {"schedule": {"type": ["FlowControl", "LambdaActivation"],
                          "parameters": {"intervalStep": 1, "startStep": 2, "lambdaValueStep": 100,
                                         "lambdaValues": [0.45]}}}

    def failing(positions, forces, step):
        if step == 4:
            raise ValueError("no convergence")

    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(bond, 0.9, steps, mass=0.0))
        sim.step(1)
        sim.set_force_callback(failing)
        with pytest.raises(structmd.CallbackError):
            sim.step(5)  # sets lambda 0.45 at step 2, fails at step 4
        assert sim.step_number == 1
        assert sim.energy("term") == pytest.approx(harmonic_bonds(0.9), rel=1e-12)
        sim.set_force_callback(None)
        sim.step(5)
        assert sim.energy("term") == pytest.approx(harmonic_bonds(0.45), rel=1e-12)


def test_terms_of_lambda_act_in_full_under_nvt(options):
    force_field = TERMS["Bond2 LambdaHarmonic"][0]
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(document(force_field, ensemble="NVT"))
        assert sim.energy("term") == pytest.approx(harmonic_bonds(1.0), rel=1e-12)


@pytest.mark.parametrize("lam", [-0.1, 1.5])
def test_lambda_outside_the_unit_interval_is_refused(options, lam):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"global\.ensemble\.data\[0\]\[2\].*lambda must be in \[0, 1\]"):
            sim.load(document(TERMS["Bond2 LambdaHarmonic"][0], lam))


SCHEDULE_ERRORS = [
    ({"type": ["FlowControl", "LambdaCycle"],
      "parameters": {"intervalStep": 1, "activationStep": 2, "measureStep": 1, "pauseStep": 1,
                     "lambdaValues": [0.2, 1.2]}},
     r"simulationStep\.step\.parameters\.lambdaValues\[1\].*\[0, 1\]"),
    ({"type": ["FlowControl", "LambdaActivation"],
      "parameters": {"intervalStep": 1, "lambdaValueStep": 2, "lambdaValues": []}},
     r"simulationStep\.step\.parameters\.lambdaValues.*non-empty list"),
    ({"type": ["ThermodynamicMeasure", "ThermodynamicIntegration"],
      "parameters": {"intervalStep": 1, "stepLambda": 2, "lambdaValues": [0.5, 0.2], "outputFilePath": "ti.dat"}},
     r"simulationStep\.step\.parameters\.lambdaValues\[0\].*ensemble's lambda"),
]


@pytest.mark.parametrize("entry, message", SCHEDULE_ERRORS)
def test_bad_lambda_steps_are_refused(options, entry, message):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=message):
            sim.load(document(TERMS["Bond2 LambdaHarmonic"][0], 0.6, {"step": entry}))


def test_a_power_below_one_is_refused(options):
    force_field = copy.deepcopy(TERMS["Bond2 LambdaHarmonic"][0])
    force_field["term"]["parameters"]["n"] = 0
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=r"topology\.forceField\.term\.parameters\.n.*integer >= 1"):
            sim.load(document(force_field))


REFERENCE = Path(__file__).resolve().parents[1] / "reference" / "data"


def test_soft_core_type1_matches_lammps_lj_cut_soft(options):
    """LAMMPS's pair_style lj/cut/soft (tests/reference/make_lammps_reference_soft_core.py) is
    LennardJonesSoftCoreType1: 80 particles of two types at lambda = 0.55, some pairs closer than
    sigma / 2."""
    doc = json.loads((REFERENCE / "soft_core.json").read_text())
    expected = json.loads((REFERENCE / "soft_core.lammps.json").read_text())
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        forces = np.asarray(sim.forces)
        energy = sim.energy("potential")
    reference = np.asarray(expected["forces"])
    assert np.max(np.abs(forces - reference)) < 1e-10 * np.max(np.abs(reference))
    assert energy == pytest.approx(expected["energy"], rel=1e-12)
