#!/usr/bin/env python3
"""JAX MD (jax-md 0.2.29) peer of structmd's Lennard-Jones liquid benchmark.

System (see lj_common.py): fcc start at rho = 0.8442, T0 = 1.44 (Maxwell-Boltzmann, zero total
momentum), LJ 12-6 (epsilon = sigma = mass = 1) cut at rc = 2.5, NVE (simulate.nve: velocity
Verlet), dt = 0.005, space.periodic box.

Variants (--variant, repeatable; default both):
  shifted   the potential the other peers run: energy.lennard_jones truncated and shifted at rc
            (U(rc) = 0), promoted with smap.pair_neighbor_list over the same neighbour list that
            energy.lennard_jones_neighbor_list builds.
  switched  energy.lennard_jones_neighbor_list exactly as shipped: LJ multiplied by JAX MD's C1
            switching function from r_onset = 2.0 to r_cutoff = 2.5 (HOOMD's XPLOR-like form). Same
            list, same cost per pair, slightly different potential.
Both use JAX MD's own neighbour-list defaults: partition.neighbor_list with r_cutoff 2.5,
dr_threshold (skin) 0.5, capacity_multiplier 1.25, cell list on, format OrderedSparse (each pair once).

Stepping: one jitted function runs `steps` steps as lax.fori_loop(0, steps, body) where body does
`nbrs = nbrs.update(state.position); state = apply_fn(state, neighbor=nbrs)` (JAX MD's documented
loop). The list is allocated from the lattice, and again (neighbor_fn.allocate, default capacity) from
the melted liquid after the warm-up. After every call, if nbrs.did_buffer_overflow (list or cell
list full) the call's steps are discarded, the list is re-allocated from the positions before the call
with extra_capacity (4, then doubled) and the steps are repeated; overflows in the timed call are
logged on stderr (none expected: the list was sized for the liquid).

Precision: single (float32, JAX's default) or double (jax_enable_x64 and float64 arrays). x64 is a
process-wide switch, so when both are asked for the script runs itself once per precision.

Timing: allocation, compilation and `--warmup` steps are untimed; a probe finds the step rate; then
`steps = rate x --seconds` run in one call, closed by block_until_ready on the positions (the step
count is a traced argument, so the timed call reuses the compiled loop).

--drift TAU: at N = 10,976, after --drift-equilibrate (default 10) time units, runs TAU/dt steps
in calls of --drift-every steps, computing E = K + U after each (K from the momenta, U from the
energy function), and reports the slope of a least-squares fit of E/N against t as a `drift` row (see
lj_common.py).

Examples:
  JAX_PLATFORMS=cpu python3 lj_jaxmd.py --n 864 --seconds 1 --drift 5 --drift-n 864   # local smoke test
  python3 lj_jaxmd.py --n 10976 --n 62500 --n 1000188 --n 4000000 --precision single
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
import warnings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lj_common as lc  # noqa: E402

ENGINE = "jax-md"
DR_THRESHOLD = 0.5          # lennard_jones_neighbor_list's default skin
CAPACITY_MULTIPLIER = 1.25  # partition.neighbor_list's default


class Runner:
    def __init__(self, jax, variant: str, cells: int, dtype, seed: int):
        from jax import jit, lax, random
        from jax import numpy as jnp
        from jax_md import energy, partition, quantity, simulate, smap, space

        self.jax = jax
        # A list whose static metadata holds arrays (lennard_jones_neighbor_list's cutoff is a jax array)
        # cannot be compared with the cached traces of another variant: start from empty caches.
        jax.clear_caches()
        positions, box = lc.fcc_lattice(cells)
        self.n = positions.shape[0]
        velocities = lc.maxwell_boltzmann(self.n, seed=seed)
        lc.log(f"jax-md {variant} n={self.n} box={box:.4f} density={self.n / box ** 3:.4f} "
               f"T0={lc.kinetic_temperature(velocities):.4f} dtype={jnp.dtype(dtype).name} device={jax.devices()[0]}")
        box_j = jnp.asarray(box, dtype=dtype)
        displacement, shift = space.periodic(box_j)
        if variant == "switched":
            neighbor_fn, energy_fn = energy.lennard_jones_neighbor_list(
                displacement, box_j, sigma=1.0, epsilon=1.0, r_cutoff=lc.CUTOFF)
        elif variant == "shifted":
            u_cut = lc.lj_shift()
            rc = lc.CUTOFF

            def shifted_lj(dr, sigma=1.0, epsilon=1.0, **unused):
                u = energy.lennard_jones(dr, sigma, epsilon) - u_cut
                return jnp.where(dr < rc, u, jnp.zeros_like(u))

            neighbor_fn = partition.neighbor_list(
                displacement, box_j, rc, DR_THRESHOLD, capacity_multiplier=CAPACITY_MULTIPLIER,
                format=partition.OrderedSparse)
            energy_fn = smap.pair_neighbor_list(
                shifted_lj, space.canonicalize_displacement_or_metric(displacement),
                ignore_unused_parameters=True, sigma=1.0, epsilon=1.0)
        else:
            raise ValueError(f"unknown variant {variant}")

        init_fn, apply_fn = simulate.nve(energy_fn, shift, dt=lc.TIME_STEP)
        r0 = jnp.asarray(positions, dtype=dtype)
        self.neighbor_fn = neighbor_fn
        self.nbrs = neighbor_fn.allocate(r0)
        self.state = init_fn(random.PRNGKey(seed), r0, kT=lc.TEMPERATURE, mass=1.0,
                             momenta=jnp.asarray(velocities, dtype=dtype), neighbor=self.nbrs)
        self.reallocations = 0
        self.extra_capacity = 0

        def body(i, carry):
            state, nbrs = carry
            nbrs = nbrs.update(state.position)
            state = apply_fn(state, neighbor=nbrs)
            return state, nbrs

        @jit
        def run(state, nbrs, steps):
            return lax.fori_loop(0, steps, body, (state, nbrs))

        @jit
        def total_energy(state, nbrs):
            return (energy_fn(state.position, neighbor=nbrs)
                    + quantity.kinetic_energy(momentum=state.momentum, mass=state.mass))

        self._run = run
        self._energy = total_energy
        self._kinetic = jit(lambda s: quantity.kinetic_energy(momentum=s.momentum, mass=s.mass))

    def run(self, steps: int) -> None:
        """steps steps, synchronised. If the list (or its cell list) overflowed during them, the steps
        are thrown away, the list is re-allocated from the positions before them with more room
        (extra_capacity, doubled each time it is needed again) and the steps are repeated."""
        while True:
            state, nbrs = self._run(self.state, self.nbrs, steps)
            state.position.block_until_ready()
            if not bool(nbrs.did_buffer_overflow):
                self.state, self.nbrs = state, nbrs
                return
            self.reallocations += 1
            self.extra_capacity = max(4, 2 * self.extra_capacity)
            self.nbrs = self.neighbor_fn.allocate(self.state.position, extra_capacity=self.extra_capacity)
            lc.log(f"  neighbour list overflow ({nbrs.error}): re-allocated with extra_capacity "
                   f"{self.extra_capacity} (pairs {self.capacity()})")

    def reallocate(self) -> None:
        """A fresh list from the current positions at JAX MD's default capacity (1.25 x occupancy)."""
        self.extra_capacity = 0
        self.nbrs = self.neighbor_fn.allocate(self.state.position)

    def capacity(self) -> int:
        idx = self.nbrs.idx
        return int(idx.shape[-1])

    def energy_per_particle(self) -> float:
        # The list must be current for these positions: update it (no overflow expected right after a run).
        self.nbrs = self.nbrs.update(self.state.position)
        return float(self._energy(self.state, self.nbrs)) / self.n

    def temperature(self) -> float:
        return 2.0 * float(self._kinetic(self.state)) / (3 * self.n - 3)


