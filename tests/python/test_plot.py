"""structmd.plot and `python -m structmd plot`: a thermodynamic measure's file written by a run is read
column by column under its header's names and drawn, energies, temperature and pressure against the step."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import structmd
from structmd.plot import panels_of, plot_thermo, read_thermo

pytest.importorskip("matplotlib")

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bead_spring.json"
INTERVAL = 10
STEPS = 100


@pytest.fixture
def thermo_file(tmp_path, options):
    document = json.loads(EXAMPLE.read_text())
    path = tmp_path / "thermo.dat"
    document["simulationStep"]["thermo"]["parameters"].update(intervalStep=INTERVAL, outputFilePath=str(path))
    with structmd.Simulation(options) as sim:
        sim.load(document)
        sim.step(STEPS)
    return path


def test_columns_are_read_under_the_header_names(thermo_file):
    columns = read_thermo(thermo_file)
    assert list(columns)[:3] == ["step", "particles", "volume"]
    assert np.array_equal(columns["step"], np.arange(0, STEPS + 1, INTERVAL))  # the last where the call ends
    # The file's own identities: total = kinetic + potential + external, potential = sum of the
    # entries, and T = 2K / (3N): the names must land on the right columns for these to hold.
    total = columns["kinetic"] + columns["potential"] + columns["external"]
    assert np.allclose(columns["total"], total, rtol=1e-8)
    assert np.allclose(columns["potential"], columns["bonds"] + columns["lj"], rtol=1e-8)
    assert np.allclose(columns["temperature"], 2 * columns["kinetic"] / (3 * columns["particles"]), rtol=1e-8)


def test_the_figure_draws_each_column_in_its_panel(thermo_file, tmp_path):
    columns = read_thermo(thermo_file)
    output = tmp_path / "thermo.png"
    figure = plot_thermo(thermo_file, output)
    assert output.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    axes = figure.axes
    assert [axis.get_ylabel() for axis in axes] == ["energy", "temperature", "pressure"]
    drawn = {line.get_label(): line for axis in axes for line in axis.get_lines()}
    # external is all zero here, so it is left out; the force field's two entries join the energies.
    assert sorted(drawn) == sorted(["kinetic", "potential", "total", "bonds", "lj", "temperature", "pressure"])
    for name, line in drawn.items():
        assert np.array_equal(line.get_xdata(), columns["step"])
        assert np.array_equal(line.get_ydata(), columns[name])


def test_panels_follow_the_columns_a_file_has():
    columns = {name: np.zeros(2) for name in ("step", "kinetic", "temperature")}
    assert panels_of(columns) == [("energy", ["kinetic"]), ("temperature", ["temperature"])]


def test_a_file_whose_rows_do_not_match_its_header_is_refused(tmp_path):
    path = tmp_path / "short.dat"
    path.write_text("#step kinetic total\n0 1.0\n")
    with pytest.raises(ValueError, match="2 columns of numbers under 3 names"):
        read_thermo(path)
    path.write_text("0 1.0\n")
    with pytest.raises(ValueError, match="header"):
        read_thermo(path)


def test_the_command_writes_the_figure_or_says_what_is_wrong(thermo_file, tmp_path):
    output = tmp_path / "thermo.svg"
    environment = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-m", "structmd", "plot", str(thermo_file), "-o", str(output)],
                          capture_output=True, text=True, env=environment)
    assert done.returncode == 0, done.stderr
    assert output.read_text().lstrip().startswith("<?xml")
    missing = subprocess.run([sys.executable, "-m", "structmd", "plot", str(tmp_path / "none.dat"), "-o", str(output)],
                             capture_output=True, text=True, env=environment)
    assert missing.returncode == 1
    assert "none.dat" in missing.stderr
