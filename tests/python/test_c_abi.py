"""The C ABI of libstructmd, called through cffi in ABI mode with declarations generated from
include/structmd.h at test time. Covers every function of the header (checked by the last test), every
status a host can provoke, and the rule that a failed call leaves the handle usable."""

import json
import math
import os
import re
import threading

import cffi
import numpy as np
import pytest

import structmd_header
import systems
from conftest import engine_options, library_path

DEFINES = structmd_header.header_defines()
PROTOTYPES = structmd_header.function_prototypes()
OK = DEFINES["STRUCTMD_OK"]
ARGUMENT = DEFINES["STRUCTMD_ERR_ARGUMENT"]
INPUT = DEFINES["STRUCTMD_ERR_INPUT"]
STATE = DEFINES["STRUCTMD_ERR_STATE"]
NUMERICAL = DEFINES["STRUCTMD_ERR_NUMERICAL"]
IO = DEFINES["STRUCTMD_ERR_IO"]
DEVICE = DEFINES["STRUCTMD_ERR_DEVICE"]
UNSUPPORTED = DEFINES["STRUCTMD_ERR_UNSUPPORTED"]
ALL_FLAGS = DEFINES["STRUCTMD_FORCES"] | DEFINES["STRUCTMD_ENERGY"] | DEFINES["STRUCTMD_VIRIAL"]
INFO_KEYS = {"backend", "precision", "precisions_compiled", "device", "threads", "loaded", "particles", "final_step"}
NAMES = {value: name for name, value in DEFINES.items() if name.startswith(("STRUCTMD_OK", "STRUCTMD_ERR_"))}

ffi = cffi.FFI()
ffi.cdef(structmd_header.preprocessed_declarations())
# DLPack's DLManagedTensor (dlpack.h, ABI-stable since 0.6), which the header leaves opaque.
ffi.cdef("""
struct DLManagedTensor {
    struct {
        void* data;
        struct { int32_t device_type; int32_t device_id; } device;
        int32_t ndim;
        struct { uint8_t code; uint8_t bits; uint16_t lanes; } dtype;
        int64_t* shape;
        int64_t* strides;
        uint64_t byte_offset;
    } dl_tensor;
    void* manager_ctx;
    void (*deleter)(struct DLManagedTensor* self);
};
""")

_called = set()


class _RecordingLibrary:
    """The cffi library, remembering which functions the tests called."""

    def __init__(self, library):
        self._library = library

    def __getattr__(self, name):
        _called.add(name)
        return getattr(self._library, name)


lib = _RecordingLibrary(ffi.dlopen(library_path()))


# ---- helpers -----------------------------------------------------------------------------------

def message(sim):
    return ffi.string(lib.structmd_last_error(sim)).decode()


def create_message():
    return message(ffi.NULL)


def expect(sim, status, expected):
    """Asserts a status, showing both names and the library's message when it differs."""
    detail = message(sim) if sim != ffi.NULL else ""
    assert status == expected, f"got {NAMES.get(status, status)}, expected {NAMES[expected]}: {detail}"


def check(sim, status):
    expect(sim, status, OK)


def default_options():
    """Every handle's options here: the test engine's, and the in-tree NeighbourCount transverser
    plugin (tests/plugins), so that structmd_traverse runs through the header-wide checks."""
    plugin = os.environ.get("STRUCTMD_TEST_TRANSVERSER_PLUGIN")
    return {**engine_options(), **({"plugins": [plugin]} if plugin else {})}


def create(options):
    out = ffi.new("structmd_sim**")
    status = lib.structmd_create(json.dumps(options).encode(), out)
    assert status == OK, f"create({options}) failed: {create_message()}"
    assert out[0] != ffi.NULL
    return out[0]


def load(sim, doc):
    check(sim, lib.structmd_load_string(sim, json.dumps(doc).encode()))


def num_particles(sim):
    n = ffi.new("int64_t*")
    check(sim, lib.structmd_get_num_particles(sim, n))
    return n[0]


def get_array(sim, function, ctype="double", components=3):
    n = num_particles(sim)
    buffer = ffi.new(f"{ctype}[]", max(1, components * n))
    check(sim, getattr(lib, function)(sim, buffer, n))
    values = np.array(ffi.unpack(buffer, components * n))
    return values.reshape(n, components) if components > 1 else values


