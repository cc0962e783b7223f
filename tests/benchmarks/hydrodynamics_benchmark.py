#!/usr/bin/env python3
"""Run time against size and error of the hydrodynamic integrators (issue 15): for each method and
size, steps per second of a thermal run (noise drawn every step, a constant random force on every
particle, nothing read back between steps) and the error of the deterministic displacement dt M F.

System: N spheres of radius 1 at random positions at volume fraction 0.05 (overlaps allowed: the RPY
mobility is defined for them), viscosity 1, kT 1, dt 0.01; a cubic box of side (4 pi N / 3 / 0.05)^(1/3),
periodic for the periodic methods, a cube the particles start in for the open-boundary ones; the
planar method (Quasi2D) puts them in the plane z = 0 of a square of side (pi N / 0.05)^(1/2), at area
fraction 0.05.

Error, relative RMS of dt M F over the particles, in double precision at the method's tolerance, against:
- open boundary: the dense RPY product written here in numpy (Zuk et al. 2014, equal radii), for
  every size;
- triply periodic: the same method in double precision at tolerance 1e-6 (the method's converged
  mobility, which tests/python/test_bdhi_*.py check against independent Ewald and lattice sums), at the
  sizes up to --reference-max;
- the fluctuating immersed boundary method (fib), which has no tolerance (its 3-point kernel gives a
  radius of 0.91 grid spacings, the grid's closest to RADIUS, and a mobility that changes by about
  2 % with where a particle is in its cell): positively split Ewald's periodic RPY mobility at
  tolerance 1e-6 for that radius, up to --reference-max;
- the slab (DPStokes, two walls 16 radii apart, particles at least 2 radii from them, grid spacing
  sigma = a / sqrt(pi) or a little less, the grid's size rounded up to one with factors 2, 3, 5 and 7
  alone): the same method on a grid of about half that spacing at tolerance 1e-6 (the tolerance cuts
  its Gaussian as well as the noise's Lanczos iteration), up to --reference-max;
- the magnetic force coupling method (magnetic_fcm: moments along z, no field, so no torque): the force
  coupling method's translation at tolerance 1e-6, up to --reference-max;
- the inertial coupling method (icm, fluid density 1): none. A particle moves with the fluid, whose
  momentum the force builds up over many steps, so one step's displacement is not dt M F;
  tests/python/test_fluctuating_hydrodynamics.py checks its long-time mobility (Hasimoto's periodic
  correction) and its equipartition instead.
- the compressible inertial coupling method (cicm, fluid density 1, speed of sound 4, bulk viscosity 1):
  none, for the same reason; tests/python/test_compressible_inertial_coupling.py checks a pulled
  particle against the linearised equations, its equipartition and its long-time diffusion, and
  tests/hydrodynamics/test_compressible_fluid.cpp the sound speed and the density structure factor.
Lanczos is exact in its deterministic part; its tolerance bounds the noise, which
tests/python/test_bdhi_open_boundary.py checks against Cholesky.

The particle fluids are not spheres in a solvent but the fluid itself: N particles of mass 1 at random
positions in a periodic cube, no external force, kT 1, each at its documented example's parameters:
- dissipative particle dynamics (dpd: density 3, a = 25, gamma = 4.5, r_c = 1, dt = 0.04): its error
  is the time step's, the relative excess of the kinetic temperature over the thermostat's (about 3 %
  at this dt, docs/input-format.md), averaged over 100 steps after 100 of equilibration, up to
  --reference-max (at 1,000 particles, windows of 100 steps differ by about 1.5 %);
- smoothed particle hydrodynamics (sph: density 1, support 1, viscosity 0.1, gas stiffness 10, rest
  density 0.5, dt 0.005): none; tests/python/test_sph.py checks its density against numpy and its
  conservation of momentum and energy.

usage: hydrodynamics_benchmark.py [--backend cuda] [--method fcm --method cholesky ...] [--n 1000 ...]
       [--precision single] [--seconds 1.0] [--csv FILE]
Prints a markdown table (docs/benchmarks.md) and writes --csv FILE if asked."""
import argparse
import csv
import math
import time

import numpy as np

import structmd

RADIUS = 1.0
ETA = 1.0
PHI = 0.05
DT = 0.01
REFERENCE_TOLERANCE = 1e-6

