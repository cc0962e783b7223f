#!/usr/bin/env python3
"""The launcher as a batch job sees it (standard error not a terminal): periodic progress lines,
--steps (past the schedule's end too), --thermo rows, a blow-up that stops the run at once with
the engine's message, a hint and the status as exit code, instead of running on and printing NaN,
and a flow-control step of the input that ends the run early.

usage: check_launcher.py LAUNCHER"""
import json
import math
import os
import subprocess
import sys
import tempfile

STRUCTMD_ERR_NUMERICAL = 4  # include/structmd.h
STRUCTMD_ERR_IO = 5
problems = []


def expect(condition, message):
    if not condition:
        problems.append(message)


def lattice_input(side, spacing, time_step, schedule_steps, squeeze=None):
    """side^3 LJ particles on a simple cubic lattice, velocity Verlet; squeeze=(i, j) puts particle j
    0.3 sigma from particle i (a violent overlap)."""
    box = side * spacing
    positions = [[(i + 0.5) * spacing - box / 2, (j + 0.5) * spacing - box / 2, (k + 0.5) * spacing - box / 2]
                 for i in range(side) for j in range(side) for k in range(side)]
    if squeeze:
        a, b = squeeze
        positions[b] = [positions[a][0] + 0.3, positions[a][1], positions[a][2]]
    n = len(positions)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "launcher", "seed": 3}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": time_step}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", schedule_steps]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, p] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"],
                       "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]},
            },
        },
    }


def run(launcher, work, name, doc, *arguments):
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(doc, f)
    result = subprocess.run([launcher, "run", path, "--backend", "cpu", "--threads", "1", *arguments],
                            capture_output=True, text=True, cwd=work, timeout=300)
    print(f"--- {name}: exit {result.returncode}\n{result.stdout}{result.stderr}")
    return result


def thermo_rows(stdout):
    """(step, kinetic, potential, total, temperature, pressure) of each --thermo row."""
    rows = []
    for line in stdout.splitlines():
        fields = line.split()
        if len(fields) == 6 and fields[0].lstrip("-").isdigit():
            rows.append((int(fields[0]), *map(float, fields[1:])))
    return rows


