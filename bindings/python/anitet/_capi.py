"""ctypes declarations of include/anitet.h and the loading of libanitet.

Every function of the header has an entry in _PROTOTYPES (tests/python checks that against the
header, so that the two cannot drift); the structs mirror the C layouts field by field.
"""
import ctypes
import ctypes.util
import os
from ctypes import (CFUNCTYPE, POINTER, Structure, c_char_p, c_double, c_int, c_int32, c_int64,
                    c_void_p)

SOVERSION = 0

# ---- constants (equal to the header's macros) -----------------------------------------------
VERSION_MAJOR = 0
VERSION_MINOR = 1
VERSION_PATCH = 0
OK = 0
ERR_INVALID_ARGUMENT = -1
ERR_FILE_NOT_FOUND = -2
ERR_PARSE = -3
ERR_UNSUPPORTED_FORMAT = -4
ERR_EMPTY_INPUT = -5
ERR_BUFFER_TOO_SMALL = -6
ERR_NON_FINITE_COORDINATE = -10
ERR_DEGENERATE_TRIANGLE = -11
ERR_DUPLICATE_TRIANGLE = -12
ERR_OPEN_BOUNDARY = -13
ERR_NON_MANIFOLD_EDGE = -14
ERR_NON_MANIFOLD_VERTEX = -15
ERR_INCONSISTENT_ORIENTATION = -16
ERR_SELF_INTERSECTION = -17
ERR_INTERSECTING_SHELLS = -18
ERR_BAD_INDEX = -19
ERR_NOT_IMPLEMENTED = -30
ERR_CANCELLED = -31
ERR_DUPLICATE_POINT = -32
ERR_RECOVERY_FAILED = -33
ERR_INVALID_MESH = -34
ERR_OUT_OF_MEMORY = -40
ERR_INTERNAL = -99
LOG_ERROR = 0
LOG_WARNING = 1
LOG_INFO = 2
LOG_DEBUG = 3
OPTIONS_VERSION = 5
QUALITY_VERSION = 1
RUN_STATS_VERSION = 3
LAYERS_PUSH = 0
LAYERS_FACE_PUSH = 1
RECOVERY_ALL = 0
RECOVERY_SPLIT = 1
RECOVERY_FUZZY = 2
BL_CELLS_TETS = 0
BL_CELLS_PRISMS = 1
GEO_ENU = 0
GEO_UTM = 1
PATCH_TYPE_FROM_NAME = -1
PATCH_TYPE_WALL = 0
PATCH_TYPE_INLET = 1
PATCH_TYPE_OUTLET = 2
PATCH_TYPE_FARFIELD = 3
PATCH_TYPE_SYMMETRY = 4
PATCH_TYPE_PATCH = 5
FIELD_KIND_SCALAR = 1
FIELD_KIND_VECTOR = 2
FIELD_KIND_SYM_TENSOR = 3
TENSORS_AUTO = 0
TENSORS_LOG_EUCLIDEAN = 1
TENSORS_LINEAR = 2
PARTITION_OPTIONS_VERSION = 1
PARTITION_INFO_VERSION = 1
HALO_VERTEX_SEND = 0
HALO_VERTEX_RECV = 1
HALO_TET_SEND = 2
HALO_TET_RECV = 3
TYPE_INT32 = 1
TYPE_INT64 = 2
TYPE_DOUBLE = 3
PART_POINTS = 0
PART_VERTEX_GLOBAL_IDS = 1
PART_VERTEX_OWNERS = 2
PART_TETS = 3
PART_TET_GLOBAL_IDS = 4
PART_TET_OWNERS = 5
PART_TET_LAYERS = 6
PART_REGIONS = 7
PART_BOUNDARY_TRIANGLES = 8
PART_BOUNDARY_PATCHES = 9
PART_BOUNDARY_GLOBAL_IDS = 10
PART_NEIGHBOURS = 11
PART_VERTEX_SEND_OFFSETS = 12
PART_VERTEX_SEND = 13
PART_VERTEX_RECV_OFFSETS = 14
PART_VERTEX_RECV = 15
PART_TET_SEND_OFFSETS = 16
PART_TET_SEND = 17
PART_TET_RECV_OFFSETS = 18
PART_TET_RECV = 19
MESH2D_OPTIONS_VERSION = 1
ADAPT_OPTIONS_VERSION = 1
ADAPT_STATS_VERSION = 1

