"""The hydrodynamics suites' shared check of a value structmd_set_parameter must refuse."""

import re

import pytest

import structmd


def assert_refused_and_kept(sim, path, value, message):
    """set_parameter refuses `value` at `path` (ArgumentError naming the path and `message`), the
    parameter keeps its value, and the simulation steps on."""
    kept = sim.get_parameter(path)
    with pytest.raises(structmd.ArgumentError, match=re.escape(path) + ".*" + message):
        sim.set_parameter(path, value)
    assert sim.get_parameter(path) == kept
    sim.step(1)