launcher = os.path.abspath(sys.argv[1])
with tempfile.TemporaryDirectory() as work:
    # A calm liquid: 50 steps past a schedule of 20, thermo every 10, progress lines every 0.01 s.
    calm = run(launcher, work, "calm", lattice_input(6, 1.12, 0.002, 20), "--steps", "50", "--thermo", "10",
               "--progress", "0.01")
    expect(calm.returncode == 0, f"calm run exited {calm.returncode}")
    rows = thermo_rows(calm.stdout)
    expect([r[0] for r in rows] == [0, 10, 20, 30, 40, 50], f"thermo rows at steps {[r[0] for r in rows]}")
    expect("temperature" in calm.stdout and "pressure" in calm.stdout, "no temperature and pressure columns")
    particles = 6 ** 3
    for step, kinetic, potential, total, temperature, pressure in rows:
        expect(all(math.isfinite(x) for x in (kinetic, potential, total, temperature, pressure)),
               f"non-finite thermo row at step {step}")
        expect(math.isclose(total, kinetic + potential, rel_tol=1e-6, abs_tol=1e-6), f"total at step {step}")
        # k_B = 1 in the input's units (none given)
        expect(math.isclose(temperature, 2 * kinetic / (3 * particles), rel_tol=1e-6), f"temperature at step {step}")
    progress = [line for line in calm.stderr.splitlines() if line.startswith("structmd: ") and "steps/s" in line]
    expect(len(progress) >= 2, f"expected progress lines on standard error, got {progress}")
    expect(any("step 50/50" in line for line in progress), "no final progress line at step 50/50")
    expect("\r" not in calm.stderr, "a carriage return in a log that is not a terminal")
    expect(any(line.split() == ["steps", "50"] for line in calm.stdout.splitlines()), "summary does not say 50 steps")

    # --no-step-graphs reaches the engine, which accepts it (the CPU backend has no graphs): the same run.
    issued = run(launcher, work, "issued", lattice_input(6, 1.12, 0.002, 20), "--steps", "50", "--thermo", "10",
                 "--no-step-graphs")
    expect(issued.returncode == 0, f"run with --no-step-graphs exited {issued.returncode}")
    expect(thermo_rows(issued.stdout) == rows, "--no-step-graphs changed the thermo rows")

    # --steps ends the run where it says, past the schedule's end or before it, and the outputs get
    # the final state there as at a schedule's end, though their interval does not land on it.
    for name, schedule_steps, steps, expected in (("longer", 20, 50, [0, 15, 30, 45, 50]),
                                                  ("shorter", 2000, 25, [0, 15, 25])):
        doc = lattice_input(5, 1.12, 0.002, schedule_steps)
        doc["simulationStep"] = {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                                            "parameters": {"intervalStep": 15, "outputFilePath": name + ".dat"}}}
        result = run(launcher, work, name, doc, "--steps", str(steps))
        expect(result.returncode == 0, f"{name}: exited {result.returncode}")
        path = os.path.join(work, name + ".dat")
        with open(path) if os.path.exists(path) else open(os.devnull) as f:
            written = [int(line.split()[0]) for line in f if not line.startswith("#")]
        expect(written == expected, f"{name}: thermo file rows at steps {written}, expected {expected}")

    # Two particles 0.3 sigma apart at a large time step: the engine reports a blow-up, the launcher
    # stops there with its message and a hint, having printed no NaN.
    blow = run(launcher, work, "blow", lattice_input(5, 1.12, 0.01, 2000, squeeze=(0, 1)), "--thermo", "1")
    expect(blow.returncode == STRUCTMD_ERR_NUMERICAL, f"blow-up exited {blow.returncode}, expected {STRUCTMD_ERR_NUMERICAL}")
    expect("blew up" in blow.stderr and "timeStep" in blow.stderr, "no hint after the blow-up")
    expect("structmd: stopped:" in blow.stderr, "the engine's message is missing")
    expect("nan" not in blow.stdout.lower(), "NaN printed before stopping")
    last = thermo_rows(blow.stdout)[-1][0] if thermo_rows(blow.stdout) else 0
    expect(last < 2000, "the run went on to the schedule's end")

    # A flow-control step ends the run early: an escape measure first firing at step 20 finds the top
    # layer outside its half-space and stops the call there; the launcher ends the run and says so.
    stopped_doc = lattice_input(5, 1.12, 0.002, 200)
    stopped_doc["simulationStep"] = {"escape": {
        "type": ["GeometricalMeasure", "EscapePolygonTime"],
        "parameters": {"intervalStep": 10, "startStep": 20, "outputFilePath": "escape.dat",
                       "stopSimulation": "true", "particlesToEscape": 1},
        "labels": ["normalVector", "independentVector"], "data": [[[0.0, 0.0, -1.0], [0.0, 0.0, 1.5]]]}}
    stopped = run(launcher, work, "stopped", stopped_doc, "--progress", "0.01")
    expect(stopped.returncode == 0, f"stopped run exited {stopped.returncode}")
    expect("stopped at step 20 by simulationStep.escape" in stopped.stderr, "no line saying where the run stopped")
    expect(any(line.split() == ["steps", "20"] for line in stopped.stdout.splitlines()), "summary does not say 20 steps")

    # A missing input file: a message naming it and the documented status 5, not CLI11's 105.
    absent = os.path.join(work, "absent.json")
    missing = subprocess.run([launcher, "run", absent, "--backend", "cpu"], capture_output=True, text=True,
                             cwd=work, timeout=60)
    print(f"--- missing input: exit {missing.returncode}\n{missing.stdout}{missing.stderr}")
    expect(missing.returncode == STRUCTMD_ERR_IO, f"a missing input exited {missing.returncode}, expected {STRUCTMD_ERR_IO}")
    expect(f"cannot read the input file {absent}" in missing.stderr, "no message naming the missing input")

if problems:
    sys.exit("\n".join(problems))
