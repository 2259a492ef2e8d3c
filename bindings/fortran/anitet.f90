! Fortran module `anitet`: iso_c_binding interfaces to every entry point of include/anitet.h
! (named c_<C name>, bound to the C name) and thin Fortran wrappers named like the C functions:
! 1-based indices by default, arrays shaped (3, n) / (4, n), allocatable outputs, Fortran
! strings for paths and messages. Handles are type(c_ptr); a destroy sets its argument to
! c_null_ptr. tests/fortran/check_interfaces.cmake checks that every C function has an interface
! here and that the error codes agree, so the two cannot drift.
module anitet
  use, intrinsic :: iso_c_binding
  implicit none
  private

  ! ---- constants (equal to the header's macros) ------------------------------------------------
  integer(c_int), parameter, public :: ANITET_VERSION_MAJOR = 0
  integer(c_int), parameter, public :: ANITET_VERSION_MINOR = 1
  integer(c_int), parameter, public :: ANITET_VERSION_PATCH = 0
  integer(c_int), parameter, public :: ANITET_OK = 0
  integer(c_int), parameter, public :: ANITET_ERR_INVALID_ARGUMENT = -1
  integer(c_int), parameter, public :: ANITET_ERR_FILE_NOT_FOUND = -2
  integer(c_int), parameter, public :: ANITET_ERR_PARSE = -3
  integer(c_int), parameter, public :: ANITET_ERR_UNSUPPORTED_FORMAT = -4
  integer(c_int), parameter, public :: ANITET_ERR_EMPTY_INPUT = -5
  integer(c_int), parameter, public :: ANITET_ERR_BUFFER_TOO_SMALL = -6
  integer(c_int), parameter, public :: ANITET_ERR_NON_FINITE_COORDINATE = -10
  integer(c_int), parameter, public :: ANITET_ERR_DEGENERATE_TRIANGLE = -11
  integer(c_int), parameter, public :: ANITET_ERR_DUPLICATE_TRIANGLE = -12
  integer(c_int), parameter, public :: ANITET_ERR_OPEN_BOUNDARY = -13
  integer(c_int), parameter, public :: ANITET_ERR_NON_MANIFOLD_EDGE = -14
  integer(c_int), parameter, public :: ANITET_ERR_NON_MANIFOLD_VERTEX = -15
  integer(c_int), parameter, public :: ANITET_ERR_INCONSISTENT_ORIENTATION = -16
  integer(c_int), parameter, public :: ANITET_ERR_SELF_INTERSECTION = -17
  integer(c_int), parameter, public :: ANITET_ERR_INTERSECTING_SHELLS = -18
  integer(c_int), parameter, public :: ANITET_ERR_BAD_INDEX = -19
  integer(c_int), parameter, public :: ANITET_ERR_NOT_IMPLEMENTED = -30
  integer(c_int), parameter, public :: ANITET_ERR_CANCELLED = -31
  integer(c_int), parameter, public :: ANITET_ERR_DUPLICATE_POINT = -32
  integer(c_int), parameter, public :: ANITET_ERR_RECOVERY_FAILED = -33
  integer(c_int), parameter, public :: ANITET_ERR_INVALID_MESH = -34
  integer(c_int), parameter, public :: ANITET_ERR_OUT_OF_MEMORY = -40
  integer(c_int), parameter, public :: ANITET_ERR_INTERNAL = -99
  integer(c_int32_t), parameter, public :: ANITET_LOG_ERROR = 0
  integer(c_int32_t), parameter, public :: ANITET_LOG_WARNING = 1
  integer(c_int32_t), parameter, public :: ANITET_LOG_INFO = 2
  integer(c_int32_t), parameter, public :: ANITET_LOG_DEBUG = 3
  integer(c_int32_t), parameter, public :: ANITET_OPTIONS_VERSION = 5
  integer(c_int32_t), parameter, public :: ANITET_LAYERS_PUSH = 0
  integer(c_int32_t), parameter, public :: ANITET_LAYERS_FACE_PUSH = 1
  integer(c_int32_t), parameter, public :: ANITET_RECOVERY_ALL = 0
  integer(c_int32_t), parameter, public :: ANITET_RECOVERY_SPLIT = 1
  integer(c_int32_t), parameter, public :: ANITET_RECOVERY_FUZZY = 2
  ! options%bl_cells: the cells anitet_mesh_write writes the boundary layer as
  integer(c_int32_t), parameter, public :: ANITET_BL_CELLS_TETS = 0
  integer(c_int32_t), parameter, public :: ANITET_BL_CELLS_PRISMS = 1
  integer(c_int32_t), parameter, public :: ANITET_RUN_STATS_VERSION = 3
  integer(c_int32_t), parameter, public :: ANITET_QUALITY_VERSION = 1
  integer(c_int32_t), parameter, public :: ANITET_GEO_ENU = 0
  integer(c_int32_t), parameter, public :: ANITET_GEO_UTM = 1
  ! patch types (anitet_mesh_set_patch_type)
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_FROM_NAME = -1
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_WALL = 0
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_INLET = 1
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_OUTLET = 2
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_FARFIELD = 3
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_SYMMETRY = 4
  integer(c_int32_t), parameter, public :: ANITET_PATCH_TYPE_PATCH = 5
  ! per-vertex fields and their transfer
  integer(c_int32_t), parameter, public :: ANITET_FIELD_KIND_SCALAR = 1
  integer(c_int32_t), parameter, public :: ANITET_FIELD_KIND_VECTOR = 2
  integer(c_int32_t), parameter, public :: ANITET_FIELD_KIND_SYM_TENSOR = 3
  integer(c_int32_t), parameter, public :: ANITET_TENSORS_AUTO = 0
  integer(c_int32_t), parameter, public :: ANITET_TENSORS_LOG_EUCLIDEAN = 1
  integer(c_int32_t), parameter, public :: ANITET_TENSORS_LINEAR = 2
  ! adaptation
  integer(c_int32_t), parameter, public :: ANITET_ADAPT_OPTIONS_VERSION = 1
  integer(c_int32_t), parameter, public :: ANITET_ADAPT_STATS_VERSION = 1
  ! partitions
  integer(c_int32_t), parameter, public :: ANITET_PARTITION_OPTIONS_VERSION = 1
  integer(c_int32_t), parameter, public :: ANITET_PARTITION_INFO_VERSION = 1
  integer(c_int32_t), parameter, public :: ANITET_HALO_VERTEX_SEND = 0
  integer(c_int32_t), parameter, public :: ANITET_HALO_VERTEX_RECV = 1
  integer(c_int32_t), parameter, public :: ANITET_HALO_TET_SEND = 2
  integer(c_int32_t), parameter, public :: ANITET_HALO_TET_RECV = 3
  integer(c_int32_t), parameter, public :: ANITET_TYPE_INT32 = 1
  integer(c_int32_t), parameter, public :: ANITET_TYPE_INT64 = 2
  integer(c_int32_t), parameter, public :: ANITET_TYPE_DOUBLE = 3
  integer(c_int32_t), parameter, public :: ANITET_PART_POINTS = 0
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_GLOBAL_IDS = 1
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_OWNERS = 2
  integer(c_int32_t), parameter, public :: ANITET_PART_TETS = 3
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_GLOBAL_IDS = 4
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_OWNERS = 5
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_LAYERS = 6
  integer(c_int32_t), parameter, public :: ANITET_PART_REGIONS = 7
  integer(c_int32_t), parameter, public :: ANITET_PART_BOUNDARY_TRIANGLES = 8
  integer(c_int32_t), parameter, public :: ANITET_PART_BOUNDARY_PATCHES = 9
  integer(c_int32_t), parameter, public :: ANITET_PART_BOUNDARY_GLOBAL_IDS = 10
  integer(c_int32_t), parameter, public :: ANITET_PART_NEIGHBOURS = 11
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_SEND_OFFSETS = 12
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_SEND = 13
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_RECV_OFFSETS = 14
  integer(c_int32_t), parameter, public :: ANITET_PART_VERTEX_RECV = 15
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_SEND_OFFSETS = 16
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_SEND = 17
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_RECV_OFFSETS = 18
  integer(c_int32_t), parameter, public :: ANITET_PART_TET_RECV = 19
  integer(c_int32_t), parameter, public :: ANITET_MESH2D_OPTIONS_VERSION = 1

  ! ---- versioned structs (same layout as the C structs) -----------------------------------------
  ! Set callbacks with c_funloc of a bind(c) procedure and user data with c_loc.
  type, bind(c), public :: anitet_options_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: num_threads
    integer(c_int32_t) :: merge_duplicate_vertices
    integer(c_int32_t) :: orient_shells
    integer(c_int32_t) :: check_self_intersections
    integer(c_int32_t) :: reserved0
    type(c_funptr) :: progress
    type(c_ptr) :: progress_user_data
    type(c_funptr) :: log
    type(c_ptr) :: log_user_data
    ! version 2
    integer(c_int32_t) :: layers
    integer(c_int32_t) :: layer_scheme
    real(c_double) :: recovery_max_seconds
    integer(c_int32_t) :: refine
    integer(c_int32_t) :: optimize
    real(c_double) :: size_scale
    ! version 3
    real(c_double) :: attempts_seconds
    integer(c_int32_t) :: retry_layer_counts
    integer(c_int32_t) :: recovery
    real(c_double) :: hmin
    real(c_double) :: hmax
    real(c_double) :: hgrad
    real(c_double) :: max_tets
    integer(c_int32_t) :: anisotropic_cycles
    integer(c_int32_t) :: bl_num_patches
    ! The wall labels: c_loc of an integer(c_int32_t), target :: walls(bl_num_patches) that lives
    ! until the run returns, or (simpler) leave it and pass bl_patches= to anitet_mesher_run.
    type(c_ptr) :: bl_patches
    real(c_double) :: bl_first_height
    real(c_double) :: bl_growth
    integer(c_int32_t) :: bl_layers
    integer(c_int32_t) :: bl_sizing
    integer(c_int32_t) :: push_tasks_min_vertices
    integer(c_int32_t) :: bl_mitre  ! 1: columns lengthened at the walls' edges and corners (--bl-mitre)
    ! version 4
    integer(c_int32_t) :: bl_num_slide_patches
    integer(c_int32_t) :: bl_cells  ! ANITET_BL_CELLS_TETS (default) or ANITET_BL_CELLS_PRISMS
    ! The slide patch labels: as bl_patches (or pass bl_slide_patches= to anitet_mesher_run).
    type(c_ptr) :: bl_slide_patches
    ! version 5
    ! With bl_sizing = 1: the normal size's growth above the layers' top (--bl-sizing-growth);
    ! 0 (default): bl_growth, otherwise at least bl_growth.
    real(c_double) :: bl_sizing_growth
  end type

  ! What the run that made a mesh did (anitet_mesh_get_run_stats).
  type, bind(c), public :: anitet_run_stats_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: layers_used
    integer(c_int32_t) :: layers_retries
    integer(c_int32_t) :: recovery_strategy
    integer(c_int32_t) :: refine_passes
    integer(c_int32_t) :: refine_stopped_at_pass_cap
    integer(c_int32_t) :: anisotropic_cycles
    integer(c_int32_t) :: num_notices
    integer(c_int64_t) :: vertices
    integer(c_int64_t) :: tets
    integer(c_int64_t) :: steiner_on_front_edges
    integer(c_int64_t) :: steiner_on_front_faces
    integer(c_int64_t) :: refine_splits
    integer(c_int64_t) :: refine_collapses
    integer(c_int64_t) :: flat_tets_left
    integer(c_int64_t) :: metric_not_spd
    real(c_double) :: seconds
    real(c_double) :: estimated_tets
    real(c_double) :: edges_in_range
    real(c_double) :: metric_radius_ratio_mean
    real(c_double) :: metric_radius_ratio_min
    integer(c_int32_t) :: bl_layers
    integer(c_int32_t) :: reserved0
    integer(c_int64_t) :: bl_wall_vertices
    integer(c_int64_t) :: bl_full_columns
    integer(c_int64_t) :: bl_nominal_columns
    integer(c_int64_t) :: bl_reduced_vertices
    integer(c_int64_t) :: bl_tets
    real(c_double) :: bl_first_height_min
    real(c_double) :: bl_first_height_mean
    real(c_double) :: bl_first_height_max
    real(c_double) :: bl_growth_mean
    real(c_double) :: bl_max_height_error
    ! version 2
    integer(c_int64_t) :: slide_junction_columns
    integer(c_int64_t) :: slide_lowered_columns
    integer(c_int64_t) :: slide_triangles_added
    ! version 3: the prism cells (options%bl_cells = ANITET_BL_CELLS_PRISMS)
    integer(c_int64_t) :: bl_prisms
    integer(c_int64_t) :: bl_prism_tets_left
  end type

  ! Options of anitet_adapt (`anitet adapt`'s); anitet_adapt_options_init sets the defaults.
  type, bind(c), public :: anitet_adapt_options_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: num_threads
    integer(c_int32_t) :: keep_surface
    integer(c_int32_t) :: max_cycles
    real(c_double) :: ridge_angle_deg
    integer(c_int32_t) :: optimize_cycles
    integer(c_int32_t) :: tensors
    type(c_funptr) :: progress
    type(c_ptr) :: progress_user_data
    type(c_funptr) :: log
    type(c_ptr) :: log_user_data
  end type

  ! What an adaptation did and the UGAWG measures of its output (anitet_adapt).
  type, bind(c), public :: anitet_adapt_stats_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: cycles
    integer(c_int64_t) :: vertices_in
    integer(c_int64_t) :: tets_in
    integer(c_int64_t) :: boundary_triangles_in
    integer(c_int64_t) :: vertices
    integer(c_int64_t) :: tets
    integer(c_int64_t) :: boundary_triangles
    integer(c_int64_t) :: ridge_edges
    integer(c_int64_t) :: corners
    integer(c_int64_t) :: splits
    integer(c_int64_t) :: surface_splits
    integer(c_int64_t) :: collapses
    integer(c_int64_t) :: surface_collapses
    integer(c_int64_t) :: swaps
    integer(c_int64_t) :: surface_swaps
    integer(c_int64_t) :: moves
    integer(c_int64_t) :: surface_moves
    integer(c_int64_t) :: splits_refused
    integer(c_int64_t) :: collapses_refused
    integer(c_int64_t) :: edges
    real(c_double) :: edges_in_range
    real(c_double) :: edges_shorter
    real(c_double) :: edges_longer
    real(c_double) :: edge_length_min
    real(c_double) :: edge_length_mean
    real(c_double) :: edge_length_max
    real(c_double) :: mean_ratio_min
    real(c_double) :: mean_ratio_mean
    real(c_double) :: seconds
    real(c_double) :: seconds_adapt
    real(c_double) :: seconds_split
    real(c_double) :: seconds_collapse
    real(c_double) :: seconds_swap
    real(c_double) :: seconds_smooth
    real(c_double) :: seconds_transfer
    real(c_double) :: seconds_measure
  end type

  type, bind(c), public :: anitet_quality_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: valid
    integer(c_int32_t) :: boundary_constrained
    integer(c_int32_t) :: reserved0
    integer(c_int64_t) :: vertices
    integer(c_int64_t) :: tets
    integer(c_int64_t) :: nonpositive_tets
    real(c_double) :: radius_ratio_mean
    real(c_double) :: radius_ratio_min
    real(c_double) :: mean_ratio_mean
    real(c_double) :: mean_ratio_min
    real(c_double) :: min_dihedral_deg
    real(c_double) :: max_dihedral_deg
    real(c_double) :: good_fraction
    real(c_double) :: bad_fraction
  end type

  type, bind(c), public :: anitet_partition_options_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: num_threads
    integer(c_int32_t) :: ghost_layers
    integer(c_int32_t) :: reserved0
    real(c_double) :: imbalance
    type(c_ptr) :: tet_weights  ! c_loc of real(c_double), target :: weights(num_tets), or c_null_ptr
    integer(c_int64_t) :: num_tet_weights
  end type

  type, bind(c), public :: anitet_partition_info_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: num_parts
    integer(c_int32_t) :: ghost_layers
    integer(c_int32_t) :: empty_parts
    integer(c_int64_t) :: num_tets
    integer(c_int64_t) :: edge_cut
    integer(c_int64_t) :: interface_vertices
    real(c_double) :: imbalance
    real(c_double) :: total_weight
    real(c_double) :: max_part_weight
  end type

  ! The 2D mesher's options (anitet_mesh2d_options); anitet_mesh2d_options_init sets the defaults.
  type, bind(c), public :: anitet_mesh2d_options_t
    integer(c_int32_t) :: version
    integer(c_int32_t) :: split_segments
    integer(c_int32_t) :: layers
    integer(c_int32_t) :: refine
    integer(c_int32_t) :: optimize
    integer(c_int32_t) :: geodetic
    integer(c_int32_t) :: geo_frame
    integer(c_int32_t) :: reserved0
    real(c_double) :: hsize
    real(c_double) :: size_scale
    real(c_double) :: hmin
    real(c_double) :: hmax
    real(c_double) :: hgrad
    type(c_funptr) :: progress
    type(c_ptr) :: progress_user_data
  end type

  ! ---- raw C interfaces ---------------------------------------------------------------------------
  public :: c_anitet_options_init, c_anitet_version, c_anitet_version_number
  public :: c_anitet_last_error_message, c_anitet_error_name
  public :: c_anitet_surface_create, c_anitet_surface_read, c_anitet_surface_destroy
  public :: c_anitet_surface_get_counts, c_anitet_surface_get_points
  public :: c_anitet_surface_get_triangles, c_anitet_surface_get_patches
  public :: c_anitet_surface_validate, c_anitet_surface_problem_count
  public :: c_anitet_surface_validation_json
  public :: c_anitet_metric_create_uniform, c_anitet_metric_create_analytic, c_anitet_metric_read
  public :: c_anitet_metric_create_from_points, c_anitet_metric_destroy, c_anitet_metric_evaluate
  public :: c_anitet_metric_create_surface_sizing, c_anitet_metric_read_on_mesh, c_anitet_metric_write
  public :: c_anitet_mesher_run, c_anitet_layers_run, c_anitet_bl_first_height
  public :: c_anitet_mesh_create, c_anitet_mesh_read, c_anitet_mesh_destroy, c_anitet_mesh_write
  public :: c_anitet_mesh_write_metric, c_anitet_mesh_write_bl_columns
  public :: c_anitet_mesh_get_counts, c_anitet_mesh_get_points
  public :: c_anitet_mesh_get_tets, c_anitet_mesh_get_regions
  public :: c_anitet_mesh_get_boundary_triangles, c_anitet_mesh_get_boundary_patches
  public :: c_anitet_mesh_get_metric_components, c_anitet_mesh_get_metric, c_anitet_mesh_set_metric
  public :: c_anitet_mesh_set_patch_name, c_anitet_mesh_get_run_stats, c_anitet_mesh_run_json
  public :: c_anitet_mesh_sample_metric, c_anitet_mesh_quality, c_anitet_mesh_quality_json
  public :: c_anitet_mesh_set_patch_type, c_anitet_mesh_get_patch_type
  public :: c_anitet_mesh_get_prism_count, c_anitet_mesh_get_prisms, c_anitet_mesh_get_tet_prisms
  public :: c_anitet_fields_create, c_anitet_fields_read, c_anitet_fields_write, c_anitet_fields_destroy
  public :: c_anitet_fields_get_counts, c_anitet_fields_get_kinds, c_anitet_fields_get_values
  public :: c_anitet_fields_get_data, c_anitet_mesh_transfer_fields, c_anitet_fields_get_transfer_report
  public :: c_anitet_mesh_transfer_fields_ext
  public :: c_anitet_adapt_options_init, c_anitet_adapt, c_anitet_adapt_to_metric
  public :: c_anitet_geo_frame_create, c_anitet_geo_frame_create_centred, c_anitet_geo_frame_destroy
  public :: c_anitet_geo_frame_get, c_anitet_surface_to_local, c_anitet_mesh_to_local
  public :: c_anitet_mesh_to_geodetic
  public :: c_anitet_partition_options_init, c_anitet_mesh_partition, c_anitet_partition_destroy
  public :: c_anitet_partition_get_info, c_anitet_partition_get_tet_parts, c_anitet_partition_get_part
  public :: c_anitet_part_destroy, c_anitet_part_get_index, c_anitet_part_get_counts
  public :: c_anitet_part_get_points, c_anitet_part_get_tets, c_anitet_part_get_regions
  public :: c_anitet_part_get_vertex_global_ids, c_anitet_part_get_vertex_owners
  public :: c_anitet_part_get_tet_global_ids, c_anitet_part_get_tet_owners, c_anitet_part_get_tet_layers
  public :: c_anitet_part_get_boundary_triangles, c_anitet_part_get_boundary_patches
  public :: c_anitet_part_get_boundary_global_ids, c_anitet_part_get_neighbours
  public :: c_anitet_part_get_halo_size, c_anitet_part_get_halo, c_anitet_part_get_array
  public :: c_anitet_part_serialize, c_anitet_part_deserialize, c_anitet_set_last_error
  public :: c_anitet_pslg_create, c_anitet_pslg_read, c_anitet_pslg_destroy, c_anitet_pslg_get_counts
  public :: c_anitet_mesh2d_options_init, c_anitet_mesh2d_run, c_anitet_mesh2d_destroy
  public :: c_anitet_mesh2d_get_counts, c_anitet_mesh2d_get_points, c_anitet_mesh2d_get_triangles
  public :: c_anitet_mesh2d_get_attributes, c_anitet_mesh2d_get_edges, c_anitet_mesh2d_get_edge_labels
  public :: c_anitet_mesh2d_write, c_anitet_mesh2d_quality

  interface
    integer(c_int) function c_anitet_options_init(options, version) &
        bind(c, name="anitet_options_init")
      import :: c_int, c_int32_t, anitet_options_t
      type(anitet_options_t), intent(out) :: options
      integer(c_int32_t), value :: version
    end function

    type(c_ptr) function c_anitet_version() bind(c, name="anitet_version")
      import :: c_ptr
    end function

    integer(c_int32_t) function c_anitet_version_number() bind(c, name="anitet_version_number")
      import :: c_int32_t
    end function

    type(c_ptr) function c_anitet_last_error_message() bind(c, name="anitet_last_error_message")
      import :: c_ptr
    end function

    type(c_ptr) function c_anitet_error_name(code) bind(c, name="anitet_error_name")
      import :: c_ptr, c_int32_t
      integer(c_int32_t), value :: code
    end function

    integer(c_int) function c_anitet_surface_create(xyz, num_points, tri, num_triangles, patch, &
        index_base, out) bind(c, name="anitet_surface_create")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      real(c_double), intent(in) :: xyz(*)
      integer(c_int64_t), value :: num_points
      integer(c_int32_t), intent(in) :: tri(*)
      integer(c_int64_t), value :: num_triangles
      type(c_ptr), value :: patch
      integer(c_int32_t), value :: index_base
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_surface_read(path, out) bind(c, name="anitet_surface_read")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_surface_destroy(surface) bind(c, name="anitet_surface_destroy")
      import :: c_ptr
      type(c_ptr), value :: surface
    end subroutine

    integer(c_int) function c_anitet_surface_get_counts(surface, num_points, num_triangles) &
        bind(c, name="anitet_surface_get_counts")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: surface
      integer(c_int64_t), intent(out) :: num_points, num_triangles
    end function

    integer(c_int) function c_anitet_surface_get_points(surface, xyz, xyz_len) &
        bind(c, name="anitet_surface_get_points")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: surface
      real(c_double), intent(out) :: xyz(*)
      integer(c_int64_t), value :: xyz_len
    end function

    integer(c_int) function c_anitet_surface_get_triangles(surface, tri, tri_len, index_base) &
        bind(c, name="anitet_surface_get_triangles")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: surface
      integer(c_int32_t), intent(out) :: tri(*)
      integer(c_int64_t), value :: tri_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_surface_get_patches(surface, patch, patch_len) &
        bind(c, name="anitet_surface_get_patches")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: surface
      integer(c_int32_t), intent(out) :: patch(*)
      integer(c_int64_t), value :: patch_len
    end function

    integer(c_int) function c_anitet_surface_validate(surface, options) &
        bind(c, name="anitet_surface_validate")
      import :: c_int, c_ptr
      type(c_ptr), value :: surface
      type(c_ptr), value :: options  ! const anitet_options*, may be c_null_ptr
    end function

    integer(c_int) function c_anitet_surface_problem_count(surface, code, count) &
        bind(c, name="anitet_surface_problem_count")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: surface
      integer(c_int32_t), value :: code
      integer(c_int64_t), intent(out) :: count
    end function

    integer(c_int) function c_anitet_surface_validation_json(surface, buf, buf_len, needed) &
        bind(c, name="anitet_surface_validation_json")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: surface
      type(c_ptr), value :: buf
      integer(c_int64_t), value :: buf_len
      integer(c_int64_t), intent(out) :: needed
    end function

    integer(c_int) function c_anitet_metric_create_uniform(size, out) &
        bind(c, name="anitet_metric_create_uniform")
      import :: c_int, c_double, c_ptr
      real(c_double), value :: size
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_metric_create_analytic(callback, user_data, out) &
        bind(c, name="anitet_metric_create_analytic")
      import :: c_int, c_funptr, c_ptr
      type(c_funptr), value :: callback
      type(c_ptr), value :: user_data
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_metric_read(path, background_mesh_path, out) &
        bind(c, name="anitet_metric_read")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), value :: background_mesh_path  ! may be c_null_ptr
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_metric_create_from_points(background, values, num_values, &
        components, out) bind(c, name="anitet_metric_create_from_points")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: background
      real(c_double), intent(in) :: values(*)
      integer(c_int64_t), value :: num_values
      integer(c_int32_t), value :: components
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_metric_destroy(metric) bind(c, name="anitet_metric_destroy")
      import :: c_ptr
      type(c_ptr), value :: metric
    end subroutine

    integer(c_int) function c_anitet_metric_evaluate(metric, x, y, z, m) &
        bind(c, name="anitet_metric_evaluate")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: metric
      real(c_double), value :: x, y, z
      real(c_double), intent(out) :: m(6)
    end function

    integer(c_int) function c_anitet_metric_create_surface_sizing(surface, options, out) &
        bind(c, name="anitet_metric_create_surface_sizing")
      import :: c_int, c_ptr
      type(c_ptr), value :: surface
      type(c_ptr), value :: options  ! may be c_null_ptr
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_metric_read_on_mesh(path, background, out) &
        bind(c, name="anitet_metric_read_on_mesh")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), value :: background
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_metric_write(metric, box_of, path) &
        bind(c, name="anitet_metric_write")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: metric
      type(c_ptr), value :: box_of  ! a surface, or c_null_ptr for a grid metric
      character(kind=c_char), intent(in) :: path(*)
    end function

    integer(c_int) function c_anitet_mesher_run(surface, metric, options, out) &
        bind(c, name="anitet_mesher_run")
      import :: c_int, c_ptr
      type(c_ptr), value :: surface
      type(c_ptr), value :: metric   ! may be c_null_ptr
      type(c_ptr), value :: options  ! may be c_null_ptr
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_layers_run(surface, options, out) &
        bind(c, name="anitet_layers_run")
      import :: c_int, c_ptr
      type(c_ptr), value :: surface
      type(c_ptr), value :: options  ! may be c_null_ptr
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_bl_first_height(yplus, reynolds, ref_length, h0) &
        bind(c, name="anitet_bl_first_height")
      import :: c_int, c_double
      real(c_double), value :: yplus, reynolds, ref_length
      real(c_double), intent(out) :: h0
    end function

    integer(c_int) function c_anitet_mesh_create(xyz, num_points, tets, num_tets, regions, &
        bnd_tri, num_boundary_triangles, bnd_patch, index_base, out) &
        bind(c, name="anitet_mesh_create")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      real(c_double), intent(in) :: xyz(*)
      integer(c_int64_t), value :: num_points
      integer(c_int32_t), intent(in) :: tets(*)
      integer(c_int64_t), value :: num_tets
      type(c_ptr), value :: regions, bnd_tri
      integer(c_int64_t), value :: num_boundary_triangles
      type(c_ptr), value :: bnd_patch
      integer(c_int32_t), value :: index_base
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_mesh_read(path, out) bind(c, name="anitet_mesh_read")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_mesh_destroy(mesh) bind(c, name="anitet_mesh_destroy")
      import :: c_ptr
      type(c_ptr), value :: mesh
    end subroutine

    integer(c_int) function c_anitet_mesh_write(mesh, path) bind(c, name="anitet_mesh_write")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: mesh
      character(kind=c_char), intent(in) :: path(*)
    end function

    integer(c_int) function c_anitet_mesh_write_metric(mesh, path) &
        bind(c, name="anitet_mesh_write_metric")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: mesh
      character(kind=c_char), intent(in) :: path(*)
    end function

    integer(c_int) function c_anitet_mesh_write_bl_columns(mesh, path) &
        bind(c, name="anitet_mesh_write_bl_columns")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: mesh
      character(kind=c_char), intent(in) :: path(*)
    end function

    integer(c_int) function c_anitet_mesh_get_counts(mesh, num_points, num_tets, &
        num_boundary_triangles) bind(c, name="anitet_mesh_get_counts")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int64_t), intent(out) :: num_points, num_tets, num_boundary_triangles
    end function

    integer(c_int) function c_anitet_mesh_get_points(mesh, xyz, xyz_len) &
        bind(c, name="anitet_mesh_get_points")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: xyz(*)
      integer(c_int64_t), value :: xyz_len
    end function

    integer(c_int) function c_anitet_mesh_get_tets(mesh, tets, tets_len, index_base) &
        bind(c, name="anitet_mesh_get_tets")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: tets(*)
      integer(c_int64_t), value :: tets_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_mesh_get_regions(mesh, regions, regions_len) &
        bind(c, name="anitet_mesh_get_regions")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: regions(*)
      integer(c_int64_t), value :: regions_len
    end function

    integer(c_int) function c_anitet_mesh_get_boundary_triangles(mesh, tri, tri_len, &
        index_base) bind(c, name="anitet_mesh_get_boundary_triangles")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: tri(*)
      integer(c_int64_t), value :: tri_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_mesh_get_boundary_patches(mesh, patch, patch_len) &
        bind(c, name="anitet_mesh_get_boundary_patches")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: patch(*)
      integer(c_int64_t), value :: patch_len
    end function

    integer(c_int) function c_anitet_mesh_get_prism_count(mesh, num_prisms) &
        bind(c, name="anitet_mesh_get_prism_count")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int64_t), intent(out) :: num_prisms
    end function

    integer(c_int) function c_anitet_mesh_get_prisms(mesh, prisms, prisms_len, index_base) &
        bind(c, name="anitet_mesh_get_prisms")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: prisms(*)
      integer(c_int64_t), value :: prisms_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_mesh_get_tet_prisms(mesh, tet_prism, tet_prism_len, &
        index_base) bind(c, name="anitet_mesh_get_tet_prisms")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: tet_prism(*)
      integer(c_int64_t), value :: tet_prism_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_mesh_get_metric_components(mesh, components) &
        bind(c, name="anitet_mesh_get_metric_components")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: components
    end function

    integer(c_int) function c_anitet_mesh_get_metric(mesh, values, values_len) &
        bind(c, name="anitet_mesh_get_metric")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: values(*)
      integer(c_int64_t), value :: values_len
    end function

    integer(c_int) function c_anitet_mesh_set_metric(mesh, values, values_len, components) &
        bind(c, name="anitet_mesh_set_metric")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(in) :: values(*)
      integer(c_int64_t), value :: values_len
      integer(c_int32_t), value :: components
    end function

    integer(c_int) function c_anitet_mesh_sample_metric(mesh, metric) &
        bind(c, name="anitet_mesh_sample_metric")
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh, metric
    end function

    integer(c_int) function c_anitet_mesh_set_patch_name(mesh, label, name) &
        bind(c, name="anitet_mesh_set_patch_name")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: label
      type(c_ptr), value :: name  ! a NUL-terminated string, or c_null_ptr to remove the name
    end function

    integer(c_int) function c_anitet_mesh_set_patch_type(mesh, label, type) &
        bind(c, name="anitet_mesh_set_patch_type")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: label, type
    end function

    integer(c_int) function c_anitet_mesh_get_patch_type(mesh, label, type) &
        bind(c, name="anitet_mesh_get_patch_type")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: label
      integer(c_int32_t), intent(out) :: type
    end function

    integer(c_int) function c_anitet_fields_create(kinds, num_fields, values, num_values, out) &
        bind(c, name="anitet_fields_create")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      integer(c_int32_t), intent(in) :: kinds(*)
      integer(c_int32_t), value :: num_fields
      real(c_double), intent(in) :: values(*)
      integer(c_int64_t), value :: num_values
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_fields_read(path, out) bind(c, name="anitet_fields_read")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_fields_write(fields, path) bind(c, name="anitet_fields_write")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: fields
      character(kind=c_char), intent(in) :: path(*)
    end function

    subroutine c_anitet_fields_destroy(fields) bind(c, name="anitet_fields_destroy")
      import :: c_ptr
      type(c_ptr), value :: fields
    end subroutine

    integer(c_int) function c_anitet_fields_get_counts(fields, num_fields, record_size, &
        num_vertices) bind(c, name="anitet_fields_get_counts")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: fields
      integer(c_int32_t), intent(out) :: num_fields, record_size
      integer(c_int64_t), intent(out) :: num_vertices
    end function

    integer(c_int) function c_anitet_fields_get_kinds(fields, kinds, kinds_len) &
        bind(c, name="anitet_fields_get_kinds")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: fields
      integer(c_int32_t), intent(out) :: kinds(*)
      integer(c_int64_t), value :: kinds_len
    end function

    integer(c_int) function c_anitet_fields_get_values(fields, values, values_len) &
        bind(c, name="anitet_fields_get_values")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: fields
      real(c_double), intent(out) :: values(*)
      integer(c_int64_t), value :: values_len
    end function

    ! Lends the values without a copy: c_f_pointer the data into a real(c_double) pointer.
    integer(c_int) function c_anitet_fields_get_data(fields, data, count) &
        bind(c, name="anitet_fields_get_data")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: fields
      type(c_ptr), intent(out) :: data
      integer(c_int64_t), intent(out) :: count
    end function

    integer(c_int) function c_anitet_mesh_transfer_fields(from, fields, to, tensors, out) &
        bind(c, name="anitet_mesh_transfer_fields")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: from, fields, to
      integer(c_int32_t), value :: tensors
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_mesh_transfer_fields_ext(from, fields, to, tensors, &
        num_threads, out) bind(c, name="anitet_mesh_transfer_fields_ext")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: from, fields, to
      integer(c_int32_t), value :: tensors, num_threads
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_fields_get_transfer_report(fields, outside, &
        max_outside_distance, log_euclidean, log_euclidean_len) &
        bind(c, name="anitet_fields_get_transfer_report")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: fields
      integer(c_int64_t), intent(out) :: outside
      real(c_double), intent(out) :: max_outside_distance
      type(c_ptr), value :: log_euclidean  ! int32_t(log_euclidean_len), or c_null_ptr
      integer(c_int64_t), value :: log_euclidean_len
    end function

    integer(c_int) function c_anitet_mesh_get_run_stats(mesh, out) &
        bind(c, name="anitet_mesh_get_run_stats")
      import :: c_int, c_ptr, anitet_run_stats_t
      type(c_ptr), value :: mesh
      type(anitet_run_stats_t), intent(inout) :: out
    end function

    integer(c_int) function c_anitet_mesh_run_json(mesh, buf, buf_len, needed) &
        bind(c, name="anitet_mesh_run_json")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      type(c_ptr), value :: buf
      integer(c_int64_t), value :: buf_len
      integer(c_int64_t), intent(out) :: needed
    end function

    integer(c_int) function c_anitet_mesh_quality(mesh, input, out) &
        bind(c, name="anitet_mesh_quality")
      import :: c_int, c_ptr, anitet_quality_t
      type(c_ptr), value :: mesh
      type(c_ptr), value :: input  ! may be c_null_ptr
      type(anitet_quality_t), intent(inout) :: out
    end function

    integer(c_int) function c_anitet_mesh_quality_json(mesh, input, buf, buf_len, needed) &
        bind(c, name="anitet_mesh_quality_json")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      type(c_ptr), value :: input  ! may be c_null_ptr
      type(c_ptr), value :: buf
      integer(c_int64_t), value :: buf_len
      integer(c_int64_t), intent(out) :: needed
    end function

    ! ---- geographic frames ----
    integer(c_int) function c_anitet_geo_frame_create(kind, lat, lon, height, out) &
        bind(c, name="anitet_geo_frame_create")
      import :: c_int, c_int32_t, c_double, c_ptr
      integer(c_int32_t), value :: kind
      real(c_double), value :: lat, lon, height
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_geo_frame_create_centred(kind, surface, out) &
        bind(c, name="anitet_geo_frame_create_centred")
      import :: c_int, c_int32_t, c_ptr
      integer(c_int32_t), value :: kind
      type(c_ptr), value :: surface
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_geo_frame_destroy(frame) bind(c, name="anitet_geo_frame_destroy")
      import :: c_ptr
      type(c_ptr), value :: frame
    end subroutine

    ! (C accepts NULL for any output; this interface asks for all five.)
    integer(c_int) function c_anitet_geo_frame_get(frame, lat, lon, height, utm_zone, utm_north) &
        bind(c, name="anitet_geo_frame_get")
      import :: c_int, c_int32_t, c_double, c_ptr
      type(c_ptr), value :: frame
      real(c_double), intent(out) :: lat, lon, height
      integer(c_int32_t), intent(out) :: utm_zone, utm_north
    end function

    integer(c_int) function c_anitet_surface_to_local(surface, frame) &
        bind(c, name="anitet_surface_to_local")
      import :: c_int, c_ptr
      type(c_ptr), value :: surface, frame
    end function

    integer(c_int) function c_anitet_mesh_to_local(mesh, frame) bind(c, name="anitet_mesh_to_local")
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh, frame
    end function

    integer(c_int) function c_anitet_mesh_to_geodetic(mesh, frame, geodetic_surface) &
        bind(c, name="anitet_mesh_to_geodetic")
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh, frame
      type(c_ptr), value :: geodetic_surface  ! may be c_null_ptr
    end function

    ! ---- partitions ----
    integer(c_int) function c_anitet_partition_options_init(options, version) &
        bind(c, name="anitet_partition_options_init")
      import :: c_int, c_int32_t, anitet_partition_options_t
      type(anitet_partition_options_t), intent(out) :: options
      integer(c_int32_t), value :: version
    end function

    integer(c_int) function c_anitet_adapt_options_init(options, version) &
        bind(c, name="anitet_adapt_options_init")
      import :: c_int, c_int32_t, anitet_adapt_options_t
      type(anitet_adapt_options_t), intent(out) :: options
      integer(c_int32_t), value :: version
    end function

    integer(c_int) function c_anitet_adapt(mesh, metric, metric_len, components, fields, options, &
        out, out_fields, stats) bind(c, name="anitet_adapt")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(in) :: metric(*)
      integer(c_int64_t), value :: metric_len
      integer(c_int32_t), value :: components
      type(c_ptr), value :: fields   ! may be c_null_ptr
      type(c_ptr), value :: options  ! c_loc of an anitet_adapt_options_t, or c_null_ptr
      type(c_ptr), intent(out) :: out
      type(c_ptr), value :: out_fields  ! c_loc of a type(c_ptr), or c_null_ptr without fields
      type(c_ptr), value :: stats       ! c_loc of an anitet_adapt_stats_t, or c_null_ptr
    end function

    integer(c_int) function c_anitet_adapt_to_metric(mesh, metric, fields, options, out, out_fields, &
        stats) bind(c, name="anitet_adapt_to_metric")
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh, metric, fields, options
      type(c_ptr), intent(out) :: out
      type(c_ptr), value :: out_fields, stats
    end function

    integer(c_int) function c_anitet_mesh_partition(mesh, num_parts, options, out) &
        bind(c, name="anitet_mesh_partition")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: num_parts
      type(c_ptr), value :: options  ! const anitet_partition_options*, may be c_null_ptr
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_partition_destroy(partition) bind(c, name="anitet_partition_destroy")
      import :: c_ptr
      type(c_ptr), value :: partition
    end subroutine

    integer(c_int) function c_anitet_partition_get_info(partition, info) &
        bind(c, name="anitet_partition_get_info")
      import :: c_int, c_ptr, anitet_partition_info_t
      type(c_ptr), value :: partition
      type(anitet_partition_info_t), intent(inout) :: info
    end function

    integer(c_int) function c_anitet_partition_get_tet_parts(partition, parts, parts_len) &
        bind(c, name="anitet_partition_get_tet_parts")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: partition
      integer(c_int32_t), intent(out) :: parts(*)
      integer(c_int64_t), value :: parts_len
    end function

    integer(c_int) function c_anitet_partition_get_part(partition, index, part) &
        bind(c, name="anitet_partition_get_part")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: partition
      integer(c_int32_t), value :: index
      type(c_ptr), intent(out) :: part
    end function

    subroutine c_anitet_part_destroy(part) bind(c, name="anitet_part_destroy")
      import :: c_ptr
      type(c_ptr), value :: part
    end subroutine

    integer(c_int) function c_anitet_part_get_index(part, index, num_parts, num_neighbours, &
        ghost_layers) bind(c, name="anitet_part_get_index")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: index, num_parts, num_neighbours, ghost_layers
    end function

    integer(c_int) function c_anitet_part_get_counts(part, num_vertices, num_owned_vertices, &
        num_tets, num_owned_tets, num_boundary_triangles, num_owned_boundary_triangles) &
        bind(c, name="anitet_part_get_counts")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int64_t), intent(out) :: num_vertices, num_owned_vertices, num_tets, num_owned_tets
      integer(c_int64_t), intent(out) :: num_boundary_triangles, num_owned_boundary_triangles
    end function

    integer(c_int) function c_anitet_part_get_points(part, xyz, xyz_len) &
        bind(c, name="anitet_part_get_points")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: part
      real(c_double), intent(out) :: xyz(*)
      integer(c_int64_t), value :: xyz_len
    end function

    integer(c_int) function c_anitet_part_get_tets(part, tets, tets_len, index_base) &
        bind(c, name="anitet_part_get_tets")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: tets(*)
      integer(c_int64_t), value :: tets_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_part_get_regions(part, regions, regions_len) &
        bind(c, name="anitet_part_get_regions")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: regions(*)
      integer(c_int64_t), value :: regions_len
    end function

    integer(c_int) function c_anitet_part_get_vertex_global_ids(part, ids, ids_len, index_base) &
        bind(c, name="anitet_part_get_vertex_global_ids")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int64_t), intent(out) :: ids(*)
      integer(c_int64_t), value :: ids_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_part_get_vertex_owners(part, owners, owners_len) &
        bind(c, name="anitet_part_get_vertex_owners")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: owners(*)
      integer(c_int64_t), value :: owners_len
    end function

    integer(c_int) function c_anitet_part_get_tet_global_ids(part, ids, ids_len, index_base) &
        bind(c, name="anitet_part_get_tet_global_ids")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int64_t), intent(out) :: ids(*)
      integer(c_int64_t), value :: ids_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_part_get_tet_owners(part, owners, owners_len) &
        bind(c, name="anitet_part_get_tet_owners")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: owners(*)
      integer(c_int64_t), value :: owners_len
    end function

    integer(c_int) function c_anitet_part_get_tet_layers(part, layers, layers_len) &
        bind(c, name="anitet_part_get_tet_layers")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: layers(*)
      integer(c_int64_t), value :: layers_len
    end function

    integer(c_int) function c_anitet_part_get_boundary_triangles(part, tri, tri_len, index_base) &
        bind(c, name="anitet_part_get_boundary_triangles")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: tri(*)
      integer(c_int64_t), value :: tri_len
      integer(c_int32_t), value :: index_base
    end function

    ! ---- 2D meshes ----
    integer(c_int) function c_anitet_pslg_create(xy, num_points, segments, num_segments, labels, &
        holes, num_holes, index_base, out) bind(c, name="anitet_pslg_create")
      import :: c_int, c_int32_t, c_int64_t, c_double, c_ptr
      real(c_double), intent(in) :: xy(*)
      integer(c_int64_t), value :: num_points
      integer(c_int32_t), intent(in) :: segments(*)
      integer(c_int64_t), value :: num_segments
      type(c_ptr), value :: labels, holes
      integer(c_int64_t), value :: num_holes
      integer(c_int32_t), value :: index_base
      type(c_ptr), intent(out) :: out
    end function

    integer(c_int) function c_anitet_pslg_read(path, out) bind(c, name="anitet_pslg_read")
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_pslg_destroy(pslg) bind(c, name="anitet_pslg_destroy")
      import :: c_ptr
      type(c_ptr), value :: pslg
    end subroutine

    integer(c_int) function c_anitet_pslg_get_counts(pslg, num_points, num_segments, num_holes) &
        bind(c, name="anitet_pslg_get_counts")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: pslg
      integer(c_int64_t), intent(out) :: num_points, num_segments, num_holes
    end function

    integer(c_int) function c_anitet_mesh2d_options_init(options, version) &
        bind(c, name="anitet_mesh2d_options_init")
      import :: c_int, c_int32_t, anitet_mesh2d_options_t
      type(anitet_mesh2d_options_t), intent(out) :: options
      integer(c_int32_t), value :: version
    end function

    integer(c_int) function c_anitet_mesh2d_run(pslg, metric, options, out) &
        bind(c, name="anitet_mesh2d_run")
      import :: c_int, c_ptr
      type(c_ptr), value :: pslg, metric, options
      type(c_ptr), intent(out) :: out
    end function

    subroutine c_anitet_mesh2d_destroy(mesh) bind(c, name="anitet_mesh2d_destroy")
      import :: c_ptr
      type(c_ptr), value :: mesh
    end subroutine

    integer(c_int) function c_anitet_mesh2d_get_counts(mesh, num_points, num_triangles, num_edges) &
        bind(c, name="anitet_mesh2d_get_counts")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int64_t), intent(out) :: num_points, num_triangles, num_edges
    end function

    integer(c_int) function c_anitet_mesh2d_get_points(mesh, xy, xy_len) &
        bind(c, name="anitet_mesh2d_get_points")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: xy(*)
      integer(c_int64_t), value :: xy_len
    end function

    integer(c_int) function c_anitet_mesh2d_get_triangles(mesh, tri, tri_len, index_base) &
        bind(c, name="anitet_mesh2d_get_triangles")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: tri(*)
      integer(c_int64_t), value :: tri_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_part_get_boundary_patches(part, patch, patch_len) &
        bind(c, name="anitet_part_get_boundary_patches")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: patch(*)
      integer(c_int64_t), value :: patch_len
    end function

    integer(c_int) function c_anitet_part_get_boundary_global_ids(part, ids, ids_len, index_base) &
        bind(c, name="anitet_part_get_boundary_global_ids")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int64_t), intent(out) :: ids(*)
      integer(c_int64_t), value :: ids_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_part_get_neighbours(part, neighbours, neighbours_len) &
        bind(c, name="anitet_part_get_neighbours")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), intent(out) :: neighbours(*)
      integer(c_int64_t), value :: neighbours_len
    end function

    integer(c_int) function c_anitet_part_get_halo_size(part, list, size) &
        bind(c, name="anitet_part_get_halo_size")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), value :: list
      integer(c_int64_t), intent(out) :: size
    end function

    integer(c_int) function c_anitet_part_get_halo(part, list, offsets, offsets_len, items, &
        items_len, index_base) bind(c, name="anitet_part_get_halo")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), value :: list
      integer(c_int64_t), intent(out) :: offsets(*)
      integer(c_int64_t), value :: offsets_len
      integer(c_int32_t), intent(out) :: items(*)
      integer(c_int64_t), value :: items_len
      integer(c_int32_t), value :: index_base
    end function

    ! Lends an array of the part without a copy (0-based ids): c_f_pointer it into a Fortran
    ! pointer of the ANITET_TYPE_* kind; valid while the part lives.
    integer(c_int) function c_anitet_part_get_array(part, array, data, count, element_type) &
        bind(c, name="anitet_part_get_array")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: part
      integer(c_int32_t), value :: array
      type(c_ptr), intent(out) :: data
      integer(c_int64_t), intent(out) :: count
      integer(c_int32_t), intent(out) :: element_type
    end function

    integer(c_int) function c_anitet_part_serialize(part, buf, buf_len, needed) &
        bind(c, name="anitet_part_serialize")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: part
      type(c_ptr), value :: buf
      integer(c_int64_t), value :: buf_len
      integer(c_int64_t), intent(out) :: needed
    end function

    integer(c_int) function c_anitet_part_deserialize(bytes, size, out) &
        bind(c, name="anitet_part_deserialize")
      import :: c_int, c_int8_t, c_int64_t, c_ptr
      integer(c_int8_t), intent(in) :: bytes(*)
      integer(c_int64_t), value :: size
      type(c_ptr), intent(out) :: out
    end function

    ! For libraries layered on the ABI: sets the last error message, returns code.
    integer(c_int) function c_anitet_set_last_error(code, message) &
        bind(c, name="anitet_set_last_error")
      import :: c_int, c_int32_t, c_char
      integer(c_int32_t), value :: code
      character(kind=c_char), intent(in) :: message(*)
    end function

    integer(c_int) function c_anitet_mesh2d_get_attributes(mesh, attributes, attributes_len) &
        bind(c, name="anitet_mesh2d_get_attributes")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: attributes(*)
      integer(c_int64_t), value :: attributes_len
    end function

    integer(c_int) function c_anitet_mesh2d_get_edges(mesh, edges, edges_len, index_base) &
        bind(c, name="anitet_mesh2d_get_edges")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: edges(*)
      integer(c_int64_t), value :: edges_len
      integer(c_int32_t), value :: index_base
    end function

    integer(c_int) function c_anitet_mesh2d_get_edge_labels(mesh, labels, labels_len) &
        bind(c, name="anitet_mesh2d_get_edge_labels")
      import :: c_int, c_int32_t, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: labels(*)
      integer(c_int64_t), value :: labels_len
    end function

    integer(c_int) function c_anitet_mesh2d_write(mesh, path) bind(c, name="anitet_mesh2d_write")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: mesh
      character(kind=c_char), intent(in) :: path(*)
    end function

    integer(c_int) function c_anitet_mesh2d_quality(mesh, min_angle_deg, min_angle_off_input_deg, &
        mean_radius_ratio, edges_in_range) bind(c, name="anitet_mesh2d_quality")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: min_angle_deg, min_angle_off_input_deg, mean_radius_ratio
      real(c_double), intent(out) :: edges_in_range
    end function

    ! From the C library, to measure returned strings.
    integer(c_size_t) function c_strlen(s) bind(c, name="strlen")
      import :: c_size_t, c_ptr
      type(c_ptr), value :: s
    end function
  end interface

  ! ---- Fortran wrappers -----------------------------------------------------------------------------
  public :: anitet_options_init, anitet_version, anitet_version_number
  public :: anitet_last_error_message, anitet_error_name
  public :: anitet_surface_create, anitet_surface_read, anitet_surface_destroy
  public :: anitet_surface_get_counts, anitet_surface_get_points, anitet_surface_get_triangles
  public :: anitet_surface_get_patches, anitet_surface_validate, anitet_surface_problem_count
  public :: anitet_surface_validation_json
  public :: anitet_metric_create_uniform, anitet_metric_create_analytic, anitet_metric_read
  public :: anitet_metric_create_from_points, anitet_metric_destroy, anitet_metric_evaluate
  public :: anitet_metric_create_surface_sizing, anitet_metric_read_on_mesh, anitet_metric_write
  public :: anitet_mesher_run, anitet_layers_run, anitet_bl_first_height
  public :: anitet_mesh_create, anitet_mesh_read, anitet_mesh_destroy, anitet_mesh_write
  public :: anitet_mesh_write_metric, anitet_mesh_write_bl_columns
  public :: anitet_mesh_get_counts, anitet_mesh_get_points
  public :: anitet_mesh_get_tets, anitet_mesh_get_regions, anitet_mesh_get_boundary_triangles
  public :: anitet_mesh_get_boundary_patches, anitet_mesh_get_metric_components
  public :: anitet_mesh_get_metric, anitet_mesh_set_metric, anitet_mesh_quality
  public :: anitet_mesh_quality_json, anitet_mesh_set_patch_name, anitet_mesh_get_run_stats
  public :: anitet_mesh_run_json, anitet_mesh_sample_metric
  public :: anitet_mesh_set_patch_type, anitet_mesh_get_patch_type
  public :: anitet_mesh_get_prism_count, anitet_mesh_get_prisms, anitet_mesh_get_tet_prisms
  public :: anitet_fields_create, anitet_fields_read, anitet_fields_write, anitet_fields_destroy
  public :: anitet_fields_get_counts, anitet_fields_get_kinds, anitet_fields_get_values
  public :: anitet_fields_get_data, anitet_mesh_transfer_fields, anitet_fields_get_transfer_report
  public :: anitet_adapt_options_init, anitet_adapt, anitet_adapt_to_metric
  public :: anitet_geo_frame_create, anitet_geo_frame_create_centred, anitet_geo_frame_destroy
  public :: anitet_geo_frame_get, anitet_surface_to_local, anitet_mesh_to_local
  public :: anitet_mesh_to_geodetic
  public :: anitet_pslg_create, anitet_pslg_read, anitet_pslg_destroy, anitet_pslg_get_counts
  public :: anitet_mesh2d_options_init, anitet_mesh2d_run, anitet_mesh2d_destroy
  public :: anitet_mesh2d_get_counts, anitet_mesh2d_get_points, anitet_mesh2d_get_triangles
  public :: anitet_mesh2d_get_attributes, anitet_mesh2d_get_edges, anitet_mesh2d_get_edge_labels
  public :: anitet_mesh2d_write, anitet_mesh2d_quality

  public :: anitet_partition_options_init, anitet_mesh_partition, anitet_partition_destroy
  public :: anitet_partition_get_info, anitet_partition_get_tet_parts, anitet_partition_get_part
  public :: anitet_part_destroy, anitet_part_get_index, anitet_part_get_counts, anitet_part_get_points
  public :: anitet_part_get_tets, anitet_part_get_regions, anitet_part_get_vertex_global_ids
  public :: anitet_part_get_vertex_owners, anitet_part_get_tet_global_ids, anitet_part_get_tet_owners
  public :: anitet_part_get_tet_layers, anitet_part_get_boundary_triangles
  public :: anitet_part_get_boundary_patches, anitet_part_get_boundary_global_ids
  public :: anitet_part_get_neighbours, anitet_part_get_halo, anitet_part_serialize
  public :: anitet_part_deserialize