# ---- callbacks and structs ----------------------------------------------------------------------
PROGRESS_FN = CFUNCTYPE(c_int, c_double, c_char_p, c_void_p)
LOG_FN = CFUNCTYPE(None, c_int32, c_char_p, c_void_p)
METRIC_FN = CFUNCTYPE(c_int, c_double, c_double, c_double, POINTER(c_double), c_void_p)


class COptions(Structure):
    _fields_ = [
        ("version", c_int32),
        ("num_threads", c_int32),
        ("merge_duplicate_vertices", c_int32),
        ("orient_shells", c_int32),
        ("check_self_intersections", c_int32),
        ("reserved0", c_int32),
        ("progress", PROGRESS_FN),
        ("progress_user_data", c_void_p),
        ("log", LOG_FN),
        ("log_user_data", c_void_p),
        # version 2
        ("layers", c_int32),
        ("layer_scheme", c_int32),
        ("recovery_max_seconds", c_double),
        ("refine", c_int32),
        ("optimize", c_int32),
        ("size_scale", c_double),
        # version 3
        ("attempts_seconds", c_double),
        ("retry_layer_counts", c_int32),
        ("recovery", c_int32),
        ("hmin", c_double),
        ("hmax", c_double),
        ("hgrad", c_double),
        ("max_tets", c_double),
        ("anisotropic_cycles", c_int32),
        ("bl_num_patches", c_int32),
        ("bl_patches", POINTER(c_int32)),
        ("bl_first_height", c_double),
        ("bl_growth", c_double),
        ("bl_layers", c_int32),
        ("bl_sizing", c_int32),
        ("push_tasks_min_vertices", c_int32),
        ("bl_mitre", c_int32),
        # version 4
        ("bl_num_slide_patches", c_int32),
        ("bl_cells", c_int32),
        ("bl_slide_patches", POINTER(c_int32)),
        # version 5
        ("bl_sizing_growth", c_double),
    ]


class CRunStats(Structure):
    _fields_ = [
        ("version", c_int32),
        ("layers_used", c_int32),
        ("layers_retries", c_int32),
        ("recovery_strategy", c_int32),
        ("refine_passes", c_int32),
        ("refine_stopped_at_pass_cap", c_int32),
        ("anisotropic_cycles", c_int32),
        ("num_notices", c_int32),
        ("vertices", c_int64),
        ("tets", c_int64),
        ("steiner_on_front_edges", c_int64),
        ("steiner_on_front_faces", c_int64),
        ("refine_splits", c_int64),
        ("refine_collapses", c_int64),
        ("flat_tets_left", c_int64),
        ("metric_not_spd", c_int64),
        ("seconds", c_double),
        ("estimated_tets", c_double),
        ("edges_in_range", c_double),
        ("metric_radius_ratio_mean", c_double),
        ("metric_radius_ratio_min", c_double),
        ("bl_layers", c_int32),
        ("reserved0", c_int32),
        ("bl_wall_vertices", c_int64),
        ("bl_full_columns", c_int64),
        ("bl_nominal_columns", c_int64),
        ("bl_reduced_vertices", c_int64),
        ("bl_tets", c_int64),
        ("bl_first_height_min", c_double),
        ("bl_first_height_mean", c_double),
        ("bl_first_height_max", c_double),
        ("bl_growth_mean", c_double),
        ("bl_max_height_error", c_double),
        # version 2
        ("slide_junction_columns", c_int64),
        ("slide_lowered_columns", c_int64),
        ("slide_triangles_added", c_int64),
        # version 3
        ("bl_prisms", c_int64),
        ("bl_prism_tets_left", c_int64),
    ]


class CQuality(Structure):
    _fields_ = [
        ("version", c_int32),
        ("valid", c_int32),
        ("boundary_constrained", c_int32),
        ("reserved0", c_int32),
        ("vertices", c_int64),
        ("tets", c_int64),
        ("nonpositive_tets", c_int64),
        ("radius_ratio_mean", c_double),
        ("radius_ratio_min", c_double),
        ("mean_ratio_mean", c_double),
        ("mean_ratio_min", c_double),
        ("min_dihedral_deg", c_double),
        ("max_dihedral_deg", c_double),
        ("good_fraction", c_double),
        ("bad_fraction", c_double),
    ]


class CPartitionOptions(Structure):
    _fields_ = [
        ("version", c_int32),
        ("num_threads", c_int32),
        ("ghost_layers", c_int32),
        ("reserved0", c_int32),
        ("imbalance", c_double),
        ("tet_weights", POINTER(c_double)),
        ("num_tet_weights", c_int64),
    ]


