"""Compares the hand-written Fortran module bindings/fortran/structmd.f90 with include/structmd.h,
type by type.

For every function of the header the module must have a public bind(C) interface of the same name
whose dummy arguments have the C parameters' names, in order, with the iso_c_binding kind of each C
type and its passing convention: a C value (int64_t nsteps) is a `value` dummy of that kind; a C
pointer is either a dummy of the pointee's kind passed by reference (a scalar or an array,
intent(in) when the pointee is const, never intent(in) when it is not) or a `type(c_ptr), value`
holding the address. The result must have the C return type's kind (a subroutine for void). Every
#define must be a Fortran parameter of the same value.

problems() returns one line per mismatch, naming the function and what differs.
"""

import re
from dataclasses import dataclass

from structmd_header import CALLBACK_TYPES

# The kind of each C value type in iso_c_binding. Fortran has no unsigned integers: uint32_t travels
# as c_int32_t, which has its size and passes the flag bits unchanged.
KIND_OF_C_TYPE = {
    "int": ("integer", "c_int"),
    "int32_t": ("integer", "c_int32_t"),
    "structmd_status": ("integer", "c_int32_t"),
    "uint32_t": ("integer", "c_int32_t"),
    "int64_t": ("integer", "c_int64_t"),
    "size_t": ("integer", "c_size_t"),
    "double": ("real", "c_double"),
    "char": ("character", "c_char"),
}
C_PTR = ("type", "c_ptr")
C_FUNPTR = ("type", "c_funptr")  # a callback, passed by value: c_funloc(f) or c_null_funptr

# Fortran names are not case sensitive, so the macro STRUCTMD_ABI_VERSION would clash with the
# function structmd_abi_version; the module names it differently.
FORTRAN_NAME_OF_MACRO = {"STRUCTMD_ABI_VERSION": "STRUCTMD_BINDING_ABI_VERSION"}


@dataclass
class Dummy:
    """A dummy argument or function result of an interface, as declared."""

    name: str
    type: tuple = None  # ("integer", "c_int64_t"), ("type", "c_ptr"), ...
    value: bool = False
    intent: str = None  # "in", "out", "inout" or None
    optional: bool = False
    dimensions: str = None  # "*", "9", "3, *" or None for a scalar

    def spelling(self):
        if self.type is None:
            return "undeclared"
        kind = f"kind={self.type[1]}" if self.type[0] == "character" else self.type[1]
        words = [f"{self.type[0]}({kind})"]
        words += ["value"] if self.value else []
        words += [f"intent({self.intent})"] if self.intent else []
        words += ["optional"] if self.optional else []
        return ", ".join(words) + (f" :: {self.name}({self.dimensions})" if self.dimensions else f" :: {self.name}")


@dataclass
class Interface:
    fortran_name: str
    arguments: list  # of Dummy, in order
    result: Dummy  # None for a subroutine


def strip_comments(text):
    return re.sub(r"![^\n]*", "", text)


def join_continuations(text):
    return re.sub(r"&\s*\n\s*&?", " ", text)


def split_top_level(text):
    """Splits at commas outside parentheses: 'a(3, *), b' -> ['a(3, *)', 'b']."""
    parts, depth, current = [], 0, ""
    for char in text:
        depth += {"(": 1, ")": -1}.get(char, 0)
        if char == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += char
    return parts + [current.strip()] if current.strip() else parts


def _type_spec(text):
    """'integer(c_int64_t)', 'integer(kind=c_int64_t)', 'character(kind=c_char, len=1)', 'type(c_ptr)'
    -> ('integer', 'c_int64_t'); None for a statement that declares nothing."""
    match = re.match(r"^(integer|real|character|type|logical|complex)\s*(?:\((.*)\))?$", text.strip(), re.I)
    if not match:
        return None
    kind = None
    for item in split_top_level(match.group(2) or ""):
        key, _, value = item.rpartition("=")
        if key.strip().lower() in ("", "kind"):
            kind = value.strip().lower()
    return match.group(1).lower(), kind


def _declare(body, dummies):
    """Reads the declarations of an interface body into the Dummy entries they name."""
    for statement in body.split("\n"):
        head, separator, entities = statement.partition("::")
        if not separator:
            continue
        spec, *attributes = split_top_level(head)
        c_type = _type_spec(spec)
        if c_type is None:
            continue  # import :: ...
        for entity in split_top_level(entities):
            match = re.match(r"^(\w+)\s*(?:\((.*)\))?$", entity)
            dummy = dummies.get(match.group(1).lower()) if match else None
            if dummy is None:
                continue
            dummy.type = c_type
            dummy.dimensions = match.group(2)
            for attribute in (a.strip().lower() for a in attributes):
                intent = re.match(r"^intent\s*\(\s*(in|out|inout)\s*\)$", attribute)
                dimension = re.match(r"^dimension\s*\((.*)\)$", attribute)
                if attribute == "value":
                    dummy.value = True
                elif attribute == "optional":
                    dummy.optional = True
                elif intent:
                    dummy.intent = intent.group(1)
                elif dimension:
                    dummy.dimensions = dimension.group(1)
            if dummy.dimensions is not None:
                dummy.dimensions = ", ".join(d.strip() for d in dummy.dimensions.split(","))


