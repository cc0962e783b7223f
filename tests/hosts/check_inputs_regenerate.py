#!/usr/bin/env python3
"""Checks that examples/make_inputs.py reproduces the committed example inputs byte for byte, so the
generator and the bundled files cannot drift apart; the generator writes them through the Python
package's input builder (structmd.Input), so this also holds the builder to the format.

usage: check_inputs_regenerate.py EXAMPLES_DIR
"""
import filecmp
import os
import subprocess
import sys
import tempfile

BUNDLED_INPUTS = ("lj_liquid.json", "bead_spring.json", "polymer_melt.json")


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    examples = sys.argv[1]
    with tempfile.TemporaryDirectory() as scratch:
        subprocess.run([sys.executable, os.path.join(examples, "make_inputs.py"), scratch], check=True)
        stale = [name for name in BUNDLED_INPUTS
                 if not filecmp.cmp(os.path.join(examples, name), os.path.join(scratch, name), shallow=False)]
    for name in stale:
        print(f"{name} differs from what make_inputs.py writes now: regenerate it")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
