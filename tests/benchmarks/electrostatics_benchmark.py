#!/usr/bin/env python3
"""Accuracy against run time of ["LongRange","Electrostatics"]: for each size, tolerance and precision,
the RMS force error relative to the RMS force (against the same engine at tolerance 1e-7 in double
precision, which the reference script tests/reference/electrostatics_reference.py checks against
exact sums; the mesh of a tighter tolerance outgrows the device at 100,000 charges) and the wall time per step of a Brownian run (forces every step, energies never read).

System: a neutral 1:1 electrolyte of Gaussian charges (width 0.5, UAMMD-structured's model) at
number density 0.1, random positions, unit dielectric in reduced units, ["Brownian","EulerMaruyama"].

usage: electrostatics_benchmark.py [--backend cuda] [--n 10000 --n 100000] [--tolerance 1e-3 ...]
       [--precision single --precision double] [--steps 200]
Prints a markdown table (docs/benchmarks.md) and writes --csv FILE if asked."""
import argparse
import csv
import time

import numpy as np

import structmd

DENSITY = 0.1
REFERENCE_TOLERANCE = 1e-7
WIDTH = 0.5


def document(n, tolerance, seed=7):
    box = (n / DENSITY) ** (1.0 / 3.0)
    rng = np.random.default_rng(seed)
    positions = rng.uniform(-box / 2, box / 2, (n, 3))
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "elec", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["P", 1.0, 0.5, 1.0], ["M", 1.0, 0.5, -1.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[box] * 3, 1.0]]},
        },
        "integrator": {
            "bd": {"type": ["Brownian", "EulerMaruyama"], "parameters": {"timeStep": 1e-4, "viscosity": 1.0}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "bd", 10**9]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, list(p)] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "P" if i % 2 == 0 else "M"] for i in range(n)]},
            "forceField": {"elec": {"type": ["LongRange", "Electrostatics"],
                                    "parameters": {"dielectricConstant": 1.0, "gaussianWidth": WIDTH,
                                                   "tolerance": tolerance}}},
        },
    }


def forces(backend, precision, n, tolerance):
    with structmd.Simulation({"backend": backend, "precision": precision, "log": "quiet"}) as sim:
        sim.load(document(n, tolerance))
        return np.array(sim.forces)


def seconds_per_step(backend, precision, n, tolerance, steps):
    with structmd.Simulation({"backend": backend, "precision": precision, "log": "quiet"}) as sim:
        sim.load(document(n, tolerance))
        sim.step(10)
        sim.positions  # the warm-up is done
        start = time.perf_counter()
        sim.step(steps)
        sim.positions  # waits for the device
        return (time.perf_counter() - start) / steps


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--n", type=int, action="append")
    parser.add_argument("--tolerance", type=float, action="append")
    parser.add_argument("--precision", action="append")
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--csv")
    args = parser.parse_args()
    sizes = args.n or [10000]
    tolerances = args.tolerance or [1e-2, 1e-3, 1e-4, 1e-5]
    precisions = args.precision or ["single", "double"]
    rows = []
    for n in sizes:
        reference = forces(args.backend, "double", n, REFERENCE_TOLERANCE)
        scale = np.sqrt(np.mean(np.sum(reference**2, axis=1)))
        for precision in precisions:
            for tolerance in tolerances:
                f = forces(args.backend, precision, n, tolerance)
                error = np.sqrt(np.mean(np.sum((f - reference) ** 2, axis=1))) / scale
                step = seconds_per_step(args.backend, precision, n, tolerance, args.steps)
                rows.append({"n": n, "backend": args.backend, "precision": precision, "tolerance": tolerance,
                             "force_error": error, "ms_per_step": 1e3 * step, "particle_steps_per_second": n / step})
    print("| N | precision | tolerance | RMS force error | ms/step | particle-steps/s |")
    print("| ---: | --- | ---: | ---: | ---: | ---: |")
    for r in rows:
        print(f"| {r['n']:,} | {r['precision']} | {r['tolerance']:.0e} | {r['force_error']:.2e} | "
              f"{r['ms_per_step']:.3f} | {r['particle_steps_per_second']:.3g} |")
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
