"""The `structmd` command of a pip installation, and `python -m structmd`: the launcher program
(`structmd run INPUT.json`, `structmd client --ipi ...`) that the wheel bundles in structmd/bin, run
with the arguments given (in a source checkout, the one `bash scripts/build.sh` made), and one
subcommand of its own, `structmd plot THERMO_FILE`, which draws a thermodynamic measure's file
(structmd/plot.py)."""

import os
import sys
from pathlib import Path
from typing import List, NoReturn, Optional

from ._library import checkout_repository


def launcher_candidates() -> List[Path]:
    """Where the launcher may be, in order: bundled in the package, then a checkout's build tree."""
    package_dir = Path(__file__).resolve().parent
    candidates = [package_dir / "bin" / "structmd"]
    repository = checkout_repository(package_dir)
    if repository is not None:
        candidates.append(repository / "build" / "src" / "launcher" / "structmd")
    return candidates


def main(arguments: Optional[List[str]] = None) -> NoReturn:
    """Runs `plot` here; otherwise replaces this process by the launcher, so that its exit status and
    signals are the command's."""
    given = sys.argv[1:] if arguments is None else arguments
    if given[:1] == ["plot"]:
        from . import plot
        sys.exit(plot.main(given[1:]))
    for launcher in launcher_candidates():
        if launcher.is_file() and os.access(launcher, os.X_OK):
            os.execv(launcher, ["structmd", *given])
    tried = ", ".join(str(path) for path in launcher_candidates())
    sys.exit(f"structmd: this installation has no launcher program (looked in {tried}); "
             "install the package with `pip install .` from the repository, or build it with `bash scripts/build.sh`")


if __name__ == "__main__":
    main()