# Each method: its integrator entry, whether the box is periodic, whether it takes a tolerance, and
# its default sizes.
METHODS = {
    "cholesky": (["BDHIOpenBoundary", "Cholesky"], False, False, [1000, 2000, 4000]),
    "lanczos": (["BDHIOpenBoundary", "Lanczos"], False, True, [1000, 4000, 16000]),
    "fcm": (["BDHITriplyPeriodic", "ForceCouplingMethod"], True, True, [1000, 10000, 100000, 1000000]),
    "pse": (["BDHITriplyPeriodic", "PositivelySplitEwald"], True, True, [1000, 10000, 100000, 1000000]),
    "fib": (["BDHITriplyPeriodic", "FluctuatingImmersedBoundary"], True, False, [1000, 10000, 100000, 1000000]),
    "quasi2d": (["BDHIDoublyPeriodic", "Quasi2D"], True, True, [1000, 10000, 100000, 1000000]),
    "dpstokes": (["BDHIDoublyPeriodic", "DPStokes"], True, True, [1000, 10000, 100000]),
    "icm": (["FluctuatingHydrodynamics", "IncompressibleInertialCoupling"], True, False, [1000, 10000, 100000]),
    "cicm": (["FluctuatingHydrodynamics", "CompressibleInertialCoupling"], True, False, [1000, 10000, 100000]),
    "magnetic_fcm": (["Magnetic", "ForceCouplingMethod"], True, True, [1000, 10000, 100000, 1000000]),
    "dpd": (["DPD", "Verlet"], True, False, [1000, 10000, 100000, 1000000]),
    "sph": (["SPH", "Verlet"], True, False, [1000, 10000, 100000, 1000000]),
}
# The particle fluids (see above): their number density and their integrator's parameters.
PARTICLE_FLUIDS = {
    "dpd": (3.0, {"timeStep": 0.04, "cutOff": 1.0, "gamma": 4.5, "alpha": 25.0}),
    "sph": (1.0, {"timeStep": 0.005, "support": 1.0, "viscosity": 0.1, "gasStiffness": 10.0, "restDensity": 0.5}),
}
# The parameters a method takes beyond time step, viscosity, radius and tolerance.
EXTRA_PARAMETERS = {
    "icm": {"density": 1.0},
    "cicm": {"density": 1.0, "speedOfSound": 4.0, "bulkViscosity": 1.0},
    "magnetic_fcm": {"msat": 1.0, "damping": 0.1, "gyroRatio": 1.0, "magneticIntegrationAlgorithm": "LLG_Heun"},
}
# The magnetic methods: each particle at the identity orientation carries a unit moment along z.
MAGNETIC = {"magnetic_fcm"}
# The methods whose error is not measured (see above).
UNREFERENCED = {"icm", "cicm", "sph"}
# The methods that name the viscosity otherwise (a compressible fluid has a bulk viscosity too).
VISCOSITY_KEY = {"cicm": "shearViscosity"}
# The planar methods: particles in the plane z = 0 of an x-y periodic square at area fraction 0.05.
PLANAR = {"quasi2d"}
# The slab methods: particles between two walls SLAB_HEIGHT apart, at least 2 radii from each, at
# volume fraction 0.05 of the slab they can reach; the grid's spacing is GRID_SPACING (sigma = a /
# sqrt(pi), the Gaussian's width) or a little less (fft_friendly), and the reference about halves it.
SLAB = {"dpstokes"}
SLAB_HEIGHT = 16.0 * RADIUS
# The methods whose reference is another method's mobility: the periodic RPY one of positively split Ewald.
RPY_REFERENCED = {"fib"}
# The methods whose translation is the force coupling method's.
FCM_REFERENCED = {"magnetic_fcm"}
GRID_SPACING = RADIUS / math.sqrt(math.pi)


def side(method, n):
    if method in PARTICLE_FLUIDS:
        return (n / PARTICLE_FLUIDS[method][0]) ** (1.0 / 3.0)
    if method in PLANAR:
        return math.sqrt(math.pi * RADIUS ** 2 * n / PHI)
    if method in SLAB:
        return math.sqrt(4.0 * math.pi * RADIUS ** 3 * n / 3.0 / PHI / (SLAB_HEIGHT - 4.0 * RADIUS))
    return (4.0 * math.pi * RADIUS ** 3 * n / 3.0 / PHI) ** (1.0 / 3.0)


def placement(method, n, seed=11):
    rng = np.random.default_rng(seed)
    length = side(method, n)
    positions = rng.uniform(-length / 2, length / 2, (n, 3))
    if method in PLANAR:
        positions[:, 2] = 0.0
    if method in SLAB:
        reach = SLAB_HEIGHT / 2 - 2.0 * RADIUS
        positions[:, 2] = rng.uniform(-reach, reach, n)
    return positions, rng.normal(size=(n, 3))


