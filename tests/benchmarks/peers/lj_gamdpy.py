#!/usr/bin/env python3
"""gamdpy (0.8.3) peer of structmd's Lennard-Jones liquid benchmark. gamdpy runs on an NVIDIA GPU
through numba.cuda (numba-cuda), in single precision (float32) only.

System (see lj_common.py): fcc start at rho = 0.8442 (gp.Configuration.make_lattice with
gp.unit_cells.FCC), T0 = 1.44 (lj_common's Maxwell-Boltzmann velocities, zero total momentum), mass 1,
LJ 12-6 truncated and shifted at rc = 2.5 (gp.apply_shifted_potential_cutoff(gp.LJ_12_6_sigma_epsilon),
params [sigma, epsilon, cut] = [1, 1, 2.5]), gp.integrators.NVE (leapfrog), dt = 0.005.

The set-up is gamdpy's own LJ benchmark (benchmarks/benchmark_LJ.py of the gamdpy repository):
gp.Simulation with gp.get_default_compute_plan (chosen from N and the GPU: particles per block 'pb',
threads per particle 'tp', 'gridsync' = one persistent kernel for all steps where N is small,
Newton's third law ('UtilizeNIII') from N >= 16k, 'N squared' neighbour-list build up to N = 8000 and
'linked lists' beyond, skin 0.5 (1.0 for 6k < N <= 8k)) and max_num_nbs = 500. No runtime actions in
the throughput runs (no trajectory, scalar or momentum-reset output); the kernels still accumulate
gamdpy's default compute_flags U, W and K per particle (they can only be switched off through a
runtime action's compute_flags, which would add a kernel of its own).

Variants (--variant, repeatable; default `default`):
  default    the default compute plan, as above.
  autotuned  the same after sim.autotune() (gamdpy's documented tuner of pb, tp, skin, gridsync,
             UtilizeNIII and nblist; it compiles many kernels and can take minutes per size).

Timing: building the Simulation compiles the kernels and runs one test step; `--warmup` steps follow
(sim.integrate_self), untimed; a probe finds the step rate; then `steps = rate x --seconds` run in one
sim.integrate_self(0, steps) call, followed by numba.cuda.synchronize(). integrate_self is the inner
call of sim.run_timeblocks() (which adds a host copy of the configuration and the savers' output per
block) and the call gamdpy's autotuner times. The neighbour list is checked afterwards
(check_datastructure_validity), and its number of rebuilds (nbflag[2]) is logged.

--drift TAU: at N = 10,976, after --drift-equilibrate (default 10) time units, runs
sim.run_timeblocks() with a gp.ScalarSaver every --drift-every steps, reads U and K with
gp.extract_scalars, and reports the slope of a least-squares fit of (U + K)/N against t as a `drift`
row (see lj_common.py). K is gamdpy's leapfrog kinetic energy at integer steps (the mean of the two
half-step velocities, squared).

Example (GPU only: numba's CUDA simulator, NUMBA_ENABLE_CUDASIM=1, cannot type gamdpy's kernels):
  python3 lj_gamdpy.py --n 10976 --n 62500 --n 1000188 --n 4000000
"""

from __future__ import annotations

import math
import os
import sys
import time

os.environ.setdefault("NUMBA_CUDA_LOW_OCCUPANCY_WARNINGS", "0")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lj_common as lc  # noqa: E402

ENGINE = "gamdpy"


def make_simulation(gp, np, args, cells: int, runtime_actions, num_timeblocks: int, steps_per_timeblock: int):
    configuration = gp.Configuration(D=3)
    configuration.make_lattice(gp.unit_cells.FCC, cells=[cells, cells, cells], rho=lc.DENSITY)
    configuration["m"] = 1.0
    n = configuration.N
    velocities = lc.maxwell_boltzmann(n, seed=args.seed)
    configuration["v"] = velocities.astype(np.float32)
    lengths = np.asarray(configuration.simbox.get_lengths(), dtype=np.float64)
    lc.log(f"gamdpy n={n} box={lengths[0]:.4f} density={n / np.prod(lengths):.4f} "
           f"T0={lc.kinetic_temperature(configuration['v']):.4f}")

    pair_func = gp.apply_shifted_potential_cutoff(gp.LJ_12_6_sigma_epsilon)
    pair_pot = gp.PairPotential(pair_func, params=[1.0, 1.0, lc.CUTOFF], max_num_nbs=args.max_num_nbs)
    integrator = gp.integrators.NVE(dt=lc.TIME_STEP)
    sim = gp.Simulation(configuration, [pair_pot], integrator, runtime_actions,
                        num_timeblocks=num_timeblocks, steps_per_timeblock=steps_per_timeblock,
                        storage="memory")
    return sim, pair_pot, n


def host_energy(sim, n: int) -> tuple[float, float]:
    """(K/N, U/N) of the configuration on the device (K from the last integration step)."""
    sim.configuration.copy_to_host()
    c = sim.configuration
    return float(c["K"].astype("float64").sum()) / n, float(c["U"].astype("float64").sum()) / n


