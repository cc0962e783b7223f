"""structmd: Python host of the structmd molecular dynamics engine, over its C ABI through ctypes.

    import structmd
    with structmd.Simulation({"backend": "cpu"}) as sim:
        sim.load("input.json")
        sim.step(100)
        f = sim.forces              # (n, 3) numpy array
        sim.external_forces = -0.1 * sim.positions
        sim.step(100)

The shared library is found through the environment variable STRUCTMD_LIBRARY, else inside or next to
this package (pip install . bundles it inside), else in a source checkout's build/src, else on the
system's library path; importing fails with ImportError if its ABI version is not ABI_VERSION.

structmd.Input builds inputs from Python values (structmd/builder.py). structmd.ase (an ASE
calculator) and structmd.ipi (an i-PI client) are imported on demand: see docs/python.md.
"""

import os as _os
from typing import Union

from ._library import lib as _lib
from ._library import library_path
from .constants import ABI_VERSION, COMPUTE_FLAGS, STATUS
from .errors import (ArgumentError, CallbackError, DeviceError, InputError, InternalError, NumericalError, StateError,
                     StructmdError, StructmdIOError, StructmdMemoryError, UnsupportedError,
                     error_for_status)
from .builder import Input
from .simulation import Simulation


def abi_version() -> int:
    """STRUCTMD_ABI_VERSION of the library actually loaded. Raises nothing."""
    return int(_lib.structmd_abi_version())


def version() -> str:
    """The library version, "MAJOR.MINOR.PATCH". Raises nothing."""
    return str(_lib.structmd_version().decode())


def load_plugin(path: Union[str, "_os.PathLike[str]"]) -> None:
    """Loads a plugin library for every Simulation created afterwards (structmd_load_plugin); a
    Simulation may also load its own through the option "plugins". Raises the StructmdError subclass
    of the failure: StructmdIOError (no such file), ArgumentError (not a plugin), UnsupportedError
    (built for another plugin ABI or another build of structmd)."""
    status = _lib.structmd_load_plugin(_os.fsencode(path))
    if status != STATUS["STRUCTMD_OK"]:
        raise error_for_status(status, _lib.structmd_last_error(None).decode(errors="replace"))


__version__ = version()

__all__ = [
    "ABI_VERSION", "COMPUTE_FLAGS", "STATUS", "Input", "Simulation", "abi_version", "version", "library_path",
    "load_plugin",
    "StructmdError", "ArgumentError", "InputError", "StateError", "NumericalError", "StructmdIOError",
    "DeviceError", "StructmdMemoryError", "UnsupportedError", "InternalError", "CallbackError", "error_for_status",
]
