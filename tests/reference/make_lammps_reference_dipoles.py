#!/usr/bin/env python3
"""Builds the LAMMPS reference for ["NonBonded","DipolarMagnetic"] that tests/python/test_magnetism.py
checks structmd against.

Writes
  data/dipoles.json         the structmd input: point dipoles in a periodic box, each with its own
                            orientation and body-frame moment, permeability 4 pi (so k = 1);
  data/dipoles.lammps.json  what LAMMPS (Debian's `lmp`, serial, pair_style lj/cut/dipole/cut with
                            epsilon 0, i.e. the dipole-dipole term alone, `units lj`, where the energy
                            is (p_i . p_j) / r^3 - 3 (p_i . r)(p_j . r) / r^5) computes: per-atom
                            forces, torques and energies, and the total energy.

An independent numpy evaluation of the same energy is checked against LAMMPS's before anything is
written, so an extraction mistake cannot slip in.

Usage: python3 tests/reference/make_lammps_reference_dipoles.py [--lmp /usr/bin/lmp]
"""
import argparse
import json
import pathlib
import subprocess
import tempfile

import numpy as np

DATA_DIR = pathlib.Path(__file__).resolve().parent / "data"
COUNT = 40
BOX = 8.0
CUTOFF = 3.0
MIN_DISTANCE = 0.9
SEED = 2026


def rotation_matrix(q):
    a, b, c, d = q
    return np.array([[a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
                     [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
                     [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d]])


def configuration():
    """Positions at least MIN_DISTANCE apart, orientations, lab-frame moments; no pair within 1e-6 of
    the cutoff, where two codes could disagree about the sharp cut."""
    rng = np.random.default_rng(SEED)
    positions = []
    while len(positions) < COUNT:
        p = rng.uniform(-BOX / 2, BOX / 2, 3)
        d = [np.linalg.norm(minimum_image(p - other)) for other in positions]
        if all(x > MIN_DISTANCE and abs(x - CUTOFF) > 1e-6 for x in d):
            positions.append(p)
    q = rng.normal(size=(COUNT, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    directions = rng.normal(size=(COUNT, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    magnitudes = rng.uniform(0.5, 1.5, COUNT)
    return np.array(positions), q, directions * magnitudes[:, None]


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def structmd_input(positions, q, moments):
    rows = []
    for i, (p, qi, mu) in enumerate(zip(positions, q, moments)):
        magnitude = float(np.linalg.norm(mu))
        body = rotation_matrix(qi).T @ (mu / magnitude)
        rows.append([i, [float(x) for x in p], [float(x) for x in qi], [*(float(x) for x in body), magnitude]])
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "dipoles"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[BOX, BOX, BOX], 1.0]]},
        },
        "state": {"labels": ["id", "position", "direction", "magnetization"], "data": rows},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(COUNT)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
                "dipoles": {"type": ["NonBonded", "DipolarMagnetic"],
                            "parameters": {"permeability": 4 * np.pi, "cutOff": CUTOFF, "condition": "all"}},
            },
        },
    }


def lammps_reference(lmp, positions, moments):
    commands = [
        "units lj", "atom_style hybrid sphere dipole", "atom_modify map array", "boundary p p p",
        f"region box block {-BOX / 2} {BOX / 2} {-BOX / 2} {BOX / 2} {-BOX / 2} {BOX / 2}", "create_box 1 box",
    ]
    for p in positions:
        commands.append(f"create_atoms 1 single {float(p[0])!r} {float(p[1])!r} {float(p[2])!r} units box")
    commands += ["set atom * charge 0.0", "set atom * diameter 1.0", "set atom * density 1.0"]
    for i, mu in enumerate(moments):
        commands.append(f"set atom {i + 1} dipole {float(mu[0])!r} {float(mu[1])!r} {float(mu[2])!r}")
    commands += [
        f"pair_style lj/cut/dipole/cut {CUTOFF}", f"pair_coeff * * 0.0 1.0 {CUTOFF} {CUTOFF}",
        "neighbor 0.5 bin", "compute pe all pe/atom",
        "dump 1 all custom 1 out.dump id fx fy fz tqx tqy tqz c_pe", "dump_modify 1 format float %.17g sort id",
        "thermo_style custom step pe", "thermo_modify norm no format float %.17g", "run 0",
    ]
    with tempfile.TemporaryDirectory() as work:
        script = pathlib.Path(work) / "in.dipoles"
        script.write_text("\n".join(commands) + "\n")
        subprocess.run([lmp, "-in", str(script), "-log", "none", "-screen", "none"], cwd=work, check=True)
        lines = (pathlib.Path(work) / "out.dump").read_text().splitlines()
    start = lines.index("ITEM: ATOMS id fx fy fz tqx tqy tqz c_pe") + 1
    table = np.array([[float(x) for x in line.split()] for line in lines[start:]])
    assert len(table) == COUNT and np.array_equal(table[:, 0], np.arange(1, COUNT + 1))
    return {"forces": table[:, 1:4].tolist(), "torques": table[:, 4:7].tolist(),
            "particle_energies": table[:, 7].tolist(), "energy": float(table[:, 7].sum())}


def numpy_energy(positions, moments):
    total = 0.0
    for i in range(COUNT):
        for j in range(i + 1, COUNT):
            r = minimum_image(positions[j] - positions[i])
            d = np.linalg.norm(r)
            if d < CUTOFF:
                total += moments[i] @ moments[j] / d ** 3 - 3 * (moments[i] @ r) * (moments[j] @ r) / d ** 5
    return total


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lmp", default="lmp")
    args = parser.parse_args()
    positions, q, moments = configuration()
    reference = lammps_reference(args.lmp, positions, moments)
    check = numpy_energy(positions, moments)
    assert abs(reference["energy"] - check) < 1e-10 * abs(check), (reference["energy"], check)
    DATA_DIR.mkdir(exist_ok=True)
    (DATA_DIR / "dipoles.json").write_text(json.dumps(structmd_input(positions, q, moments)) + "\n")
    (DATA_DIR / "dipoles.lammps.json").write_text(json.dumps(reference) + "\n")


if __name__ == "__main__":
    main()
