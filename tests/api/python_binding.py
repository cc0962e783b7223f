"""Compares the signature table of the ctypes package (bindings/python/structmd/_library.py,
SIGNATURES: {name: (restype, argtypes)}) with include/structmd.h, type by type.

Each C type has exactly one ctypes type here; the table must use it for every parameter and result.
problems() returns one line per mismatch, naming the function and what differs.
"""

import ctypes

from structmd_header import CALLBACK_TYPES

CTYPES_OF_C_VALUE = {
    "int": ctypes.c_int,
    "int32_t": ctypes.c_int32,
    "structmd_status": ctypes.c_int32,
    "uint32_t": ctypes.c_uint32,
    "int64_t": ctypes.c_int64,
    "size_t": ctypes.c_size_t,
    "double": ctypes.c_double,
}


def expected_ctype(c_type):
    """The ctypes type that passes or returns a C type: None for void, c_char_p for char*, c_void_p
    for the opaque handle and a DLPack tensor, c_void_p for a callback (its address), POINTER(T) for any
    other pointer or array parameter."""
    if c_type.pointers == 0:
        if c_type.base in CALLBACK_TYPES:
            return ctypes.c_void_p  # the function's address, so that None clears a callback
        return None if c_type.base == "void" else CTYPES_OF_C_VALUE[c_type.base]
    # A pointer to one of these is itself a ctypes type; deeper pointers wrap it in POINTER.
    pointer_to = {"char": ctypes.c_char_p, "structmd_sim": ctypes.c_void_p, "void": ctypes.c_void_p,
                  "structmd_dlpack_tensor": ctypes.c_void_p}
    if c_type.base in pointer_to:
        result, depth = pointer_to[c_type.base], c_type.pointers - 1
    else:
        result, depth = CTYPES_OF_C_VALUE[c_type.base], c_type.pointers
    for _ in range(depth):
        result = ctypes.POINTER(result)
    return result


def ctype_name(t):
    """'c_int64', 'POINTER(c_double)', 'None': the spelling of the table's source, not ctypes' aliases
    (c_int64 is c_long on LP64 systems)."""
    if t is None:
        return "None"
    if isinstance(t, type) and issubclass(t, ctypes._Pointer):
        return f"POINTER({ctype_name(t._type_)})"
    for name in ("c_int32", "c_uint32", "c_int64", "c_size_t", "c_double", "c_char_p", "c_void_p"):
        if t is getattr(ctypes, name):
            return name
    return getattr(t, "__name__", repr(t))


def problems(header_functions, signatures):
    """One line per difference between the header's prototypes and the ctypes table."""
    found = []
    for name, function in header_functions.items():
        if name not in signatures:
            found.append(f"{name}: missing from the signature table")
            continue
        restype, argtypes = signatures[name]
        wanted = expected_ctype(function.returns)
        if restype is not wanted:
            found.append(f"{name}: result: C returns {function.returns}: expected {ctype_name(wanted)}, "
                         f"the table says {ctype_name(restype)}")
        if len(argtypes) != len(function.parameters):
            found.append(f"{name}: {len(function.parameters)} parameters in C, {len(argtypes)} in the table")
            continue
        for position, (parameter, given) in enumerate(zip(function.parameters, argtypes), 1):
            wanted = expected_ctype(parameter.type)
            if given is not wanted:
                found.append(f"{name}: argument {position} ({parameter.type.declare(parameter.name)}): "
                             f"expected {ctype_name(wanted)}, the table says {ctype_name(given)}")
    for name in sorted(set(signatures) - set(header_functions)):
        found.append(f"{name}: in the signature table but not declared in the header")
    return found
