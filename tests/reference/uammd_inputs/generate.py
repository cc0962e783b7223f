#!/usr/bin/env python3
"""Regenerate UAMMD-structured's own inputs at small size, and sort them by whether structmd loads them.

    python3 generate.py /path/to/UAMMD-structured [--vlmp /path/to/VLMP] [--out DIR] [--keep-scratch]
                        [--no-classify] [--only REGEX]

UAMMD-structured's Examples/*/*.py and Tests/**/scripts/generate*.py (written with its pyUAMMD package)
make the inputs its users have. This script copies the checkout into a scratch directory, shrinks each
generator there (a parameters.json override, or a substitution in an example's source: never in the
checkout itself), runs it from the directory it expects (the one holding parameters.json; an example's
own), and collects the JSON it writes.

With the structmd Python binding importable (bindings/python on sys.path, STRUCTMD_LIBRARY set), each
input is then loaded on the CPU backend and stepped 10 steps: those that pass are copied into --out
(default: this script's directory) as <Origin>__<file>.json; the others, and the generators skipped or
failing, are listed in UNSUPPORTED.md there, grouped by what is missing, the most common first. With
--no-classify every generated input is copied and no table is written.

Python packages the generators need: numpy scipy deepdiff tqdm jsbeautifier json5 icosphere
numpy-quaternion. The HarmonicRAP generator takes its helix geometry from VLMP (github.com/PabloIbannez/VLMP,
not on PyPI): with --vlmp naming a VLMP checkout it runs, importing only the VLMP modules it uses.
"""

import argparse
import collections
import copy
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", "..", ".."))

# Generators not run, and why.
SKIPPED = {}
# Generators that import VLMP, run only with --vlmp.
NEEDS_VLMP = {
    "Tests/RAP/HarmonicRAP/scripts/generateHarmonicRAPTest.py":
        "needs the VLMP package (not on PyPI) for its helix geometry: give --vlmp",
}
# The VLMP modules the generators import. They are taken from the checkout into packages of their own
# with empty __init__ files, so that VLMP's package set-up (its logger, colorama, pyquaternion) is not
# needed.
VLMP_MODULES = ["utils/geometry/objects/helix.py"]

# Reductions of Tests/**/parameters.json, applied to the scratch copy: key -> value (dotted keys reach
# into nested objects). Steps are cut so that the inputs are short runs; N so that they are small.
PARAMETER_OVERRIDES = {
    "Tests/AFM/scripts/generateAFMTest.py": {"N": [60, 20, 30, 40, 25]},
    "Tests/Bonds/scripts/generateBondsTest.py": {"N": 10, "nSteps": 100000},
    "Tests/ConditionalListSet/scripts/generateConditionalListSetTest.py": {"nSteps": 100000},
    "Tests/External/ExternalTabulated/scripts/generateExternalTabulated.py": {"Nx": 10, "Ny": 10, "Nz": 10,
                                                                              "N": 100},
    "Tests/External/PolarizationTabulated/scripts/generateExternalTabulated.py": {"Nx": 10, "Ny": 10, "Nz": 10,
                                                                                  "N": 100},
    "Tests/Integrators/scripts/generateIntegratorsTest.py": {"N": 500},
    "Tests/Magnetism/ACFieldFixedParticles/scripts/generateMagneticIntegratorsTest.py": {"N": 100},
    "Tests/Magnetism/ACFieldRigidDipole/scripts/generateMagneticIntegratorsTest.py": {"N": 100},
    "Tests/Magnetism/MagneticRelaxation/scripts/generateTestRelaxationCombined.py": {"N": 100},
    "Tests/Magnetism/MagneticRelaxation/scripts/generateTestRelaxationFixed.py": {"N": 100},
    "Tests/Magnetism/MagneticRelaxation/scripts/generateTestRelaxationRigidDipole.py": {"N": 100},
    "Tests/Magnetism/ThermalFluctuationsFixed/scripts/generateMagneticIntegratorsTest.py": {"N": 100},
    "Tests/NonBonded/scripts/generateNonBondedTest.py": {"N": 4, "nSteps": 100000},
    "Tests/PairParameterHandler/scripts/generatePairParameterHandlerTest.py": {"N": 10, "nSteps": 100000},
    "Tests/Patches/COSRAP/scripts/generateCOSRAPTest.py": {"N": 100},
    "Tests/SingleParameterHandler/scripts/generateSingleParameterHandlerTest.py": {"N": 10, "N_eps_sgm": 10,
                                                                                   "nSteps": 100000},
    "Tests/Surfaces/PlainCylinder/scripts/generatePlainCylinder.py": {"N": 200},
    "Tests/Surfaces/Polyhedron/scripts/generatePolyhedron.py": {"N": 200},
}

