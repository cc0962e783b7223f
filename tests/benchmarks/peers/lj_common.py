"""Shared pieces of the peer Lennard-Jones benchmarks (lj_openmm.py, lj_gamdpy.py, lj_jaxmd.py).

The system is the one of structmd's tests/benchmarks/lj_liquid.hpp (LAMMPS's bench/in.lj):
fcc lattice, 4 particles per cubic cell, reduced density 0.8442, Maxwell-Boltzmann velocities at
T0 = 1.44 with zero total momentum, LJ 12-6 (epsilon = sigma = mass = 1) cut at 2.5, NVE, dt = 0.005.

Only numpy is needed here, so each peer script imports this module before its engine.

CSV written by every peer script (one header line, then rows):

    engine,variant,n,precision,steps,seconds,steps_per_s,particle_steps_per_s,mode,drift_tau,drift_per_particle_per_tau

The first eight columns are the throughput table. `mode` is `throughput` or `drift` (or
`<mode>-failed`, with empty numbers, for a configuration that failed: the reason is on stderr); the last
two columns are empty on throughput rows. A drift row (from `--drift TAU`) gives the slope of a
least-squares line through E_total/N against time, over TAU time units that follow
--drift-equilibrate (default 10) untimed time units from the lattice start, in epsilon per particle
per tau; its steps/seconds columns are those of the drift run (energy read-backs included).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time

import numpy as np

DENSITY = 0.8442
TEMPERATURE = 1.44
CUTOFF = 2.5
TIME_STEP = 0.005
DRIFT_N = 10_976  # 4 * 14^3

CSV_HEADER = ("engine,variant,n,precision,steps,seconds,steps_per_s,particle_steps_per_s,"
              "mode,drift_tau,drift_per_particle_per_tau,relative_force_error")


def log(*args) -> None:
    """Diagnostics go to stderr, so stdout stays pure CSV."""
    print(*args, file=sys.stderr, flush=True)


def cells_per_edge(requested: int) -> int:
    """fcc cells per edge whose 4 k^3 is nearest to the requested count (as lj_liquid.cpp)."""
    return max(1, int(round((requested / 4.0) ** (1.0 / 3.0))))


def fcc_lattice(cells: int, density: float = DENSITY) -> tuple[np.ndarray, float]:
    """Positions (float64, in [0, L)) of a cubic fcc lattice of cells^3 cells, and the box edge L."""
    lattice = (4.0 / density) ** (1.0 / 3.0)
    basis = np.array([[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]])
    grid = np.stack(np.meshgrid(np.arange(cells), np.arange(cells), np.arange(cells), indexing="ij"),
                    axis=-1).reshape(-1, 1, 3)
    positions = ((grid + basis[None, :, :]) * lattice).reshape(-1, 3)
    return positions, lattice * cells


def maxwell_boltzmann(n: int, temperature: float = TEMPERATURE, mass: float = 1.0,
                      seed: int = 1) -> np.ndarray:
    """Gaussian velocities, total momentum removed, rescaled so that the kinetic temperature over
    3N - 3 degrees of freedom is exactly `temperature` (k_B = 1)."""
    rng = np.random.default_rng(seed)
    v = rng.normal(0.0, math.sqrt(temperature / mass), size=(n, 3))
    v -= v.mean(axis=0)
    t_now = mass * np.sum(v * v) / (3 * n - 3)
    v *= math.sqrt(temperature / t_now)
    return v


def kinetic_temperature(v: np.ndarray, mass: float = 1.0) -> float:
    n = v.shape[0]
    return float(mass * np.sum(np.asarray(v, dtype=np.float64) ** 2) / (3 * n - 3))


def lj_shift() -> float:
    """U_LJ(rc), subtracted so that the truncated potential is continuous at the cutoff."""
    ir6 = CUTOFF ** -6
    return 4.0 * (ir6 * ir6 - ir6)


def sizes_from_args(requested: list[int] | None) -> list[int]:
    """Requested N values rounded to fcc 4 n^3, deduplicated, order kept."""
    out: list[int] = []
    for n in requested or []:
        k = cells_per_edge(n)
        if k not in out:
            out.append(k)
    return out


def drift_slope(times: np.ndarray, energy_per_particle: np.ndarray) -> float:
    """Slope of the least-squares line through E/N against t (epsilon per particle per tau)."""
    t = np.asarray(times, dtype=np.float64)
    e = np.asarray(energy_per_particle, dtype=np.float64)
    if t.size < 2:
        return float("nan")
    return float(np.polyfit(t, e, 1)[0])


def equilibration_steps(args) -> int:
    return max(0, int(round(args.drift_equilibrate / TIME_STEP)))


def steps_for(rate_steps_per_s: float, seconds: float, minimum: int = 1) -> int:
    return max(minimum, int(math.ceil(rate_steps_per_s * seconds)))


def calibrate(run_steps, seconds: float, start: int = 10, min_probe: float = 0.2) -> float:
    """Runs run_steps(k) (which must return only when the k steps are done) for k = start, 2 start,
    ... until one call takes at least min(min_probe, seconds / 4) s; returns that call's rate."""
    target = min(min_probe, max(seconds / 4.0, 0.01))
    k = max(1, start)
    while True:
        t0 = time.perf_counter()
        run_steps(k)
        elapsed = time.perf_counter() - t0
        if elapsed >= target or k >= 1 << 30:
            return k / max(elapsed, 1e-9)
        k *= 2 if elapsed > target / 8 else 8