contains

  ! A NUL-terminated C string as a Fortran string ("" for NULL).
  function from_c_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(p)) then
      s = ""
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function

  function to_c_string(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=:), allocatable :: c
    c = trim(s) // c_null_char
  end function

  ! The index base to pass: 1 (Fortran's) unless given.
  function base_of(index_base) result(b)
    integer, intent(in), optional :: index_base
    integer(c_int32_t) :: b
    b = 1
    if (present(index_base)) b = int(index_base, c_int32_t)
  end function

  ! An optional handle, or c_null_ptr.
  function opt_ptr(h) result(p)
    type(c_ptr), intent(in), optional :: h
    type(c_ptr) :: p
    p = c_null_ptr
    if (present(h)) p = h
  end function

  ! Copies a NUL-terminated buffer into a Fortran string.
  function buffer_text(buf, needed) result(s)
    character(kind=c_char), intent(in) :: buf(:)
    integer(c_int64_t), intent(in) :: needed
    character(len=:), allocatable :: s
    integer :: i
    allocate(character(len=max(0, int(needed) - 1)) :: s)
    do i = 1, len(s)
      s(i:i) = buf(i)
    end do
  end function

  ! ---- library ----------------------------------------------------------------------------------

  integer function anitet_options_init(options, version) result(rc)
    type(anitet_options_t), intent(out) :: options
    integer, intent(in), optional :: version
    integer(c_int32_t) :: v
    v = ANITET_OPTIONS_VERSION
    if (present(version)) v = int(version, c_int32_t)
    rc = c_anitet_options_init(options, v)
  end function

  function anitet_version() result(s)
    character(len=:), allocatable :: s
    s = from_c_string(c_anitet_version())
  end function

  integer function anitet_version_number()
    anitet_version_number = int(c_anitet_version_number())
  end function

  function anitet_last_error_message() result(s)
    character(len=:), allocatable :: s
    s = from_c_string(c_anitet_last_error_message())
  end function

  function anitet_error_name(code) result(s)
    integer, intent(in) :: code
    character(len=:), allocatable :: s
    s = from_c_string(c_anitet_error_name(int(code, c_int32_t)))
  end function

  ! ---- surfaces ---------------------------------------------------------------------------------

  ! xyz(3, num_points), tri(3, num_triangles) counted from index_base (default 1).
  integer function anitet_surface_create(xyz, tri, surface, patch, index_base) result(rc)
    real(c_double), intent(in) :: xyz(:, :)
    integer(c_int32_t), intent(in) :: tri(:, :)
    type(c_ptr), intent(out) :: surface
    integer(c_int32_t), intent(in), optional :: patch(:)
    integer, intent(in), optional :: index_base
    integer(c_int32_t), allocatable, target :: labels(:)
    type(c_ptr) :: p
    ! A wrong leading dimension would be misread silently by C (the last error message is not
    ! updated for this Fortran-only check).
    surface = c_null_ptr
    rc = ANITET_ERR_INVALID_ARGUMENT
    if (size(xyz, 1) /= 3 .or. size(tri, 1) /= 3) return
    if (present(patch)) then
      if (size(patch) /= size(tri, 2)) return
    end if
    p = c_null_ptr
    if (present(patch)) then
      allocate(labels(size(patch)))
      labels(:) = patch
      p = c_loc(labels)
    end if
    rc = c_anitet_surface_create(xyz, size(xyz, 2, c_int64_t), tri, size(tri, 2, c_int64_t), p, &
                                 base_of(index_base), surface)
  end function

  integer function anitet_surface_read(path, surface) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(out) :: surface
    rc = c_anitet_surface_read(to_c_string(path), surface)
  end function

  subroutine anitet_surface_destroy(surface)
    type(c_ptr), intent(inout) :: surface
    call c_anitet_surface_destroy(surface)
    surface = c_null_ptr
  end subroutine

  integer function anitet_surface_get_counts(surface, num_points, num_triangles) result(rc)
    type(c_ptr), intent(in) :: surface
    integer(c_int64_t), intent(out) :: num_points, num_triangles
    rc = c_anitet_surface_get_counts(surface, num_points, num_triangles)
  end function

  integer function anitet_surface_get_points(surface, xyz) result(rc)
    type(c_ptr), intent(in) :: surface
    real(c_double), allocatable, intent(out) :: xyz(:, :)
    integer(c_int64_t) :: np, nt
    rc = c_anitet_surface_get_counts(surface, np, nt)
    if (rc /= ANITET_OK) return
    allocate(xyz(3, np))
    rc = c_anitet_surface_get_points(surface, xyz, size(xyz, kind=c_int64_t))
  end function

  integer function anitet_surface_get_triangles(surface, tri, index_base) result(rc)
    type(c_ptr), intent(in) :: surface
    integer(c_int32_t), allocatable, intent(out) :: tri(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt
    rc = c_anitet_surface_get_counts(surface, np, nt)
    if (rc /= ANITET_OK) return
    allocate(tri(3, nt))
    rc = c_anitet_surface_get_triangles(surface, tri, size(tri, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_surface_get_patches(surface, patch) result(rc)
    type(c_ptr), intent(in) :: surface
    integer(c_int32_t), allocatable, intent(out) :: patch(:)
    integer(c_int64_t) :: np, nt
    rc = c_anitet_surface_get_counts(surface, np, nt)
    if (rc /= ANITET_OK) return
    allocate(patch(nt))
    rc = c_anitet_surface_get_patches(surface, patch, size(patch, kind=c_int64_t))
  end function

  integer function anitet_surface_validate(surface, options) result(rc)
    type(c_ptr), intent(in) :: surface
    type(anitet_options_t), intent(in), optional, target :: options
    if (present(options)) then
      rc = c_anitet_surface_validate(surface, c_loc(options))
    else
      rc = c_anitet_surface_validate(surface, c_null_ptr)
    end if
  end function

  integer function anitet_surface_problem_count(surface, code, count) result(rc)
    type(c_ptr), intent(in) :: surface
    integer, intent(in) :: code
    integer(c_int64_t), intent(out) :: count
    rc = c_anitet_surface_problem_count(surface, int(code, c_int32_t), count)
  end function

  integer function anitet_surface_validation_json(surface, text) result(rc)
    type(c_ptr), intent(in) :: surface
    character(len=:), allocatable, intent(out) :: text
    character(kind=c_char), allocatable, target :: buf(:)
    integer(c_int64_t) :: needed, written
    text = ""
    needed = 0
    rc = c_anitet_surface_validation_json(surface, c_null_ptr, 0_c_int64_t, needed)
    if (rc /= ANITET_OK) return
    allocate(buf(needed))
    rc = c_anitet_surface_validation_json(surface, c_loc(buf), needed, written)
    if (rc == ANITET_OK) text = buffer_text(buf, needed)
  end function

  ! ---- metrics ----------------------------------------------------------------------------------

  integer function anitet_metric_create_uniform(size, metric) result(rc)
    real(c_double), intent(in) :: size
    type(c_ptr), intent(out) :: metric
    rc = c_anitet_metric_create_uniform(size, metric)
  end function

  ! callback: c_funloc of a bind(c) function
  !   integer(c_int) function f(x, y, z, m, user_data) bind(c)
  !     real(c_double), value :: x, y, z;  real(c_double) :: m(6);  type(c_ptr), value :: user_data
  integer function anitet_metric_create_analytic(callback, user_data, metric) result(rc)
    type(c_funptr), intent(in) :: callback
    type(c_ptr), intent(in) :: user_data
    type(c_ptr), intent(out) :: metric
    rc = c_anitet_metric_create_analytic(callback, user_data, metric)
  end function

  integer function anitet_metric_read(path, metric, background_mesh_path) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(out) :: metric
    character(len=*), intent(in), optional :: background_mesh_path
    character(kind=c_char, len=:), allocatable, target :: background
    if (present(background_mesh_path)) then
      background = to_c_string(background_mesh_path)
      rc = c_anitet_metric_read(to_c_string(path), c_loc(background), metric)
    else
      rc = c_anitet_metric_read(to_c_string(path), c_null_ptr, metric)
    end if
  end function

  ! values(components, num_points of background)
  integer function anitet_metric_create_from_points(background, values, metric) result(rc)
    type(c_ptr), intent(in) :: background
    real(c_double), intent(in) :: values(:, :)
    type(c_ptr), intent(out) :: metric
    metric = c_null_ptr
    rc = ANITET_ERR_INVALID_ARGUMENT  ! a (0, n) array: no component (Fortran-only check)
    if (size(values, 1) == 0) return
    rc = c_anitet_metric_create_from_points(background, values, size(values, kind=c_int64_t), &
                                            size(values, 1, c_int32_t), metric)
  end function

  subroutine anitet_metric_destroy(metric)
    type(c_ptr), intent(inout) :: metric
    call c_anitet_metric_destroy(metric)
    metric = c_null_ptr
  end subroutine

  integer function anitet_metric_evaluate(metric, point, m) result(rc)
    type(c_ptr), intent(in) :: metric
    real(c_double), intent(in) :: point(3)
    real(c_double), intent(out) :: m(6)
    rc = c_anitet_metric_evaluate(metric, point(1), point(2), point(3), m)
  end function

  ! The sizing field anitet_mesher_run follows without a metric (bounded by options%hmin, hmax,
  ! hgrad; `anitet mesh --write-sizing`).
  integer function anitet_metric_create_surface_sizing(surface, metric, options) result(rc)
    type(c_ptr), intent(in) :: surface
    type(c_ptr), intent(out) :: metric
    type(anitet_options_t), intent(in), optional, target :: options
    if (present(options)) then
      rc = c_anitet_metric_create_surface_sizing(surface, c_loc(options), metric)
    else
      rc = c_anitet_metric_create_surface_sizing(surface, c_null_ptr, metric)
    end if
  end function

  ! A .sol/.solb metric on a background mesh in memory (copied).
  integer function anitet_metric_read_on_mesh(path, background, metric) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(in) :: background
    type(c_ptr), intent(out) :: metric
    rc = c_anitet_metric_read_on_mesh(to_c_string(path), background, metric)
  end function

  ! Writes the metric as OpenVDB grids (.vdb): a grid metric as it is, any other sampled over the
  ! box of the surface box_of (then required).
  integer function anitet_metric_write(metric, path, box_of) result(rc)
    type(c_ptr), intent(in) :: metric
    character(len=*), intent(in) :: path
    type(c_ptr), intent(in), optional :: box_of
    rc = c_anitet_metric_write(metric, opt_ptr(box_of), to_c_string(path))
  end function

  ! ---- meshing ----------------------------------------------------------------------------------

  ! bl_patches: the boundary layer's wall labels for this call, in place of options%bl_patches and
  ! options%bl_num_patches; bl_slide_patches: the patches the layers may slide along, in place of
  ! options%bl_slide_patches and options%bl_num_slide_patches (both copied for the call: any
  ! integer(c_int32_t) array or expression will do); the other bl_ fields (bl_first_height, ...)
  ! come from options.
  integer function anitet_mesher_run(surface, mesh, metric, options, bl_patches, bl_slide_patches) &
      result(rc)
    type(c_ptr), intent(in) :: surface
    type(c_ptr), intent(out) :: mesh
    type(c_ptr), intent(in), optional :: metric
    type(anitet_options_t), intent(in), optional, target :: options
    integer(c_int32_t), intent(in), optional :: bl_patches(:), bl_slide_patches(:)
    type(anitet_options_t), target :: with_labels
    integer(c_int32_t), allocatable, target :: walls(:), slides(:)
    mesh = c_null_ptr
    if (.not. present(bl_patches) .and. .not. present(bl_slide_patches)) then
      if (present(options)) then
        rc = c_anitet_mesher_run(surface, opt_ptr(metric), c_loc(options), mesh)
      else
        rc = c_anitet_mesher_run(surface, opt_ptr(metric), c_null_ptr, mesh)
      end if
      return
    end if
    rc = options_with_labels("anitet_mesher_run", with_labels, walls, slides, options, bl_patches, &
                             bl_slide_patches)
    if (rc /= ANITET_OK) return
    if (allocated(walls)) with_labels%bl_patches = c_loc(walls)
    if (allocated(slides)) with_labels%bl_slide_patches = c_loc(slides)
    rc = c_anitet_mesher_run(surface, opt_ptr(metric), c_loc(with_labels), mesh)
  end function

  ! Stage 1 alone (`anitet mesh --stop-after layers`): T1, with the surface's triangles under
  ! their labels and the new front under the largest label + 1. bl_patches and bl_slide_patches
  ! as anitet_mesher_run.
  integer function anitet_layers_run(surface, mesh, options, bl_patches, bl_slide_patches) result(rc)
    type(c_ptr), intent(in) :: surface
    type(c_ptr), intent(out) :: mesh
    type(anitet_options_t), intent(in), optional, target :: options
    integer(c_int32_t), intent(in), optional :: bl_patches(:), bl_slide_patches(:)
    type(anitet_options_t), target :: with_labels
    integer(c_int32_t), allocatable, target :: walls(:), slides(:)
    mesh = c_null_ptr
    if (.not. present(bl_patches) .and. .not. present(bl_slide_patches)) then
      if (present(options)) then
        rc = c_anitet_layers_run(surface, c_loc(options), mesh)
      else
        rc = c_anitet_layers_run(surface, c_null_ptr, mesh)
      end if
      return
    end if
    rc = options_with_labels("anitet_layers_run", with_labels, walls, slides, options, bl_patches, &
                             bl_slide_patches)
    if (rc /= ANITET_OK) return
    if (allocated(walls)) with_labels%bl_patches = c_loc(walls)
    if (allocated(slides)) with_labels%bl_slide_patches = c_loc(slides)
    rc = c_anitet_layers_run(surface, c_loc(with_labels), mesh)
  end function

  ! The options (or the defaults) with the counts set for the given wall and slide labels, copied
  ! into `walls` and `slides` (not allocated when there are none); the caller points bl_patches
  ! and bl_slide_patches at them, which must outlive the call that reads them.
  integer function options_with_labels(caller, with_labels, walls, slides, options, bl_patches, &
                                       bl_slide_patches) result(rc)
    character(len=*), intent(in) :: caller
    type(anitet_options_t), intent(out) :: with_labels
    integer(c_int32_t), allocatable, intent(out) :: walls(:), slides(:)
    type(anitet_options_t), intent(in), optional :: options
    integer(c_int32_t), intent(in), optional :: bl_patches(:), bl_slide_patches(:)
    rc = ANITET_OK
    if (present(options)) then
      with_labels = options
    else
      rc = c_anitet_options_init(with_labels, ANITET_OPTIONS_VERSION)
      if (rc /= ANITET_OK) return
    end if
    ! Older structs have no such fields: the labels would be ignored.
    if (present(bl_patches)) then
      if (with_labels%version < 3) then
        rc = c_anitet_set_last_error(ANITET_ERR_INVALID_ARGUMENT, caller // ": bl_patches " // &
                                     "needs options of version 3 or later" // c_null_char)
        return
      end if
      with_labels%bl_num_patches = size(bl_patches, kind=c_int32_t)
      with_labels%bl_patches = c_null_ptr
      if (size(bl_patches) > 0) walls = bl_patches
    end if
    if (present(bl_slide_patches)) then
      if (with_labels%version < 4) then
        rc = c_anitet_set_last_error(ANITET_ERR_INVALID_ARGUMENT, caller // ": bl_slide_patches " // &
                                     "needs options of version 4 or later" // c_null_char)
        return
      end if
      with_labels%bl_num_slide_patches = size(bl_slide_patches, kind=c_int32_t)
      with_labels%bl_slide_patches = c_null_ptr
      if (size(bl_slide_patches) > 0) slides = bl_slide_patches
    end if
  end function

  ! The first boundary-layer height h0 for a target y+ (flat-plate estimate; `--bl-yplus`).
  integer function anitet_bl_first_height(yplus, reynolds, ref_length, h0) result(rc)
    real(c_double), intent(in) :: yplus, reynolds, ref_length
    real(c_double), intent(out) :: h0
    rc = c_anitet_bl_first_height(yplus, reynolds, ref_length, h0)
  end function

  ! ---- volume meshes ----------------------------------------------------------------------------

  ! xyz(3, np), tets(4, nt), regions(nt), bnd_tri(3, nb), bnd_patch(nb); index_base default 1.
  integer function anitet_mesh_create(xyz, tets, mesh, regions, bnd_tri, bnd_patch, index_base) &
      result(rc)
    real(c_double), intent(in) :: xyz(:, :)
    integer(c_int32_t), intent(in) :: tets(:, :)
    type(c_ptr), intent(out) :: mesh
    integer(c_int32_t), intent(in), optional :: regions(:), bnd_tri(:, :), bnd_patch(:)
    integer, intent(in), optional :: index_base
    integer(c_int32_t), allocatable, target :: r(:), t(:, :), p(:)
    type(c_ptr) :: rp, tp, pp
    integer(c_int64_t) :: nb
    ! Wrong shapes would be misread silently by C (Fortran-only check: no last error message).
    mesh = c_null_ptr
    rc = ANITET_ERR_INVALID_ARGUMENT
    if (size(xyz, 1) /= 3 .or. size(tets, 1) /= 4) return
    if (present(regions)) then
      if (size(regions) /= size(tets, 2)) return
    end if
    if (present(bnd_tri)) then
      if (size(bnd_tri, 1) /= 3) return
      if (present(bnd_patch)) then
        if (size(bnd_patch) /= size(bnd_tri, 2)) return
      end if
    else if (present(bnd_patch)) then
      return
    end if
    rp = c_null_ptr
    tp = c_null_ptr
    pp = c_null_ptr
    nb = 0
    if (present(regions)) then
      allocate(r(size(regions)))
      r(:) = regions
      rp = c_loc(r)
    end if
    if (present(bnd_tri)) then
      allocate(t(size(bnd_tri, 1), size(bnd_tri, 2)))
      t(:, :) = bnd_tri
      tp = c_loc(t)
      nb = size(bnd_tri, 2, c_int64_t)
    end if
    if (present(bnd_patch)) then
      allocate(p(size(bnd_patch)))
      p(:) = bnd_patch
      pp = c_loc(p)
    end if
    rc = c_anitet_mesh_create(xyz, size(xyz, 2, c_int64_t), tets, size(tets, 2, c_int64_t), rp, &
                              tp, nb, pp, base_of(index_base), mesh)
  end function

  integer function anitet_mesh_read(path, mesh) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(out) :: mesh
    rc = c_anitet_mesh_read(to_c_string(path), mesh)
  end function

  subroutine anitet_mesh_destroy(mesh)
    type(c_ptr), intent(inout) :: mesh
    call c_anitet_mesh_destroy(mesh)
    mesh = c_null_ptr
  end subroutine

  integer function anitet_mesh_write(mesh, path) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=*), intent(in) :: path
    rc = c_anitet_mesh_write(mesh, to_c_string(path))
  end function

  integer function anitet_mesh_write_metric(mesh, path) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=*), intent(in) :: path
    rc = c_anitet_mesh_write_metric(mesh, to_c_string(path))
  end function

  ! The boundary layer's columns as CSV (`anitet mesh --bl-columns`), for a mesh of a run with walls.
  integer function anitet_mesh_write_bl_columns(mesh, path) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=*), intent(in) :: path
    rc = c_anitet_mesh_write_bl_columns(mesh, to_c_string(path))
  end function

  integer function anitet_mesh_get_counts(mesh, num_points, num_tets, num_boundary_triangles) &
      result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int64_t), intent(out) :: num_points, num_tets, num_boundary_triangles
    rc = c_anitet_mesh_get_counts(mesh, num_points, num_tets, num_boundary_triangles)
  end function

  integer function anitet_mesh_get_points(mesh, xyz) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), allocatable, intent(out) :: xyz(:, :)
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(xyz(3, np))
    rc = c_anitet_mesh_get_points(mesh, xyz, size(xyz, kind=c_int64_t))
  end function

  integer function anitet_mesh_get_tets(mesh, tets, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: tets(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(tets(4, nt))
    rc = c_anitet_mesh_get_tets(mesh, tets, size(tets, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_mesh_get_regions(mesh, regions) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: regions(:)
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(regions(nt))
    rc = c_anitet_mesh_get_regions(mesh, regions, size(regions, kind=c_int64_t))
  end function

  integer function anitet_mesh_get_boundary_triangles(mesh, tri, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: tri(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(tri(3, nb))
    rc = c_anitet_mesh_get_boundary_triangles(mesh, tri, size(tri, kind=c_int64_t), &
                                              base_of(index_base))
  end function

  integer function anitet_mesh_get_boundary_patches(mesh, patch) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: patch(:)
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(patch(nb))
    rc = c_anitet_mesh_get_boundary_patches(mesh, patch, size(patch, kind=c_int64_t))
  end function

  ! Prism cells (options%bl_cells = ANITET_BL_CELLS_PRISMS): how many (0 without).
  integer function anitet_mesh_get_prism_count(mesh, num_prisms) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int64_t), intent(out) :: num_prisms
    rc = c_anitet_mesh_get_prism_count(mesh, num_prisms)
  end function

  ! prisms(6, num_prisms): the wall-side triangle, then the one its columns reach; 1-based
  ! unless index_base = 0.
  integer function anitet_mesh_get_prisms(mesh, prisms, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: prisms(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: n
    rc = c_anitet_mesh_get_prism_count(mesh, n)
    if (rc /= ANITET_OK) return
    allocate(prisms(6, n))
    rc = c_anitet_mesh_get_prisms(mesh, prisms, size(prisms, kind=c_int64_t), base_of(index_base))
  end function

  ! tet_prism(num_tets): per tet, the prism it is one of the 3 tets of, or
  ! -1 for a tet written as a tet; 1-based unless index_base = 0.
  integer function anitet_mesh_get_tet_prisms(mesh, tet_prism, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: tet_prism(:)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt, nb
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    allocate(tet_prism(nt))
    rc = c_anitet_mesh_get_tet_prisms(mesh, tet_prism, size(tet_prism, kind=c_int64_t), &
                                      base_of(index_base))
  end function

  integer function anitet_mesh_get_metric_components(mesh, components) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer, intent(out) :: components
    integer(c_int32_t) :: c
    rc = c_anitet_mesh_get_metric_components(mesh, c)
    components = int(c)
  end function

  ! values(components, num_points); components 0 gives a (0, num_points) array.
  integer function anitet_mesh_get_metric(mesh, values) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), allocatable, intent(out) :: values(:, :)
    integer(c_int64_t) :: np, nt, nb
    integer(c_int32_t) :: c
    rc = c_anitet_mesh_get_counts(mesh, np, nt, nb)
    if (rc /= ANITET_OK) return
    rc = c_anitet_mesh_get_metric_components(mesh, c)
    if (rc /= ANITET_OK) return
    allocate(values(c, np))
    if (c == 0) return
    rc = c_anitet_mesh_get_metric(mesh, values, size(values, kind=c_int64_t))
  end function

  ! values(components, num_points) with components 1 or 6; a (0, n) array removes the metric.
  integer function anitet_mesh_set_metric(mesh, values) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), intent(in) :: values(:, :)
    real(c_double) :: none(1)
    if (size(values, 1) == 0) then
      none = 0
      rc = c_anitet_mesh_set_metric(mesh, none, 0_c_int64_t, 0_c_int32_t)
    else
      rc = c_anitet_mesh_set_metric(mesh, values, size(values, kind=c_int64_t), &
                                    size(values, 1, c_int32_t))
    end if
  end function

  ! The mesh's per-vertex metric set to metric's values at its points (sizes when every tensor is
  ! isotropic, else tensors), for anitet_mesh_write_metric (`anitet mesh --write-metric`).
  integer function anitet_mesh_sample_metric(mesh, metric) result(rc)
    type(c_ptr), intent(in) :: mesh, metric
    rc = c_anitet_mesh_sample_metric(mesh, metric)
  end function

  ! Names the boundary patch `label` in the files anitet_mesh_write writes (SU2 markers, OpenFOAM
  ! patches, ...); trailing blanks are not part of the name. Without a name: removes it.
  integer function anitet_mesh_set_patch_name(mesh, label, name) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer, intent(in) :: label
    character(len=*), intent(in), optional :: name
    character(kind=c_char, len=:), allocatable, target :: c_name
    if (present(name)) then
      c_name = to_c_string(name)
      rc = c_anitet_mesh_set_patch_name(mesh, int(label, c_int32_t), c_loc(c_name))
    else
      rc = c_anitet_mesh_set_patch_name(mesh, int(label, c_int32_t), c_null_ptr)
    end if
  end function

  ! Sets the type (ANITET_PATCH_TYPE_*) of the boundary patch `label` in the files
  ! anitet_mesh_write writes (OpenFOAM, CGNS, Exodus II); ANITET_PATCH_TYPE_FROM_NAME removes it.
  integer function anitet_mesh_set_patch_type(mesh, label, type) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer, intent(in) :: label, type
    rc = c_anitet_mesh_set_patch_type(mesh, int(label, c_int32_t), int(type, c_int32_t))
  end function

  ! The type anitet_mesh_write gives the patch `label`: the one set, else the one its name implies.
  integer function anitet_mesh_get_patch_type(mesh, label, type) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer, intent(in) :: label
    integer, intent(out) :: type
    integer(c_int32_t) :: t
    t = ANITET_PATCH_TYPE_FROM_NAME
    rc = c_anitet_mesh_get_patch_type(mesh, int(label, c_int32_t), t)
    type = int(t)
  end function

  ! The figures of the run that made the mesh (an error for a mesh read or made from arrays).
  integer function anitet_mesh_get_run_stats(mesh, stats) result(rc)
    type(c_ptr), intent(in) :: mesh
    type(anitet_run_stats_t), intent(out) :: stats
    stats%version = ANITET_RUN_STATS_VERSION
    rc = c_anitet_mesh_get_run_stats(mesh, stats)
  end function

  ! The run's whole report as JSON text (stages, recovery, boundary_layer, notices, ...).
  integer function anitet_mesh_run_json(mesh, text) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=:), allocatable, intent(out) :: text
    character(kind=c_char), allocatable, target :: buf(:)
    integer(c_int64_t) :: needed, written
    text = ""
    needed = 0
    rc = c_anitet_mesh_run_json(mesh, c_null_ptr, 0_c_int64_t, needed)
    if (rc /= ANITET_OK) return
    allocate(buf(needed))
    rc = c_anitet_mesh_run_json(mesh, c_loc(buf), needed, written)
    if (rc == ANITET_OK) text = buffer_text(buf, needed)
  end function

  integer function anitet_mesh_quality(mesh, quality, input) result(rc)
    type(c_ptr), intent(in) :: mesh
    type(anitet_quality_t), intent(out) :: quality
    type(c_ptr), intent(in), optional :: input
    quality%version = ANITET_QUALITY_VERSION
    rc = c_anitet_mesh_quality(mesh, opt_ptr(input), quality)
  end function

  integer function anitet_mesh_quality_json(mesh, text, input) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=:), allocatable, intent(out) :: text
    type(c_ptr), intent(in), optional :: input
    character(kind=c_char), allocatable, target :: buf(:)
    integer(c_int64_t) :: needed, written
    text = ""
    needed = 0
    rc = c_anitet_mesh_quality_json(mesh, opt_ptr(input), c_null_ptr, 0_c_int64_t, needed)
    if (rc /= ANITET_OK) return
    allocate(buf(needed))
    rc = c_anitet_mesh_quality_json(mesh, opt_ptr(input), c_loc(buf), needed, written)
    if (rc == ANITET_OK) text = buffer_text(buf, needed)
  end function

  ! ---- per-vertex fields ------------------------------------------------------------------------

  ! Fields from kinds(num_fields) (ANITET_FIELD_KIND_*) and values(record_size, num_vertices):
  ! each column one vertex's record, every field's components in field order (copied).
  integer function anitet_fields_create(kinds, values, fields) result(rc)
    integer(c_int32_t), intent(in) :: kinds(:)
    real(c_double), intent(in) :: values(:, :)
    type(c_ptr), intent(out) :: fields
    rc = c_anitet_fields_create(kinds, size(kinds, kind=c_int32_t), values, &
                                size(values, kind=c_int64_t), fields)
  end function

  ! Fields from a Medit .sol or GMF .solb (by extension): its SolAtVertices block.
  integer function anitet_fields_read(path, fields) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(out) :: fields
    rc = c_anitet_fields_read(to_c_string(path), fields)
  end function

  integer function anitet_fields_write(fields, path) result(rc)
    type(c_ptr), intent(in) :: fields
    character(len=*), intent(in) :: path
    rc = c_anitet_fields_write(fields, to_c_string(path))
  end function

  subroutine anitet_fields_destroy(fields)
    type(c_ptr), intent(inout) :: fields
    call c_anitet_fields_destroy(fields)
    fields = c_null_ptr
  end subroutine

  integer function anitet_fields_get_counts(fields, num_fields, record_size, num_vertices) result(rc)
    type(c_ptr), intent(in) :: fields
    integer, intent(out), optional :: num_fields, record_size
    integer(c_int64_t), intent(out), optional :: num_vertices
    integer(c_int32_t) :: nf, rs
    integer(c_int64_t) :: nv
    rc = c_anitet_fields_get_counts(fields, nf, rs, nv)
    if (present(num_fields)) num_fields = int(nf)
    if (present(record_size)) record_size = int(rs)
    if (present(num_vertices)) num_vertices = nv
  end function

  ! kinds(num_fields): the fields' ANITET_FIELD_KIND_* values.
  integer function anitet_fields_get_kinds(fields, kinds) result(rc)
    type(c_ptr), intent(in) :: fields
    integer(c_int32_t), allocatable, intent(out) :: kinds(:)
    integer(c_int32_t) :: nf, rs
    integer(c_int64_t) :: nv
    rc = c_anitet_fields_get_counts(fields, nf, rs, nv)
    if (rc /= ANITET_OK) return
    allocate(kinds(nf))
    rc = c_anitet_fields_get_kinds(fields, kinds, size(kinds, kind=c_int64_t))
  end function

  ! values(record_size, num_vertices), a copy.
  integer function anitet_fields_get_values(fields, values) result(rc)
    type(c_ptr), intent(in) :: fields
    real(c_double), allocatable, intent(out) :: values(:, :)
    integer(c_int32_t) :: nf, rs
    integer(c_int64_t) :: nv
    rc = c_anitet_fields_get_counts(fields, nf, rs, nv)
    if (rc /= ANITET_OK) return
    allocate(values(rs, nv))
    if (size(values) == 0) return
    rc = c_anitet_fields_get_values(fields, values, size(values, kind=c_int64_t))
  end function

  ! data(record_size, num_vertices) pointing at the library's values, no copy: read only, valid
  ! while `fields` lives.
  integer function anitet_fields_get_data(fields, data) result(rc)
    type(c_ptr), intent(in) :: fields
    real(c_double), pointer, intent(out) :: data(:, :)
    integer(c_int32_t) :: nf, rs
    integer(c_int64_t) :: nv, count
    type(c_ptr) :: p
    nullify(data)
    rc = c_anitet_fields_get_counts(fields, nf, rs, nv)
    if (rc /= ANITET_OK) return
    rc = c_anitet_fields_get_data(fields, p, count)
    if (rc /= ANITET_OK) return
    call c_f_pointer(p, data, [int(rs, c_int64_t), nv])
  end function

  ! `fields` (at the points of `from`) carried to the points of `to` in a new `out`; tensors:
  ! ANITET_TENSORS_* (default ANITET_TENSORS_AUTO: metrics in log space); num_threads: the task
  ! arena's threads (default 0: all cores; the same values on any number).
  integer function anitet_mesh_transfer_fields(from, fields, to, out, tensors, num_threads) result(rc)
    type(c_ptr), intent(in) :: from, fields, to
    type(c_ptr), intent(out) :: out
    integer, intent(in), optional :: tensors, num_threads
    integer(c_int32_t) :: t, threads
    t = ANITET_TENSORS_AUTO
    if (present(tensors)) t = int(tensors, c_int32_t)
    threads = 0
    if (present(num_threads)) threads = int(num_threads, c_int32_t)
    rc = c_anitet_mesh_transfer_fields_ext(from, fields, to, t, threads, out)
  end function

  ! What the transfer that made `fields` found: points outside the old mesh, their largest
  ! distance to it and, per field, whether it went through log space.
  integer function anitet_fields_get_transfer_report(fields, outside, max_outside_distance, &
                                                     log_euclidean) result(rc)
    type(c_ptr), intent(in) :: fields
    integer(c_int64_t), intent(out), optional :: outside
    real(c_double), intent(out), optional :: max_outside_distance
    logical, allocatable, intent(out), optional :: log_euclidean(:)
    integer(c_int32_t) :: nf, rs
    integer(c_int64_t) :: nv, n_out
    real(c_double) :: distance
    integer(c_int32_t), allocatable, target :: flags(:)
    rc = c_anitet_fields_get_counts(fields, nf, rs, nv)
    if (rc /= ANITET_OK) return
    allocate(flags(max(nf, 1_c_int32_t)))
    rc = c_anitet_fields_get_transfer_report(fields, n_out, distance, c_loc(flags), &
                                             size(flags, kind=c_int64_t))
    if (rc /= ANITET_OK) return
    if (present(outside)) outside = n_out
    if (present(max_outside_distance)) max_outside_distance = distance
    if (present(log_euclidean)) log_euclidean = flags(1:nf) /= 0
  end function

  ! ---- adaptation -------------------------------------------------------------------------------

  integer function anitet_adapt_options_init(options, version) result(rc)
    type(anitet_adapt_options_t), intent(out) :: options
    integer, intent(in), optional :: version
    integer(c_int32_t) :: v
    v = ANITET_ADAPT_OPTIONS_VERSION
    if (present(version)) v = int(version, c_int32_t)
    rc = c_anitet_adapt_options_init(options, v)
  end function

  ! `mesh` adapted to metric(components, num_points) (components 1: sizes, 6: tensors xx xy yy xz
  ! yz zz) into a new mesh `out`; fields (at mesh's points) carried to out's points into
  ! out_fields (both or neither); stats filled when given (version ANITET_ADAPT_STATS_VERSION).
  integer function anitet_adapt(mesh, metric, out, fields, out_fields, options, stats) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), intent(in) :: metric(:, :)
    type(c_ptr), intent(out) :: out
    type(c_ptr), intent(in), optional :: fields
    type(c_ptr), intent(out), optional, target :: out_fields
    type(anitet_adapt_options_t), intent(in), optional, target :: options
    type(anitet_adapt_stats_t), intent(out), optional, target :: stats
    type(c_ptr) :: o, of, st
    call adapt_arguments(o, of, st, out_fields, options, stats)
    rc = c_anitet_adapt(mesh, metric, size(metric, kind=c_int64_t), size(metric, 1, kind=c_int32_t), &
                        opt_ptr(fields), o, out, of, st)
  end function

  ! The same with a metric handle evaluated at every new point (an analytic callback, a file).
  integer function anitet_adapt_to_metric(mesh, metric, out, fields, out_fields, options, stats) result(rc)
    type(c_ptr), intent(in) :: mesh, metric
    type(c_ptr), intent(out) :: out
    type(c_ptr), intent(in), optional :: fields
    type(c_ptr), intent(out), optional, target :: out_fields
    type(anitet_adapt_options_t), intent(in), optional, target :: options
    type(anitet_adapt_stats_t), intent(out), optional, target :: stats
    type(c_ptr) :: o, of, st
    call adapt_arguments(o, of, st, out_fields, options, stats)
    rc = c_anitet_adapt_to_metric(mesh, metric, opt_ptr(fields), o, out, of, st)
  end function

  ! The C pointers of anitet_adapt's optional arguments (c_null_ptr when absent); stats gets
  ! the newest version.
  subroutine adapt_arguments(o, of, st, out_fields, options, stats)
    type(c_ptr), intent(out) :: o, of, st
    type(c_ptr), intent(out), optional, target :: out_fields
    type(anitet_adapt_options_t), intent(in), optional, target :: options
    type(anitet_adapt_stats_t), intent(out), optional, target :: stats
    o = c_null_ptr
    of = c_null_ptr
    st = c_null_ptr
    if (present(options)) o = c_loc(options)
    if (present(out_fields)) then
      out_fields = c_null_ptr
      of = c_loc(out_fields)
    end if
    if (present(stats)) then
      stats%version = ANITET_ADAPT_STATS_VERSION
      st = c_loc(stats)
    end if
  end subroutine

  ! ---- geographic frames ------------------------------------------------------------------------
  ! Points in (longitude, latitude, height) on WGS84 moved to a local frame in metres and back.

  ! A frame of kind ANITET_GEO_ENU or ANITET_GEO_UTM at the origin (lat, lon in degrees, height
  ! in metres).
  integer function anitet_geo_frame_create(kind, lat, lon, height, frame) result(rc)
    integer, intent(in) :: kind
    real(c_double), intent(in) :: lat, lon, height
    type(c_ptr), intent(out) :: frame
    rc = c_anitet_geo_frame_create(int(kind, c_int32_t), lat, lon, height, frame)
  end function

  ! A frame at the centre of the bounding box of the surface's (lon, lat, h) points.
  integer function anitet_geo_frame_create_centred(kind, surface, frame) result(rc)
    integer, intent(in) :: kind
    type(c_ptr), intent(in) :: surface
    type(c_ptr), intent(out) :: frame
    rc = c_anitet_geo_frame_create_centred(int(kind, c_int32_t), surface, frame)
  end function

  subroutine anitet_geo_frame_destroy(frame)
    type(c_ptr), intent(inout) :: frame
    call c_anitet_geo_frame_destroy(frame)
    frame = c_null_ptr
  end subroutine

  ! The frame's origin and, for UTM, its zone (1-60; 0 for ENU) and hemisphere (north: .true.);
  ! every output is optional.
  integer function anitet_geo_frame_get(frame, lat, lon, height, utm_zone, utm_north) result(rc)
    type(c_ptr), intent(in) :: frame
    real(c_double), intent(out), optional :: lat, lon, height
    integer, intent(out), optional :: utm_zone
    logical, intent(out), optional :: utm_north
    real(c_double) :: la, lo, h
    integer(c_int32_t) :: zone, north
    rc = c_anitet_geo_frame_get(frame, la, lo, h, zone, north)
    if (rc /= ANITET_OK) return
    if (present(lat)) lat = la
    if (present(lon)) lon = lo
    if (present(height)) height = h
    if (present(utm_zone)) utm_zone = int(zone)
    if (present(utm_north)) utm_north = north == 1
  end function

  ! Moves the surface's points from (lon, lat, h) to the frame, in place.
  integer function anitet_surface_to_local(surface, frame) result(rc)
    type(c_ptr), intent(in) :: surface, frame
    rc = c_anitet_surface_to_local(surface, frame)
  end function

  ! The same for a mesh (a background mesh; its metric values are not converted).
  integer function anitet_mesh_to_local(mesh, frame) result(rc)
    type(c_ptr), intent(in) :: mesh, frame
    rc = c_anitet_mesh_to_local(mesh, frame)
  end function

  ! Moves the mesh's points back to (lon, lat, h); with geodetic_surface (the surface, before
  ! anitet_surface_to_local, that the mesh was made from) its points come back exactly.
  integer function anitet_mesh_to_geodetic(mesh, frame, geodetic_surface) result(rc)
    type(c_ptr), intent(in) :: mesh, frame
    type(c_ptr), intent(in), optional :: geodetic_surface
    rc = c_anitet_mesh_to_geodetic(mesh, frame, opt_ptr(geodetic_surface))
  end function

  ! ---- partitions -------------------------------------------------------------------------------
  ! Part numbers (indices, owners, neighbours) are 0-based: they are MPI ranks. Local and global
  ! ids are counted from index_base (default 1).

  integer function anitet_partition_options_init(options, version) result(rc)
    type(anitet_partition_options_t), intent(out) :: options
    integer, intent(in), optional :: version
    integer(c_int32_t) :: v
    v = ANITET_PARTITION_OPTIONS_VERSION
    if (present(version)) v = int(version, c_int32_t)
    rc = c_anitet_partition_options_init(options, v)
  end function

  integer function anitet_mesh_partition(mesh, num_parts, partition, options) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer, intent(in) :: num_parts
    type(c_ptr), intent(out) :: partition
    type(anitet_partition_options_t), intent(in), optional, target :: options
    if (present(options)) then
      rc = c_anitet_mesh_partition(mesh, int(num_parts, c_int32_t), c_loc(options), partition)
    else
      rc = c_anitet_mesh_partition(mesh, int(num_parts, c_int32_t), c_null_ptr, partition)
    end if
  end function

  subroutine anitet_partition_destroy(partition)
    type(c_ptr), intent(inout) :: partition
    call c_anitet_partition_destroy(partition)
    partition = c_null_ptr
  end subroutine

  integer function anitet_partition_get_info(partition, info) result(rc)
    type(c_ptr), intent(in) :: partition
    type(anitet_partition_info_t), intent(out) :: info
    info%version = ANITET_PARTITION_INFO_VERSION
    rc = c_anitet_partition_get_info(partition, info)
  end function

  ! parts(num_tets of the mesh): the part of each tet.
  integer function anitet_partition_get_tet_parts(partition, parts) result(rc)
    type(c_ptr), intent(in) :: partition
    integer(c_int32_t), allocatable, intent(out) :: parts(:)
    type(anitet_partition_info_t) :: info
    rc = anitet_partition_get_info(partition, info)
    if (rc /= ANITET_OK) return
    allocate(parts(info%num_tets))
    rc = c_anitet_partition_get_tet_parts(partition, parts, size(parts, kind=c_int64_t))
  end function

  ! A part lent by the partition (index 0 .. num_parts - 1): valid while the partition lives.
  integer function anitet_partition_get_part(partition, index, part) result(rc)
    type(c_ptr), intent(in) :: partition
    integer, intent(in) :: index
    type(c_ptr), intent(out) :: part
    rc = c_anitet_partition_get_part(partition, int(index, c_int32_t), part)
  end function

  ! Frees a part of one's own (anitet_part_deserialize, anitet_mesh_scatter); a lent one is left.
  subroutine anitet_part_destroy(part)
    type(c_ptr), intent(inout) :: part
    call c_anitet_part_destroy(part)
    part = c_null_ptr
  end subroutine

  integer function anitet_part_get_index(part, index, num_parts, num_neighbours, ghost_layers) &
      result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), intent(out) :: index, num_parts, num_neighbours, ghost_layers
    rc = c_anitet_part_get_index(part, index, num_parts, num_neighbours, ghost_layers)
  end function

  integer function anitet_part_get_counts(part, num_vertices, num_owned_vertices, num_tets, &
      num_owned_tets, num_boundary_triangles, num_owned_boundary_triangles) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int64_t), intent(out) :: num_vertices, num_owned_vertices, num_tets, num_owned_tets
    integer(c_int64_t), intent(out) :: num_boundary_triangles, num_owned_boundary_triangles
    rc = c_anitet_part_get_counts(part, num_vertices, num_owned_vertices, num_tets, &
                                  num_owned_tets, num_boundary_triangles, &
                                  num_owned_boundary_triangles)
  end function

  integer function anitet_part_get_points(part, xyz) result(rc)
    type(c_ptr), intent(in) :: part
    real(c_double), allocatable, intent(out) :: xyz(:, :)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(xyz(3, nv))
    rc = c_anitet_part_get_points(part, xyz, size(xyz, kind=c_int64_t))
  end function

  integer function anitet_part_get_tets(part, tets, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: tets(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(tets(4, nt))
    rc = c_anitet_part_get_tets(part, tets, size(tets, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_part_get_regions(part, regions) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: regions(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(regions(nt))
    rc = c_anitet_part_get_regions(part, regions, size(regions, kind=c_int64_t))
  end function

  integer function anitet_part_get_vertex_global_ids(part, ids, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int64_t), allocatable, intent(out) :: ids(:)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(ids(nv))
    rc = c_anitet_part_get_vertex_global_ids(part, ids, size(ids, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_part_get_vertex_owners(part, owners) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: owners(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(owners(nv))
    rc = c_anitet_part_get_vertex_owners(part, owners, size(owners, kind=c_int64_t))
  end function

  integer function anitet_part_get_tet_global_ids(part, ids, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int64_t), allocatable, intent(out) :: ids(:)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(ids(nt))
    rc = c_anitet_part_get_tet_global_ids(part, ids, size(ids, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_part_get_tet_owners(part, owners) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: owners(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(owners(nt))
    rc = c_anitet_part_get_tet_owners(part, owners, size(owners, kind=c_int64_t))
  end function

  integer function anitet_part_get_tet_layers(part, layers) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: layers(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(layers(nt))
    rc = c_anitet_part_get_tet_layers(part, layers, size(layers, kind=c_int64_t))
  end function

  integer function anitet_part_get_boundary_triangles(part, tri, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: tri(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(tri(3, nb))
    rc = c_anitet_part_get_boundary_triangles(part, tri, size(tri, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_part_get_boundary_patches(part, patch) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: patch(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(patch(nb))
    rc = c_anitet_part_get_boundary_patches(part, patch, size(patch, kind=c_int64_t))
  end function

  integer function anitet_part_get_boundary_global_ids(part, ids, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int64_t), allocatable, intent(out) :: ids(:)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob
    rc = c_anitet_part_get_counts(part, nv, nov, nt, nto, nb, nob)
    if (rc /= ANITET_OK) return
    allocate(ids(nb))
    rc = c_anitet_part_get_boundary_global_ids(part, ids, size(ids, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_part_get_neighbours(part, neighbours) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int32_t), allocatable, intent(out) :: neighbours(:)
    integer(c_int32_t) :: index, num_parts, num_neighbours, ghost_layers
    rc = c_anitet_part_get_index(part, index, num_parts, num_neighbours, ghost_layers)
    if (rc /= ANITET_OK) return
    allocate(neighbours(num_neighbours))
    rc = c_anitet_part_get_neighbours(part, neighbours, size(neighbours, kind=c_int64_t))
  end function

  ! Halo list `list` (ANITET_HALO_*): offsets(num_neighbours + 1) and items; with the default
  ! index_base 1, items(offsets(i) : offsets(i + 1) - 1) is the list of neighbours(i).
  integer function anitet_part_get_halo(part, list, offsets, items, index_base) result(rc)
    type(c_ptr), intent(in) :: part
    integer, intent(in) :: list
    integer(c_int64_t), allocatable, intent(out) :: offsets(:)
    integer(c_int32_t), allocatable, intent(out) :: items(:)
    integer, intent(in), optional :: index_base
    integer(c_int32_t) :: index, num_parts, num_neighbours, ghost_layers
    integer(c_int64_t) :: n
    rc = c_anitet_part_get_index(part, index, num_parts, num_neighbours, ghost_layers)
    if (rc /= ANITET_OK) return
    rc = c_anitet_part_get_halo_size(part, int(list, c_int32_t), n)
    if (rc /= ANITET_OK) return
    allocate(offsets(num_neighbours + 1), items(n))
    rc = c_anitet_part_get_halo(part, int(list, c_int32_t), offsets, size(offsets, kind=c_int64_t), &
                                items, n, base_of(index_base))
  end function

  integer function anitet_part_serialize(part, bytes) result(rc)
    type(c_ptr), intent(in) :: part
    integer(c_int8_t), allocatable, target, intent(out) :: bytes(:)
    integer(c_int64_t) :: needed, written
    needed = 0
    rc = c_anitet_part_serialize(part, c_null_ptr, 0_c_int64_t, needed)
    if (rc /= ANITET_OK) return
    allocate(bytes(needed))
    rc = c_anitet_part_serialize(part, c_loc(bytes), needed, written)
  end function

  integer function anitet_part_deserialize(bytes, part) result(rc)
    integer(c_int8_t), intent(in) :: bytes(:)
    type(c_ptr), intent(out) :: part
    rc = c_anitet_part_deserialize(bytes, size(bytes, kind=c_int64_t), part)
  end function

  ! ---- 2D meshes ----------------------------------------------------------------------------------

  ! xy(2, np), segments(2, ns), labels(ns), holes(2, nh); index_base default 1.
  integer function anitet_pslg_create(xy, segments, pslg, labels, holes, index_base) result(rc)
    real(c_double), intent(in) :: xy(:, :)
    integer(c_int32_t), intent(in) :: segments(:, :)
    type(c_ptr), intent(out) :: pslg
    integer(c_int32_t), intent(in), optional :: labels(:)
    real(c_double), intent(in), optional :: holes(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int32_t), allocatable, target :: l(:)
    real(c_double), allocatable, target :: h(:, :)
    type(c_ptr) :: lp, hp
    integer(c_int64_t) :: nh
    ! Wrong shapes would be misread silently by C (Fortran-only check: no last error message).
    pslg = c_null_ptr
    rc = ANITET_ERR_INVALID_ARGUMENT
    if (size(xy, 1) /= 2 .or. size(segments, 1) /= 2) return
    lp = c_null_ptr
    hp = c_null_ptr
    nh = 0
    if (present(labels)) then
      if (size(labels) /= size(segments, 2)) return
      allocate(l(size(labels)))
      l(:) = labels
      lp = c_loc(l)
    end if
    if (present(holes)) then
      if (size(holes, 1) /= 2) return
      allocate(h(2, size(holes, 2)))
      h(:, :) = holes
      hp = c_loc(h)
      nh = size(holes, 2, c_int64_t)
    end if
    rc = c_anitet_pslg_create(xy, size(xy, 2, c_int64_t), segments, size(segments, 2, c_int64_t), lp, &
                              hp, nh, base_of(index_base), pslg)
  end function

  integer function anitet_pslg_read(path, pslg) result(rc)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(out) :: pslg
    rc = c_anitet_pslg_read(to_c_string(path), pslg)
  end function

  subroutine anitet_pslg_destroy(pslg)
    type(c_ptr), intent(inout) :: pslg
    call c_anitet_pslg_destroy(pslg)
    pslg = c_null_ptr
  end subroutine

  integer function anitet_pslg_get_counts(pslg, num_points, num_segments, num_holes) result(rc)
    type(c_ptr), intent(in) :: pslg
    integer(c_int64_t), intent(out) :: num_points, num_segments, num_holes
    rc = c_anitet_pslg_get_counts(pslg, num_points, num_segments, num_holes)
  end function

  integer function anitet_mesh2d_options_init(options, version) result(rc)
    type(anitet_mesh2d_options_t), intent(out) :: options
    integer, intent(in), optional :: version
    integer(c_int32_t) :: v
    v = ANITET_MESH2D_OPTIONS_VERSION
    if (present(version)) v = int(version, c_int32_t)
    rc = c_anitet_mesh2d_options_init(options, v)
  end function

  integer function anitet_mesh2d_run(pslg, mesh, metric, options) result(rc)
    type(c_ptr), intent(in) :: pslg
    type(c_ptr), intent(out) :: mesh
    type(c_ptr), intent(in), optional :: metric
    type(anitet_mesh2d_options_t), intent(in), optional, target :: options
    if (present(options)) then
      rc = c_anitet_mesh2d_run(pslg, opt_ptr(metric), c_loc(options), mesh)
    else
      rc = c_anitet_mesh2d_run(pslg, opt_ptr(metric), c_null_ptr, mesh)
    end if
  end function

  subroutine anitet_mesh2d_destroy(mesh)
    type(c_ptr), intent(inout) :: mesh
    call c_anitet_mesh2d_destroy(mesh)
    mesh = c_null_ptr
  end subroutine

  integer function anitet_mesh2d_get_counts(mesh, num_points, num_triangles, num_edges) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int64_t), intent(out) :: num_points, num_triangles, num_edges
    rc = c_anitet_mesh2d_get_counts(mesh, num_points, num_triangles, num_edges)
  end function

  integer function anitet_mesh2d_get_points(mesh, xy) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), allocatable, intent(out) :: xy(:, :)
    integer(c_int64_t) :: np, nt, ne
    rc = c_anitet_mesh2d_get_counts(mesh, np, nt, ne)
    if (rc /= ANITET_OK) return
    allocate(xy(2, np))
    rc = c_anitet_mesh2d_get_points(mesh, xy, size(xy, kind=c_int64_t))
  end function

  integer function anitet_mesh2d_get_triangles(mesh, tri, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: tri(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt, ne
    rc = c_anitet_mesh2d_get_counts(mesh, np, nt, ne)
    if (rc /= ANITET_OK) return
    allocate(tri(3, nt))
    rc = c_anitet_mesh2d_get_triangles(mesh, tri, size(tri, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_mesh2d_get_attributes(mesh, attributes) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), allocatable, intent(out) :: attributes(:)
    integer(c_int64_t) :: np, nt, ne
    rc = c_anitet_mesh2d_get_counts(mesh, np, nt, ne)
    if (rc /= ANITET_OK) return
    allocate(attributes(nt))
    rc = c_anitet_mesh2d_get_attributes(mesh, attributes, size(attributes, kind=c_int64_t))
  end function

  integer function anitet_mesh2d_get_edges(mesh, edges, index_base) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: edges(:, :)
    integer, intent(in), optional :: index_base
    integer(c_int64_t) :: np, nt, ne
    rc = c_anitet_mesh2d_get_counts(mesh, np, nt, ne)
    if (rc /= ANITET_OK) return
    allocate(edges(2, ne))
    rc = c_anitet_mesh2d_get_edges(mesh, edges, size(edges, kind=c_int64_t), base_of(index_base))
  end function

  integer function anitet_mesh2d_get_edge_labels(mesh, labels) result(rc)
    type(c_ptr), intent(in) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: labels(:)
    integer(c_int64_t) :: np, nt, ne
    rc = c_anitet_mesh2d_get_counts(mesh, np, nt, ne)
    if (rc /= ANITET_OK) return
    allocate(labels(ne))
    rc = c_anitet_mesh2d_get_edge_labels(mesh, labels, size(labels, kind=c_int64_t))
  end function

  integer function anitet_mesh2d_write(mesh, path) result(rc)
    type(c_ptr), intent(in) :: mesh
    character(len=*), intent(in) :: path
    rc = c_anitet_mesh2d_write(mesh, to_c_string(path))
  end function

  integer function anitet_mesh2d_quality(mesh, min_angle_deg, min_angle_off_input_deg, &
                                         mean_radius_ratio, edges_in_range) result(rc)
    type(c_ptr), intent(in) :: mesh
    real(c_double), intent(out) :: min_angle_deg, min_angle_off_input_deg, mean_radius_ratio
    real(c_double), intent(out) :: edges_in_range
    rc = c_anitet_mesh2d_quality(mesh, min_angle_deg, min_angle_off_input_deg, mean_radius_ratio, &
                                 edges_in_range)
  end function

end module anitet
