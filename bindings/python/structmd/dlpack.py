"""DLPack tensors over memory that structmd owns, for numpy, CuPy, PyTorch or JAX to read without a copy.

DLPackView wraps a DLManagedTensor (the library's from structmd_get_view, or one made here for the
arrays a device force callback receives) and speaks the Python DLPack protocol: __dlpack__ returns a
"dltensor" capsule, __dlpack_device__ the device. Consumers call `numpy.from_dlpack(view)`,
`cupy.from_dlpack(view)` or `torch.from_dlpack(view)`.
"""

import ctypes
from ctypes import CFUNCTYPE, POINTER, Structure, c_char_p, c_int, c_int32, c_int64, c_uint8, c_uint16, c_uint64, c_void_p

from .constants import STATUS
from .errors import StateError

K_DL_CPU = 1
K_DL_CUDA = 2
K_DL_FLOAT = 2
_CAPSULE_NAME = b"dltensor"


class DLDevice(Structure):
    _fields_ = [("device_type", c_int32), ("device_id", c_int32)]


class DLDataType(Structure):
    _fields_ = [("code", c_uint8), ("bits", c_uint8), ("lanes", c_uint16)]


class DLTensor(Structure):
    _fields_ = [("data", c_void_p), ("device", DLDevice), ("ndim", c_int32), ("dtype", DLDataType),
                ("shape", POINTER(c_int64)), ("strides", POINTER(c_int64)), ("byte_offset", c_uint64)]


class DLManagedTensor(Structure):
    pass


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


@CFUNCTYPE(None, c_void_p)
def _capsule_destructor(capsule):
    # A consumer renames the capsule to "used_dltensor" and owns the tensor from then on; a capsule
    # nobody consumed still owns it and releases it here.
    if _capsule_is_valid(capsule, _CAPSULE_NAME):
        managed = DLManagedTensor.from_address(_capsule_pointer(capsule, _CAPSULE_NAME))
        if managed.deleter:
            managed.deleter(ctypes.addressof(managed))


# Tensors made in Python stay alive, with their shape and strides, until their deleter runs.
_made_here = {}


@_DELETER_T
def _release_made_here(address):
    _made_here.pop(address, None)


def make_tensor(data, n, real_size, device):
    """A DLManagedTensor of shape (n, 3) and strides (4, 1) over records of four reals at data (an
    address) on device (-1: host memory), released by its own deleter."""
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
    """One DLManagedTensor, handed to the first consumer that asks (the DLPack protocol allows one)."""

    def __init__(self, address, stream=None, owner=None):
        self._address = address
        self._stream = stream  # the producer's CUDA stream, for information: the data are ready already
        # The Simulation whose engine holds the data: once it is closed they are freed, and reading
        # them would read whatever the memory holds next.
        self._owner = owner
        tensor = DLManagedTensor.from_address(address).dl_tensor
        self.shape = (tensor.shape[0], tensor.shape[1])
        self.device = (tensor.device.device_type, tensor.device.device_id)
        self.bits = tensor.dtype.bits
        self.data_pointer = tensor.data or 0

    def numpy(self):
        """A writable numpy array (n, 3) over the same host memory (kDLCPU views only); numpy's own
        from_dlpack makes read-only arrays, which a device callback on the CPU backend cannot fill."""
        import numpy

        self._require_open_owner()
        if self.device[0] != K_DL_CPU:
            raise BufferError("only a view of host memory (the CPU backend) becomes a numpy array")
        real = ctypes.c_float if self.bits == 32 else ctypes.c_double
        records = numpy.ctypeslib.as_array((real * (4 * self.shape[0])).from_address(self.data_pointer))
        return records.reshape(self.shape[0], 4)[:, :3]

    def _require_open_owner(self):
        if self._owner is not None and self._owner.closed:
            raise StateError(STATUS["STRUCTMD_ERR_STATE"], "the Simulation of this view is closed: its memory is freed")

    def __dlpack_device__(self):
        return self.device

    def __dlpack__(self, *, stream=None, max_version=None, dl_device=None, copy=None):
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

    def __del__(self):
        # Never handed to a consumer: release it here.
        if getattr(self, "_address", None) is not None:
            managed = DLManagedTensor.from_address(self._address)
            if managed.deleter:
                managed.deleter(self._address)
