#!/usr/bin/env python3
"""Batches over MPI ranks through the launcher: `mpirun -np K structmd run INPUT.json` for K = 1, 2
and 3 against a run without MPI, on batched inputs (4 bead chains, Langevin with velocities drawn at
load, and Brownian). Trajectory files (wrapped and unwrapped positions, velocities) must be the
same bytes, the thermodynamic measure (whole-system sums, added over the ranks) the same to
rounding, and rank 0 alone must print. A flow-control step stops every rank at the same step, and an
input with more ranks than batches (but more than one batch) is refused with one message, and one batch
over two ranks (split in space) writes the one-process trajectories to their printed digits. Parallel tempering (four
temperatures, replicas over 1, 2 and 3 ranks, two on rank 0 of 3) makes the same exchanges and writes
the same files as one process. Without MPI in the build, checks
that `structmd run --mpi` says MPI is not compiled in, and reports itself skipped (77).

usage: check_launcher_batches.py LAUNCHER [--mpiexec MPIEXEC --numproc-flag=FLAG --mpi-flags="..."]"""
import argparse
import filecmp
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile

STRUCTMD_ERR_UNSUPPORTED = 8  # include/structmd.h
BATCHES, PER_BATCH = 4, 16
problems = []


def expect(condition, message):
    if not condition:
        problems.append(message)


def chains(integrator, steps, escape=False):
    """BATCHES overlaid chains of PER_BATCH beads (harmonic bonds, Lennard-Jones within a batch)."""
    n = BATCHES * PER_BATCH
    positions = [[1.05 * (i % PER_BATCH % 8) - 4.0, 1.05 * (i % PER_BATCH // 8), 0.0] for i in range(n)]
    bonds = [[i, i + 1, 100.0, 1.05] for i in range(n - 1) if (i + 1) % PER_BATCH]
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "batches", "seed": 5}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[12.0] * 3, 1.0]]},
        },
        "integrator": {
            "dynamics": integrator,
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "dynamics", steps]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, p] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type", "batchId"], "data": [[i, "A", i // PER_BATCH] for i in range(n)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]},
                "bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": bonds},
            },
        },
        "simulationStep": {
            "wrapped": {"type": ["WriteStep", "WriteStep"],
                        "parameters": {"intervalStep": 50, "outputFilePath": "wrapped", "outputFormat": "svv"}},
            "unwrapped": {"type": ["WriteStep", "WriteStep"],
                          "parameters": {"intervalStep": 50, "outputFilePath": "unwrapped", "outputFormat": "lammpstrj",
                                         "pbc": False}},
            "velocities": {"type": ["WriteStep", "WriteStep"],
                           "parameters": {"intervalStep": 50, "outputFilePath": "velocities", "outputFormat": "vel"}},
            "thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                       "parameters": {"intervalStep": 50, "outputFilePath": "thermo.dat"}},
        },
    }
    if escape:
        # Every bead lies above z = -0.5, outside the half-space: the step stops the run at step 100.
        doc["simulationStep"]["escape"] = {
            "type": ["GeometricalMeasure", "EscapePolygonTime"],
            "parameters": {"intervalStep": 10, "startStep": 100, "outputFilePath": "escape.dat",
                           "stopSimulation": "true", "particlesToEscape": 1},
            "labels": ["normalVector", "independentVector"], "data": [[[0.0, 0.0, -1.0], [0.0, 0.0, -0.5]]]}
    return doc


LANGEVIN = {"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.002, "frictionConstant": 1.0}}
BROWNIAN = {"type": ["Brownian", "EulerMaruyama"], "parameters": {"timeStep": 0.001, "viscosity": 1.0}}
OUTPUTS = ["wrapped.svv", "unwrapped.lammpstrj", "velocities.vel"]


def run(command, folder, doc):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "input.json"), "w") as f:
        json.dump(doc, f)
    result = subprocess.run(command + ["run", "input.json", "--backend", "cpu", "--threads", "1",
                                       "--precision", "double", "--progress", "1000"],
                            capture_output=True, text=True, cwd=folder, timeout=300)
    print(f"--- {' '.join(command)} in {folder}: exit {result.returncode}\n{result.stdout}{result.stderr}")
    return result