# Reductions of generators that keep their parameters in their source: (regex, replacement); also the
# repairs of generators that lag behind UAMMD-structured's own code.
SOURCE_OVERRIDES = {
    # PolarizationTabulated's dielectricConstant (eps = dielectricConstant / (4 pi f)), which the
    # generator predates, was required when this input was made; 4 pi in units None (f = 1) gives
    # eps = 1, the energies its analysis script expects (tabulated x scale x polarizability), the same
    # as leaving it out now.
    "Tests/External/PolarizationTabulated/scripts/generateExternalTabulated.py": [
        (r'\{"nx":Nx,"ny":Ny,"nz":Nz,"scale":scale\}',
         '{"nx":Nx,"ny":Ny,"nz":Nz,"scale":scale,"dielectricConstant":4.0*np.pi}')],
    "Tests/ConditionalListSet/scripts/generateConditionalListSetTest.py": [
        (r"^N  = 8000", "N  = 512"), (r"^box = \[25,25,25\]", "box = [10,10,10]")],
    "Tests/Electrostatics/scripts/generateElectrostaticsTest.py": [(r"^N    = 2e4", "N    = 500"),
                                                                     (r"^nSteps = .*", "nSteps = 1000")],
    "Examples/IdealGas/IdealGas.py": [(r"^N = 2e5", "N = 500"), (r"^nSteps = .*", "nSteps = 1000")],
    "Examples/LennardJones/LennardJones.py": [(r"^N = 2e5", "N = 500"), (r"^nSteps = .*", "nSteps = 1000")],
    "Examples/LennardJonesBatches/LennardJonesBatches.py": [
        (r"^NpartPerBatch = 1e4", "NpartPerBatch = 100"), (r"^Nbatch = 10", "Nbatch = 4"),
        (r"^nSteps = .*", "nSteps = 1000")],
    "Examples/Patches/Patches.py": [(r"^N = 2000", "N = 100"), (r"^nSteps = .*", "nSteps = 1000")],
    # The same volume fraction in a box the near field still fits (psi 0.6: it reaches 6.4).
    "Examples/PSE/PSE.py": [(r"^nParticles        = 1000", "nParticles        = 27"),
                            (r"^L                 = 100", "L                 = 30"),
                            (r"^numberOfSteps     = .*", "numberOfSteps     = 1000")],
    "Examples/WormLikeChain/WLC.py": [(r"^nPolymers = 100", "nPolymers = 5"), (r"^nSteps = .*", "nSteps = 1000")],
    "Examples/WormLikeChainCompression/WLCCompression.py": [
        (r"^nPolymers = 100", "nPolymers = 5"), (r"^nSteps = .*", "nSteps = 1000")],
}

STEPS = 10


def discover(root):
    """Every generator of the checkout, as paths relative to it, in a stable order."""
    found = sorted(glob.glob("Examples/*/*.py", root_dir=root))
    found += sorted(glob.glob("Tests/**/scripts/generate*.py", root_dir=root, recursive=True))
    return found


def origin_name(script):
    """A short name for a generator: Examples/LennardJones/LennardJones.py -> LennardJones,
    Tests/Hessian/WCAType1/scripts/generateTest.py -> Hessian-WCAType1; the file written is appended
    when it is not simulation.json or test.json."""
    parts = script.split("/")
    if parts[0] == "Examples":
        return "Example-" + parts[1]
    name = "-".join(parts[1:parts.index("scripts")])
    return name


def working_directory(script):
    parts = script.split("/")
    if parts[0] == "Examples":
        return os.path.dirname(script)
    return "/".join(parts[:parts.index("scripts")])


def set_dotted(document, key, value):
    *path, last = key.split(".")
    for part in path:
        document = document[part]
    document[last] = value


