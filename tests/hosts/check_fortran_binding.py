#!/usr/bin/env python3
"""Checks that bindings/fortran/structmd.f90 mirrors include/structmd.h.

The Fortran module restates the header's constants and function signatures by hand, so this test
fails when the two drift apart: every #define value must appear as a Fortran parameter with the same
value, and every exported C function must have a public bind(C) interface of the same name taking the
same number of arguments.

usage: check_fortran_binding.py HEADER FORTRAN_MODULE
"""
import re
import sys

# Fortran names are not case sensitive, so the macro STRUCTMD_ABI_VERSION would clash with the
# function structmd_abi_version; the module names it differently.
FORTRAN_NAME_OF_MACRO = {"STRUCTMD_ABI_VERSION": "STRUCTMD_BINDING_ABI_VERSION"}
NOT_CONSTANTS = {"STRUCTMD_H", "STRUCTMD_API"}


def strip_c_comments(text):
    return re.sub(r"/\*.*?\*/|//[^\n]*", "", text, flags=re.S)


def strip_fortran_comments(text):
    return re.sub(r"![^\n]*", "", text)


def join_fortran_continuations(text):
    return re.sub(r"&\s*\n\s*&?", " ", text)


def header_constants(header):
    constants = {}
    for name, value in re.findall(r"^\s*#define\s+(STRUCTMD_\w+)\s+(\d+)u?\s*$", header, flags=re.M):
        if name not in NOT_CONSTANTS:
            constants[name] = int(value)
    return constants


def header_functions(header):
    """Maps each exported function name to its number of parameters."""
    functions = {}
    for match in re.finditer(r"STRUCTMD_API\s+[^;{]*?\b(structmd_\w+)\s*\(([^)]*)\)\s*;", header):
        parameters = match.group(2).strip()
        functions[match.group(1)] = 0 if parameters in ("", "void") else parameters.count(",") + 1
    return functions


def fortran_constants(module):
    return {name.upper(): int(value) for name, value in
            re.findall(r"parameter\s*,\s*public\s*::\s*(\w+)\s*=\s*(\d+)", module, flags=re.I)}


def fortran_interfaces(module):
    """Maps each bound C name to (Fortran name, number of dummy arguments)."""
    interfaces = {}
    pattern = r"(?:function|subroutine)\s+(\w+)\s*\(([^)]*)\)\s*bind\s*\(\s*C\s*,\s*name\s*=\s*\"(\w+)\"\s*\)"
    for fortran_name, arguments, c_name in re.findall(pattern, module, flags=re.I):
        count = len([a for a in arguments.split(",") if a.strip()])
        interfaces[c_name] = (fortran_name, count)
    return interfaces


def fortran_public_names(module):
    names = set()
    for statement in re.findall(r"^\s*public\s*::([^\n]*)$", module, flags=re.M | re.I):
        names.update(n.strip().lower() for n in statement.split(",") if n.strip())
    return names


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    with open(sys.argv[1]) as f:
        header = strip_c_comments(f.read())
    with open(sys.argv[2]) as f:
        module = join_fortran_continuations(strip_fortran_comments(f.read()))

    problems = []
    c_constants = header_constants(header)
    f_constants = fortran_constants(module)
    for name, value in sorted(c_constants.items()):
        fortran_name = FORTRAN_NAME_OF_MACRO.get(name, name)
        if fortran_name not in f_constants:
            problems.append(f"constant {name}: no Fortran parameter {fortran_name}")
        elif f_constants[fortran_name] != value:
            problems.append(f"constant {name}: header says {value}, Fortran says {f_constants[fortran_name]}")

    c_functions = header_functions(header)
    f_interfaces = fortran_interfaces(module)
    public = fortran_public_names(module)
    for name, count in sorted(c_functions.items()):
        if name not in f_interfaces:
            problems.append(f"function {name}: no bind(C) interface")
            continue
        fortran_name, fortran_count = f_interfaces[name]
        if fortran_name.lower() != name:
            problems.append(f"function {name}: Fortran interface is named {fortran_name}")
        if fortran_count != count:
            problems.append(f"function {name}: {count} parameters in C, {fortran_count} in Fortran")
        if name not in public:
            problems.append(f"function {name}: interface is not public")
    for name in sorted(set(f_interfaces) - set(c_functions)):
        if name.startswith("structmd_"):
            problems.append(f"function {name}: bound in Fortran but not in the header")

    if not c_constants or not c_functions:
        problems.append("nothing parsed from the header: the parser no longer matches its layout")
    for problem in problems:
        print(problem)
    print(f"{len(c_constants)} constants and {len(c_functions)} functions compared, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