def throughput(jax, dtype, args, cells: int, variant: str, precision: str) -> None:
    t_setup = time.perf_counter()
    runner = Runner(jax, variant, cells, dtype, args.seed)
    e0 = runner.energy_per_particle()
    runner.run(args.warmup)  # compiles the loop (steps is traced, so once) and melts the lattice
    runner.reallocate()  # size the list for the liquid, not the lattice
    runner.run(10)
    e1 = runner.energy_per_particle()
    lc.log(f"  setup+compile+warm-up {time.perf_counter() - t_setup:.2f} s; E/N {e0:.5f} -> {e1:.5f} after "
           f"{args.warmup} steps (T = {runner.temperature():.4f}); list capacity {runner.capacity()}")
    before = runner.reallocations
    steps, seconds = lc.timed_run(runner.run, args.seconds)
    e2 = runner.energy_per_particle()
    lc.log(f"  timed {steps} steps in {seconds:.3f} s; E/N {e2:.5f} (T = {runner.temperature():.4f}); "
           f"re-allocations while probing and timing: {runner.reallocations - before}")
    lc.throughput_row(ENGINE, variant, runner.n, precision, steps, seconds)


def drift(jax, dtype, args, variant: str, precision: str) -> None:
    import numpy as np

    runner = Runner(jax, variant, lc.cells_per_edge(args.drift_n), dtype, args.seed)
    runner.run(lc.equilibration_steps(args))
    runner.reallocate()
    every = max(1, args.drift_every)
    samples = max(2, int(round(args.drift / (every * lc.TIME_STEP))))
    times, energy = [0.0], [runner.energy_per_particle()]
    t0 = time.perf_counter()
    for i in range(1, samples + 1):
        runner.run(every)
        times.append(i * every * lc.TIME_STEP)
        energy.append(runner.energy_per_particle())
    seconds = time.perf_counter() - t0
    slope = lc.drift_slope(np.array(times), np.array(energy))
    lc.log(f"  drift: E/N {energy[0]:.6f} -> {energy[-1]:.6f} over {times[-1]:g} tau, slope {slope:.3e} "
           f"per particle per tau (T end = {runner.temperature():.4f})")
    lc.drift_row(ENGINE, variant, runner.n, precision, samples * every, seconds, times[-1], slope)