def throughput(gp, np, cuda, args, cells: int, variant: str) -> None:
    t_setup = time.perf_counter()
    sim, pair_pot, n = make_simulation(gp, np, args, cells, [], 1, max(1, args.warmup))
    if variant == "autotuned":
        sim.autotune()
    lc.log(f"  compute plan: {sim.compute_plan}")

    def run(k: int) -> None:
        sim.integrate_self(0.0, k)
        cuda.synchronize()

    run(args.warmup)
    k1, u1 = host_energy(sim, n)
    lc.log(f"  setup+compile+warm-up {time.perf_counter() - t_setup:.2f} s; E/N {k1 + u1:.5f} after "
           f"{args.warmup} steps (T = {2 * k1 / 3:.4f})")
    builds_before = int(pair_pot.nblist.d_nbflag.copy_to_host()[2])
    steps, seconds = lc.timed_run(run, args.seconds)
    pair_pot.check_datastructure_validity()
    builds = int(pair_pot.nblist.d_nbflag.copy_to_host()[2]) - builds_before
    k2, u2 = host_energy(sim, n)
    lc.log(f"  timed {steps} steps in {seconds:.3f} s; E/N {k2 + u2:.5f} (T = {2 * k2 / 3:.4f}); "
           f"neighbour-list builds while probing and timing: {builds}")
    lc.throughput_row(ENGINE, variant, n, "single", steps, seconds)


def drift(gp, np, cuda, args, variant: str) -> None:
    every = max(1, args.drift_every)
    samples = max(2, int(round(args.drift / (every * lc.TIME_STEP))))
    per_block = min(samples, 64)
    blocks = int(math.ceil(samples / per_block))
    saver = gp.ScalarSaver(steps_between_output=every)
    sim, pair_pot, n = make_simulation(gp, np, args, lc.cells_per_edge(args.drift_n), [saver], blocks,
                                       every * per_block)
    if variant == "autotuned":
        sim.autotune()
    # Warm up from the lattice, then hand the melted state to run_timeblocks (which starts from the host copy).
    sim.integrate_self(0.0, lc.equilibration_steps(args))
    cuda.synchronize()
    sim.configuration.copy_to_host()
    t0 = time.perf_counter()
    for _ in sim.run_timeblocks():
        pass
    seconds = time.perf_counter() - t0
    pair_pot.check_datastructure_validity()
    u, k = gp.extract_scalars(sim.output, ["U", "K"])
    e = (np.asarray(u, dtype=np.float64) + np.asarray(k, dtype=np.float64)) / n
    times = np.arange(e.size) * every * lc.TIME_STEP
    slope = lc.drift_slope(times, e)
    lc.log(f"  drift: E/N {e[0]:.6f} -> {e[-1]:.6f} over {times[-1]:g} tau, slope {slope:.3e} per particle per tau "
           f"(T end = {2 * float(k[-1]) / (3 * n - 3):.4f})")
    lc.drift_row(ENGINE, variant, n, "single", blocks * per_block * every, seconds,
                 blocks * per_block * every * lc.TIME_STEP, slope)


def main() -> int:
    parser = lc.common_parser(__doc__, ["single"], "single")
    parser.add_argument("--variant", action="append", choices=["default", "autotuned"],
                        help="default and/or autotuned (repeatable; default: default)")
    parser.add_argument("--max-num-nbs", type=int, default=500,
                        help="neighbour-list slots per particle (default 500, as gamdpy's LJ benchmark)")
    args = parser.parse_args()
    lc.resolve(args, "single")
    variants = args.variant or ["default"]

    lc.header(args)
    try:
        import numpy as np
        from numba import cuda
        if not hasattr(np, "row_stack"):  # gamdpy 0.8.3 calls it; NumPy 2 removed it (an alias of vstack)
            np.row_stack = np.vstack
        import gamdpy as gp
    except Exception as error:  # noqa: BLE001
        lc.error_row(ENGINE, "-", 0, "single", "import", f"cannot import gamdpy / numba.cuda: {lc.describe(error)}")
        return 2
    try:
        import numba
        numba.config.CUDA_LOW_OCCUPANCY_WARNINGS = False
        if os.environ.get("NUMBA_ENABLE_CUDASIM") == "1":
            device = "CUDA simulator"
        else:
            device = cuda.get_current_device().name
            device = device.decode() if isinstance(device, bytes) else device
        lc.log(f"gamdpy {gp.__version__}, numba {numba.__version__}, device {device}")
    except Exception as error:  # noqa: BLE001
        lc.error_row(ENGINE, "-", 0, "single", "device", f"no CUDA device for numba: {lc.describe(error)}")
        return 2

    return lc.run_variants(
        ENGINE, variants, args.cells, "single",
        lambda variant, cells: throughput(gp, np, cuda, args, cells, variant),
        (lambda variant: drift(gp, np, cuda, args, variant)) if args.drift is not None else None, args.drift_n)


if __name__ == "__main__":
    sys.exit(main())