class CPartitionInfo(Structure):
    _fields_ = [
        ("version", c_int32),
        ("num_parts", c_int32),
        ("ghost_layers", c_int32),
        ("empty_parts", c_int32),
        ("num_tets", c_int64),
        ("edge_cut", c_int64),
        ("interface_vertices", c_int64),
        ("imbalance", c_double),
        ("total_weight", c_double),
        ("max_part_weight", c_double),
    ]


class CAdaptOptions(Structure):
    _fields_ = [
        ("version", c_int32),
        ("num_threads", c_int32),
        ("keep_surface", c_int32),
        ("max_cycles", c_int32),
        ("ridge_angle_deg", c_double),
        ("optimize_cycles", c_int32),
        ("tensors", c_int32),
        ("progress", PROGRESS_FN),
        ("progress_user_data", c_void_p),
        ("log", LOG_FN),
        ("log_user_data", c_void_p),
    ]


class CAdaptStats(Structure):
    _fields_ = [("version", c_int32), ("cycles", c_int32)] + [
        (name, c_int64) for name in (
            "vertices_in", "tets_in", "boundary_triangles_in", "vertices", "tets", "boundary_triangles",
            "ridge_edges", "corners", "splits", "surface_splits", "collapses", "surface_collapses", "swaps",
            "surface_swaps", "moves", "surface_moves", "splits_refused", "collapses_refused", "edges")
    ] + [
        (name, c_double) for name in (
            "edges_in_range", "edges_shorter", "edges_longer", "edge_length_min", "edge_length_mean",
            "edge_length_max", "mean_ratio_min", "mean_ratio_mean", "seconds", "seconds_adapt", "seconds_split",
            "seconds_collapse", "seconds_swap", "seconds_smooth", "seconds_transfer", "seconds_measure")
    ]


class CMesh2dOptions(Structure):
    _fields_ = [
        ("version", c_int32),
        ("split_segments", c_int32),
        ("layers", c_int32),
        ("refine", c_int32),
        ("optimize", c_int32),
        ("geodetic", c_int32),
        ("geo_frame", c_int32),
        ("reserved0", c_int32),
        ("hsize", c_double),
        ("size_scale", c_double),
        ("hmin", c_double),
        ("hmax", c_double),
        ("hgrad", c_double),
        ("progress", PROGRESS_FN),
        ("progress_user_data", c_void_p),
    ]


_P = c_void_p  # an opaque handle
_PP = POINTER(c_void_p)  # a handle returned through the last argument
_D = POINTER(c_double)
_I32 = POINTER(c_int32)
_I64 = POINTER(c_int64)

