"""Plots of a thermodynamic measure's file (["ThermodynamicMeasure","ThermodynamicQuantityMeasure"]'s
outputFilePath): energies, temperature and pressure against the step, with matplotlib.

From a shell, `structmd plot THERMO_FILE [-o FIGURE.png]` (or `python -m structmd plot ...`); from
Python, `structmd.plot.plot_thermo(path)`. matplotlib is needed only here (`pip install matplotlib`)."""

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

PathLike = Union[str, Path]

# The panels drawn, each with the columns it shows when the file has them; energy terms of the force
# field (one column per entry, named by the input) join the energies' panel.
ENERGY_TOTALS = ("kinetic", "potential", "total")
NOT_ENERGY_TERMS = {"step", "particles", "volume", "temperature", "virial", "pressure", "external"}


def read_thermo(path: PathLike) -> Dict[str, np.ndarray]:
    """The file's columns (numpy arrays, in the input's units) by the names of its header line
    (`#step particles volume ...`). Raises OSError for an unreadable file, ValueError for one that is
    not a thermodynamic measure's."""
    with open(path, encoding="utf-8") as stream:
        header = stream.readline()
    if not header.startswith("#"):
        raise ValueError(f"{path}: the first line is not a thermodynamic measure's header (#step ...)")
    names = header[1:].split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    if data.size == 0:
        data = np.empty((0, len(names)))
    if data.shape[1] != len(names):
        raise ValueError(f"{path}: {data.shape[1]} columns of numbers under {len(names)} names in the header")
    return {name: data[:, column] for column, name in enumerate(names)}


def panels_of(columns: Dict[str, np.ndarray]) -> List[Tuple[str, List[str]]]:
    """(y label, column names) of each panel, for the columns the file has. Raises nothing."""
    terms = [name for name in columns if name not in NOT_ENERGY_TERMS and name not in ENERGY_TOTALS]
    energies = [name for name in ENERGY_TOTALS if name in columns] + terms
    if "external" in columns and np.any(columns["external"] != 0.0):
        energies.append("external")
    chosen = [("energy", energies), ("temperature", ["temperature"]), ("pressure", ["pressure"])]
    return [(label, [name for name in names if name in columns]) for label, names in chosen
            if any(name in columns for name in names)]


def plot_thermo(path: PathLike, output: Optional[PathLike] = None) -> "Figure":
    """One matplotlib figure of stacked panels against the step; saved to `output` when given (format
    from its suffix). Raises ImportError without matplotlib, OSError and ValueError as read_thermo, and
    ValueError for a file without a step column."""
    try:
        import matplotlib
        if output is not None:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        raise ImportError("structmd.plot needs matplotlib: pip install matplotlib") from error
    columns = read_thermo(path)
    if "step" not in columns:
        raise ValueError(f"{path}: the header has no 'step' column")
    panels = panels_of(columns)
    figure, axes = plt.subplots(len(panels), 1, sharex=True, squeeze=False, figsize=(7.0, 2.4 * len(panels)))
    # Markers where lines alone would hide a short series (one firing draws no line).
    marker = "." if len(columns["step"]) < 50 else None
    for axis, (label, names) in zip(axes[:, 0], panels):
        for name in names:
            axis.plot(columns["step"], columns[name], label=name, marker=marker)
        axis.set_ylabel(label)
        if len(names) > 1:
            axis.legend(loc="best", fontsize="small")
    axes[-1, 0].set_xlabel("step")
    figure.suptitle(Path(path).name)
    figure.tight_layout()
    if output is not None:
        figure.savefig(output)
    return figure


def main(arguments: Optional[Sequence[str]] = None) -> int:
    """`structmd plot`: draws the file, into a window or (with -o) into a figure file. Returns the exit
    status 0; a failure exits (SystemExit) with status 1 and the reason on stderr."""
    parser = argparse.ArgumentParser(prog="structmd plot", description=__doc__.splitlines()[0])
    parser.add_argument("thermo_file", help="a ThermodynamicQuantityMeasure output file")
    parser.add_argument("-o", "--output", help="write the figure to this file (png, pdf, svg) instead of showing it")
    options = parser.parse_args(arguments)
    try:
        plot_thermo(options.thermo_file, options.output)
    except (OSError, ValueError, ImportError) as error:
        parser.exit(1, f"structmd plot: {error}\n")
    if options.output is None:
        import matplotlib.pyplot as plt
        plt.show()
    else:
        print(f"structmd plot: wrote {options.output}")
    return 0
