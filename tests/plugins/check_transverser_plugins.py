"""Loads the example transverser plugins (examples/plugins: neighbour_count.cu, local_density.cu,
lennard_jones_force.cu) into the installed library and runs them by name with structmd_traverse
(Simulation.traverse): neighbour counts and local densities against numpy over a neighbour list, over
all pairs and over a group, the Lennard-Jones force transverser against the engine's own
["NonBonded", "LennardJonesType1"] forces, before and after steps, on every precision the library
has; structmd_traverse_view (Simulation.traverse_view) lends the same values where the engine computed
them (host memory on the CPU backend, the GPU on CUDA, read through CuPy or PyTorch where installed);
then the refusals (unknown name, bad parameters, unknown group, wrong n).
Exit 77 (ctest's skip) for --backend cuda where no GPU is usable."""

import argparse
import ctypes
import importlib
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

import structmd
from structmd._library import lib
from structmd.dlpack import K_DL_CPU, K_DL_CUDA

from check_plugins import expect_failure  # beside this script, which is run by its path
from measure_files import read_step_blocks  # tests/python, on the path check_plugins.sh gives

SKIP = 77
BOX = 8.0
N = 240


def liquid_input(seed=4):
    """A box of N particles of two types (masses 1 and 2), well apart (no overlaps: finite LJ forces),
    with an LJ entry of cutoff 2.5 and a group of the even ids."""
    rng = np.random.default_rng(seed)
    positions = []
    while len(positions) < N:
        p = rng.uniform(-BOX / 2, BOX / 2, 3)
        if all(np.linalg.norm(minimum_image(p - q)) > 0.85 for q in positions):
            positions.append(p)
    velocities = rng.normal(0.0, 0.5, size=(N, 3))
    types = ["A" if i % 3 else "B" for i in range(N)]
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "transversers", "seed": 3}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.5, 0.0], ["B", 2.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 1.0]]},
            "fundamental": {"type": ["Fundamental", "Time"], "parameters": {"timeStep": 0.002}},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"]},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 1000]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, list(map(float, p)), list(map(float, v))]
                           for i, (p, v) in enumerate(zip(positions, velocities))]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
            "forceField": {
                "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                           "data": [["even", "Ids", list(range(0, N, 2))]]},
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"],
                       "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"],
                       "data": [["A", "A", 1.0, 1.0], ["A", "B", 1.0, 1.0], ["B", "B", 1.0, 1.0]]},
            },
        },
    }


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def separations(positions):
    p = np.asarray(positions)
    d = minimum_image(p[None, :, :] - p[:, None, :])  # d[i, j] = r_j - r_i
    r = np.linalg.norm(d, axis=2)
    np.fill_diagonal(r, np.inf)
    return d, r


def close(got, expected, tolerance, label):
    scale = max(1.0, float(np.abs(expected).max()))
    error = float(np.abs(np.asarray(got) - expected).max())
    assert error <= tolerance * scale, f"{label}: off by {error} (scale {scale})"


def check_counts_and_densities(sim, tolerance, label):
    d, r = separations(sim.positions)
    counts = sim.traverse("NeighbourCount", 1.5)
    assert counts.shape == (N,)
    np.testing.assert_array_equal(counts, np.sum(r < 1.5, axis=1), err_msg=label)
    assert counts.sum() > 2 * N, "too sparse a test"
    np.testing.assert_array_equal(sim.traverse("NeighbourCount"), np.full(N, N - 1), err_msg=label)

    # Over a group: only its members are traversed, and they pair with members only.
    even = np.arange(N) % 2 == 0
    grouped = sim.traverse("NeighbourCount", 1.5, {"group": "even"})
    expected = np.where(even, np.sum((r < 1.5) & even[None, :], axis=1), 0)
    np.testing.assert_array_equal(grouped, expected, err_msg=label)

    masses = np.asarray(sim.masses)
    sigma = 0.8
    weights = masses[None, :] * np.exp(-r**2 / (2 * sigma**2))
    close(sim.traverse("LocalDensity", 2.5, {"sigma": sigma}), np.where(r < 2.5, weights, 0.0).sum(axis=1),
          tolerance, f"{label}: local density over a list")
    close(sim.traverse("LocalDensity", 0.0, {"sigma": sigma}), weights.sum(axis=1), tolerance,
          f"{label}: local density over all pairs")


