"""Loads the example plugin (examples/plugins/yukawa.cu) into the installed library and checks it:
its component is read from JSON and computed (forces and energy equal the Yukawa formula, on every
precision, before and after steps), it loads through the "plugins" option and through
structmd_load_plugin with the semantics of the header (handles created before a process-wide load
do not see it; handles stay independent), and bad plugins are refused with clear errors.
Exit 77 (ctest's skip) for --backend cuda where no GPU is usable."""

import argparse
import json
import math
import os
import re
import shutil
import sys
import tempfile

import numpy as np

import structmd

SKIP = 77


def yukawa_reference(doc, positions):
    """Forces (n, 3) and energy of the input's Yukawa entry at `positions`, from the formula
    U = epsilon (sigma / r) exp(-kappa (r - sigma)) for r < cutOffFactor sigma."""
    box = np.array(doc["global"]["ensemble"]["data"][0][0])
    entry = doc["topology"]["forceField"]["yukawa"]
    kappa, factor = entry["parameters"]["kappa"], entry["parameters"]["cutOffFactor"]
    table = {}
    for name_i, name_j, epsilon, sigma in entry["data"]:
        table[(name_i, name_j)] = table[(name_j, name_i)] = (epsilon, sigma)
    types = [t for _, t in doc["topology"]["structure"]["data"]]
    n = len(types)
    forces, energy = np.zeros((n, 3)), 0.0
    for i in range(n):
        for j in range(i + 1, n):
            epsilon, sigma = table[(types[i], types[j])]
            d = positions[j] - positions[i]
            d -= box * np.round(d / box)
            r = np.linalg.norm(d)
            if r >= factor * sigma:
                continue
            u = epsilon * sigma / r * math.exp(-kappa * (r - sigma))
            dudr = -u * (1.0 / r + kappa)
            energy += u
            forces[i] += dudr * d / r  # F_i = U'(r) r_ij / r, r_ij = r_j - r_i
            forces[j] -= dudr * d / r
    return forces, energy


def check_physics(sim, doc, tolerance, label):
    for steps in (0, 20):
        sim.step(steps)
        forces, energy = yukawa_reference(doc, np.asarray(sim.positions))
        assert np.abs(forces).max() > 0.05, f"{label}: the test geometry has no force to check"
        got_f, got_e = np.asarray(sim.forces), sim.energy("potential")
        assert np.allclose(got_f, forces, rtol=tolerance, atol=tolerance), f"{label}: forces {got_f} != {forces}"
        assert abs(got_e - energy) <= tolerance * max(1.0, abs(energy)), f"{label}: energy {got_e} != {energy}"
        assert abs(sim.energy("yukawa") - got_e) <= tolerance * max(1.0, abs(energy))


def expect_failure(error_type, words, call):
    try:
        call()
    except error_type as e:
        for word in words:
            assert word in e.message, f"message {e.message!r} lacks {word!r}"
        print(f"refused as expected ({error_type.__name__}): {e.message}")
        return
    raise AssertionError(f"expected {error_type.__name__} mentioning {words}")


def plugin_abi_version():
    """The plugin ABI version this source tree's library speaks (engines/plugin_abi.hpp)."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "engines", "plugin_abi.hpp")
    with open(header) as f:
        return int(re.search(r"#define STRUCTMD_PLUGIN_ABI_VERSION (\d+)", f.read()).group(1))


def main():
    parser = argparse.ArgumentParser()
    for option in ("--backend", "--plugin", "--wrong-abi", "--not-plugin", "--input"):
        parser.add_argument(option, required=True)
    parser.add_argument("--cpu-only", help="the plugin built without CUDA factories (CUDA runs only)")
    args = parser.parse_args()
    with open(args.input) as f:
        doc = json.load(f)
    text = json.dumps(doc)
    options = {"backend": args.backend, "log": "quiet"}

    if args.backend == "cuda":
        try:
            structmd.Simulation(options).close()
        except (structmd.DeviceError, structmd.UnsupportedError) as e:
            print(f"skipped: {e.message}")
            return SKIP

    # Without the plugin the component is unknown: the checks below can only pass through the plugin.
    before = structmd.Simulation(options)
    expect_failure(structmd.InputError, ['["NonBonded", "Yukawa"]', "unknown"], lambda: before.load(text))

    # Per handle, through the "plugins" option, on every precision.
    tolerances = {"single": 2e-4, "mixed": 2e-4, "double": 1e-10}
    for precision, tolerance in tolerances.items():
        with structmd.Simulation({**options, "precision": precision, "plugins": [args.plugin]}) as sim:
            sim.load(text)
            check_physics(sim, doc, tolerance, f"option, {precision}")
    # The option is the handle's own: a handle created afterwards without it does not know Yukawa.
    with structmd.Simulation(options) as other:
        expect_failure(structmd.InputError, ["unknown"], lambda: other.load(text))

    # The same component twice (the plugin under a second name) is refused, naming both.
    with tempfile.TemporaryDirectory() as folder:
        twin = os.path.join(folder, "twin.so")
        shutil.copy(args.plugin, twin)
        expect_failure(structmd.ArgumentError, ["already provides", twin, args.plugin],
                       lambda: structmd.Simulation({**options, "plugins": [args.plugin, twin]}))

    # A plugin without CUDA factories runs on the CPU, and is refused by name on CUDA.
    if args.cpu_only:
        with structmd.Simulation({**options, "backend": "cpu", "plugins": [args.cpu_only]}) as sim:
            sim.load(text)
            check_physics(sim, doc, 1e-4, "no CUDA factories, on the CPU")
        with structmd.Simulation({**options, "plugins": [args.cpu_only]}) as sim:
            expect_failure(structmd.UnsupportedError,
                           ["topology.forceField.yukawa", '["NonBonded", "Yukawa"]', "no implementation for the cuda"],
                           lambda: sim.load(text))

    # Refused plugins: another plugin ABI, not a plugin, no file. Nothing of them is loaded.
    expect_failure(structmd.UnsupportedError, ["plugin ABI 999", f"speaks plugin ABI {plugin_abi_version()}", "not loaded"],
                   lambda: structmd.load_plugin(args.wrong_abi))
    expect_failure(structmd.UnsupportedError, ['option "plugins"', "plugin ABI 999"],
                   lambda: structmd.Simulation({**options, "plugins": [args.wrong_abi]}))
    expect_failure(structmd.ArgumentError, ["not a structmd plugin"], lambda: structmd.load_plugin(args.not_plugin))
    expect_failure(structmd.StructmdIOError, ["cannot open"], lambda: structmd.load_plugin(args.plugin + ".missing"))
    expect_failure(structmd.ArgumentError, ['option "plugins"', "expected an array"],
                   lambda: structmd.Simulation({**options, "plugins": args.plugin}))
    with structmd.Simulation(options) as other:
        expect_failure(structmd.InputError, ["unknown"], lambda: other.load(text))

    # Process-wide: handles created after structmd_load_plugin know the component, those created
    # before do not; loading it again is no error, nor is naming it again in the option.
    structmd.load_plugin(args.plugin)
    structmd.load_plugin(args.plugin)
    expect_failure(structmd.InputError, ["unknown"], lambda: before.load(text))
    before.close()
    with structmd.Simulation({**options, "precision": "double"}) as sim:
        sim.load(text)
        check_physics(sim, doc, tolerances["double"], "structmd_load_plugin")
    with structmd.Simulation({**options, "precision": "double", "plugins": [args.plugin]}) as sim:
        sim.load(text)
        check_physics(sim, doc, tolerances["double"], "structmd_load_plugin and option")
    print(f"plugin checks passed on {args.backend}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
