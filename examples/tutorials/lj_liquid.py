#!/usr/bin/env python3
"""Tutorial: a Lennard-Jones liquid near its triple point (docs/tutorials/lj-liquid.md).

256 particles on an FCC lattice at density 0.8442 are melted by a Langevin thermostat at T = 1.44,
then run at constant energy. The host samples the positions every 50 steps and computes the radial
distribution function g(r) with numpy; the thermodynamic measure's file gives the energy. Checks: the
total energy of the constant-energy stage drifts by less than 0.5 %, and g(r) has the liquid's first
peak near r = 1.1 sigma, above 2.

usage: lj_liquid.py [FIGURE.png]   (the figure needs matplotlib)
"""

import sys
import tempfile
from pathlib import Path

import numpy as np

try:
    import structmd
except ImportError:  # running from a source checkout
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))
    import structmd
from structmd.plot import read_thermo  # noqa: E402

CELLS, DENSITY, TEMPERATURE = 4, 0.8442, 1.44
MELT_STEPS, NVE_STEPS, SAMPLE_EVERY = 1000, 1000, 50


def fcc_lattice(cells, density):
    """4 cells^3 sites of a face-centred cubic lattice of the density, centred on the origin."""
    edge = (4 / density) ** (1 / 3)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    cells_at = np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)])
    sites = (cells_at[:, None, :] + basis[None, :, :]).reshape(-1, 3) * edge
    box = cells * edge
    return sites - box / 2 + edge / 4, box


def build(thermo_path):
    positions, box = fcc_lattice(CELLS, DENSITY)
    lj = structmd.Input("lj_liquid", seed=7)
    lj.add_type("A", mass=1.0, radius=0.5)
    lj.set_ensemble(box=box, temperature=TEMPERATURE)
    lj.add_particles(positions, "A")
    lj.add_interaction("nl", ["VerletConditionalListSet", "all"], {"cutOffVerletFactor": 1.1})
    lj.add_interaction("lj", ["NonBonded", "LennardJonesType1"], {"cutOffFactor": 2.5, "condition": "all"},
                       labels=["name_i", "name_j", "epsilon", "sigma"], data=[["A", "A", 1.0, 1.0]])
    lj.add_integrator("melt", ["Langevin", "BBK"], {"timeStep": 0.005, "frictionConstant": 1.0}, steps=MELT_STEPS)
    lj.add_integrator("nve", ["Verlet", "VelocityVerlet"], {"timeStep": 0.005}, steps=NVE_STEPS)
    lj.add_step("thermo", ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                {"intervalStep": 20, "outputFilePath": str(thermo_path)})
    return lj, box


def radial_distribution(samples, box, bins=60):
    """g(r) up to half the box from position samples (each (n, 3)), by minimum-image distances."""
    edges = np.linspace(0.0, box / 2, bins + 1)
    counts = np.zeros(bins)
    for x in samples:
        d = x[:, None, :] - x[None, :, :]
        d -= box * np.round(d / box)
        r = np.sqrt((d ** 2).sum(-1))[np.triu_indices(len(x), 1)]
        counts += np.histogram(r, edges)[0]
    n = len(samples[0])
    shells = 4 / 3 * np.pi * (edges[1:] ** 3 - edges[:-1] ** 3)
    ideal = len(samples) * n * (n - 1) / 2 * shells / box ** 3
    return 0.5 * (edges[1:] + edges[:-1]), counts / ideal


def run(folder):
    thermo_path = Path(folder) / "lj_thermo.dat"
    lj, box = build(thermo_path)
    samples = []
    with structmd.Simulation({"backend": "cpu", "log": "quiet"}) as sim:
        sim.load(lj.document())
        sim.step(MELT_STEPS)
        while sim.step_number < MELT_STEPS + NVE_STEPS:
            sim.step(SAMPLE_EVERY)
            samples.append(np.asarray(sim.positions))
    thermo = read_thermo(thermo_path)
    r, g = radial_distribution(samples, box)
    return thermo, r, g


def check(thermo, r, g):
    nve = thermo["step"] >= MELT_STEPS
    total = thermo["total"][nve]
    drift = np.ptp(total) / abs(total.mean())
    peak = r[np.argmax(g)]
    print(f"lj_liquid: energy drift {drift:.2e} of |E|, g(r) peak {g.max():.2f} at r = {peak:.3f}")
    assert drift < 5e-3, "velocity Verlet should conserve the total energy"
    assert 1.0 < peak < 1.2 and g.max() > 2.0, "the first neighbour shell of a dense liquid"


def draw(thermo, r, g, figure_path):
    try:
        import matplotlib
    except ImportError:
        print("no figure: matplotlib is not installed")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (left, right) = plt.subplots(1, 2, figsize=(8, 3), dpi=80)
    left.plot(r, g)
    left.axhline(1.0, color="grey", lw=0.5)
    left.set(xlabel="r / sigma", ylabel="g(r)", title="radial distribution (NVE stage)")
    for name in ("kinetic", "potential", "total"):
        right.plot(thermo["step"], thermo[name], label=name)
    right.axvline(MELT_STEPS, color="grey", ls="--", lw=0.8)
    right.set(xlabel="step", ylabel="energy", title="Langevin melt, then NVE")
    right.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(figure_path)


def main(arguments):
    with tempfile.TemporaryDirectory() as folder:
        thermo, r, g = run(folder)
    check(thermo, r, g)
    if arguments:
        draw(thermo, r, g, arguments[0])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