def check_lennard_jones(sim, tolerance, label):
    forces = sim.traverse("LennardJonesForce", 2.5, {"epsilon": 1.0, "sigma": 1.0})
    assert forces.shape == (N, 3)
    engine = np.asarray(sim.forces)
    assert np.abs(engine).max() > 1.0, "the test geometry has no force to check"
    close(forces, engine, tolerance, f"{label}: LJ transverser against the engine's LJ")
    # The handle keeps its last call made from the same arguments: other parameters make another.
    close(sim.traverse("LennardJonesForce", 2.5, {"epsilon": 2.0, "sigma": 1.0}), 2 * forces, tolerance,
          f"{label}: LJ transverser at twice epsilon")
    close(sim.traverse("LennardJonesForce", 2.5, {"epsilon": 1.0, "sigma": 1.0}), forces, tolerance,
          f"{label}: LJ transverser back at epsilon 1")
    # And against numpy, which knows nothing of either.
    d, r = separations(sim.positions)
    with np.errstate(divide="ignore", invalid="ignore"):
        s6 = np.where(r < 2.5, r**-6.0, 0.0)
        magnitude = np.where(r < 2.5, -24.0 * (2 * s6 * s6 - s6) / r**2, 0.0)
    close(forces, (magnitude[:, :, None] * d).sum(axis=1), tolerance, f"{label}: LJ transverser against numpy")


def host_copy(view):
    """The view's values copied to the host: by numpy for host memory; through CuPy or PyTorch, where
    one is installed, for GPU memory (None without either)."""
    if view.device[0] == K_DL_CPU:
        return np.from_dlpack(view).copy()
    for name in ("cupy", "torch"):
        try:
            module = importlib.import_module(name)
        except ImportError:
            continue
        array = module.from_dlpack(view)
        return array.get() if name == "cupy" else array.cpu().numpy()
    return None


def check_views(sim, backend, bits, tolerance, label):
    """traverse_view: the shape, the device and the precision of the engine, the values of traverse.
    Each view is read before the next run, which reuses the engine's output array."""
    for name, cutoff, parameters, shape in (("NeighbourCount", 1.5, None, (N,)),
                                            ("LocalDensity", 2.5, {"sigma": 0.8}, (N,)),
                                            ("LennardJonesForce", 2.5, {"epsilon": 1.0, "sigma": 1.0}, (N, 3))):
        expected = sim.traverse(name, cutoff, parameters)
        view = sim.traverse_view(name, cutoff, parameters)
        assert view.shape == shape and view.bits == bits, (label, name, view.shape, view.bits)
        assert view.device[0] == (K_DL_CUDA if backend == "cuda" else K_DL_CPU), (label, name, view.device)
        values = host_copy(view)
        if values is not None:
            close(values, expected, tolerance, f"{label}: {name} through traverse_view")


def check_measure(options, tolerance, label):
    """["TransverserMeasure","Plugin"] with the LJ force transverser (three values a particle) over
    the even group: every 25 steps the rows of the group, each the engine's LJ force on the particle
    from the other members, as traverse gives it at that step."""
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "forces.dat"
        doc = liquid_input()
        doc["simulationStep"] = {"forces": {
            "type": ["TransverserMeasure", "Plugin"],
            "parameters": {"intervalStep": 25, "outputFilePath": str(output), "transverser": "LennardJonesForce",
                           "transverserParameters": {"epsilon": 1.0, "sigma": 1.0}, "cutOff": 2.5,
                           "group": "even"}}}
        expected = {}
        with structmd.Simulation(options) as sim:
            sim.load(json.dumps(doc))
            for steps in (0, 25, 25):
                sim.step(steps)
                expected[sim.step_number] = sim.traverse("LennardJonesForce", 2.5,
                                                         {"epsilon": 1.0, "sigma": 1.0, "group": "even"})
        header, blocks = read_step_blocks(output)
        assert header == "# id value_0 value_1 value_2", header
        assert sorted(blocks) == [0, 25, 50], sorted(blocks)
        even = np.arange(0, N, 2)
        for step, rows in blocks.items():
            np.testing.assert_array_equal(rows[:, 0], even)
            assert np.abs(rows[:, 1:]).max() > 1.0, "the test geometry has no force to check"
            close(rows[:, 1:], expected[step][even], tolerance, f"{label}: the measure's forces at step {step}")


