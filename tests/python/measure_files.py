"""Readers of the files simulation steps write, shared by the Python tests and the plugin checks
(tests/plugins/check_transverser_plugins.py, which check_plugins.sh runs with this folder on its path)."""

from pathlib import Path

import numpy as np


def read_step_blocks(path):
    """(header, {step: array of rows}) of a file of a header line, then per firing a `# <step>` line
    and its numeric rows: what ["TransverserMeasure", ...] writes."""
    lines = Path(path).read_text().splitlines()
    blocks, current = {}, None
    for line in lines[1:]:
        if line.startswith("# "):
            current = int(line[2:])
            blocks[current] = []
        else:
            blocks[current].append([float(x) for x in line.split()])
    return lines[0], {step: np.array(rows) for step, rows in blocks.items()}
