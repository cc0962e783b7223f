"""One exception class per structmd status code, all derived from StructmdError."""

from typing import Optional

from .constants import STATUS

_STATUS_NAMES = {value: name for name, value in STATUS.items()}


class StructmdError(Exception):
    """A structmd call failed. `status` is the C status code, `message` the library's explanation."""

    status_name: Optional[str] = None

    def __init__(self, status: int, message: str) -> None:
        # Both values go to Exception so that the exception pickles and copies faithfully.
        super().__init__(status, message)
        self.status = status
        self.message = message

    def __str__(self) -> str:
        name = _STATUS_NAMES.get(self.status, f"status {self.status}")
        return f"{self.message} [{name}]" if self.message else name


class ArgumentError(StructmdError):
    """Null pointer, wrong array length, unknown name or bad option."""

    status_name = "STRUCTMD_ERR_ARGUMENT"


class InputError(StructmdError):
    """The JSON input is malformed or inconsistent; the message names the JSON path."""

    status_name = "STRUCTMD_ERR_INPUT"


class StateError(StructmdError):
    """The call is not valid now, for example stepping before a load or after close()."""

    status_name = "STRUCTMD_ERR_STATE"


class NumericalError(StructmdError):
    """NaN, Inf or a blow-up was detected; the message names the particle id and the step."""

    status_name = "STRUCTMD_ERR_NUMERICAL"


class StructmdIOError(StructmdError):
    """A file could not be read or written."""

    status_name = "STRUCTMD_ERR_IO"


class DeviceError(StructmdError):
    """A GPU error, or a GPU was demanded and none is usable."""

    status_name = "STRUCTMD_ERR_DEVICE"


class StructmdMemoryError(StructmdError):
    """Out of host or device memory."""

    status_name = "STRUCTMD_ERR_MEMORY"


class UnsupportedError(StructmdError):
    """A valid request that this build or backend cannot do."""

    status_name = "STRUCTMD_ERR_UNSUPPORTED"


class InternalError(StructmdError):
    """A bug in structmd: please report it with the message."""

    status_name = "STRUCTMD_ERR_INTERNAL"


class CallbackError(StructmdError):
    """A force callback of the host failed; the message carries its own (or its exception's) words."""

    status_name = "STRUCTMD_ERR_CALLBACK"


ERROR_CLASSES = {
    STATUS[cls.status_name]: cls
    for cls in (ArgumentError, InputError, StateError, NumericalError, StructmdIOError, DeviceError,
                StructmdMemoryError, UnsupportedError, InternalError, CallbackError)
}


def error_for_status(status: int, message: str) -> StructmdError:
    """The exception (returned, not raised) for a failed call; an unknown status (a newer library)
    gives StructmdError."""
    return ERROR_CLASSES.get(status, StructmdError)(status, message)
