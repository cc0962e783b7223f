!> Fortran binding of the structmd C ABI (include/structmd.h).
!>
!> Two layers:
!> - iso_c_binding interfaces named exactly as the C functions (structmd_step, structmd_get_forces...),
!>   with the C conventions: strings are NUL-terminated character(kind=c_char) arrays, vectors are
!>   flat real(c_double) arrays of 3n values, the handle is a type(c_ptr).
!> - thin wrappers named with the suffix _f (as HDF5 does) that take Fortran strings (trimmed, NUL
!>   added here), arrays shaped x(3,n) or e(n) whose extent gives n, and return C strings as
!>   allocatable Fortran characters.
!> Every function that can fail returns the C status, an integer(c_int32_t) equal to one of the
!> STRUCTMD_OK / STRUCTMD_ERR_* parameters below; structmd_last_error_f(sim) says why it failed.
!> The constants mirror the #defines of the header and the interfaces its prototypes;
!> tests/api/test_fortran_binding.py checks them against the header, kind by kind.
module structmd
  use, intrinsic :: iso_c_binding, only: c_ptr, c_associated, c_f_pointer, c_char, &
                                         c_null_char, c_int, c_int32_t, c_int64_t, c_size_t, c_double, &
                                         c_funptr
  implicit none
  private

  ! STRUCTMD_ABI_VERSION of the header this module was written against. Fortran names are not case
  ! sensitive, so the C macro's own name would clash with the function structmd_abi_version.
  integer(c_int), parameter, public :: STRUCTMD_BINDING_ABI_VERSION = 4

  integer(c_int32_t), parameter, public :: STRUCTMD_OK = 0
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_ARGUMENT = 1
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_INPUT = 2
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_STATE = 3
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_NUMERICAL = 4
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_IO = 5
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_DEVICE = 6
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_MEMORY = 7
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_UNSUPPORTED = 8
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_INTERNAL = 9
  integer(c_int32_t), parameter, public :: STRUCTMD_ERR_CALLBACK = 10

  ! Compute flags for structmd_compute (uint32_t in C; the bits are the same), combined with ior.
  integer(c_int32_t), parameter, public :: STRUCTMD_FORCES = 1
  integer(c_int32_t), parameter, public :: STRUCTMD_ENERGY = 2
  integer(c_int32_t), parameter, public :: STRUCTMD_VIRIAL = 4

  public :: structmd_abi_version, structmd_version, structmd_create, structmd_destroy, &
            structmd_last_error, structmd_load_file, structmd_load_string, structmd_step, &
            structmd_run, structmd_compute, structmd_get_num_particles, structmd_get_ids, &
            structmd_get_positions, structmd_get_velocities, structmd_get_forces, &
            structmd_get_particle_energies, structmd_get_masses, structmd_get_types, &
            structmd_get_energy, structmd_get_virial, structmd_get_pressure, structmd_get_temperature, &
            structmd_get_box, &
            structmd_get_step, structmd_get_time, structmd_set_positions, structmd_set_velocities, &
            structmd_set_box, structmd_set_external_forces, structmd_get_info, &
            structmd_save_checkpoint, structmd_load_checkpoint, structmd_get_counters, &
            structmd_load_plugin, structmd_set_external_energy, structmd_get_positions_of, &
            structmd_get_velocities_of, structmd_get_forces_of, structmd_set_positions_of, &
            structmd_set_velocities_of, structmd_set_external_forces_of, structmd_set_parameter, &
            structmd_get_parameter, structmd_set_force_callback, structmd_set_device_force_callback, &
            structmd_set_callback_error, structmd_get_view, structmd_force_callback, &
            structmd_get_orientations, structmd_set_orientations, structmd_get_torques, &
            structmd_get_magnetic_moments, structmd_traverse_expression, &
            structmd_transverser_values, structmd_traverse, structmd_traverse_view

  public :: structmd_version_f, structmd_last_error_f, structmd_create_f, structmd_load_file_f, &
            structmd_load_string_f, structmd_get_energy_f, structmd_get_ids_f, &
            structmd_get_positions_f, structmd_get_velocities_f, structmd_get_forces_f, &
            structmd_get_particle_energies_f, structmd_get_masses_f, structmd_get_types_f, &
            structmd_set_positions_f, structmd_set_velocities_f, structmd_set_external_forces_f, &
            structmd_clear_external_forces_f, structmd_get_info_f, structmd_save_checkpoint_f, &
            structmd_load_checkpoint_f, structmd_get_counters_f, structmd_load_plugin_f, &
            structmd_get_positions_of_f, structmd_get_velocities_of_f, structmd_get_forces_of_f, &
            structmd_set_positions_of_f, structmd_set_velocities_of_f, structmd_set_external_forces_of_f, &
            structmd_set_parameter_f, structmd_get_parameter_f

  ! The shape of a host force callback (structmd_force_callback in C): pass c_funloc of a bind(C)
  ! function of this interface to structmd_set_force_callback.
  abstract interface
    function structmd_force_callback(positions, forces, n, energy, virial, step, user_data) bind(C) result(status)
      import :: c_double, c_int64_t, c_int32_t, c_ptr
      integer(c_int64_t), value :: n
      real(c_double), intent(in) :: positions(3, n)
      real(c_double), intent(inout) :: forces(3, n)
      real(c_double), intent(inout) :: energy
      real(c_double), intent(inout) :: virial(9)
      integer(c_int64_t), value :: step
      type(c_ptr), value :: user_data
      integer(c_int32_t) :: status
    end function
  end interface

  interface
    function structmd_abi_version() bind(C, name="structmd_abi_version") result(version)
      import :: c_int
      integer(c_int) :: version
    end function

    function structmd_version() bind(C, name="structmd_version") result(text)
      import :: c_ptr
      type(c_ptr) :: text
    end function

    !> options_json may be left out (NULL: all defaults).
    function structmd_create(options_json, out) bind(C, name="structmd_create") result(status)
      import :: c_ptr, c_char, c_int32_t
      character(kind=c_char), intent(in), optional :: options_json(*)
      type(c_ptr), intent(out) :: out
      integer(c_int32_t) :: status
    end function

    subroutine structmd_destroy(sim) bind(C, name="structmd_destroy")
      import :: c_ptr
      type(c_ptr), value :: sim
    end subroutine

    function structmd_last_error(sim) bind(C, name="structmd_last_error") result(text)
      import :: c_ptr
      type(c_ptr), value :: sim
      type(c_ptr) :: text
    end function

    function structmd_load_file(sim, path) bind(C, name="structmd_load_file") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int32_t) :: status
    end function

    function structmd_load_string(sim, json) bind(C, name="structmd_load_string") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: json(*)
      integer(c_int32_t) :: status
    end function

    function structmd_load_plugin(path) bind(C, name="structmd_load_plugin") result(status)
      import :: c_char, c_int32_t
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int32_t) :: status
    end function

    function structmd_step(sim, nsteps) bind(C, name="structmd_step") result(status)
      import :: c_ptr, c_int32_t, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int64_t), value :: nsteps
      integer(c_int32_t) :: status
    end function

    function structmd_run(sim) bind(C, name="structmd_run") result(status)
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: sim
      integer(c_int32_t) :: status
    end function

    function structmd_compute(sim, flags) bind(C, name="structmd_compute") result(status)
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: sim
      integer(c_int32_t), value :: flags
      integer(c_int32_t) :: status
    end function

    function structmd_get_num_particles(sim, n) bind(C, name="structmd_get_num_particles") result(status)
      import :: c_ptr, c_int32_t, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(out) :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_ids(sim, ids, n) bind(C, name="structmd_get_ids") result(status)
      import :: c_ptr, c_int32_t, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(inout) :: ids(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_positions(sim, xyz, n) bind(C, name="structmd_get_positions") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: xyz(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_velocities(sim, v, n) bind(C, name="structmd_get_velocities") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: v(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_orientations(sim, q, n) bind(C, name="structmd_get_orientations") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: q(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_torques(sim, t, n) bind(C, name="structmd_get_torques") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: t(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_magnetic_moments(sim, m, n) bind(C, name="structmd_get_magnetic_moments") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: m(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_forces(sim, f, n) bind(C, name="structmd_get_forces") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: f(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_particle_energies(sim, e, n) bind(C, name="structmd_get_particle_energies") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: e(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_masses(sim, m, n) bind(C, name="structmd_get_masses") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: m(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_types(sim, type_index, n) bind(C, name="structmd_get_types") result(status)
      import :: c_ptr, c_int32_t, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int32_t), intent(inout) :: type_index(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_get_energy(sim, term, value) bind(C, name="structmd_get_energy") result(status)
      import :: c_ptr, c_char, c_int32_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: term(*)
      real(c_double), intent(out) :: value
      integer(c_int32_t) :: status
    end function

    function structmd_get_virial(sim, w) bind(C, name="structmd_get_virial") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: w(9)
      integer(c_int32_t) :: status
    end function

    function structmd_get_pressure(sim, p) bind(C, name="structmd_get_pressure") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: p
      integer(c_int32_t) :: status
    end function

    function structmd_get_temperature(sim, t) bind(C, name="structmd_get_temperature") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: t
      integer(c_int32_t) :: status
    end function

    function structmd_get_box(sim, lengths) bind(C, name="structmd_get_box") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(inout) :: lengths(3)
      integer(c_int32_t) :: status
    end function

    function structmd_get_step(sim, step) bind(C, name="structmd_get_step") result(status)
      import :: c_ptr, c_int32_t, c_int64_t
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(out) :: step
      integer(c_int32_t) :: status
    end function

    function structmd_get_time(sim, t) bind(C, name="structmd_get_time") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(out) :: t
      integer(c_int32_t) :: status
    end function

    function structmd_traverse_expression(sim, compute, cutoff, sums, n) &
        bind(C, name="structmd_traverse_expression") result(status)
      import :: c_ptr, c_char, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: compute(*)
      real(c_double), value :: cutoff
      real(c_double), intent(inout) :: sums(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_transverser_values(sim, name, values) &
        bind(C, name="structmd_transverser_values") result(status)
      import :: c_ptr, c_char, c_int, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int), intent(out) :: values
      integer(c_int32_t) :: status
    end function

    function structmd_traverse(sim, name, parameters, cutoff, out, n) &
        bind(C, name="structmd_traverse") result(status)
      import :: c_ptr, c_char, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: name(*), parameters(*)
      real(c_double), value :: cutoff
      real(c_double), intent(inout) :: out(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_set_positions(sim, xyz, n) bind(C, name="structmd_set_positions") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(in) :: xyz(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_set_velocities(sim, v, n) bind(C, name="structmd_set_velocities") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(in) :: v(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_set_orientations(sim, q, n) bind(C, name="structmd_set_orientations") result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(in) :: q(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_set_box(sim, lengths) bind(C, name="structmd_set_box") result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(in) :: lengths(3)
      integer(c_int32_t) :: status
    end function

    !> f left out (NULL) with n = 0 clears the external forces.
    function structmd_set_external_forces(sim, f, n) bind(C, name="structmd_set_external_forces") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      real(c_double), intent(in), optional :: f(*)
      integer(c_int64_t), value :: n
      integer(c_int32_t) :: status
    end function

    function structmd_set_parameter(sim, path, value) bind(C, name="structmd_set_parameter") result(status)
      import :: c_ptr, c_char, c_int32_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: path(*)
      real(c_double), value :: value
      integer(c_int32_t) :: status
    end function

    function structmd_get_parameter(sim, path, value) bind(C, name="structmd_get_parameter") result(status)
      import :: c_ptr, c_char, c_int32_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: path(*)
      real(c_double), intent(out) :: value
      integer(c_int32_t) :: status
    end function

    function structmd_set_force_callback(sim, callback, user_data) bind(C, name="structmd_set_force_callback") &
        result(status)
      import :: c_ptr, c_funptr, c_int32_t
      type(c_ptr), value :: sim
      type(c_funptr), value :: callback
      type(c_ptr), value :: user_data
      integer(c_int32_t) :: status
    end function

    function structmd_set_device_force_callback(sim, callback, user_data) &
        bind(C, name="structmd_set_device_force_callback") result(status)
      import :: c_ptr, c_funptr, c_int32_t
      type(c_ptr), value :: sim
      type(c_funptr), value :: callback
      type(c_ptr), value :: user_data
      integer(c_int32_t) :: status
    end function

    function structmd_set_callback_error(sim, message) bind(C, name="structmd_set_callback_error") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: message(*)
      integer(c_int32_t) :: status
    end function

    function structmd_get_view(sim, quantity, view) bind(C, name="structmd_get_view") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: quantity(*)
      type(c_ptr), intent(out) :: view
      integer(c_int32_t) :: status
    end function

    function structmd_traverse_view(sim, name, parameters, cutoff, view) &
        bind(C, name="structmd_traverse_view") result(status)
      import :: c_ptr, c_char, c_int32_t, c_double
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: name(*), parameters(*)
      real(c_double), value :: cutoff
      type(c_ptr), intent(out) :: view
      integer(c_int32_t) :: status
    end function

    function structmd_set_external_energy(sim, energy) bind(C, name="structmd_set_external_energy") &
        result(status)
      import :: c_ptr, c_int32_t, c_double
      type(c_ptr), value :: sim
      real(c_double), value :: energy
      integer(c_int32_t) :: status
    end function

    function structmd_get_positions_of(sim, ids, m, xyz) bind(C, name="structmd_get_positions_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(inout) :: xyz(3, *)
      integer(c_int32_t) :: status
    end function

    function structmd_get_velocities_of(sim, ids, m, v) bind(C, name="structmd_get_velocities_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(inout) :: v(3, *)
      integer(c_int32_t) :: status
    end function

    function structmd_get_forces_of(sim, ids, m, f) bind(C, name="structmd_get_forces_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(inout) :: f(3, *)
      integer(c_int32_t) :: status
    end function

    function structmd_set_positions_of(sim, ids, m, xyz) bind(C, name="structmd_set_positions_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(in) :: xyz(3, *)
      integer(c_int32_t) :: status
    end function

    function structmd_set_velocities_of(sim, ids, m, v) bind(C, name="structmd_set_velocities_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(in) :: v(3, *)
      integer(c_int32_t) :: status
    end function

    function structmd_set_external_forces_of(sim, ids, m, f) bind(C, name="structmd_set_external_forces_of") &
        result(status)
      import :: c_ptr, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: sim
      integer(c_int64_t), intent(in) :: ids(*)
      integer(c_int64_t), value :: m
      real(c_double), intent(in) :: f(3, *)
      integer(c_int32_t) :: status
    end function

    !> buffer and needed may be left out (NULL); buffer only with size = 0.
    function structmd_get_info(sim, buffer, size, needed) bind(C, name="structmd_get_info") result(status)
      import :: c_ptr, c_char, c_int32_t, c_size_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(inout), optional :: buffer(*)
      integer(c_size_t), value :: size
      integer(c_size_t), intent(out), optional :: needed
      integer(c_int32_t) :: status
    end function

    function structmd_save_checkpoint(sim, path) bind(C, name="structmd_save_checkpoint") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int32_t) :: status
    end function

    function structmd_load_checkpoint(sim, path) bind(C, name="structmd_load_checkpoint") result(status)
      import :: c_ptr, c_char, c_int32_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int32_t) :: status
    end function

    function structmd_get_counters(sim, buffer, size) bind(C, name="structmd_get_counters") result(status)
      import :: c_ptr, c_char, c_int32_t, c_size_t
      type(c_ptr), value :: sim
      character(kind=c_char), intent(inout) :: buffer(*)
      integer(c_size_t), value :: size
      integer(c_int32_t) :: status
    end function

    function c_strlen(text) bind(C, name="strlen") result(length)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: text
      integer(c_size_t) :: length
    end function
  end interface

contains

  !> The library version, "MAJOR.MINOR.PATCH".
  function structmd_version_f() result(text)
    character(len=:), allocatable :: text
    text = fortran_string(structmd_version())
  end function

  !> The message of the last failed call on sim ("" if none); sim = c_null_ptr gives the last failed
  !> structmd_create on this thread.
  function structmd_last_error_f(sim) result(text)
    type(c_ptr), intent(in) :: sim
    character(len=:), allocatable :: text
    text = fortran_string(structmd_last_error(sim))
  end function

  !> options_json: a JSON object such as '{"backend":"cpu"}', or '' for all defaults.
  function structmd_create_f(options_json, sim) result(status)
    character(len=*), intent(in) :: options_json
    type(c_ptr), intent(out) :: sim
    integer(c_int32_t) :: status
    status = structmd_create(c_string(options_json), sim)
  end function

  function structmd_load_file_f(sim, path) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    integer(c_int32_t) :: status
    status = structmd_load_file(sim, c_string(path))
  end function

  function structmd_load_plugin_f(path) result(status)
    character(len=*), intent(in) :: path
    integer(c_int32_t) :: status
    status = structmd_load_plugin(c_string(path))
  end function

  function structmd_save_checkpoint_f(sim, path) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    integer(c_int32_t) :: status
    status = structmd_save_checkpoint(sim, c_string(path))
  end function

  function structmd_load_checkpoint_f(sim, path) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    integer(c_int32_t) :: status
    status = structmd_load_checkpoint(sim, c_string(path))
  end function

  function structmd_load_string_f(sim, json) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: json
    integer(c_int32_t) :: status
    status = structmd_load_string(sim, c_string(json))
  end function

  !> term: "potential", "kinetic", "total" or the name of a topology.forceField entry.
  function structmd_get_energy_f(sim, term, value) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: term
    real(c_double), intent(out) :: value
    integer(c_int32_t) :: status
    status = structmd_get_energy(sim, c_string(term), value)
  end function

  !> path: "global.ensemble.temperature", "integrator.<name>.parameters.<key>" or
  !> "topology.forceField.<name>.parameters.<key>".
  function structmd_set_parameter_f(sim, path, value) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    real(c_double), intent(in) :: value
    integer(c_int32_t) :: status
    status = structmd_set_parameter(sim, c_string(path), value)
  end function

  function structmd_get_parameter_f(sim, path, value) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=*), intent(in) :: path
    real(c_double), intent(out) :: value
    integer(c_int32_t) :: status
    status = structmd_get_parameter(sim, c_string(path), value)
  end function

  !> ids(n), n the number of particles.
  function structmd_get_ids_f(sim, ids) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(inout) :: ids(:)
    integer(c_int32_t) :: status
    status = structmd_get_ids(sim, ids, size(ids, kind=c_int64_t))
  end function

  !> xyz(3,n): positions wrapped into the box [-L/2, L/2).
  function structmd_get_positions_f(sim, xyz) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(inout) :: xyz(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(xyz, 1) == 3) status = structmd_get_positions(sim, xyz, size(xyz, 2, kind=c_int64_t))
  end function

  !> v(3,n).
  function structmd_get_velocities_f(sim, v) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(inout) :: v(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(v, 1) == 3) status = structmd_get_velocities(sim, v, size(v, 2, kind=c_int64_t))
  end function

  !> f(3,n): total force on each particle, external forces included.
  function structmd_get_forces_f(sim, f) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(inout) :: f(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(f, 1) == 3) status = structmd_get_forces(sim, f, size(f, 2, kind=c_int64_t))
  end function

  !> e(n): potential energy per particle; the values sum to the potential energy.
  function structmd_get_particle_energies_f(sim, e) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(inout) :: e(:)
    integer(c_int32_t) :: status
    status = structmd_get_particle_energies(sim, e, size(e, kind=c_int64_t))
  end function

  !> m(n).
  function structmd_get_masses_f(sim, m) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(inout) :: m(:)
    integer(c_int32_t) :: status
    status = structmd_get_masses(sim, m, size(m, kind=c_int64_t))
  end function

  !> type_index(n): each particle's row in global.types, counted from 0 as in C.
  function structmd_get_types_f(sim, type_index) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int32_t), intent(inout) :: type_index(:)
    integer(c_int32_t) :: status
    status = structmd_get_types(sim, type_index, size(type_index, kind=c_int64_t))
  end function

  !> xyz(3,n).
  function structmd_set_positions_f(sim, xyz) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(in) :: xyz(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(xyz, 1) == 3) status = structmd_set_positions(sim, xyz, size(xyz, 2, kind=c_int64_t))
  end function

  !> v(3,n).
  function structmd_set_velocities_f(sim, v) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(in) :: v(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(v, 1) == 3) status = structmd_set_velocities(sim, v, size(v, 2, kind=c_int64_t))
  end function

  !> f(3,n): added to each particle's force at every force evaluation until replaced or cleared.
  function structmd_set_external_forces_f(sim, f) result(status)
    type(c_ptr), intent(in) :: sim
    real(c_double), intent(in) :: f(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(f, 1) == 3) status = structmd_set_external_forces(sim, f, size(f, 2, kind=c_int64_t))
  end function

  function structmd_clear_external_forces_f(sim) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int32_t) :: status
    status = structmd_set_external_forces(sim, n=0_c_int64_t)
  end function

  !> ids(m), xyz(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_get_positions_of_f(sim, ids, xyz) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(inout) :: xyz(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(xyz, 1) == 3 .and. size(xyz, 2) == size(ids)) &
      status = structmd_get_positions_of(sim, ids, size(ids, kind=c_int64_t), xyz)
  end function

  !> ids(m), v(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_get_velocities_of_f(sim, ids, v) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(inout) :: v(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(v, 1) == 3 .and. size(v, 2) == size(ids)) &
      status = structmd_get_velocities_of(sim, ids, size(ids, kind=c_int64_t), v)
  end function

  !> ids(m), f(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_get_forces_of_f(sim, ids, f) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(inout) :: f(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(f, 1) == 3 .and. size(f, 2) == size(ids)) &
      status = structmd_get_forces_of(sim, ids, size(ids, kind=c_int64_t), f)
  end function

  !> ids(m), xyz(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_set_positions_of_f(sim, ids, xyz) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(in) :: xyz(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(xyz, 1) == 3 .and. size(xyz, 2) == size(ids)) &
      status = structmd_set_positions_of(sim, ids, size(ids, kind=c_int64_t), xyz)
  end function

  !> ids(m), v(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_set_velocities_of_f(sim, ids, v) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(in) :: v(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(v, 1) == 3 .and. size(v, 2) == size(ids)) &
      status = structmd_set_velocities_of(sim, ids, size(ids, kind=c_int64_t), v)
  end function

  !> ids(m), f(3,m) in the order of ids: particle ids count from 0, as in C.
  function structmd_set_external_forces_of_f(sim, ids, f) result(status)
    type(c_ptr), intent(in) :: sim
    integer(c_int64_t), intent(in) :: ids(:)
    real(c_double), intent(in) :: f(:, :)
    integer(c_int32_t) :: status
    status = STRUCTMD_ERR_ARGUMENT
    if (size(f, 1) == 3 .and. size(f, 2) == size(ids)) &
      status = structmd_set_external_forces_of(sim, ids, size(ids, kind=c_int64_t), f)
  end function

  !> info: the JSON description of the handle (see structmd_get_info in the header).
  function structmd_get_info_f(sim, info) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=:), allocatable, intent(out) :: info
    integer(c_int32_t) :: status
    character(kind=c_char), allocatable :: buffer(:)
    integer(c_size_t) :: needed
    integer :: length

    info = ''
    needed = 0
    ! Asking with an empty buffer reports the size; its status says the buffer is too small.
    status = structmd_get_info(sim, size=0_c_size_t, needed=needed)
    if (needed == 0) return
    allocate (buffer(needed))
    status = structmd_get_info(sim, buffer, needed)
    if (status /= STRUCTMD_OK) return
    length = int(needed) - 1
    info = repeat(' ', length)
    if (length > 0) info = transfer(buffer(1:length), info)
  end function

  !> counters: the JSON text of structmd_get_counters (512 bytes always suffice).
  function structmd_get_counters_f(sim, counters) result(status)
    type(c_ptr), intent(in) :: sim
    character(len=:), allocatable, intent(out) :: counters
    integer(c_int32_t) :: status
    character(kind=c_char) :: buffer(512)
    integer :: length

    counters = ''
    status = structmd_get_counters(sim, buffer, int(size(buffer), c_size_t))
    if (status /= STRUCTMD_OK) return
    length = 0
    do while (buffer(length + 1) /= c_null_char)
      length = length + 1
    end do
    counters = repeat(' ', length)
    if (length > 0) counters = transfer(buffer(1:length), counters)
  end function

  !> s without trailing blanks, NUL-terminated for C.
  pure function c_string(s) result(text)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: text
    text = trim(s)//c_null_char
  end function

  !> A copy of the NUL-terminated C string text ('' for NULL).
  function fortran_string(text) result(s)
    type(c_ptr), intent(in) :: text
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: length

    if (.not. c_associated(text)) then
      s = ''
      return
    end if
    length = int(c_strlen(text))
    call c_f_pointer(text, chars, [length])
    allocate (character(len=length) :: s)
    if (length > 0) s = transfer(chars, s)
  end function

end module structmd
