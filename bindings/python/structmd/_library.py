"""Finds libstructmd, checks its ABI version and declares the C signature of every function.

Search order: the path in the environment variable STRUCTMD_LIBRARY; a library file next to the
package (inside it, where a wheel from `pip install .` puts it under its soname, or in its parent folder); in a source
checkout (bindings/python/structmd), the build tree of scripts/build.sh, build/src; then
ctypes.util.find_library("structmd").
"""

import ctypes
import ctypes.util
import os
import sys
from ctypes import CFUNCTYPE, POINTER, c_char_p, c_double, c_int, c_int32, c_int64, c_size_t, c_uint32, c_void_p
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

from .constants import ABI_VERSION

LIBRARY_ENV = "STRUCTMD_LIBRARY"

STATUS_T = c_int32  # structmd_status
HANDLE_T = c_void_p  # structmd_sim*, opaque

# structmd_force_callback and structmd_device_force_callback; the functions that take them receive
# their addresses (c_void_p), so NULL clears a callback.
FORCE_CALLBACK_T = CFUNCTYPE(c_int32, POINTER(c_double), POINTER(c_double), c_int64, POINTER(c_double),
                             POINTER(c_double), c_int64, c_void_p)
DEVICE_FORCE_CALLBACK_T = CFUNCTYPE(c_int32, c_void_p, c_void_p, c_int64, c_int32, POINTER(c_double),
                                    POINTER(c_double), c_int64, c_void_p, c_void_p)

# name: (restype, argtypes), in the order of include/structmd.h.
SIGNATURES: Dict[str, Tuple[Any, List[Any]]] = {
    "structmd_abi_version": (c_int, []),
    "structmd_version": (c_char_p, []),
    "structmd_create": (STATUS_T, [c_char_p, POINTER(HANDLE_T)]),
    "structmd_destroy": (None, [HANDLE_T]),
    "structmd_last_error": (c_char_p, [HANDLE_T]),
    "structmd_load_file": (STATUS_T, [HANDLE_T, c_char_p]),
    "structmd_load_string": (STATUS_T, [HANDLE_T, c_char_p]),
    "structmd_load_plugin": (STATUS_T, [c_char_p]),
    "structmd_step": (STATUS_T, [HANDLE_T, c_int64]),
    "structmd_run": (STATUS_T, [HANDLE_T]),
    "structmd_compute": (STATUS_T, [HANDLE_T, c_uint32]),
    "structmd_get_num_particles": (STATUS_T, [HANDLE_T, POINTER(c_int64)]),
    "structmd_get_ids": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64]),
    "structmd_get_positions": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_velocities": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_orientations": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_torques": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_magnetic_moments": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_set_orientations": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_forces": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_particle_energies": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_masses": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_get_types": (STATUS_T, [HANDLE_T, POINTER(c_int32), c_int64]),
    "structmd_get_energy": (STATUS_T, [HANDLE_T, c_char_p, POINTER(c_double)]),
    "structmd_get_virial": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_get_pressure": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_get_temperature": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_get_box": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_get_step": (STATUS_T, [HANDLE_T, POINTER(c_int64)]),
    "structmd_get_time": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_traverse_expression": (STATUS_T, [HANDLE_T, c_char_p, c_double, POINTER(c_double), c_int64]),
    "structmd_transverser_values": (STATUS_T, [HANDLE_T, c_char_p, POINTER(c_int)]),
    "structmd_traverse": (STATUS_T, [HANDLE_T, c_char_p, c_char_p, c_double, POINTER(c_double), c_int64]),
    "structmd_set_positions": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_set_velocities": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_set_box": (STATUS_T, [HANDLE_T, POINTER(c_double)]),
    "structmd_set_external_forces": (STATUS_T, [HANDLE_T, POINTER(c_double), c_int64]),
    "structmd_set_external_energy": (STATUS_T, [HANDLE_T, c_double]),
    "structmd_get_positions_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_get_velocities_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_get_forces_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_set_positions_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_set_velocities_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_set_external_forces_of": (STATUS_T, [HANDLE_T, POINTER(c_int64), c_int64, POINTER(c_double)]),
    "structmd_set_parameter": (STATUS_T, [HANDLE_T, c_char_p, c_double]),
    "structmd_get_parameter": (STATUS_T, [HANDLE_T, c_char_p, POINTER(c_double)]),
    "structmd_set_force_callback": (STATUS_T, [HANDLE_T, c_void_p, c_void_p]),
    "structmd_set_device_force_callback": (STATUS_T, [HANDLE_T, c_void_p, c_void_p]),
    "structmd_set_callback_error": (STATUS_T, [HANDLE_T, c_char_p]),
    "structmd_get_view": (STATUS_T, [HANDLE_T, c_char_p, POINTER(c_void_p)]),
    "structmd_traverse_view": (STATUS_T, [HANDLE_T, c_char_p, c_char_p, c_double, POINTER(c_void_p)]),
    "structmd_save_checkpoint": (STATUS_T, [HANDLE_T, c_char_p]),
    "structmd_load_checkpoint": (STATUS_T, [HANDLE_T, c_char_p]),
    "structmd_get_info": (STATUS_T, [HANDLE_T, c_char_p, c_size_t, POINTER(c_size_t)]),
    "structmd_get_counters": (STATUS_T, [HANDLE_T, c_char_p, c_size_t]),
}


