#!/usr/bin/env python3
"""structmd's CPU backend against LAMMPS's plain lj/cut on the same Lennard-Jones liquid.

The liquid of structmd_lj_benchmark (fcc at rho 0.8442, T0 1.44, r_c 2.5, skin 0.3, NVE velocity
Verlet, dt 0.005, a list rebuilt once a particle has moved half the skin) run by
`structmd_lj_benchmark --backend cpu` and by LAMMPS (`lmp`, e.g. Debian's `lammps` package) from
an in.lj-style input written here (`neighbor 0.3 bin`, `neigh_modify every 1 delay 0 check yes`,
the same half-skin rule). One thread is OMP_NUM_THREADS=1 and one LAMMPS process; two threads are
OMP_NUM_THREADS=2 and `mpirun -np 2 lmp` (the Debian build has no OPENMP package, so LAMMPS runs
two MPI ranks, its usual way to use two cores).

Runs alternate (structmd, LAMMPS, structmd, LAMMPS, ...) for --rounds rounds and the best of each
is reported, so that a machine shared with other work favours neither. Prints a table of
particle-steps/s and the ratio structmd / LAMMPS.

  tests/benchmarks/cpu_vs_lammps.py --benchmark build/tests/benchmarks/structmd_lj_benchmark \
      --n 4000 --n 32000 --threads 1 --threads 2 --rounds 3
"""
import argparse
import csv
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile

DENSITY = 0.8442
TEMPERATURE = 1.44
CUTOFF = 2.5
TIMESTEP = 0.005


def lammps_input(cells, skin, warmup, steps):
    return f"""# structmd's LJ liquid (tests/benchmarks/lj_liquid.cpp) for LAMMPS
units           lj
atom_style      atomic
lattice         fcc {DENSITY}
region          box block 0 {cells} 0 {cells} 0 {cells}
create_box      1 box
create_atoms    1 box
mass            1 1.0
velocity        all create {TEMPERATURE} 87287 loop geom
pair_style      lj/cut {CUTOFF}
pair_coeff      1 1 1.0 1.0 {CUTOFF}
neighbor        {skin} bin
neigh_modify    every 1 delay 0 check yes
fix             1 all nve
timestep        {TIMESTEP}
thermo          {max(steps, warmup) + 1}
run             {warmup}
run             {steps}
"""


LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
BUILDS = re.compile(r"Neighbor list builds = (\d+)")


def run_lammps(lmp, mpirun, cells, threads, skin, warmup, steps, workdir):
    path = os.path.join(workdir, f"in.lj.{cells}")
    with open(path, "w") as f:
        f.write(lammps_input(cells, skin, warmup, steps))
    command = [lmp, "-in", path, "-log", "none", "-screen", os.path.join(workdir, "screen")]
    if threads > 1:
        command = [mpirun, "-np", str(threads), "--oversubscribe"] + command
    # Open MPI refuses to start as root unless told (containers often run as root).
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(command, check=True, env=env, cwd=workdir, stdout=subprocess.DEVNULL)
    text = open(os.path.join(workdir, "screen")).read()
    loops = LOOP.findall(text)
    builds = BUILDS.findall(text)
    seconds, _, nsteps, atoms = loops[-1]  # the timed run
    rate = int(atoms) * int(nsteps) / float(seconds)
    return rate, int(atoms), 1000.0 * int(builds[-1]) / int(nsteps) if builds else float("nan")


def run_structmd(benchmark, n, threads, precisions, skin, warmup, seconds, repeats, workdir):
    out = os.path.join(workdir, "structmd.csv")
    command = [benchmark, "--backend", "cpu", "--threads", str(threads), "--n", str(n), "--skin", str(skin),
               "--warmup", str(warmup), "--seconds", str(seconds), "--repeats", str(repeats), "--csv", out]
    for p in precisions:
        command += ["--precision", p]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    rows = {}
    with open(out) as f:
        for row in csv.DictReader(f):
            rows[row["precision"]] = (float(row["particle_steps_per_second"]), int(row["n"]),
                                      float(row["list_builds_per_1000_steps"]))
    return rows