def check_refusals(sim):
    expect_failure(structmd.ArgumentError, ["no transverser named 'Nope'", "'NeighbourCount'", "'LocalDensity'"],
                   lambda: sim.traverse("Nope"))
    expect_failure(structmd.InputError, ["LocalDensity.parameters.sigma", "missing required"],
                   lambda: sim.traverse("LocalDensity", 2.5))
    expect_failure(structmd.InputError, ["LocalDensity.parameters.sigma", "positive"],
                   lambda: sim.traverse("LocalDensity", 2.5, {"sigma": -1.0}))
    expect_failure(structmd.InputError, ["NeighbourCount.parameters.radius", "unknown parameter"],
                   lambda: sim.traverse("NeighbourCount", 2.5, {"radius": 1.0}))
    expect_failure(structmd.InputError, ["no group named 'odd'"],
                   lambda: sim.traverse("NeighbourCount", 2.5, {"group": "odd"}))
    expect_failure(structmd.InputError, ["cutoff"], lambda: sim.traverse("NeighbourCount", -1.0))
    expect_failure(structmd.ArgumentError, ["no transverser named 'Nope'"], lambda: sim.traverse_view("Nope"))
    expect_failure(structmd.InputError, ["LocalDensity.parameters.sigma", "positive"],
                   lambda: sim.traverse_view("LocalDensity", 2.5, {"sigma": -1.0}))
    # The C call itself: n must be values x particles, parameters a JSON object.
    out = (ctypes.c_double * (3 * N))()
    handle = sim._handle
    assert lib.structmd_traverse(handle, b"LennardJonesForce", b'{"epsilon": 1, "sigma": 1}', 2.5, out, N) != 0
    assert "3 per particle" in sim.last_error, sim.last_error
    assert lib.structmd_traverse(handle, b"NeighbourCount", b"[1]", 2.5, out, N) != 0
    assert "expected a JSON object" in sim.last_error, sim.last_error
    assert lib.structmd_traverse(handle, b"NeighbourCount", None, 2.5, out, N) == 0
    values = ctypes.c_int()
    assert lib.structmd_transverser_values(handle, b"LennardJonesForce", ctypes.byref(values)) == 0
    assert values.value == 3


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--backend", required=True)
    parser.add_argument("--plugins", nargs="+", required=True)
    args = parser.parse_args()
    options = {"backend": args.backend, "log": "quiet", "plugins": args.plugins}
    text = json.dumps(liquid_input())

    if args.backend == "cuda":
        try:
            structmd.Simulation({"backend": "cuda", "log": "quiet"}).close()
        except (structmd.DeviceError, structmd.UnsupportedError) as e:
            print(f"skipped: {e.message}")
            return SKIP

    checked = []
    for precision, tolerance in {"single": 2e-4, "mixed": 2e-4, "double": 1e-10}.items():
        try:
            sim = structmd.Simulation({**options, "precision": precision})
        except structmd.UnsupportedError as e:
            print(f"{precision}: not built ({e.message})")
            continue
        with sim:
            sim.load(text)
            for steps in (0, 50):
                sim.step(steps)
                check_counts_and_densities(sim, tolerance, f"{precision}, step {sim.step_number}")
                check_lennard_jones(sim, tolerance, f"{precision}, step {sim.step_number}")
                check_views(sim, args.backend, 32 if precision == "single" else 64, tolerance,
                            f"{precision}, step {sim.step_number}")
            if precision == "double":
                check_refusals(sim)
        check_measure({**options, "precision": precision}, tolerance, precision)
        checked.append(precision)
    assert checked, "no precision could be checked"
    print(f"transverser plugin checks passed on {args.backend} ({', '.join(checked)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
