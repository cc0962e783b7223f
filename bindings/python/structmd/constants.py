"""The numeric constants of include/structmd.h, kept in this one table.

tests/python/test_binding.py checks that these equal the header's #defines, so a change to the header
that is not mirrored here fails the tests instead of silently drifting.
"""

from typing import Dict

ABI_VERSION = 4

STATUS = {
    "STRUCTMD_OK": 0,
    "STRUCTMD_ERR_ARGUMENT": 1,
    "STRUCTMD_ERR_INPUT": 2,
    "STRUCTMD_ERR_STATE": 3,
    "STRUCTMD_ERR_NUMERICAL": 4,
    "STRUCTMD_ERR_IO": 5,
    "STRUCTMD_ERR_DEVICE": 6,
    "STRUCTMD_ERR_MEMORY": 7,
    "STRUCTMD_ERR_UNSUPPORTED": 8,
    "STRUCTMD_ERR_INTERNAL": 9,
    "STRUCTMD_ERR_CALLBACK": 10,
}

COMPUTE_FLAGS = {
    "STRUCTMD_FORCES": 1,
    "STRUCTMD_ENERGY": 2,
    "STRUCTMD_VIRIAL": 4,
}


def header_defines() -> Dict[str, int]:
    """Every #define of structmd.h that this package mirrors, by its C name. Raises nothing."""
    return {"STRUCTMD_ABI_VERSION": ABI_VERSION, **STATUS, **COMPUTE_FLAGS}
