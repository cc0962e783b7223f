#!/usr/bin/env python3
"""Writes the bundled example inputs (UAMMD-structured JSON) next to this script.

- lj_liquid.json: the classic Lennard-Jones liquid, 32000 particles on an fcc lattice at density
  0.8442 and temperature 1.44; velocities are drawn by the engine (the state gives none).
- bead_spring.json: 20 bead-spring chains of 20 beads (harmonic bonds, LJ between all pairs) at
  density 0.5 and temperature 1.0, with velocities given.
- polymer_melt.json: a Kremer-Grest melt, 40 chains of 25 beads at density 0.85 (FENE bonds, WCA
  between all pairs, bonded ones included), grown as random walks that may overlap a little; a schedule first
  minimises the energy (SteepestDescent), then equilibrates at T = 1 (Langevin BBK), writing a DCD
  trajectory and the thermodynamics.

The output is deterministic (fixed seeds, Python's own Mersenne Twister, no numpy), so running the
script again reproduces the committed files byte for byte.

usage: make_inputs.py [OUTPUT_DIR]
"""
import json
import math
import os
import random
import sys

LJ_EPSILON = 1.0
LJ_SIGMA = 1.0
LJ_CUTOFF_FACTOR = 2.5
VERLET_SKIN = 0.3
# The list radius is cutoff * cutOffVerletFactor; this factor gives the requested skin (rounded so
# the file shows 1.12, not its binary neighbour).
CUT_OFF_VERLET_FACTOR = round((LJ_CUTOFF_FACTOR * LJ_SIGMA + VERLET_SKIN) / (LJ_CUTOFF_FACTOR * LJ_SIGMA), 12)

POSITION_DIGITS = 10
LINE_WIDTH = 100


def rounded(x, digits=POSITION_DIGITS):
    """x to the given significant digits, so the file carries %.10g values that parse back exactly."""
    return float(f"{x:.{digits}g}")


def wrapped(x, box_length):
    """x folded into [-L/2, L/2), after rounding, so that rounding cannot push it out again."""
    x = rounded(x - box_length * math.floor(x / box_length + 0.5))
    if x >= box_length / 2:
        x = rounded(x - box_length)
    return x


def gaussian(rng):
    """A standard normal deviate by Box-Muller, spelled out so the stream never depends on the Python
    version's random.gauss."""
    u1 = 1.0 - rng.random()
    u2 = rng.random()
    return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)


def single_type():
    return {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
            "data": [["A", 1.0, 0.5, 0.0]]}


def lennard_jones_force_field():
    return {
        "nl": {"type": ["VerletConditionalListSet", "all"],
               "parameters": {"cutOffVerletFactor": CUT_OFF_VERLET_FACTOR}},
        "lj": {"type": ["NonBonded", "LennardJonesType1"],
               "parameters": {"cutOffFactor": LJ_CUTOFF_FACTOR, "condition": "all"},
               "labels": ["name_i", "name_j", "epsilon", "sigma"],
               "data": [["A", "A", LJ_EPSILON, LJ_SIGMA]]},
    }


def velocity_verlet(time_step, steps):
    return {
        "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": time_step}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "vv", steps]]},
    }


def thermo_every(interval, path):
    return {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                       "parameters": {"intervalStep": interval, "outputFilePath": path}}}


def lj_liquid():
    cells_per_side = 20
    density = 0.8442
    temperature = 1.44
    basis = [(0.0, 0.0, 0.0), (0.5, 0.5, 0.0), (0.5, 0.0, 0.5), (0.0, 0.5, 0.5)]
    n = len(basis) * cells_per_side ** 3
    box_length = (n / density) ** (1.0 / 3.0)
    lattice_constant = box_length / cells_per_side

    positions = []
    for i in range(cells_per_side):
        for j in range(cells_per_side):
            for k in range(cells_per_side):
                for bx, by, bz in basis:
                    # The quarter-cell offset keeps every site strictly inside the box.
                    positions.append([wrapped(-box_length / 2 + lattice_constant * (c + b + 0.25), box_length)
                                      for c, b in ((i, bx), (j, by), (k, bz))])

    return {
        "system": {"info": {"type": ["Simulation", "Information"],
                            "parameters": {"name": "lj_liquid", "seed": 20240611}}},
        "global": {
            "units": {"type": ["Units", "None"]},
            "types": single_type(),
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box_length] * 3, temperature]]},
        },
        "integrator": velocity_verlet(0.005, 1000),
        "state": {"labels": ["id", "position"],
                  "data": [[index, position] for index, position in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[index, "A"] for index in range(n)]},
            "forceField": lennard_jones_force_field(),
        },
        "simulationStep": thermo_every(100, "lj_liquid_thermo.dat"),
    }


