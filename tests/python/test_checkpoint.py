"""Checkpoint and restart: a run stopped at step k and restarted from its checkpoint continues the
same trajectory as the run that never stopped (bit for bit on the CPU backend), corrupt, truncated
and foreign files are refused with the reason and leave the handle as it was, a failed write never
replaces a good file, and ["Simulation","Backup"] writes checkpoints on its own."""

import json
import struct

import numpy as np
import pytest

import structmd

N_SIDE = 4  # 4 x 4 x 4 simple cubic, spacing 1.15: a dense LJ liquid whose lists rebuild often


def document(integrators, schedule, backup=None):
    spacing = 1.15
    box = N_SIDE * spacing
    positions = [[(i + 0.5) * spacing - box / 2, (j + 0.5) * spacing - box / 2, (k + 0.5) * spacing - box / 2]
                 for i in range(N_SIDE) for j in range(N_SIDE) for k in range(N_SIDE)]
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "restart", "seed": 11}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.5]]},
        },
        "integrator": dict(integrators, schedule={"type": ["Schedule", "Integrator"],
                                                  "labels": ["order", "integrator", "steps"], "data": schedule}),
        "state": {"labels": ["id", "position"], "data": [[i, p] for i, p in enumerate(positions)]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(positions))]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.0,
                                                                                  "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]},
            },
        },
    }
    if backup:
        doc["system"]["backup"] = {"type": ["Simulation", "Backup"], "parameters": backup}
    return doc


LANGEVIN = {"langevin": {"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.004, "frictionConstant": 1.0}}}
MINIMISE_THEN_LANGEVIN = {
    "minimise": {"type": ["SteepestDescent", "SteepestDescent"], "parameters": {"h": 0.01, "maxObjectiveForce": 1e-3}},
    **LANGEVIN,
}


def state(sim):
    return sim.positions.copy(), sim.velocities.copy(), sim.step_number, sim.time


def assert_same_state(a, b, exact):
    if exact:
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]), "the restarted run left the trajectory"
    else:
        np.testing.assert_allclose(a[0], b[0], rtol=0, atol=1e-9)
        np.testing.assert_allclose(a[1], b[1], rtol=0, atol=1e-9)
    assert a[2] == b[2] and a[3] == pytest.approx(b[3], rel=1e-15)


@pytest.mark.parametrize("integrators, schedule, stop", [
    (LANGEVIN, [[1, "langevin", 300]], 137),
    (MINIMISE_THEN_LANGEVIN, [[1, "minimise", 60], [2, "langevin", 140]], 41),   # inside the minimisation
    (MINIMISE_THEN_LANGEVIN, [[1, "minimise", 60], [2, "langevin", 140]], 60),   # at the stage boundary
])
def test_restart_continues_the_same_trajectory(options, tmp_path, integrators, schedule, stop):
    options = dict(options, precision="double")
    doc = document(integrators, schedule)
    total = sum(row[2] for row in schedule)
    with structmd.Simulation(options) as whole:
        whole.load(doc)
        whole.run()
        uninterrupted = state(whole)
    path = tmp_path / "run.chk"
    with structmd.Simulation(options) as first:
        first.load(doc)
        first.step(stop)
        first.save_checkpoint(path)
    with structmd.Simulation(options) as second:
        second.load(doc)
        second.load_checkpoint(path)
        assert second.step_number == stop
        second.step(total - stop)
        assert_same_state(state(second), uninterrupted, exact=second.info["backend"] == "cpu")


@pytest.fixture
def saved(options, tmp_path):
    """A simulation 50 steps in, its checkpoint, and the state it had when saving."""
    sim = structmd.Simulation(dict(options, precision="double"))
    sim.load(document(LANGEVIN, [[1, "langevin", 300]]))
    sim.step(50)
    path = tmp_path / "good.chk"
    sim.save_checkpoint(path)
    sim.step(10)
    yield sim, path
    sim.close()


def refused(sim, path, reason):
    before = state(sim)
    with pytest.raises(structmd.StructmdIOError, match=reason):
        sim.load_checkpoint(path)
    assert_same_state(state(sim), before, exact=True)
    sim.step(1)  # still usable


def test_a_corrupt_checkpoint_is_refused_and_nothing_changes(saved, tmp_path):
    sim, path = saved
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x40
    corrupt = tmp_path / "corrupt.chk"
    corrupt.write_bytes(bytes(data))
    refused(sim, corrupt, "checksum")


def test_a_truncated_checkpoint_is_refused(saved, tmp_path):
    sim, path = saved
    truncated = tmp_path / "truncated.chk"
    truncated.write_bytes(path.read_bytes()[:-100])
    refused(sim, truncated, "truncated")


