"""The ctypes package bindings/python/structmd: its constants against include/structmd.h (its
signature table: tests/api/test_python_binding.py), library discovery, every method and property of Simulation, and the exception class of each status."""

import inspect
import json
import os
import pickle
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import structmd
import structmd.dlpack
import structmd.ipi
import structmd.plot
import structmd.simulation as simulation_module
import structmd_header
import systems
from structmd import _library
from structmd.errors import ERROR_CLASSES

PACKAGE_PARENT = Path(structmd.__file__).resolve().parents[1]

def status_of(name):
    return structmd_header.header_defines()[name]


@pytest.fixture
def sim(options):
    with structmd.Simulation(options) as simulation:
        yield simulation


@pytest.fixture
def loaded(sim):
    return sim.load(systems.lj_bond_system())


@pytest.fixture
def without_numpy(monkeypatch):
    monkeypatch.setattr(simulation_module, "_np", None)


def run_python(code, env_changes):
    env = {key: value for key, value in os.environ.items() if key != "STRUCTMD_LIBRARY"}
    env.update(env_changes)
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], env=env, capture_output=True, text=True)


# ---- the package's tables against the header ---------------------------------------------------

def test_constants_equal_the_header_defines():
    assert structmd.constants.header_defines() == structmd_header.header_defines()


def test_every_failure_status_has_its_own_exception_class():
    failures = {value for name, value in structmd.STATUS.items() if name != "STRUCTMD_OK"}
    assert set(ERROR_CLASSES) == failures
    assert len(set(ERROR_CLASSES.values())) == len(failures)
    for status, cls in ERROR_CLASSES.items():
        assert issubclass(cls, structmd.StructmdError)
        assert structmd.STATUS[cls.status_name] == status


def test_loading_declares_every_function_of_the_table():
    # The table itself is held to the header type by type in tests/api/test_python_binding.py.
    for name, (restype, argtypes) in _library.SIGNATURES.items():
        function = getattr(_library.lib, name)
        assert (function.restype, function.argtypes) == (restype, argtypes), name


def test_versions():
    assert structmd.abi_version() == structmd.ABI_VERSION == status_of("STRUCTMD_ABI_VERSION")
    assert structmd.version() == structmd.__version__
    expected = os.environ.get("STRUCTMD_EXPECTED_VERSION")
    if expected:
        assert structmd.version() == expected


# Public members held to issue 36's "Typed Python" rule: a docstring, and annotations on every
# parameter and the return (mypy --strict checks them: the ctest test python_typing).
def public_functions():
    """(name, object with the docstring, the functions whose signatures must be annotated)."""
    classes = [structmd.Simulation, structmd.Input, structmd.dlpack.DLPackView]
    for cls in classes:
        for name, member in vars(cls).items():
            if name.startswith("_"):
                continue
            if isinstance(member, property):
                yield f"{cls.__name__}.{name}", member, [f for f in (member.fget, member.fset) if f is not None]
            elif isinstance(member, (staticmethod, classmethod)):
                yield f"{cls.__name__}.{name}", member.__func__, [member.__func__]
            elif inspect.isfunction(member):
                yield f"{cls.__name__}.{name}", member, [member]
    for module in (structmd, structmd.simulation, structmd.builder, structmd.constants, structmd.errors,
                   structmd.dlpack, structmd.ipi, structmd.plot):
        for name, member in vars(module).items():
            if not name.startswith("_") and inspect.isfunction(member) and member.__module__ == module.__name__:
                yield f"{module.__name__}.{name}", member, [member]


