#!/usr/bin/env python3
"""Draws the figures of the tutorials (docs/tutorials/*.png) by running their scripts
(examples/tutorials) on the CPU backend, each a small system that takes seconds.

The figures are committed rather than drawn when the documentation is built: the site then builds
with MkDocs alone, without compiling the engine (as the benchmark figures of docs/ are), and each is
about 30 KB. What keeps them honest is that the tests tutorial_* run the same scripts, checks and
figure code included, so a script that no longer runs or no longer gives the physics fails there.
Run this after changing a tutorial. It needs matplotlib and MDAnalysis (the polymer melt); the
figure of the coupling loop comes from its Python twin, so no C build is needed.

usage: tutorial_figures.py     (the library: STRUCTMD_LIBRARY, else build/src/libstructmd.so)
"""

import os
import subprocess
import sys
import tempfile
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]
TUTORIALS = REPOSITORY / "examples" / "tutorials"
FIGURES = REPOSITORY / "docs" / "tutorials"
# (script, arguments before the figure's path, figure)
RUNS = [("lj_liquid.py", [], "lj-liquid.png"),
        ("coupling_loop.py", [str(REPOSITORY / "examples" / "bead_spring.json")], "coupling-loop.png"),
        ("polymer_melt.py", [], "polymer-melt.png"),
        ("bdhi_suspension.py", [], "bdhi-suspension.png")]


def main() -> int:
    environment = dict(os.environ)
    environment.setdefault("STRUCTMD_LIBRARY", str(REPOSITORY / "build" / "src" / "libstructmd.so"))
    for script, arguments, figure in RUNS:
        print(f"tutorial_figures: {script} -> docs/tutorials/{figure}", flush=True)
        # The scripts write their other outputs to temporary folders or the working directory: a
        # scratch one keeps them out of the repository.
        subprocess.run([sys.executable, str(TUTORIALS / script), *arguments, str(FIGURES / figure)],
                       env=environment, check=True, cwd=tempfile.gettempdir())
    return 0


if __name__ == "__main__":
    sys.exit(main())
