#!/usr/bin/env python3
"""Checks that every #include in src/ points down the layers of docs/architecture.md, and that
components are known through their registries only.

Each folder of src/ may include only the folders listed for it. CMake's targets keep the layers'
compiled code apart; this check covers the headers, which a target cannot fence off because every
layer sees src/ as its include root.

A component's name (the SubClass of its key ["Class", "SubClass"]) is written in its registry or its
own definition only: anywhere else a string literal of it would be a second list of components by
hand. And parallel/ and api/ decide from the parsed input (input/description.hpp), not from the
JSON: they include nlohmann only in the files listed with a reason in JSON_ALLOWED.

Run with the repository root; --self-test shows that each kind of violation is caught.
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
    "transverser": BASE | {"state", "neighbour", "transverser"},
    "forcefield": BASE | {"state", "input", "expression", "neighbour", "transverser", "forcefield"},
    "hydrodynamics": BASE | {"state", "neighbour", "hydrodynamics"},
    "integrators": BASE | {"state", "input", "expression", "neighbour", "forcefield", "hydrodynamics", "integrators"},
    "steps": BASE | {"state", "input", "expression", "neighbour", "transverser", "forcefield", "hydrodynamics", "integrators",
                     "simulation", "steps"},
    "simulation": BASE | {"state", "input", "expression", "neighbour", "transverser", "forcefield", "hydrodynamics", "integrators",
                          "simulation", "steps"},
    "engines": BASE | {"state", "input", "expression", "neighbour", "transverser", "forcefield", "hydrodynamics", "integrators",
                       "simulation", "steps", "backends", "engines"},
    "parallel": BASE | {"state", "input", "forcefield", "integrators", "simulation", "steps", "engines", "parallel"},
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


# Where component keys are written: the force-field and integrator lists (a visitor call's first
# argument, `v.template pair<P>({"NonBonded", "X"})`) and each simulation step's entry function
# (`return {{"WriteStep", "WriteStep"}, ...}` or `SimulationStepEntry entry{{...}, ...}`).
KEY_LISTS = ("forcefield/components.hpp", "integrators/integrators.hpp")
LIST_KEY = re.compile(r'\(\s*\{\s*"(\w+)"\s*,\s*"(\w+)"\s*\}')
STEP_KEY = re.compile(r'\{\{\s*"(\w+)"\s*,\s*"(\w+)"\s*\}')
# Files besides those that write keys that may name components, and why.
NAME_ALLOWED = {
    "integrators/read_integrators.cpp": "the integrator registry's reader: refuses two UAMMD-structured "
                                        "integrators that structmd lacks, naming what to use instead",
    "integrators/bdhi_quasi2d.hpp": "the integrator's own definition: its hydrodynamic kernel is also "
                                    "called Quasi2D",
    "forcefield/patchy_read.cpp": "the reader of the patchy particles' two keys, which differ in whether "
                                  "bonds form",
}
# Registered names that are also words of another vocabulary.
NOT_COMPONENT_NAMES = {
    "None": "also the units and the fundamental entry of none (input/document.cpp)",
}
# Files of parallel/ and api/ that may include nlohmann, and why.
JSON_ALLOWED = {
    "parallel/batch_split.hpp": "writes each rank's share of the batches as a document of its own",
    "parallel/batch_split.cpp": "writes each rank's share of the batches as a document of its own",
    "parallel/replica_documents.hpp": "writes each replica's document: its temperature, seed and file names",
    "parallel/replica_documents.cpp": "writes each replica's document: its temperature, seed and file names",
    "parallel/load_over_ranks.cpp": "hands the documents of batch_split and replica_documents to the reader",
    "api/info.cpp": "writes the JSON of structmd_get_info",
    "api/counters.cpp": "writes the JSON of structmd_get_counters",
    "api/parameters.cpp": "structmd_set_parameter edits the kept input's tables before they are read again",
}
COMMENT = re.compile(r'//[^\n]*|/\*.*?\*/', re.DOTALL)
STRING = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
NLOHMANN = re.compile(r'^\s*#\s*include\s+<nlohmann/', re.MULTILINE)


def component_names(files):
    """{name: the files that write its key}, from the key lists and the simulation steps' entries."""
    names = {}
    for path, text in files.items():
        pattern = LIST_KEY if path in KEY_LISTS else STEP_KEY if path.startswith("steps/") else None
        if pattern:
            for _, name in pattern.findall(COMMENT.sub("", text)):
                names.setdefault(name, set()).add(path)
    for name in NOT_COMPONENT_NAMES:
        names.pop(name, None)
    return names


def name_violations(files):
    """String literals of a component's name outside the files that write component keys."""
    names = component_names(files)
    writers = set().union(*names.values()) if names else set()
    found = []
    for path, text in sorted(files.items()):
        if path in writers or path in NAME_ALLOWED:
            continue
        for literal in STRING.findall(COMMENT.sub("", text)):
            if literal in names:
                found.append(f"src/{path}: the string \"{literal}\" names a component "
                             f"(registered in {', '.join(sorted(names[literal]))}); ask its registry entry instead")
    return found


def json_violations(files):
    """parallel/ and api/ files that include nlohmann without a reason in JSON_ALLOWED."""
    return [f"src/{path}: includes nlohmann; parallel/ and api/ work from the parsed input "
            f"(input/description.hpp), or list the file with its reason in JSON_ALLOWED"
            for path, text in sorted(files.items())
            if path.split("/", 1)[0] in ("parallel", "api") and path not in JSON_ALLOWED and NLOHMANN.search(text)]


def read_tree(src):
    return {str(p.relative_to(src)): p.read_text(encoding="utf-8")
            for p in src.rglob("*") if p.suffix in SOURCES}


def self_test(files):
    """Each check finds a violation planted in a copy of the tree; returns what was missed."""
    missed = []
    broken = dict(files)
    broken["backends/cpu/cpu_backend.hpp"] += '\n#include "simulation/engine.hpp"\n'
    if not any("backends/cpu/cpu_backend.hpp" in v and "simulation/engine.hpp" in v for v in violations(broken)):
        missed.append("an upward include from backends/ to simulation/")
    broken = dict(files)
    broken["parallel/communicator.cpp"] += '\nconst char* const kTerm = "LennardJonesType1";\n'
    if not any("parallel/communicator.cpp" in v and "LennardJonesType1" in v for v in name_violations(broken)):
        missed.append("a pair term's name in parallel/")
    broken = dict(files)
    broken["api/lifecycle.cpp"] += '\n#include <nlohmann/json.hpp>\n'
    if not any("api/lifecycle.cpp" in v for v in json_violations(broken)):
        missed.append("an include of nlohmann in api/")
    return missed


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else ".")
    files = read_tree(root / "src")
    if "--self-test" in sys.argv:
        missed = self_test(files)
        for what in missed:
            print(f"self-test: {what} was not caught")
        if missed:
            return 1
        print("self-test: an upward include, a component's name and an include of nlohmann are caught")
    found = violations(files) + name_violations(files) + json_violations(files)
    for v in found:
        print(v)
    print(f"{len(files)} files checked, {len(found)} violations "
          f"({len(component_names(files))} component names known)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
