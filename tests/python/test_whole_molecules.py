"""Bonded groups made whole at load (src/simulation/whole_molecules.cpp): an input whose positions are
already wrapped into the box, with a chain and a bent trimer crossing its faces, must give the same
unwrapped trajectory as the same input given unwrapped, with every bond at its own length rather
than about a box length. The unwrapped frame is read back from a LAMMPS dump ("pbc": false)."""

import numpy as np
import pytest

import structmd

BOX = np.array([8.0, 9.0, 10.0])
BOND = 1.0
CHAIN = 8    # along x from x = 0.5: six of its beads lie beyond the +x face when unwrapped
TRIMER = 3   # along -y from y = -3.5 (bonded by an angle term only, arity 3)
LONE = 2     # unbonded particles, outside the box: wrapped as before, images from their positions


def unwrapped_positions():
    chain = [[0.5 + BOND * k, 0.3, -1.0] for k in range(CHAIN)]
    trimer = [[-2.0, -3.5 - BOND * k, 2.0 + 0.4 * k] for k in range(TRIMER)]
    lone = [[5.5, 0.0, 0.0], [-1.0, -6.0, 7.5]]
    return np.array(chain + trimer + lone)


def wrap(positions):
    return positions - BOX * np.floor((positions + BOX / 2) / BOX)


def document(positions, dump_path):
    n = len(positions)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "whole"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[BOX.tolist(), 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 1]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, p.tolist(), [0.0, 0.0, 0.0]] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(n)]},
            "forceField": {
                "bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 10.0, "r0": BOND},
                          "labels": ["id_i", "id_j"], "data": [[k, k + 1] for k in range(CHAIN - 1)]},
                "angle": {"type": ["Bond3", "HarmonicAngularCommon_K_theta0"], "parameters": {"K": 1.0, "theta0": 3.0},
                          "labels": ["id_i", "id_j", "id_k"], "data": [[CHAIN, CHAIN + 1, CHAIN + 2]]},
            },
        },
        "simulationStep": {"dump": {"type": ["WriteStep", "WriteStep"],
                                    "parameters": {"intervalStep": 1, "outputFilePath": str(dump_path),
                                                   "outputFormat": "lammpstrj", "pbc": False}}},
    }


def first_dump_frame(path):
    """id -> (xu, yu, zu) of the first frame of a LAMMPS text dump."""
    lines = path.read_text().splitlines()
    header = lines.index("ITEM: ATOMS id type xu yu zu")
    count = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
    rows = [line.split() for line in lines[header + 1:header + 1 + count]]
    frame = np.zeros((count, 3))
    for row in rows:
        frame[int(row[0]) - 1] = [float(x) for x in row[2:5]]
    return frame


def load_and_dump(positions, path, options):
    """The wrapped positions after loading, and the first unwrapped frame; path has no extension
    (the writer adds .lammpstrj)."""
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, path))
        loaded = sim.positions
        sim.step(1)
    return loaded, first_dump_frame(path.with_suffix(".lammpstrj"))


def bond_lengths(frame):
    chain = np.linalg.norm(np.diff(frame[:CHAIN], axis=0), axis=1)
    trimer = np.linalg.norm(np.diff(frame[CHAIN:CHAIN + TRIMER], axis=0), axis=1)
    return chain, trimer


def test_wrapped_input_gives_whole_molecules_like_the_unwrapped_input(options, tmp_path):
    unwrapped = unwrapped_positions()
    wrapped = wrap(unwrapped)
    chain, _ = bond_lengths(wrapped)
    assert chain.max() > BOX[0] / 2  # the input as given is broken across the face
    from_unwrapped = load_and_dump(unwrapped, tmp_path / "unwrapped", options)
    from_wrapped = load_and_dump(wrapped, tmp_path / "wrapped", options)

    # The same state: wrapped positions alike, and unwrapped frames alike for the bonded groups.
    np.testing.assert_allclose(from_wrapped[0], from_unwrapped[0], atol=1e-12)
    bonded = CHAIN + TRIMER
    np.testing.assert_allclose(from_wrapped[1][:bonded] - from_wrapped[1][0],
                               from_unwrapped[1][:bonded] - from_unwrapped[1][0], atol=1e-6)
    for frame in (from_wrapped[1], from_unwrapped[1]):
        chain, trimer = bond_lengths(frame)
        np.testing.assert_allclose(chain, BOND, atol=1e-5)
        np.testing.assert_allclose(trimer, np.linalg.norm([BOND, 0.4]), atol=1e-5)
    # The input given unwrapped keeps its own coordinates, also for particles without bonds.
    np.testing.assert_allclose(from_unwrapped[1], unwrapped, atol=1e-5)
    # Unbonded particles given wrapped stay where they were given.
    np.testing.assert_allclose(from_wrapped[1][bonded:], wrapped[bonded:], atol=1e-5)
