"""The Simulation class: one structmd handle, driven through the C ABI."""

from __future__ import annotations

import json
import math
import operator
import os
import sys
import time as _time
from collections.abc import Mapping
from ctypes import POINTER, byref, cast, c_double, c_int, c_int32, c_int64, c_size_t, c_void_p, create_string_buffer
from typing import (TYPE_CHECKING, Any, Callable, Dict, Iterable, Literal, Optional, SupportsIndex,
                    TextIO, Tuple, TypeVar, Union)

from ._library import DEVICE_FORCE_CALLBACK_T, FORCE_CALLBACK_T, lib
from .dlpack import K_DL_CUDA, DLPackView, make_tensor
from .constants import COMPUTE_FLAGS, STATUS
from .errors import ArgumentError, StateError, StructmdError, error_for_status

if TYPE_CHECKING:
    import _ctypes
    import ctypes

    # The annotations describe the arrays as numpy gives them (numpy is a dependency of the package);
    # without numpy importable the same members give lists of tuples, which the types leave out.
    import numpy as _np
    from numpy.typing import ArrayLike, NDArray

    FloatArray = NDArray[_np.float64]
    CPointer = ctypes._Pointer
else:
    try:
        import numpy as _np
    except ImportError:
        _np = None

# What a force callback may return: None, its energy, or (energy, virial as 3x3 or 9 numbers).
CallbackResult = Union[None, float, Tuple[float, "ArrayLike"]]
# callback(positions (n, 3) read-only, forces (n, 3) to add to, step) of set_force_callback.
ForceCallback = Callable[["FloatArray", "FloatArray", int], CallbackResult]
# callback(positions, forces, step, stream) of set_device_force_callback.
DeviceForceCallback = Callable[[DLPackView, DLPackView, int, int], CallbackResult]
# A file path as os.fsencode takes it.
PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
# What Simulation.load takes: a dict, a JSON document string or a path.
InputSource = Union[Mapping[str, Any], str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
ViewQuantity = Literal["positions", "velocities", "forces"]

_Self = TypeVar("_Self", bound="Simulation")

_INFO_FIRST_GUESS = 512  # bytes; structmd_get_info says how much it needs if this is short
_COUNTERS_SIZE = 512  # bytes; the header promises structmd_get_counters never needs more
_PROGRESS_INTERVAL = 0.2  # seconds of steps between two redraws of run(progress=True)'s bar
_PROGRESS_WIDTH = 30  # characters of the bar itself


def _decode(text: Optional[bytes]) -> str:
    return text.decode("utf-8", errors="replace") if text else ""


def _looks_like_json(text: str) -> bool:
    # An input document is a JSON object, possibly preceded by comments; a path never starts so.
    return text.lstrip().startswith(("{", "//", "/*"))


def ctypes_address(function: _ctypes.CFuncPtr) -> Optional[int]:
    """The address (an int) of a ctypes function object, as the C ABI's callback parameters take it;
    None for a NULL function pointer. Raises nothing."""
    return cast(function, c_void_p).value


def _raise_for(status: int, message: str) -> None:
    if status != STATUS["STRUCTMD_OK"]:
        raise error_for_status(status, message)


def _clock(seconds: float) -> str:
    """H:MM:SS of a duration in seconds, "?" when unknown."""
    if not math.isfinite(seconds):
        return "?"
    minutes, secs = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}"


class _ProgressBar:
    """A one-line progress bar redrawn in place (carriage return) on a text stream; no dependency."""

    def __init__(self, total: int, stream: TextIO) -> None:
        self.total = total
        self.stream = stream

    def draw(self, done: int, elapsed: float) -> None:
        fraction = done / self.total if self.total > 0 else 1.0
        filled = int(round(_PROGRESS_WIDTH * fraction))
        rate = done / elapsed if elapsed > 0.0 and done > 0 else math.nan
        remaining = (self.total - done) / rate if rate > 0.0 else math.nan
        speed = "?" if not math.isfinite(rate) else f"{rate:.3g}" if rate < 100.0 else f"{rate:,.0f}"
        self.stream.write(f"\r{done}/{self.total} steps [{'#' * filled}{'.' * (_PROGRESS_WIDTH - filled)}] "
                          f"{100.0 * fraction:3.0f}% {speed} steps/s ETA {_clock(remaining)}")
        self.stream.flush()

    def close(self) -> None:
        self.stream.write("\n")
        self.stream.flush()


