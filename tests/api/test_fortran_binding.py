"""bindings/fortran/structmd.f90 against include/structmd.h, type by type (fortran_binding.py says
what must agree); then the same check on a module or header altered on purpose, so that each kind of
mismatch is shown to be caught and named."""

import re

import pytest

import fortran_binding
import structmd_header

MODULE = structmd_header.REPO_ROOT / "bindings" / "fortran" / "structmd.f90"


def findings(module_text=None, header_text=None):
    header_text = header_text or structmd_header.header_text()
    return fortran_binding.problems(structmd_header.functions(header_text),
                                    structmd_header.header_defines(header_text),
                                    module_text or MODULE.read_text())


def altered(text, pattern, replacement):
    """text with the one match of pattern replaced; the pattern must still match the source, or the
    test would pass without testing anything."""
    result, count = re.subn(pattern, replacement, text, flags=re.M)
    assert count == 1, f"the pattern {pattern!r} matches {count} times: update this test"
    return result


def test_fortran_module_matches_the_header():
    interfaces = fortran_binding.parse_module(MODULE.read_text())[2]
    assert set(structmd_header.functions()) <= set(interfaces)
    found = findings()
    assert not found, "bindings/fortran/structmd.f90 disagrees with include/structmd.h:\n" + "\n".join(found)


@pytest.mark.parametrize("pattern, replacement, expected", [
    # a value of the wrong kind
    (r"integer\(c_int64_t\), value :: nsteps", "integer(c_int32_t), value :: nsteps",
     "structmd_step: argument 2 (int64_t nsteps): C passes int64_t by value: expected integer(c_int64_t), "
     "value; Fortran declares integer(c_int32_t), value :: nsteps"),
    # a value passed by reference
    (r"integer\(c_int64_t\), value :: nsteps", "integer(c_int64_t) :: nsteps",
     "structmd_step: argument 2 (int64_t nsteps): C passes int64_t by value"),
    # a pointer passed as a value of the pointee's kind
    (r"real\(c_double\), intent\(out\) :: p$", "real(c_double), value :: p",
     "structmd_get_pressure: argument 2 (double* p): C passes double*, a pointer: a value dummy must be "
     "type(c_ptr)"),
    # a pointee of the wrong kind
    (r"integer\(c_int32_t\), intent\(inout\) :: type_index\(\*\)", "integer(c_int64_t), intent(inout) :: type_index(*)",
     "structmd_get_types: argument 2 (int32_t* type_index): C passes int32_t*: expected integer(c_int32_t) "
     "by reference"),
    # an array of the wrong extent
    (r"real\(c_double\), intent\(inout\) :: w\(9\)", "real(c_double), intent(inout) :: w(3)",
     "structmd_get_virial: argument 2 (double w[9]): C passes 9 values, Fortran declares w(3)"),
    # an output declared as input, an input declared as output
    (r"real\(c_double\), intent\(inout\) :: xyz\(\*\)", "real(c_double), intent(in) :: xyz(*)",
     "structmd_get_positions: argument 2 (double* xyz): C writes through double*"),
    (r"real\(c_double\), intent\(in\) :: v\(\*\)", "real(c_double), intent(out) :: v(*)",
     "structmd_set_velocities: argument 2 (const double* v): C promises not to write through const double*"),
    # a string that is not a character array
    (r"character\(kind=c_char\), intent\(in\) :: json\(\*\)", "character(kind=c_char), intent(in) :: json",
     "structmd_load_string: argument 2 (const char* json): C passes const char*, a string"),
    # two arguments swapped
    (r"structmd_get_info\(sim, buffer, size, needed\)", "structmd_get_info(sim, buffer, needed, size)",
     "structmd_get_info: argument 3 (size_t size): Fortran names it needed"),
    # an argument missing
    (r"structmd_get_counters\(sim, buffer, size\)", "structmd_get_counters(sim, buffer)",
     "structmd_get_counters: 3 parameters in C (sim, buffer, size), 2 in Fortran (sim, buffer)"),
    # a result of the wrong kind, a function bound as a subroutine
    (r"integer\(c_int\) :: version", "integer(c_int64_t) :: version",
     "structmd_abi_version: result: C returns int: expected integer(c_int)"),
    (r"^    function structmd_run\(sim\) (.*) result\(status\)", r"    subroutine structmd_run(sim) \1",
     "structmd_run: result: C returns structmd_status: a subroutine discards it"),
    # an interface bound to another name, a constant of another value
    (r'bind\(C, name="structmd_get_time"\)', 'bind(C, name="structmd_get_times")',
     'structmd_get_time: no bind(C, name="structmd_get_time") interface'),
    (r"STRUCTMD_ERR_IO = 5", "STRUCTMD_ERR_IO = 6",
     "constant STRUCTMD_ERR_IO: the header says 5, Fortran says 6"),
])
def test_module_drift_is_caught(pattern, replacement, expected):
    found = findings(module_text=altered(MODULE.read_text(), pattern, replacement))
    assert any(expected in line for line in found), f"expected '{expected}' among: {found}"


def test_header_drift_is_caught():
    header = altered(structmd_header.header_text(), r"int64_t nsteps\)", "double nsteps)")
    assert findings(header_text=header) == [
        "structmd_step: argument 2 (double nsteps): C passes double by value: expected real(c_double), value; "
        "Fortran declares integer(c_int64_t), value :: nsteps"]
