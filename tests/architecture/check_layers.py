#!/usr/bin/env python3
"""Checks that every #include in src/ points down the layers of docs/architecture.md.

Each folder of src/ may include only the folders listed for it. CMake's targets keep the layers'
compiled code apart; this check covers the headers, which a target cannot fence off because every
layer sees src/ as its include root. Run with the repository root; --self-test shows that an upward
include is caught.
"""
import pathlib
import re
import sys

BASE = {"core"}
ALLOWED = {
    "core": BASE,
    "state": BASE | {"state"},
    "backends": BASE | {"state", "backends"},
    "input": BASE | {"input"},
    "expression": BASE | {"expression"},
    "neighbour": BASE | {"state", "neighbour"},
    "forcefield": BASE | {"state", "input", "expression", "neighbour", "forcefield"},
    "hydrodynamics": BASE | {"state", "neighbour", "hydrodynamics"},
    "integrators": BASE | {"state", "input", "expression", "neighbour", "forcefield", "hydrodynamics", "integrators"},
    "steps": BASE | {"state", "input", "expression", "neighbour", "forcefield", "hydrodynamics", "integrators",
                     "simulation", "steps"},
    "simulation": BASE | {"state", "input", "expression", "neighbour", "forcefield", "hydrodynamics", "integrators",
                          "simulation", "steps"},
    "engines": BASE | {"state", "input", "expression", "neighbour", "forcefield", "hydrodynamics", "integrators",
                       "simulation", "steps", "backends", "engines"},
    "parallel": BASE | {"state", "input", "forcefield", "simulation", "steps", "engines", "parallel"},
    "api": BASE | {"simulation", "engines", "parallel", "api"},
    "launcher": set(),  # a host like any other: the public header only
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
SOURCES = {".hpp", ".cpp", ".cuh", ".cu", ".h"}


def violations(files):
    """files: {relative path under src/: text}. Returns the upward or unknown includes."""
    found = []
    for path, text in sorted(files.items()):
        layer = path.split("/", 1)[0]
        if layer not in ALLOWED:
            found.append(f"src/{path}: folder '{layer}' has no place in the layers (add it to {__file__})")
            continue
        for target in INCLUDE.findall(text):
            if "/" not in target:
                continue  # the public header and system-style includes
            folder = target.split("/", 1)[0]
            if folder not in ALLOWED[layer]:
                found.append(f"src/{path}: includes \"{target}\", but {layer}/ may include only "
                             f"{', '.join(sorted(ALLOWED[layer])) or 'the public header'}")
    return found


def read_tree(src):
    return {str(p.relative_to(src)): p.read_text(encoding="utf-8")
            for p in src.rglob("*") if p.suffix in SOURCES}


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else ".")
    files = read_tree(root / "src")
    if "--self-test" in sys.argv:
        broken = dict(files)
        broken["backends/cpu/cpu_backend.hpp"] += '\n#include "simulation/engine.hpp"\n'
        caught = violations(broken)
        if not any("backends/cpu/cpu_backend.hpp" in v and "simulation/engine.hpp" in v for v in caught):
            print("self-test: an upward include from backends/ to simulation/ was not caught")
            return 1
        print("self-test: an upward include is caught")
    found = violations(files)
    for v in found:
        print(v)
    print(f"{len(files)} files checked, {len(found)} upward includes")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
