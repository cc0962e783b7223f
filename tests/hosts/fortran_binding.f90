! Test of the Fortran binding (module structmd): every _f wrapper on a three-particle system whose
! forces are known in closed form, plus the error paths a Fortran host meets (bad options, missing
! file, unknown energy term, wrongly shaped array). Exits non-zero listing each failed check.
!
! usage: test_fortran_binding [OPTIONS_JSON]   (default {"backend":"cpu","precision":"double"})
! Exit status 77 when the requested backend is not available (the test is then skipped).
program fortran_binding
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int32_t, c_int64_t, c_double
  use, intrinsic :: iso_fortran_env, only: error_unit
  use structmd
  implicit none

  ! Particles 0 and 1 are bonded (harmonic) and within the LJ cutoff of each other, on the x axis;
  ! particle 2 is out of reach of both.
  real(c_double), parameter :: box_length = 10, bond_k = 100, bond_r0 = 1, separation = 1.1_c_double
  real(c_double), parameter :: initial_positions(3, 3) = reshape([0.0_c_double, 0.0_c_double, 0.0_c_double, &
                                                                   separation, 0.0_c_double, 0.0_c_double, &
                                                                   4.8_c_double, 0.2_c_double, -4.9_c_double], [3, 3])
  real(c_double), parameter :: initial_velocities(3, 3) = reshape([0.0_c_double, 0.0_c_double, 0.0_c_double, &
                                                                    0.1_c_double, 0.0_c_double, 0.0_c_double, &
                                                                    0.0_c_double, -0.2_c_double, 0.3_c_double], [3, 3])
  character(len=*), parameter :: input = &
    '{"system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "fortran", "seed": 1}}},'// &
    ' "global": {"units": {"type": ["Units", "None"]},'// &
    '  "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],'// &
    '            "data": [["A", 2.0, 0.5, 0.0], ["B", 1.0, 0.5, 0.0]]},'// &
    '  "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],'// &
    '               "data": [[[10.0, 10.0, 10.0], 1.0]]}},'// &
    ' "integrator": {"vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},'// &
    '  "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],'// &
    '               "data": [[1, "vv", 100]]}},'// &
    ' "state": {"labels": ["id", "position", "velocity"], "data": ['// &
    '  [0, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]], [1, [1.1, 0.0, 0.0], [0.1, 0.0, 0.0]],'// &
    '  [2, [4.8, 0.2, -4.9], [0.0, -0.2, 0.3]]]},'// &
    ' "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "B"], [2, "B"]]},'// &
    '  "forceField": {'// &
    '   "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},'// &
    '   "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.5, "condition": "all"},'// &
    '          "labels": ["name_i", "name_j", "epsilon", "sigma"],'// &
    '          "data": [["A", "A", 1.0, 1.0], ["A", "B", 1.0, 1.0], ["B", "B", 1.0, 1.0]]},'// &
    '   "bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 100.0, "r0": 1.0},'// &
    '             "labels": ["id_i", "id_j"], "data": [[0, 1]]}}}}'
  real(c_double), parameter :: tolerance = 1e-9_c_double

  character(len=:), allocatable :: options, info
  type(c_ptr) :: sim = c_null_ptr, rejected = c_null_ptr
  integer(c_int32_t) :: status
  integer :: failures = 0

  options = '{"backend":"cpu","precision":"double"}'
  if (command_argument_count() >= 1) options = argument(1)

  status = structmd_create_f('{"backend":"cpu","no_such_option":1}', rejected)
  call expect(status == STRUCTMD_ERR_ARGUMENT, 'structmd_create_f rejects an unknown option')
  call expect(len(structmd_last_error_f(c_null_ptr)) > 0, 'structmd_last_error_f(c_null_ptr) explains the rejection')

  status = structmd_create_f(options, sim)
  if (status == STRUCTMD_ERR_DEVICE .or. status == STRUCTMD_ERR_UNSUPPORTED) then
    write (error_unit, '(2a)') 'backend not available, skipping: ', structmd_last_error_f(c_null_ptr)
    stop 77
  end if
  if (status /= STRUCTMD_OK) then
    write (error_unit, '(3a)') 'structmd_create_f(', options, ') failed: ', structmd_last_error_f(c_null_ptr)
    stop 1
  end if

  call check_error_paths()
  call require(structmd_load_string_f(sim, input), 'structmd_load_string_f')
  call require(structmd_get_info_f(sim, info), 'structmd_get_info_f')
  call expect(index(info, '"particles"') > 0 .and. info(len(info):len(info)) == '}', &
              'structmd_get_info_f returns the whole JSON object')
  call check_particle_data()
  call check_forces_and_energies()
  call check_setters()
  call check_coupling()
  call structmd_destroy(sim)

  if (failures > 0) then
    write (error_unit, '(i0, a)') failures, ' check(s) failed'
    stop 1
  end if
  write (*, '(a)') 'all checks passed'