def prepare(scratch, script):
    """Apply this generator's reductions to the scratch copy."""
    cwd = os.path.join(scratch, working_directory(script))
    overrides = PARAMETER_OVERRIDES.get(script)
    if overrides:
        path = os.path.join(cwd, "parameters.json")
        with open(path) as f:
            text = f.read()
        import json5  # the generators read their parameters with json5 or json; json5 takes both
        parameters = json5.loads(text)
        for key, value in overrides.items():
            set_dotted(parameters, key, value)
        with open(path, "w") as f:
            json.dump(parameters, f, indent=2)
    substitutions = SOURCE_OVERRIDES.get(script)
    if substitutions:
        path = os.path.join(scratch, script)
        with open(path) as f:
            text = f.read()
        for pattern, replacement in substitutions:
            text, count = re.subn(pattern, replacement, text, flags=re.M)
            if count != 1:
                raise RuntimeError(f"{script}: the reduction {pattern!r} matched {count} times")
        with open(path, "w") as f:
            f.write(text)
    return cwd


def stage_vlmp(vlmp, scratch):
    """VLMP_MODULES of the checkout vlmp under scratch/_vlmp/VLMP, returned as a path to import from."""
    root = os.path.join(scratch, "_vlmp")
    for module in VLMP_MODULES:
        target = os.path.join(root, "VLMP", module)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy(os.path.join(vlmp, "VLMP", module), target)
        package = os.path.dirname(target)
        while package != root:
            open(os.path.join(package, "__init__.py"), "a").close()
            package = os.path.dirname(package)
    return root


def run_generator(scratch, script, log, extra_path=()):
    cwd = prepare(scratch, script)
    before = {p: os.path.getmtime(os.path.join(cwd, p)) for p in glob.glob("**/*.json", root_dir=cwd, recursive=True)}
    path = [scratch, *extra_path, os.environ.get("PYTHONPATH", "")]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(path),
               UAMMD_PATH=os.path.join(scratch, "structured"), MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, os.path.relpath(os.path.join(scratch, script), cwd)], cwd=cwd,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    log.write(f"==== {script} (rc {result.returncode})\n{result.stdout}\n")
    if result.returncode != 0:
        lines = [l for l in result.stdout.strip().splitlines() if l.strip()]
        return None, lines[-1] if lines else f"exit code {result.returncode}"
    written = [p for p in glob.glob("**/*.json", root_dir=cwd, recursive=True)
               if p != "parameters.json" and before.get(p) != os.path.getmtime(os.path.join(cwd, p))]
    return [os.path.join(cwd, p) for p in sorted(written)], None


# ---------------------------------------------------------------------------------------------------
# Classification with structmd


def redirect_outputs(document, directory):
    """Point every file an input would write (outputFilePath, filePath...) into directory."""
    for entry in (document.get("simulationStep") or {}).values():
        parameters = entry.get("parameters") if isinstance(entry, dict) else None
        if not isinstance(parameters, dict):
            continue
        for key, value in list(parameters.items()):
            if isinstance(value, str) and key.lower().endswith("filepath"):
                parameters[key] = os.path.join(directory, os.path.basename(str(value)) or "out")
    return document


def try_structmd(path, steps=STEPS):
    """None if structmd loads and steps the input, else (kind, message)."""
    import numpy as np
    import structmd
    with open(path) as f:
        document = json.load(f)
    with tempfile.TemporaryDirectory() as tmp:
        redirect_outputs(document, tmp)
        try:
            with structmd.Simulation({"backend": "cpu", "log": "quiet"}) as sim:
                sim.load(document)
                sim.step(steps)
                if not np.all(np.isfinite(sim.positions)):
                    return ("step", "positions not finite after 10 steps")
        except structmd.StructmdError as error:
            return (type(error).__name__, str(error))
    return None


def first_error(message):
    """The message without the nearest known names that follow it, on one line."""
    return re.sub(r"\s+", " ", message.split("; nearest known")[0]).strip()