def test_every_public_member_is_documented_and_annotated():
    undocumented, unannotated = [], []
    for name, member, functions in public_functions():
        if not (inspect.getdoc(member) or "").strip():
            undocumented.append(name)
        for function in functions:
            signature = inspect.signature(function)
            parameters = list(signature.parameters.values())
            if parameters and parameters[0].name in ("self", "cls"):
                parameters = parameters[1:]  # annotated only where it matters (Self-typed loads)
            missing = [p.name for p in parameters if p.annotation is inspect.Parameter.empty]
            if signature.return_annotation is inspect.Signature.empty:
                missing.append("return")
            if missing:
                unannotated.append(f"{name} ({function.__name__}: {', '.join(missing)})")
    assert not undocumented, f"public members without a docstring: {undocumented}"
    assert not unannotated, f"public members not fully annotated: {unannotated}"
    assert "Simulation.step" in {name for name, _, _ in public_functions()}


# ---- finding the library -----------------------------------------------------------------------

def test_import_refuses_a_library_of_another_abi_version(tmp_path):
    source = tmp_path / "other_abi.c"
    source.write_text("int structmd_abi_version(void) { return 999; }\n")
    library = tmp_path / "libother_abi.so"
    subprocess.run([structmd_header.c_compiler(), "-shared", "-fPIC", "-o", str(library), str(source)], check=True)
    result = run_python("import structmd", {"STRUCTMD_LIBRARY": str(library), "PYTHONPATH": str(PACKAGE_PARENT)})
    assert result.returncode != 0
    assert "ImportError" in result.stderr
    assert "ABI version 999" in result.stderr and f"ABI version {structmd.ABI_VERSION}" in result.stderr


def test_import_names_a_wrong_library_path(tmp_path):
    missing = tmp_path / "libnothing.so"
    result = run_python("import structmd", {"STRUCTMD_LIBRARY": str(missing), "PYTHONPATH": str(PACKAGE_PARENT)})
    assert result.returncode != 0
    assert "ImportError" in result.stderr and str(missing) in result.stderr


# An installed package bundles its library (under its soname) and the launcher; copies take its Python files only.
PACKAGE_FILES_ONLY = shutil.ignore_patterns("__pycache__", "libstructmd.so*", "bin")


def link_library(link):
    """Makes `link` name the loaded library. A wheel repaired by auditwheel keeps the libraries it
    bundles (libgomp) in structmd_engine.libs beside the package, found through $ORIGIN/.., and
    $ORIGIN is the folder of the link: that folder is linked beside it too."""
    library = Path(structmd.library_path).resolve()
    link.symlink_to(library)
    bundled = library.parent.parent / "structmd_engine.libs"
    if bundled.is_dir() and not (link.parent.parent / bundled.name).exists():
        (link.parent.parent / bundled.name).symlink_to(bundled)


def test_library_next_to_the_package_is_found(tmp_path):
    copy = tmp_path / "structmd"
    shutil.copytree(PACKAGE_PARENT / "structmd", copy, ignore=PACKAGE_FILES_ONLY)
    link_library(copy / Path(structmd.library_path).name)
    result = run_python("import structmd; print(structmd.library_path)", {"PYTHONPATH": str(tmp_path)})
    assert result.returncode == 0, result.stderr
    assert Path(result.stdout.strip()).parent == copy


def test_a_source_checkout_finds_the_library_of_its_build_tree(tmp_path):
    # A checkout's layout: bindings/python/structmd beside include/structmd.h, the library where
    # scripts/build.sh puts it, build/src; examples/coupling.py relies on this after a plain build.
    checkout = tmp_path / "checkout"
    package = checkout / "bindings" / "python" / "structmd"
    shutil.copytree(PACKAGE_PARENT / "structmd", package, ignore=PACKAGE_FILES_ONLY)
    (checkout / "include").mkdir()
    (checkout / "include" / "structmd.h").touch()
    built = checkout / "build" / "src" / "libstructmd.so"
    built.parent.mkdir(parents=True)
    link_library(built)
    code = "import structmd; print(structmd.library_path)"
    result = run_python(code, {"PYTHONPATH": str(package.parent)})
    assert result.returncode == 0, result.stderr
    assert Path(result.stdout.strip()) == built
    # Without the header the folders are not a checkout, and build/src is not looked into.
    (checkout / "include" / "structmd.h").unlink()
    result = run_python(code, {"PYTHONPATH": str(package.parent)})
    assert Path(result.stdout.strip() or "none") != built


