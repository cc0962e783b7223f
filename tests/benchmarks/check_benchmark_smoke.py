#!/usr/bin/env python3
"""Smoke test of the LJ and coupling benchmarks on the CPU backend: tiny systems, a few steps (and the
LJ benchmark's other scenes: batches and bead chains). Runs one
program with --csv and checks that it exits 0 and that its CSV has the expected columns, one row per
configuration asked, and sane values: positive finite rates, finite drift, and force errors that
test the host reference of the accuracy benchmark. In double precision the engine's forces (Verlet
list) and the reference (exact cell search, double) differ by summation order alone, so the
relative error is ~1e-15; the bound 1e-10 fails on any missed pair, wrong image or wrong formula.
With forces in single precision the error is ~1e-7 (float rounding), hence 1e-9 .. 1e-3.

The coupling benchmark's bytes per exchange must scale with the region, not the system: one packed
vector each way for m particles (16 or 32 bytes each, by precision; the region's ids cross once, as
the loop names the same ones every time) is 32-64 bytes per particle, far below the 24 N bytes of
one whole array. The plain-step loop that follows an exchange still gathers the watched region once
(docs/c-api.md), which the difference of the two loops takes off: hence 10% of slack below.

The hydrodynamics benchmark (a Python script over the binding) measures the error of each method's
deterministic displacement; its bounds are in check_hydrodynamics.

The domains benchmark runs a liquid on 1 MPI rank and over 2, long enough that the domains are
rebuilt (the particles migrate), in double precision: the drift of the NVE energy over the timed
steps is the same on both to 1e-8, which a ghost that missed a neighbour would break.

usage: check_benchmark_smoke.py lj|accuracy|coupling|hydrodynamics PROGRAM
       check_benchmark_smoke.py transverser PROGRAM NEIGHBOUR_COUNT_PLUGIN LJ_FORCE_PLUGIN
       check_benchmark_smoke.py domains PROGRAM MPIEXEC [MPIEXEC FLAGS...]"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

LJ_COLUMNS = ["n", "backend", "precision", "steps_per_call", "steps_per_second", "particle_steps_per_second",
              "list_builds_per_1000_steps", "device_memory_mib", "setup_seconds", "pair", "scene", "traversal"]
ACCURACY_COLUMNS = ["precision", "dt", "skin", "n", "backend", "steps", "steps_per_second", "seconds_per_tau",
                    "energy_drift", "relative_force_error", "list_builds_per_1000_steps"]
HYDRODYNAMICS_COLUMNS = ["method", "n", "backend", "precision", "tolerance", "steps_per_second", "error"]
DOMAINS_COLUMNS = ["n", "ranks", "backend", "precision", "ghost_exchange", "steps_per_second",
                   "particle_steps_per_second", "domain_rebuilds_per_1000_steps", "list_builds_per_1000_steps",
                   "force_evaluations_per_1000_steps", "setup_seconds", "energy_drift"]
TRANSVERSER_COLUMNS = ["n", "backend", "precision", "form", "seconds_per_call", "ratio_to_builtin"]
COUPLING_COLUMNS = ["n", "backend", "precision", "region", "iterations", "step_us", "exchange_us", "extra_us",
                    "extra_fraction", "bytes_per_exchange", "get_us", "set_us"]
# Force-error bounds per precision (the forces' arithmetic), see the docstring.
FORCE_ERROR_BOUNDS = {"double": (0.0, 1e-10), "mixed": (1e-9, 1e-3), "single": (1e-9, 1e-3)}

problems = []


def run(program, arguments, columns, launcher=()):
    """Runs the program (under launcher, e.g. mpiexec) with --csv and returns its rows as dicts after
    checking the header."""
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "rows.csv")
        command = [*launcher, sys.executable, program] if program.endswith(".py") else [*launcher, program]
        result = subprocess.run([*command, *arguments, "--csv", path], capture_output=True, text=True)
        print(result.stdout, result.stderr, sep="")
        if result.returncode != 0:
            sys.exit(f"{os.path.basename(program)} {' '.join(arguments)} exited with {result.returncode}")
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            if reader.fieldnames != columns:
                sys.exit(f"CSV columns {reader.fieldnames}, expected {columns}")
            return list(reader)


def expect(condition, message):
    if not condition:
        problems.append(message)


def positive_finite(row, key):
    value = float(row[key])
    expect(math.isfinite(value) and value > 0, f"{key} = {row[key]} is not positive and finite in {row}")
    return value


def check_lj(program):
    # --write-input: the liquid of 500 particles as an input, timing nothing.
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "lj.json")
        result = subprocess.run([program, "--n", "500", "--write-input", path], capture_output=True, text=True)
        expect(result.returncode == 0 and result.stdout == "", f"--write-input: {result.returncode} {result.stdout}")
        with open(path) as f:
            document = json.load(f)
        expect(len(document["state"]["data"]) == 500, "--write-input: 500 particles")
        expect("NonBonded" in json.dumps(document["topology"]["forceField"]), "--write-input: the LJ term")
    # The adaptive path (steps per call from a probe) and the fixed one.
    for arguments in (["--seconds", "0.05"], ["--steps", "10"]):
        rows = run(program, ["--n", "500", "--backend", "cpu", "--precision", "single", "--precision", "double",
                             "--pair", "builtin", "--pair", "expression", "--repeats", "3", "--warmup", "5",
                             *arguments], LJ_COLUMNS)
        expect([(row["precision"], row["pair"]) for row in rows] ==
               [("single", "builtin"), ("single", "expression"), ("double", "builtin"), ("double", "expression")],
               f"rows {rows}")
        for row in rows:
            expect(row["n"] == "500" and row["backend"] == "cpu", f"n and backend of {row}")
            steps_per_call = int(row["steps_per_call"])
            expect(steps_per_call >= 1, f"steps_per_call in {row}")
            if arguments[0] == "--steps":
                expect(steps_per_call == 10, f"--steps 10 ran {steps_per_call} per call")
            rate = positive_finite(row, "steps_per_second")
            particle_rate = positive_finite(row, "particle_steps_per_second")
            expect(math.isclose(particle_rate, 500 * rate, rel_tol=1e-4), f"particle-steps/s in {row}")
            builds = float(row["list_builds_per_1000_steps"])
            expect(math.isfinite(builds) and 0 <= builds <= 1000, f"list builds in {row}")
            positive_finite(row, "device_memory_mib")  # this engine reports it, on the CPU backend too
            setup = float(row["setup_seconds"])
            expect(math.isfinite(setup) and setup >= 0, f"setup_seconds in {row}")
            expect(row["scene"] == "lj", f"scene of {row}")
    # The other scenes: 4 and 2 batches of 500 particles; 16 and 9 chains of 100 beads (a square number).
    rows = run(program, ["--n", "2000", "--n", "900", "--backend", "cpu", "--scene", "batches", "--scene", "chains",
                         "--steps", "10", "--repeats", "2", "--warmup", "5"], LJ_COLUMNS)
    expect([(row["scene"], row["n"]) for row in rows] ==
           [("batches", "2000"), ("batches", "1000"), ("chains", "1600"), ("chains", "900")], f"rows {rows}")
    for row in rows:
        positive_finite(row, "particle_steps_per_second")
    # Both pair traversals, in the order asked, each named in its row.
    rows = run(program, ["--n", "4000", "--backend", "cpu", "--traversal", "clusters", "--traversal", "particles",
                         "--steps", "5", "--repeats", "1", "--warmup", "2"], LJ_COLUMNS)
    expect([row["traversal"] for row in rows] == ["clusters", "particles"], f"rows {rows}")
    for row in rows:
        positive_finite(row, "particle_steps_per_second")


def check_transverser(program, plugins):
    """One row per form, the plugins' forms too, the baseline (a step) first with a positive time; the
    others' net times finite (on a loaded machine a small difference may come out negative), and the
    ratio their time over their built-in counterpart's where that is positive (the built-ins' own 0)."""
    arguments = ["--n", "500", "--backend", "cpu", "--precision", "double", "--calls", "5", "--repeats", "3",
                 "--warmup", "1"]
    for plugin in plugins:
        arguments += ["--plugin", plugin]
    rows = run(program, arguments, TRANSVERSER_COLUMNS)
    against = {"expression_lj": "builtin_energy_read", "expression_count": "builtin_energy_read",
               "plugin_count_view": "builtin_energy", "plugin_lj_force_view": "builtin_energy"}
    forms = ["baseline", "builtin_energy", "builtin_energy_read", "expression_lj", "expression_count",
             "plugin_count_view", "plugin_lj_force_view"]
    expect([row["form"] for row in rows] == forms, f"rows {rows}")
    positive_finite(rows[0], "seconds_per_call")
    times = {row["form"]: float(row["seconds_per_call"]) for row in rows}
    expect(all(math.isfinite(t) for t in times.values()), f"times {times}")
    for row in rows[1:]:
        builtin = times.get(against.get(row["form"], ""), 0.0)
        expected = times[row["form"]] / builtin if builtin > 0 else 0.0
        expect(math.isclose(float(row["ratio_to_builtin"]), expected, rel_tol=1e-4, abs_tol=1e-12),
               f"ratio of {row}")


def check_accuracy(program):
    # 500 particles: 3 reference cells per edge. 256 particles (box 6.7): 2 cells per edge, where
    # the adjacent cells repeat and the reference must visit each once.
    cases = [("500", ["single", "mixed", "double"]), ("256", ["double"])]
    for size, precisions in cases:
        arguments = ["--n", size, "--backend", "cpu", "--dt", "0.005", "--skin", "0.3", "--steps", "200",
                     "--samples", "10", "--equilibrate", "0.5"]
        for precision in precisions:
            arguments += ["--precision", precision]
        rows = run(program, arguments, ACCURACY_COLUMNS)
        expect([row["precision"] for row in rows] == precisions, f"rows {rows}")
        for row in rows:
            expect(row["n"] == size and row["backend"] == "cpu" and row["steps"] == "200", f"n, backend, steps of {row}")
            rate = positive_finite(row, "steps_per_second")
            seconds_per_tau = positive_finite(row, "seconds_per_tau")
            expect(math.isclose(seconds_per_tau, 1 / (rate * 0.005), rel_tol=1e-4), f"seconds_per_tau in {row}")
            expect(math.isfinite(float(row["energy_drift"])), f"energy_drift in {row}")
            error = float(row["relative_force_error"])
            low, high = FORCE_ERROR_BOUNDS[row["precision"]]
            expect(low <= error < high, f"{row['precision']} force error {error} outside [{low}, {high})")
            builds = float(row["list_builds_per_1000_steps"])
            expect(math.isfinite(builds) and 0 <= builds <= 1000, f"list builds in {row}")


def check_coupling(program):
    rows = run(program, ["--n", "500", "--backend", "cpu", "--precision", "single", "--precision", "double",
                         "--fraction", "0.02", "--seconds", "0.05", "--repeats", "2", "--warmup", "5"],
               COUPLING_COLUMNS)
    expect([row["precision"] for row in rows] == ["single", "double"], f"rows {rows}")
    for row in rows:
        expect(row["n"] == "500" and row["backend"] == "cpu" and row["region"] == "10", f"n, backend, region of {row}")
        expect(int(row["iterations"]) >= 1, f"iterations in {row}")
        step = positive_finite(row, "step_us")
        exchange = positive_finite(row, "exchange_us")
        expect(math.isclose(float(row["extra_us"]), exchange - step, rel_tol=1e-3, abs_tol=1e-3), f"extra_us in {row}")
        calls = positive_finite(row, "get_us") + positive_finite(row, "set_us")
        expect(calls < exchange, f"the calls' {calls} us exceed the whole iteration's {exchange} us in {row}")
        moved = float(row["bytes_per_exchange"])
        expect(0.9 * 32 * 10 <= moved <= 64 * 10, f"{moved} bytes per exchange of 10 particles in {row}")


def check_hydrodynamics(script):
    # The open-boundary methods against the RPY product the script writes in numpy: exact but for
    # rounding in double precision. The periodic ones against themselves at tolerance 1e-6: within a
    # few times the asked tolerance 1e-3, and not exact (a reference that is the measured run itself
    # would give 0).
    rows = run(script, ["--n", "150", "--backend", "cpu", "--seconds", "0.05", "--reference-max", "200"],
               HYDRODYNAMICS_COLUMNS)
    # The immersed boundary method against the periodic RPY mobility: its kernel's translational
    # invariance (2 %) and radius (0.91 h, 1.5 % off the RPY one in this box) bound it, 10 %.
    # The inertial coupling methods have no one-step reference: their error is left empty. The magnetic
    # force coupling method against the force coupling method's translation at tolerance 1e-6.
    # Dissipative particle dynamics: its kinetic temperature a few per cent over the thermostat's at
    # dt 0.04 (a broken thermostat drifts far from it; 150 particles average to within about 5 %);
    # smoothed particle hydrodynamics has no error column.
    expect([row["method"] for row in rows] == ["cholesky", "lanczos", "fcm", "pse", "fib", "quasi2d", "dpstokes",
                                               "icm", "cicm", "magnetic_fcm", "dpd", "sph"], f"rows {rows}")
    bounds = {"cholesky": (1e-25, 1e-10), "lanczos": (1e-25, 1e-10), "fib": (1e-4, 0.1), "dpd": (-0.05, 0.12)}
    for row in rows:
        positive_finite(row, "steps_per_second")
        if row["method"] in ("icm", "cicm", "sph"):
            expect(row["error"] == "", f"{row['method']} has no error to measure, got {row['error']}")
            continue
        error = float(row["error"])
        bound = bounds.get(row["method"], (1e-7, 1e-2))
        expect(bound[0] < error < bound[1], f"{row['method']} error {error} outside {bound}")


def check_domains(program, launcher):
    arguments = ["--n", "500", "--n", "2048", "--backend", "cpu", "--precision", "double", "--steps", "100",
                 "--repeats", "2", "--warmup", "20"]
    alone = run(program, arguments, DOMAINS_COLUMNS, [*launcher, "-np", "1"])
    split = run(program, arguments, DOMAINS_COLUMNS, [*launcher, "-np", "2"])
    expect([int(row["n"]) for row in split] == [500, 2048], f"rows {split}")
    for one, two in zip(alone, split):
        expect(int(one["ranks"]) == 1 and int(two["ranks"]) == 2, f"ranks in {one}, {two}")
        positive_finite(two, "particle_steps_per_second")
        expect(float(one["domain_rebuilds_per_1000_steps"]) == 0, f"domain rebuilds on one rank in {one}")
        expect(positive_finite(two, "domain_rebuilds_per_1000_steps") > 0, f"no domain rebuild in {two}")
        # The same trajectory to rounding: the drift of the total energy (the unshifted cutoff's
        # jumps, ~1e-3) is the one rank's to many digits.
        drift_one, drift_two = float(one["energy_drift"]), float(two["energy_drift"])
        expect(abs(drift_two - drift_one) < 1e-8, f"energy drift {drift_two} over 2 ranks, {drift_one} on one")


kind, program = sys.argv[1], os.path.abspath(sys.argv[2])
if kind == "domains":
    check_domains(program, sys.argv[3:])
elif kind == "transverser":
    check_transverser(program, [os.path.abspath(plugin) for plugin in sys.argv[3:]])
else:
    {"lj": check_lj, "accuracy": check_accuracy, "coupling": check_coupling,
     "hydrodynamics": check_hydrodynamics}[kind](program)
if problems:
    sys.exit("\n".join(problems))
