"""The signature table of the ctypes package (bindings/python/structmd/_library.py) against
include/structmd.h, type by type (python_binding.py says what must agree); then the same check on a
table or header altered on purpose, so that each kind of mismatch is shown to be caught and named.

The table is hand-written rather than generated at build time: the package is pure Python and runs
from the source tree, and this check keeps it exact."""

import ctypes
import re

import pytest

import python_binding
import structmd_header
from structmd import _library

HANDLE, STATUS = ctypes.c_void_p, ctypes.c_int32


def findings(signatures=None, header_text=None):
    functions = structmd_header.functions(header_text or structmd_header.header_text())
    return python_binding.problems(functions, signatures or _library.SIGNATURES)


def test_python_signature_table_matches_the_header():
    found = findings()
    assert not found, "bindings/python/structmd/_library.py disagrees with include/structmd.h:\n" + "\n".join(found)


@pytest.mark.parametrize("name, entry, expected", [
    ("structmd_step", (STATUS, [HANDLE, ctypes.c_int32]),
     "structmd_step: argument 2 (int64_t nsteps): expected c_int64, the table says c_int32"),
    ("structmd_create", (STATUS, [ctypes.c_char_p, HANDLE]),
     "structmd_create: argument 2 (structmd_sim** out): expected POINTER(c_void_p), the table says c_void_p"),
    ("structmd_get_types", (STATUS, [HANDLE, ctypes.POINTER(ctypes.c_int64), ctypes.c_int64]),
     "structmd_get_types: argument 2 (int32_t* type_index): expected POINTER(c_int32), "
     "the table says POINTER(c_int64)"),
    ("structmd_get_box", (STATUS, [HANDLE, ctypes.c_double]),
     "structmd_get_box: argument 2 (double lengths[3]): expected POINTER(c_double), the table says c_double"),
    ("structmd_compute", (STATUS, [HANDLE, ctypes.c_int64]),
     "structmd_compute: argument 2 (uint32_t flags): expected c_uint32, the table says c_int64"),
    ("structmd_version", (ctypes.c_void_p, []),
     "structmd_version: result: C returns const char*: expected c_char_p, the table says c_void_p"),
    ("structmd_destroy", (STATUS, [HANDLE]),
     "structmd_destroy: result: C returns void: expected None, the table says c_int32"),
    ("structmd_get_counters", (STATUS, [HANDLE, ctypes.c_char_p]),
     "structmd_get_counters: 3 parameters in C, 2 in the table"),
    ("structmd_run", None, "structmd_run: missing from the signature table"),
    ("structmd_get_enthalpy", (STATUS, [HANDLE, ctypes.POINTER(ctypes.c_double)]),
     "structmd_get_enthalpy: in the signature table but not declared in the header"),
])
def test_table_drift_is_caught(name, entry, expected):
    signatures = dict(_library.SIGNATURES)
    if entry is None:
        del signatures[name]
    else:
        signatures[name] = entry
    found = findings(signatures=signatures)
    assert expected in found, f"expected '{expected}' among: {found}"


def test_header_drift_is_caught():
    header, count = re.subn(r"size_t size\);", "int64_t size);", structmd_header.header_text())
    assert count == 1, "the pattern no longer matches the header: update this test"
    assert findings(header_text=header) == [
        "structmd_get_counters: argument 3 (int64_t size): expected c_int64, the table says c_size_t"]