def set_vectors(sim, function, values):
    flat = np.ascontiguousarray(values, dtype=np.float64).ravel()
    return getattr(lib, function)(sim, ffi.new("double[]", flat.tolist()), flat.size // 3)


def get_scalar(sim, function, ctype):
    out = ffi.new(f"{ctype}*")
    check(sim, getattr(lib, function)(sim, out))
    return out[0]


def get_fixed(sim, function, count):
    out = ffi.new("double[]", count)
    check(sim, getattr(lib, function)(sim, out))
    return np.array(ffi.unpack(out, count))


def energy(sim, term="potential"):
    out = ffi.new("double*")
    check(sim, lib.structmd_get_energy(sim, term.encode(), out))
    return out[0]


def info(sim):
    needed = ffi.new("size_t*")
    lib.structmd_get_info(sim, ffi.NULL, 0, needed)
    buffer = ffi.new("char[]", needed[0])
    check(sim, lib.structmd_get_info(sim, buffer, needed[0], ffi.NULL))
    return json.loads(ffi.string(buffer).decode())


def snapshot(sim):
    """What a failed call must leave unchanged."""
    return {
        "step": get_scalar(sim, "structmd_get_step", "int64_t"),
        "time": get_scalar(sim, "structmd_get_time", "double"),
        "positions": get_array(sim, "structmd_get_positions"),
        "velocities": get_array(sim, "structmd_get_velocities"),
        "box": get_fixed(sim, "structmd_get_box", 3),
    }


def assert_same_state(before, after):
    assert before["step"] == after["step"]
    assert before["time"] == after["time"]
    for key in ("positions", "velocities", "box"):
        np.testing.assert_array_equal(before[key], after[key], err_msg=key)


def assert_usable(sim):
    """The handle accepts a good input afterwards and steps."""
    load(sim, systems.lj_bond_system())
    check(sim, lib.structmd_step(sim, 3))
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 3


def minimum_image(d, box):
    return d - box * np.round(d / box)


@pytest.fixture
def new_handle():
    handles = []

    def make(options=None):
        handles.append(create(default_options() if options is None else options))
        return handles[-1]

    yield make
    for handle in handles:
        lib.structmd_destroy(handle)


@pytest.fixture
def sim(new_handle):
    return new_handle()


@pytest.fixture
def loaded(sim):
    load(sim, systems.lj_bond_system())
    return sim


@pytest.fixture
def good_input_file(tmp_path):
    path = tmp_path / "good.json"
    path.write_text("// comments are allowed\n" + json.dumps(systems.lj_bond_system(), indent=1))
    return path


def valid_arguments(sim, prototype, n, good_input_file):
    """Arguments for a call that would succeed on a loaded handle with n particles."""
    by_name = {
        "term": lambda: ffi.new("char[]", b"potential"),
        "compute": lambda: ffi.new("char[]", b"r < 1.5"),
        "path": lambda: ffi.new("char[]", str(good_input_file).encode()),
        "json": lambda: ffi.new("char[]", json.dumps(systems.lj_bond_system()).encode()),
        "buffer": lambda: ffi.new("char[]", 4096),
        "lengths": lambda: ffi.new("double[]", [systems.BASE_BOX] * 3),
        "xyz": lambda: ffi.new("double[]", np.ravel(systems.BASE_POSITIONS).tolist()),
        "v": lambda: ffi.new("double[]", np.ravel(systems.BASE_VELOCITIES).tolist()),
        "q": lambda: ffi.new("double[]", [1.0, 0.0, 0.0, 0.0] * max(1, n)),  # identity orientations
        "ids": lambda: ffi.new("int64_t[]", list(range(max(1, n)))),
        "energy": lambda: 0.5,
        "quantity": lambda: ffi.new("char[]", b"positions"),
        "message": lambda: ffi.new("char[]", b"a reason"),
        "callback": lambda: ffi.NULL,
        "user_data": lambda: ffi.NULL,
        "view": lambda: ffi.new("structmd_dlpack_tensor**"),
        "name": lambda: ffi.new("char[]", b"NeighbourCount"),
        "parameters": lambda: ffi.new("char[]", b"{}"),
    }
    by_type = {
        "structmd_sim*": lambda: sim,
        "int64_t": lambda: n,
        "uint32_t": lambda: DEFINES["STRUCTMD_FORCES"],
        "double": lambda: 1.0,
        "size_t": lambda: 4096,
        "double*": lambda: ffi.new("double[]", 64),
        "int64_t*": lambda: ffi.new("int64_t[]", 64),
        "int32_t*": lambda: ffi.new("int32_t[]", 64),
        "size_t*": lambda: ffi.new("size_t*"),
        "int*": lambda: ffi.new("int*"),
    }
    return [by_name[name]() if name in by_name else by_type[c_type]() for c_type, name in prototype[1]]


HANDLE_FUNCTIONS = sorted(name for name, (_, params) in PROTOTYPES.items()
                          if params and params[0][0] == "structmd_sim*"
                          and name not in ("structmd_destroy", "structmd_last_error"))
NEEDS_LOADED = sorted(set(HANDLE_FUNCTIONS) - {"structmd_load_file", "structmd_load_string", "structmd_get_info",
                                                "structmd_set_callback_error", "structmd_transverser_values"})
NULLABLE = {("structmd_get_info", "needed"), ("structmd_set_force_callback", "user_data"),
            ("structmd_set_device_force_callback", "user_data"), ("structmd_traverse", "parameters"),
            ("structmd_traverse_view", "parameters")}  # optional pointers
POINTER_ARGUMENTS = sorted((name, index, param_name)
                           for name in HANDLE_FUNCTIONS
                           for index, (c_type, param_name) in enumerate(PROTOTYPES[name][1])
                           if index > 0 and c_type.endswith("*") and (name, param_name) not in NULLABLE)
COUNTED_ARRAYS = sorted(name for name in HANDLE_FUNCTIONS
                        if [t for t, _ in PROTOTYPES[name][1]][-1:] == ["int64_t"]
                        and PROTOTYPES[name][1][1][0].endswith("*"))


# ---- versions and creation ---------------------------------------------------------------------

def test_abi_version_is_the_headers():
    assert lib.structmd_abi_version() == DEFINES["STRUCTMD_ABI_VERSION"]


def test_version_is_major_minor_patch():
    text = ffi.string(lib.structmd_version()).decode()
    assert re.fullmatch(r"\d+\.\d+\.\d+", text)
    expected = os.environ.get("STRUCTMD_EXPECTED_VERSION")
    if expected:
        assert text == expected


@pytest.mark.parametrize("options", [None, b"", b"{}"])
def test_create_with_default_options(options):
    out = ffi.new("structmd_sim**")
    status = lib.structmd_create(ffi.NULL if options is None else options, out)
    assert status == OK, create_message()
    try:
        assert message(out[0]) == ""
        assert info(out[0])["backend"] in ("cpu", "cuda")
    finally:
        lib.structmd_destroy(out[0])


@pytest.mark.parametrize("options, culprit", [
    ({"bogus": 1}, "bogus"),
    ({"precision": "quad"}, "precision"),
    ({"backend": "opencl"}, "backend"),
    ({"log": "loud"}, "log"),
    ({"device": "first"}, "device"),
    ({"threads": "many"}, "threads"),
    ({"step_graphs": "no"}, "step_graphs"),
    ({"step_graphs": 0}, "step_graphs"),
])
def test_create_rejects_bad_options(options, culprit):
    out = ffi.new("structmd_sim**")
    out[0] = ffi.cast("structmd_sim*", 0x1)  # must be reset to NULL on failure
    assert lib.structmd_create(json.dumps(options).encode(), out) == ARGUMENT
    assert out[0] == ffi.NULL
    assert culprit in create_message()


@pytest.mark.parametrize("options", [b"not json", b"[1, 2]", b'{"backend": '])
def test_create_rejects_options_that_are_not_a_json_object(options):
    out = ffi.new("structmd_sim**")
    assert lib.structmd_create(options, out) == ARGUMENT
    assert out[0] == ffi.NULL
    assert create_message() != ""


def test_create_without_out_pointer_is_an_argument_error():
    assert lib.structmd_create(ffi.NULL, ffi.NULL) == ARGUMENT
    assert "out" in create_message()


def test_last_error_of_null_follows_the_latest_create():
    out = ffi.new("structmd_sim**")
    assert lib.structmd_create(b'{"bogus": 1}', out) == ARGUMENT
    assert "bogus" in create_message()
    assert lib.structmd_create(b'{"log": "loud"}', out) == ARGUMENT
    assert "loud" in create_message() or "log" in create_message()


def test_load_plugin_reports_without_a_handle(tmp_path):
    # The example plugin is built and loaded by tests/plugins; here, failures at the ABI.
    assert lib.structmd_load_plugin(ffi.NULL) == ARGUMENT
    assert "path" in create_message()
    missing = str(tmp_path / "missing.so").encode()
    assert lib.structmd_load_plugin(missing) == IO
    assert "missing.so" in create_message() and "cannot open" in create_message()
    assert lib.structmd_load_plugin(library_path().encode()) == ARGUMENT
    assert "not a structmd plugin" in create_message()


def test_cuda_backend_either_works_or_says_why():
    out = ffi.new("structmd_sim**")
    status = lib.structmd_create(b'{"backend": "cuda", "log": "quiet"}', out)
    if status == OK:
        try:
            assert info(out[0])["backend"] == "cuda"
        finally:
            lib.structmd_destroy(out[0])
        return
    assert status in (DEVICE, UNSUPPORTED), NAMES.get(status, status)
    assert out[0] == ffi.NULL
    reason = create_message()
    assert re.search(r"cuda|gpu", reason, re.IGNORECASE), reason
    assert len(reason) > len("cuda backend"), f"no reason given: {reason!r}"


def test_destroy_accepts_null():
    lib.structmd_destroy(ffi.NULL)


def test_fresh_handle_has_no_error_and_is_not_loaded(sim):
    assert message(sim) == ""
    description = info(sim)
    assert set(description) >= INFO_KEYS
    assert description["loaded"] is False
    assert description["particles"] == 0
    assert description["final_step"] == -1
    assert description["backend"] in ("cpu", "cuda")
    assert description["precision"] in description["precisions_compiled"]


# ---- argument errors ---------------------------------------------------------------------------

@pytest.mark.parametrize("function", HANDLE_FUNCTIONS)
def test_null_handle_is_an_argument_error(function, good_input_file):
    arguments = valid_arguments(ffi.NULL, PROTOTYPES[function], 4, good_input_file)
    assert getattr(lib, function)(*arguments) == ARGUMENT


@pytest.mark.parametrize("function, index, param_name", POINTER_ARGUMENTS)
def test_null_pointer_argument_is_an_argument_error(loaded, function, index, param_name, good_input_file):
    before = snapshot(loaded)
    arguments = valid_arguments(loaded, PROTOTYPES[function], num_particles(loaded), good_input_file)
    arguments[index] = ffi.NULL
    expect(loaded, getattr(lib, function)(*arguments), ARGUMENT)
    assert param_name in message(loaded), f"the message should name the argument {param_name}"
    if function not in ("structmd_load_file", "structmd_load_string"):
        assert_same_state(before, snapshot(loaded))
    assert_usable(loaded)


@pytest.mark.parametrize("function", COUNTED_ARRAYS)
@pytest.mark.parametrize("offset", [-1, +1, "zero", "negative"])
def test_wrong_array_length_is_an_argument_error_and_writes_nothing(loaded, function, offset, good_input_file):
    n = num_particles(loaded)
    wrong_n = {"zero": 0, "negative": -1}.get(offset, n + offset if isinstance(offset, int) else None)
    before = snapshot(loaded)
    arguments = valid_arguments(loaded, PROTOTYPES[function], wrong_n, good_input_file)
    array_type = PROTOTYPES[function][1][1][0]
    sentinel = 12345
    if function.startswith("structmd_get_"):
        arguments[1] = ffi.new(array_type.replace("*", "[]"), [sentinel] * 64)
    expect(loaded, getattr(lib, function)(*arguments), ARGUMENT)
    assert message(loaded) != ""
    if function.startswith("structmd_get_"):
        assert ffi.unpack(arguments[1], 64) == [sentinel] * 64
    assert_same_state(before, snapshot(loaded))
    assert_usable(loaded)


@pytest.mark.parametrize("term", ["nonexistent", "", "Potential"])
def test_unknown_energy_term_is_an_argument_error(loaded, term):
    value = ffi.new("double*", 7.0)
    expect(loaded, lib.structmd_get_energy(loaded, term.encode(), value), ARGUMENT)
    assert value[0] == 7.0
    assert f"{term}" in message(loaded)
    assert_usable(loaded)


@pytest.mark.parametrize("flags", [8, 16, 1 << 31, 0xFFFFFFFF, ALL_FLAGS | 8])
def test_unknown_compute_flags_are_an_argument_error(loaded, flags):
    expect(loaded, lib.structmd_compute(loaded, flags), ARGUMENT)
    assert message(loaded) != ""
    assert_usable(loaded)


@pytest.mark.parametrize("flags", range(ALL_FLAGS + 1))
def test_every_combination_of_known_compute_flags_works(loaded, flags):
    before = snapshot(loaded)
    check(loaded, lib.structmd_compute(loaded, flags))
    assert_same_state(before, snapshot(loaded))


@pytest.mark.parametrize("nsteps", [-1, -(2**63)])
def test_negative_step_count_is_an_argument_error(loaded, nsteps):
    before = snapshot(loaded)
    expect(loaded, lib.structmd_step(loaded, nsteps), ARGUMENT)
    assert "nsteps" in message(loaded)
    assert_same_state(before, snapshot(loaded))
    assert_usable(loaded)


def test_non_finite_positions_and_velocities_are_rejected_and_change_nothing(loaded):
    for function, values in (("structmd_set_positions", systems.BASE_POSITIONS),
                             ("structmd_set_velocities", systems.BASE_VELOCITIES)):
        for bad in (math.nan, math.inf, -math.inf):
            corrupted = np.array(values, dtype=float) * 0.5
            corrupted[2, 1] = bad
            before = snapshot(loaded)
            expect(loaded, set_vectors(loaded, function, corrupted), ARGUMENT)
            assert_same_state(before, snapshot(loaded))
    assert_usable(loaded)


@pytest.mark.parametrize("lengths", [[1e300, 10.0, 10.0], [10.0, -10.0, 10.0], [10.0, 10.0, math.nan],
                                     [4.0, 10.0, 10.0]])
def test_set_box_rejects_bad_lengths_and_cutoffs_over_half_the_box(loaded, lengths):
    # [4, 10, 10]: the LJ cutoff 2.5 sigma would exceed half of Lx.
    before = snapshot(loaded)
    expect(loaded, lib.structmd_set_box(loaded, ffi.new("double[]", lengths)), ARGUMENT)
    assert message(loaded) != ""
    assert_same_state(before, snapshot(loaded))
    assert_usable(loaded)


SUBSET_FUNCTIONS = sorted(name for name in PROTOTYPES if name.endswith("_of"))


@pytest.mark.parametrize("function", SUBSET_FUNCTIONS)
def test_subsets_refuse_a_negative_count_and_take_zero_as_nothing(loaded, function):
    before = snapshot(loaded)
    values = ffi.new("double[]", [7.0] * 6)
    ids = ffi.new("int64_t[]", [0, 1])
    expect(loaded, getattr(lib, function)(loaded, ids, -1, values), ARGUMENT)
    assert "m: expected a count >= 0" in message(loaded)
    check(loaded, getattr(lib, function)(loaded, ffi.NULL, 0, ffi.NULL))
    check(loaded, getattr(lib, function)(loaded, ids, 0, values))
    assert ffi.unpack(values, 6) == [7.0] * 6
    assert_same_state(before, snapshot(loaded))


@pytest.mark.parametrize("function", SUBSET_FUNCTIONS)
def test_subsets_refuse_null_arrays_naming_them(loaded, function):
    values = ffi.new("double[]", [7.0] * 6)
    ids = ffi.new("int64_t[]", [0, 1])
    expect(loaded, getattr(lib, function)(loaded, ffi.NULL, 2, values), ARGUMENT)
    assert "ids: NULL pointer" in message(loaded)
    expect(loaded, getattr(lib, function)(loaded, ids, 2, ffi.NULL), ARGUMENT)
    assert "NULL pointer" in message(loaded)


def test_parameters_round_trip_through_the_c_abi(loaded):
    value = ffi.new("double*")
    check(loaded, lib.structmd_get_parameter(loaded, b"integrator.vv.parameters.timeStep", value))
    assert value[0] == systems.BASE_TIME_STEP
    check(loaded, lib.structmd_set_parameter(loaded, b"integrator.vv.parameters.timeStep", 0.001))
    check(loaded, lib.structmd_get_parameter(loaded, b"integrator.vv.parameters.timeStep", value))
    assert value[0] == 0.001
    value[0] = 5.0
    expect(loaded, lib.structmd_get_parameter(loaded, b"integrator.nothing.parameters.timeStep", value), ARGUMENT)
    assert "integrator.nothing.parameters.timeStep" in message(loaded) and value[0] == 5.0


# ---- state errors ------------------------------------------------------------------------------

@pytest.mark.parametrize("function", NEEDS_LOADED)
def test_calls_before_a_load_are_state_errors(sim, function, good_input_file):
    arguments = valid_arguments(sim, PROTOTYPES[function], 0, good_input_file)
    expect(sim, getattr(lib, function)(*arguments), STATE)
    assert message(sim) != ""
    assert_usable(sim)


def test_stepping_past_the_schedule_end_goes_on_with_the_last_integrator(sim):
    doc = systems.lj_bond_system()
    doc["integrator"]["fine"] = {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}}
    doc["integrator"]["schedule"]["data"] = [[1, "vv", 10], [2, "fine", 15], [3, "vv", 0]]
    load(sim, doc)
    assert info(sim)["final_step"] == 25
    check(sim, lib.structmd_step(sim, 20))
    check(sim, lib.structmd_step(sim, 12))  # through the end at 25, on with "fine" (the "vv" row has 0 steps)
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 32
    expected_time = 10 * systems.BASE_TIME_STEP + 22 * 0.001
    assert get_scalar(sim, "structmd_get_time", "double") == pytest.approx(expected_time, rel=1e-12)
    after = snapshot(sim)
    check(sim, lib.structmd_run(sim))  # past the end: nothing to do
    assert_same_state(after, snapshot(sim))
    assert info(sim)["final_step"] == 25
    assert_usable(sim)