def smooth(m, primes):
    """Whether m has no prime factor but those of `primes`: a size cuFFT and FFTW transform fast."""
    for p in primes:
        while m % p == 0:
            m //= p
    return m == 1


def fft_friendly(m):
    """The smallest size >= m with factors 2, 3, 5 and 7 alone, as UAMMD's own DPStokes set-up rounds its
    grid: a prime size such as 149 takes cuFFT's slower general algorithm (H200: 159 against 200 steps/s
    at 1,000 particles, docs/benchmarks.md)."""
    while not smooth(m, (2, 3, 5, 7)):
        m += 1
    return m


def immersed_boundary_radius(length):
    """The radius the immersed boundary method gives for RADIUS: 0.91 L / n, n the even size with
    factors 2, 3 and 5 closest in ratio to 0.91 L / RADIUS (docs/input-format.md)."""
    wanted = 0.91 * length / RADIUS
    cells = min((m for m in range(2, 2 * int(wanted) + 8, 2) if smooth(m, (2, 3, 5))), key=lambda m: abs(wanted / m - 1))
    return 0.91 * length / cells


def document(method, n, positions, temperature, tolerance, refinement=1, radius=RADIUS):
    kind, periodic, tolerant, _ = METHODS[method]
    length = side(method, n)
    # An open-boundary box only has to hold the particles: they are never folded back into it.
    box = [length] * 3 if periodic else [10.0 * length] * 3
    if method in PARTICLE_FLUIDS:
        parameters = dict(PARTICLE_FLUIDS[method][1])
    else:
        parameters = {"timeStep": DT, VISCOSITY_KEY.get(method, "viscosity"): ETA, "hydrodynamicRadius": radius,
                      **EXTRA_PARAMETERS.get(method, {})}
    if tolerant:
        parameters["tolerance"] = tolerance
    if method in SLAB:
        box[2] = SLAB_HEIGHT
        cells = fft_friendly(math.ceil(length / GRID_SPACING) * refinement)
        parameters.update({"nx": cells, "ny": cells, "Lx": length, "Ly": length, "H": SLAB_HEIGHT, "w": 6,
                           "mode": "slit", "nz": math.ceil(SLAB_HEIGHT / GRID_SPACING) * refinement + 1})
    if method in MAGNETIC:
        state = {"labels": ["id", "position", "direction", "magnetization"],
                 "data": [[i, list(p), [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 1.0]] for i, p in enumerate(positions)]}
    else:
        state = {"labels": ["id", "position"], "data": [[i, list(p)] for i, p in enumerate(positions)]}
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": method, "seed": 5}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, RADIUS, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[box, temperature]]},
        },
        "integrator": {
            "bd": {"type": kind, "parameters": parameters},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "bd", 10 ** 9]]},
        },
        "state": state,
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
                     "forceField": {}},
    }


def displacement(backend, precision, method, n, tolerance, refinement=1, radius=RADIUS):
    """dt M F from one step at temperature 0 (on a grid `refinement` times finer for a slab method)."""
    positions, forces = placement(method, n)
    with structmd.Simulation({"backend": backend, "precision": precision, "log": "quiet"}) as sim:
        sim.load(document(method, n, positions, 0.0, tolerance, refinement, radius))
        start = np.array(sim.positions)
        sim.external_forces = forces
        sim.step(1)
        moved = np.array(sim.positions) - start
    if METHODS[method][1]:
        length = side(method, n)
        moved -= length * np.round(moved / length)
    return moved


def rpy_product(positions, forces, chunk=512):
    """dt M F for the free-space RPY mobility of equal spheres (overlapping pairs included)."""
    a = RADIUS
    mu0 = 1.0 / (6.0 * math.pi * ETA * a)
    velocity = mu0 * forces.copy()
    for begin in range(0, len(positions), chunk):
        r = positions[begin:begin + chunk, None, :] - positions[None, :, :]
        d = np.linalg.norm(r, axis=2)
        same = d == 0.0
        d = np.where(same, 1.0, d)
        unit = r / d[..., None]
        far = d >= 2 * a
        c1 = np.where(far, 0.75 * a / d * (1 + 2 * a * a / (3 * d * d)), 1 - 9 * d / (32 * a))
        c2 = np.where(far, 0.75 * a / d * (1 - 2 * a * a / (d * d)), 3 * d / (32 * a))
        c1 = np.where(same, 0.0, c1)
        c2 = np.where(same, 0.0, c2)
        projected = np.einsum("ijk,jk->ij", unit, forces)
        velocity[begin:begin + chunk] += mu0 * (np.einsum("ij,jk->ik", c1, forces)
                                                + np.einsum("ij,ij,ijk->ik", c2, projected, unit))
    return DT * velocity


