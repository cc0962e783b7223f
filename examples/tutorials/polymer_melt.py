#!/usr/bin/env python3
"""Tutorial: a Kremer-Grest polymer melt (docs/tutorials/polymer-melt.md).

Runs the bundled examples/polymer_melt.json (40 chains of 25 beads at density 0.85: FENE bonds and
WCA between every pair; a minimisation, then Langevin dynamics at T = 1), as `structmd run
polymer_melt.json` would, and reads what it wrote with MDAnalysis: the trajectory polymer_melt.dcd
with the topology polymer_melt.psf written beside it (names, masses, chains, bonds). Checks: 40
segments of 25 beads and 960 bonds; the median bond length of the melt is Kremer-Grest's 0.97
(0.94 to 1.0); the chains are random coils, <R_ee^2> / <R_g^2> between 4.5 and 7.5 (6 for ideal
chains). Exit status 77 when MDAnalysis is not installed.

usage: polymer_melt.py [FIGURE.png]   (the figure needs matplotlib)
"""

import os
import shutil
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np

try:
    import structmd
except ImportError:  # running from a source checkout
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))
    import structmd
from structmd.plot import read_thermo  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[1]
MELTED_FROM_STEP = 1500  # frames from here on: 1000 steps (2.5 friction times) into the Langevin stage


def run(folder):
    """Runs the bundled input in `folder`, where its outputs land (their paths are relative)."""
    shutil.copy(EXAMPLES / "polymer_melt.json", folder)
    here = os.getcwd()
    os.chdir(folder)
    try:
        with structmd.Simulation({"backend": "cpu"}) as sim:
            sim.load_file("polymer_melt.json")
            sim.run()
    finally:
        os.chdir(here)


def analyse(folder):
    import MDAnalysis as mda
    warnings.filterwarnings("ignore", category=DeprecationWarning, module="MDAnalysis")
    universe = mda.Universe(str(Path(folder) / "polymer_melt.psf"), str(Path(folder) / "polymer_melt.dcd"))
    chains = universe.segments
    assert len(chains) == 40 and all(len(chain.atoms) == 25 for chain in chains)
    assert len(universe.bonds) == 40 * 24
    steps, gyration2, end_to_end2, bond_lengths = [], [], [], []
    for timestep in universe.trajectory:
        # The DCD's NSAVC is MDAnalysis's skip_timestep; this input's first frame is step 0.
        step = timestep.frame * universe.trajectory.skip_timestep
        universe.atoms.unwrap(compound="segments")  # whole chains across the periodic boundary
        steps.append(step)
        gyration2.append(np.mean([chain.atoms.radius_of_gyration() ** 2 for chain in chains]))
        end_to_end2.append(np.mean([np.sum((chain.atoms.positions[-1] - chain.atoms.positions[0]) ** 2)
                                    for chain in chains]))
        if step >= MELTED_FROM_STEP:
            bond_lengths.extend(universe.bonds.values())
    return np.array(steps), np.array(gyration2), np.array(end_to_end2), np.array(bond_lengths)


def check(steps, gyration2, end_to_end2, bond_lengths):
    melted = steps >= MELTED_FROM_STEP
    ratio = end_to_end2[melted].mean() / gyration2[melted].mean()
    median = np.median(bond_lengths)
    print(f"polymer_melt: {melted.sum()} frames, median bond {median:.3f}, <Rg^2> {gyration2[melted].mean():.2f}, "
          f"<Ree^2>/<Rg^2> {ratio:.2f}")
    assert 0.94 <= median <= 1.0, "FENE against WCA holds the bonds near 0.97"
    assert 4.5 < ratio < 7.5, "random coils: about 6"


def fene_wca_bond_distribution(r):
    """r^2 exp(-U(r) / kT), normalised, for one bond on its own: FENE (K = 30, R0 = 1.5) plus WCA."""
    fene = -0.5 * 30.0 * 1.5 ** 2 * np.log(1.0 - (r / 1.5) ** 2)
    wca = np.where(r < 2 ** (1 / 6), 4.0 * (r ** -12 - r ** -6) + 1.0, 0.0)
    weight = r ** 2 * np.exp(-(fene + wca))
    return weight / (weight.sum() * (r[1] - r[0]))


def draw(folder, steps, gyration2, end_to_end2, bond_lengths, figure_path):
    try:
        import matplotlib
    except ImportError:
        print("no figure: matplotlib is not installed")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    thermo = read_thermo(Path(folder) / "polymer_melt_thermo.dat")
    figure, (left, middle, right) = plt.subplots(1, 3, figsize=(10, 3), dpi=80)
    left.plot(thermo["step"], thermo["temperature"])
    left.set(xlabel="step", ylabel="temperature", title="minimise, then Langevin")
    middle.plot(steps, end_to_end2 / gyration2, "o-")
    middle.axhline(6.0, color="grey", ls="--", lw=0.8)
    middle.set(xlabel="step", ylabel="<R_ee^2> / <R_g^2>", title="chain shape (ideal: 6)")
    r = np.linspace(0.8, 1.2, 200)
    right.hist(bond_lengths, bins=40, range=(0.8, 1.2), density=True, alpha=0.6, label="melt")
    right.plot(r, fene_wca_bond_distribution(r), label="lone bond, Boltzmann")
    right.set(xlabel="bond length", ylabel="density", title="bond lengths")
    right.legend(fontsize=7, loc="upper right")
    figure.tight_layout()
    figure.savefig(figure_path)


def main(arguments):
    try:
        import MDAnalysis  # noqa: F401
    except ImportError:
        print("skipped: MDAnalysis is not installed (pip install MDAnalysis)")
        return 77
    with tempfile.TemporaryDirectory() as folder:
        run(folder)
        results = analyse(folder)
        check(*results)
        if arguments:
            draw(folder, *results, arguments[0])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