@pytest.mark.parametrize("integrator", ["absent", "empty schedule"])
def test_stepping_without_an_integrator_is_a_state_error_and_energies_still_read(sim, integrator):
    doc = systems.lj_bond_system()
    if integrator == "absent":
        del doc["integrator"]
    else:
        doc["integrator"] = {"schedule": {"type": ["Schedule", "Integrator"],
                                          "labels": ["order", "integrator", "steps"], "data": []}}
    load(sim, doc)
    expect(sim, lib.structmd_step(sim, 3), STATE)
    assert "integrator" in message(sim)
    check(sim, lib.structmd_step(sim, 0))
    check(sim, lib.structmd_run(sim))  # the schedule is empty: nothing to do
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 0
    assert math.isfinite(energy(sim))


def test_run_goes_through_every_schedule_row(sim):
    doc = systems.lj_bond_system()
    doc["integrator"]["fine"] = {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}}
    doc["integrator"]["schedule"]["data"] = [[1, "vv", 10], [2, "fine", 15]]
    load(sim, doc)
    assert info(sim)["final_step"] == 25
    check(sim, lib.structmd_run(sim))
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 25
    expected_time = 10 * systems.BASE_TIME_STEP + 15 * 0.001
    assert get_scalar(sim, "structmd_get_time", "double") == pytest.approx(expected_time, rel=1e-12)


