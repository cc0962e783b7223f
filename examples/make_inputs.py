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

Each is written through structmd.builder.Input, the input builder of the Python package. The output
is deterministic (fixed seeds, Python's own Mersenne Twister), so running the script again
reproduces the committed files byte for byte.

usage: make_inputs.py [OUTPUT_DIR]
"""
import math
import os
import random
import sys
from pathlib import Path

try:
    from structmd.builder import Input
except ImportError:
    # Running from a source checkout: the package lives in bindings/python.
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bindings" / "python"))
    from structmd.builder import Input

LJ_EPSILON = 1.0
LJ_SIGMA = 1.0
LJ_CUTOFF_FACTOR = 2.5
VERLET_SKIN = 0.3
# The list radius is cutoff * cutOffVerletFactor; this factor gives the requested skin (rounded so
# the file shows 1.12, not its binary neighbour).
CUT_OFF_VERLET_FACTOR = round((LJ_CUTOFF_FACTOR * LJ_SIGMA + VERLET_SKIN) / (LJ_CUTOFF_FACTOR * LJ_SIGMA), 12)

POSITION_DIGITS = 10


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


def new_input(name, seed, box_length, temperature):
    """An input of one type A (mass 1, radius 0.5) in a cubic box at the given temperature."""
    system = Input(name, seed=seed)
    system.add_type("A", mass=1.0, radius=0.5, charge=0.0)
    system.set_ensemble(box_length, temperature)
    return system


def add_neighbour_list(system, factor=CUT_OFF_VERLET_FACTOR):
    system.add_interaction("nl", ["VerletConditionalListSet", "all"], {"cutOffVerletFactor": factor})


def add_pair_term(system, name, kind, cutoff_factor):
    system.add_interaction(name, ["NonBonded", kind], {"cutOffFactor": cutoff_factor, "condition": "all"},
                           labels=["name_i", "name_j", "epsilon", "sigma"], data=[["A", "A", LJ_EPSILON, LJ_SIGMA]])


def add_thermo(system, interval, path):
    system.add_step("thermo", ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                    {"intervalStep": interval, "outputFilePath": path})


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

    system = new_input("lj_liquid", 20240611, box_length, temperature)
    system.add_integrator("vv", ["Verlet", "VelocityVerlet"], {"timeStep": 0.005}, steps=1000)
    system.add_particles(positions, "A")
    add_neighbour_list(system)
    add_pair_term(system, "lj", "LennardJonesType1", LJ_CUTOFF_FACTOR)
    add_thermo(system, 100, "lj_liquid_thermo.dat")
    return system

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

    system = new_input("bead_spring", 20240612, box_length, temperature)
    system.add_integrator("vv", ["Verlet", "VelocityVerlet"], {"timeStep": 0.002}, steps=2000)
    system.add_particles(positions, "A", velocities=velocities,
                         structure_columns={"chainId": [index // beads_per_chain for index in range(n)]})
    add_neighbour_list(system)
    add_pair_term(system, "lj", "LennardJonesType1", LJ_CUTOFF_FACTOR)
    system.add_interaction("bonds", ["Bond2", "HarmonicCommon_K_r0"], {"K": 100.0, "r0": 1.0},
                           labels=["id_i", "id_j"], data=bonds)
    add_thermo(system, 200, "bead_spring_thermo.dat")
    return system

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
    system = new_input("polymer_melt", 1986, box_length, 1.0)
    system.add_integrator("minimise", ["SteepestDescent", "SteepestDescent"], {"h": 0.01, "maxObjectiveForce": 10.0},
                          steps=500)
    system.add_integrator("langevin", ["Langevin", "BBK"], {"timeStep": 0.005, "frictionConstant": 0.5}, steps=5000)
    system.add_particles(positions, "A", structure_columns={"chainId": [index // beads_per_chain for index in range(n)]})
    # Kremer-Grest: WCA between every pair, bonded ones included (it keeps bonds near 0.97).
    add_neighbour_list(system, 1.3)
    add_pair_term(system, "wca", "WCAType1", wca_cut)
    system.add_interaction("fene", ["Bond2", "FeneCommon_r0_K_R0"], {"r0": 0.0, "K": 30.0, "R0": 1.5},
                           labels=["id_i", "id_j"], data=bonds)
    system.add_step("trajectory", ["WriteStep", "WriteStep"],
                    {"intervalStep": 500, "outputFilePath": "polymer_melt", "outputFormat": "dcd"})
    add_thermo(system, 100, "polymer_melt_thermo.dat")
    return system

def main():
    output_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, system in (("lj_liquid.json", lj_liquid()), ("bead_spring.json", bead_spring()),
                         ("polymer_melt.json", polymer_melt())):
        path = os.path.join(output_dir, name)
        system.write(path)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