def cpu_seconds(command, env, cwd=None):
    """User plus system time of the command (and its children)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True, env=env, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cpu_time_rates(args, n, precisions, workdir):
    """One thread: particle-steps per CPU-second, from two runs of different lengths each (the
    difference cancels set-up and warm-up). On a shared machine this counts the time the process
    ran, not the time it waited for a core."""
    cells = max(1, round((n / 4) ** (1 / 3)))
    atoms = 4 * cells ** 3
    long_steps = max(50, int(args.cpu_seconds * 1.5e6 / atoms))
    short_steps = long_steps // 5
    rates = {}
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for p in precisions:
        seconds = []
        for steps in (short_steps, long_steps):
            seconds.append(cpu_seconds([args.benchmark, "--backend", "cpu", "--threads", "1", "--n", str(n),
                                        "--skin", str(args.skin), "--precision", p, "--warmup", "20",
                                        "--steps", str(steps), "--repeats", "1"], env))
        rates[p] = atoms * (long_steps - short_steps) / (seconds[1] - seconds[0])
    env = dict(env, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    seconds = []
    for steps in (short_steps, long_steps):
        path = os.path.join(workdir, f"in.cpu.{cells}.{steps}")
        with open(path, "w") as f:
            f.write(lammps_input(cells, args.skin, 20, steps))
        seconds.append(cpu_seconds([args.lmp, "-in", path, "-log", "none", "-screen", "none"], env, workdir))
    rates["lammps"] = atoms * (long_steps - short_steps) / (seconds[1] - seconds[0])
    return atoms, rates


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--benchmark", default="build/tests/benchmarks/structmd_lj_benchmark")
    parser.add_argument("--lmp", default=shutil.which("lmp") or "lmp")
    parser.add_argument("--mpirun", default=shutil.which("mpirun") or "mpirun")
    parser.add_argument("--n", type=int, action="append", help="particles (4 k^3); default 4000 and 32000")
    parser.add_argument("--threads", type=int, action="append", help="default 1 and 2")
    parser.add_argument("--precision", action="append", help="default single and double")
    parser.add_argument("--rounds", type=int, default=2, help="alternating rounds; the best is reported")
    parser.add_argument("--skin", type=float, default=0.3)
    parser.add_argument("--warmup", type=int, default=100)
    parser.add_argument("--seconds", type=float, default=1.0, help="structmd: target time of a timed call")
    parser.add_argument("--repeats", type=int, default=3, help="structmd: timed calls (median)")
    parser.add_argument("--lammps-seconds", type=float, default=3.0, help="LAMMPS: about this long a run")
    parser.add_argument("--csv", help="also write the best figures here")
    parser.add_argument("--cpu-time", action="store_true",
                        help="also one thread in particle-steps per CPU-second (for a loaded machine)")
    parser.add_argument("--cpu-time-only", action="store_true", help="--cpu-time without the wall-clock table")
    parser.add_argument("--cpu-seconds", type=float, default=3.0, help="--cpu-time: about this long a run")
    args = parser.parse_args()
    sizes = args.n or [4000, 32000]
    threads = args.threads or [1, 2]
    precisions = args.precision or ["single", "double"]

    best = {}
    args.cpu_time = args.cpu_time or args.cpu_time_only
    with tempfile.TemporaryDirectory() as workdir:
        for round_ in range(0 if args.cpu_time_only else args.rounds):
            for n in sizes:
                cells = max(1, round((n / 4) ** (1 / 3)))
                for t in threads:
                    rows = run_structmd(args.benchmark, n, t, precisions, args.skin, args.warmup, args.seconds,
                                        args.repeats, workdir)
                    for p, (rate, atoms, builds) in rows.items():
                        key = (atoms, t, p)
                        if rate > best.get(key, (0,))[0]:
                            best[key] = (rate, builds)
                    # About lammps-seconds of steps at a rate guessed from 1.5e6 particle-steps/s a core.
                    steps = max(100, int(args.lammps_seconds * 1.5e6 * t / (4 * cells ** 3)))
                    rate, atoms, builds = run_lammps(args.lmp, args.mpirun, cells, t, args.skin, args.warmup, steps,
                                                     workdir)
                    key = (atoms, t, "lammps")
                    if rate > best.get(key, (0,))[0]:
                        best[key] = (rate, builds)
                    print(f"round {round_ + 1}: N={atoms} threads={t}: "
                          + ", ".join(f"{p} {best_rate:.3g}" for p, (best_rate, _, _) in rows.items())
                          + f", lammps {rate:.3g}", file=sys.stderr, flush=True)

    lines = []
    if not args.cpu_time_only:
        header = ["N", "threads"] + [f"structmd {p}" for p in precisions] + ["LAMMPS lj/cut"] + \
                 [f"{p} / LAMMPS" for p in precisions] + ["builds/1000 (structmd, LAMMPS)"]
        print("| " + " | ".join(header) + " |")
        print("| " + " | ".join(["---:"] * len(header)) + " |")
        for n in sorted({k[0] for k in best}):
            for t in threads:
                lam = best.get((n, t, "lammps"), (float("nan"), float("nan")))
                cells = [f"{n:,}", str(t)]
                cells += [f"{best.get((n, t, p), (float('nan'),))[0]:.3g}" for p in precisions]
                cells += [f"{lam[0]:.3g}"]
                cells += [f"{best.get((n, t, p), (float('nan'),))[0] / lam[0]:.2f}x" for p in precisions]
                cells += [f"{best.get((n, t, precisions[0]), (0, float('nan')))[1]:.0f}, {lam[1]:.0f}"]
                print("| " + " | ".join(cells) + " |")
                lines.append([n, t] + [best.get((n, t, p), (float("nan"),))[0] for p in precisions] + [lam[0]])
    if args.cpu_time:
        best_cpu = {}
        with tempfile.TemporaryDirectory() as workdir:
            for round_ in range(args.rounds):
                for n in sizes:
                    atoms, rates = cpu_time_rates(args, n, precisions, workdir)
                    for key, rate in rates.items():
                        best_cpu[(atoms, key)] = max(best_cpu.get((atoms, key), 0.0), rate)
                    print(f"cpu time, round {round_ + 1}: N={atoms}: "
                          + ", ".join(f"{k} {r:.3g}" for k, r in rates.items()), file=sys.stderr, flush=True)
        print()
        print("One thread, particle-steps per CPU-second (best of the rounds):")
        print()
        header = ["N"] + [f"structmd {p}" for p in precisions] + ["LAMMPS lj/cut"] + \
                 [f"{p} / LAMMPS" for p in precisions]
        print("| " + " | ".join(header) + " |")
        print("| " + " | ".join(["---:"] * len(header)) + " |")
        for atoms in sorted({k[0] for k in best_cpu}):
            lam = best_cpu[(atoms, "lammps")]
            cells = [f"{atoms:,}"] + [f"{best_cpu[(atoms, p)]:.3g}" for p in precisions] + [f"{lam:.3g}"]
            cells += [f"{best_cpu[(atoms, p)] / lam:.2f}x" for p in precisions]
            print("| " + " | ".join(cells) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["n", "threads"] + [f"structmd_{p}" for p in precisions] + ["lammps_lj_cut"])
            w.writerows(lines)


if __name__ == "__main__":
    main()