class Simulation:
    """A structmd simulation: create, load an input, step, read and set particle data, close.

    Arrays come back as numpy arrays when numpy is installed: (n, 3) for vector quantities, (n,) for
    scalars, always in ascending particle-id order. Without numpy they come back as lists of tuples
    (vectors) or lists (scalars). Every failure raises the StructmdError subclass of its status.

    options: None (all defaults), a dict or a JSON string with the keys of structmd_create
    ("backend", "device", "precision", "threads", "log", "log_file", "plugins", "mpi_comm": a
    communicator as a Fortran handle, e.g. mpi4py's comm.py2f(), under which every call is collective;
    "ghost_exchange": "auto", "host" or "nccl", how spatial domains' ghosts travel between ranks).
    Raises TypeError for options of another type, and the StructmdError of structmd_create's failure
    (ArgumentError for an unknown option, DeviceError when a GPU is demanded and none is usable).

    Units: every physical value (positions, velocities, forces, energies, box, time, ...) is in the
    units of the loaded input (its ["Units", ...] entry), as the engine holds it.
    """

    def __init__(self, options: Union[None, Mapping[str, Any], str] = None) -> None:
        if options is None:
            encoded = None
        elif isinstance(options, Mapping):
            encoded = json.dumps(dict(options)).encode()
        elif isinstance(options, str):
            encoded = options.encode()
        else:
            raise TypeError(f"options must be a dict, a JSON string or None, not {type(options).__name__}")
        self._handle: Optional[c_void_p] = None
        self._external_forces: Optional[FloatArray] = None
        self._callbacks: Dict[str, _ctypes.CFuncPtr] = {}  # the ctypes function objects the library holds, kept alive while set
        handle = c_void_p()
        status = lib.structmd_create(encoded, byref(handle))
        _raise_for(status, _decode(lib.structmd_last_error(None)))
        self._handle = handle

    # ---- lifetime ----------------------------------------------------------------------------

    def close(self) -> None:
        """Releases the handle and everything it owns; later calls raise StateError. Idempotent."""
        if self._handle is not None:
            lib.structmd_destroy(self._handle)
            self._handle = None

    @property
    def closed(self) -> bool:
        """True after close(): the handle is released and every other call raises StateError."""
        return self._handle is None

    def __enter__(self: _Self) -> _Self:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def __del__(self) -> None:
        # At interpreter shutdown the module globals may already be gone; nothing to do then.
        if getattr(self, "_handle", None) is not None and lib is not None:
            self.close()

    def __repr__(self) -> str:
        if self.closed:
            return "<structmd.Simulation closed>"
        try:
            return f"<structmd.Simulation {self.info!r}>"
        except StructmdError as error:
            return f"<structmd.Simulation ({error})>"

    def _checked_handle(self) -> c_void_p:
        if self._handle is None:
            raise StateError(STATUS["STRUCTMD_ERR_STATE"], "this Simulation is closed")
        return self._handle

    def _call(self, function: Callable[..., int], *args: Any) -> None:
        handle = self._checked_handle()
        status = function(handle, *args)
        if status != STATUS["STRUCTMD_OK"]:
            raise error_for_status(status, _decode(lib.structmd_last_error(handle)))

    @property
    def last_error(self) -> str:
        """The message of the last failed call on this handle, "" if none. Raises StateError after close()."""
        return _decode(lib.structmd_last_error(self._checked_handle()))

    # ---- force callbacks and views -----------------------------------------------------------

    def _report_callback_failure(self, error: BaseException) -> int:
        lib.structmd_set_callback_error(self._handle, f"{type(error).__name__}: {error}".encode(errors="replace"))
        return 1

    @staticmethod
    def _add_energy_and_virial(result: CallbackResult, energy: CPointer[c_double],
                               virial: CPointer[c_double]) -> None:
        """A callback returns None, its energy, or (energy, virial as 3x3 or 9 numbers)."""
        if result is None:
            return
        if isinstance(result, tuple):
            energy[0] = float(result[0])
            for k, w in enumerate(_np.ravel(result[1]) if _np is not None else result[1]):
                virial[k] = float(w)
        else:
            energy[0] = float(result)

    def set_force_callback(self, callback: Optional[ForceCallback]) -> None:
        """Sets (None clears) the host force callback (structmd_set_force_callback):
        callback(positions, forces, step) is called at every force evaluation at new positions with
        positions (n, 3), read-only, and forces (n, 3), zeros to add to, both numpy arrays valid
        during the call only. It returns None, its energy, or (energy, virial 3x3). An exception it
        raises stops the structmd call with CallbackError carrying the exception's text. Positions,
        forces and the energy are in the input's units. Raises RuntimeError without numpy, StateError
        after close()."""
        if callback is None:
            self._call(lib.structmd_set_force_callback, None, None)
            self._callbacks.pop("host", None)
            return
        if _np is None:
            raise RuntimeError("force callbacks need numpy")

        def trampoline(positions: CPointer[c_double], forces: CPointer[c_double], n: int,
                       energy: CPointer[c_double], virial: CPointer[c_double], step: int,
                       _user_data: Optional[int]) -> int:
            try:
                xyz = _np.ctypeslib.as_array(positions, shape=(n, 3))
                xyz.flags.writeable = False
                result = callback(xyz, _np.ctypeslib.as_array(forces, shape=(n, 3)), step)
                self._add_energy_and_virial(result, energy, virial)
                return 0
            except BaseException as error:  # noqa: B902 - nothing may cross back into C
                return self._report_callback_failure(error)

        function = FORCE_CALLBACK_T(trampoline)
        self._call(lib.structmd_set_force_callback, ctypes_address(function), None)
        self._callbacks["host"] = function

    def set_device_force_callback(self, callback: Optional[DeviceForceCallback]) -> None:
        """Sets (None clears) the device force callback (structmd_set_device_force_callback):
        callback(positions, forces, step, stream) receives the engine's own arrays as DLPackView
        objects of shape (n, 3) (cupy.from_dlpack / torch.from_dlpack on CUDA; view.numpy() on the
        CPU backend, writable), forces zero on entry to be added to, and the engine's CUDA stream as an
        integer (0 on the CPU backend). The callback returns as for set_force_callback. Raises
        StateError before a load or after close()."""
        if callback is None:
            self._call(lib.structmd_set_device_force_callback, None, None)
            self._callbacks.pop("device", None)
            return
        device_type, device_id = self.view("positions").device
        ordinal = device_id if device_type == K_DL_CUDA else -1

        def trampoline(positions: Optional[int], forces: Optional[int], n: int, real_size: int,
                       energy: CPointer[c_double], virial: CPointer[c_double], step: int,
                       stream: Optional[int], _user_data: Optional[int]) -> int:
            try:
                result = callback(DLPackView(make_tensor(positions, n, real_size, ordinal)),
                                  DLPackView(make_tensor(forces, n, real_size, ordinal)), step, stream or 0)
                self._add_energy_and_virial(result, energy, virial)
                return 0
            except BaseException as error:  # noqa: B902 - nothing may cross back into C
                return self._report_callback_failure(error)

        function = DEVICE_FORCE_CALLBACK_T(trampoline)
        self._call(lib.structmd_set_device_force_callback, ctypes_address(function), None)
        self._callbacks["device"] = function

    def view(self, quantity: ViewQuantity) -> DLPackView:
        """The engine's "positions", "velocities" or "forces" as a DLPackView (structmd_get_view):
        no copy; valid until the next call that steps or sets anything. After close(), reading it
        raises StateError; an array made from it before must not be used then. Raises
        ArgumentError for another quantity, StateError before a load."""
        address = c_void_p()
        self._call(lib.structmd_get_view, quantity.encode(), byref(address))
        assert address.value is not None  # structmd_get_view succeeds only with a view
        return DLPackView(address.value, owner=self)

    def positions_view(self) -> DLPackView:
        """view("positions"): the engine's positions, in input lengths, without a copy."""
        return self.view("positions")

    def velocities_view(self) -> DLPackView:
        """view("velocities"): the engine's velocities, in input units, without a copy."""
        return self.view("velocities")

    def forces_view(self) -> DLPackView:
        """view("forces"): the engine's forces, in input units, without a copy."""
        return self.view("forces")

    # ---- loading and advancing ---------------------------------------------------------------

    def load_file(self: _Self, path: PathLike) -> _Self:
        """Builds the simulation from an input file (UAMMD-structured JSON). Returns self. Raises
        StructmdIOError when the file cannot be read, InputError (naming the JSON path) for a wrong
        input."""
        self._call(lib.structmd_load_file, os.fsencode(path))
        self._external_forces = None
        return self

    def load_string(self: _Self, document: str) -> _Self:
        """Builds the simulation from a JSON document given as a string. Returns self. Raises
        InputError (naming the JSON path) for a wrong input."""
        self._call(lib.structmd_load_string, document.encode())
        self._external_forces = None
        return self

    def load(self: _Self, source: InputSource) -> _Self:
        """Loads from a dict, a JSON document string, or a file path (str or path-like). Returns self.

        A string whose first non-blank characters are "{", "//" or "/*" is a document; any other
        string is a path. A load that raises keeps the simulation loaded before, if any, as it was.
        Raises TypeError for another type, else as load_file and load_string.
        """
        if isinstance(source, Mapping):
            return self.load_string(json.dumps(source))
        if isinstance(source, str) and _looks_like_json(source):
            return self.load_string(source)
        if isinstance(source, (str, bytes, os.PathLike)):
            return self.load_file(source)
        raise TypeError(f"cannot load from a {type(source).__name__}: give a dict, a JSON string or a path")

    def step(self, n: SupportsIndex = 1) -> None:
        """Advances n integration steps along the integrator schedule (past its end, its last
        integrator goes on); a flow-control step of the input may end the call early (info's
        "stopped_by" names it). When it returns, the outputs due up to the step reached (that step
        included) are written and flushed, so a loop may stop anywhere. Raises TypeError for a
        non-integer n, ArgumentError for n < 0, StateError before a load, NumericalError (state
        restored to the call's start) for a blow-up."""
        self._call(lib.structmd_step, operator.index(n))

    def run(self, steps: Optional[SupportsIndex] = None, progress: bool = False) -> None:
        """Advances until the integrator schedule ends (steps None), or by `steps` steps (as step(steps)),
        stopping early where a flow-control step ends the run. With progress=True a progress bar on
        stderr shows the steps done of the total, steps per second and the remaining time; the steps
        are then taken in chunks of about 0.2 s each (at most 1% of the run while the speed is being
        measured), which ends in the same step and state. Raises as step()."""
        if not progress:
            if steps is None:
                self._call(lib.structmd_run)
            else:
                self.step(steps)
            return
        if steps is None:
            info = self.info
            if not info["loaded"]:
                self._call(lib.structmd_run)  # raises the library's StateError
            total = max(0, int(info["final_step"]) - self.step_number)
        else:
            total = operator.index(steps)
            if total < 0:
                self.step(total)  # raises the library's ArgumentError
        self._run_with_progress(total, sys.stderr)

    def _run_with_progress(self, total: int, stream: TextIO) -> None:
        """Takes total steps in chunks, redrawing a progress bar on stream after each."""
        bar = _ProgressBar(total, stream)
        done = 0
        chunk = max(1, min(total // 100, 10))
        started = _time.perf_counter()
        try:
            bar.draw(done, 0.0)
            while done < total:
                chunk = min(chunk, total - done)
                before = _time.perf_counter()
                start_step = self.step_number
                self.step(chunk)
                taken = self.step_number - start_step
                elapsed = _time.perf_counter() - before
                done += taken
                bar.draw(done, _time.perf_counter() - started)
                if taken < chunk:
                    break  # a flow-control step ended the run
                # The next chunk takes about _PROGRESS_INTERVAL seconds, growing at most tenfold at once.
                rate = chunk / elapsed if elapsed > 0.0 else math.inf
                chunk = max(1, min(10 * chunk, int(rate * _PROGRESS_INTERVAL) if math.isfinite(rate) else 10 * chunk))
        finally:
            bar.close()

    def save_checkpoint(self, path: PathLike) -> None:
        """Writes the dynamic state (step, time, box, positions, velocities, ...) to a file, atomically.
        Raises StateError before a load, StructmdIOError when the file cannot be written."""
        self._call(lib.structmd_save_checkpoint, os.fsencode(path))

    def load_checkpoint(self, path: PathLike) -> None:
        """Restores a checkpoint of a simulation loaded from the same input; on failure nothing changes.
        Raises StructmdIOError for an unreadable file, InputError for one of another input."""
        self._call(lib.structmd_load_checkpoint, os.fsencode(path))

    def compute(self, forces: bool = True, energy: bool = False, virial: bool = False) -> None:
        """Evaluates now what is asked for (unless already current), without advancing time; read the
        results through forces, energy() and virial. Raises StateError before a load."""
        flags = ((COMPUTE_FLAGS["STRUCTMD_FORCES"] if forces else 0)
                 | (COMPUTE_FLAGS["STRUCTMD_ENERGY"] if energy else 0)
                 | (COMPUTE_FLAGS["STRUCTMD_VIRIAL"] if virial else 0))
        self._call(lib.structmd_compute, flags)

    # ---- particle data -----------------------------------------------------------------------

    @property
    def num_particles(self) -> int:
        """The number of particles n (0 before a load). Raises StateError after close()."""
        n = c_int64()
        self._call(lib.structmd_get_num_particles, byref(n))
        return n.value

    def _get_array(self, function: Callable[..., int], ctype: Any, numpy_dtype: str,
                   components: int) -> NDArray[Any]:
        n = self.num_particles
        if _np is not None:
            shape = (n, components) if components > 1 else (n,)
            out = _np.empty(shape, dtype=numpy_dtype)
            self._call(function, out.ctypes.data_as(POINTER(ctype)), n)
            return out
        buffer = (ctype * (components * n))()
        self._call(function, buffer, n)
        if components == 1:
            return list(buffer)
        return [tuple(buffer[components * i:components * (i + 1)]) for i in range(n)]

    def _vectors_argument(self, values: ArrayLike, name: str, components: int = 3) -> Tuple[FloatArray, int]:
        """(a C double[components n] the library can read, n), checking the shape against the particle
        count."""
        n = self.num_particles
        k = components
        if _np is not None:
            array = _np.ascontiguousarray(values, dtype=_np.float64)
            if array.shape not in ((n, k), (k * n,)):
                raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                                    f"{name}: expected shape ({n}, {k}) or ({k * n},), got {array.shape}")
            return array, n
        rows = [tuple(row) for row in values]
        flat = [float(component) for row in rows for component in row]
        if len(rows) != n or any(len(row) != k for row in rows):
            raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                                f"{name}: expected {n} rows of {k} values")
        return (c_double * (k * n))(*flat), n

    def _set_vectors(self, function: Callable[..., int], values: ArrayLike, name: str,
                     components: int = 3) -> FloatArray:
        buffer, n = self._vectors_argument(values, name, components)
        pointer = buffer.ctypes.data_as(POINTER(c_double)) if _np is not None else buffer
        self._call(function, pointer, n)
        return buffer

    @property
    def ids(self) -> NDArray[_np.int64]:
        """Particle ids, ascending (0..n-1), shape (n,). Raises StateError before a load."""
        return self._get_array(lib.structmd_get_ids, c_int64, "int64", 1)

    @property
    def positions(self) -> FloatArray:
        """Positions (input lengths), shape (n, 3), wrapped into the box [-L/2, L/2); setting them
        ((n, 3) or (3n,)) wraps them too. Raises ArgumentError for another shape, StateError before a load."""
        return self._get_array(lib.structmd_get_positions, c_double, "float64", 3)

    @positions.setter
    def positions(self, values: ArrayLike) -> None:
        self._set_vectors(lib.structmd_set_positions, values, "positions")

    @property
    def velocities(self) -> FloatArray:
        """Velocities (input lengths per input time), shape (n, 3); settable as positions. Raises
        ArgumentError for another shape, StateError before a load."""
        return self._get_array(lib.structmd_get_velocities, c_double, "float64", 3)

    @velocities.setter
    def velocities(self, values: ArrayLike) -> None:
        self._set_vectors(lib.structmd_set_velocities, values, "velocities")

    @property
    def orientations(self) -> FloatArray:
        """Unit quaternions [q0, q1, q2, q3] (scalar first), shape (n, 4); the identity for a simulation
        without orientations. Setting them checks each is of unit norm (ArgumentError otherwise)."""
        return self._get_array(lib.structmd_get_orientations, c_double, "float64", 4)

    @orientations.setter
    def orientations(self, values: ArrayLike) -> None:
        self._set_vectors(lib.structmd_set_orientations, values, "orientations", 4)

    @property
    def torques(self) -> FloatArray:
        """The torque on each particle (lab frame, input energy units), shape (n, 3); kept with the
        forces from the first read on. Raises StateError before a load."""
        return self._get_array(lib.structmd_get_torques, c_double, "float64", 3)

    @property
    def magnetic_moments(self) -> FloatArray:
        """The magnetic moment of each particle (lab frame, input units), shape (n, 3); zeros without
        a magnetization. Raises StateError before a load."""
        return self._get_array(lib.structmd_get_magnetic_moments, c_double, "float64", 3)

    @property
    def forces(self) -> FloatArray:
        """The total force on each particle (input energy per input length), shape (n, 3), external
        forces included. Raises StateError before a load."""
        return self._get_array(lib.structmd_get_forces, c_double, "float64", 3)

    @property
    def external_forces(self) -> Optional[FloatArray]:
        """The external force field last set since the last load (a copy, (n, 3), input force units),
        or None when there is none.

        Setting it ((n, 3) or (3n,)) adds that force to each particle at every force evaluation; None
        clears it. Setting raises ArgumentError for another shape, StateError before a load.
        """
        if self._external_forces is None:
            return None
        if _np is not None:
            return self._external_forces.reshape(-1, 3).copy()
        values = list(self._external_forces)
        return [tuple(values[3 * i:3 * i + 3]) for i in range(len(values) // 3)]

    @external_forces.setter
    def external_forces(self, values: Optional[ArrayLike]) -> None:
        if values is None:
            self._call(lib.structmd_set_external_forces, None, 0)
            self._external_forces = None
            return
        buffer = self._set_vectors(lib.structmd_set_external_forces, values, "external_forces")
        self._external_forces = buffer.copy() if _np is not None else buffer

    def set_external_energy(self, energy: float) -> None:
        """Gives the energy of the host's external field: the energy term "external", part of
        "total" and of the thermodynamic outputs, in input energy units. Cleared with the external
        forces and by a load. Raises StateError before a load."""
        self._call(lib.structmd_set_external_energy, float(energy))

    # ---- run-time parameters -----------------------------------------------------------------

    def set_parameter(self, path: str, value: float) -> None:
        """Changes a parameter from the next force evaluation on. path: "global.ensemble.temperature",
        "integrator.<name>.parameters.<key>" or "topology.forceField.<name>.parameters.<key>"; value in
        the input's units. Raises ArgumentError for a path that names no settable parameter."""
        self._call(lib.structmd_set_parameter, path.encode(), float(value))

    def get_parameter(self, path: str) -> float:
        """A parameter (paths as set_parameter) as the input gives it, or as set_parameter last set it,
        in the input's units. Raises ArgumentError for a path that names no such parameter."""
        value = c_double()
        self._call(lib.structmd_get_parameter, path.encode(), byref(value))
        return value.value

    # ---- subsets by id -----------------------------------------------------------------------
    # Only the m particles named move between the host and the backend. ids: a sequence of distinct
    # particle ids (any order); values come back, and are given, as (m, 3) in the order of ids.

    def _ids_argument(self, ids: ArrayLike) -> Tuple[Any, int, NDArray[_np.int64]]:
        """(a C int64_t[m], m, the ids as a list or array)."""
        if _np is not None:
            array = _np.ascontiguousarray(ids, dtype=_np.int64).reshape(-1)
            return array.ctypes.data_as(POINTER(c_int64)), array.size, array
        values = [operator.index(i) for i in ids]
        return (c_int64 * max(1, len(values)))(*values), len(values), values

    def _get_subset(self, function: Callable[..., int], ids: ArrayLike) -> FloatArray:
        pointer, m, _ = self._ids_argument(ids)
        if _np is not None:
            out = _np.empty((m, 3), dtype=_np.float64)
            self._call(function, pointer, m, out.ctypes.data_as(POINTER(c_double)))
            return out
        buffer = (c_double * max(1, 3 * m))()
        self._call(function, pointer, m, buffer)
        return [tuple(buffer[3 * k:3 * k + 3]) for k in range(m)]

    def _set_subset(self, function: Callable[..., int], ids: ArrayLike, values: ArrayLike,
                    name: str) -> Tuple[NDArray[_np.int64], FloatArray]:
        pointer, m, id_values = self._ids_argument(ids)
        if _np is not None:
            array = _np.ascontiguousarray(values, dtype=_np.float64)
            if array.shape not in ((m, 3), (3 * m,)):
                raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                                    f"{name}: expected shape ({m}, 3) or ({3 * m},) for {m} ids, got {array.shape}")
            self._call(function, pointer, m, array.ctypes.data_as(POINTER(c_double)))
            return id_values, array.reshape(m, 3)
        rows = [tuple(float(c) for c in row) for row in values]
        if len(rows) != m or any(len(row) != 3 for row in rows):
            raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"], f"{name}: expected {m} rows of 3 values")
        self._call(function, pointer, m, (c_double * max(1, 3 * m))(*[c for row in rows for c in row]))
        return id_values, rows

    def positions_of(self, ids: ArrayLike) -> FloatArray:
        """Positions (input lengths, wrapped into the box) of the particles ids, shape (m, 3) in the
        order of ids. Raises ArgumentError for an unknown or repeated id."""
        return self._get_subset(lib.structmd_get_positions_of, ids)

    def velocities_of(self, ids: ArrayLike) -> FloatArray:
        """Velocities (input units) of the particles ids, shape (m, 3) in the order of ids. Raises
        ArgumentError for an unknown or repeated id."""
        return self._get_subset(lib.structmd_get_velocities_of, ids)

    def forces_of(self, ids: ArrayLike) -> FloatArray:
        """The total force (input units) on each of the particles ids, external forces included,
        shape (m, 3) in the order of ids. Raises ArgumentError for an unknown or repeated id."""
        return self._get_subset(lib.structmd_get_forces_of, ids)

    def set_positions_of(self, ids: ArrayLike, values: ArrayLike) -> None:
        """Sets the positions (input lengths, (m, 3) in the order of ids) of the particles ids as the
        positions setter does for all. Raises ArgumentError for a wrong shape or an unknown or repeated id."""
        self._set_subset(lib.structmd_set_positions_of, ids, values, "positions")

    def set_velocities_of(self, ids: ArrayLike, values: ArrayLike) -> None:
        """Sets the velocities (input units, (m, 3) in the order of ids) of the particles ids. Raises
        ArgumentError for a wrong shape or an unknown or repeated id."""
        self._set_subset(lib.structmd_set_velocities_of, ids, values, "velocities")

    def set_external_forces_of(self, ids: ArrayLike, values: ArrayLike) -> None:
        """Sets the external force (input units, (m, 3) in the order of ids) of the particles ids; the
        others keep theirs (zero without a field). Raises ArgumentError for a wrong shape or an
        unknown or repeated id."""
        id_values, rows = self._set_subset(lib.structmd_set_external_forces_of, ids, values, "external_forces")
        if len(id_values) == 0:
            return
        n = self.num_particles
        if _np is not None:
            field = _np.zeros(3 * n) if self._external_forces is None else self._external_forces
            field = field.reshape(n, 3)
            field[_np.asarray(id_values)] = rows
            self._external_forces = field.reshape(-1)
        else:
            field = [0.0] * (3 * n) if self._external_forces is None else list(self._external_forces)
            for i, row in zip(id_values, rows):
                field[3 * i:3 * i + 3] = row
            self._external_forces = field

    # ---- per-particle scalars ----------------------------------------------------------------

    @property
    def particle_energies(self) -> FloatArray:
        """Potential energy per particle (input energy units), shape (n,); the values sum to the
        potential energy. Raises StateError before a load."""
        return self._get_array(lib.structmd_get_particle_energies, c_double, "float64", 1)

    @property
    def masses(self) -> FloatArray:
        """Each particle's mass (input mass units), shape (n,). Raises StateError before a load."""
        return self._get_array(lib.structmd_get_masses, c_double, "float64", 1)

    @property
    def types(self) -> NDArray[_np.int32]:
        """Each particle's row in global.types (0-based), shape (n,). Raises StateError before a load."""
        return self._get_array(lib.structmd_get_types, c_int32, "int32", 1)

    def traverse_expression(self, compute: str, cutoff: float = 0.0) -> FloatArray:
        """Each particle's sum over its pairs of the expression compute (of r, dx, dy, dz, type_i,
        type_j, charge_i, charge_j, radius_i, radius_j, mass_i, mass_j; "r < 1.5" counts neighbours),
        shape (n,), id order: over the pairs closer than cutoff (a neighbour list), or every pair for
        cutoff 0. Raises InputError for a bad expression or cutoff, StateError before a load."""
        def call(handle: c_void_p, pointer: Any, n: int) -> int:
            return int(lib.structmd_traverse_expression(handle, compute.encode(), c_double(cutoff), pointer, n))
        return self._get_array(call, c_double, "float64", 1)

    def transverser_values(self, name: str) -> int:
        """How many numbers per particle the transverser name (registered by a loaded plugin) writes.
        Raises ArgumentError for a name no plugin of this handle registered."""
        values = c_int()
        self._call(lib.structmd_transverser_values, name.encode(), byref(values))
        return values.value

    def traverse(self, name: str, cutoff: float = 0.0,
                 parameters: Optional[Mapping[str, Any]] = None) -> FloatArray:
        """Runs the transverser name, registered by a loaded plugin (docs/plugins.md), once over the
        pairs closer than cutoff (a neighbour list), or every pair for cutoff 0: shape (n,) for one
        value per particle, else (n, values), id order. parameters: its named parameters and,
        optionally, "group" (a force-field group; the other particles get 0). Raises ArgumentError
        for an unknown name, InputError for a bad parameter or cutoff, StateError before a load."""
        values = self.transverser_values(name)
        text = json.dumps(dict(parameters)).encode() if parameters else None
        def call(handle: c_void_p, pointer: Any, n: int) -> int:
            return int(lib.structmd_traverse(handle, name.encode(), text, c_double(cutoff), pointer, values * n))
        return self._get_array(call, c_double, "float64", values)

    def traverse_view(self, name: str, cutoff: float = 0.0,
                      parameters: Optional[Mapping[str, Any]] = None) -> DLPackView:
        """Runs the transverser name as traverse does, and gives its values where the engine computed
        them as a DLPackView (structmd_traverse_view): on CUDA they stay on the GPU
        (cupy.from_dlpack / torch.from_dlpack), on the CPU backend numpy.from_dlpack or view.numpy()
        read them without a copy. Shape (n,) for one value per particle, else (n, values); float64,
        or float32 in single precision. Valid until the next call that runs a registered transverser,
        steps or sets anything. Raises as traverse does."""
        text = json.dumps(dict(parameters)).encode() if parameters else None
        address = c_void_p()
        self._call(lib.structmd_traverse_view, name.encode(), text, c_double(cutoff), byref(address))
        assert address.value is not None  # structmd_traverse_view succeeds only with a view
        return DLPackView(address.value, owner=self)

    # ---- global quantities -------------------------------------------------------------------

    def energy(self, term: str = "potential") -> float:
        """The energy (input energy units) of term: "potential", "kinetic", "total", "external" (the
        host's, see set_external_energy), or a topology.forceField entry's name (its share). Raises
        ArgumentError for an unknown term, StateError before a load."""
        value = c_double()
        self._call(lib.structmd_get_energy, term.encode(), byref(value))
        return value.value

    @property
    def virial(self) -> FloatArray:
        """The virial tensor W (3x3, input energy units, LAMMPS's pressure-virial convention). Raises
        StateError before a load."""
        w = (c_double * 9)()
        self._call(lib.structmd_get_virial, w)
        if _np is not None:
            return _np.array(w[:], dtype=_np.float64).reshape(3, 3)
        return [tuple(w[3 * row:3 * row + 3]) for row in range(3)]

    @property
    def pressure(self) -> float:
        """The pressure (input energy per input volume), from the kinetic energy and the virial.
        Raises StateError before a load."""
        p = c_double()
        self._call(lib.structmd_get_pressure, byref(p))
        return p.value

    @property
    def temperature(self) -> float:
        """T = 2K / (3 N k_B) over the particles of mass > 0 (input temperature units); under Brownian
        dynamics the bath's. Raises StateError before a load."""
        t = c_double()
        self._call(lib.structmd_get_temperature, byref(t))
        return t.value

    @property
    def box(self) -> FloatArray:
        """Box edge lengths (Lx, Ly, Lz) in input lengths, shape (3,); setting them scales the
        particles with the box. Setting raises ArgumentError for other than three lengths."""
        lengths = (c_double * 3)()
        self._call(lib.structmd_get_box, lengths)
        return _np.array(lengths[:], dtype=_np.float64) if _np is not None else tuple(lengths)

    @box.setter
    def box(self, lengths: Iterable[float]) -> None:
        values = [float(length) for length in lengths]
        if len(values) != 3:
            raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"], f"box: expected 3 lengths, got {len(values)}")
        self._call(lib.structmd_set_box, (c_double * 3)(*values))

    @property
    def step_number(self) -> int:
        """The number of steps taken since the load (or as a checkpoint restored). Raises StateError
        before a load."""
        step = c_int64()
        self._call(lib.structmd_get_step, byref(step))
        return step.value

    @property
    def time(self) -> float:
        """The simulated time (input time units). Raises StateError before a load."""
        t = c_double()
        self._call(lib.structmd_get_time, byref(t))
        return t.value

    @property
    def counters(self) -> Dict[str, Any]:
        """A dict of what the engine did since the load: force, energy and virial evaluations,
        neighbour-list builds, and bytes copied to and from the backend's buffers. Raises StateError
        after close()."""
        buffer = create_string_buffer(_COUNTERS_SIZE)
        self._call(lib.structmd_get_counters, buffer, _COUNTERS_SIZE)
        counters: Dict[str, Any] = json.loads(buffer.value.decode("utf-8"))
        return counters

    @property
    def info(self) -> Dict[str, Any]:
        """A dict describing the handle: backend, precision, precisions_compiled (those the build
        has), device, threads, loaded, particles, final_step, stopped_by, mpi (compiled, ranks, rank,
        node_rank, nccl). Raises StateError after close()."""
        size = _INFO_FIRST_GUESS
        while True:
            buffer = create_string_buffer(size)
            needed = c_size_t()
            handle = self._checked_handle()
            status = lib.structmd_get_info(handle, buffer, size, byref(needed))
            if status == STATUS["STRUCTMD_OK"]:
                info: Dict[str, Any] = json.loads(buffer.value.decode("utf-8"))
                return info
            if needed.value <= size:
                _raise_for(status, _decode(lib.structmd_last_error(handle)))
            size = needed.value
