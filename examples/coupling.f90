! coupling.f90 - drives structmd from a Fortran host through the structmd module, the way a coupled
! code does: step, read forces and energies, answer with an external force field that depends on the
! positions, step again.
!
! The field is a harmonic tether toward the box centre, f_i = -k x_i (the box spans [-L/2, L/2), so
! its centre is the origin). At the end the program checks its own results and stops with a non-zero
! code, saying what failed, if any check does:
!   - the forces with the field minus the forces with the field cleared equal the field;
!   - every energy read is finite;
!   - the step counter advanced by exactly the steps taken.
!
! usage: example_coupling_fortran [INPUT_JSON [OPTIONS_JSON]]
!   INPUT_JSON    default: the bead_spring.json bundled with the examples (STRUCTMD_EXAMPLE_INPUT)
!   OPTIONS_JSON  structmd_create options, default {"backend":"auto"}
! Exit status: 0 on success, 1 on any failure, 77 when the requested backend is not available in this
! build or on this machine (the exit code test drivers read as "skipped").
! The source is preprocessed: the build passes the default input path as STRUCTMD_EXAMPLE_INPUT.
program coupling
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int32_t, c_int64_t, c_double
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use structmd
  implicit none

#ifndef STRUCTMD_EXAMPLE_INPUT
#define STRUCTMD_EXAMPLE_INPUT "bead_spring.json"
#endif

  integer, parameter :: coupling_rounds = 20
  integer(c_int64_t), parameter :: steps_per_round = 10
  integer, parameter :: exit_skipped = 77
  ! Weak enough to leave the dynamics of the bundled inputs almost untouched.
  real(c_double), parameter :: tether_stiffness = 0.05_c_double
  ! Forces are accumulated in the engine's precision, so the field is recovered to that precision.
  real(c_double), parameter :: double_precision_tolerance = 1e-9_c_double
  real(c_double), parameter :: single_precision_tolerance = 1e-5_c_double

  character(len=:), allocatable :: input_path, options, info
  type(c_ptr) :: sim = c_null_ptr
  integer(c_int32_t) :: status
  integer :: failures

  input_path = argument_or(1, STRUCTMD_EXAMPLE_INPUT)
  options = argument_or(2, '{"backend":"auto"}')

  if (structmd_abi_version() /= STRUCTMD_BINDING_ABI_VERSION) then
    write (error_unit, '(a, i0, a, i0)') 'FAILED: library ABI version ', structmd_abi_version(), &
      ', this program was built against ', STRUCTMD_BINDING_ABI_VERSION
    stop 1
  end if
  write (*, '(6a)') 'structmd ', structmd_version_f(), ', options ', options, ', input ', input_path

  status = structmd_create_f(options, sim)
  if (status /= STRUCTMD_OK) then
    write (error_unit, '(3a, i0, 2a)') 'structmd_create_f(', options, ') returned status ', status, ': ', &
      structmd_last_error_f(c_null_ptr)
    if (status == STRUCTMD_ERR_DEVICE .or. status == STRUCTMD_ERR_UNSUPPORTED) stop exit_skipped
    stop 1
  end if

  failures = -1
  if (succeeded(structmd_load_file_f(sim, input_path), 'structmd_load_file_f')) then
    if (succeeded(structmd_get_info_f(sim, info), 'structmd_get_info_f')) then
      write (*, '(a)') info
      if (index(info, '"double"') > 0) then
        failures = couple(double_precision_tolerance)
      else
        failures = couple(single_precision_tolerance)
      end if
    end if
  end if
  call structmd_destroy(sim)

  if (failures == 0) then
    write (*, '(a)') 'all checks passed'
  else
    if (failures > 0) write (error_unit, '(i0, a)') failures, ' check(s) failed'
    stop 1
  end if