def test_initial_step_and_time_come_from_the_fundamental(sim):
    doc = systems.lj_bond_system()
    doc["global"]["fundamental"]["parameters"].update({"currentStep": 7, "simulationTime": 1.5})
    load(sim, doc)
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 7
    assert get_scalar(sim, "structmd_get_time", "double") == 1.5
    check(sim, lib.structmd_step(sim, 3))
    assert get_scalar(sim, "structmd_get_step", "int64_t") == 10
    assert get_scalar(sim, "structmd_get_time", "double") == pytest.approx(1.5 + 3 * systems.BASE_TIME_STEP)


def test_step_zero_changes_nothing(loaded):
    before = snapshot(loaded)
    check(loaded, lib.structmd_step(loaded, 0))
    assert_same_state(before, snapshot(loaded))


# ---- input and IO errors -----------------------------------------------------------------------

def _edit(path, value):
    """An edit of the base document: set (or, for value None, delete) the key at path."""
    def apply(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        if value is None:
            del node[path[-1]]
        else:
            node[path[-1]] = value
        return doc
    return apply


def _duplicate_id(doc):
    doc["state"]["data"][3][0] = 0
    return doc


def _id_gap(doc):
    doc["state"]["data"][3][0] = 9
    doc["topology"]["structure"]["data"][3][0] = 9
    return doc


def _short_row(doc):
    doc["state"]["data"][1] = doc["state"]["data"][1][:2]
    return doc


BAD_INPUTS = {
    "missing state": (_edit(["state"], None), ["state"]),
    "unknown type name": (_edit(["topology", "structure", "data", 2, 1], "Z"), ["topology.structure"]),
    "duplicate id": (_duplicate_id, ["state"]),
    "ids not covering 0..N-1": (_id_gap, ["state", "topology.structure"]),
    "bond to a missing id": (_edit(["topology", "forceField", "bonds", "data", 0, 1], 99),
                             ["topology.forceField.bonds"]),
    "negative box": (_edit(["global", "ensemble", "data", 0, 0], [-10.0, 10.0, 10.0]), ["global.ensemble"]),
    "cutoff over half the box": (_edit(["global", "ensemble", "data", 0, 0], [4.0, 10.0, 10.0]),
                                 ["topology.forceField.lj", "global.ensemble"]),
    "unknown component type": (_edit(["topology", "forceField", "lj", "type"], ["NonBonded", "NoSuchPotential"]),
                               ["topology.forceField.lj"]),
    "unused parameter": (_edit(["topology", "forceField", "lj", "parameters", "cutoffFactor"], 2.5),
                         ["topology.forceField.lj.parameters.cutoffFactor"]),
    "unknown section": (_edit(["postprocessing"], {}), ["postprocessing"]),
    "unknown state label": (_edit(["state", "labels"], ["id", "position", "colour"]), ["state"]),
    "row of the wrong length": (_short_row, ["state"]),
    "schedule naming no integrator": (_edit(["integrator", "schedule", "data"], [[1, "nosuch", 10]]),
                                      ["integrator"]),
    "component without type": (_edit(["topology", "forceField", "bonds", "type"], None),
                               ["topology.forceField.bonds"]),
}


@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_inconsistent_input_is_an_input_error_naming_its_path(loaded, case):
    edit, paths = BAD_INPUTS[case]
    document = json.dumps(edit(systems.lj_bond_system()))
    expect(loaded, lib.structmd_load_string(loaded, document.encode()), INPUT)
    text = message(loaded)
    assert any(path in text for path in paths), f"{text!r} names none of {paths}"
    # A failed load keeps the simulation loaded before.
    count = ffi.new("int64_t*")
    expect(loaded, lib.structmd_get_num_particles(loaded, count), OK)
    assert count[0] == 4
    assert_usable(loaded)


def test_malformed_json_reports_line_and_column(sim):
    document = '{\n  "system": {},\n  "global": [1, 2,, 3]\n}\n'
    expect(sim, lib.structmd_load_string(sim, document.encode()), INPUT)
    text = message(sim)
    line = re.search(r"line\D{0,3}(\d+)", text, re.IGNORECASE)
    column = re.search(r"col(?:umn)?\D{0,3}(\d+)", text, re.IGNORECASE)
    assert line and int(line.group(1)) == 3, text
    assert column and 15 <= int(column.group(1)) <= 20, text
    assert_usable(sim)


def test_missing_file_is_an_io_error_naming_the_file(sim, tmp_path):
    missing = tmp_path / "no-such-input.json"
    expect(sim, lib.structmd_load_file(sim, str(missing).encode()), IO)
    assert "no-such-input.json" in message(sim)
    assert_usable(sim)


def test_unwritable_output_is_an_io_error(sim, tmp_path):
    doc = systems.lj_bond_system()
    output = tmp_path / "no-such-folder" / "trajectory"
    doc["simulationStep"] = {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                                        "parameters": {"intervalStep": 1, "outputFilePath": str(output)}}}
    status = lib.structmd_load_string(sim, json.dumps(doc).encode())
    if status == OK:  # the engine may open its outputs lazily, at the first write
        status = lib.structmd_step(sim, 2)
    expect(sim, status, IO)
    assert "no-such-folder" in message(sim)
    assert_usable(sim)


def test_coincident_particles_are_a_numerical_error_not_nan(loaded):
    positions = get_array(loaded, "structmd_get_positions")
    positions[3] = positions[2]  # a Lennard-Jones pair at r = 0
    check(loaded, set_vectors(loaded, "structmd_set_positions", positions))
    n = num_particles(loaded)
    forces = ffi.new("double[]", 3 * n)
    status = lib.structmd_get_forces(loaded, forces, n)
    if status == OK:  # a non-finite force may instead be reported by the step that meets it
        assert all(math.isfinite(value) for value in ffi.unpack(forces, 3 * n))
        status = lib.structmd_step(loaded, 1)
    expect(loaded, status, NUMERICAL)
    text = message(loaded)
    assert re.search(r"step", text, re.IGNORECASE) and re.search(r"\b[23]\b", text), text
    # Every getter of what the pair makes non-finite says so too, on each backend, rather than
    # returning OK with NaN or inf.
    value = ffi.new("double*")
    for term in ("potential", "total"):
        expect(loaded, lib.structmd_get_energy(loaded, term.encode(), value), NUMERICAL)
    expect(loaded, lib.structmd_get_particle_energies(loaded, ffi.new("double[]", n), n), NUMERICAL)
    expect(loaded, lib.structmd_get_virial(loaded, ffi.new("double[]", 9)), NUMERICAL)
    expect(loaded, lib.structmd_get_pressure(loaded, value), NUMERICAL)
    assert_usable(loaded)