def test_a_file_that_is_no_checkpoint_is_refused(saved, tmp_path):
    sim, _ = saved
    other = tmp_path / "other.chk"
    other.write_text(json.dumps({"not": "a checkpoint"}))
    refused(sim, other, "not a structmd checkpoint")
    refused(sim, tmp_path / "missing.chk", "cannot open")


def test_a_checkpoint_of_another_simulation_is_refused(saved, options, tmp_path):
    sim, path = saved
    with structmd.Simulation(dict(options, precision="single")) as single:
        single.load(document(LANGEVIN, [[1, "langevin", 300]]))
        refused(single, path, "precision")
    smaller = document(LANGEVIN, [[1, "langevin", 300]])
    smaller["state"]["data"] = smaller["state"]["data"][:-1]
    smaller["topology"]["structure"]["data"] = smaller["topology"]["structure"]["data"][:-1]
    with structmd.Simulation(dict(options, precision="double")) as fewer:
        fewer.load(smaller)
        refused(fewer, path, "particles")


# The layout of structmd's checkpoint (src/simulation/checkpoint_file.cpp, state_checkpoint.cpp): a
# 20-byte header (magic, version, length), the payload, and an FNV-1a checksum of all before it. In
# the payload (double precision): the box at 40, the time at 28, then Real4 positions (32 bytes
# each), images (12 bytes) and Real4 velocities.
HEADER = 20
TIME, BOX, POSITIONS = 28, 40, 72
PARTICLES = N_SIDE ** 3
VELOCITIES = POSITIONS + PARTICLES * (32 + 12)


def fnv1a(data):
    value = 1469598103934665603
    for byte in data:
        value = ((value ^ byte) * 1099511628211) % 2 ** 64
    return value


def edited(path, out, changes):
    """The checkpoint at path with doubles written at payload offsets and the checksum recomputed,
    as one who edits a checkpoint by hand would: only its values can refuse it."""
    data = bytearray(path.read_bytes()[:-8])
    for offset, value in changes.items():
        struct.pack_into("<d", data, HEADER + offset, value)
    out.write_bytes(bytes(data) + struct.pack("<Q", fnv1a(data)))
    return out


@pytest.mark.parametrize("changes, reason", [
    ({BOX: -1.0}, "box length 0 is -1"),
    ({BOX + 8: 1e300}, "box length 1 is 1.0000000000000001e\\+300"),
    ({BOX: 1.0, BOX + 8: 1.0, BOX + 16: 1.0}, "largest cutoff \\(2\\) must be shorter than half the box \\(0.5\\)"),
    ({BOX + 16: 3.9}, "largest cutoff \\(2\\) must be shorter than half the box \\(1.95\\)"),  # below 2 cutoffs
    ({TIME: float("nan")}, "time is nan"),
    ({POSITIONS + 5 * 32 + 8: float("nan")}, "position of particle id 5"),
    ({POSITIONS + 7 * 32 + 24: 3.0}, "type of particle id 7 is 3"),           # there is one type
    ({VELOCITIES + 3 * 32 + 16: float("inf")}, "velocity or mass of particle id 3"),
])
def test_an_edited_checkpoint_with_values_the_setters_refuse_is_refused(saved, tmp_path, changes, reason):
    sim, path = saved
    refused(sim, edited(path, tmp_path / "edited.chk", changes), "refuses: (the )?" + reason)
    sim.load_checkpoint(edited(path, tmp_path / "same.chk", {}))  # the edit alone is not what is refused
    assert sim.step_number == 50


def test_a_failed_save_leaves_the_previous_checkpoint_intact(saved, tmp_path):
    sim, path = saved
    good = path.read_bytes()
    (tmp_path / "good.chk.tmp").mkdir()  # the temporary file cannot be created
    with pytest.raises(structmd.StructmdIOError, match="good.chk"):
        sim.save_checkpoint(path)
    assert path.read_bytes() == good
    sim.load_checkpoint(path)
    assert sim.step_number == 50


def test_backup_entry_writes_checkpoints_at_its_interval(options, tmp_path):
    path = tmp_path / "backup.chk"
    doc = document(LANGEVIN, [[1, "langevin", 300]], backup={"backupFilePath": str(path), "backupIntervalStep": 40})
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        sim.step(130)
        at_130 = state(sim)
        sim.load_checkpoint(path)
        assert sim.step_number == 120
        sim.step(10)
        assert_same_state(state(sim), at_130, exact=sim.info["backend"] == "cpu")