# ---- creating, loading, advancing --------------------------------------------------------------

@pytest.mark.parametrize("form", ["dict", "string"])
def test_options_as_dict_or_json_string(options, form):
    given = options if form == "dict" else json.dumps(options)
    with structmd.Simulation(given) as sim:
        assert sim.info["precision"] == options["precision"]
        assert sim.info["loaded"] is False


def test_default_options():
    with structmd.Simulation() as sim:
        assert sim.info["backend"] in ("cpu", "cuda")
        assert sim.info["precision"] == sim.info["precisions_compiled"][0]


def test_bad_options_raise_argument_error_with_the_librarys_message():
    with pytest.raises(structmd.ArgumentError) as raised:
        structmd.Simulation({"bogus": 1})
    assert raised.value.status == status_of("STRUCTMD_ERR_ARGUMENT")
    assert "bogus" in raised.value.message
    with pytest.raises(TypeError):
        structmd.Simulation(42)


def test_load_plugin_raises_the_class_of_its_status(tmp_path):
    # The example plugin itself is built and loaded by tests/plugins; here, the binding's failures.
    with pytest.raises(structmd.StructmdIOError) as raised:
        structmd.load_plugin(tmp_path / "missing.so")
    assert "missing.so" in raised.value.message and "cannot open" in raised.value.message
    with pytest.raises(structmd.ArgumentError) as raised:
        structmd.load_plugin(structmd.library_path)
    assert "not a structmd plugin" in raised.value.message
    with pytest.raises(structmd.StructmdIOError) as raised:
        structmd.Simulation({"plugins": [str(tmp_path / "missing.so")]})
    assert raised.value.message.startswith('option "plugins": ')


def test_load_accepts_dict_json_text_and_paths(sim, tmp_path):
    doc = systems.lj_bond_system()
    path = tmp_path / "input.json"
    path.write_text(json.dumps(doc))
    sources = [doc, json.dumps(doc), "// a comment first\n" + json.dumps(doc), str(path), path]
    for source in sources:
        assert sim.load(source) is sim
        assert sim.num_particles == 4
        sim.step(2)
    assert sim.load_file(path) is sim and sim.step_number == 0
    assert sim.load_string(json.dumps(systems.dimer_system())) is sim and sim.num_particles == 2
    with pytest.raises(TypeError):
        sim.load(3.5)


def test_a_failed_load_keeps_the_simulation_loaded_before(loaded, tmp_path):
    loaded.step(5)
    positions = loaded.positions.copy()
    field = -0.5 * positions
    loaded.external_forces = field
    bad = systems.lj_bond_system()
    bad["topology"]["forceField"]["bonds"]["type"] = ["Bond2", "Harmonic_K_r0"]
    with pytest.raises(structmd.InputError):
        loaded.load(bad)
    with pytest.raises(structmd.StructmdIOError):
        loaded.load(tmp_path / "absent.json")
    assert loaded.step_number == 5 and loaded.num_particles == 4
    np.testing.assert_array_equal(loaded.positions, positions)
    np.testing.assert_allclose(loaded.external_forces, field)
    loaded.step(2)
    assert loaded.step_number == 7


def test_the_log_says_where_each_output_file_goes(options, tmp_path, monkeypatch):
    """Relative output paths are the working directory's, as in LAMMPS and OpenMM; loading an input
    says so in the log instead of writing there unseen."""
    monkeypatch.chdir(tmp_path)
    log = tmp_path / "log.txt"
    doc = systems.lj_bond_system()
    doc["simulationStep"] = {
        "thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                   "parameters": {"intervalStep": 10, "outputFilePath": "thermo.dat"}},
        "traj": {"type": ["WriteStep", "WriteStep"],
                 "parameters": {"intervalStep": 10, "outputFilePath": "traj", "outputFormat": "xyz"}}}
    with structmd.Simulation({**options, "log": "info", "log_file": str(log)}) as sim:
        sim.load(doc)
    text = log.read_text()
    assert f"simulationStep.thermo writes {tmp_path / 'thermo.dat'}" in text, text
    assert f"simulationStep.traj writes {tmp_path / 'traj.xyz'}" in text, text


