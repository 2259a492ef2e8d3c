! A Fortran program outside the project, built against an installed anitet (the module anitet.mod
! and libanitet_fortran.a, through pkg-config anitet-fortran or find_package(anitet COMPONENTS
! fortran)): it meshes a unit cube, reads the tets back 1-based and checks the mesh.
program consumer_fortran
  use, intrinsic :: iso_c_binding
  use anitet
  implicit none
  type(c_ptr) :: surface, metric, mesh
  type(anitet_quality_t) :: quality
  real(c_double) :: xyz(3, 8)
  integer(c_int32_t) :: tri(3, 12)
  integer(c_int32_t), allocatable :: tets(:, :)
  integer :: i
  ! Corner i - 1 = (x, y, z) in binary; two outward triangles per face, 1-based.
  do i = 1, 8
    xyz(:, i) = [real(iand(i - 1, 1), c_double), real(iand(i - 1, 2) / 2, c_double), &
                 real(iand(i - 1, 4) / 4, c_double)]
  end do
  tri = reshape([1, 3, 4, 1, 4, 2, 5, 6, 8, 5, 8, 7, 1, 2, 6, 1, 6, 5, &
                 3, 7, 8, 3, 8, 4, 1, 5, 7, 1, 7, 3, 2, 4, 8, 2, 8, 6], [3, 12])
  call check(anitet_surface_create(xyz, tri, surface), 1)
  call check(anitet_metric_create_uniform(0.25_c_double, metric), 2)
  call check(anitet_mesher_run(surface, mesh, metric), 3)
  call check(anitet_mesh_get_tets(mesh, tets), 4)
  call check(anitet_mesh_quality(mesh, quality, surface), 5)
  if (quality%valid /= 1 .or. quality%boundary_constrained /= 1) error stop 6
  if (size(tets, 2) /= quality%tets .or. minval(tets) < 1) error stop 7
  print '(a, a, a, i0, a)', "Fortran consumer: anitet ", anitet_version(), ", a cube meshed into ", &
    size(tets, 2), " tets"
  deallocate(tets)  ! main program variables are not freed at its end: LeakSanitizer would say so
  call anitet_mesh_destroy(mesh)
  call anitet_metric_destroy(metric)
  call anitet_surface_destroy(surface)
contains
  subroutine check(rc, step)
    integer, intent(in) :: rc, step
    if (rc /= ANITET_OK) then
      print '(a, i0, a, a)', "step ", step, ": ", anitet_last_error_message()
      error stop 1
    end if
  end subroutine
end program consumer_fortran
