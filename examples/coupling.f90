! coupling.f90 - drives structmd from a Fortran host through the structmd module, the way a coupled
! code does: step, read forces and energies, answer with an external force field that depends on the
! positions, step again. Then the same tether as a force callback (the engine calls the Fortran function
! inside its step loop), a region read by particle id, and a time step changed at run time.
!
! The field is a harmonic tether toward the box centre, f_i = -k x_i (the box spans [-L/2, L/2), so
! its centre is the origin). At the end the program checks its own results and stops with a non-zero
! code, saying what failed, if any check does:
!   - the forces with the field minus the forces with the field cleared equal the field;
!   - every energy read is finite;
!   - the step counter advanced by exactly the steps taken;
!   - the forces with the callback minus those without it equal its forces, and it runs once per step;
!   - positions read for a region by id equal those of the whole array;
!   - after halving integrator.vv.parameters.timeStep (when the input has it), time advances by it.
!
! usage: example_coupling_fortran [INPUT_JSON [OPTIONS_JSON]]
!   INPUT_JSON    default: the bead_spring.json bundled with the examples (STRUCTMD_EXAMPLE_INPUT)
!   OPTIONS_JSON  structmd_create options, default {"backend":"auto"}
! Exit status: 0 on success, 1 on any failure, 77 when the requested backend is not available in this
! build or on this machine (the exit code test drivers read as "skipped").
! The source is preprocessed: the build passes the default input path as STRUCTMD_EXAMPLE_INPUT.
! The tether as a force callback (the abstract interface structmd_force_callback of the module).
module tether_callback
  use, intrinsic :: iso_c_binding, only: c_ptr, c_f_pointer, c_int32_t, c_int64_t, c_double
  implicit none
  ! Weak enough to leave the dynamics of the bundled inputs almost untouched.
  real(c_double), parameter :: tether_stiffness = 0.05_c_double
  integer :: tether_calls = 0
  integer(c_int64_t) :: tether_last_step = -1

contains

  function tether_forces(positions, forces, n, energy, virial, step, user_data) bind(C) result(status)
    integer(c_int64_t), value :: n
    real(c_double), intent(in) :: positions(3, n)
    real(c_double), intent(inout) :: forces(3, n)
    real(c_double), intent(inout) :: energy
    real(c_double), intent(inout) :: virial(9)
    integer(c_int64_t), value :: step
    type(c_ptr), value :: user_data
    integer(c_int32_t) :: status
    real(c_double), pointer :: stiffness  ! user_data: the host's stiffness, passed by address
    integer :: c

    call c_f_pointer(user_data, stiffness)
    forces = forces - stiffness*positions
    energy = energy + 0.5_c_double*stiffness*sum(positions**2)
    do c = 1, 3
      virial(4*c - 3) = virial(4*c - 3) - stiffness*sum(positions(c, :)**2)
    end do
    tether_calls = tether_calls + 1
    tether_last_step = step
    status = 0
  end function

end module tether_callback

program coupling
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_null_funptr, c_funloc, c_loc, c_int32_t, c_int64_t, &
                                         c_double
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use structmd
  use tether_callback, only: tether_stiffness, tether_calls, tether_last_step, tether_forces
  implicit none

