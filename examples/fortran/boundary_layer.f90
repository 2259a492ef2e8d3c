! anitet from Fortran: a boundary layer. The example sphere (patches 1-3) inside the box
! [-3, 3]^3 (patch 4), meshed with a boundary layer on the sphere; the patches named; the run's
! boundary-layer report read through anitet_mesh_get_run_stats and printed. Prints the same text
! and writes the same file as examples/c/boundary_layer.c and examples/python/boundary_layer.py.
!
!   boundary_layer [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.su2 (markers named) when given
program boundary_layer
  use, intrinsic :: iso_c_binding
  use anitet
  use sphere_surface
  implicit none

  character(len=*), parameter :: names(4) = [character(len=12) :: "sphere_south", "sphere_band", &
                                             "sphere_north", "farfield"]
  real(c_double) :: xyz(3, SPHERE_IN_BOX_NPOINTS)
  integer(c_int32_t) :: tri(3, SPHERE_IN_BOX_NTRI), patch(SPHERE_IN_BOX_NTRI)
  type(c_ptr) :: surface, mesh
  type(anitet_options_t) :: options
  type(anitet_run_stats_t) :: stats
  type(anitet_quality_t) :: quality
  integer(c_int64_t) :: np, nt, nb
  integer :: i
  character(len=4096) :: prefix

  call sphere_in_box_build(xyz, tri, patch)
  call check(anitet_surface_create(xyz, tri, surface, patch), "surface")
  call check(anitet_options_init(options), "options")
  options%bl_first_height = 0.02d0
  options%bl_growth = 1.25d0
  options%bl_layers = 5
  options%hgrad = 1.3d0
  ! The walls: bl_patches= is copied for the call (or set options%bl_patches to c_loc of a
  ! target array and options%bl_num_patches to its size).
  call check(anitet_mesher_run(surface, mesh, options=options, bl_patches=[1, 2, 3]), "mesher")
  call check(anitet_mesh_get_run_stats(mesh, stats), "run stats")
  call check(anitet_mesh_get_counts(mesh, np, nt, nb), "counts")
  call check(anitet_mesh_quality(mesh, quality, surface), "quality")
  print '(a, i0, a, i0, a)', "surface: ", SPHERE_IN_BOX_NPOINTS, " points, ", SPHERE_IN_BOX_NTRI, &
        " triangles"
  print '(a, i0, a, i0, a, i0, a)', "mesh: ", np, " vertices, ", nt, " tets, ", nb, &
        " boundary triangles"
  print '(a, i0, a, i0)', "quality: valid ", quality%valid, ", boundary constrained ", &
        quality%boundary_constrained
  call print_report(stats)
  do i = 1, 4
    call check(anitet_mesh_set_patch_name(mesh, i, names(i)), "patch name")  ! trailing blanks go
    print '(a, i0, a, a)', "patch ", i, ": ", trim(names(i))
  end do

  call get_command_argument(1, prefix)
  if (len_trim(prefix) > 0) call check(anitet_mesh_write(mesh, trim(prefix) // ".su2"), "write")
  call anitet_mesh_destroy(mesh)
  call anitet_surface_destroy(surface)

contains

  subroutine print_report(s)
    type(anitet_run_stats_t), intent(in) :: s
    print '(a, i0, a, i0, a, i0, a, i0, a, i0, a, i0, a)', "boundary layer: ", s%bl_layers, &
          " layers, ", s%bl_wall_vertices, " wall vertices, ", s%bl_full_columns, &
          " full columns, ", s%bl_nominal_columns, " nominal columns, ", s%bl_reduced_vertices, &
          " reduced vertices, ", s%bl_tets, " tets"
    print '(6a)', "first height: min ", fixed(s%bl_first_height_min), ", mean ", &
          fixed(s%bl_first_height_mean), ", max ", fixed(s%bl_first_height_max)
    print '(4a)', "growth: mean ", fixed(s%bl_growth_mean), "; max height error ", &
          fixed(s%bl_max_height_error)
  end subroutine

  ! C's "%.6f": F0.6 may drop the zero before the decimal point, which is put back.
  function fixed(v) result(text)
    real(c_double), intent(in) :: v
    character(len=:), allocatable :: text
    character(len=64) :: buffer
    write (buffer, '(f0.6)') v
    text = trim(buffer)
    if (text(1:1) == ".") text = "0" // text
    if (text(1:2) == "-.") text = "-0" // text(2:)
  end function

  subroutine check(rc, what)
    integer, intent(in) :: rc
    character(len=*), intent(in) :: what
    if (rc /= ANITET_OK) then
      write (0, '(a, a, a, a, a)') what, ": ", anitet_last_error_message(), " ", anitet_error_name(rc)
      error stop 1
    end if
  end subroutine

end program boundary_layer
