"""Reads include/structmd.h at test time: its #define constants and its function declarations.

The declarations come from the C preprocessor (`cc -E -P -DSTRUCTMD_API=`) run against empty stand-ins
for <stddef.h> and <stdint.h>, so that only the header's own declarations remain: cffi's cdef accepts
them as they are (it knows size_t, int32_t, ...), and the binding test compares them with ctypes.
"""

import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
HEADER = Path(os.environ.get("STRUCTMD_HEADER", REPO_ROOT / "include" / "structmd.h"))

_DEFINE = re.compile(r"^\s*#\s*define\s+(STRUCTMD_\w+)\s+(\d+)[uU]?\b", re.MULTILINE)
_FUNCTION = re.compile(r"([^;{}]*?)\b(structmd_\w+)\s*\(([^)]*)\)\s*;")


def header_text():
    return HEADER.read_text()


def header_defines():
    """{name: value} of every integer #define of the header (ABI version, statuses, flags)."""
    return {name: int(value) for name, value in _DEFINE.findall(header_text())}


def c_compiler():
    compiler = os.environ.get("CC") or shutil.which("cc")
    if not compiler:
        raise RuntimeError("no C compiler to preprocess structmd.h: set CC")
    return compiler


def preprocessed_declarations():
    """The header's declarations, preprocessed, without any system header's content."""
    with tempfile.TemporaryDirectory() as stand_ins:
        for name in ("stddef.h", "stdint.h"):
            Path(stand_ins, name).write_text("")
        result = subprocess.run(
            [c_compiler(), "-E", "-P", "-nostdinc", "-I", stand_ins, "-DSTRUCTMD_API=", str(HEADER)],
            capture_output=True, text=True, check=True)
    return result.stdout


def _strip_name(parameter):
    """'const double lengths[3]' -> ('double*', 'lengths'); 'void' -> None."""
    parameter = " ".join(parameter.replace("const ", " ").split())
    if parameter in ("", "void"):
        return None
    is_array = parameter.endswith("]")
    parameter = re.sub(r"\[[^\]]*\]$", "", parameter)
    match = re.match(r"^(.*?[\s*])(\w+)$", parameter)
    c_type, name = match.group(1), match.group(2)
    c_type = c_type.replace(" ", "") + ("*" if is_array else "")
    return c_type, name


def function_prototypes():
    """{function name: (return type, [(parameter type, parameter name), ...])}, const dropped and
    arrays written as pointers, e.g. 'structmd_get_box': ('structmd_status', [('structmd_sim*', 'sim'),
    ('double*', 'lengths')])."""
    prototypes = {}
    for return_part, name, parameters in _FUNCTION.findall(preprocessed_declarations()):
        return_type = "".join(return_part.replace("const ", " ").split())
        parsed = [_strip_name(p) for p in parameters.split(",")]
        prototypes[name] = (return_type, [p for p in parsed if p is not None])
    return prototypes
