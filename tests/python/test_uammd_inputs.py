"""Real UAMMD-structured inputs: each JSON in tests/reference/uammd_inputs was written by one of
UAMMD-structured's own generator scripts (at small size, see generate.py and README.md there). Every one
must load and step; the inputs structmd cannot load yet are listed in UNSUPPORTED.md beside them."""

import glob
import json
import os
import sys

import numpy as np
import pytest

import structmd

INPUTS_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference", "uammd_inputs")
sys.path.insert(0, INPUTS_DIR)
from generate import redirect_outputs  # noqa: E402  (the script that made the inputs rewrites their paths too)
INPUTS = sorted(p for p in glob.glob(os.path.join(INPUTS_DIR, "*.json")) if os.path.basename(p) != "origins.json")
STEPS = 10


def scheduled_types(document):
    """The types (["Class", "SubClass"]) of the integrators the schedule runs."""
    integrators = document.get("integrator") or {}
    schedule = integrators.get("schedule") or {}
    labels = schedule.get("labels") or []
    if "integrator" not in labels:
        return []
    column = labels.index("integrator")
    return [integrators.get(row[column], {}).get("type", ["", ""]) for row in schedule.get("data") or []]


def scheduled_classes(document):
    """The classes (["Class", ...]) of the integrators the schedule runs."""
    return [t[0] for t in scheduled_types(document)]


def turns_moments_only(document):
    """True where every integrator is ["Magnetic","Fixed"]: the particles stay, their moments turn."""
    types = scheduled_types(document)
    return bool(types) and all(t == ["Magnetic", "Fixed"] for t in types)


def may_stand_still(document, masses):
    """True where no particle need move: every integrator is a minimiser (which may have converged) or
    ["None","None"] (which moves nothing: its inputs measure a configuration as given), or
    every particle has mass 0 and every integrator is inertial (which holds massless particles fixed;
    UAMMD-structured's Hessian tests are such inputs), or every integrator turns magnetic moments only."""
    classes = scheduled_classes(document)
    if classes and all(c in ("Minimization", "None") for c in classes):
        return True
    if turns_moments_only(document):
        return True
    return bool(classes) and all(c in ("Verlet", "Langevin") for c in classes) and not np.any(masses > 0)


def test_there_are_inputs():
    assert len(INPUTS) >= 1, f"no inputs in {INPUTS_DIR}"


@pytest.mark.parametrize("path", INPUTS, ids=[os.path.splitext(os.path.basename(p))[0] for p in INPUTS])
def test_loads_and_steps(path, options, tmp_path):
    with open(path) as f:
        document = json.load(f)
    document = redirect_outputs(document, str(tmp_path))
    with structmd.Simulation(options) as sim:
        sim.load(document)
        assert sim.num_particles == len(document["state"]["data"])
        before = np.array(sim.positions, copy=True)
        moments_before = np.array(sim.magnetic_moments, copy=True)
        masses = np.array(sim.masses)
        sim.step(STEPS)
        after = np.array(sim.positions, copy=True)
        moments_after = np.array(sim.magnetic_moments, copy=True)
    assert np.all(np.isfinite(moments_after)), "magnetic moments not finite after stepping"
    if turns_moments_only(document):
        assert np.any(moments_after != moments_before), "no magnetic moment turned in 10 steps"
    assert np.all(np.isfinite(after)), "positions not finite after stepping"
    moved = np.any(np.abs(after - before) > 0.0, axis=1)
    if not may_stand_still(document, masses):
        assert moved.any(), "no particle moved in 10 steps"
    # Nothing is written outside tmp_path: the working directory keeps no output of the input.
    for entry in (document.get("simulationStep") or {}).values():
        for key, value in (entry.get("parameters") or {}).items():
            if isinstance(value, str) and key.lower().endswith("filepath"):
                assert value.startswith(str(tmp_path))