# name: (restype, argtypes), in the header's order.
_PROTOTYPES = {
    "anitet_options_init": (c_int, [POINTER(COptions), c_int32]),
    "anitet_version": (c_char_p, []),
    "anitet_version_number": (c_int32, []),
    "anitet_last_error_message": (c_char_p, []),
    "anitet_error_name": (c_char_p, [c_int32]),
    "anitet_surface_create": (c_int, [_D, c_int64, _I32, c_int64, _I32, c_int32, _PP]),
    "anitet_surface_read": (c_int, [c_char_p, _PP]),
    "anitet_surface_destroy": (None, [_P]),
    "anitet_surface_get_counts": (c_int, [_P, _I64, _I64]),
    "anitet_surface_get_points": (c_int, [_P, _D, c_int64]),
    "anitet_surface_get_triangles": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_surface_get_patches": (c_int, [_P, _I32, c_int64]),
    "anitet_surface_validate": (c_int, [_P, POINTER(COptions)]),
    "anitet_surface_problem_count": (c_int, [_P, c_int32, _I64]),
    "anitet_surface_validation_json": (c_int, [_P, c_char_p, c_int64, _I64]),
    "anitet_metric_create_uniform": (c_int, [c_double, _PP]),
    "anitet_metric_create_analytic": (c_int, [METRIC_FN, c_void_p, _PP]),
    "anitet_metric_read": (c_int, [c_char_p, c_char_p, _PP]),
    "anitet_metric_create_from_points": (c_int, [_P, _D, c_int64, c_int32, _PP]),
    "anitet_metric_destroy": (None, [_P]),
    "anitet_metric_evaluate": (c_int, [_P, c_double, c_double, c_double, _D]),
    "anitet_metric_create_surface_sizing": (c_int, [_P, POINTER(COptions), _PP]),
    "anitet_metric_read_on_mesh": (c_int, [c_char_p, _P, _PP]),
    "anitet_metric_write": (c_int, [_P, _P, c_char_p]),
    "anitet_mesher_run": (c_int, [_P, _P, POINTER(COptions), _PP]),
    "anitet_layers_run": (c_int, [_P, POINTER(COptions), _PP]),
    "anitet_bl_first_height": (c_int, [c_double, c_double, c_double, _D]),
    "anitet_mesh_create": (c_int, [_D, c_int64, _I32, c_int64, _I32, _I32, c_int64, _I32, c_int32,
                                   _PP]),
    "anitet_mesh_read": (c_int, [c_char_p, _PP]),
    "anitet_mesh_destroy": (None, [_P]),
    "anitet_mesh_write": (c_int, [_P, c_char_p]),
    "anitet_mesh_write_metric": (c_int, [_P, c_char_p]),
    "anitet_mesh_write_bl_columns": (c_int, [_P, c_char_p]),
    "anitet_mesh_get_counts": (c_int, [_P, _I64, _I64, _I64]),
    "anitet_mesh_get_points": (c_int, [_P, _D, c_int64]),
    "anitet_mesh_get_prism_count": (c_int, [_P, _I64]),
    "anitet_mesh_get_prisms": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh_get_tet_prisms": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh_get_tets": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh_get_regions": (c_int, [_P, _I32, c_int64]),
    "anitet_mesh_get_boundary_triangles": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh_get_boundary_patches": (c_int, [_P, _I32, c_int64]),
    "anitet_mesh_get_metric_components": (c_int, [_P, _I32]),
    "anitet_mesh_get_metric": (c_int, [_P, _D, c_int64]),
    "anitet_mesh_set_patch_name": (c_int, [_P, c_int32, c_char_p]),
    "anitet_mesh_set_patch_type": (c_int, [_P, c_int32, c_int32]),
    "anitet_mesh_get_patch_type": (c_int, [_P, c_int32, _I32]),
    "anitet_mesh_set_metric": (c_int, [_P, _D, c_int64, c_int32]),
    "anitet_mesh_sample_metric": (c_int, [_P, _P]),
    "anitet_fields_create": (c_int, [_I32, c_int32, _D, c_int64, _PP]),
    "anitet_fields_read": (c_int, [c_char_p, _PP]),
    "anitet_fields_write": (c_int, [_P, c_char_p]),
    "anitet_fields_destroy": (None, [_P]),
    "anitet_fields_get_counts": (c_int, [_P, _I32, _I32, _I64]),
    "anitet_fields_get_kinds": (c_int, [_P, _I32, c_int64]),
    "anitet_fields_get_values": (c_int, [_P, _D, c_int64]),
    "anitet_fields_get_data": (c_int, [_P, POINTER(_D), _I64]),
    "anitet_mesh_transfer_fields": (c_int, [_P, _P, _P, c_int32, _PP]),
    "anitet_mesh_transfer_fields_ext": (c_int, [_P, _P, _P, c_int32, c_int32, _PP]),
    "anitet_fields_get_transfer_report": (c_int, [_P, _I64, _D, _I32, c_int64]),
    "anitet_adapt_options_init": (c_int, [POINTER(CAdaptOptions), c_int32]),
    "anitet_adapt": (c_int, [_P, _D, c_int64, c_int32, _P, POINTER(CAdaptOptions), _PP, _PP,
                             POINTER(CAdaptStats)]),
    "anitet_adapt_to_metric": (c_int, [_P, _P, _P, POINTER(CAdaptOptions), _PP, _PP, POINTER(CAdaptStats)]),
    "anitet_mesh_get_run_stats": (c_int, [_P, POINTER(CRunStats)]),
    "anitet_mesh_run_json": (c_int, [_P, c_char_p, c_int64, _I64]),
    "anitet_mesh_quality": (c_int, [_P, _P, POINTER(CQuality)]),
    "anitet_mesh_quality_json": (c_int, [_P, _P, c_char_p, c_int64, _I64]),
    "anitet_geo_frame_create": (c_int, [c_int32, c_double, c_double, c_double, _PP]),
    "anitet_geo_frame_create_centred": (c_int, [c_int32, _P, _PP]),
    "anitet_geo_frame_destroy": (None, [_P]),
    "anitet_geo_frame_get": (c_int, [_P, _D, _D, _D, _I32, _I32]),
    "anitet_surface_to_local": (c_int, [_P, _P]),
    "anitet_mesh_to_local": (c_int, [_P, _P]),
    "anitet_mesh_to_geodetic": (c_int, [_P, _P, _P]),
    "anitet_partition_options_init": (c_int, [POINTER(CPartitionOptions), c_int32]),
    "anitet_mesh_partition": (c_int, [_P, c_int32, POINTER(CPartitionOptions), _PP]),
    "anitet_partition_destroy": (None, [_P]),
    "anitet_partition_get_info": (c_int, [_P, POINTER(CPartitionInfo)]),
    "anitet_partition_get_tet_parts": (c_int, [_P, _I32, c_int64]),
    "anitet_partition_get_part": (c_int, [_P, c_int32, _PP]),
    "anitet_part_destroy": (None, [_P]),
    "anitet_part_get_index": (c_int, [_P, _I32, _I32, _I32, _I32]),
    "anitet_part_get_counts": (c_int, [_P, _I64, _I64, _I64, _I64, _I64, _I64]),
    "anitet_part_get_points": (c_int, [_P, _D, c_int64]),
    "anitet_part_get_tets": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_part_get_regions": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_vertex_global_ids": (c_int, [_P, _I64, c_int64, c_int32]),
    "anitet_part_get_vertex_owners": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_tet_global_ids": (c_int, [_P, _I64, c_int64, c_int32]),
    "anitet_part_get_tet_owners": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_tet_layers": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_boundary_triangles": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_part_get_boundary_patches": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_boundary_global_ids": (c_int, [_P, _I64, c_int64, c_int32]),
    "anitet_part_get_neighbours": (c_int, [_P, _I32, c_int64]),
    "anitet_part_get_halo_size": (c_int, [_P, c_int32, _I64]),
    "anitet_part_get_halo": (c_int, [_P, c_int32, _I64, c_int64, _I32, c_int64, c_int32]),
    "anitet_part_get_array": (c_int, [_P, c_int32, _PP, _I64, _I32]),
    "anitet_part_serialize": (c_int, [_P, c_void_p, c_int64, _I64]),
    "anitet_part_deserialize": (c_int, [c_void_p, c_int64, _PP]),
    "anitet_set_last_error": (c_int, [c_int32, c_char_p]),
    "anitet_pslg_create": (c_int, [_D, c_int64, _I32, c_int64, _I32, _D, c_int64, c_int32, _PP]),
    "anitet_pslg_read": (c_int, [c_char_p, _PP]),
    "anitet_pslg_destroy": (None, [_P]),
    "anitet_pslg_get_counts": (c_int, [_P, _I64, _I64, _I64]),
    "anitet_mesh2d_options_init": (c_int, [POINTER(CMesh2dOptions), c_int32]),
    "anitet_mesh2d_run": (c_int, [_P, _P, POINTER(CMesh2dOptions), _PP]),
    "anitet_mesh2d_destroy": (None, [_P]),
    "anitet_mesh2d_get_counts": (c_int, [_P, _I64, _I64, _I64]),
    "anitet_mesh2d_get_points": (c_int, [_P, _D, c_int64]),
    "anitet_mesh2d_get_triangles": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh2d_get_attributes": (c_int, [_P, _D, c_int64]),
    "anitet_mesh2d_get_edges": (c_int, [_P, _I32, c_int64, c_int32]),
    "anitet_mesh2d_get_edge_labels": (c_int, [_P, _I32, c_int64]),
    "anitet_mesh2d_write": (c_int, [_P, c_char_p]),
    "anitet_mesh2d_quality": (c_int, [_P, _D, _D, _D, _D]),
}


def _candidates():
    """Where libanitet may be, most specific first."""
    env = os.environ.get("ANITET_LIBRARY")
    if env:
        return [env]  # an explicit choice is not second-guessed
    found = []
    try:  # written into an installed copy by `cmake --install` (bindings/python/CMakeLists.txt)
        from . import _installed  # type: ignore
        found.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), _installed.LIBRARY))
    except ImportError:
        pass
    found.append("libanitet.so.%d" % SOVERSION)  # the loader's search path (ldconfig, LD_LIBRARY_PATH)
    name = ctypes.util.find_library("anitet")
    if name:
        found.append(name)
    return found


def _load():
    errors = []
    for path in _candidates():
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            errors.append("%s: %s" % (path, e))
            continue
        for name, (restype, argtypes) in _PROTOTYPES.items():
            fn = getattr(lib, name)
            fn.restype = restype
            fn.argtypes = argtypes
        return lib
    raise OSError("anitet: cannot load libanitet (set ANITET_LIBRARY to its path); tried:\n  " +
                  "\n  ".join(errors))


lib = _load()