def test_overstretched_fene_bond_is_a_numerical_error(sim):
    fene = ("Fene", ["r0", "K", "R0"], [0.0, 30.0, 1.5])
    load(sim, systems.dimer_system(separation=1.0, bond=fene))
    good = get_array(sim, "structmd_get_positions")
    check(sim, set_vectors(sim, "structmd_set_positions", good * 2.0))
    n = num_particles(sim)
    expect(sim, lib.structmd_get_forces(sim, ffi.new("double[]", 3 * n), n), NUMERICAL)
    text = message(sim)
    assert re.search(r"step", text, re.IGNORECASE) and re.search(r"\b[01]\b", text), text
    check(sim, set_vectors(sim, "structmd_set_positions", good))
    assert np.all(np.isfinite(get_array(sim, "structmd_get_forces")))
    assert_usable(sim)


# ---- successful loads and getters --------------------------------------------------------------

def test_load_file_accepts_comments(sim, good_input_file):
    check(sim, lib.structmd_load_file(sim, str(good_input_file).encode()))
    assert num_particles(sim) == len(systems.BASE_POSITIONS)
    assert info(sim)["loaded"] is True


def test_loading_again_replaces_the_simulation(loaded):
    check(loaded, lib.structmd_step(loaded, 5))
    load(loaded, systems.dimer_system())
    assert num_particles(loaded) == 2
    assert get_scalar(loaded, "structmd_get_step", "int64_t") == 0
    np.testing.assert_allclose(get_fixed(loaded, "structmd_get_box", 3), [8.0] * 3)


def test_getters_return_the_loaded_state(loaded):
    n = len(systems.BASE_POSITIONS)
    assert num_particles(loaded) == n
    np.testing.assert_array_equal(get_array(loaded, "structmd_get_ids", "int64_t", 1), np.arange(n))
    np.testing.assert_allclose(get_array(loaded, "structmd_get_positions"), systems.BASE_POSITIONS, atol=1e-12)
    np.testing.assert_allclose(get_array(loaded, "structmd_get_velocities"), systems.BASE_VELOCITIES, atol=1e-12)
    type_rows = {row[0]: i for i, row in enumerate(systems.TYPE_TABLE)}
    expected_types = [type_rows[name] for name in systems.BASE_TYPES]
    np.testing.assert_array_equal(get_array(loaded, "structmd_get_types", "int32_t", 1), expected_types)
    masses = {row[0]: row[1] for row in systems.TYPE_TABLE}
    np.testing.assert_allclose(get_array(loaded, "structmd_get_masses", "double", 1),
                               [masses[name] for name in systems.BASE_TYPES])
    np.testing.assert_allclose(get_fixed(loaded, "structmd_get_box", 3), [systems.BASE_BOX] * 3)
    description = info(loaded)
    assert description["particles"] == n
    assert description["precision"] == "double"
    assert description["final_step"] == 1000


def test_state_mass_column_overrides_the_type_mass(sim):
    doc = systems.lj_bond_system()
    doc["state"]["labels"].append("mass")
    for row, mass in zip(doc["state"]["data"], [1.5, 2.5, 3.5, 4.5]):
        row.append(mass)
    load(sim, doc)
    np.testing.assert_allclose(get_array(sim, "structmd_get_masses", "double", 1), [1.5, 2.5, 3.5, 4.5])


def test_energies_virial_and_pressure_agree_with_each_other(loaded):
    check(loaded, lib.structmd_step(loaded, 10))
    masses = get_array(loaded, "structmd_get_masses", "double", 1)
    velocities = get_array(loaded, "structmd_get_velocities")
    kinetic = 0.5 * np.sum(masses[:, None] * velocities**2)
    potential = energy(loaded, "potential")
    assert energy(loaded, "kinetic") == pytest.approx(kinetic, rel=1e-12)
    assert energy(loaded, "total") == pytest.approx(potential + kinetic, rel=1e-12)
    assert energy(loaded, "lj") + energy(loaded, "bonds") == pytest.approx(potential, rel=1e-12)
    assert np.sum(get_array(loaded, "structmd_get_particle_energies", "double", 1)) == pytest.approx(potential, rel=1e-12)
    virial = get_fixed(loaded, "structmd_get_virial", 9).reshape(3, 3)
    np.testing.assert_allclose(virial, virial.T, rtol=1e-10, atol=1e-12)  # central forces only
    volume = np.prod(get_fixed(loaded, "structmd_get_box", 3))
    pressure = get_scalar(loaded, "structmd_get_pressure", "double")
    assert pressure == pytest.approx((2 * kinetic + np.trace(virial)) / (3 * volume), rel=1e-10)


def test_harmonic_bond_force_energy_and_virial(sim):
    separation = 1.3
    load(sim, systems.dimer_system(separation=separation))
    positions = get_array(sim, "structmd_get_positions")
    forces = get_array(sim, "structmd_get_forces")
    d = positions[1] - positions[0]
    stretch = np.linalg.norm(d) - systems.BOND_R0
    expected_on_0 = systems.BOND_K * stretch * d / np.linalg.norm(d)  # pulled toward particle 1
    np.testing.assert_allclose(forces[0], expected_on_0, rtol=1e-12)
    np.testing.assert_allclose(forces[1], -expected_on_0, rtol=1e-12)
    assert energy(sim) == pytest.approx(0.5 * systems.BOND_K * stretch**2, rel=1e-12)
    np.testing.assert_allclose(get_array(sim, "structmd_get_particle_energies", "double", 1),
                               [0.25 * systems.BOND_K * stretch**2] * 2, rtol=1e-12)
    virial = get_fixed(sim, "structmd_get_virial", 9).reshape(3, 3)
    np.testing.assert_allclose(virial, np.outer(-d, expected_on_0), rtol=1e-12, atol=1e-14)


# ---- setters -----------------------------------------------------------------------------------

def test_set_positions_wraps_into_the_box(loaded):
    box = systems.BASE_BOX
    outside = np.array(systems.BASE_POSITIONS) + np.array([[box, 0, 0], [-2 * box, box, 0],
                                                           [0, 0, 3 * box], [-box, -box, -box]])
    outside[0] = [0.5 * box + 0.3, -0.5 * box - 0.2, 0.1]  # just past the faces
    check(loaded, set_vectors(loaded, "structmd_set_positions", outside))
    wrapped = get_array(loaded, "structmd_get_positions")
    assert np.all(wrapped >= -box / 2) and np.all(wrapped < box / 2)
    np.testing.assert_allclose(minimum_image(wrapped - outside, box), 0.0, atol=1e-12)