def main() -> int:
    parser = lc.common_parser(__doc__, ["single", "double"], "single")
    parser.add_argument("--variant", action="append", choices=["shifted", "switched"],
                        help="shifted and/or switched (repeatable; default both)")
    args = parser.parse_args()
    lc.resolve(args, "single")
    variants = args.variant or ["shifted", "switched"]

    if len(args.precision) > 1:  # x64 is process-wide: one child process per precision
        lc.header(args)
        status = 0
        for i, precision in enumerate(args.precision):
            argv = [a for a in sys.argv[1:]]
            cleaned, skip = [], False
            for a in argv:
                if skip:
                    skip = False
                    continue
                if a == "--precision":
                    skip = True
                    continue
                if a.startswith("--precision="):
                    continue
                cleaned.append(a)
            cmd = [sys.executable, os.path.abspath(__file__), *cleaned, "--precision", precision, "--no-header"]
            sys.stdout.flush()
            status |= subprocess.call(cmd)
        return status

    precision = args.precision[0]
    lc.header(args)
    # jax_md asks for float64 reductions that JAX truncates to float32 without x64: expected, not news.
    warnings.filterwarnings("ignore", message="Explicitly requested dtype")
    try:
        import jax
        if precision == "double":
            jax.config.update("jax_enable_x64", True)
        from jax import numpy as jnp
        import jax_md  # noqa: F401
    except Exception as error:  # noqa: BLE001
        lc.error_row(ENGINE, "-", 0, precision, "import", f"cannot import jax / jax_md: {lc.describe(error)}")
        return 2
    dtype = jnp.float64 if precision == "double" else jnp.float32
    try:
        from importlib.metadata import version
        jax_md_version = version("jax-md")
    except Exception:  # noqa: BLE001
        jax_md_version = "?"
    lc.log(f"jax {jax.__version__}, jax_md {jax_md_version}, devices {jax.devices()}")

    return lc.run_variants(
        ENGINE, variants, args.cells, precision,
        lambda variant, cells: throughput(jax, dtype, args, cells, variant, precision),
        (lambda variant: drift(jax, dtype, args, variant, precision)) if args.drift is not None else None,
        args.drift_n)


if __name__ == "__main__":
    sys.exit(main())
