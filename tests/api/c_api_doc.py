"""Holds docs/c-api.md to include/structmd.h.

The page is narrative: it names functions, calls them in examples and may quote a signature, but the
reference is the header. So every `structmd_...` name it mentions must be declared in the header (or,
for a `_f` name, be a public procedure of the Fortran module); a quoted signature, with or without
parameter names or return type, must be the header's, type for type; a call in an example must pass
as many arguments as the function takes; every STRUCTMD_ name must exist; and every relative link and
#anchor must lead somewhere.

problems() returns one line per finding, each starting with the line of the page it is on.
"""

import re
from pathlib import Path

from structmd_header import C_BASE_TYPES, HeaderError, parse_declaration, parse_parameters

# A name in running text or code; one inside a path or URL (html/structmd_8h.html) is not an API name.
_NAME = re.compile(r"(?<![\w/.-])structmd_\w+")
_MACRO = re.compile(r"\bSTRUCTMD_[A-Z0-9_]*[A-Z0-9]\b")  # STRUCTMD_ERR_* (a family) ends in "_"
_RETURN_TYPE = re.compile(r"(?:\bconst\s+)?\b(\w+)\s*\**\s*$")
_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def _line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def _unquoted(text, start=0):
    """(index, char) for each character of text[start:] outside string and character literals."""
    quote, index = None, start
    while index < len(text):
        char = text[index]
        if quote:
            if char == "\\":
                index += 1
            elif char == quote:
                quote = None
        elif char in "\"'":
            quote = char
        else:
            yield index, char
        index += 1


def _arguments(text, start):
    """The text between the parenthesis at text[start] and its match, quotes respected; None when
    it is not closed."""
    depth = 0
    for index, char in _unquoted(text, start):
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0:
                return text[start + 1:index]
    return None


def _count_arguments(arguments):
    """Top-level arguments of a call: 'sim, "a, b", f(x, y)' -> 3."""
    if not arguments.strip():
        return 0
    depth, count = 0, 1
    for _, char in _unquoted(arguments):
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
        elif char == "," and depth == 0:
            count += 1
    return count


def _quoted_signature(name, arguments):
    """The parameters of a quoted signature, or None when the text is a call (some argument is not
    a C declaration)."""
    try:
        return parse_parameters(arguments, name)
    except HeaderError:
        return None


def _signature_problems(where, function, returns, parameters):
    found = []
    if returns is not None and returns != function.returns:
        found.append(f"{where}: returns {returns} here, {function.returns} in the header")
    if len(parameters) != len(function.parameters):
        found.append(f"{where}: {len(parameters)} parameters here, {len(function.parameters)} in the header "
                     f"({function})")
        return found
    for position, (quoted, declared) in enumerate(zip(parameters, function.parameters), 1):
        if quoted.type != declared.type or quoted.name not in (None, declared.name):
            found.append(f"{where}: parameter {position} is '{quoted.type.declare(quoted.name or '')}' here, "
                         f"'{declared.type.declare(declared.name)}' in the header")
    return found


def _slug(heading):
    """The anchor GitHub gives a heading: 'C++ conveniences' -> 'c-conveniences'."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower().replace("`", ""))
    return text.replace(" ", "-")


def _link_problems(text, doc_path):
    anchors = {_slug(h) for h in re.findall(r"^#+\s+(.*)$", text, flags=re.M)}
    found = []
    for match in _LINK.finditer(text):
        target = match.group(1)
        if re.match(r"^[a-z]+:", target):
            continue  # an external URL
        path, _, anchor = target.partition("#")
        where = f"line {_line_of(text, match.start())}: link {target}"
        if path and not (doc_path.parent / path).exists():
            found.append(f"{where}: {path} does not exist")
        elif not path and anchor not in anchors:
            found.append(f"{where}: no heading of this page has the anchor #{anchor}")
    return found


def problems(text, doc_path, header_functions, other_names, macros):
    """Findings of docs/c-api.md (its text, at doc_path) against the header's functions.
    other_names: type names and Fortran procedures the page may name besides the functions;
    macros: the STRUCTMD_ names that exist (the header's, the bindings')."""
    found = []
    for match in _NAME.finditer(text):
        name, line = match.group(0), _line_of(text, match.start())
        function = header_functions.get(name)
        if function is None:
            if name not in other_names:
                found.append(f"line {line}: {name} is not declared in include/structmd.h"
                             + (" nor public in the Fortran module" if name.endswith("_f") else ""))
            continue
        opening = re.match(r"\s*\(", text[match.end():])
        if not opening:
            continue
        arguments = _arguments(text, match.end() + opening.end() - 1)
        if arguments is None:
            found.append(f"line {line}: {name}( is not closed")
            continue
        parameters = _quoted_signature(name, arguments)
        where = f"line {line}: {name}({' '.join(arguments.split())})"
        if parameters is None:
            count = _count_arguments(arguments)
            if count != len(function.parameters):
                found.append(f"{where}: called with {count} arguments, the header declares "
                             f"{len(function.parameters)} ({function})")
            continue
        line_start = text.rfind("\n", 0, match.start()) + 1
        returns = None
        before = _RETURN_TYPE.search(text[line_start:match.start()])
        if before and before.group(1) in C_BASE_TYPES:
            returns = parse_declaration(before.group(0), where).type
        found += _signature_problems(where, function, returns, parameters)
    for match in _MACRO.finditer(text):
        if match.group(0) not in macros:
            found.append(f"line {_line_of(text, match.start())}: {match.group(0)} is defined nowhere "
                         "(not in include/structmd.h, not in the bindings)")
    return found + _link_problems(text, Path(doc_path))