def missing_thing(message):
    """What the first error says is missing, as a short key to group inputs by."""
    m = re.search(r"unknown (component|simulation step|integrator) \[\s*\"?(\w+)\"?\s*,\s*\"?(\w+)\"?\s*\]", message)
    if m:
        return f"{m.group(1)} {m.group(2)}/{m.group(3)}"
    m = re.search(r"^(\w+)\.labels\[\d+\]: unknown label '(\w+)'", message)
    if m:
        return f"{m.group(1)} label {m.group(2)}"
    return first_error(message)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("checkout", help="a UAMMD-structured checkout (its Examples/, Tests/ and pyUAMMD/)")
    parser.add_argument("--out", default=HERE)
    parser.add_argument("--keep-scratch", action="store_true")
    parser.add_argument("--no-classify", action="store_true")
    parser.add_argument("--only", help="a regular expression on the generator paths")
    parser.add_argument("--vlmp", help="a VLMP checkout, for the generators that import it")
    args = parser.parse_args()

    checkout = os.path.abspath(args.checkout)
    scratch = tempfile.mkdtemp(prefix="uammd-inputs-")
    shutil.copytree(checkout, scratch, dirs_exist_ok=True, ignore=shutil.ignore_patterns(".git", "results"))
    staged = os.path.join(scratch, "_generated")
    os.makedirs(staged)
    if not args.no_classify:
        sys.path.insert(0, os.path.join(REPO, "bindings", "python"))

    generators = [g for g in discover(checkout) if not args.only or re.search(args.only, g)]
    vlmp_path = [stage_vlmp(os.path.abspath(args.vlmp), scratch)] if args.vlmp else []
    not_run = dict(SKIPPED, **({} if args.vlmp else NEEDS_VLMP))
    skipped, failed, inputs = [], [], []  # inputs: (origin script, staged path)
    with open(os.path.join(scratch, "generators.log"), "w") as log:
        for script in generators:
            if script in not_run:
                skipped.append((script, not_run[script]))
                print(f"skip  {script}: {not_run[script]}")
                continue
            try:
                written, error = run_generator(scratch, script, log, vlmp_path if script in NEEDS_VLMP else ())
            except subprocess.TimeoutExpired:
                written, error = None, "timed out"
            if error:
                failed.append((script, error))
                print(f"FAIL  {script}: {error}")
                continue
            for path in written:
                name = origin_name(script)
                base = os.path.splitext(os.path.basename(path))[0]
                if base not in ("simulation", "test"):
                    name += "__" + base
                target = os.path.join(staged, name + ".json")
                shutil.copy(path, target)
                inputs.append((script, target))
                print(f"ok    {script} -> {name}.json ({os.path.getsize(target) // 1024} kB)")

    os.makedirs(args.out, exist_ok=True)
    results = {}
    for script, path in inputs:
        name = os.path.basename(path)
        results[name] = None if args.no_classify else try_structmd(path)
        if results[name] is None:
            shutil.copy(path, os.path.join(args.out, name))
        print(("copied " if args.no_classify else "loads " if results[name] is None else "no    ") + name +
              ("" if results[name] is None else f": {results[name][1][:160]}"))

    with open(os.path.join(args.out, "origins.json"), "w") as f:
        json.dump({os.path.basename(p): s for s, p in inputs if results[os.path.basename(p)] is None}, f,
                  indent=1, sort_keys=True)
        f.write("\n")
    if not args.no_classify:
        write_unsupported(args.out, inputs, results, skipped, failed)
    print(f"{len(generators)} generators: {len(skipped)} skipped, {len(failed)} failed; "
          f"{len(inputs)} inputs, {sum(r is None for r in results.values())} load and step")
    if args.keep_scratch:
        print("scratch:", scratch)
    else:
        shutil.rmtree(scratch)


def write_unsupported(out, inputs, results, skipped, failed):
    groups = collections.defaultdict(list)
    for script, path in inputs:
        name = os.path.basename(path)
        if results[name] is not None:
            kind, message = results[name]
            groups[missing_thing(message)].append((name, script, kind, message))
    lines = ["# UAMMD-structured inputs structmd cannot load yet", "",
             "Written by generate.py (do not edit by hand). Each row is one input made by UAMMD-structured's",
             "generators at small size, with the first error structmd gives when it loads it and steps it",
             f"{STEPS} steps on the CPU backend. Grouped by what is missing, the thing blocking most inputs first.",
             "", "## Missing, by number of inputs blocked", "", "| missing | inputs |", "| --- | --- |"]
    ordered = sorted(groups.items(), key=lambda item: (-len(item[1]), item[0]))
    for key, rows in ordered:
        lines.append(f"| {key} | {len(rows)} |")
    lines += ["", "## Inputs", "", "| missing | input | generator | first error |", "| --- | --- | --- | --- |"]
    for key, rows in ordered:
        for name, script, kind, message in sorted(rows):
            text = first_error(message).replace("|", "\\|")
            lines.append(f"| {key} | {name} | {script} | {kind}: {text} |")
    if skipped or failed:
        lines += ["", "## Generators not run or failing", "", "| generator | why |", "| --- | --- |"]
        for script, why in skipped + failed:
            lines.append(f"| {script} | {why.replace('|', '/')} |")
    with open(os.path.join(out, "UNSUPPORTED.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