def test_step_run_compute_and_clock(sim):
    sim.load(systems.lj_bond_system(steps=30))
    assert (sim.step_number, sim.time) == (0, 0.0)
    sim.step()
    sim.step(4)
    assert sim.step_number == 5
    assert sim.time == pytest.approx(5 * systems.BASE_TIME_STEP)
    sim.compute()
    sim.compute(forces=False, energy=True, virial=True)
    sim.run()
    assert sim.step_number == sim.info["final_step"] == 30
    sim.step(2)  # past the schedule's end, on with its last integrator
    assert sim.step_number == 32
    assert sim.time == pytest.approx(32 * systems.BASE_TIME_STEP)
    sim.run()  # nothing left to run
    assert sim.step_number == 32


@pytest.mark.parametrize("steps", [None, 120])
def test_run_with_progress_ends_in_the_same_step_and_state_and_draws_a_bar_on_stderr(options, capsys, steps):
    ends = []
    for progress in (False, True):
        with structmd.Simulation(options) as sim:
            sim.load(systems.lj_bond_system(steps=300))
            sim.run(steps, progress=progress)
            ends.append((sim.step_number, sim.time, sim.positions, sim.velocities, sim.forces))
    expected_steps = 300 if steps is None else steps
    assert ends[0][0] == ends[1][0] == expected_steps
    for without, with_bar in zip(ends[0][1:], ends[1][1:]):
        np.testing.assert_array_equal(with_bar, without)
    captured = capsys.readouterr()
    assert captured.out == ""
    last = captured.err.rstrip("\n").split("\r")[-1]
    assert last.startswith(f"{expected_steps}/{expected_steps} steps [")
    assert "100%" in last and "steps/s" in last and "ETA 0:00:00" in last
    assert captured.err.endswith("\n")


def test_run_past_the_schedule_and_its_refusals(loaded, options, capsys):
    loaded.run()
    assert loaded.step_number == 1000
    loaded.run(progress=True)  # at the schedule's end: nothing to do
    loaded.run(5, progress=True)  # past it, as step(5)
    assert loaded.step_number == 1005
    assert "0/0 steps" in capsys.readouterr().err
    with pytest.raises(TypeError):
        loaded.run("ten")
    with pytest.raises(structmd.ArgumentError):
        loaded.run(-1, progress=True)
    with structmd.Simulation(options) as empty, pytest.raises(structmd.StateError):
        empty.run(progress=True)


# ---- properties --------------------------------------------------------------------------------

def test_array_properties_have_the_documented_shapes_and_values(loaded):
    n = len(systems.BASE_POSITIONS)
    assert loaded.num_particles == n
    for name in ("positions", "velocities", "forces"):
        value = getattr(loaded, name)
        assert value.shape == (n, 3) and value.dtype == np.float64, name
    for name, dtype in (("particle_energies", np.float64), ("masses", np.float64), ("types", np.int32),
                        ("ids", np.int64)):
        value = getattr(loaded, name)
        assert value.shape == (n,) and value.dtype == dtype, name
    np.testing.assert_array_equal(loaded.ids, np.arange(n))
    np.testing.assert_allclose(loaded.positions, systems.BASE_POSITIONS, atol=1e-12)
    np.testing.assert_allclose(loaded.velocities, systems.BASE_VELOCITIES, atol=1e-12)
    rows = [row[0] for row in systems.TYPE_TABLE]
    np.testing.assert_array_equal(loaded.types, [rows.index(name) for name in systems.BASE_TYPES])
    masses = {row[0]: row[1] for row in systems.TYPE_TABLE}
    np.testing.assert_allclose(loaded.masses, [masses[name] for name in systems.BASE_TYPES])
    np.testing.assert_allclose(loaded.forces.sum(axis=0), 0.0, atol=1e-10)  # no external field yet
    assert loaded.particle_energies.sum() == pytest.approx(loaded.energy(), rel=1e-12)


