"""DLPack tensors over memory that structmd owns, for numpy, CuPy, PyTorch or JAX to read without a copy.

DLPackView wraps a DLManagedTensor (the library's from structmd_get_view or structmd_traverse_view, or
one made here for the arrays a device force callback receives) and speaks the Python DLPack protocol: __dlpack__ returns a
"dltensor" capsule, __dlpack_device__ the device. Consumers call `numpy.from_dlpack(view)`,
`cupy.from_dlpack(view)` or `torch.from_dlpack(view)`.
"""

from __future__ import annotations

import ctypes
from ctypes import CFUNCTYPE, POINTER, Structure, c_char_p, c_int, c_int32, c_int64, c_uint8, c_uint16, c_uint64, c_void_p

from typing import TYPE_CHECKING, Any, Dict, Optional, Tuple

from .constants import STATUS
from .errors import StateError

if TYPE_CHECKING:
    import numpy
    from numpy.typing import NDArray

    from .simulation import Simulation

K_DL_CPU = 1
K_DL_CUDA = 2
K_DL_FLOAT = 2
_CAPSULE_NAME = b"dltensor"


class DLDevice(Structure):
    """DLPack's DLDevice: device_type (K_DL_CPU, K_DL_CUDA) and device_id (the GPU's ordinal)."""

    _fields_ = [("device_type", c_int32), ("device_id", c_int32)]


class DLDataType(Structure):
    """DLPack's DLDataType: code (K_DL_FLOAT), bits per lane and lanes."""

    _fields_ = [("code", c_uint8), ("bits", c_uint8), ("lanes", c_uint16)]


class DLTensor(Structure):
    """DLPack's DLTensor: data, device, ndim, dtype, shape, strides (in elements) and byte_offset."""

    _fields_ = [("data", c_void_p), ("device", DLDevice), ("ndim", c_int32), ("dtype", DLDataType),
                ("shape", POINTER(c_int64)), ("strides", POINTER(c_int64)), ("byte_offset", c_uint64)]


class DLManagedTensor(Structure):
    """DLPack's DLManagedTensor: a DLTensor with the context and deleter that release it."""


_DELETER_T = CFUNCTYPE(None, c_void_p)
DLManagedTensor._fields_ = [("dl_tensor", DLTensor), ("manager_ctx", c_void_p), ("deleter", _DELETER_T)]

_capsule_new = ctypes.pythonapi.PyCapsule_New
_capsule_new.restype = ctypes.py_object
_capsule_new.argtypes = [c_void_p, c_char_p, c_void_p]
_capsule_is_valid = ctypes.pythonapi.PyCapsule_IsValid
_capsule_is_valid.restype = c_int
_capsule_is_valid.argtypes = [c_void_p, c_char_p]
_capsule_pointer = ctypes.pythonapi.PyCapsule_GetPointer
_capsule_pointer.restype = c_void_p
_capsule_pointer.argtypes = [c_void_p, c_char_p]


def _destroy_capsule(capsule: Optional[int]) -> None:
    # A consumer renames the capsule to "used_dltensor" and owns the tensor from then on; a capsule
    # nobody consumed still owns it and releases it here.
    if _capsule_is_valid(capsule, _CAPSULE_NAME):
        managed = DLManagedTensor.from_address(_capsule_pointer(capsule, _CAPSULE_NAME))
        if managed.deleter:
            managed.deleter(ctypes.addressof(managed))


_capsule_destructor = CFUNCTYPE(None, c_void_p)(_destroy_capsule)


# Tensors made in Python stay alive, with their shape and strides, until their deleter runs.
_made_here: Dict[int, Tuple[DLManagedTensor, Any, Any]] = {}


def _forget_made_here(address: Optional[int]) -> None:
    if address is not None:
        _made_here.pop(address, None)


_release_made_here = _DELETER_T(_forget_made_here)


