#!/usr/bin/env python3
"""OpenMM (8.6.1) peer of structmd's Lennard-Jones liquid benchmark.

System (see lj_common.py): fcc start at rho = 0.8442, T0 = 1.44 (Maxwell-Boltzmann, zero total
momentum), LJ 12-6 cut at rc = 2.5, NVE, dt = 0.005, mass 1.

Reduced units -> OpenMM units: sigma = 1 nm, epsilon = 1 kJ/mol, mass = 1 amu, so the time unit
tau = sqrt(m sigma^2 / epsilon) = 1 ps (1 kJ/mol = 1 amu nm^2 / ps^2 exactly) and dt = 0.005 ps.
Velocities are set directly (nm/ps = sigma/tau), so no temperature in kelvin is needed.

Variants (--variant, repeatable; default both):
  custom     CustomNonbondedForce, energy 4*((1/r)^12 - (1/r)^6) - U(rc): the truncated and
             shifted LJ, continuous at rc (the potential the other peers run), CutoffPeriodic,
             no switching, no long-range correction.
  nonbonded  NonbondedForce, charge 0, sigma 1, epsilon 1, CutoffPeriodic, no dispersion
             correction, no switching. NonbondedForce cannot shift the LJ energy: it is truncated
             (not shifted) at rc, so E jumps by ~0.016 epsilon whenever a pair crosses the cutoff.
             Forces are identical to `custom`; only the energy (and so the drift figure) differs.

Integrator: VerletIntegrator (leapfrog; OpenMM reports the kinetic energy at full steps).
Neighbour list: OpenMM's own default (its CUDA platform builds a tile list with its internal padding;
it is not a user setting). No CMMotionRemover is added.

Precision (--precision single|mixed|double) is the CUDA/OpenCL/HIP platform property 'Precision';
CPU and Reference have no such property (CPU computes forces in single precision, Reference in
double) and their rows carry 'cpu' / 'double'.

Timing: the context is created and `--warmup` steps (and one energy evaluation, which compiles the
energy kernels) run untimed; a probe finds the step rate; then `steps = rate x --seconds` are run in
one integrator.step() call, closed by context.getState(getEnergy=True): that read-back waits for the
GPU, and costs one extra force evaluation (negligible against thousands of steps).

--drift TAU: at N = 10,976, after --drift-equilibrate (default 10) time units, runs TAU/dt steps
in chunks of --drift-every steps, reading E = K + U after each, and reports the slope of a
least-squares fit of E/N against t as a `drift` row (see lj_common.py for the CSV columns).

Examples:
  python3 lj_openmm.py --platform CPU --n 864 --seconds 1 --drift 5 --drift-n 864  # local smoke test
  python3 lj_openmm.py --n 10976 --n 62500 --n 1000188 --n 4000000 --precision single --precision mixed
"""

from __future__ import annotations

import ctypes
import glob
import importlib.util
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lj_common as lc  # noqa: E402

ENGINE = "openmm"


def preload_cuda_libraries() -> None:
    """libOpenMMCUDA.so needs libnvrtc.so.13 and libcufft.so.12 and looks for them in its RUNPATH
    ($ORIGIN/../../../nvidia/cu13/lib), i.e. next to the OpenMM wheel. Installed with --target into
    another directory, that misses the nvidia-* wheels of the main environment; loading the libraries
    here (RTLD_GLOBAL) lets the plugin's dlopen find them by soname. OPENMM_CUDA_LIBDIR, if set, is
    searched first."""
    # The system toolkit first (its NVRTC matches the driver there), then the nvidia-* wheels.
    dirs = [os.environ.get("OPENMM_CUDA_LIBDIR", ""), "/usr/local/cuda/lib64",
            "/usr/local/cuda/targets/x86_64-linux/lib"]
    spec = importlib.util.find_spec("nvidia")
    if spec is not None and spec.submodule_search_locations:
        for root in spec.submodule_search_locations:
            dirs += sorted(glob.glob(os.path.join(root, "cu13", "lib")))
            dirs += sorted(glob.glob(os.path.join(root, "*", "lib")))
    dirs += os.environ.get("LD_LIBRARY_PATH", "").split(":")
    dirs = [d for d in dirs if d and os.path.isdir(d)]

    def first(pattern: str, only=None):
        for d in only or dirs:
            hits = sorted(glob.glob(os.path.join(d, pattern)))
            if hits:
                return hits[0]
        return None

    def load(path) -> None:
        if path:
            try:
                ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
                lc.log(f"openmm: preloaded {path}")
            except OSError as error:
                lc.log(f"openmm: could not preload {path}: {error}")

    nvrtc = first("libnvrtc.so.13")
    if nvrtc:  # NVRTC's builtins from the same folder as NVRTC itself
        load(first("libnvrtc-builtins.so.13*", [os.path.dirname(nvrtc)]))
        load(nvrtc)
    load(first("libcufft.so.12"))