def test_scalar_properties(loaded):
    kinetic = 0.5 * np.sum(loaded.masses[:, None] * loaded.velocities**2)
    assert loaded.energy("kinetic") == pytest.approx(kinetic, rel=1e-12)
    assert loaded.energy("total") == pytest.approx(loaded.energy() + kinetic, rel=1e-12)
    assert loaded.energy("lj") + loaded.energy("bonds") == pytest.approx(loaded.energy("potential"), rel=1e-12)
    virial = loaded.virial
    assert virial.shape == (3, 3)
    volume = np.prod(loaded.box)
    assert loaded.pressure == pytest.approx((2 * kinetic + np.trace(virial)) / (3 * volume), rel=1e-10)
    assert loaded.temperature == pytest.approx(2 * kinetic / (3 * loaded.num_particles), rel=1e-12)  # k_B = 1
    np.testing.assert_allclose(loaded.box, [systems.BASE_BOX] * 3)
    description = loaded.info
    assert description["particles"] == 4 and description["loaded"] is True
    assert loaded.last_error == ""


def test_setters(loaded):
    moved = np.array(systems.BASE_POSITIONS) + 0.01
    loaded.positions = moved
    np.testing.assert_allclose(loaded.positions, moved, atol=1e-12)
    loaded.positions = moved.ravel()  # a flat array of 3n values is accepted too
    loaded.velocities = [[0.0, 0.0, 0.0]] * 4
    assert loaded.energy("kinetic") == 0.0
    loaded.box = (11.0, 12.0, 13.0)
    np.testing.assert_allclose(loaded.box, [11.0, 12.0, 13.0])
    with pytest.raises(structmd.ArgumentError):
        loaded.positions = np.zeros((3, 3))
    with pytest.raises(structmd.ArgumentError):
        loaded.box = (1.0, 2.0)
    with pytest.raises(structmd.ArgumentError):
        loaded.box = (-1.0, 12.0, 13.0)


def test_external_forces_show_in_forces_and_none_clears_them(loaded):
    assert loaded.external_forces is None
    internal = loaded.forces
    field = -0.5 * loaded.positions
    loaded.external_forces = field
    np.testing.assert_allclose(loaded.external_forces, field)
    np.testing.assert_allclose(loaded.forces - internal, field, rtol=1e-12, atol=1e-12)
    loaded.external_forces = None
    assert loaded.external_forces is None
    np.testing.assert_allclose(loaded.forces, internal, rtol=1e-12, atol=1e-12)
    loaded.external_forces = field
    loaded.load(systems.lj_bond_system())
    assert loaded.external_forces is None  # a load starts a new simulation


def test_without_numpy_arrays_are_lists(loaded, without_numpy):
    positions = loaded.positions
    assert isinstance(positions, list) and all(isinstance(row, tuple) and len(row) == 3 for row in positions)
    np.testing.assert_allclose(positions, systems.BASE_POSITIONS, atol=1e-12)
    assert loaded.ids == [0, 1, 2, 3]
    assert isinstance(loaded.masses, list) and isinstance(loaded.types, list)
    assert isinstance(loaded.box, tuple) and len(loaded.virial) == 3
    internal = loaded.forces
    field = [(0.1 * i, -0.2, 0.3) for i in range(4)]
    loaded.external_forces = field
    assert loaded.external_forces == field
    difference = np.array(loaded.forces) - np.array(internal)
    np.testing.assert_allclose(difference, field, rtol=1e-12, atol=1e-12)
    loaded.positions = [tuple(row) for row in systems.BASE_POSITIONS]
    with pytest.raises(structmd.ArgumentError):
        loaded.velocities = [(0.0, 0.0)] * 4