def temperature_excess(backend, method, n):
    """The kinetic temperature's relative excess over the thermostat's (kT 1, mass 1), averaged over 100
    steps after 100 of equilibration from random positions, in double precision."""
    positions, _ = placement(method, n)
    with structmd.Simulation({"backend": backend, "precision": "double", "log": "quiet"}) as sim:
        sim.load(document(method, n, positions, 1.0, None))
        sim.step(100)
        samples = []
        for _ in range(100):
            sim.step(1)
            v = np.array(sim.velocities)
            v -= v.mean(axis=0)
            samples.append(np.sum(v * v) / (3 * (n - 1)))
    return float(np.mean(samples)) - 1.0


def relative_error(measured, reference):
    return float(np.sqrt(np.mean((measured - reference) ** 2) / np.mean(reference ** 2)))


def error(backend, method, n, tolerance, reference_max):
    # In double precision: a one-step displacement is a few 1e-4 of a position, so single precision
    # would measure its own rounding, not the method.
    if method in UNREFERENCED:
        return None
    if method in PARTICLE_FLUIDS:
        return temperature_excess(backend, method, n) if n <= reference_max else None
    if METHODS[method][1] and n > reference_max:
        return None
    measured = displacement(backend, "double", method, n, tolerance)
    if not METHODS[method][1]:
        positions, forces = placement(method, n)
        return relative_error(measured, rpy_product(positions, forces))
    if method in RPY_REFERENCED:
        return relative_error(measured, displacement(backend, "double", "pse", n, REFERENCE_TOLERANCE,
                                                     radius=immersed_boundary_radius(side(method, n))))
    if method in FCM_REFERENCED:
        return relative_error(measured, displacement(backend, "double", "fcm", n, REFERENCE_TOLERANCE))
    if method in SLAB:
        # The grid's error and the Gaussian's cut at the tolerance together.
        return relative_error(measured, displacement(backend, "double", method, n, REFERENCE_TOLERANCE, refinement=2))
    return relative_error(measured, displacement(backend, "double", method, n, REFERENCE_TOLERANCE))


def steps_per_second(backend, precision, method, n, tolerance, seconds):
    positions, forces = placement(method, n)
    with structmd.Simulation({"backend": backend, "precision": precision, "log": "quiet"}) as sim:
        sim.load(document(method, n, positions, 1.0, tolerance))
        if method not in PARTICLE_FLUIDS:
            sim.external_forces = forces
        sim.step(2)
        sim.positions  # the first launches and the FFT plans are behind
        start = time.perf_counter()
        sim.step(3)
        sim.positions
        estimate = max((time.perf_counter() - start) / 3, 1e-6)
        steps = max(3, int(seconds / estimate))
        start = time.perf_counter()
        sim.step(steps)
        sim.positions  # waits for the device
        return steps / (time.perf_counter() - start)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--method", action="append", choices=sorted(METHODS))
    parser.add_argument("--n", type=int, action="append", help="sizes for every method (default: each method's own)")
    parser.add_argument("--tolerance", type=float, default=1e-3)
    parser.add_argument("--precision", default="single")
    parser.add_argument("--seconds", type=float, default=1.0)
    parser.add_argument("--reference-max", type=int, default=10000,
                        help="largest periodic size whose error is measured (the reference is a double-precision run)")
    parser.add_argument("--csv")
    args = parser.parse_args()
    rows = []
    print("| method | N | precision | tolerance | steps/s | particle-steps/s | relative error of dt M F, or DPD's "
          "kinetic temperature excess (double) |")
    print("| --- | ---: | --- | ---: | ---: | ---: | ---: |")
    for method in args.method or list(METHODS):
        for n in args.n or METHODS[method][3]:
            rate = steps_per_second(args.backend, args.precision, method, n, args.tolerance, args.seconds)
            err = error(args.backend, method, n, args.tolerance, args.reference_max)
            rows.append({"method": method, "n": n, "backend": args.backend, "precision": args.precision,
                         "tolerance": args.tolerance if METHODS[method][2] else "",
                         "steps_per_second": rate, "error": err})
            shown = "-" if err is None else f"{err:.1e}"
            untolerant = "none" if method in RPY_REFERENCED | UNREFERENCED | set(PARTICLE_FLUIDS) else "exact"
            tolerance = f"{args.tolerance:g}" if METHODS[method][2] else untolerant
            print(f"| {method} | {n:,} | {args.precision} | {tolerance} | {rate:,.0f} | {rate * n:.3g} | {shown} |",
                  flush=True)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
