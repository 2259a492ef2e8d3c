! anitet from Fortran: build a surface in memory, mesh it to an analytic metric (a bind(c)
! callback), print the quality report. Prints the same text and writes the same files as
! examples/c/mesh_sphere.c and examples/python/mesh_sphere.py.
!
!   mesh_sphere [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.mesh and OUTPUT_PREFIX.sol when given
! The metric callback: a bind(c) procedure of a module, so that c_funloc can pass it to C.
module example_metric
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: stretched_metric

contains

  ! The sizing a solver would supply: edges of hx along x and of hx + 0.2 |z| across it (hx is
  ! the user data). Returns non-zero outside the box [-2, 2]^3, where it is not defined.
  integer(c_int) function stretched_metric(x, y, z, m, user_data) bind(c)
    real(c_double), value :: x, y, z
    real(c_double), intent(out) :: m(6)
    type(c_ptr), value :: user_data
    real(c_double), pointer :: hx_
    real(c_double) :: h
    call c_f_pointer(user_data, hx_)
    h = hx_ + 0.2d0 * abs(z)
    m = 0d0
    stretched_metric = 1
    if (abs(x) > 2d0 .or. abs(y) > 2d0 .or. abs(z) > 2d0) return
    m(1) = 1d0 / (hx_ * hx_)
    m(3) = 1d0 / (h * h)
    m(6) = 1d0 / (h * h)
    stretched_metric = 0
  end function

end module example_metric

program mesh_sphere
  use, intrinsic :: iso_c_binding
  use anitet
  use sphere_surface
  use example_metric
  implicit none

  real(c_double) :: xyz(3, SPHERE_NPOINTS)
  integer(c_int32_t) :: tri(3, SPHERE_NTRI), patch(SPHERE_NTRI)
  real(c_double), target :: hx = 0.25d0
  type(c_ptr) :: surface, metric, mesh
  type(c_funptr) :: callback
  type(anitet_options_t) :: options
  integer(c_int64_t) :: np, nt, nb
  integer :: components
  character(len=:), allocatable :: json
  character(len=4096) :: prefix

  call sphere_build(xyz, tri, patch)
  call check(anitet_surface_create(xyz, tri, surface, patch), "surface")
  callback = c_funloc(stretched_metric)  ! (a variable: a constant here trips PIE linking)
  call check(anitet_metric_create_analytic(callback, c_loc(hx), metric), "metric")
  call check(anitet_options_init(options), "options")
  options%layers = 2
  call check(anitet_mesher_run(surface, mesh, metric, options), "mesher")
  call check(anitet_mesh_get_counts(mesh, np, nt, nb), "counts")
  call check(anitet_mesh_get_metric_components(mesh, components), "metric components")
  print '(a, i0, a, i0, a)', "surface: ", SPHERE_NPOINTS, " points, ", SPHERE_NTRI, " triangles"
  print '(a, i0, a, i0, a, i0, a, i0, a)', "mesh: ", np, " vertices, ", nt, " tets, ", nb, &
        " boundary triangles, metric of ", components, " components"
  call check(anitet_mesh_quality_json(mesh, json, surface), "quality")
  print '(a, a)', "quality: ", json

  call get_command_argument(1, prefix)
  if (len_trim(prefix) > 0) then
    call check(anitet_mesh_write(mesh, trim(prefix) // ".mesh"), "write mesh")
    call check(anitet_mesh_write_metric(mesh, trim(prefix) // ".sol"), "write metric")
  end if
  deallocate(json)  ! a main program's variables are never freed automatically
  call anitet_mesh_destroy(mesh)
  call anitet_metric_destroy(metric)
  call anitet_surface_destroy(surface)

contains

  subroutine check(rc, what)
    integer, intent(in) :: rc
    character(len=*), intent(in) :: what
    if (rc /= ANITET_OK) then
      write (0, '(a, a, a, a, a)') what, ": ", anitet_last_error_message(), " ", anitet_error_name(rc)
      error stop 1
    end if
  end subroutine

end program mesh_sphere