def _library_file_patterns() -> List[str]:
    """The library's file names, as glob patterns: a wheel holds it under its soname (libstructmd.so.0.1)."""
    if sys.platform == "win32":
        return ["structmd.dll"]
    if sys.platform == "darwin":
        return ["libstructmd.dylib"]
    return ["libstructmd.so", "libstructmd.so.*"]


def checkout_repository(package_dir: Path) -> Optional[Path]:
    """The repository when the package is the one of a source checkout (bindings/python/structmd), else None."""
    bindings = package_dir.parent.parent
    repository = bindings.parent
    in_checkout = (package_dir.parent.name, bindings.name) == ("python", "bindings")
    if in_checkout and (repository / "include" / "structmd.h").is_file():
        return repository
    return None


def _checkout_build_folders(package_dir: Path) -> List[Path]:
    """build/src of the repository when the package is the one of a source checkout, else nothing."""
    repository = checkout_repository(package_dir)
    return [] if repository is None else [repository / "build" / "src"]


def find_library_path() -> str:
    """The library file to load, by the search order above; ImportError when there is none."""
    explicit = os.environ.get(LIBRARY_ENV)
    if explicit:
        if not Path(explicit).is_file():
            raise ImportError(f"structmd: {LIBRARY_ENV}={explicit} does not name a file")
        return explicit
    package_dir = Path(__file__).resolve().parent
    for folder in (package_dir, package_dir.parent, *_checkout_build_folders(package_dir)):
        for pattern in _library_file_patterns():
            for candidate in sorted(folder.glob(pattern)):
                if candidate.is_file():
                    return str(candidate)
    found = ctypes.util.find_library("structmd")
    if found:
        return found
    raise ImportError(
        "structmd: the shared library libstructmd was not found; set "
        f"{LIBRARY_ENV} to its path, put it next to the package ({package_dir}) or on the "
        "system's library path, or install the package with `pip install .` from the repository")


def load_library() -> Tuple[ctypes.CDLL, str]:
    """Loads the library, refuses one of another ABI version and declares every function."""
    path = find_library_path()
    try:
        lib = ctypes.CDLL(path)
    except OSError as error:
        raise ImportError(f"structmd: cannot load {path}: {error}") from error
    # The version check comes before any other symbol is looked up, so a library of another ABI
    # is reported as such rather than as a missing function.
    restype, argtypes = SIGNATURES["structmd_abi_version"]
    lib.structmd_abi_version.restype = restype
    lib.structmd_abi_version.argtypes = argtypes
    found = lib.structmd_abi_version()
    if found != ABI_VERSION:
        raise ImportError(
            f"structmd: {path} implements ABI version {found}, but this Python package is written "
            f"for ABI version {ABI_VERSION}; use the package that ships with that library")
    for name, (restype, argtypes) in SIGNATURES.items():
        try:
            function = getattr(lib, name)
        except AttributeError as error:
            raise ImportError(f"structmd: {path} does not export {name}") from error
        function.restype = restype
        function.argtypes = argtypes
    return lib, path


lib, library_path = load_library()