def parse_module(text):
    """(constants {NAME: value}, public names {lowercase}, interfaces {bound C name: Interface})."""
    text = join_continuations(strip_comments(text))
    constants = {name.upper(): int(value) for name, value in
                 re.findall(r"parameter\s*,\s*public\s*::\s*(\w+)\s*=\s*(\d+)", text, flags=re.I)}
    public = set()
    for statement in re.findall(r"^\s*public\s*::([^\n]*)$", text, flags=re.M | re.I):
        public.update(n.strip().lower() for n in statement.split(",") if n.strip())
    interfaces = {}
    pattern = re.compile(
        r"^\s*(function|subroutine)\s+(\w+)\s*\(([^)]*)\)\s*bind\s*\(\s*C\s*,\s*name\s*=\s*[\"'](\w+)[\"']\s*\)"
        r"\s*(?:result\s*\(\s*(\w+)\s*\))?\s*$(.*?)^\s*end\s+(?:function|subroutine)\b",
        flags=re.I | re.M | re.S)
    for kind, fortran_name, arguments, c_name, result_name, body in pattern.findall(text):
        names = [a.strip().lower() for a in arguments.split(",") if a.strip()]
        dummies = {name: Dummy(name) for name in names}
        result = None
        if kind.lower() == "function":
            result = Dummy((result_name or fortran_name).lower())
            dummies[result.name] = result
        _declare(body, dummies)
        interfaces[c_name] = Interface(fortran_name, [dummies[name] for name in names], result)
    return constants, public, interfaces


def _argument_problem(c_type, dummy):
    """Why a Fortran dummy cannot receive a C parameter of c_type, or None if it can."""
    if dummy.type is None:
        return "the dummy argument is not declared"
    if c_type.pointers == 0:
        wanted = C_FUNPTR if c_type.base in CALLBACK_TYPES else KIND_OF_C_TYPE.get(c_type.base)
        if dummy.type != wanted or not dummy.value or dummy.dimensions is not None or dummy.optional:
            return f"C passes {c_type} by value: expected {wanted[0]}({wanted[1]}), value"
        return None
    if dummy.type == C_PTR and dummy.value and dummy.dimensions is None:
        return None  # the address itself, c_loc(x) or c_null_ptr
    if dummy.value:
        return f"C passes {c_type}, a pointer: a value dummy must be type(c_ptr)"
    opaque = ("structmd_sim", "structmd_dlpack_tensor")
    pointee = C_PTR if c_type.pointers == 2 or c_type.base in opaque else KIND_OF_C_TYPE.get(c_type.base)
    if c_type.pointers > 2 or (c_type.pointers == 2 and c_type.base not in opaque):
        pointee = None
    if dummy.type != pointee:
        expected = f"{pointee[0]}({pointee[1]}) by reference" if pointee else "nothing Fortran can pass by reference"
        return f"C passes {c_type}: expected {expected}, or type(c_ptr), value"
    if c_type.base == "char" and dummy.dimensions is None:
        return f"C passes {c_type}, a string: expected an array of character(kind=c_char), such as {dummy.name}(*)"
    if c_type.extent is not None and dummy.dimensions not in (None, "*", str(c_type.extent)):
        return f"C passes {c_type.extent} values, Fortran declares {dummy.name}({dummy.dimensions})"
    if c_type.const and dummy.intent in ("out", "inout"):
        return f"C promises not to write through {c_type}: intent({dummy.intent}) says it does"
    if not c_type.const and dummy.intent == "in":
        return f"C writes through {c_type}: intent(in) lets the compiler assume it does not"
    return None


def _result_problem(c_type, result):
    if c_type.base == "void" and c_type.pointers == 0:
        return None if result is None else "C returns void: expected a subroutine"
    if result is None:
        return f"C returns {c_type}: a subroutine discards it"
    wanted = C_PTR if c_type.pointers else KIND_OF_C_TYPE.get(c_type.base)
    if result.type != wanted or result.dimensions is not None:
        return f"C returns {c_type}: expected {wanted[0]}({wanted[1]}), got {result.spelling()}"
    return None


def problems(header_functions, header_defines, module_text):
    """One line per difference between the header's functions and constants and the module."""
    constants, public, interfaces = parse_module(module_text)
    found = []
    for name, value in sorted(header_defines.items()):
        fortran_name = FORTRAN_NAME_OF_MACRO.get(name, name)
        if fortran_name not in constants:
            found.append(f"constant {name}: no public Fortran parameter {fortran_name}")
        elif constants[fortran_name] != value:
            found.append(f"constant {name}: the header says {value}, Fortran says {constants[fortran_name]}")

    for name, function in header_functions.items():
        interface = interfaces.get(name)
        if interface is None:
            found.append(f"{name}: no bind(C, name=\"{name}\") interface")
            continue
        if interface.fortran_name.lower() != name:
            found.append(f"{name}: the Fortran interface is named {interface.fortran_name}")
        if name not in public:
            found.append(f"{name}: the interface is not public")
        result = _result_problem(function.returns, interface.result)
        if result:
            found.append(f"{name}: result: {result}")
        if len(interface.arguments) != len(function.parameters):
            found.append(f"{name}: {len(function.parameters)} parameters in C "
                         f"({', '.join(p.name for p in function.parameters) or 'none'}), "
                         f"{len(interface.arguments)} in Fortran "
                         f"({', '.join(d.name for d in interface.arguments) or 'none'})")
            continue
        for position, (parameter, dummy) in enumerate(zip(function.parameters, interface.arguments), 1):
            where = f"{name}: argument {position} ({parameter.type.declare(parameter.name)})"
            if dummy.name != parameter.name.lower():
                found.append(f"{where}: Fortran names it {dummy.name}")
            problem = _argument_problem(parameter.type, dummy)
            if problem:
                found.append(f"{where}: {problem}; Fortran declares {dummy.spelling()}")
    for name in sorted(set(interfaces) - set(header_functions)):
        if name.startswith("structmd_"):
            found.append(f"{name}: bound in Fortran but not declared in the header")
    return found
