! The Fortran module over the C ABI: a cube surface built in memory (1-based), validated and read
! back; a volume mesh read from the tests' data and filled into allocatable arrays; the error
! paths a Fortran caller meets; the examples' sphere meshed with and without a metric, and with
! a metric from per-point values or a .sol on a background mesh; a mesh in parts; options
! versions 3 and 4, a boundary layer on the sphere inside a box and the run's report, patch names;
! stage 1 alone, y+ to a first height, the surface's sizing field written and read back, a
! metric sampled on a mesh and read on a mesh in memory, geographic frames; a boundary layer
! sliding along a pipe's caps, patch types, per-vertex fields and their transfer, the boundary
! layer as prism cells, one adaptation pass of the UGAWG cube with a field carried.
! Argument 1: the tests' data directory (tests/data); argument 2: the UGAWG data directory.
! The analytic metric of check_sample_metric: a bind(c) procedure of a module, for c_funloc.
module test_fortran_metrics
  use, intrinsic :: iso_c_binding
  implicit none
contains
  ! 100 along x, 4 along y and z; fails (returns 3) beyond x = 1.5.
  integer(c_int) function stretched_below_x1(x, y, z, m, user_data) bind(c)
    real(c_double), value :: x, y, z
    real(c_double) :: m(6)
    type(c_ptr), value :: user_data
    stretched_below_x1 = 0
    if (x > 1.5d0 .or. c_associated(user_data)) then
      stretched_below_x1 = 3
      return
    end if
    m = [100d0, 0d0, 4d0, 0d0, 0d0, 4d0] + 0 * (y + z)
  end function
end module test_fortran_metrics