def make_tensor(data: Optional[int], n: int, real_size: int, device: int) -> int:
    """The address of a DLManagedTensor of shape (n, 3) and strides (4, 1) over records of four reals
    (real_size bytes each) at data (an address) on device (-1: host memory, else the CUDA ordinal),
    released by its own deleter. Raises nothing."""
    shape = (c_int64 * 2)(n, 3)
    strides = (c_int64 * 2)(4, 1)
    managed = DLManagedTensor()
    tensor = managed.dl_tensor
    tensor.data = data
    tensor.device = DLDevice(K_DL_CPU, 0) if device < 0 else DLDevice(K_DL_CUDA, device)
    tensor.ndim = 2
    tensor.dtype = DLDataType(K_DL_FLOAT, 8 * real_size, 1)
    tensor.shape = shape
    tensor.strides = strides
    managed.deleter = _release_made_here
    _made_here[ctypes.addressof(managed)] = (managed, shape, strides)
    return ctypes.addressof(managed)


class DLPackView:
    """One DLManagedTensor, handed to the first consumer that asks (the DLPack protocol allows one).

    Attributes: shape ((n, 3) for the engine's arrays; (n,) or (n, values) for a transverser's values);
    strides, in elements; device (device_type, device_id) as __dlpack_device__ gives it; bits (32 or 64,
    the engine's precision); data_pointer, the address of the first element (0 for none).
    """

    def __init__(self, address: int, stream: Optional[int] = None, owner: Optional[Simulation] = None) -> None:
        self._address: Optional[int] = address
        self._stream = stream  # the producer's CUDA stream, for information: the data are ready already
        # The Simulation whose engine holds the data: once it is closed they are freed, and reading
        # them would read whatever the memory holds next.
        self._owner = owner
        tensor = DLManagedTensor.from_address(address).dl_tensor
        self.shape = tuple(tensor.shape[k] for k in range(tensor.ndim))
        self.strides = tuple(tensor.strides[k] for k in range(tensor.ndim))
        self.device = (tensor.device.device_type, tensor.device.device_id)
        self.bits = tensor.dtype.bits
        self.data_pointer = tensor.data or 0

    def numpy(self) -> NDArray[numpy.floating[Any]]:
        """A writable numpy array of the view's shape over the same host memory (kDLCPU views only);
        numpy's own from_dlpack makes read-only arrays, which a device callback on the CPU backend
        cannot fill. Raises BufferError for a view of GPU memory, StateError when its Simulation is
        closed."""
        import numpy

        self._require_open_owner()
        if self.device[0] != K_DL_CPU:
            raise BufferError("only a view of host memory (the CPU backend) becomes a numpy array")
        real = ctypes.c_float if self.bits == 32 else ctypes.c_double
        if not self.data_pointer or 0 in self.shape:
            return numpy.zeros(self.shape, dtype=real)
        # The elements the view spans, from its first to its last.
        span = 1 + sum((size - 1) * stride for size, stride in zip(self.shape, self.strides))
        elements = numpy.ctypeslib.as_array((real * span).from_address(self.data_pointer))
        return numpy.lib.stride_tricks.as_strided(
            elements, shape=self.shape, strides=tuple(ctypes.sizeof(real) * stride for stride in self.strides))

    def _require_open_owner(self) -> None:
        if self._owner is not None and self._owner.closed:
            raise StateError(STATUS["STRUCTMD_ERR_STATE"], "the Simulation of this view is closed: its memory is freed")

    def __dlpack_device__(self) -> Tuple[int, int]:
        """(device_type, device_id) of the data, as the DLPack protocol asks."""
        return self.device

    def __dlpack__(self, *, stream: Optional[int] = None, max_version: Optional[Tuple[int, int]] = None,
                   dl_device: Optional[Tuple[int, int]] = None, copy: Optional[bool] = None) -> object:
        """A "dltensor" capsule owning the tensor (the DLPack protocol; once only). Raises BufferError
        when consumed already, for copy=True or another dl_device; StateError when the Simulation is closed."""
        # The data are complete when the view is made, so any consumer stream may read them.
        if self._address is None:
            raise BufferError("this DLPack view was consumed already")
        self._require_open_owner()
        if copy:
            raise BufferError("a structmd view cannot be copied by its producer; copy the consumer's array")
        if dl_device is not None and tuple(dl_device) != self.device:
            raise BufferError(f"the view lives on device {self.device}, not {tuple(dl_device)}")
        address, self._address = self._address, None
        return _capsule_new(address, _CAPSULE_NAME, ctypes.cast(_capsule_destructor, c_void_p))

    def __del__(self) -> None:
        # Never handed to a consumer: release it here.
        address = getattr(self, "_address", None)
        if address is not None:
            managed = DLManagedTensor.from_address(address)
            if managed.deleter:
                managed.deleter(address)