def build_system(mm, unit, cells: int, variant: str):
    positions, box = lc.fcc_lattice(cells)
    n = positions.shape[0]
    system = mm.System()
    system.setDefaultPeriodicBoxVectors(mm.Vec3(box, 0, 0), mm.Vec3(0, box, 0), mm.Vec3(0, 0, box))
    for _ in range(n):
        system.addParticle(1.0)
    if variant == "custom":
        # Truncated and shifted LJ: U(r) = 4 (r^-12 - r^-6) - U_LJ(rc) for r < rc, 0 beyond.
        force = mm.CustomNonbondedForce(f"4*(s6*s6 - s6) - {lc.lj_shift()!r}; s6 = (1/r)^6")
        force.setNonbondedMethod(mm.CustomNonbondedForce.CutoffPeriodic)
        force.setCutoffDistance(lc.CUTOFF)
        force.setUseSwitchingFunction(False)
        force.setUseLongRangeCorrection(False)
        for _ in range(n):
            force.addParticle([])
    elif variant == "nonbonded":
        # NB: NonbondedForce has no energy shift: the LJ energy is truncated (discontinuous) at rc.
        force = mm.NonbondedForce()
        force.setNonbondedMethod(mm.NonbondedForce.CutoffPeriodic)
        force.setCutoffDistance(lc.CUTOFF)
        force.setUseDispersionCorrection(False)
        force.setUseSwitchingFunction(False)
        for _ in range(n):
            force.addParticle(0.0, 1.0, 1.0)  # charge 0 e, sigma 1 nm, epsilon 1 kJ/mol
    else:
        raise ValueError(f"unknown variant {variant}")
    system.addForce(force)
    return system, positions, box


def make_context(mm, args, built, variant: str, precision: str):
    system, positions, box = built
    n = positions.shape[0]
    velocities = lc.maxwell_boltzmann(n, seed=args.seed)
    integrator = mm.VerletIntegrator(lc.TIME_STEP)
    platform = mm.Platform.getPlatformByName(args.platform)
    properties = {}
    if args.platform in ("CUDA", "OpenCL", "HIP"):
        properties["Precision"] = precision
        if args.device is not None:
            properties["DeviceIndex"] = str(args.device)
    if args.platform == "CPU" and args.threads:
        properties["Threads"] = str(args.threads)
    context = mm.Context(system, integrator, platform, properties)
    context.setPositions(positions)
    context.setVelocities(velocities)
    lc.log(f"openmm {variant} n={n} box={box:.4f} density={n / box ** 3:.4f} T0={lc.kinetic_temperature(velocities):.4f} "
           f"platform={platform.getName()} "
           + " ".join(f"{k}={platform.getPropertyValue(context, k)}" for k in platform.getPropertyNames()
                      if k in ("Precision", "DeviceIndex", "DeviceName", "Threads")))
    return context, integrator, n


def energies(context, unit, n: int) -> tuple[float, float]:
    state = context.getState(getEnergy=True)
    ke = state.getKineticEnergy().value_in_unit(unit.kilojoule_per_mole)
    pe = state.getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    return ke / n, pe / n


def precision_label(args, precision: str) -> str:
    if args.platform in ("CUDA", "OpenCL", "HIP"):
        return precision
    return {"CPU": "cpu", "Reference": "double"}.get(args.platform, precision)


def throughput(mm, unit, args, built, variant: str, precision: str) -> None:
    t_setup = time.perf_counter()
    context, integrator, n = make_context(mm, args, built, variant, precision)
    k0, u0 = energies(context, unit, n)  # compiles the energy kernels too
    integrator.step(args.warmup)
    k1, u1 = energies(context, unit, n)
    lc.log(f"  setup+warm-up {time.perf_counter() - t_setup:.2f} s; E/N {k0 + u0:.5f} -> {k1 + u1:.5f} "
           f"after {args.warmup} steps (T = {2 * k1 / 3:.4f})")

    def run(k: int) -> None:
        integrator.step(k)
        context.getState(getEnergy=True)

    steps, seconds = lc.timed_run(run, args.seconds)
    k2, u2 = energies(context, unit, n)
    lc.log(f"  timed {steps} steps in {seconds:.3f} s; E/N {k2 + u2:.5f} (T = {2 * k2 / 3:.4f})")
    lc.throughput_row(ENGINE, variant, n, precision_label(args, precision), steps, seconds)