def minimum_image_distance2(a, b, box_length):
    total = 0.0
    for x, y in zip(a, b):
        d = y - x
        d -= box_length * round(d / box_length)
        total += d * d
    return total


def grow_chains(rng, chains, beads_per_chain, bond_length, min_distance, box_length):
    """Self-avoiding random walks: each bead lies bond_length from the previous one and at least
    min_distance (minimum image) from every other bead already placed. A chain that gets stuck is
    started again."""
    placed = []
    min_distance2 = min_distance ** 2
    attempts_per_bead = 1000

    def free(candidate, ignore):
        return all(minimum_image_distance2(candidate, other, box_length) >= min_distance2
                   for index, other in enumerate(placed) if index != ignore)

    def random_point():
        return [(rng.random() - 0.5) * box_length for _ in range(3)]

    def random_direction():
        while True:
            v = [gaussian(rng) for _ in range(3)]
            norm = math.sqrt(sum(c * c for c in v))
            if norm > 1e-12:
                return [c / norm for c in v]

    while len(placed) < chains * beads_per_chain:
        chain_start = len(placed)
        head = random_point()
        while not free(head, ignore=-1):
            head = random_point()
        placed.append(head)
        while len(placed) - chain_start < beads_per_chain:
            previous_index = len(placed) - 1
            previous = placed[previous_index]
            for _ in range(attempts_per_bead):
                candidate = [p + bond_length * d for p, d in zip(previous, random_direction())]
                if free(candidate, ignore=previous_index):
                    placed.append(candidate)
                    break
            else:
                del placed[chain_start:]
                break
    return placed


def maxwell_boltzmann_velocities(rng, n, temperature, mass):
    """Velocities with zero total momentum, scaled so that 2K / (3 N k_B) equals the temperature."""
    velocities = [[gaussian(rng) * math.sqrt(temperature / mass) for _ in range(3)] for _ in range(n)]
    mean = [sum(v[c] for v in velocities) / n for c in range(3)]
    velocities = [[v[c] - mean[c] for c in range(3)] for v in velocities]
    kinetic = 0.5 * mass * sum(c * c for v in velocities for c in v)
    scale = math.sqrt(1.5 * n * temperature / kinetic)
    return [[rounded(c * scale) for c in v] for v in velocities]