#ifndef STRUCTMD_EXAMPLE_INPUT
#define STRUCTMD_EXAMPLE_INPUT "bead_spring.json"
#endif

  integer, parameter :: coupling_rounds = 20
  integer(c_int64_t), parameter :: steps_per_round = 10
  integer, parameter :: exit_skipped = 77
  ! Forces are accumulated in the engine's precision, so the field is recovered to that precision.
  real(c_double), parameter :: double_precision_tolerance = 1e-9_c_double
  real(c_double), parameter :: single_precision_tolerance = 1e-5_c_double

  real(c_double), target :: callback_stiffness = tether_stiffness
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
      if (index(info, '"precision":"double"') > 0) then
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

    ! The tether again, as a force callback the engine calls at each new configuration.
    if (.not. succeeded(structmd_get_positions_f(sim, positions), 'structmd_get_positions_f')) return
    field = -tether_stiffness*positions
    if (.not. succeeded(structmd_set_force_callback(sim, c_funloc(tether_forces), c_loc(callback_stiffness)), &
                        'structmd_set_force_callback')) return
    if (.not. succeeded(structmd_get_forces_f(sim, forces), 'structmd_get_forces_f')) return
    error = field_recovery_error(forces, forces_without_field, field)
    if (.not. (error <= tolerance)) then
      write (error_unit, '(a, g12.4)') 'FAILED: the callback''s forces recovered to (relative)', error
      failures_found = failures_found + 1
    end if
    if (.not. succeeded(structmd_step(sim, steps_per_round), 'structmd_step')) return
    if (tether_calls /= steps_per_round + 1) then
      write (error_unit, '(a, i0, a, i0, a)') 'FAILED: the callback ran ', tether_calls, ' times over ', &
        steps_per_round, ' steps'
      failures_found = failures_found + 1
    end if
    write (*, '(a, es10.3, a, i0, a, i0)') 'callback: forces recovered to ', error, ' relative, ', tether_calls, &
      ' calls, the last at step ', tether_last_step
    if (.not. succeeded(structmd_set_force_callback(sim, c_null_funptr, c_null_ptr), &
                        'structmd_set_force_callback')) return

    failures_found = failures_found + region_and_parameter(n)
    failed_checks = failures_found
  end function

  !> Every tenth particle read by id against the whole array, then the time step halved at run time;
  !> returns the number of failed checks.
  integer function region_and_parameter(n) result(failures_found)
    integer(c_int64_t), intent(in) :: n
    character(len=*), parameter :: time_step_path = 'integrator.vv.parameters.timeStep'
    integer(c_int64_t), allocatable :: region(:)
    real(c_double), allocatable :: positions(:, :), region_positions(:, :)
    real(c_double) :: dt, before, after
    integer(c_int64_t) :: k

    failures_found = 0
    allocate (region((n + 9)/10))
    do k = 1, size(region, kind=c_int64_t)
      region(k) = 10*(k - 1)
    end do
    allocate (positions(3, n), region_positions(3, size(region)))
    if (.not. succeeded(structmd_get_positions_f(sim, positions), 'structmd_get_positions_f')) return
    if (.not. succeeded(structmd_get_positions_of_f(sim, region, region_positions), 'structmd_get_positions_of_f')) &
      return
    if (any(region_positions /= positions(:, region + 1))) then
      write (error_unit, '(a)') 'FAILED: positions read by id differ from the whole array'
      failures_found = failures_found + 1
    end if
    write (*, '(a, i0, a)') 'region: ', size(region), ' particles read by id'

    if (structmd_get_parameter_f(sim, time_step_path, dt) /= STRUCTMD_OK) then
      write (*, '(3a)') 'parameter: this input has no ', time_step_path, '; not changed'
      return
    end if
    if (.not. succeeded(structmd_set_parameter_f(sim, time_step_path, 0.5_c_double*dt), 'structmd_set_parameter_f')) &
      return
    if (.not. succeeded(structmd_get_time(sim, before), 'structmd_get_time')) return
    if (.not. succeeded(structmd_step(sim, steps_per_round), 'structmd_step')) return
    if (.not. succeeded(structmd_get_time(sim, after), 'structmd_get_time')) return
    if (abs(after - before - steps_per_round*0.5_c_double*dt) > 1e-9_c_double*max(1.0_c_double, after)) then
      write (error_unit, '(a, g14.6)') 'FAILED: time advanced by ', after - before
      failures_found = failures_found + 1
    end if
    if (.not. succeeded(structmd_set_parameter_f(sim, time_step_path, dt), 'structmd_set_parameter_f')) return
    write (*, '(3a, g12.4)') 'parameter: ', time_step_path, ' halved, then back to ', dt
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
