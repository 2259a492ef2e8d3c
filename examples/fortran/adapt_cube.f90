! anitet from Fortran: a solver's adaptation loop. The UGAWG linear cube is adapted three times to
! the analytic metric of the UGAWG benchmark, evaluated at the vertices of each new mesh, with a
! field carried from mesh to mesh, and the measures printed. Prints the same text and writes the
! same files as examples/c/adapt_cube.c and examples/python/adapt_cube.py.
!
!   adapt_cube CUBE_MESH [OUTPUT_PREFIX]   CUBE_MESH: ../shared/data/ugawg/cube-linear-00.mesh;
!                                          writes OUTPUT_PREFIX.meshb and OUTPUT_PREFIX.solb
program adapt_cube
  use, intrinsic :: iso_c_binding
  use anitet
  implicit none
  character(len=4096) :: cube, prefix
  type(c_ptr) :: mesh, next, solution, carried
  type(anitet_adapt_options_t) :: options
  type(anitet_adapt_stats_t) :: stats
  real(c_double), allocatable :: xyz(:, :), metric(:, :), u(:, :)
  real(c_double) :: hz
  integer :: pass, i

  call get_command_argument(1, cube)
  call get_command_argument(2, prefix)
  if (len_trim(cube) == 0) error stop "usage: adapt_cube CUBE_MESH [OUTPUT_PREFIX]"
  call ok(anitet_mesh_read(trim(cube), mesh), "read")
  ! A solver's solution on the first mesh (1 + 2x - y + 3z), carried to every new mesh.
  call ok(anitet_mesh_get_points(mesh, xyz), "points")
  allocate(u(1, size(xyz, 2)))
  u(1, :) = 1d0 + 2d0 * xyz(1, :) - xyz(2, :) + 3d0 * xyz(3, :)
  call ok(anitet_fields_create([ANITET_FIELD_KIND_SCALAR], u, solution), "solution")
  call ok(anitet_adapt_options_init(options), "options")
  options%num_threads = 1  ! the sweeps are serial: one thread for the transfer and measures too
  do pass = 1, 3
    ! UGAWG's linear metric at the points: h_x = h_y = 0.1, h_z = 0.001 + 2 (0.1 - 0.001) |z - 0.5|.
    if (pass > 1) call ok(anitet_mesh_get_points(mesh, xyz), "points")
    allocate(metric(6, size(xyz, 2)))
    do i = 1, size(xyz, 2)
      hz = 0.001d0 + 2d0 * (0.1d0 - 0.001d0) * abs(xyz(3, i) - 0.5d0)
      metric(:, i) = [100d0, 0d0, 100d0, 0d0, 0d0, 1d0 / (hz * hz)]
    end do
    call ok(anitet_adapt(mesh, metric, next, fields=solution, out_fields=carried, options=options, &
                         stats=stats), "adapt")
    deallocate(metric)
    call anitet_mesh_destroy(mesh)
    call anitet_fields_destroy(solution)
    mesh = next
    solution = carried
    write (*, '(a, i0, a, i0, a, i0, a, i0, a, i0, a, i0, a)') "pass ", pass, ": ", stats%splits, &
      " splits, ", stats%collapses, " collapses, ", stats%swaps, " swaps, ", stats%moves, " moves in ", &
      stats%cycles, " cycles"
    write (*, '(a, i0, a, i0, a, i0, a)') "mesh: ", stats%vertices, " vertices, ", stats%tets, " tets, ", &
      stats%boundary_triangles, " boundary triangles"
    write (*, '(a, f0.2, a, f5.3, a, f5.3)') "edges in range: ", 100d0 * stats%edges_in_range, &
      "%, mean ratio min ", stats%mean_ratio_min, " mean ", stats%mean_ratio_mean
  end do
  if (len_trim(prefix) > 0) then
    call ok(anitet_mesh_write(mesh, trim(prefix) // ".meshb"), "write mesh")
    call ok(anitet_fields_write(solution, trim(prefix) // ".solb"), "write solution")
  end if
  call anitet_fields_destroy(solution)
  call anitet_mesh_destroy(mesh)
  deallocate(xyz, u)  ! a main program's variables are never freed automatically

contains

  subroutine ok(code, what)
    integer, intent(in) :: code
    character(len=*), intent(in) :: what
    if (code == ANITET_OK) return
    write (0, '(a, a, a, a, a)') what, ": ", anitet_last_error_message(), " ", anitet_error_name(code)
    error stop 1
  end subroutine
end program adapt_cube