def test_orientations_round_trip_and_a_non_unit_quaternion_changes_nothing(loaded):
    n = num_particles(loaded)
    np.testing.assert_array_equal(get_array(loaded, "structmd_get_orientations", components=4),
                                  [[1.0, 0.0, 0.0, 0.0]] * n)  # the input gives no directions
    q = np.random.default_rng(11).normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    check(loaded, lib.structmd_set_orientations(loaded, ffi.new("double[]", q.ravel().tolist()), n))
    np.testing.assert_allclose(get_array(loaded, "structmd_get_orientations", components=4), q, atol=1e-15)
    bad = q.copy()
    bad[n - 1] *= 1.001
    expect(loaded, lib.structmd_set_orientations(loaded, ffi.new("double[]", bad.ravel().tolist()), n), ARGUMENT)
    assert f"particle id {n - 1} is not a unit quaternion" in message(loaded)
    np.testing.assert_allclose(get_array(loaded, "structmd_get_orientations", components=4), q, atol=1e-15)
    # No term of this system acts on orientations: zero torques, and the forces are unchanged.
    forces = get_array(loaded, "structmd_get_forces")
    np.testing.assert_array_equal(get_array(loaded, "structmd_get_torques"), 0.0)
    np.testing.assert_array_equal(get_array(loaded, "structmd_get_forces"), forces)
    assert_usable(loaded)


def test_set_positions_makes_forces_and_energies_current(new_handle):
    moved = np.array(systems.BASE_POSITIONS) + [[0.05, 0.0, 0.0], [0.0, -0.04, 0.0],
                                                 [0.0, 0.0, 0.03], [-0.02, 0.02, 0.0]]
    updated = new_handle()
    load(updated, systems.lj_bond_system())
    get_array(updated, "structmd_get_forces")
    energy(updated)
    check(updated, set_vectors(updated, "structmd_set_positions", moved))
    reference = new_handle()
    load(reference, systems.lj_bond_system(positions=moved.tolist()))
    np.testing.assert_allclose(get_array(updated, "structmd_get_forces"),
                               get_array(reference, "structmd_get_forces"), rtol=1e-12, atol=1e-12)
    assert energy(updated) == pytest.approx(energy(reference), rel=1e-12)
    np.testing.assert_allclose(get_fixed(updated, "structmd_get_virial", 9),
                               get_fixed(reference, "structmd_get_virial", 9), rtol=1e-12, atol=1e-12)


def test_set_velocities_round_trips_and_changes_kinetic_energy(loaded):
    new_velocities = -2.0 * np.array(systems.BASE_VELOCITIES)
    kinetic_before = energy(loaded, "kinetic")
    check(loaded, set_vectors(loaded, "structmd_set_velocities", new_velocities))
    np.testing.assert_allclose(get_array(loaded, "structmd_get_velocities"), new_velocities, rtol=1e-15)
    assert energy(loaded, "kinetic") == pytest.approx(4.0 * kinetic_before, rel=1e-12)


def test_set_box_keeps_fractional_coordinates(loaded):
    before = get_array(loaded, "structmd_get_positions")
    new_box = [12.0, 11.0, 10.5]
    check(loaded, lib.structmd_set_box(loaded, ffi.new("double[]", new_box)))
    np.testing.assert_allclose(get_fixed(loaded, "structmd_get_box", 3), new_box)
    scaled = before / systems.BASE_BOX * np.array(new_box)
    np.testing.assert_allclose(get_array(loaded, "structmd_get_positions"), scaled, rtol=1e-12, atol=1e-12)


def test_external_forces_add_to_the_total_force_until_cleared(loaded):
    n = num_particles(loaded)
    rng = np.random.default_rng(3)
    external = rng.uniform(-2.0, 2.0, size=(n, 3))
    for _ in range(2):  # once at the start and once after steps: the field persists
        internal = get_array(loaded, "structmd_get_forces")
        potential = energy(loaded)
        check(loaded, set_vectors(loaded, "structmd_set_external_forces", external))
        total = get_array(loaded, "structmd_get_forces")
        np.testing.assert_allclose(total - internal, external, rtol=1e-12, atol=1e-12)
        assert energy(loaded) == potential  # the field's energy is the host's business
        check(loaded, lib.structmd_step(loaded, 5))
        with_field = get_array(loaded, "structmd_get_forces")
        check(loaded, lib.structmd_set_external_forces(loaded, ffi.NULL, 0))
        np.testing.assert_allclose(with_field - get_array(loaded, "structmd_get_forces"), external,
                                   rtol=1e-12, atol=1e-12)


def test_external_forces_change_the_trajectory(new_handle):
    pushed, free = new_handle(), new_handle()
    for handle in (pushed, free):
        load(handle, systems.lj_bond_system())
    push = np.zeros((len(systems.BASE_POSITIONS), 3))
    push[2] = [0.0, 0.0, 5.0]
    check(pushed, set_vectors(pushed, "structmd_set_external_forces", push))
    for handle in (pushed, free):
        check(handle, lib.structmd_step(handle, 10))
    dv = get_array(pushed, "structmd_get_velocities") - get_array(free, "structmd_get_velocities")
    assert dv[2, 2] > 0.0


# ---- get_info ----------------------------------------------------------------------------------

def test_get_info_reports_the_size_it_needs(loaded):
    needed = ffi.new("size_t*")
    expect(loaded, lib.structmd_get_info(loaded, ffi.NULL, 0, needed), ARGUMENT)
    size = needed[0]
    assert size > 2
    short = ffi.new("char[]", size)
    expect(loaded, lib.structmd_get_info(loaded, short, size - 1, needed), ARGUMENT)
    assert needed[0] == size
    check(loaded, lib.structmd_get_info(loaded, short, size, needed))
    text = ffi.string(short).decode()
    assert len(text.encode()) + 1 == size
    description = json.loads(text)
    assert set(description) >= INFO_KEYS
    assert description["backend"] in ("cpu", "cuda")
    assert description["precision"] in ("single", "double")


def test_get_counters_fits_512_bytes_and_refuses_a_short_buffer(loaded):
    buffer = ffi.new("char[]", 512)
    check(loaded, lib.structmd_get_counters(loaded, buffer, 512))
    text = ffi.string(buffer).decode()
    assert set(json.loads(text)) >= {"force_evaluations", "neighbour_list_builds", "device_to_host_bytes"}
    expect(loaded, lib.structmd_get_counters(loaded, buffer, len(text)), ARGUMENT)
    assert str(len(text) + 1) in message(loaded)


@pytest.mark.parametrize("precision", ["single", "double"])
def test_get_info_reports_the_requested_precision(new_handle, precision):
    handle = new_handle({**engine_options(), "precision": precision})
    assert info(handle)["precision"] == precision


# ---- several handles ---------------------------------------------------------------------------

def test_two_handles_are_independent(new_handle):
    first, second = new_handle(), new_handle()
    load(first, systems.lj_bond_system())
    load(second, systems.dimer_system())
    second_before = snapshot(second)
    check(first, lib.structmd_step(first, 10))
    check(first, set_vectors(first, "structmd_set_external_forces", np.ones((4, 3))))
    check(first, lib.structmd_set_box(first, ffi.new("double[]", [11.0, 11.0, 11.0])))
    expect(first, lib.structmd_step(first, -1), ARGUMENT)
    assert_same_state(second_before, snapshot(second))
    assert message(second) == ""
    assert get_scalar(first, "structmd_get_step", "int64_t") == 10
    assert num_particles(first) == 4 and num_particles(second) == 2
    np.testing.assert_allclose(get_array(second, "structmd_get_forces").sum(axis=0), 0.0, atol=1e-12)


def test_handles_can_be_driven_from_different_threads_at_once(new_handle):
    options = {**engine_options(), "threads": 1}
    reference = new_handle(options)
    load(reference, systems.lj_bond_system())
    check(reference, lib.structmd_step(reference, 200))
    expected = get_array(reference, "structmd_get_positions")

    workers = [new_handle(options) for _ in range(2)]
    statuses = []

    def drive(handle):
        statuses.append(lib.structmd_load_string(handle, json.dumps(systems.lj_bond_system()).encode()))
        statuses.append(lib.structmd_step(handle, 200))

    threads = [threading.Thread(target=drive, args=(handle,)) for handle in workers]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert statuses == [OK] * 4
    for handle in workers:
        np.testing.assert_allclose(get_array(handle, "structmd_get_positions"), expected, rtol=1e-9, atol=1e-9)