contains

  !> Command-line argument position, or fallback when it is not given.
  function argument_or(position, fallback) result(value)
    integer, intent(in) :: position
    character(len=*), intent(in) :: fallback
    character(len=:), allocatable :: value
    integer :: length

    if (command_argument_count() < position) then
      value = fallback
      return
    end if
    call get_command_argument(position, length=length)
    allocate (character(len=length) :: value)
    call get_command_argument(position, value)
  end function

  !> Prints the failed call and the library's message; returns whether status is STRUCTMD_OK.
  logical function succeeded(status, call_name)
    integer(c_int32_t), intent(in) :: status
    character(len=*), intent(in) :: call_name

    succeeded = status == STRUCTMD_OK
    if (.not. succeeded) write (error_unit, '(3a, i0, 2a)') 'FAILED: ', call_name, ' returned status ', status, &
      ': ', structmd_last_error_f(sim)
  end function

  !> Runs the coupling loop and the checks on the loaded handle; returns the number of failed checks,
  !> or -1 when a call failed.
  integer function couple(tolerance) result(failed_checks)
    real(c_double), intent(in) :: tolerance
    real(c_double), allocatable :: positions(:, :), forces(:, :), forces_without_field(:, :), field(:, :)
    real(c_double) :: potential, kinetic, error
    integer(c_int64_t) :: n, first_step, last_step, expected_step
    integer :: round, failures_found

    failed_checks = -1
    failures_found = 0
    if (.not. succeeded(structmd_get_num_particles(sim, n), 'structmd_get_num_particles')) return
    if (.not. succeeded(structmd_get_step(sim, first_step), 'structmd_get_step')) return
    allocate (positions(3, n), forces(3, n), forces_without_field(3, n), field(3, n))

    last_step = first_step
    write (*, '(a8, 3a17)') 'step', 'potential', 'kinetic', 'max |force|'
    do round = 1, coupling_rounds
      if (.not. succeeded(structmd_step(sim, steps_per_round), 'structmd_step')) return
      if (.not. succeeded(structmd_get_forces_f(sim, forces), 'structmd_get_forces_f')) return
      if (.not. succeeded(structmd_get_energy_f(sim, 'potential', potential), 'structmd_get_energy_f')) return
      if (.not. succeeded(structmd_get_energy_f(sim, 'kinetic', kinetic), 'structmd_get_energy_f')) return
      if (.not. (ieee_is_finite(potential) .and. ieee_is_finite(kinetic))) then
        write (error_unit, '(a, i0, a, 2g17.8)') 'FAILED: energies not finite after round ', round, &
          ': potential, kinetic', potential, kinetic
        failures_found = failures_found + 1
      end if

      if (.not. succeeded(structmd_get_positions_f(sim, positions), 'structmd_get_positions_f')) return
      field = -tether_stiffness*positions
      if (.not. succeeded(structmd_set_external_forces_f(sim, field), 'structmd_set_external_forces_f')) return

      if (.not. succeeded(structmd_get_step(sim, last_step), 'structmd_get_step')) return
      write (*, '(i8, 3g17.8)') last_step, potential, kinetic, maxval(abs(forces))
    end do

    expected_step = first_step + coupling_rounds*steps_per_round
    if (last_step /= expected_step) then
      write (error_unit, '(a, i0, a, i0)') 'FAILED: step counter is ', last_step, ', expected ', expected_step
      failures_found = failures_found + 1
    end if

    ! The field set in the last round is still in force; compare with the forces once it is cleared.
    if (.not. succeeded(structmd_get_forces_f(sim, forces), 'structmd_get_forces_f')) return
    if (.not. succeeded(structmd_clear_external_forces_f(sim), 'structmd_clear_external_forces_f')) return
    if (.not. succeeded(structmd_get_forces_f(sim, forces_without_field), 'structmd_get_forces_f')) return
    error = field_recovery_error(forces, forces_without_field, field)
    if (.not. (error <= tolerance)) then
      write (error_unit, '(a, g12.4, a, g12.4)') 'FAILED: forces with the field minus forces without it differ '// &
        'from the field by (relative)', error, ', more than', tolerance
      failures_found = failures_found + 1
    end if
    write (*, '(a, es10.3, a, es10.3, a)') 'field recovered from the forces to ', error, &
      ' relative (tolerance ', tolerance, ')'
    failed_checks = failures_found
  end function

  !> Largest |with_field - without_field - field| relative to the largest of the three magnitudes, per
  !> component.
  real(c_double) function field_recovery_error(with_field, without_field, field) result(worst)
    real(c_double), intent(in) :: with_field(:, :), without_field(:, :), field(:, :)
    real(c_double) :: scale, error
    integer(c_int64_t) :: i, c

    worst = 0
    do i = 1, size(field, 2, kind=c_int64_t)
      do c = 1, 3
        scale = max(abs(field(c, i)), abs(with_field(c, i)), abs(without_field(c, i)))
        if (scale <= 0) cycle
        error = abs(with_field(c, i) - without_field(c, i) - field(c, i))/scale
        if (ieee_is_nan(error)) then
          worst = error
          return
        end if
        worst = max(worst, error)
      end do
    end do
  end function

end program coupling
