"""anitet: boundary-constrained tetrahedral meshing, from Python.

A pure-Python binding (ctypes) over the C ABI of libanitet (include/anitet.h): no compiled
extension. The library is found through ANITET_LIBRARY (a path), then next to an installed copy
of this package, then the system's loader (libanitet.so.0). NumPy is optional.

    import anitet
    surface = anitet.Surface.read("fandisk.off")          # or Surface.from_arrays(points, tris)
    mesh = anitet.mesh_surface(surface, layers=2, progress=lambda stage, f: print(stage, f))
    print(mesh.counts(), mesh.quality(surface), mesh.run_stats)
    t1 = anitet.build_layers(surface, bl_patches=[0], bl_first_height=0.01)  # stage 1 alone
    mesh.patch_names[0] = "wall"                           # an OFF file: every triangle label 0
    mesh.set_patch_type(0, "wall")                         # OpenFOAM/CGNS/Exodus patch types
    mesh.write("fandisk.su2")
    partition = mesh.partition(4)                          # parts for 4 ranks, NumPy views
    moved = old.transfer_fields(anitet.Fields.read("flow.sol"), mesh)  # fields to new vertices
    new, flow, stats = anitet.adapt(mesh, metric_at_points, fields=flow)  # `anitet adapt`

    lake = anitet.Pslg.read("superior.poly")               # 2D: or Pslg.from_arrays(xy, segments)
    tri = anitet.mesh2d(lake, hsize=0.01)                  # every segment kept whole
    print(tri.counts(), tri.quality())
"""
from ._capi import (BL_CELLS_PRISMS, BL_CELLS_TETS, ERR_BAD_INDEX, ERR_BUFFER_TOO_SMALL, ERR_CANCELLED, ERR_DEGENERATE_TRIANGLE,
                    ERR_DUPLICATE_POINT, ERR_DUPLICATE_TRIANGLE, ERR_EMPTY_INPUT,
                    ERR_FILE_NOT_FOUND, ERR_INCONSISTENT_ORIENTATION, ERR_INTERNAL,
                    ERR_INTERSECTING_SHELLS, ERR_INVALID_ARGUMENT, ERR_INVALID_MESH,
                    ERR_NON_FINITE_COORDINATE, ERR_NON_MANIFOLD_EDGE, ERR_NON_MANIFOLD_VERTEX,
                    ERR_NOT_IMPLEMENTED, ERR_OPEN_BOUNDARY, ERR_OUT_OF_MEMORY, ERR_PARSE,
                    ERR_RECOVERY_FAILED, ERR_SELF_INTERSECTION, ERR_UNSUPPORTED_FORMAT,
                    GEO_ENU, GEO_UTM, LAYERS_FACE_PUSH, LAYERS_PUSH, LOG_DEBUG, LOG_ERROR, LOG_INFO, LOG_WARNING, OK,
                    OPTIONS_VERSION, QUALITY_VERSION, RECOVERY_ALL, RECOVERY_FUZZY, RECOVERY_SPLIT,
                    RUN_STATS_VERSION, VERSION_MAJOR, VERSION_MINOR, VERSION_PATCH,
                    HALO_TET_RECV, HALO_TET_SEND, HALO_VERTEX_RECV, HALO_VERTEX_SEND,
                    PARTITION_INFO_VERSION, PARTITION_OPTIONS_VERSION, TYPE_DOUBLE, TYPE_INT32,
                    TYPE_INT64, MESH2D_OPTIONS_VERSION, PATCH_TYPE_FROM_NAME, PATCH_TYPE_WALL,
                    PATCH_TYPE_INLET, PATCH_TYPE_OUTLET, PATCH_TYPE_FARFIELD, PATCH_TYPE_SYMMETRY,
                    PATCH_TYPE_PATCH, FIELD_KIND_SCALAR, FIELD_KIND_VECTOR, FIELD_KIND_SYM_TENSOR,
                    TENSORS_AUTO, TENSORS_LOG_EUCLIDEAN, TENSORS_LINEAR, ADAPT_OPTIONS_VERSION,
                    ADAPT_STATS_VERSION)
from ._capi import (PART_BOUNDARY_GLOBAL_IDS, PART_BOUNDARY_PATCHES, PART_BOUNDARY_TRIANGLES,  # noqa: F401
                    PART_NEIGHBOURS, PART_POINTS, PART_REGIONS, PART_TET_GLOBAL_IDS, PART_TET_LAYERS,
                    PART_TET_OWNERS, PART_TET_RECV, PART_TET_RECV_OFFSETS, PART_TET_SEND,
                    PART_TET_SEND_OFFSETS, PART_TETS, PART_VERTEX_GLOBAL_IDS, PART_VERTEX_OWNERS,
                    PART_VERTEX_RECV, PART_VERTEX_RECV_OFFSETS, PART_VERTEX_SEND,
                    PART_VERTEX_SEND_OFFSETS)
from ._api import (BL_CELLS, HAVE_NUMPY, PATCH_TYPES, AnitetError, Mesh, Metric, Options, PatchNames, Quality,
                   RunStats, Surface, bl_first_height, build_layers, error_name, mesh_surface,
                   version, version_number, Pslg, Mesh2d, mesh2d)
from ._geo import GeoFrame
from ._partition import Part, Partition, PartitionInfo, partition_mesh
from ._fields import Fields, TransferReport, transfer_fields
from ._adapt import AdaptResult, AdaptStats, adapt

__version__ = "%d.%d.%d" % (VERSION_MAJOR, VERSION_MINOR, VERSION_PATCH)