def drift(mm, unit, args, variant: str, precision: str) -> None:
    import numpy as np

    built = build_system(mm, unit, lc.cells_per_edge(args.drift_n), variant)
    context, integrator, n = make_context(mm, args, built, variant, precision)
    integrator.step(lc.equilibration_steps(args))
    every = max(1, args.drift_every)
    samples = max(2, int(round(args.drift / (every * lc.TIME_STEP))))
    times, energy = [], []
    k, u = energies(context, unit, n)
    times.append(0.0)
    energy.append(k + u)
    t0 = time.perf_counter()
    for i in range(1, samples + 1):
        integrator.step(every)
        k, u = energies(context, unit, n)
        times.append(i * every * lc.TIME_STEP)
        energy.append(k + u)
    seconds = time.perf_counter() - t0
    slope = lc.drift_slope(np.array(times), np.array(energy))
    error = force_error(mm, built[0], context)
    lc.log(f"  drift: E/N {energy[0]:.6f} -> {energy[-1]:.6f} over {times[-1]:g} tau, slope {slope:.3e} "
           f"per particle per tau (T end = {2 * k / 3:.4f}); relative force error {error:.3e}")
    lc.drift_row(ENGINE, variant, n, precision_label(args, precision), samples * every, seconds, times[-1], slope,
                 error)


def force_error(mm, system, context) -> float:
    """Relative RMS difference between the context's forces and the Reference platform's (double
    precision) at the context's current positions: sqrt(sum |F - F_ref|^2 / sum |F_ref|^2)."""
    import numpy as np

    state = context.getState(getPositions=True, getForces=True)
    reference = mm.Context(system, mm.VerletIntegrator(lc.TIME_STEP), mm.Platform.getPlatformByName("Reference"))
    reference.setPositions(state.getPositions())
    forces = np.asarray(state.getForces(asNumpy=True)._value, dtype=np.float64)
    exact = np.asarray(reference.getState(getForces=True).getForces(asNumpy=True)._value, dtype=np.float64)
    return float(np.sqrt(np.sum((forces - exact) ** 2) / np.sum(exact ** 2)))


def main() -> int:
    parser = lc.common_parser(__doc__, ["single", "mixed", "double"], "mixed")
    parser.add_argument("--variant", action="append", choices=["custom", "nonbonded"],
                        help="custom and/or nonbonded (repeatable; default both)")
    parser.add_argument("--platform", default="CUDA", choices=["CUDA", "OpenCL", "HIP", "CPU", "Reference"],
                        help="OpenMM platform (default CUDA)")
    parser.add_argument("--device", type=int, default=None, help="DeviceIndex for GPU platforms")
    parser.add_argument("--threads", type=int, default=0, help="threads of the CPU platform")
    args = parser.parse_args()
    lc.resolve(args, "mixed")
    variants = args.variant or ["custom", "nonbonded"]
    precisions = args.precision if args.platform in ("CUDA", "OpenCL", "HIP") else args.precision[:1]

    lc.header(args)
    if args.platform == "CUDA":
        preload_cuda_libraries()
    try:
        import openmm as mm
        from openmm import unit
    except Exception as error:  # noqa: BLE001
        lc.error_row(ENGINE, "-", 0, "-", "import", f"cannot import openmm: {lc.describe(error)}")
        return 2
    names = [mm.Platform.getPlatform(i).getName() for i in range(mm.Platform.getNumPlatforms())]
    lc.log(f"openmm {mm.__version__}, platforms: {', '.join(names)}")
    if args.platform not in names:
        failures = "; ".join(mm.Platform.getPluginLoadFailures())
        lc.error_row(ENGINE, "-", 0, "-", "platform", f"no {args.platform} platform; plugin load failures: {failures}")
        return 2

    failed = 0
    for variant in variants:
        for cells in args.cells:
            try:
                t0 = time.perf_counter()
                built = build_system(mm, unit, cells, variant)  # once for all precisions
                lc.log(f"openmm {variant} n={4 * cells ** 3}: System built in {time.perf_counter() - t0:.2f} s")
            except Exception as error:  # noqa: BLE001
                built = error
            for precision in precisions:
                try:
                    if isinstance(built, Exception):
                        raise built
                    throughput(mm, unit, args, built, variant, precision)
                except Exception as error:  # noqa: BLE001
                    failed += 1
                    lc.error_row(ENGINE, variant, 4 * cells ** 3, precision, "throughput", lc.describe(error))
            built = None
        if args.drift is not None:
            for precision in precisions:
                try:
                    drift(mm, unit, args, variant, precision)
                except Exception as error:  # noqa: BLE001
                    failed += 1
                    lc.error_row(ENGINE, variant, 4 * lc.cells_per_edge(args.drift_n) ** 3, precision, "drift",
                                 lc.describe(error))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
