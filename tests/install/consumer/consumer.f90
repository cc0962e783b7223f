! A Fortran host of the installed package: `use structmd` from the installed module, linked through
! structmd::fortran or pkg-config's structmd-fortran; creates a handle and checks the ABI version.
program consumer_fortran
  use, intrinsic :: iso_c_binding, only: c_ptr
  use structmd
  implicit none
  type(c_ptr) :: sim

  if (structmd_abi_version() /= STRUCTMD_BINDING_ABI_VERSION) then
    print '(a, i0, a, i0)', 'ABI ', structmd_abi_version(), ', module ', STRUCTMD_BINDING_ABI_VERSION
    error stop 1
  end if
  if (structmd_create_f('{"backend": "cpu"}', sim) /= STRUCTMD_OK) then
    print '(a)', structmd_last_error_f(sim)
    error stop 1
  end if
  call structmd_destroy(sim)
  print '(a, a)', 'structmd (Fortran) ', structmd_version_f()
end program
