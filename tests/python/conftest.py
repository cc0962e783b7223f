"""Shared fixtures. STRUCTMD_TEST_BACKEND (default "cpu") picks the backend every test handle uses, so
one test body runs on each backend; with "cuda" the session ends with exit code 77 (ctest's skip) when
no double-precision handle can be made on it: no usable GPU, or a build without double (the message
says which)."""

import ctypes
import json
import os

import pytest

BACKEND = os.environ.get("STRUCTMD_TEST_BACKEND", "cpu")
SKIP_RETURN_CODE = 77


def engine_options():
    """Options for every test handle: double precision, so that comparisons can be tight."""
    return {"backend": BACKEND, "precision": "double", "log": "quiet"}


def library_path():
    path = os.environ.get("STRUCTMD_LIBRARY")
    if not path:
        raise RuntimeError("set STRUCTMD_LIBRARY to the path of libstructmd (ctest does this)")
    return path


def pytest_sessionstart(session):
    if BACKEND != "cuda":
        return
    lib = ctypes.CDLL(library_path())
    lib.structmd_create.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)]
    lib.structmd_create.restype = ctypes.c_int32
    lib.structmd_destroy.argtypes = [ctypes.c_void_p]
    lib.structmd_last_error.argtypes = [ctypes.c_void_p]
    lib.structmd_last_error.restype = ctypes.c_char_p
    handle = ctypes.c_void_p()
    if lib.structmd_create(json.dumps(engine_options()).encode(), ctypes.byref(handle)) != 0:
        reason = lib.structmd_last_error(None).decode()
        pytest.exit(f"no double-precision handle on the cuda backend: {reason}", returncode=SKIP_RETURN_CODE)
    lib.structmd_destroy(handle)


@pytest.fixture
def options():
    return engine_options()
