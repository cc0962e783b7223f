#!/usr/bin/env python3
"""Renders the API reference from include/structmd.h with docs/Doxyfile into OUTPUT_DIR and fails on
any Doxygen warning (an undocumented parameter or result, a bad command, a broken reference).
Exits 77, which ctest reads as skipped, when doxygen is not installed.

usage: check_reference.py SOURCE_DIR OUTPUT_DIR
"""
import shutil
import subprocess
import sys
from pathlib import Path

SKIPPED = 77


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    source, output = Path(sys.argv[1]), Path(sys.argv[2]).resolve()
    doxygen = shutil.which("doxygen")
    if not doxygen:
        print("doxygen is not installed (Debian: apt-get install doxygen): the reference is not rendered")
        return SKIPPED
    version = subprocess.run([doxygen, "--version"], capture_output=True, text=True).stdout.strip()
    shutil.rmtree(output, ignore_errors=True)
    # The repository's configuration, read from standard input with the output redirected into this
    # build folder; its paths are relative to the repository root.
    config = (source / "docs" / "Doxyfile").read_text() + f'\nOUTPUT_DIRECTORY = "{output}"\n'
    result = subprocess.run([doxygen, "-"], input=config, cwd=source, capture_output=True, text=True)
    # WARN_AS_ERROR = FAIL_ON_WARNINGS sets the exit status; a Doxygen too old for that setting still
    # prints its warnings, so any output at all fails too.
    messages = (result.stdout + result.stderr).strip()
    page = output / "html" / "structmd_8h.html"
    if result.returncode != 0 or messages or not page.is_file():
        print(messages or f"doxygen exited with {result.returncode} and wrote no {page}")
        print(f"doxygen {version}: the reference of include/structmd.h has warnings (see above)")
        return 1
    print(f"doxygen {version}: include/structmd.h rendered without warnings into {page}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