def timed_run(run_steps, seconds: float, attempts: int = 3) -> tuple[int, float]:
    """Times run_steps(k) for about `seconds`: k from a probe (calibrate), and again with the rate the
    timed call showed if it took less than half of `seconds` (a slow probe call, e.g. a list
    re-allocation or a reorder, would otherwise leave a window too short to trust). Returns (k, s)."""
    rate = calibrate(run_steps, seconds)
    for _ in range(attempts):
        steps = steps_for(rate, seconds)
        t0 = time.perf_counter()
        run_steps(steps)
        elapsed = time.perf_counter() - t0
        if elapsed >= 0.5 * seconds:
            break
        rate = steps / max(elapsed, 1e-9)
    return steps, elapsed


def run_variants(engine: str, variants, cells_list, precision: str, throughput, drift=None,
                 drift_n: int = 0) -> int:
    """throughput(variant, cells) for every size of every variant, then drift(variant) if given; a
    failure becomes an error row and the rest still run. Returns the exit status (1 if any failed)."""
    failed = 0
    for variant in variants:
        for cells in cells_list:
            try:
                throughput(variant, cells)
            except Exception as error:  # noqa: BLE001
                failed += 1
                error_row(engine, variant, 4 * cells ** 3, precision, "throughput", describe(error))
        if drift is not None:
            try:
                drift(variant)
            except Exception as error:  # noqa: BLE001
                failed += 1
                error_row(engine, variant, 4 * cells_per_edge(drift_n) ** 3, precision, "drift", describe(error))
    return 1 if failed else 0


def common_parser(description: str, precisions: list[str], default_precision: str) -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description=description,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, action="append", metavar="N",
                   help="particle count, rounded to fcc 4 n^3 (repeatable; default 10976 unless only --drift)")
    p.add_argument("--precision", action="append", choices=precisions, metavar="P",
                   help=f"one of {', '.join(precisions)} (repeatable; default {default_precision})")
    p.add_argument("--seconds", type=float, default=2.0, help="target timed seconds per size (default 2)")
    p.add_argument("--warmup", type=int, default=200,
                   help="untimed steps after compilation/allocation, before calibration (default 200)")
    p.add_argument("--drift", type=float, metavar="TAU", default=None,
                   help=f"also measure the energy drift over TAU time units at N = {DRIFT_N}")
    p.add_argument("--drift-n", type=int, default=DRIFT_N,
                   help=f"particle count of the drift run (default {DRIFT_N}; smaller for a quick local test)")
    p.add_argument("--drift-equilibrate", type=float, default=10.0, metavar="T",
                   help="untimed, unfitted time units before the drift run (default 10 tau, as "
                        "structmd_accuracy_benchmark --equilibrate)")
    p.add_argument("--drift-every", type=int, default=100,
                   help="steps between energy samples in --drift mode (default 100 = 0.5 tau)")
    p.add_argument("--seed", type=int, default=1, help="velocity seed (default 1)")
    p.add_argument("--no-header", action="store_true", help="do not print the CSV header line")
    return p


def resolve(args, default_precision: str) -> None:
    if not args.precision:
        args.precision = [default_precision]
    if not args.n and args.drift is None:
        args.n = [DRIFT_N]
    args.cells = sizes_from_args(args.n)


def header(args) -> None:
    if not args.no_header:
        print(CSV_HEADER, flush=True)


def throughput_row(engine: str, variant: str, n: int, precision: str, steps: int, seconds: float) -> None:
    rate = steps / seconds
    print(f"{engine},{variant},{n},{precision},{steps},{seconds:.6f},{rate:.6g},{rate * n:.6g},throughput,,,",
          flush=True)


def drift_row(engine: str, variant: str, n: int, precision: str, steps: int, seconds: float,
              tau: float, slope: float, force_error: float | None = None) -> None:
    """force_error: the relative RMS force error at the run's last configuration, where measured."""
    rate = steps / seconds
    error = "" if force_error is None else f"{force_error:.6e}"
    print(f"{engine},{variant},{n},{precision},{steps},{seconds:.6f},{rate:.6g},{rate * n:.6g},drift,"
          f"{tau:g},{slope:.6e},{error}", flush=True)


def describe(error: BaseException) -> str:
    """One line for an exception: its type and message, colour codes and newlines removed."""
    text = re.sub(r"\x1b\[[0-9;]*m", "", f"{type(error).__name__}: {error}")
    return " ".join(text.split())


def error_row(engine: str, variant: str, n: int, precision: str, mode: str, message: str) -> None:
    """A failed configuration: logged on stderr, and a CSV row with empty numbers (so a table keeps it)."""
    message = re.sub(r"\x1b\[[0-9;]*m", "", message)
    if len(message) > 600:
        message = message[:600] + " ..."
    log(f"{engine} {variant} n={n} {precision} {mode}: FAILED: {message}")
    print(f"{engine},{variant},{n},{precision},,,,,{mode}-failed,,,", flush=True)
