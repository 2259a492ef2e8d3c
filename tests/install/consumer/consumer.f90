! A Fortran program outside the project, compiled with the installed module source
! (share/anitet/fortran/anitet.f90) and linked with pkg-config's flags.
program consumer_fortran
  use, intrinsic :: iso_c_binding
  use anitet
  implicit none
  type(c_ptr) :: surface
  real(c_double) :: xyz(3, 4)
  integer(c_int32_t) :: tri(3, 4)
  xyz = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0], [3, 4])
  tri = reshape([1, 3, 2, 1, 2, 4, 2, 3, 4, 1, 4, 3], [3, 4])
  if (anitet_surface_create(xyz, tri, surface) /= ANITET_OK) error stop 1
  if (anitet_surface_validate(surface) /= ANITET_OK) error stop 2
  call anitet_surface_destroy(surface)
  print '(a, a)', "Fortran consumer: anitet ", anitet_version()
end program consumer_fortran