program test_fortran
  use, intrinsic :: iso_c_binding
  use anitet
  use sphere_surface
  use test_fortran_metrics
  implicit none

  integer :: failures = 0
  character(len=1024) :: data_dir, ugawg_dir

  call get_command_argument(1, data_dir)
  call get_command_argument(2, ugawg_dir)
  if (len_trim(data_dir) == 0 .or. len_trim(ugawg_dir) == 0) &
    error stop "usage: test_fortran <tests/data directory> <UGAWG data directory>"

  call check_library()
  call check_cube_surface()
  call check_volume_mesh(trim(data_dir) // "/io/box.mesh")
  call check_mesh_from_arrays()
  call check_metric_and_mesher()
  call check_metric_on_background(trim(data_dir) // "/io/box.mesh")
  call check_partition(trim(data_dir) // "/io/box.mesh")
  call check_mesh2d(trim(data_dir) // "/mesh2d")
  call check_options_v3()
  call check_boundary_layer()
  call check_run_report_errors(trim(data_dir) // "/io/box.mesh")
  call check_layers_run()
  call check_bl_first_height()
  call check_surface_sizing()
  call check_sample_metric(trim(data_dir) // "/io/box.mesh")
  call check_geo_frames()
  call check_slide_patches()
  call check_patch_types(trim(data_dir) // "/io/box.mesh")
  call check_fields(trim(data_dir) // "/io/box.mesh")
  call check_bl_prisms()
  call check_adapt(trim(ugawg_dir) // "/cube-linear-00.mesh")

  if (failures > 0) then
    print '(a, i0, a)', "test_fortran: ", failures, " check(s) failed"
    error stop 1
  end if
  print '(a)', "test_fortran: all checks passed"

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      failures = failures + 1
      print '(a, a, a, a)', "FAILED: ", what, "; last error: ", anitet_last_error_message()
    end if
  end subroutine

  subroutine check_library()
    type(anitet_options_t) :: options
    call check(anitet_version() == "0.1.0", "version string")
    call check(anitet_version_number() == ANITET_VERSION_MAJOR * 10000 + &
               ANITET_VERSION_MINOR * 100 + ANITET_VERSION_PATCH, "version number")
    call check(anitet_error_name(ANITET_ERR_OPEN_BOUNDARY) == "open_boundary", "error name")
    call check(anitet_options_init(options) == ANITET_OK, "options init")
    call check(options%version == ANITET_OPTIONS_VERSION .and. options%orient_shells == 1, &
               "options defaults")
    call check(anitet_options_init(options, 42) == ANITET_ERR_INVALID_ARGUMENT, "bad options version")
    call check(index(anitet_last_error_message(), "version 42") > 0, "options error message")
  end subroutine

  subroutine check_cube_surface()
    real(c_double) :: xyz(3, 8)
    integer(c_int32_t) :: tri(3, 12), patch(12)
    real(c_double), allocatable :: xyz_back(:, :)
    integer(c_int32_t), allocatable :: tri_back(:, :), tri0(:, :), patch_back(:)
    type(c_ptr) :: surface, open_surface
    type(anitet_options_t) :: options
    integer(c_int64_t) :: np, nt, count
    character(len=:), allocatable :: json
    integer :: rc

    xyz = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 1d0, 1d0, 0d0, 0d0, 1d0, 0d0, &
                   0d0, 0d0, 1d0, 1d0, 0d0, 1d0, 1d0, 1d0, 1d0, 0d0, 1d0, 1d0], [3, 8])
    ! 1-based, counter-clockwise seen from outside.
    tri = reshape([1, 3, 2, 1, 4, 3, 5, 6, 7, 5, 7, 8, 1, 2, 6, 1, 6, 5, &
                   4, 8, 7, 4, 7, 3, 1, 5, 8, 1, 8, 4, 2, 3, 7, 2, 7, 6], [3, 12])
    patch = [1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6]

    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "cube surface")
    call check(anitet_surface_get_counts(surface, np, nt) == ANITET_OK, "surface counts")
    call check(np == 8 .and. nt == 12, "cube counts 8 / 12")
    call check(anitet_surface_validate(surface) == ANITET_OK, "cube validates")
    rc = anitet_surface_problem_count(surface, ANITET_ERR_OPEN_BOUNDARY, count)
    call check(rc == ANITET_OK .and. count == 0, "no open edge")
    call check(anitet_surface_validation_json(surface, json) == ANITET_OK, "validation json")
    call check(len(json) > 2 .and. json(1:1) == "{", "validation json text")
    call check(anitet_surface_get_points(surface, xyz_back) == ANITET_OK, "surface points")
    call check(all(shape(xyz_back) == [3, 8]) .and. all(xyz_back == xyz), "points round trip")
    call check(anitet_surface_get_triangles(surface, tri_back) == ANITET_OK, "surface triangles")
    call check(all(tri_back == tri), "1-based triangles round trip")
    call check(anitet_surface_get_triangles(surface, tri0, index_base=0) == ANITET_OK, "0-based")
    call check(all(tri0 == tri - 1), "0-based triangles")
    call check(anitet_surface_get_patches(surface, patch_back) == ANITET_OK, "surface patches")
    call check(all(patch_back == patch), "patches round trip")

    ! Options with cancellation would need a callback; here: a bad version is refused.
    call check(anitet_options_init(options) == ANITET_OK, "options")
    options%version = 0
    call check(anitet_surface_validate(surface, options) == ANITET_ERR_INVALID_ARGUMENT, &
               "validate with bad options version")
    call anitet_surface_destroy(surface)
    call check(.not. c_associated(surface), "destroy clears the handle")

    ! The cube without its last triangle.
    call check(anitet_surface_create(xyz, tri(:, 1:11), open_surface) == ANITET_OK, "open cube")
    call check(anitet_surface_validate(open_surface) == ANITET_ERR_OPEN_BOUNDARY, "open boundary")
    call check(len(anitet_last_error_message()) > 0, "open boundary message")
    rc = anitet_surface_problem_count(open_surface, ANITET_ERR_OPEN_BOUNDARY, count)
    call check(rc == ANITET_OK .and. count == 3, "three open edges")
    call anitet_surface_destroy(open_surface)

    ! 1-based data passed as 0-based is fine (all < 8), but index 9 is not.
    tri(1, 1) = 9
    call check(anitet_surface_create(xyz, tri, surface) == ANITET_ERR_BAD_INDEX, "bad index")
    call check(.not. c_associated(surface), "no handle on error")
  end subroutine

  subroutine check_volume_mesh(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: mesh
    integer(c_int64_t) :: np, nt, nb
    real(c_double), allocatable :: xyz(:, :), metric(:, :)
    integer(c_int32_t), allocatable :: tets(:, :), regions(:), tri(:, :), patch(:)
    integer :: components
    type(anitet_quality_t) :: q
    character(len=:), allocatable :: json
    integer :: rc, i

    call check(anitet_mesh_read(path, mesh) == ANITET_OK, "read " // path)
    call check(anitet_mesh_get_counts(mesh, np, nt, nb) == ANITET_OK, "mesh counts")
    call check(np == 8 .and. nt == 6 .and. nb == 12, "box counts 8 / 6 / 12")
    call check(anitet_mesh_get_points(mesh, xyz) == ANITET_OK, "mesh points")
    call check(all(shape(xyz) == [3, 8]) .and. xyz(1, 2) == 1.5d0 .and. xyz(3, 1) == -0.25d0, &
               "box points")
    call check(anitet_mesh_get_tets(mesh, tets) == ANITET_OK, "mesh tets")
    ! The file's first tet is "1 2 4 8" (1-based, as Fortran gets it).
    call check(all(tets(:, 1) == [1, 2, 4, 8]), "first tet, 1-based")
    call check(minval(tets) == 1 .and. maxval(tets) == 8, "tet index range")
    call check(anitet_mesh_get_regions(mesh, regions) == ANITET_OK, "regions")
    call check(size(regions) == 6 .and. regions(1) == 1 .and. regions(6) == 2, "region labels")
    call check(anitet_mesh_get_boundary_triangles(mesh, tri) == ANITET_OK, "boundary triangles")
    call check(all(shape(tri) == [3, 12]) .and. all(tri(:, 1) == [1, 7, 3]), "first triangle")
    call check(anitet_mesh_get_boundary_patches(mesh, patch) == ANITET_OK, "boundary patches")
    call check(size(patch) == 12 .and. patch(1) == 1, "patch labels")
    rc = anitet_mesh_get_metric_components(mesh, components)
    call check(rc == ANITET_OK .and. components == 0, "no metric")
    rc = anitet_mesh_get_metric(mesh, metric)
    call check(rc == ANITET_OK .and. size(metric) == 0, "empty metric")
    call check(anitet_mesh_set_metric(mesh, reshape([(real(i, c_double), i = 1, 8)], [1, 8])) &
               == ANITET_OK, "set sizes")
    rc = anitet_mesh_get_metric(mesh, metric)
    call check(rc == ANITET_OK .and. all(shape(metric) == [1, 8]), "metric shape")
    call check(metric(1, 8) == 8d0, "metric values")
    call check(anitet_mesh_write_metric(mesh, "fortran_box.sol") == ANITET_OK, "write .sol")
    call check(anitet_mesh_quality(mesh, q) == ANITET_OK, "quality")
    call check(q%tets == 6 .and. q%nonpositive_tets == 0 .and. q%valid == 1, "quality numbers")
    call check(q%radius_ratio_min > 0d0 .and. q%radius_ratio_min <= q%radius_ratio_mean, &
               "radius ratio")
    call check(anitet_mesh_quality_json(mesh, json) == ANITET_OK, "quality json")
    call check(index(json, '"tets"') > 0, "quality json text")
    call check(anitet_mesh_write(mesh, "fortran_box.vtu") == ANITET_OK, "write vtu")
    call check(anitet_mesh_write(mesh, "fortran_box.unknown") == ANITET_ERR_UNSUPPORTED_FORMAT, &
               "write unknown format")
    call anitet_mesh_destroy(mesh)
    call check(anitet_mesh_read(path // "-missing.mesh", mesh) == ANITET_ERR_FILE_NOT_FOUND, &
               "missing file")
    call check(index(anitet_last_error_message(), "-missing.mesh") > 0, "missing file message")
  end subroutine

  subroutine check_mesh_from_arrays()
    real(c_double) :: xyz(3, 4)
    integer(c_int32_t) :: tet(4, 1), faces(3, 4)
    integer(c_int32_t), allocatable :: tets0(:, :)
    type(c_ptr) :: mesh, faces_surface
    type(anitet_quality_t) :: q
    xyz = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0], [3, 4])
    tet(:, 1) = [1, 2, 3, 4]
    faces = reshape([1, 3, 2, 1, 2, 4, 2, 3, 4, 1, 4, 3], [3, 4])
    call check(anitet_mesh_create(xyz, tet, mesh, bnd_tri=faces) == ANITET_OK, "mesh from arrays")
    call check(anitet_mesh_get_tets(mesh, tets0, index_base=0) == ANITET_OK, "tets 0-based")
    call check(all(tets0(:, 1) == [0, 1, 2, 3]), "tet 0-based values")
    call check(anitet_surface_create(xyz, faces, faces_surface) == ANITET_OK, "faces surface")
    call check(anitet_mesh_quality(mesh, q, faces_surface) == ANITET_OK, "quality with input")
    call check(q%boundary_constrained == 1 .and. q%tets == 1, "boundary constrained")
    call anitet_surface_destroy(faces_surface)
    call anitet_mesh_destroy(mesh)
    call check(anitet_mesh_create(xyz, reshape(tet, [2, 2]), mesh) == ANITET_ERR_INVALID_ARGUMENT, &
               "tets not shaped (4, n)")
    tet(4, 1) = 5
    call check(anitet_mesh_create(xyz, tet, mesh) == ANITET_ERR_BAD_INDEX, "tet bad index")
  end subroutine

  subroutine check_metric_and_mesher()
    type(c_ptr) :: metric, other, surface, mesh
    type(anitet_options_t), target :: options
    real(c_double) :: m(6)
    real(c_double) :: xyz(3, SPHERE_NPOINTS)
    integer(c_int32_t) :: faces(3, SPHERE_NTRI), patch(SPHERE_NTRI)
    integer(c_int32_t), allocatable :: tets(:, :), tri(:, :)
    real(c_double), allocatable :: values(:, :)
    integer(c_int64_t) :: np, nt, nb
    call check(anitet_metric_create_uniform(0.5d0, metric) == ANITET_OK, "uniform metric")
    call check(anitet_metric_evaluate(metric, [0d0, 0d0, 0d0], m) == ANITET_OK, "evaluate")
    call check(m(1) == 4d0 .and. m(3) == 4d0 .and. m(6) == 4d0 .and. m(2) == 0d0, "uniform tensor")
    ! The examples' sphere, 1-based.
    call sphere_build(xyz, faces, patch)
    call check(anitet_surface_create(xyz, faces, surface, patch) == ANITET_OK, "sphere surface")
    call check(anitet_mesher_run(surface, mesh) == ANITET_OK, "mesher runs")
    call check(anitet_mesh_get_counts(mesh, np, nt, nb) == ANITET_OK, "mesh counts")
    call check(np >= SPHERE_NPOINTS .and. nt > np .and. nb == SPHERE_NTRI, "mesh counts values")
    call check(anitet_mesh_get_tets(mesh, tets) == ANITET_OK, "mesh tets")
    call check(size(tets, 1) == 4 .and. size(tets, 2) == nt, "tets shape")
    call check(minval(tets) == 1 .and. maxval(tets) <= np, "tets 1-based")
    call check(anitet_mesh_get_boundary_triangles(mesh, tri) == ANITET_OK, "boundary triangles")
    call check(all(tri == faces), "boundary triangles are the input")
    call anitet_mesh_destroy(mesh)
    ! With a metric: its tensors at the vertices.
    call check(anitet_mesher_run(surface, mesh, metric) == ANITET_OK, "mesher with a metric")
    call check(anitet_mesh_get_metric(mesh, values) == ANITET_OK, "mesh metric")
    call check(size(values, 1) == 6 .and. all(values(1, :) == 4d0), "mesh metric values")
    call anitet_mesh_destroy(mesh)
    ! Version 2 options: a bad layer count is refused.
    call check(anitet_options_init(options) == ANITET_OK, "options v2")
    call check(options%layers == 1 .and. options%layer_scheme == ANITET_LAYERS_PUSH, &
               "options v2 defaults")
    ! The struct's layout is the C one: version 1 ends after four pointers, version 2 adds
    ! 2 * (4 + 4 + 8) bytes, version 3 seven 8-byte fields, eight 4-byte ones and a pointer,
    ! version 4 two 4-byte fields and a pointer, version 5 a double.
    call check(c_sizeof(options) == 6 * 4 + 4 * c_sizeof(c_null_ptr) + 32 + 88 + &
               c_sizeof(c_null_ptr) + 8 + c_sizeof(c_null_ptr) + 8, "options size")
    call check(options%refine == 1 .and. options%optimize == 1 .and. options%size_scale == 1d0, &
               "options v2 refine defaults")
    options%layers = 0
    call check(anitet_mesher_run(surface, mesh, options=options) == ANITET_ERR_INVALID_ARGUMENT, &
               "zero layers refused")
    options%layers = 2
    call check(anitet_mesher_run(surface, mesh, options=options) == ANITET_OK, "two layers")
    call anitet_mesh_destroy(mesh)
    call check(anitet_metric_read("no_such_size.vdb", other) == ANITET_ERR_FILE_NOT_FOUND, &
               "metric read: missing file")
    call check(.not. c_associated(other), "no metric handle")
    call anitet_metric_destroy(metric)
    call anitet_surface_destroy(surface)
  end subroutine

  ! Metrics on a background mesh (tests/data/io/box.mesh: 8 points, 6 tets): per-point values,
  ! and the same values written as .sol + .mesh then read back; the sphere meshed with it.
  subroutine check_metric_on_background(box_path)
    character(len=*), intent(in) :: box_path
    type(c_ptr) :: background, from_points, from_file, surface, mesh
    real(c_double) :: sizes(1, 8), tensors(6, 8), short(1, 7), three(3, 8), m(6)
    real(c_double) :: xyz(3, SPHERE_NPOINTS)
    integer(c_int32_t) :: faces(3, SPHERE_NTRI), patch(SPHERE_NTRI)
    real(c_double), allocatable :: values(:, :)
    integer :: i
    sizes = 0.25d0
    short = 0.25d0
    three = 1d0
    do i = 1, 8
      tensors(:, i) = [100d0, 0d0, 25d0, 0d0, 0d0, 6.25d0]
    end do
    call check(anitet_mesh_read(box_path, background) == ANITET_OK, "background mesh")
    call check(anitet_metric_create_from_points(background, sizes, from_points) == ANITET_OK, &
               "metric from points")
    call check(anitet_metric_evaluate(from_points, [0.5d0, 0.05d0, 1d0], m) == ANITET_OK, &
               "evaluate from points")
    call check(abs(m(1) - 16d0) < 1d-12 .and. abs(m(6) - 16d0) < 1d-12 .and. abs(m(2)) < 1d-12, &
               "per-point size 0.25")
    call anitet_metric_destroy(from_points)
    call check(anitet_metric_create_from_points(background, tensors, from_points) == ANITET_OK, &
               "tensor metric from points")
    call check(anitet_metric_evaluate(from_points, [1d0, 0.02d0, 0.5d0], m) == ANITET_OK, &
               "evaluate tensor")
    call check(abs(m(1) - 100d0) < 1d-10 .and. abs(m(3) - 25d0) < 1d-10 .and. &
               abs(m(6) - 6.25d0) < 1d-10, "per-point tensor")
    call anitet_metric_destroy(from_points)
    call check(anitet_metric_create_from_points(background, short, from_points) == &
               ANITET_ERR_INVALID_ARGUMENT, "7 values for 8 points refused")
    call check(index(anitet_last_error_message(), "num_values is 7") > 0, "sizes mismatch message")
    call check(anitet_metric_create_from_points(background, three, from_points) == &
               ANITET_ERR_INVALID_ARGUMENT, "3 components refused")
    call check(.not. c_associated(from_points), "no metric after an error")

    ! .sol + background mesh, written through the C ABI (in the test's working directory).
    call check(anitet_mesh_set_metric(background, sizes) == ANITET_OK, "set metric")
    call check(anitet_mesh_write(background, "fortran_background.mesh") == ANITET_OK, "write mesh")
    call check(anitet_mesh_write_metric(background, "fortran_background.sol") == ANITET_OK, &
               "write sol")
    call check(anitet_metric_read("fortran_background.sol", from_file, "fortran_background.mesh") &
               == ANITET_OK, "metric read .sol")
    call check(anitet_metric_evaluate(from_file, [0.7d0, 0.03d0, 0.2d0], m) == ANITET_OK, &
               "evaluate .sol")
    call check(abs(m(1) - 16d0) < 1d-12 .and. abs(m(3) - 16d0) < 1d-12, ".sol size 0.25")
    call check(anitet_metric_read("fortran_background.sol", from_points) == &
               ANITET_ERR_INVALID_ARGUMENT, ".sol without background refused")
    call check(anitet_metric_read("fortran_background.sol", from_points, "no_such.mesh") == &
               ANITET_ERR_FILE_NOT_FOUND, "missing background")

    ! The sphere meshed to it: the mesh carries the size 0.25 at every vertex.
    call sphere_build(xyz, faces, patch)
    call check(anitet_surface_create(xyz, faces, surface, patch) == ANITET_OK, "sphere surface")
    call check(anitet_mesher_run(surface, mesh, from_file) == ANITET_OK, "mesher with a .sol")
    call check(anitet_mesh_get_metric(mesh, values) == ANITET_OK, "mesh metric")
    call check(size(values, 1) == 6 .and. all(abs(values(1, :) - 16d0) < 1d-9), &
               "mesh metric of the .sol")
    call anitet_mesh_destroy(mesh)
    call anitet_surface_destroy(surface)
    call anitet_metric_destroy(from_file)
    call anitet_mesh_destroy(background)
  end subroutine

  ! The box's 6 tets in 2 parts: every tet own once, 1-based local ids in range, halo offsets
  ! from 1, the bytes of a part round trip, and the documented errors.
  subroutine check_partition(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: mesh, partition, part, copy
    type(anitet_partition_options_t), target :: options
    type(anitet_partition_info_t) :: info
    integer(c_int32_t), allocatable :: tet_parts(:), tets(:, :), owners(:), items(:), neighbours(:)
    integer(c_int64_t), allocatable :: ids(:), offsets(:)
    integer(c_int8_t), allocatable :: bytes(:), bytes2(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    integer(c_int32_t) :: part_index, num_parts, num_neighbours, layers
    integer :: p, own(6)
    call check(anitet_mesh_read(path, mesh) == ANITET_OK, "read " // path)
    call check(anitet_partition_options_init(options) == ANITET_OK, "partition options")
    call check(options%ghost_layers == 1 .and. options%imbalance == 0.03_c_double, "partition defaults")
    call check(anitet_mesh_partition(mesh, 2, partition, options) == ANITET_OK, "partition")
    call check(anitet_partition_get_info(partition, info) == ANITET_OK, "partition info")
    call check(info%num_parts == 2 .and. info%num_tets == 6 .and. info%edge_cut > 0, "info figures")
    call check(anitet_partition_get_tet_parts(partition, tet_parts) == ANITET_OK, "tet parts")
    call check(size(tet_parts) == 6 .and. all(tet_parts >= 0 .and. tet_parts <= 1), "tet parts range")
    own = 0
    do p = 0, 1
      call check(anitet_partition_get_part(partition, p, part) == ANITET_OK, "get part")
      call check(anitet_part_get_index(part, part_index, num_parts, num_neighbours, layers) == ANITET_OK &
                 .and. part_index == p .and. num_parts == 2 .and. num_neighbours == 1, "part index")
      call check(anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob) == ANITET_OK, "part counts")
      call check(anitet_part_get_tets(part, tets) == ANITET_OK, "part tets")
      call check(all(shape(tets) == [4_c_int64_t, nt]) .and. all(tets >= 1 .and. tets <= nv), &
                 "1-based local tets")
      call check(anitet_part_get_tet_global_ids(part, ids) == ANITET_OK, "tet global ids")
      own(ids(1:nto)) = own(ids(1:nto)) + 1
      call check(anitet_part_get_tet_owners(part, owners) == ANITET_OK, "tet owners")
      call check(all(owners(1:nto) == p) .and. all(owners(nto + 1:) /= p), "own tets first")
      call check(anitet_part_get_neighbours(part, neighbours) == ANITET_OK, "neighbours")
      call check(neighbours(1) == 1 - p, "the other part is the neighbour")
      call check(anitet_part_get_halo(part, ANITET_HALO_VERTEX_RECV, offsets, items) == ANITET_OK, &
                 "vertex recv list")
      call check(offsets(1) == 1 .and. offsets(2) == size(items) + 1, "1-based offsets")
      call check(all(items > nov .and. items <= nv), "received vertices are not own")
      call check(anitet_part_serialize(part, bytes) == ANITET_OK, "serialize")
      call check(anitet_part_deserialize(bytes, copy) == ANITET_OK, "deserialize")
      call check(anitet_part_serialize(copy, bytes2) == ANITET_OK, "serialize again")
      call check(size(bytes2) == size(bytes) .and. all(bytes2 == bytes), "bytes round trip")
      call anitet_part_destroy(copy)
      call check(anitet_part_deserialize(bytes(1:size(bytes) - 1), copy) == ANITET_ERR_PARSE, &
                 "truncated bytes")
      call check(.not. c_associated(copy), "no part from truncated bytes")
    end do
    call check(all(own == 1), "every tet own in one part")
    call check(anitet_partition_get_part(partition, 2, part) == ANITET_ERR_INVALID_ARGUMENT, &
               "part 2 of 2")
    call anitet_partition_destroy(partition)
    call check(.not. c_associated(partition), "destroy clears the partition")
    call check(anitet_mesh_partition(mesh, 0, partition) == ANITET_ERR_INVALID_ARGUMENT, "0 parts")
    call check(anitet_mesh_partition(mesh, 7, partition) == ANITET_ERR_INVALID_ARGUMENT, "7 parts")
    call check(.not. c_associated(partition), "no partition on error")
    options%version = 99
    call check(anitet_mesh_partition(mesh, 2, partition, options) == ANITET_ERR_INVALID_ARGUMENT, &
               "unknown options version")
    call check(index(anitet_last_error_message(), "version 99") > 0, "version error message")
    call anitet_mesh_destroy(mesh)
  end subroutine

  ! The 2D mesher: a square with a square hole from arrays (1-based), meshed with points allowed
  ! on its long sides; the input's points come first and exactly; the segments' labels come
  ! back on their pieces; a bad input is refused with its element named.
  subroutine check_mesh2d(dir)
    character(len=*), intent(in) :: dir
    real(c_double) :: xy(2, 8), holes(2, 1)
    integer(c_int32_t) :: seg(2, 8), labels(8)
    real(c_double), allocatable :: xy_back(:, :), attributes(:)
    integer(c_int32_t), allocatable :: tri(:, :), edges(:, :), edge_labels(:)
    type(c_ptr) :: pslg, mesh
    type(anitet_mesh2d_options_t) :: options
    integer(c_int64_t) :: np, ns, nh, nt, ne
    real(c_double) :: min_angle, off_input, mean_rr, in_range, area
    integer :: t, e
    xy = reshape([0d0, 0d0, 4d0, 0d0, 4d0, 4d0, 0d0, 4d0, 1.5d0, 1.5d0, 2.5d0, 1.5d0, 2.5d0, 2.5d0, &
                  1.5d0, 2.5d0], [2, 8])
    seg = reshape([1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5], [2, 8])
    labels = [1, 1, 1, 1, 2, 2, 2, 2]
    holes(:, 1) = [2d0, 2d0]
    call check(anitet_pslg_create(xy, seg, pslg, labels, holes) == ANITET_OK, "pslg create")
    call check(anitet_pslg_get_counts(pslg, np, ns, nh) == ANITET_OK, "pslg counts")
    call check(np == 8 .and. ns == 8 .and. nh == 1, "pslg counts' values")
    call check(anitet_mesh2d_options_init(options) == ANITET_OK, "mesh2d options")
    call check(options%layers == 1 .and. options%size_scale == 1d0, "mesh2d options' defaults")
    options%split_segments = 1
    options%hsize = 0.25d0
    call check(anitet_mesh2d_run(pslg, mesh, options=options) == ANITET_OK, "mesh2d run")
    call check(anitet_mesh2d_get_counts(mesh, np, nt, ne) == ANITET_OK, "mesh2d counts")
    call check(nt > 100 .and. ne > 8, "mesh2d counts' values")
    call check(anitet_mesh2d_get_points(mesh, xy_back) == ANITET_OK, "mesh2d points")
    call check(all(xy_back(:, 1:8) == xy), "the input's points first")
    call check(anitet_mesh2d_get_triangles(mesh, tri) == ANITET_OK, "mesh2d triangles")
    call check(minval(tri) == 1 .and. maxval(tri) == np, "mesh2d triangles, 1-based")
    area = 0
    do t = 1, int(nt)
      area = area + 0.5d0 * ((xy_back(1, tri(2, t)) - xy_back(1, tri(1, t))) * &
                             (xy_back(2, tri(3, t)) - xy_back(2, tri(1, t))) - &
                             (xy_back(2, tri(2, t)) - xy_back(2, tri(1, t))) * &
                             (xy_back(1, tri(3, t)) - xy_back(1, tri(1, t))))
    end do
    call check(abs(area - 15d0) < 1d-9, "mesh2d area: the square less its hole")
    call check(anitet_mesh2d_get_attributes(mesh, attributes) == ANITET_OK, "mesh2d attributes")
    call check(size(attributes) == nt, "mesh2d attributes' size")
    call check(anitet_mesh2d_get_edges(mesh, edges) == ANITET_OK, "mesh2d edges")
    call check(anitet_mesh2d_get_edge_labels(mesh, edge_labels) == ANITET_OK, "mesh2d edge labels")
    do e = 1, int(ne)  ! the outer square's pieces have label 1, the hole's 2
      call check(edge_labels(e) == merge(1, 2, maxval(abs(xy_back(:, edges(1, e)) - 2d0)) > 1.9d0), &
                 "mesh2d edge label")
    end do
    call check(anitet_mesh2d_quality(mesh, min_angle, off_input, mean_rr, in_range) == ANITET_OK, &
               "mesh2d quality")
    call check(min_angle >= 25d0 .and. mean_rr >= 0.9d0, "mesh2d quality figures")
    call check(anitet_mesh2d_write(mesh, "fortran_mesh2d.mesh") == ANITET_OK, "mesh2d write")
    call anitet_mesh2d_destroy(mesh)
    call check(.not. c_associated(mesh), "mesh2d destroy")
    call anitet_pslg_destroy(pslg)
    call check(anitet_pslg_read(dir // "/crossing.poly", pslg) == ANITET_OK, "pslg read")
    call check(anitet_mesh2d_run(pslg, mesh) == ANITET_ERR_SELF_INTERSECTION, "crossing refused")
    call check(index(anitet_last_error_message(), "segment 2 (line 9)") > 0, "crossing named")
    call anitet_pslg_destroy(pslg)
  end subroutine

  ! Versions 3 to 5 of the options: the defaults of anitet_options_init, the run stats' layout,
  ! and version 2 to 4 structs still accepted.
  subroutine check_options_v3()
    type(anitet_options_t) :: o
    type(anitet_run_stats_t) :: st
    call check(anitet_options_init(o) == ANITET_OK, "options v5")
    call check(o%version == 5 .and. o%bl_sizing_growth == 0d0, "options v5: version, sizing growth")
    call check(o%bl_num_slide_patches == 0 .and. o%bl_cells == ANITET_BL_CELLS_TETS .and. &
               .not. c_associated(o%bl_slide_patches), "options v4: no slide patches")
    call check(o%attempts_seconds == 240d0 .and. o%retry_layer_counts == 1 .and. &
               o%recovery == ANITET_RECOVERY_ALL, "options v3: attempts, retries, recovery")
    call check(o%hmin == 0d0 .and. o%hmax == 0d0 .and. o%hgrad == 0d0 .and. o%max_tets == 0d0, &
               "options v3: no size bounds, no tet cap")
    call check(o%anisotropic_cycles == 2 .and. o%bl_num_patches == 0 .and. &
               .not. c_associated(o%bl_patches), "options v3: cycles, no walls")
    call check(o%bl_first_height == 0d0 .and. o%bl_growth == 1.2d0 .and. o%bl_layers == 10 .and. &
               o%bl_sizing == 0, "options v3: boundary layer defaults")
    call check(o%push_tasks_min_vertices == 2000 .and. o%bl_mitre == 0, &
               "options v3: push tasks from 2000 front vertices")
    ! 8 int32, 8 int64, 5 doubles, 2 int32, 5 int64, 5 doubles, 3 + 2 int64: no padding.
    call check(c_sizeof(st) == 264, "run stats size")
    call check(anitet_options_init(o, 4) == ANITET_OK, "options v4 still")
    call check(o%version == 4, "options v4: version")
    call check(anitet_options_init(o, 3) == ANITET_OK, "options v3 still")
    call check(o%version == 3, "options v3: version")
    call check(anitet_options_init(o, 2) == ANITET_OK, "options v2 still")
    call check(o%version == 2, "options v2: version")
  end subroutine

  ! The sphere (patches 1-3) inside the box [-3, 3]^3 (patch 4) with a boundary layer on the
  ! sphere: the walls given as a c_loc, then through bl_patches=; the report; patch names.
  ! The sphere's boundary layer as prism cells (options%bl_cells), on the cheapest run: each
  ! prism is 3 of the mesh's tets; polyMesh gets them, a format of tets only refuses the mesh.
  subroutine check_bl_prisms()
    real(c_double) :: xyz(3, SPHERE_IN_BOX_NPOINTS)
    integer(c_int32_t) :: tri(3, SPHERE_IN_BOX_NTRI), patch(SPHERE_IN_BOX_NTRI)
    type(c_ptr) :: surface, mesh
    type(anitet_options_t) :: o
    type(anitet_run_stats_t) :: st
    integer(c_int64_t) :: np, nt, nb, nprisms
    integer(c_int32_t), allocatable :: tets(:, :), prisms(:, :), tet_prism(:)
    integer :: t, k, p
    logical :: inside
    character(len=:), allocatable :: owner
    character(len=64) :: note
    call sphere_in_box_build(xyz, tri, patch)
    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "prisms: sphere in box")
    call check(anitet_options_init(o) == ANITET_OK, "prisms: options")
    o%bl_first_height = 0.02d0
    o%bl_layers = 2
    o%refine = 0
    o%optimize = 0
    o%bl_cells = ANITET_BL_CELLS_PRISMS
    call check(anitet_mesher_run(surface, mesh, options=o) == ANITET_ERR_INVALID_ARGUMENT, &
               "prisms without walls refused")
    call check(index(anitet_last_error_message(), "needs boundary-layer walls") > 0, &
               "prisms without walls: the message")
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1, 2, 3]) == ANITET_OK, &
               "prisms: run")
    call check(anitet_mesh_get_counts(mesh, np, nt, nb) == ANITET_OK, "prisms: counts")
    call check(anitet_mesh_get_prism_count(mesh, nprisms) == ANITET_OK .and. &
               nprisms == 2 * SPHERE_NTRI, "prisms: one per wall triangle and layer")
    call check(anitet_mesh_get_run_stats(mesh, st) == ANITET_OK .and. st%bl_prisms == nprisms .and. &
               3 * st%bl_prisms + st%bl_prism_tets_left == st%bl_tets, "prisms: run stats version 3")
    call check(anitet_mesh_get_tets(mesh, tets) == ANITET_OK, "prisms: tets")
    call check(anitet_mesh_get_prisms(mesh, prisms) == ANITET_OK, "prisms: get")
    call check(anitet_mesh_get_tet_prisms(mesh, tet_prism) == ANITET_OK, "prisms: tet_prism")
    call check(size(prisms, 2) == nprisms .and. size(tet_prism) == nt .and. &
               count(tet_prism > 0) == 3 * nprisms .and. count(tet_prism == -1) == nt - 3 * nprisms, &
               "prisms: 3 tets each")
    inside = .true.
    do t = 1, int(nt)
      p = tet_prism(t)
      if (p < 1) cycle
      do k = 1, 4
        inside = inside .and. any(prisms(:, p) == tets(k, t))  ! both 1-based
      end do
    end do
    call check(inside, "prisms: each tet's vertices are its prism's")
    call check(anitet_mesh_write(mesh, "fortran_prisms/constant/polyMesh") == ANITET_OK, &
               "prisms: write polyMesh")
    owner = file_text("fortran_prisms/constant/polyMesh/owner")
    write(note, '(a, i0)') "nCells:", nt - 2 * nprisms
    call check(index(owner, trim(note)) > 0, "prisms: polyMesh cells")
    call check(anitet_mesh_write(mesh, "fortran_prisms.su2") == ANITET_ERR_UNSUPPORTED_FORMAT, &
               "prisms: .su2 refused")
    call check(index(anitet_last_error_message(), "prisms") > 0, "prisms: .su2 refused, the message")
    call anitet_mesh_destroy(mesh)
    call anitet_surface_destroy(surface)
  end subroutine

  subroutine check_boundary_layer()
    real(c_double) :: xyz(3, SPHERE_IN_BOX_NPOINTS)
    integer(c_int32_t) :: tri(3, SPHERE_IN_BOX_NTRI), patch(SPHERE_IN_BOX_NTRI)
    integer(c_int32_t), target :: walls(3) = [1, 2, 3]
    type(c_ptr) :: surface, mesh, other
    type(anitet_options_t), target :: o
    type(anitet_run_stats_t) :: st, st2
    integer(c_int64_t) :: np, nt, nb
    character(len=:), allocatable :: json, su2
    call sphere_in_box_build(xyz, tri, patch)
    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "sphere in box")
    call check(anitet_options_init(o) == ANITET_OK, "options")
    o%bl_first_height = 0.02d0
    o%bl_growth = 1.25d0
    o%bl_layers = 4
    o%bl_num_patches = size(walls)
    o%bl_patches = c_loc(walls)
    call check(anitet_mesher_run(surface, mesh, options=o) == ANITET_OK, "BL run, walls by c_loc")
    call check(anitet_mesh_get_run_stats(mesh, st) == ANITET_OK, "run stats")
    call check(anitet_mesh_get_counts(mesh, np, nt, nb) == ANITET_OK, "BL mesh counts")
    call check(st%version == ANITET_RUN_STATS_VERSION .and. st%vertices == np .and. st%tets == nt, &
               "run stats: version, counts")
    call check(st%layers_used >= 1 .and. st%seconds > 0d0 .and. st%refine_passes >= 1 .and. &
               (st%recovery_strategy == ANITET_RECOVERY_SPLIT .or. &
                st%recovery_strategy == ANITET_RECOVERY_FUZZY), "run stats: stages")
    call check(st%bl_layers == 4 .and. st%bl_wall_vertices == SPHERE_NPOINTS .and. &
               st%bl_full_columns == SPHERE_NPOINTS, "BL: 4 layers, every wall vertex a full column")
    call check(10 * st%bl_nominal_columns >= 9 * SPHERE_NPOINTS .and. &
               st%bl_tets >= 3 * 4 * SPHERE_NTRI, "BL: nominal columns, tets")
    call check(abs(st%bl_first_height_mean - 0.02d0) < 0.002d0 .and. st%bl_first_height_min > 0d0 &
               .and. st%bl_first_height_min <= st%bl_first_height_max, "BL: first heights")
    call check(abs(st%bl_growth_mean - 1.25d0) < 0.05d0 .and. st%bl_max_height_error <= 0.1d0, &
               "BL: growth, height error")
    call check(anitet_mesh_run_json(mesh, json) == ANITET_OK, "run json")
    call check(json(1:1) == "{" .and. index(json, '"boundary_layer"') > 0 .and. &
               index(json, '"columns_reaching"') > 0 .and. index(json, '"stages"') > 0, "run json text")

    ! The same walls through bl_patches= (an expression: the wrapper keeps a copy for the call).
    o%bl_num_patches = 0
    o%bl_patches = c_null_ptr
    call check(anitet_mesher_run(surface, other, options=o, bl_patches=walls(1:3) + 0) == ANITET_OK, &
               "BL run, walls by bl_patches=")
    call check(anitet_mesh_get_run_stats(other, st2) == ANITET_OK, "run stats again")
    call check(st2%bl_tets == st%bl_tets .and. st2%tets == st%tets, "the same boundary layer")
    call anitet_mesh_destroy(other)

    ! Patch names in the written files; trailing blanks are not part of a name.
    call check(anitet_mesh_set_patch_name(mesh, 4, "farfield") == ANITET_OK, "name patch 4")
    call check(anitet_mesh_set_patch_name(mesh, 1, "sphere_south   ") == ANITET_OK, "name patch 1")
    call check(anitet_mesh_write(mesh, "fortran_bl.su2") == ANITET_OK, "write su2")
    su2 = file_text("fortran_bl.su2")
    call check(index(su2, "MARKER_TAG= farfield") > 0 .and. index(su2, "MARKER_TAG= sphere_south" // &
               new_line("a")) > 0 .and. index(su2, "MARKER_TAG= patch2") > 0, "named markers")
    call check(anitet_mesh_set_patch_name(mesh, 1) == ANITET_OK, "remove a name")
    call check(anitet_mesh_write(mesh, "fortran_bl.su2") == ANITET_OK, "write su2 again")
    su2 = file_text("fortran_bl.su2")
    call check(index(su2, "MARKER_TAG= patch1") > 0 .and. index(su2, "sphere_south") == 0, &
               "name removed")
    call check(anitet_mesh_set_patch_name(mesh, 9, "wall") == ANITET_ERR_INVALID_ARGUMENT, &
               "no patch 9")
    call check(index(anitet_last_error_message(), "9") > 0, "no patch 9: message")
    call check(anitet_mesh_set_patch_name(mesh, 4, "far field") == ANITET_ERR_INVALID_ARGUMENT, &
               "a name with a blank")
    call check(anitet_mesh_set_patch_name(mesh, 4, "") == ANITET_ERR_INVALID_ARGUMENT, "empty name")
    call check(anitet_mesh_set_patch_name(mesh, 4, "9lives") == ANITET_ERR_INVALID_ARGUMENT, &
               "a name starting with a digit")
    call check(anitet_mesh_set_patch_name(mesh, 2, "farfield") == ANITET_OK, "a name twice")
    call check(anitet_mesh_write(mesh, "fortran_bl_twice.su2") == ANITET_ERR_INVALID_ARGUMENT, &
               "two patches of one name: no write")
    call check(index(anitet_last_error_message(), "farfield") > 0, "two patches: message")
    call anitet_mesh_destroy(mesh)

    ! The options' errors, named.
    o%bl_first_height = 0d0
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1, 2, 3]) == &
               ANITET_ERR_INVALID_ARGUMENT, "walls without a first height")
    call check(index(anitet_last_error_message(), "bl_first_height") > 0, "first height: message")
    call check(.not. c_associated(mesh), "no mesh on error")
    o%bl_first_height = 0.02d0
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1, 7]) == &
               ANITET_ERR_INVALID_ARGUMENT, "an unknown wall label")
    call check(index(anitet_last_error_message(), "wall patch label 7") > 0, "wall 7: message")
    call check(anitet_mesher_run(surface, mesh, bl_patches=[1, 2, 3]) == ANITET_ERR_INVALID_ARGUMENT, &
               "walls with the default options (no first height)")
    o%recovery = 3
    call check(anitet_mesher_run(surface, mesh, options=o) == ANITET_ERR_INVALID_ARGUMENT, "recovery 3")
    call check(index(anitet_last_error_message(), "recovery is 3") > 0, "recovery 3: message")
    call check(anitet_options_init(o, 2) == ANITET_OK, "options v2")
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1, 2, 3]) == &
               ANITET_ERR_INVALID_ARGUMENT, "walls with version 2 options")
    call check(index(anitet_last_error_message(), "version 3") > 0, "walls with v2: message")
    call anitet_surface_destroy(surface)
  end subroutine

  ! A mesh read from a file was made by no run: no stats, no report.
  subroutine check_run_report_errors(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: mesh
    type(anitet_run_stats_t) :: st
    character(len=:), allocatable :: json
    call check(anitet_mesh_read(path, mesh) == ANITET_OK, "read " // path)
    call check(anitet_mesh_get_run_stats(mesh, st) == ANITET_ERR_INVALID_ARGUMENT, "stats of a read mesh")
    call check(index(anitet_last_error_message(), "not made by anitet_mesher_run") > 0, &
               "stats of a read mesh: message")
    call check(anitet_mesh_run_json(mesh, json) == ANITET_ERR_INVALID_ARGUMENT .and. len(json) == 0, &
               "report of a read mesh")
    call anitet_mesh_destroy(mesh)
    call check(anitet_mesh_get_run_stats(mesh, st) == ANITET_ERR_INVALID_ARGUMENT, "stats of no mesh")
  end subroutine

  ! Stage 1 alone on the sphere in the box with 3 boundary layers: T1 holds the input's triangles
  ! under their labels and the new front under label 5; its stats the layers measured on T1.
  subroutine check_layers_run()
    real(c_double) :: xyz(3, SPHERE_IN_BOX_NPOINTS)
    integer(c_int32_t) :: tri(3, SPHERE_IN_BOX_NTRI), patch(SPHERE_IN_BOX_NTRI)
    integer(c_int32_t), allocatable :: t1_patch(:)
    type(c_ptr) :: surface, t1, again
    type(anitet_options_t) :: o
    type(anitet_run_stats_t) :: st
    integer(c_int64_t) :: np, nt, nb, nt2
    character(len=:), allocatable :: json
    call sphere_in_box_build(xyz, tri, patch)
    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "sphere in box")
    call check(anitet_options_init(o) == ANITET_OK, "options")
    o%bl_first_height = 0.02d0
    o%bl_growth = 1.25d0
    o%bl_layers = 3
    call check(anitet_layers_run(surface, t1, options=o, bl_patches=[1, 2, 3]) == ANITET_OK, &
               "layers run")
    call check(anitet_mesh_get_counts(t1, np, nt, nb) == ANITET_OK, "T1 counts")
    call check(anitet_mesh_get_boundary_patches(t1, t1_patch) == ANITET_OK, "T1 patches")
    call check(nb > SPHERE_IN_BOX_NTRI .and. all(t1_patch(1:SPHERE_IN_BOX_NTRI) == patch) .and. &
               all(t1_patch(SPHERE_IN_BOX_NTRI + 1:) == 5), "T1: the input's labels, then S1 as 5")
    call check(anitet_mesh_get_run_stats(t1, st) == ANITET_OK, "T1 run stats")
    call check(st%layers_used == 1 .and. st%recovery_strategy == 0 .and. st%refine_passes == 0 &
               .and. st%tets == nt, "T1 stats: one layer, no recovery, no refinement")
    call check(st%bl_layers == 3 .and. st%bl_wall_vertices == SPHERE_NPOINTS .and. &
               st%bl_full_columns == SPHERE_NPOINTS .and. st%bl_tets > 0 .and. st%bl_tets < nt .and. &
               abs(st%bl_first_height_mean - 0.02d0) < 0.002d0, "T1 stats: the boundary layer")
    call check(anitet_mesh_run_json(t1, json) == ANITET_OK, "T1 run json")
    call check(index(json, '"layers"') > 0, "T1 run json text")
    ! One push at a time: the same T1.
    o%push_tasks_min_vertices = 0
    call check(anitet_layers_run(surface, again, options=o, bl_patches=[1, 2, 3]) == ANITET_OK, &
               "layers run, pushes one by one")
    call check(anitet_mesh_get_counts(again, np, nt2, nb) == ANITET_OK, "T1 counts again")
    call check(nt2 == nt, "the same T1")
    call anitet_mesh_destroy(again)
    ! Errors.
    o%push_tasks_min_vertices = -1
    call check(anitet_layers_run(surface, again, options=o, bl_patches=[1, 2, 3]) == &
               ANITET_ERR_INVALID_ARGUMENT, "push_tasks_min_vertices -1")
    call check(index(anitet_last_error_message(), "push_tasks_min_vertices") > 0, &
               "push_tasks_min_vertices: message")
    call check(.not. c_associated(again), "no T1 on error")
    call check(anitet_layers_run(surface, again, bl_patches=[1, 9]) == ANITET_ERR_INVALID_ARGUMENT, &
               "layers run: walls without a first height")
    call check(anitet_options_init(o, 2) == ANITET_OK, "options v2")
    call check(anitet_layers_run(surface, again, options=o, bl_patches=[1]) == &
               ANITET_ERR_INVALID_ARGUMENT, "layers run: walls with version 2 options")
    call check(index(anitet_last_error_message(), "anitet_layers_run") > 0, "v2 walls: message")
    call check(anitet_layers_run(surface, again) == ANITET_OK, "layers run, default options")
    call anitet_mesh_destroy(again)
    call anitet_mesh_destroy(t1)
    call anitet_surface_destroy(surface)
  end subroutine

  subroutine check_bl_first_height()
    real(c_double) :: h0, cf
    cf = 0.026d0 * 1d6**(-1d0 / 7d0)
    call check(anitet_bl_first_height(1d0, 1d6, 1d0, h0) == ANITET_OK, "y+ 1 at Re 1e6")
    call check(abs(h0 - 1d0 / (1d6 * sqrt(cf / 2d0))) < 1d-18, "y+ 1: the flat-plate h0")
    call check(anitet_bl_first_height(0d0, 1d6, 1d0, h0) == ANITET_ERR_INVALID_ARGUMENT, "y+ 0")
    call check(anitet_bl_first_height(1d0, 1d6, -1d0, h0) == ANITET_ERR_INVALID_ARGUMENT, &
               "a negative reference length")
  end subroutine

  ! The field the mesher follows without a metric, bounded by hmax, written as a .vdb and read
  ! back; another metric written over the sphere's box.
  subroutine check_surface_sizing()
    real(c_double) :: xyz(3, SPHERE_NPOINTS)
    integer(c_int32_t) :: faces(3, SPHERE_NTRI), patch(SPHERE_NTRI)
    type(c_ptr) :: surface, field, back, uniform
    type(anitet_options_t) :: o
    real(c_double) :: a(6), b(6)
    call sphere_build(xyz, faces, patch)
    call check(anitet_surface_create(xyz, faces, surface, patch) == ANITET_OK, "sphere surface")
    call check(anitet_options_init(o) == ANITET_OK, "options")
    o%hmax = 0.1d0
    call check(anitet_metric_create_surface_sizing(surface, field, o) == ANITET_OK, &
               "surface sizing, hmax 0.1")
    call check(anitet_metric_evaluate(field, [0d0, 0d0, 0d0], a) == ANITET_OK, "evaluate sizing")
    call check(a(1) >= 100d0 * (1 - 1d-6) .and. a(3) >= 100d0 * (1 - 1d-6), "hmax bounds the field")
    call check(anitet_metric_write(field, "fortran_sizing.vdb") == ANITET_OK, "write sizing .vdb")
    call check(anitet_metric_read("fortran_sizing.vdb", back) == ANITET_OK, "read sizing .vdb")
    call check(anitet_metric_evaluate(back, [0d0, 0d0, 0d0], b) == ANITET_OK, "evaluate read back")
    call check(abs(b(1) - a(1)) <= 1d-5 * a(1) .and. abs(b(6) - a(6)) <= 1d-5 * a(6), &
               "the same field read back")
    call anitet_metric_destroy(back)
    call anitet_metric_destroy(field)
    call check(anitet_metric_create_surface_sizing(surface, field) == ANITET_OK, &
               "surface sizing, no options")
    call anitet_metric_destroy(field)
    ! Another metric is sampled over a surface's box, which must then be given.
    call check(anitet_metric_create_uniform(0.3d0, uniform) == ANITET_OK, "uniform")
    call check(anitet_metric_write(uniform, "fortran_uniform.vdb") == ANITET_ERR_INVALID_ARGUMENT, &
               "no box to sample on")
    call check(index(anitet_last_error_message(), "box_of") > 0, "no box: message")
    call check(anitet_metric_write(uniform, "fortran_uniform.vdb", surface) == ANITET_OK, &
               "uniform written over the sphere's box")
    call check(anitet_metric_read("fortran_uniform.vdb", back) == ANITET_OK, "read uniform .vdb")
    call check(anitet_metric_evaluate(back, [0.2d0, -0.3d0, 0.1d0], b) == ANITET_OK, "evaluate")
    call check(abs(b(1) - 1d0 / 0.09d0) < 1d-4 .and. abs(b(2)) < 1d-9, "size 0.3 read back")
    call anitet_metric_destroy(back)
    call check(anitet_metric_write(uniform, "fortran_uniform.sol", surface) == &
               ANITET_ERR_UNSUPPORTED_FORMAT, "write .sol refused")
    o%hgrad = 0.5d0
    call check(anitet_metric_create_surface_sizing(surface, field, o) == ANITET_ERR_INVALID_ARGUMENT, &
               "hgrad 0.5")
    call check(.not. c_associated(field), "no field on error")
    call anitet_metric_destroy(uniform)
    call anitet_surface_destroy(surface)
  end subroutine

  ! A metric sampled at a mesh's points (sizes, then tensors), its .sol read back on the mesh in
  ! memory; a failing callback leaves the metric as it was.
  subroutine check_sample_metric(box_path)
    character(len=*), intent(in) :: box_path
    type(c_ptr) :: mesh, uniform, stretched, on_mesh
    real(c_double), allocatable :: values(:, :)
    real(c_double) :: m(6)
    integer :: components
    type(c_funptr) :: callback
    call check(anitet_mesh_read(box_path, mesh) == ANITET_OK, "read " // box_path)
    call check(anitet_metric_create_uniform(0.25d0, uniform) == ANITET_OK, "uniform")
    call check(anitet_mesh_sample_metric(mesh, uniform) == ANITET_OK, "sample uniform")
    call check(anitet_mesh_get_metric(mesh, values) == ANITET_OK, "sampled metric")
    call check(size(values, 1) == 1 .and. all(values == 0.25d0), "sizes where isotropic")
    callback = c_funloc(stretched_below_x1)  ! (a variable: a constant trips PIE linking)
    call check(anitet_metric_create_analytic(callback, c_null_ptr, stretched) == ANITET_OK, &
               "analytic metric")
    call check(anitet_mesh_sample_metric(mesh, stretched) == ANITET_OK, "sample stretched")
    call check(anitet_mesh_get_metric(mesh, values) == ANITET_OK, "sampled tensors")
    call check(size(values, 1) == 6 .and. all(values(1, :) == 100d0) .and. all(values(3, :) == 4d0), &
               "tensors where anisotropic")
    call check(anitet_mesh_write_metric(mesh, "fortran_sampled.sol") == ANITET_OK, "write .sol")
    call check(anitet_metric_read_on_mesh("fortran_sampled.sol", mesh, on_mesh) == ANITET_OK, &
               "read .sol on the mesh in memory")
    call check(anitet_metric_evaluate(on_mesh, [0.5d0, 0.05d0, 0.5d0], m) == ANITET_OK, "evaluate")
    call check(abs(m(1) - 100d0) < 1d-9 .and. abs(m(3) - 4d0) < 1d-9, "the .sol's tensors")
    call anitet_metric_destroy(on_mesh)
    call check(anitet_metric_read_on_mesh("no_such.sol", mesh, on_mesh) == ANITET_ERR_FILE_NOT_FOUND, &
               "read_on_mesh: missing file")
    call check(anitet_metric_read_on_mesh("fortran_sampled.sol", c_null_ptr, on_mesh) == &
               ANITET_ERR_INVALID_ARGUMENT, "read_on_mesh: no mesh")
    call check(anitet_mesh_sample_metric(mesh, c_null_ptr) == ANITET_ERR_INVALID_ARGUMENT, &
               "sample: no metric")
    ! Beyond x = 1.5 the callback fails: an error, the mesh's metric unchanged.
    call scale_mesh(mesh, 2d0)
    call check(anitet_mesh_sample_metric(mesh, uniform) == ANITET_OK, "sample the scaled mesh")
    call check(anitet_mesh_sample_metric(mesh, stretched) == ANITET_ERR_INVALID_ARGUMENT, &
               "a failing callback")
    call check(index(anitet_last_error_message(), "returned 3") > 0, "failing callback: message")
    call check(anitet_mesh_get_metric_components(mesh, components) == ANITET_OK, "components")
    call check(components == 1, "the metric unchanged")
    call anitet_metric_destroy(stretched)
    call anitet_metric_destroy(uniform)
    call anitet_mesh_destroy(mesh)
  end subroutine

  ! Replaces `mesh` by a copy with its points times `factor`.
  subroutine scale_mesh(mesh, factor)
    type(c_ptr), intent(inout) :: mesh
    real(c_double), intent(in) :: factor
    real(c_double), allocatable :: xyz(:, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    call check(anitet_mesh_get_points(mesh, xyz) == ANITET_OK, "points")
    call check(anitet_mesh_get_tets(mesh, tets) == ANITET_OK, "tets")
    call anitet_mesh_destroy(mesh)
    call check(anitet_mesh_create(factor * xyz, tets, mesh) == ANITET_OK, "scaled mesh")
  end subroutine

  ! The unit cube as a box of 0.01 deg x 0.01 deg x 1000 m at (lon 7.44, lat 46.95): meshed in
  ! an ENU frame at its centre and moved back, its points exactly as given; a UTM frame's zone.
  subroutine check_geo_frames()
    real(c_double) :: lonlat(3, 8), local(3, 8)
    integer(c_int32_t) :: tri(3, 12)
    real(c_double), allocatable :: xyz(:, :)
    type(c_ptr) :: geo, moved, frame, sizing, mesh, made
    real(c_double) :: lat, lon, h
    integer :: zone, i
    logical :: north
    lonlat = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 1d0, 1d0, 0d0, 0d0, 1d0, 0d0, &
                      0d0, 0d0, 1d0, 1d0, 0d0, 1d0, 1d0, 1d0, 1d0, 0d0, 1d0, 1d0], [3, 8])
    do i = 1, 8
      lonlat(:, i) = [7.44d0, 46.95d0, 0d0] + [0.01d0, 0.01d0, 1000d0] * lonlat(:, i)
    end do
    tri = reshape([1, 3, 2, 1, 4, 3, 5, 6, 7, 5, 7, 8, 1, 2, 6, 1, 6, 5, &
                   4, 8, 7, 4, 7, 3, 1, 5, 8, 1, 8, 4, 2, 3, 7, 2, 7, 6], [3, 12])
    call check(anitet_surface_create(lonlat, tri, geo) == ANITET_OK, "geodetic box")
    call check(anitet_surface_create(lonlat, tri, moved) == ANITET_OK, "geodetic box, to move")
    call check(anitet_geo_frame_create_centred(ANITET_GEO_ENU, moved, frame) == ANITET_OK, &
               "ENU frame at the centre")
    call check(anitet_geo_frame_get(frame, lat, lon, h, zone) == ANITET_OK, "frame origin")
    call check(abs(lat - 46.955d0) < 1d-9 .and. abs(lon - 7.445d0) < 1d-9 .and. &
               abs(h - 500d0) < 1d-9 .and. zone == 0, "the box's centre, no UTM zone")
    call check(anitet_surface_to_local(moved, frame) == ANITET_OK, "surface to local")
    call check(anitet_surface_get_points(moved, xyz) == ANITET_OK, "local points")
    local = xyz
    ! Metres: about 760 m east-west, 1112 m north-south, 1000 m high.
    call check(abs(local(1, 2) - local(1, 1) - 760d0) < 10d0 .and. &
               abs(local(2, 4) - local(2, 1) - 1112d0) < 10d0 .and. &
               abs(local(3, 5) - local(3, 1) - 1000d0) < 1d0, "the box in metres")
    call check(anitet_metric_create_uniform(300d0, sizing) == ANITET_OK, "size 300 m")
    call check(anitet_mesher_run(moved, mesh, sizing) == ANITET_OK, "mesh in the local frame")
    call check(anitet_mesh_to_geodetic(mesh, frame, geo) == ANITET_OK, "mesh to geodetic")
    call check(anitet_mesh_get_points(mesh, xyz) == ANITET_OK, "geodetic points")
    call check(size(xyz, 2) > 8, "points inside")
    call check(all(xyz(:, 1:8) == lonlat), "the surface's points exactly as given")
    call check(all(xyz(1, :) > 7.44d0 - 1d-9 .and. xyz(1, :) < 7.45d0 + 1d-9 .and. &
                   xyz(2, :) > 46.95d0 - 1d-9 .and. xyz(2, :) < 46.96d0 + 1d-9), "in the box")
    ! A mesh made from arrays: moved to the frame and back, but not against a surface.
    call check(anitet_mesh_create(lonlat, reshape([1_c_int32_t, 2_c_int32_t, 4_c_int32_t, &
               5_c_int32_t], [4, 1]), made) == ANITET_OK, "one tet")
    call check(anitet_mesh_to_local(made, frame) == ANITET_OK, "mesh to local")
    call check(anitet_mesh_to_geodetic(made, frame, geo) == ANITET_ERR_INVALID_ARGUMENT, &
               "geodetic surface for a mesh no run made")
    call check(index(anitet_last_error_message(), "not made by anitet_mesher_run") > 0, &
               "no run: message")
    call check(anitet_mesh_to_geodetic(made, frame) == ANITET_OK, "mesh back without a surface")
    call check(anitet_mesh_get_points(made, xyz) == ANITET_OK, "points back")
    call check(all(abs(xyz(1:2, :) - lonlat(1:2, :)) < 1d-9) .and. &
               all(abs(xyz(3, :) - lonlat(3, :)) < 1d-6), "a round trip to rounding")
    call anitet_mesh_destroy(made)
    call anitet_geo_frame_destroy(frame)
    call check(.not. c_associated(frame), "destroy clears the frame")
    ! UTM: zone 32 north at 7.44 E.
    call check(anitet_geo_frame_create(ANITET_GEO_UTM, 46.95d0, 7.44d0, 0d0, frame) == ANITET_OK, &
               "UTM frame")
    call check(anitet_geo_frame_get(frame, utm_zone=zone, utm_north=north) == ANITET_OK, "UTM zone")
    call check(zone == 32 .and. north, "UTM zone 32 north")
    call anitet_geo_frame_destroy(frame)
    ! Errors.
    call check(anitet_geo_frame_create(7, 46d0, 7d0, 0d0, frame) == ANITET_ERR_INVALID_ARGUMENT, &
               "frame kind 7")
    call check(index(anitet_last_error_message(), "kind is 7") > 0, "kind 7: message")
    call check(.not. c_associated(frame), "no frame on error")
    call check(anitet_geo_frame_create(ANITET_GEO_ENU, 95d0, 7d0, 0d0, frame) == &
               ANITET_ERR_INVALID_ARGUMENT, "latitude 95")
    call check(anitet_geo_frame_get(c_null_ptr, lat) == ANITET_ERR_INVALID_ARGUMENT, "get: no frame")
    call check(anitet_surface_to_local(geo, c_null_ptr) == ANITET_ERR_INVALID_ARGUMENT, &
               "to local: no frame")
    call anitet_mesh_destroy(mesh)
    call anitet_metric_destroy(sizing)
    call anitet_surface_destroy(moved)
    call anitet_surface_destroy(geo)
  end subroutine

  ! The whole file as one string.
  ! A pipe along z (radius 1, length 2, 16 segments, 7 rings): wall 1, inlet 2 (z = 0), outlet 3
  ! (z = 2), each cap a fan around its centre.
  subroutine pipe_surface(surface)
    type(c_ptr), intent(out) :: surface
    integer, parameter :: n = 16, rings = 7, np = n * rings + 2, ntri = 2 * n * (rings - 1) + 2 * n
    real(c_double) :: xyz(3, np), a
    integer(c_int32_t) :: tri(3, ntri), patch(ntri)
    integer :: i, j, t, c0, c1, top
    c0 = n * rings + 1
    c1 = c0 + 1
    top = n * (rings - 1)
    do j = 0, rings - 1
      do i = 0, n - 1
        a = 2 * acos(-1d0) * i / n
        xyz(:, j * n + i + 1) = [cos(a), sin(a), 2d0 * j / (rings - 1)]
      end do
    end do
    xyz(:, c0) = [0d0, 0d0, 0d0]
    xyz(:, c1) = [0d0, 0d0, 2d0]
    t = 0
    do j = 0, rings - 2
      do i = 0, n - 1
        tri(:, t + 1) = [j * n + i, j * n + mod(i + 1, n), (j + 1) * n + mod(i + 1, n)] + 1
        tri(:, t + 2) = [j * n + i, (j + 1) * n + mod(i + 1, n), (j + 1) * n + i] + 1
        patch(t + 1:t + 2) = 1
        t = t + 2
      end do
    end do
    do i = 0, n - 1
      tri(:, t + 1) = [i + 1, c0, mod(i + 1, n) + 1]
      tri(:, t + 2) = [top + i + 1, top + mod(i + 1, n) + 1, c1]
      patch(t + 1) = 2
      patch(t + 2) = 3
      t = t + 2
    end do
    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "pipe surface")
  end subroutine

  ! Boundary layers on the pipe's wall sliding along its caps (options version 4).
  subroutine check_slide_patches()
    type(c_ptr) :: surface, mesh
    type(anitet_options_t), target :: o
    integer(c_int32_t), target :: caps(2) = [2, 3]
    type(anitet_run_stats_t) :: st
    integer(c_int32_t), allocatable :: patch(:)
    character(len=:), allocatable :: json
    call pipe_surface(surface)
    call check(anitet_options_init(o) == ANITET_OK, "options")
    o%bl_first_height = 0.01d0
    o%bl_layers = 4
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1]) == &
               ANITET_ERR_INVALID_ARGUMENT, "a wall meeting the caps without slide patches")
    call check(index(anitet_last_error_message(), "bl_slide_patches 2") > 0, &
               "without slide patches: message")
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1], bl_slide_patches=[2, 3]) &
               == ANITET_OK, "slide patches by bl_slide_patches=")
    call check(anitet_mesh_get_run_stats(mesh, st) == ANITET_OK, "slide: run stats")
    call check(st%bl_layers == 4 .and. st%bl_wall_vertices == 16 * 7 .and. &
               st%bl_full_columns == 16 * 7, "slide: every wall vertex a full column")
    call check(st%slide_junction_columns == 32 .and. st%slide_lowered_columns == 0 .and. &
               st%slide_triangles_added > 0, "slide: run stats version 2")
    call check(anitet_mesh_run_json(mesh, json) == ANITET_OK, "slide: run json")
    call check(index(json, '"slide_patches"') > 0, "slide: the report's slide patches")
    call check(anitet_mesh_get_boundary_patches(mesh, patch) == ANITET_OK, "slide: patches")
    call check(count(patch == 1) == 2 * 16 * 6 .and. count(patch == 2) > 16 .and. &
               count(patch == 3) > 16, "slide: the wall as given, the caps triangulated again")
    call anitet_mesh_destroy(mesh)
    ! The labels by c_loc in the struct.
    o%bl_num_slide_patches = size(caps)
    o%bl_slide_patches = c_loc(caps)
    call check(anitet_layers_run(surface, mesh, options=o, bl_patches=[1]) == ANITET_OK, &
               "stage 1 with slide patches by c_loc")
    call anitet_mesh_destroy(mesh)
    ! Errors: slide patches without walls; with version 3 options.
    call check(anitet_mesher_run(surface, mesh, options=o) == ANITET_ERR_INVALID_ARGUMENT, &
               "slide patches without walls")
    call check(index(anitet_last_error_message(), "needs boundary-layer walls") > 0, &
               "slide patches without walls: message")
    call check(anitet_options_init(o, 3) == ANITET_OK, "options v3")
    o%bl_first_height = 0.01d0
    call check(anitet_mesher_run(surface, mesh, options=o, bl_patches=[1], bl_slide_patches=[2, 3]) &
               == ANITET_ERR_INVALID_ARGUMENT, "slide patches with version 3 options")
    call check(index(anitet_last_error_message(), "version 4") > 0, "slide patches with v3: message")
    call check(.not. c_associated(mesh), "no mesh on error")
    call anitet_surface_destroy(surface)
  end subroutine

  ! Patch types of the box's six faces in OpenFOAM's boundary file.
  subroutine check_patch_types(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: mesh
    integer :: type, rc
    character(len=:), allocatable :: boundary
    character(len=*), parameter :: entry = new_line("a") // "    {" // new_line("a") // &
                                           "        type            "
    call check(anitet_mesh_read(path, mesh) == ANITET_OK, "read " // path)
    rc = anitet_mesh_get_patch_type(mesh, 3, type)
    call check(rc == ANITET_OK .and. type == ANITET_PATCH_TYPE_WALL, "patch 3: a wall by default")
    call check(anitet_mesh_set_patch_name(mesh, 2, "inlet") == ANITET_OK, "name patch 2")
    rc = anitet_mesh_get_patch_type(mesh, 2, type)
    call check(rc == ANITET_OK .and. type == ANITET_PATCH_TYPE_INLET, "patch 2: an inlet by its name")
    call check(anitet_mesh_set_patch_type(mesh, 1, ANITET_PATCH_TYPE_SYMMETRY) == ANITET_OK, &
               "patch 1 a symmetry plane")
    call check(anitet_mesh_set_patch_type(mesh, 4, ANITET_PATCH_TYPE_FARFIELD) == ANITET_OK, &
               "patch 4 a farfield")
    call check(anitet_mesh_set_patch_type(mesh, 4, ANITET_PATCH_TYPE_FROM_NAME) == ANITET_OK, &
               "patch 4 from its name again")
    rc = anitet_mesh_get_patch_type(mesh, 4, type)
    call check(rc == ANITET_OK .and. type == ANITET_PATCH_TYPE_WALL, "patch 4: a wall again")
    call check(anitet_mesh_write(mesh, "fortran_types/constant/polyMesh") == ANITET_OK, "write polyMesh")
    boundary = file_text("fortran_types/constant/polyMesh/boundary")
    call check(index(boundary, "patch1" // entry // "symmetryPlane;") > 0, "patch1 symmetryPlane")
    call check(index(boundary, "inlet" // entry // "patch;") > 0, "inlet patch")
    call check(index(boundary, "patch3" // entry // "wall;") > 0, "patch3 wall")
    call check(anitet_mesh_set_patch_type(mesh, 1, 6) == ANITET_ERR_INVALID_ARGUMENT, "type 6")
    call check(anitet_mesh_set_patch_type(mesh, 9, ANITET_PATCH_TYPE_WALL) == &
               ANITET_ERR_INVALID_ARGUMENT, "no patch 9")
    call check(index(anitet_last_error_message(), "patch label 9") > 0, "no patch 9: message")
    call anitet_mesh_destroy(mesh)
  end subroutine

  ! Linear fields on the box carried to its own points and to a mesh twice as large; a .solb
  ! round trip; the errors.
  subroutine check_fields(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: box, big, fields, moved, back
    real(c_double), allocatable :: xyz(:, :), values(:, :), got(:, :)
    real(c_double), pointer :: data(:, :)
    integer(c_int32_t), allocatable :: kinds(:)
    logical, allocatable :: log_euclidean(:)
    integer(c_int64_t) :: nv, outside
    real(c_double) :: distance
    integer :: nf, record, i, rc
    call check(anitet_mesh_read(path, box) == ANITET_OK, "read " // path)
    call check(anitet_mesh_get_points(box, xyz) == ANITET_OK, "box points")
    allocate(values(4, size(xyz, 2)))
    do i = 1, size(xyz, 2)
      values(:, i) = [1 + 2 * xyz(1, i) - xyz(2, i) + 3 * xyz(3, i), xyz(:, i)]
    end do
    call check(anitet_fields_create([ANITET_FIELD_KIND_SCALAR, ANITET_FIELD_KIND_VECTOR], values, &
                                    fields) == ANITET_OK, "fields from arrays")
    rc = anitet_fields_get_counts(fields, nf, record, nv)
    call check(rc == ANITET_OK .and. nf == 2 .and. record == 4 .and. nv == 8, "fields counts")
    call check(anitet_fields_get_kinds(fields, kinds) == ANITET_OK, "fields kinds")
    call check(all(kinds == [ANITET_FIELD_KIND_SCALAR, ANITET_FIELD_KIND_VECTOR]), "kinds values")
    call check(anitet_fields_get_data(fields, data) == ANITET_OK, "fields data, no copy")
    call check(all(shape(data) == [4, 8]) .and. all(data == values), "fields data values")
    ! To the box's own points: the same values; to a mesh twice as large: points outside.
    call check(anitet_mesh_transfer_fields(box, fields, box, moved, num_threads=1) == ANITET_OK, &
               "transfer on one thread")
    call check(anitet_fields_get_values(moved, got) == ANITET_OK, "transferred values")
    call check(all(shape(got) == [4, 8]) .and. maxval(abs(got - values)) < 1d-12, &
               "transfer to the same points")
    rc = anitet_fields_get_transfer_report(moved, outside, distance, log_euclidean)
    call check(rc == ANITET_OK .and. outside == 0 .and. distance == 0d0, "transfer report")
    call check(allocated(log_euclidean), "transfer report: per field")
    if (allocated(log_euclidean)) call check(size(log_euclidean) == 2 .and. .not. any(log_euclidean), &
                                             "transfer report: no field in log space")
    call anitet_fields_destroy(moved)
    call check(anitet_mesh_read(path, big) == ANITET_OK, "read the box again")
    call scale_mesh(big, 2d0)
    call check(anitet_mesh_transfer_fields(box, fields, big, moved, ANITET_TENSORS_LINEAR) == &
               ANITET_OK, "transfer to a larger mesh")
    rc = anitet_fields_get_transfer_report(moved, outside=outside, max_outside_distance=distance)
    call check(rc == ANITET_OK .and. outside > 0 .and. distance > 0d0, "points outside counted")
    call anitet_fields_destroy(moved)
    ! A .solb round trip.
    call check(anitet_fields_write(fields, "fortran_fields.solb") == ANITET_OK, "write .solb")
    call check(anitet_fields_read("fortran_fields.solb", back) == ANITET_OK, "read .solb")
    call check(anitet_fields_get_values(back, got) == ANITET_OK, ".solb: values")
    call check(all(got == values), ".solb: the same values")
    call anitet_fields_destroy(back)
    ! Errors: fields of another mesh, an unknown tensor mode, a report of fields not transferred.
    call check(anitet_mesh_transfer_fields(big, fields, box, moved, 7) == ANITET_ERR_INVALID_ARGUMENT, &
               "tensors 7")
    call check(anitet_mesh_transfer_fields(box, fields, box, moved, num_threads=-1) == &
               ANITET_ERR_INVALID_ARGUMENT, "num_threads -1")
    call anitet_fields_destroy(fields)
    call check(anitet_fields_create([ANITET_FIELD_KIND_SCALAR], values(1:1, 1:7), fields) == &
               ANITET_OK, "7 values")
    call check(anitet_mesh_transfer_fields(box, fields, big, moved) == ANITET_ERR_INVALID_ARGUMENT, &
               "fields of another mesh")
    call check(index(anitet_last_error_message(), "another mesh") > 0, "another mesh: message")
    call check(.not. c_associated(moved), "no fields on error")
    call check(anitet_fields_get_transfer_report(fields, outside) == ANITET_ERR_INVALID_ARGUMENT, &
               "no transfer report")
    call anitet_fields_destroy(fields)
    call check(.not. c_associated(fields), "destroyed")
    call check(anitet_fields_read("fortran_fields.txt", fields) == ANITET_ERR_UNSUPPORTED_FORMAT, &
               "fields: unknown extension")
    call anitet_mesh_destroy(big)
    call anitet_mesh_destroy(box)
  end subroutine

  function file_text(path) result(text)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: text
    integer :: unit, n
    open(newunit=unit, file=path, access="stream", form="unformatted", status="old", action="read")
    inquire(unit=unit, size=n)
    allocate(character(len=n) :: text)
    read(unit) text
    close(unit)
  end function

  ! One pass of anitet_adapt on the UGAWG cube to its linear metric (evaluated at the points), a
  ! linear field carried exactly; the errors a Fortran caller meets.
  subroutine check_adapt(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: cube, fields, out, moved
    type(anitet_adapt_options_t) :: o
    type(anitet_adapt_stats_t) :: st
    real(c_double), allocatable :: xyz(:, :), metric(:, :), values(:, :), got(:, :)
    integer(c_int64_t) :: np, nt, nb
    integer :: i
    call check(anitet_mesh_read(path, cube) == ANITET_OK, "adapt: read the cube")
    call check(anitet_mesh_get_points(cube, xyz) == ANITET_OK, "adapt: points")
    allocate(metric(6, size(xyz, 2)), values(1, size(xyz, 2)))
    do i = 1, size(xyz, 2)
      metric(:, i) = [100d0, 0d0, 100d0, 0d0, 0d0, &
                      1d0 / (0.001d0 + 2d0 * (0.1d0 - 0.001d0) * abs(xyz(3, i) - 0.5d0))**2]
      values(1, i) = 1d0 + 2d0 * xyz(1, i) - xyz(2, i) + 3d0 * xyz(3, i)
    end do
    call check(anitet_fields_create([ANITET_FIELD_KIND_SCALAR], values, fields) == ANITET_OK, &
               "adapt: a linear field")
    call check(anitet_adapt_options_init(o) == ANITET_OK .and. o%max_cycles == 30, "adapt: options")
    call check(anitet_adapt(cube, metric, out, fields=fields, out_fields=moved, options=o, stats=st) &
               == ANITET_OK, "adapt: one pass")
    call check(anitet_mesh_get_counts(out, np, nt, nb) == ANITET_OK .and. st%vertices == np .and. &
               st%tets == nt .and. st%vertices_in == size(xyz, 2), "adapt: counts")
    call check(st%edges_in_range > 0.9d0 .and. st%mean_ratio_min > 0d0, "adapt: edges in range")
    deallocate(xyz)
    call check(anitet_mesh_get_points(out, xyz) == ANITET_OK, "adapt: new points")
    call check(anitet_fields_get_values(moved, got) == ANITET_OK .and. size(got, 2) == np, &
               "adapt: carried field")
    call check(maxval(abs(got(1, :) - (1d0 + 2d0 * xyz(1, :) - xyz(2, :) + 3d0 * xyz(3, :)))) < 1d-9, &
               "adapt: a linear field carried exactly")
    call anitet_fields_destroy(moved)
    call anitet_mesh_destroy(out)
    ! Errors: a metric of another mesh, an unknown options version, fields without out_fields.
    call check(anitet_adapt(cube, metric(:, 1:10), out) == ANITET_ERR_INVALID_ARGUMENT .and. &
               .not. c_associated(out), "adapt: metric of the wrong length")
    call check(index(anitet_last_error_message(), "metric_len is 60") > 0, "adapt: its message")
    o%version = 99
    call check(anitet_adapt(cube, metric, out, options=o) == ANITET_ERR_INVALID_ARGUMENT, &
               "adapt: options version 99")
    call check(anitet_adapt(cube, metric, out, fields=fields) == ANITET_ERR_INVALID_ARGUMENT, &
               "adapt: fields without out_fields")
    call anitet_fields_destroy(fields)
    call anitet_mesh_destroy(cube)
  end subroutine

end program test_fortran