contains

  function argument(position) result(value)
    integer, intent(in) :: position
    character(len=:), allocatable :: value
    integer :: length
    call get_command_argument(position, length=length)
    allocate (character(len=length) :: value)
    call get_command_argument(position, value)
  end function

  subroutine expect(condition, what)
    logical, intent(in) :: condition
    character(len=*), intent(in) :: what
    if (condition) return
    failures = failures + 1
    write (error_unit, '(2a)') 'FAILED: ', what
  end subroutine

  !> Stops the test when a call the rest depends on fails.
  subroutine require(call_status, call_name)
    integer(c_int32_t), intent(in) :: call_status
    character(len=*), intent(in) :: call_name
    if (call_status == STRUCTMD_OK) return
    write (error_unit, '(3a, i0, 2a)') 'FAILED: ', call_name, ' returned ', call_status, ': ', &
      structmd_last_error_f(sim)
    stop 1
  end subroutine

  subroutine check_error_paths()
    real(c_double) :: value
    call expect(structmd_step(sim, 1_c_int64_t) == STRUCTMD_ERR_STATE, 'structmd_step before a load is a state error')
    call expect(structmd_load_file_f(sim, '/nonexistent/structmd/input.json') == STRUCTMD_ERR_IO, &
                'structmd_load_file_f of a missing file is an I/O error')
    call expect(index(structmd_last_error_f(sim), '/nonexistent/structmd/input.json') > 0, &
                'structmd_last_error_f names the missing file')
    call expect(structmd_load_string_f(sim, '{"system": ') == STRUCTMD_ERR_INPUT, &
                'structmd_load_string_f of malformed JSON is an input error')
    call expect(structmd_get_energy_f(sim, 'potential', value) == STRUCTMD_ERR_STATE, &
                'structmd_get_energy_f before a load is a state error')
  end subroutine

  subroutine check_particle_data()
    integer(c_int64_t) :: n
    integer(c_int64_t), allocatable :: ids(:)
    integer(c_int32_t), allocatable :: types(:)
    real(c_double), allocatable :: positions(:, :), velocities(:, :), masses(:), too_wide(:, :)

    call require(structmd_get_num_particles(sim, n), 'structmd_get_num_particles')
    call expect(n == 3, 'three particles loaded')
    allocate (ids(n), types(n), positions(3, n), velocities(3, n), masses(n), too_wide(4, n))

    call require(structmd_get_ids_f(sim, ids), 'structmd_get_ids_f')
    call expect(all(ids == [0, 1, 2]), 'structmd_get_ids_f gives 0, 1, 2')
    call require(structmd_get_types_f(sim, types), 'structmd_get_types_f')
    call expect(all(types == [0, 1, 1]), 'structmd_get_types_f gives the rows of global.types from 0')
    call require(structmd_get_masses_f(sim, masses), 'structmd_get_masses_f')
    call expect(all(masses == [2, 1, 1]), 'structmd_get_masses_f gives the masses of the types')
    call require(structmd_get_positions_f(sim, positions), 'structmd_get_positions_f')
    call expect(all(abs(positions - initial_positions) <= tolerance), 'structmd_get_positions_f returns x(3,n)')
    call require(structmd_get_velocities_f(sim, velocities), 'structmd_get_velocities_f')
    call expect(all(abs(velocities - initial_velocities) <= tolerance), 'structmd_get_velocities_f returns v(3,n)')

    too_wide = -1
    call expect(structmd_get_positions_f(sim, too_wide) == STRUCTMD_ERR_ARGUMENT .and. all(too_wide == -1), &
                'structmd_get_positions_f refuses an array not shaped (3, n) and writes nothing')
    call expect(structmd_get_masses_f(sim, masses(1:2)) == STRUCTMD_ERR_ARGUMENT, &
                'structmd_get_masses_f refuses an array of the wrong length')
  end subroutine

  !> Forces from the closed forms: bond K (r - r0) and LJ 4 (12 r^-13 - 6 r^-7) along x, both acting
  !> on particles 0 and 1 in opposite directions; nothing on particle 2.
  subroutine check_forces_and_energies()
    real(c_double) :: forces(3, 3), forces_with_field(3, 3), field(3, 3), particle_energies(3)
    real(c_double) :: expected_force_on_0, potential, bond_energy, lj_energy, kinetic, total
    real(c_double) :: w(9), pressure, lengths(3)

    expected_force_on_0 = bond_k*(separation - bond_r0) - 4*(12/separation**13 - 6/separation**7)
    call require(structmd_compute(sim, ior(STRUCTMD_FORCES, ior(STRUCTMD_ENERGY, STRUCTMD_VIRIAL))), &
                 'structmd_compute')
    call require(structmd_get_forces_f(sim, forces), 'structmd_get_forces_f')
    call expect(abs(forces(1, 1) - expected_force_on_0) <= tolerance*abs(expected_force_on_0) &
                .and. all(forces(2:3, 1) == 0), 'force on particle 0 is the bond plus LJ force along x')
    call expect(all(abs(forces(:, 2) + forces(:, 1)) <= tolerance*abs(expected_force_on_0)), &
                'force on particle 1 is opposite to the force on particle 0')
    call expect(all(forces(:, 3) == 0), 'no force on the isolated particle 2')

    call require(structmd_get_energy_f(sim, 'potential', potential), 'structmd_get_energy_f(potential)')
    ! Trailing blanks of a Fortran string are not part of the term's name.
    call require(structmd_get_energy_f(sim, 'bonds     ', bond_energy), 'structmd_get_energy_f(bonds)')
    call require(structmd_get_energy_f(sim, 'lj', lj_energy), 'structmd_get_energy_f(lj)')
    call expect(abs(bond_energy - bond_k/2*(separation - bond_r0)**2) <= tolerance, 'bond energy 1/2 K (r - r0)^2')
    call expect(abs(lj_energy - 4*(separation**(-12) - separation**(-6))) <= tolerance, 'LJ energy 4 (r^-12 - r^-6)')
    call expect(abs(potential - bond_energy - lj_energy) <= tolerance, 'potential energy is the sum of its terms')
    call require(structmd_get_particle_energies_f(sim, particle_energies), 'structmd_get_particle_energies_f')
    call expect(abs(sum(particle_energies) - potential) <= tolerance .and. particle_energies(3) == 0, &
                'particle energies sum to the potential energy')
    call require(structmd_get_energy_f(sim, 'kinetic', kinetic), 'structmd_get_energy_f(kinetic)')
    call expect(abs(kinetic - 0.5_c_double*(2*sum(initial_velocities(:, 1)**2) + sum(initial_velocities(:, 2:3)**2))) &
                <= tolerance, 'kinetic energy 1/2 m v^2 with each particle''s mass')
    call require(structmd_get_energy_f(sim, 'total', total), 'structmd_get_energy_f(total)')
    call expect(abs(total - potential - kinetic) <= tolerance, 'total energy is potential plus kinetic')
    call expect(structmd_get_energy_f(sim, 'no_such_term', total) == STRUCTMD_ERR_ARGUMENT, &
                'structmd_get_energy_f of an unknown term is an argument error')
    call expect(index(structmd_last_error_f(sim), 'no_such_term') > 0, 'structmd_last_error_f names the unknown term')

    ! Row-major W: only W_xx = (x_0 - x_1) F_0x is non-zero here.
    call require(structmd_get_virial(sim, w), 'structmd_get_virial')
    call expect(abs(w(1) + separation*expected_force_on_0) <= tolerance*abs(w(1)) .and. all(w(2:9) == 0), &
                'virial W_xx = (x_0 - x_1) F_0x')
    call require(structmd_get_box(sim, lengths), 'structmd_get_box')
    call expect(all(lengths == box_length), 'structmd_get_box gives the ensemble box')
    call require(structmd_get_pressure(sim, pressure), 'structmd_get_pressure')
    call expect(abs(pressure - (2*kinetic + w(1))/(3*box_length**3)) <= tolerance, 'pressure (2K + tr W) / (3V)')

    field = reshape([1, 2, 3, 4, 5, 6, 7, 8, 9], [3, 3])*0.25_c_double
    call require(structmd_set_external_forces_f(sim, field), 'structmd_set_external_forces_f')
    call require(structmd_get_forces_f(sim, forces_with_field), 'structmd_get_forces_f with a field')
    call expect(all(abs(forces_with_field - forces - field) <= tolerance*maxval(abs(forces_with_field))), &
                'the external field x(3,n) adds to each particle''s force')
    call require(structmd_clear_external_forces_f(sim), 'structmd_clear_external_forces_f')
    call require(structmd_get_forces_f(sim, forces_with_field), 'structmd_get_forces_f after clearing')
    call expect(all(forces_with_field == forces), 'clearing the field restores the forces')
  end subroutine

  subroutine check_setters()
    real(c_double) :: positions(3, 3), moved(3, 3), velocities(3, 3), time
    integer(c_int64_t) :: step

    moved = initial_positions
    moved(:, 3) = [1.0_c_double, 3.0_c_double, 3.0_c_double]
    moved(1, 1) = box_length - 0.5_c_double
    call require(structmd_set_positions_f(sim, moved), 'structmd_set_positions_f')
    call require(structmd_get_positions_f(sim, positions), 'structmd_get_positions_f after setting')
    moved(1, 1) = moved(1, 1) - box_length
    call expect(all(abs(positions - moved) <= tolerance), 'structmd_set_positions_f stores x(3,n), wrapped into the box')

    call require(structmd_set_velocities_f(sim, 2*initial_velocities), 'structmd_set_velocities_f')
    call require(structmd_get_velocities_f(sim, velocities), 'structmd_get_velocities_f after setting')
    call expect(all(abs(velocities - 2*initial_velocities) <= tolerance), 'structmd_set_velocities_f stores v(3,n)')

    call require(structmd_step(sim, 5_c_int64_t), 'structmd_step')
    call require(structmd_get_step(sim, step), 'structmd_get_step')
    call require(structmd_get_time(sim, time), 'structmd_get_time')
    call expect(step == 5 .and. abs(time - 5*0.001_c_double) <= tolerance, 'five steps of 0.001 taken')
  end subroutine

  subroutine check_coupling()
    real(c_double) :: all_positions(3, 3), some(3, 2), field(3, 2), forces(3, 3), forces_with_field(3, 3)
    real(c_double) :: k, bond_energy, external, total, potential, kinetic
    integer(c_int64_t), parameter :: ids(2) = [2_c_int64_t, 0_c_int64_t]

    call require(structmd_get_positions_f(sim, all_positions), 'structmd_get_positions_f')
    call require(structmd_get_positions_of_f(sim, ids, some), 'structmd_get_positions_of_f')
    call expect(all(some(:, 1) == all_positions(:, 3)) .and. all(some(:, 2) == all_positions(:, 1)), &
                'structmd_get_positions_of_f gives x(3,m) in the order of the ids')
    call expect(structmd_get_positions_of_f(sim, [1_c_int64_t, 1_c_int64_t], some) == STRUCTMD_ERR_ARGUMENT, &
                'an id given twice is an argument error')
    call require(structmd_get_forces_f(sim, forces), 'structmd_get_forces_f')
    field = reshape([1, 2, 3, 4, 5, 6], [3, 2])*0.5_c_double
    call require(structmd_set_external_forces_of_f(sim, ids, field), 'structmd_set_external_forces_of_f')
    call require(structmd_get_forces_f(sim, forces_with_field), 'structmd_get_forces_f with a subset field')
    call expect(all(abs(forces_with_field(:, 3) - forces(:, 3) - field(:, 1)) <= tolerance) .and. &
                all(abs(forces_with_field(:, 1) - forces(:, 1) - field(:, 2)) <= tolerance) .and. &
                all(forces_with_field(:, 2) == forces(:, 2)), 'the subset field acts on those ids only')
    call require(structmd_set_external_energy(sim, 1.5_c_double), 'structmd_set_external_energy')
    call require(structmd_get_energy_f(sim, 'external', external), 'structmd_get_energy_f(external)')
    call require(structmd_get_energy_f(sim, 'potential', potential), 'structmd_get_energy_f(potential)')
    call require(structmd_get_energy_f(sim, 'kinetic', kinetic), 'structmd_get_energy_f(kinetic)')
    call require(structmd_get_energy_f(sim, 'total', total), 'structmd_get_energy_f(total)')
    call expect(external == 1.5_c_double .and. abs(total - potential - kinetic - 1.5_c_double) <= tolerance, &
                'the external energy is its own term and part of the total')
    call require(structmd_clear_external_forces_f(sim), 'structmd_clear_external_forces_f')

    call require(structmd_get_energy_f(sim, 'bonds', bond_energy), 'structmd_get_energy_f(bonds)')
    call require(structmd_get_parameter_f(sim, 'topology.forceField.bonds.parameters.K', k), &
                 'structmd_get_parameter_f')
    call expect(k == 100.0_c_double, 'structmd_get_parameter_f reads the input''s K')
    call require(structmd_set_parameter_f(sim, 'topology.forceField.bonds.parameters.K', 2*k), &
                 'structmd_set_parameter_f')
    call require(structmd_get_energy_f(sim, 'bonds', potential), 'structmd_get_energy_f(bonds) after the change')
    call expect(abs(potential - 2*bond_energy) <= tolerance*abs(potential), 'doubling K doubles the bond energy')
    call expect(structmd_set_parameter_f(sim, 'integrator.vv.parameters.noSuchKey', 1.0_c_double) == &
                STRUCTMD_ERR_ARGUMENT, 'an unknown parameter is an argument error')
  end subroutine

end program fortran_binding
