"""Reads include/structmd.h: its integer #define constants, its typedefs and its function prototypes.

The prototypes are parsed into types (base type, const, pointer depth, array extent) so that the
bindings and docs/c-api.md can be compared with the header type by type. Parsing is strict: a
declaration it does not understand raises HeaderError naming it, rather than being skipped.

cffi needs the declarations as C text: preprocessed_declarations() runs the C preprocessor
(`cc -E -P -DSTRUCTMD_API=`) against empty stand-ins for <stddef.h> and <stdint.h>, so that only the
header's own declarations remain.
"""

import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
HEADER = Path(os.environ.get("STRUCTMD_HEADER", REPO_ROOT / "include" / "structmd.h"))

# The only base types a declaration of the ABI may use.
C_BASE_TYPES = ("void", "char", "int", "int32_t", "uint32_t", "int64_t", "size_t", "double",
                "structmd_status", "structmd_sim", "structmd_force_callback", "structmd_device_force_callback",
                "structmd_dlpack_tensor")
# The typedefs of function pointers: parameters of these types carry a function's address by value.
CALLBACK_TYPES = ("structmd_force_callback", "structmd_device_force_callback")

_DEFINE = re.compile(r"^\s*#\s*define\s+(STRUCTMD_\w+)\s+(\d+)[uU]?\b", re.MULTILINE)
_TYPEDEF = re.compile(r"\btypedef\s+[^;(]*?\b(\w+)\s*;|\btypedef\s+[^;(]*\(\s*\*\s*(\w+)\s*\)")
_PROTOTYPE = re.compile(r"\bSTRUCTMD_API\s+([^;{}()]*?)\b(structmd_\w+)\s*\(([^()]*)\)\s*;")
_DECLARATION = re.compile(r"^(?P<const>const\s+)?(?P<base>\w+)\s*(?P<stars>(?:\*\s*)*)"
                          r"(?P<name>\w+)?\s*(?:\[\s*(?P<extent>\d*)\s*\])?$")


class HeaderError(ValueError):
    """A declaration this parser does not understand."""


@dataclass(frozen=True)
class CType:
    """A C type as the ABI spells it: 'const double*' is CType('double', const=True, pointers=1),
    'double lengths[3]' is CType('double', pointers=1, extent=3)."""

    base: str
    const: bool = False
    pointers: int = 0
    extent: int = None  # the N of an array parameter T x[N], which C passes as T*

    def __str__(self):
        return self.declare("")

    def declare(self, name):
        """The C declaration of name with this type: 'const double lengths[3]', 'int64_t* n'."""
        const = "const " if self.const else ""
        if self.extent is not None:
            return f"{const}{self.base} {name}[{self.extent}]".replace(" [", "[")
        return f"{const}{self.base}{'*' * self.pointers} {name}".rstrip()

    @property
    def plain(self):
        """The spelling with const dropped and arrays written as pointers: 'double*'."""
        return self.base + "*" * self.pointers


@dataclass(frozen=True)
class Parameter:
    type: CType
    name: str  # None when a quoted signature leaves it out


@dataclass(frozen=True)
class Function:
    name: str
    returns: CType
    parameters: tuple

    def __str__(self):
        parameters = ", ".join(p.type.declare(p.name or "") for p in self.parameters) or "void"
        return f"{self.returns} {self.name}({parameters})"


def strip_comments(text):
    return re.sub(r"/\*.*?\*/|//[^\n]*", " ", text, flags=re.S)


def parse_declaration(text, where):
    """'const double lengths[3]' -> Parameter(CType('double', True, 1, 3), 'lengths'); names and
    spaces are optional ('int64_t*'). HeaderError when text is not such a declaration."""
    text = " ".join(text.split())
    match = _DECLARATION.match(text)
    if not match or match.group("base") not in C_BASE_TYPES:
        raise HeaderError(f"{where}: cannot read the declaration '{text}'")
    extent = match.group("extent")
    if extent == "":
        raise HeaderError(f"{where}: '{text}': an array parameter needs its extent")
    pointers = match.group("stars").count("*") + (extent is not None)
    c_type = CType(match.group("base"), bool(match.group("const")), pointers,
                   int(extent) if extent is not None else None)
    return Parameter(c_type, match.group("name"))


def parse_parameters(text, where):
    """The parameter list of a prototype ('void' or empty: none) as a tuple of Parameter."""
    if text.strip() in ("", "void"):
        return ()
    return tuple(parse_declaration(p, f"{where}, parameter {i}") for i, p in enumerate(text.split(","), 1))


def header_text():
    return HEADER.read_text()


def header_defines(text=None):
    """{name: value} of every integer #define of the header (ABI version, statuses, flags)."""
    return {name: int(value) for name, value in _DEFINE.findall(text or header_text())}


def header_typedefs(text=None):
    """The type names the header defines (structmd_status, structmd_sim)."""
    return {plain or pointer for plain, pointer in _TYPEDEF.findall(strip_comments(text or header_text()))}


def functions(text=None):
    """{name: Function} of every STRUCTMD_API prototype, in the order of the header."""
    text = strip_comments(text or header_text())
    found = {}
    for return_part, name, parameters in _PROTOTYPE.findall(text):
        returns = parse_declaration(return_part, f"{name}, return type")
        if returns.name is not None:
            raise HeaderError(f"{name}: cannot read the return type '{return_part.strip()}'")
        found[name] = Function(name, returns.type, parse_parameters(parameters, name))
    declared = len(re.findall(r"^\s*STRUCTMD_API\b", text, flags=re.M))
    if not found or len(found) != declared:
        raise HeaderError(f"{len(found)} of the header's {declared} STRUCTMD_API declarations were read: "
                          "the parser no longer matches the header's layout")
    return found


def function_prototypes():
    """{function name: (return type, [(parameter type, parameter name), ...])} in the plain spelling
    (const dropped, arrays written as pointers), e.g. 'structmd_get_box': ('structmd_status',
    [('structmd_sim*', 'sim'), ('double*', 'lengths')])."""
    return {name: (f.returns.plain, [(p.type.plain, p.name) for p in f.parameters])
            for name, f in functions().items()}


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
