#!/usr/bin/env python3
"""Tutorial: a coupling loop in Python (docs/tutorials/coupling-loop.md), the loop of
coupling_loop.c with the Python package: every round the host reads the positions, answers with a
harmonic tether toward the box centre (f_i = -k x_i, energy k |x_i|^2 / 2) and lets structmd take
some steps. It prints the same lines as the C program: step, the field's energy, the potential
energy of the force field, and the particles' mean distance from the centre.

usage: coupling_loop.py INPUT_JSON [FIGURE.png]   (the figure needs matplotlib)
"""

import sys
from pathlib import Path

import numpy as np

try:
    import structmd
except ImportError:  # running from a source checkout
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bindings" / "python"))
    import structmd

ROUNDS, STEPS_PER_ROUND = 40, 25
STIFFNESS = 0.5


def coupling_loop(input_path):
    """Rows (step, field energy, potential energy, mean distance from the centre), one a round."""
    rows = []
    with structmd.Simulation({"backend": "cpu"}) as sim:
        sim.load_file(input_path)
        for round_number in range(ROUNDS + 1):
            x = np.asarray(sim.positions)               # the host's side: the field at the positions
            sim.external_forces = -STIFFNESS * x        # added to every force evaluation until replaced
            field_energy = 0.5 * STIFFNESS * float((x ** 2).sum())
            sim.set_external_energy(field_energy)
            distance = float(np.linalg.norm(x, axis=1).mean())
            rows.append((sim.step_number, field_energy, sim.energy("potential"), distance))
            if round_number < ROUNDS:
                sim.step(STEPS_PER_ROUND)
    return rows


def draw(rows, figure_path):
    try:
        import matplotlib
    except ImportError:
        print("no figure: matplotlib is not installed")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    step, field, potential, distance = np.array(rows).T
    figure, (left, right) = plt.subplots(1, 2, figsize=(8, 3), dpi=80)
    left.plot(step, distance)
    left.set(xlabel="step", ylabel="mean |x|", title="particles pulled toward the centre")
    right.plot(step, field, label="host's field")
    right.plot(step, potential, label="force field (structmd)")
    right.set(xlabel="step", ylabel="energy", title="energies")
    right.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(figure_path)


def main(arguments):
    if not arguments:
        sys.exit(__doc__)
    rows = coupling_loop(arguments[0])
    print("# step field_energy potential mean_distance")
    for step, field, potential, distance in rows:
        print(f"{step} {field:.12e} {potential:.12e} {distance:.12e}")
    if len(arguments) > 1:
        draw(rows, arguments[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
