"""The ctest test python_typing: `python3 -m mypy --strict` over the package bindings/python/structmd,
configured by the [tool.mypy] section of the repository's pyproject.toml. Any error fails the test;
exit 77 (ctest's skip) only where mypy is not installed (`pip install mypy`, or
scripts/install-deps.sh --profile test).

    python3 check_typing.py REPOSITORY
"""

import importlib.util
import subprocess
import sys
from pathlib import Path
from typing import List

SKIP_RETURN_CODE = 77


def main(arguments: List[str]) -> int:
    if len(arguments) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    repository = Path(arguments[0]).resolve()
    if importlib.util.find_spec("mypy") is None:
        print("python_typing: mypy is not installed (pip install mypy); skipped")
        return SKIP_RETURN_CODE
    command = [sys.executable, "-m", "mypy", "--strict", "--config-file", str(repository / "pyproject.toml"),
               str(repository / "bindings" / "python" / "structmd")]
    print(" ".join(command), flush=True)
    # mypy exits 1 for type errors and 2 for a crash or a bad configuration: both fail the test.
    return 0 if subprocess.run(command).returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