def thermo_values(path):
    with open(path) as f:
        return [[float(x) for x in line.split()] for line in f if not line.startswith("#")]


def same_to_rounding(a, b):
    return len(a) == len(b) and all(len(r) == len(s) and all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12)
                                                             for x, y in zip(r, s)) for r, s in zip(a, b))


def same_numbers(path_a, path_b, rel_tol):
    """The same text but for numbers, which agree to rel_tol (or 1e-7 absolute)."""
    def tokens(path):
        with open(path) as f:
            return f.read().split()
    a, b = tokens(path_a), tokens(path_b)
    if len(a) != len(b):
        return False
    for x, y in zip(a, b):
        if x == y:
            continue
        try:
            if not math.isclose(float(x), float(y), rel_tol=rel_tol, abs_tol=1e-7):
                return False
        except ValueError:
            return False
    return True


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("launcher")
    parser.add_argument("--mpiexec")
    parser.add_argument("--numproc-flag", default="-np")
    parser.add_argument("--mpi-flags", default="")
    args = parser.parse_args()
    launcher = os.path.abspath(args.launcher)

    with tempfile.TemporaryDirectory() as work:
        if not args.mpiexec:
            folder = os.path.join(work, "nompi")
            os.makedirs(folder)
            with open(os.path.join(folder, "input.json"), "w") as f:
                json.dump(chains(BROWNIAN, 10), f)
            result = subprocess.run([launcher, "run", "input.json", "--mpi"], capture_output=True, text=True,
                                    cwd=folder, timeout=60)
            print(result.stdout + result.stderr)
            expect(result.returncode == STRUCTMD_ERR_UNSUPPORTED, f"--mpi without MPI exited {result.returncode}")
            expect("MPI is not compiled in" in result.stderr, "--mpi without MPI does not say MPI is not compiled in")
            if problems:
                sys.exit("\n".join(problems))
            print("skipped: MPI is not compiled in (and --mpi says so)")
            sys.exit(77)

        def mpirun(ranks):
            return [args.mpiexec, args.numproc_flag, str(ranks), *shlex.split(args.mpi_flags), launcher]

        for name, integrator in (("langevin", LANGEVIN), ("brownian", BROWNIAN)):
            doc = chains(integrator, 300)
            one = run([launcher], os.path.join(work, name, "alone"), doc)
            expect(one.returncode == 0, f"{name}: the run without MPI exited {one.returncode}")
            reference = os.path.join(work, name, "alone")
            for ranks in (1, 2, 3):
                folder = os.path.join(work, name, f"np{ranks}")
                result = run(mpirun(ranks), folder, doc)
                expect(result.returncode == 0, f"{name}, {ranks} ranks: exited {result.returncode}")
                for output in OUTPUTS:
                    expect(os.path.exists(os.path.join(folder, output)) and
                           filecmp.cmp(os.path.join(reference, output), os.path.join(folder, output), shallow=False),
                           f"{name}, {ranks} ranks: {output} differs from the run without MPI")
                expect(same_to_rounding(thermo_values(os.path.join(reference, "thermo.dat")),
                                        thermo_values(os.path.join(folder, "thermo.dat"))),
                       f"{name}, {ranks} ranks: thermo.dat differs beyond rounding")
                summaries = [line for line in result.stdout.splitlines() if line.startswith("structmd run:")]
                expect(len(summaries) == 1, f"{name}, {ranks} ranks: {len(summaries)} summaries, expected rank 0's alone")
                expect(f"MPI ranks         {ranks}" in result.stdout, f"{name}, {ranks} ranks: the summary names no ranks")

        # Parallel tempering (each replica the four batches): the same exchanges, and so the same files,
        # however the replicas are spread.
        tempering = chains(LANGEVIN, 400)
        tempering["simulationStep"]["exchange"] = {
            "type": ["ReplicaExchange", "ParallelTempering"],
            "parameters": {"intervalStep": 10, "temperatures": [1.0, 1.3, 1.7, 2.2], "outputFilePath": "exchanges.dat"}}
        alone = os.path.join(work, "tempering", "alone")
        result = run([launcher], alone, tempering)
        expect(result.returncode == 0, f"tempering without MPI exited {result.returncode}")
        files = sorted(f for f in os.listdir(alone) if f != "input.json")
        expect(len(files) == 1 + 4 * (len(OUTPUTS) + 1), f"tempering wrote {files}")
        exchanged = [line.split()[1:4] for line in open(os.path.join(alone, "exchanges.dat")) if line[0] != "#"]
        expect(any("1" in row for row in exchanged) and any("0" in row for row in exchanged),
               "tempering: no exchange accepted, or none refused")
        for ranks in (1, 2, 3):
            folder = os.path.join(work, "tempering", f"np{ranks}")
            result = run(mpirun(ranks), folder, tempering)
            expect(result.returncode == 0, f"tempering, {ranks} ranks: exited {result.returncode}")
            for name in files:
                expect(os.path.exists(os.path.join(folder, name)) and
                       filecmp.cmp(os.path.join(alone, name), os.path.join(folder, name), shallow=False),
                       f"tempering, {ranks} ranks: {name} differs from the run without MPI")

        # A flow-control step on rank 0 stops every rank at the same step.
        stopped = run(mpirun(2), os.path.join(work, "stopped"), chains(BROWNIAN, 300, escape=True))
        expect(stopped.returncode == 0, f"stopped run exited {stopped.returncode}")
        expect(stopped.stderr.count("stopped at step 100 by simulationStep.escape") == 1,
               "the stop is not said once, at step 100")

        # One batch over two ranks is split in space (tests/mpi/domains.c checks it to 1e-10 through the C
        # API): through the launcher, the trajectory files that rank 0 writes hold the one-process
        # values to their 8 digits, give or take the last.
        spread = chains(LANGEVIN, 300)
        for row in spread["topology"]["structure"]["data"]:
            row[2] = 0
        for row in spread["state"]["data"]:
            k = row[0] % PER_BATCH  # each chain a U of two rows across the slabs' face at x = 0, in a plane of its own
            row[1] = [1.05 * (k if k < 8 else 15 - k) - 4.0, 1.05 * (k // 8), 3.0 * (row[0] // PER_BATCH) - 4.5]
        del spread["simulationStep"]["thermo"]
        alone = run([launcher], os.path.join(work, "domains", "alone"), spread)
        split = run(mpirun(2), os.path.join(work, "domains", "np2"), spread)
        expect(alone.returncode == 0 and split.returncode == 0,
               f"one batch: exited {alone.returncode} alone, {split.returncode} over 2 ranks")
        for output in OUTPUTS:
            a, b = (os.path.join(work, "domains", folder, output) for folder in ("alone", "np2"))
            expect(os.path.exists(b) and same_numbers(a, b, 1e-6), f"one batch over 2 ranks: {output} differs")

        # More ranks than batches (two, over three ranks): refused, said once, with the engine's status as
        # exit code. (One batch over several ranks is split in space instead: tests/mpi/domains.c.)
        few = chains(BROWNIAN, 10)
        for row in few["topology"]["structure"]["data"]:
            row[2] = row[0] // (2 * PER_BATCH)
        refused = run(mpirun(3), os.path.join(work, "refused"), few)
        expect(refused.returncode == STRUCTMD_ERR_UNSUPPORTED, f"two batches over 3 ranks exited {refused.returncode}")
        expect(refused.stderr.count("cannot be spread over 3 ranks") == 1, "the refusal is not said once")

    if problems:
        sys.exit("\n".join(problems))
    print("batches and parallel tempering over 1, 2 and 3 ranks: outputs identical to one process")


if __name__ == "__main__":
    main()