# ---- errors ------------------------------------------------------------------------------------

def _provoke(kind, sim, tmp_path):
    if kind == "STRUCTMD_ERR_ARGUMENT":
        sim.load(systems.lj_bond_system()).energy("no-such-term")
    elif kind == "STRUCTMD_ERR_INPUT":
        sim.load_string('{"system": ')
    elif kind == "STRUCTMD_ERR_STATE":
        sim.step(1)
    elif kind == "STRUCTMD_ERR_IO":
        sim.load_file(tmp_path / "missing.json")
    elif kind == "STRUCTMD_ERR_NUMERICAL":
        positions = sim.load(systems.lj_bond_system()).positions
        positions[3] = positions[2]  # a Lennard-Jones pair at r = 0
        sim.positions = positions
        sim.compute()
        sim.step(1)


@pytest.mark.parametrize("kind, cls", [
    ("STRUCTMD_ERR_ARGUMENT", structmd.ArgumentError),
    ("STRUCTMD_ERR_INPUT", structmd.InputError),
    ("STRUCTMD_ERR_STATE", structmd.StateError),
    ("STRUCTMD_ERR_IO", structmd.StructmdIOError),
    ("STRUCTMD_ERR_NUMERICAL", structmd.NumericalError),
])
def test_failures_raise_the_class_of_their_status(sim, tmp_path, kind, cls):
    with pytest.raises(cls) as raised:
        _provoke(kind, sim, tmp_path)
    error = raised.value
    assert error.status == status_of(kind)
    assert error.message == sim.last_error != ""
    assert kind in str(error)
    sim.load(systems.lj_bond_system()).step(2)  # still usable


def test_cuda_on_a_machine_without_gpu_raises_device_or_unsupported():
    try:
        with structmd.Simulation({"backend": "cuda", "log": "quiet"}) as sim:
            assert sim.info["backend"] == "cuda"
    except (structmd.DeviceError, structmd.UnsupportedError) as error:
        assert error.status in (status_of("STRUCTMD_ERR_DEVICE"), status_of("STRUCTMD_ERR_UNSUPPORTED"))
        assert error.message


def test_error_for_status_and_pickling():
    for status, cls in ERROR_CLASSES.items():
        error = structmd.error_for_status(status, "why")
        assert type(error) is cls and error.status == status
        copy = pickle.loads(pickle.dumps(error))
        assert (type(copy), copy.status, copy.message) == (cls, status, "why")
    unknown = structmd.error_for_status(1000, "from a newer library")
    assert type(unknown) is structmd.StructmdError and "1000" in str(unknown)


def test_context_manager_closes_and_closed_handles_raise_state_error(options):
    with structmd.Simulation(options) as sim:
        sim.load(systems.dimer_system())
        assert not sim.closed
    assert sim.closed
    assert "closed" in repr(sim)
    for action in (lambda: sim.step(1), lambda: sim.positions, lambda: sim.info, lambda: sim.last_error):
        with pytest.raises(structmd.StateError):
            action()
    sim.close()  # closing twice is fine


def test_explicit_close_and_repr(options):
    sim = structmd.Simulation(options)
    assert "backend" in repr(sim)
    sim.close()
    assert sim.closed


def test_two_simulations_are_independent(options):
    with structmd.Simulation(options) as first, structmd.Simulation(options) as second:
        first.load(systems.lj_bond_system())
        second.load(systems.dimer_system())
        positions = second.positions
        first.step(10)
        first.external_forces = np.ones((4, 3))
        with pytest.raises(structmd.ArgumentError):
            first.step(-1)
        assert second.step_number == 0 and second.last_error == ""
        np.testing.assert_array_equal(second.positions, positions)