# ---- force callbacks and views -----------------------------------------------------------------

CALLBACK = DEFINES["STRUCTMD_ERR_CALLBACK"]
PUSH = np.array([0.25, -0.5, 1.0])  # the force the callbacks below add to every particle


def constant_push(calls, fail_at=None):
    """A host callback adding PUSH to every particle, energy 2.5 and a diagonal virial; it counts its
    calls and, at call number fail_at, explains itself and returns 7."""

    @ffi.callback("structmd_force_callback")
    def callback(positions, forces, n, energy, virial, step, user_data):
        calls.append((step, np.frombuffer(ffi.buffer(positions, 24 * n), dtype=np.float64).reshape(n, 3).copy()))
        if len(calls) == fail_at:
            lib.structmd_set_callback_error(ffi.cast("structmd_sim*", user_data), b"the host's model diverged")
            return 7
        for i in range(n):
            for d in range(3):
                forces[3 * i + d] += PUSH[d]
        energy[0] += 2.5
        for d in range(3):
            virial[4 * d] += 1.0 + d
        return 0

    return callback


def test_force_callback_adds_its_forces_energy_and_virial(new_handle):
    plain, pushed = new_handle(), new_handle()
    for sim in (plain, pushed):
        load(sim, systems.lj_bond_system())
    calls = []
    callback = constant_push(calls)
    check(pushed, lib.structmd_set_force_callback(pushed, callback, pushed))
    n = num_particles(pushed)
    np.testing.assert_allclose(get_array(pushed, "structmd_get_forces"),
                               get_array(plain, "structmd_get_forces") + PUSH, rtol=1e-12, atol=1e-12)
    # The callback saw the positions the engine holds, in id order.
    np.testing.assert_array_equal(calls[0][1], get_array(pushed, "structmd_get_positions"))
    assert energy(pushed, "callback") == 2.5
    assert energy(plain, "callback") == 0.0
    assert energy(pushed, "potential") == pytest.approx(energy(plain, "potential") + 2.5, rel=1e-12)
    assert energy(pushed, "total") == pytest.approx(energy(plain, "total") + 2.5, rel=1e-12)
    np.testing.assert_allclose(get_fixed(pushed, "structmd_get_virial", 9),
                               get_fixed(plain, "structmd_get_virial", 9) + np.diag([1.0, 2.0, 3.0]).ravel(),
                               rtol=1e-12, atol=1e-12)
    assert len(calls) == 1 and n == len(calls[0][1])


def test_force_callback_is_called_once_per_configuration_and_shapes_the_trajectory(new_handle):
    sim = new_handle()
    load(sim, systems.lj_bond_system())
    calls = []
    callback = constant_push(calls)
    check(sim, lib.structmd_set_force_callback(sim, callback, sim))
    get_array(sim, "structmd_get_forces")
    get_array(sim, "structmd_get_forces")
    energy(sim, "potential")
    assert len(calls) == 1
    check(sim, lib.structmd_step(sim, 5))
    # Velocity Verlet evaluates forces once per step, at the step the positions belong to.
    assert [step for step, _ in calls] == [0, 1, 2, 3, 4, 5]
    # Without the callback the same steps go elsewhere: its forces drove the particles.
    reference = new_handle()
    load(reference, systems.lj_bond_system())
    check(reference, lib.structmd_step(reference, 5))
    masses = get_array(sim, "structmd_get_masses", components=1)
    moved = get_array(sim, "structmd_get_velocities") - get_array(reference, "structmd_get_velocities")
    # Over 5 steps of dt the push changes each velocity by about 5 dt PUSH / m.
    expected = 5 * systems.BASE_TIME_STEP * PUSH[None, :] / masses[:, None]
    np.testing.assert_allclose(moved, expected, rtol=0.2, atol=1e-6)


def test_failing_force_callback_stops_the_step_and_rolls_back(loaded):
    check(loaded, lib.structmd_step(loaded, 2))
    calls = []
    callback = constant_push(calls, fail_at=3)
    check(loaded, lib.structmd_set_force_callback(loaded, callback, loaded))
    before = snapshot(loaded)
    expect(loaded, lib.structmd_step(loaded, 10), CALLBACK)
    assert "returned 7: the host's model diverged" in message(loaded)
    assert "step 4" in message(loaded)
    assert_same_state(before, snapshot(loaded))
    check(loaded, lib.structmd_set_force_callback(loaded, ffi.NULL, ffi.NULL))
    assert energy(loaded, "callback") == 0.0
    check(loaded, lib.structmd_step(loaded, 10))
    assert get_scalar(loaded, "structmd_get_step", "int64_t") == 12


def test_callback_error_outside_a_callback_changes_nothing(loaded):
    expect(loaded, lib.structmd_step(loaded, -1), ARGUMENT)
    reason = message(loaded)
    check(loaded, lib.structmd_set_callback_error(loaded, b"not in a callback"))
    assert message(loaded) == reason
    expect(loaded, lib.structmd_set_callback_error(loaded, ffi.NULL), ARGUMENT)


def test_device_force_callback_gets_the_engines_records(new_handle):
    if engine_options()["backend"] != "cpu":
        pytest.skip("the host reads these records only on the CPU backend; tests/python/test_force_callbacks.py "
                    "covers CUDA through CuPy")
    host, device = new_handle(), new_handle()
    for sim in (host, device):
        load(sim, systems.lj_bond_system())
    host_calls = []
    host_callback = constant_push(host_calls)
    check(host, lib.structmd_set_force_callback(host, host_callback, host))
    seen = []

    @ffi.callback("structmd_device_force_callback")
    def device_callback(positions, forces, n, real_size, energy, virial, step, stream, user_data):
        assert real_size == 8 and stream == ffi.NULL
        records = np.frombuffer(ffi.buffer(positions, 32 * n), dtype=np.float64).reshape(n, 4)
        seen.append(records[:, :3].copy())
        out = np.frombuffer(ffi.buffer(forces, 32 * n), dtype=np.float64).reshape(n, 4)
        out[:, :3] += PUSH
        energy[0] += 2.5
        return 0

    check(device, lib.structmd_set_device_force_callback(device, device_callback, ffi.NULL))
    check(host, lib.structmd_step(host, 20))
    check(device, lib.structmd_step(device, 20))
    np.testing.assert_array_equal(seen[0], host_calls[0][1])
    assert len(seen) == 21
    np.testing.assert_array_equal(get_array(device, "structmd_get_positions"), get_array(host, "structmd_get_positions"))
    assert energy(device, "callback") == 2.5


def test_view_describes_the_engines_array(loaded):
    view = ffi.new("structmd_dlpack_tensor**")
    for quantity, getter in (("positions", "structmd_get_positions"), ("velocities", "structmd_get_velocities"),
                             ("forces", "structmd_get_forces")):
        check(loaded, lib.structmd_get_view(loaded, quantity.encode(), view))
        managed = view[0]
        tensor = managed.dl_tensor
        n = num_particles(loaded)
        assert (tensor.ndim, tensor.shape[0], tensor.shape[1]) == (2, n, 3)
        assert (tensor.strides[0], tensor.strides[1], tensor.byte_offset) == (4, 1, 0)
        assert (tensor.dtype.code, tensor.dtype.bits, tensor.dtype.lanes) == (2, 64, 1)  # kDLFloat, double
        if engine_options()["backend"] == "cpu":
            assert tensor.device.device_type == 1
            records = np.frombuffer(ffi.buffer(tensor.data, 32 * n), dtype=np.float64).reshape(n, 4)
            np.testing.assert_array_equal(records[:, :3], get_array(loaded, getter))
        else:
            assert tensor.device.device_type == 2
        managed.deleter(managed)
    expect(loaded, lib.structmd_get_view(loaded, b"masses", view), ARGUMENT)
    assert "known: positions, velocities, forces" in message(loaded)


