#!/usr/bin/env python3
"""Tutorial: Brownian dynamics with hydrodynamic interactions (docs/tutorials/bdhi-suspension.md).

64 force-free spheres (radius a = 0.5) in an unbounded fluid of viscosity eta = 1 at k_B T = 1, moved
by ["BDHIOpenBoundary","Cholesky"]: each step's displacements have the covariance 2 k_B T dt M, M
the Rotne-Prager-Yamakawa mobility. The host records the positions after every step and measures
two things the mobility fixes:
  - self-diffusion: every particle's own block of M is 1/(6 pi eta a), so the mean square
    displacement is 6 D0 t with D0 = k_B T / (6 pi eta a), whatever the neighbours do;
  - hydrodynamic coupling: two particles at distance r > 2a move together, <dx_i . dx_j> =
    2 k_B T dt tr M_ij = 2 k_B T dt / (2 pi eta r).
Checks: D0 within 3 % (from the one-step displacements, 0.5 % statistical error) and the coupling
within 10 % of those values between r = 1.5 and 4.

usage: bdhi_suspension.py [FIGURE.png]   (the figure needs matplotlib)
"""

import sys
from pathlib import Path

import numpy as np

try:
    import structmd
except ImportError:  # running from a source checkout
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))
    import structmd

PARTICLES, RADIUS, VISCOSITY, TEMPERATURE, TIME_STEP, STEPS = 64, 0.5, 1.0, 1.0, 0.01, 400
D0 = TEMPERATURE / (6 * np.pi * VISCOSITY * RADIUS)


def cluster(rng, n, side, closest):
    """n points in a cube of the side, none closer than `closest`."""
    points = []
    while len(points) < n:
        candidate = rng.uniform(-side / 2, side / 2, 3)
        if all(np.linalg.norm(candidate - p) >= closest for p in points):
            points.append(candidate)
    return np.array(points)


def build():
    suspension = structmd.Input("bdhi_suspension", seed=11)
    suspension.add_type("S", radius=RADIUS)
    # The fluid is unbounded; the box only wraps the positions reported, and is far larger than the cluster.
    suspension.set_ensemble(box=200.0, temperature=TEMPERATURE)
    suspension.add_particles(cluster(np.random.default_rng(5), PARTICLES, 8.0, 1.2), "S")
    suspension.add_integrator("bdhi", ["BDHIOpenBoundary", "Cholesky"],
                              {"timeStep": TIME_STEP, "viscosity": VISCOSITY}, steps=STEPS)
    return suspension


def trajectory():
    """Positions (STEPS + 1, n, 3), one row a step."""
    with structmd.Simulation({"backend": "cpu"}) as sim:
        sim.load(build().document())
        frames = [np.asarray(sim.positions)]
        for _ in range(STEPS):
            sim.step(1)
            frames.append(np.asarray(sim.positions))
    return np.array(frames)


def mean_square_displacement(frames, lags):
    return np.array([np.mean(np.sum((frames[lag:] - frames[:-lag]) ** 2, axis=-1)) for lag in lags])


def pair_coupling(frames, edges):
    """<dx_i . dx_j> / (2 k_B T dt) of pairs binned by their distance at the step's start."""
    steps = np.diff(frames, axis=0)
    i, j = np.triu_indices(frames.shape[1], 1)
    r = np.linalg.norm(frames[:-1, i] - frames[:-1, j], axis=-1).ravel()
    products = np.sum(steps[:, i] * steps[:, j], axis=-1).ravel() / (2 * TEMPERATURE * TIME_STEP)
    which = np.digitize(r, edges) - 1
    inside = (which >= 0) & (which < len(edges) - 1)
    sums = np.bincount(which[inside], products[inside], len(edges) - 1)
    counts = np.bincount(which[inside], minlength=len(edges) - 1)
    return sums / np.maximum(counts, 1)


def rpy_trace(r):
    """tr M_ij of the RPY mobility of two spheres of radius a at distance r > 2a: 1 / (2 pi eta r)."""
    return 1.0 / (2 * np.pi * VISCOSITY * r)


def draw(lags, msd, centres, coupling, figure_path):
    try:
        import matplotlib
    except ImportError:
        print("no figure: matplotlib is not installed")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (left, right) = plt.subplots(1, 2, figsize=(8, 3), dpi=80)
    left.plot(lags * TIME_STEP, msd, "o", ms=3, label="measured")
    left.plot(lags * TIME_STEP, 6 * D0 * lags * TIME_STEP, label="6 D0 t")
    left.set(xlabel="t", ylabel="mean square displacement", title="self-diffusion")
    left.legend(fontsize=8)
    r = np.linspace(1.4, 4.1, 100)
    right.plot(centres, coupling, "o", ms=4, label="measured")
    right.plot(r, rpy_trace(r), label="RPY: 1 / (2 pi eta r)")
    right.set(xlabel="r", ylabel="<dx_i . dx_j> / (2 kT dt)", title="hydrodynamic coupling of pairs")
    right.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(figure_path)


def main(arguments):
    frames = trajectory()
    lags = np.arange(1, 41)
    msd = mean_square_displacement(frames, lags)
    diffusion = msd[0] / (6 * TIME_STEP)  # one-step displacements: the most samples, all independent
    edges = np.linspace(1.5, 4.0, 11)
    centres = 0.5 * (edges[1:] + edges[:-1])
    coupling = pair_coupling(frames, edges)
    worst = np.max(np.abs(coupling / rpy_trace(centres) - 1))
    print(f"bdhi_suspension: D = {diffusion:.4f} (D0 = {D0:.4f}); pair coupling within {100 * worst:.1f} % of RPY")
    assert abs(diffusion / D0 - 1) < 0.03, "self-diffusion is D0"
    assert worst < 0.10, "pairs move together as the RPY mobility says"
    if arguments:
        draw(lags, msd, centres, coupling, arguments[0])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
