#!/usr/bin/env python3
"""Couples a Python "field code" to structmd: every 10 steps the host reads forces, energy and positions,
and applies an external force that depends on the positions, a harmonic tether pulling each particle
toward the box centre (f = -k x, the box spans [-L/2, L/2) so its centre is the origin). Then it
tethers only a region of the particles, exchanging just their positions and forces by id every step,
and changes the bonds' spring constant at run time (structmd_set_parameter). Last, the tether becomes a
force callback: the engine calls the host's function inside its own step loop (structmd_set_force_callback).

Usage: coupling.py [input.json]   (default: bead_spring.json next to this script if it exists, else a
small bead-spring chain built here). It checks its own results and exits non-zero when they are wrong:
the force the engine reports minus the force without the field equals the field, and energies stay
finite.
"""

import math
import sys
from pathlib import Path

import numpy as np

try:
    import structmd
except ImportError:
    # Running from a source checkout: the package lives in bindings/python.
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bindings" / "python"))
    import structmd

TETHER_K = 0.05
ROUNDS = 20
STEPS_PER_ROUND = 10
# Relative agreement expected between (total - internal) and the field, per engine precision.
TOLERANCE = {"double": 1e-10, "single": 1e-4}


def bead_spring_chain(beads=16, box=20.0):
    """A short bead-spring chain: harmonic bonds and Lennard-Jones cut at its minimum (purely repulsive),
    on a zigzag so nothing overlaps."""
    positions = [[-6.0 + 0.8 * i, 0.3 * (i % 2), 0.0] for i in range(beads)]
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "coupling", "seed": 3}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["M", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", ROUNDS * STEPS_PER_ROUND]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, p, [0.0, 0.0, 0.0]] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "M"] for i in range(beads)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
                "repulsion": {"type": ["NonBonded", "LennardJonesType1"],
                              "parameters": {"cutOffFactor": 1.122462, "condition": "all"},
                              "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["M", "M", 1.0, 0.8]]},
                "bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 100.0, "r0": 0.85},
                          "labels": ["id_i", "id_j"], "data": [[i, i + 1] for i in range(beads - 1)]},
            },
        },
    }


def default_input():
    bundled = Path(__file__).resolve().parent / "bead_spring.json"
    return bundled if bundled.is_file() else bead_spring_chain()


def tether(positions):
    return -TETHER_K * positions


def check_field(sim, field, tolerance):
    """The engine's total force minus its force without the field must be the field."""
    total = sim.forces
    sim.external_forces = None
    internal = sim.forces
    sim.external_forces = field
    scale = max(1.0, float(np.abs(total).max()))
    error = float(np.abs((total - internal) - field).max())
    if error > tolerance * scale:
        raise AssertionError(f"forces minus internal forces differ from the field by {error:.3e}")


def region_and_parameter(sim, tolerance):
    """A tether on every other particle only, exchanged by id each step, then the bond constant
    doubled at run time: the bond energy at fixed positions must double with it."""
    failures = []
    sim.external_forces = None
    region = np.arange(0, sim.num_particles, 2)
    for _ in range(STEPS_PER_ROUND):
        sim.step(1)
        sim.set_external_forces_of(region, tether(sim.positions_of(region)))
    expected = np.zeros((sim.num_particles, 3))
    expected[region] = tether(sim.positions[region])
    try:
        check_field(sim, expected, tolerance)
    except AssertionError as error:
        failures.append(f"region: {error}")
    path = "topology.forceField.bonds.parameters.K"
    k = sim.get_parameter(path)
    before = sim.energy("bonds")
    sim.set_parameter(path, 2 * k)
    after = sim.energy("bonds")
    print(f"bond constant {k:g} -> {sim.get_parameter(path):g}: bond energy {before:.6f} -> {after:.6f}")
    if not math.isclose(after, 2 * before, rel_tol=tolerance, abs_tol=1e-12):
        failures.append(f"bond energy {after} after doubling K, expected {2 * before}")
    return failures


def callback(sim, tolerance):
    """The tether as a force callback, called by the engine at each new configuration: its forces
    join the engine's, its energy is the term "callback", and it runs once per step."""
    failures = []
    sim.external_forces = None
    internal = sim.forces
    calls = []

    def tether_callback(positions, forces, step):
        calls.append(step)
        forces += tether(positions)
        return 0.5 * TETHER_K * float(np.sum(positions ** 2))

    sim.set_force_callback(tether_callback)
    expected = tether(sim.positions)
    error = float(np.abs(sim.forces - internal - expected).max())
    if error > tolerance * max(1.0, float(np.abs(sim.forces).max())):
        failures.append(f"callback: forces minus internal forces differ from its forces by {error:.3e}")
    energy = sim.energy("callback")
    if not math.isclose(energy, 0.5 * TETHER_K * float(np.sum(sim.positions ** 2)), rel_tol=1e-9):
        failures.append(f"callback: energy term {energy}")
    sim.step(STEPS_PER_ROUND)
    if len(calls) != STEPS_PER_ROUND + 1:
        failures.append(f"callback: called {len(calls)} times over {STEPS_PER_ROUND} steps")
    print(f"callback: energy {energy:.6f}, {len(calls)} calls, steps {calls[0]}..{calls[-1]}")
    sim.set_force_callback(None)
    return failures


def main(argv):
    source = argv[1] if len(argv) > 1 else default_input()
    with structmd.Simulation({"log": "warning"}) as sim:
        sim.load(source)
        tolerance = TOLERANCE[sim.info["precision"]]
        print(f"structmd {structmd.version()} on {sim.info['backend']} ({sim.info['precision']}), "
              f"{sim.num_particles} particles")
        failures = []
        for round_index in range(ROUNDS):
            sim.step(STEPS_PER_ROUND)
            forces = sim.forces
            potential = sim.energy("potential")
            kinetic = sim.energy("kinetic")
            field = tether(sim.positions)
            sim.external_forces = field
            if not (math.isfinite(potential) and math.isfinite(kinetic) and np.all(np.isfinite(forces))):
                failures.append(f"round {round_index}: non-finite forces or energies")
                break
            try:
                check_field(sim, field, tolerance)
            except AssertionError as error:
                failures.append(f"round {round_index}: {error}")
            print(f"step {sim.step_number:5d}  potential {potential: .6f}  kinetic {kinetic: .6f}  "
                  f"max |f| {np.abs(forces).max():.4f}")
        failures += region_and_parameter(sim, tolerance)
        failures += callback(sim, tolerance)
    for failure in failures:
        print("FAILED:", failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
