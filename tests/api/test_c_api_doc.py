"""docs/c-api.md against include/structmd.h: the names, calls and signatures it quotes, its macros and
its links (c_api_doc.py says what is checked); then the same check on pages altered on purpose, so
that each kind of drift is shown to be caught."""

import ast

import pytest

import c_api_doc
import fortran_binding
import structmd_header

REPO_ROOT = structmd_header.REPO_ROOT
DOC = REPO_ROOT / "docs" / "c-api.md"


def python_library_env():
    """The environment variable the ctypes package reads, from its source (importing it would load
    the library)."""
    source = (REPO_ROOT / "bindings" / "python" / "structmd" / "_library.py").read_text()
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign) and [t.id for t in node.targets] == ["LIBRARY_ENV"]:
            return node.value.value
    raise AssertionError("_library.py no longer assigns LIBRARY_ENV")


def findings(text):
    module = (REPO_ROOT / "bindings" / "fortran" / "structmd.f90").read_text()
    constants, public, _ = fortran_binding.parse_module(module)
    fortran_procedures = {name for name in public if name.endswith("_f")}
    macros = set(structmd_header.header_defines()) | set(constants) | {python_library_env()}
    return c_api_doc.problems(text, DOC, structmd_header.functions(),
                              structmd_header.header_typedefs() | fortran_procedures, macros)


def test_c_api_doc_matches_the_header():
    found = findings(DOC.read_text())
    assert not found, "docs/c-api.md disagrees with include/structmd.h:\n" + "\n".join(found)


def test_c_api_doc_links_to_the_header_and_the_reference():
    text = DOC.read_text()
    assert "](../include/structmd.h)" in text and "](Doxyfile)" in text


@pytest.mark.parametrize("alteration, expected", [
    ("structmd_step(sim)", "structmd_step(sim): called with 1 arguments, the header declares 2"),
    ("structmd_status structmd_get_step(const structmd_sim* sim, int32_t* step)",
     "parameter 2 is 'int32_t* step' here, 'int64_t* step' in the header"),
    ("structmd_status structmd_get_step(const structmd_sim* sim, int64_t* steps)",
     "parameter 2 is 'int64_t* steps' here, 'int64_t* step' in the header"),
    ("int64_t structmd_get_step(const structmd_sim*, int64_t*)",
     "returns int64_t here, structmd_status in the header"),
    ("structmd_status structmd_set_box(structmd_sim* sim, double lengths[3])",
     "parameter 2 is 'double lengths[3]' here, 'const double lengths[3]' in the header"),
    ("`structmd_get_enthalpy`", "structmd_get_enthalpy is not declared in include/structmd.h"),
    ("`structmd_get_mass_f`", "structmd_get_mass_f is not declared in include/structmd.h nor public in the Fortran"),
    ("`STRUCTMD_ERR_TIMEOUT`", "STRUCTMD_ERR_TIMEOUT is defined nowhere"),
    ("[energy](#energies)", "no heading of this page has the anchor #energies"),
    ("[format](input_format.md)", "input_format.md does not exist"),
])
def test_drift_is_caught(alteration, expected):
    found = findings(DOC.read_text() + "\n" + alteration + "\n")
    assert any(expected in line for line in found), f"expected '{expected}' among: {found}"