# ---- coverage of the header --------------------------------------------------------------------

def base_separations():
    """The base system's positions, minimum-image separations d[i, j] = r_j - r_i and distances
    (infinite on the diagonal)."""
    p = np.array(systems.BASE_POSITIONS)
    d = p[None, :, :] - p[:, None, :]
    d -= systems.BASE_BOX * np.round(d / systems.BASE_BOX)
    r = np.linalg.norm(d, axis=2)
    np.fill_diagonal(r, np.inf)
    return p, d, r


def test_traverse_expression_sums_over_pairs_by_minimum_image(loaded):
    """structmd_traverse_expression: each particle's sum of an expression over its pairs, against
    numpy over every minimum image, with a neighbour list (cutoff) and over all pairs (0)."""
    p, d, r = base_separations()
    n = len(p)
    sums = ffi.new("double[]", n)
    check(loaded, lib.structmd_traverse_expression(loaded, b"r < 3", 3.0, sums, n))
    np.testing.assert_array_equal(list(sums), np.sum(r < 3.0, axis=1))
    check(loaded, lib.structmd_traverse_expression(loaded, b"exp(-r) * dy", 0.0, sums, n))
    np.testing.assert_allclose(list(sums), np.sum(np.exp(-r) * d[:, :, 1], axis=1), rtol=1e-12, atol=1e-15)
    before = list(sums)
    assert lib.structmd_traverse_expression(loaded, b"r < q", 3.0, sums, n) == INPUT
    assert "unknown variable 'q'" in ffi.string(lib.structmd_last_error(loaded)).decode()
    assert list(sums) == before


def test_traverse_runs_a_plugin_transverser_and_refuses_unknown_names(new_handle, loaded):
    """structmd_traverse with the NeighbourCount plugin every handle here loads: neighbour counts
    against numpy by minimum image; structmd_transverser_values needs no load; a handle without the
    plugin refuses the name, saying that no loaded plugin registers one, and writes nothing."""
    if not os.environ.get("STRUCTMD_TEST_TRANSVERSER_PLUGIN"):
        pytest.skip("STRUCTMD_TEST_TRANSVERSER_PLUGIN not set (ctest sets it)")
    p, d, r = base_separations()
    n = len(p)
    out = ffi.new("double[]", n)
    check(loaded, lib.structmd_traverse(loaded, b"NeighbourCount", ffi.NULL, 3.0, out, n))
    np.testing.assert_array_equal(list(out), np.sum(r < 3.0, axis=1))
    check(loaded, lib.structmd_traverse(loaded, b"NeighbourCount", b"", 0.0, out, n))
    assert list(out) == [n - 1] * n
    values = ffi.new("int*", -1)
    unloaded = new_handle()
    check(unloaded, lib.structmd_transverser_values(unloaded, b"NeighbourCount", values))
    assert values[0] == 1

    bare = new_handle(engine_options())
    assert lib.structmd_transverser_values(bare, b"NeighbourCount", values) == ARGUMENT
    assert "no loaded plugin registers one" in ffi.string(lib.structmd_last_error(bare)).decode()
    load(bare, systems.lj_bond_system())
    untouched = ffi.new("double[]", [7.0] * n)
    assert lib.structmd_traverse(bare, b"NeighbourCount", ffi.NULL, 3.0, untouched, n) == ARGUMENT
    assert "no transverser named 'NeighbourCount'" in ffi.string(lib.structmd_last_error(bare)).decode()
    assert list(untouched) == [7.0] * n


def test_traverse_view_lends_the_transverser_output_as_a_dlpack_tensor(new_handle, loaded):
    """structmd_traverse_view: the NeighbourCount plugin's counts as a DLPack tensor of shape (n), in
    host memory on the CPU backend (on the GPU on CUDA), equal to structmd_traverse's and to numpy's;
    then its refusals: an unknown name (the message lists the known ones), a NULL view, parameters it
    does not take, no load; each leaves the out-pointer alone."""
    if not os.environ.get("STRUCTMD_TEST_TRANSVERSER_PLUGIN"):
        pytest.skip("STRUCTMD_TEST_TRANSVERSER_PLUGIN not set (ctest sets it)")
    p, d, r = base_separations()
    n = len(p)
    view = ffi.new("structmd_dlpack_tensor**")
    for cutoff, expected in ((3.0, np.sum(r < 3.0, axis=1)), (0.0, np.full(n, n - 1))):
        check(loaded, lib.structmd_traverse_view(loaded, b"NeighbourCount", ffi.NULL, cutoff, view))
        managed = view[0]
        tensor = managed.dl_tensor
        assert (tensor.ndim, tensor.shape[0], tensor.strides[0], tensor.byte_offset) == (1, n, 1, 0)
        assert (tensor.dtype.code, tensor.dtype.bits, tensor.dtype.lanes) == (2, 64, 1)  # kDLFloat, double
        if engine_options()["backend"] == "cpu":
            assert tensor.device.device_type == 1
            counts = np.frombuffer(ffi.buffer(tensor.data, 8 * n), dtype=np.float64).copy()
            np.testing.assert_array_equal(counts, expected)
            host = ffi.new("double[]", n)
            check(loaded, lib.structmd_traverse(loaded, b"NeighbourCount", ffi.NULL, cutoff, host, n))
            np.testing.assert_array_equal(counts, list(host))
        else:
            assert tensor.device.device_type == 2
        managed.deleter(managed)

    untouched = ffi.cast("structmd_dlpack_tensor*", 0x1234)
    view[0] = untouched
    expect(loaded, lib.structmd_traverse_view(loaded, b"Nope", ffi.NULL, 3.0, view), ARGUMENT)
    assert "no transverser named 'Nope'" in message(loaded) and "'NeighbourCount'" in message(loaded)
    expect(loaded, lib.structmd_traverse_view(loaded, b"NeighbourCount", b'{"radius": 1}', 3.0, view), INPUT)
    assert "NeighbourCount.parameters.radius" in message(loaded)
    expect(loaded, lib.structmd_traverse_view(loaded, b"NeighbourCount", b"[1]", 3.0, view), ARGUMENT)
    expect(loaded, lib.structmd_traverse_view(loaded, b"NeighbourCount", ffi.NULL, -1.0, view), INPUT)
    assert view[0] == untouched
    expect(loaded, lib.structmd_traverse_view(loaded, b"NeighbourCount", ffi.NULL, 3.0, ffi.NULL), ARGUMENT)
    assert "view" in message(loaded)
    expect(loaded, lib.structmd_traverse_view(loaded, ffi.NULL, ffi.NULL, 3.0, view), ARGUMENT)
    unloaded = new_handle()
    expect(unloaded, lib.structmd_traverse_view(unloaded, b"NeighbourCount", ffi.NULL, 3.0, view), STATE)
    assert view[0] == untouched


def test_every_header_function_was_called(request):
    selected = {item.originalname for item in request.session.items if item.module is request.module}
    defined = {name for name in dir(request.module) if name.startswith("test_")}
    if selected != defined:
        pytest.skip("only meaningful when the whole module runs")
    assert set(PROTOTYPES) - _called == set()