def bead_spring():
    chains = 20
    beads_per_chain = 20
    density = 0.5
    temperature = 1.0
    n = chains * beads_per_chain
    box_length = (n / density) ** (1.0 / 3.0)
    rng = random.Random(7)

    walk = grow_chains(rng, chains, beads_per_chain, bond_length=0.97, min_distance=0.9, box_length=box_length)
    positions = [[wrapped(x, box_length) for x in bead] for bead in walk]
    velocities = maxwell_boltzmann_velocities(rng, n, temperature, mass=1.0)
    bonds = [[chain * beads_per_chain + bead, chain * beads_per_chain + bead + 1]
             for chain in range(chains) for bead in range(beads_per_chain - 1)]

    force_field = lennard_jones_force_field()
    force_field["bonds"] = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 100.0, "r0": 1.0},
                            "labels": ["id_i", "id_j"], "data": bonds}
    return {
        "system": {"info": {"type": ["Simulation", "Information"],
                            "parameters": {"name": "bead_spring", "seed": 20240612}}},
        "global": {
            "units": {"type": ["Units", "None"]},
            "types": single_type(),
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box_length] * 3, temperature]]},
        },
        "integrator": velocity_verlet(0.002, 2000),
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[index, positions[index], velocities[index]] for index in range(n)]},
        "topology": {
            "structure": {"labels": ["id", "type", "chainId"],
                          "data": [[index, "A", index // beads_per_chain] for index in range(n)]},
            "forceField": force_field,
        },
        "simulationStep": thermo_every(200, "bead_spring_thermo.dat"),
    }


def polymer_melt():
    chains = 40
    beads_per_chain = 25
    density = 0.85
    n = chains * beads_per_chain
    box_length = (n / density) ** (1.0 / 3.0)
    rng = random.Random(1986)

    # Loose walks (beads may come as close as 0.75): the minimiser removes the overlaps.
    walk = grow_chains(rng, chains, beads_per_chain, bond_length=0.97, min_distance=0.75, box_length=box_length)
    positions = [[rounded(wrapped(x, box_length)) for x in bead] for bead in walk]
    bonds = [[chain * beads_per_chain + bead, chain * beads_per_chain + bead + 1]
             for chain in range(chains) for bead in range(beads_per_chain - 1)]
    wca_cut = round(2.0 ** (1.0 / 6.0), 12)
    return {
        "system": {"info": {"type": ["Simulation", "Information"],
                            "parameters": {"name": "polymer_melt", "seed": 1986}}},
        "global": {
            "units": {"type": ["Units", "None"]},
            "types": single_type(),
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box_length] * 3, 1.0]]},
        },
        "integrator": {
            "minimise": {"type": ["SteepestDescent", "SteepestDescent"],
                         "parameters": {"h": 0.01, "maxObjectiveForce": 10.0}},
            "langevin": {"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.005, "frictionConstant": 0.5}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "minimise", 500], [2, "langevin", 5000]]},
        },
        "state": {"labels": ["id", "position"], "data": [[index, positions[index]] for index in range(n)]},
        "topology": {
            "structure": {"labels": ["id", "type", "chainId"],
                          "data": [[index, "A", index // beads_per_chain] for index in range(n)]},
            "forceField": {
                # Kremer-Grest: WCA between every pair, bonded ones included (it keeps bonds near 0.97).
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.3}},
                "wca": {"type": ["NonBonded", "WCAType1"], "parameters": {"cutOffFactor": wca_cut,
                                                                          "condition": "all"},
                        "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]},
                "fene": {"type": ["Bond2", "FeneCommon_r0_K_R0"], "parameters": {"r0": 0.0, "K": 30.0, "R0": 1.5},
                         "labels": ["id_i", "id_j"], "data": bonds},
            },
        },
        "simulationStep": {
            "trajectory": {"type": ["WriteStep", "WriteStep"],
                           "parameters": {"intervalStep": 500, "outputFilePath": "polymer_melt",
                                          "outputFormat": "dcd"}},
            **thermo_every(100, "polymer_melt_thermo.dat"),
        },
    }


def to_text(value, indent=0):
    """JSON with long objects spread over lines and each row of a "data" table on a line of its own."""
    pad = "  " * indent
    inner = "  " * (indent + 1)
    if isinstance(value, dict):
        items = []
        for key, item in value.items():
            if key == "data" and len(item) > 1:
                rows = (",\n" + inner + "  ").join(json.dumps(row) for row in item)
                items.append(f"{inner}{json.dumps(key)}: [\n{inner}  {rows}\n{inner}]")
            elif isinstance(item, dict) and len(json.dumps(item)) > LINE_WIDTH:
                items.append(f"{inner}{json.dumps(key)}: {to_text(item, indent + 1)}")
            else:
                items.append(f"{inner}{json.dumps(key)}: {json.dumps(item)}")
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    return json.dumps(value)


def main():
    output_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, document in (("lj_liquid.json", lj_liquid()), ("bead_spring.json", bead_spring()),
                           ("polymer_melt.json", polymer_melt())):
        path = os.path.join(output_dir, name)
        with open(path, "w") as f:
            f.write(to_text(document) + "\n")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
