/**
 * @file anitet.h
 * The stable C ABI of anitet (C99; also valid C++).
 *
 * Conventions (docs/c-api.md has the long form and an example):
 *  - Opaque handles: anitet_surface, anitet_mesh, anitet_metric. Create with a *_create / *_read
 *    function (the handle is returned through the last argument), free with *_destroy (NULL is
 *    accepted). A handle is used by one thread at a time; distinct handles may be used by
 *    different threads at the same time. The library has no global state.
 *  - Every fallible function returns int: ANITET_OK (0) or a negative ANITET_ERR_* code. The codes
 *    are never renumbered; new ones are only added. anitet_last_error_message() gives the message
 *    of the last call made on the calling thread (thread-local; "" after a success).
 *  - Only fixed-width types cross the boundary: int32_t, int64_t, double, const char*.
 *  - Caller arrays: indices are int32_t with an explicit index_base (0 for C, 1 for Fortran).
 *    Outputs go to caller-owned buffers: ask for the counts, then pass a buffer and its length in
 *    elements; a short buffer gives ANITET_ERR_BUFFER_TOO_SMALL and nothing is written.
 *  - Versioned structs (anitet_options, anitet_quality): the first field is the version; set it
 *    with the *_INIT macro or the *_init function. New fields are only appended, and the library
 *    reads or writes only the fields of the version the caller declares.
 *  - Callbacks take a trailing void* user_data that the library passes through untouched.
 *  - Strings are NUL-terminated UTF-8; paths are file-system paths.
 */
#ifndef ANITET_H
#define ANITET_H

#include <stdint.h>

/* Version of this header; anitet_version() gives the library's at run time. */
#define ANITET_VERSION_MAJOR 0         /**< major version of this header */
#define ANITET_VERSION_MINOR 1         /**< minor version of this header */
#define ANITET_VERSION_PATCH 0         /**< patch level of this header */
#define ANITET_VERSION_STRING "0.1.0"  /**< "major.minor.patch" of this header */
/** major*10000 + minor*100 + patch, comparable with anitet_version_number(). */
#define ANITET_VERSION_NUMBER \
  (ANITET_VERSION_MAJOR * 10000 + ANITET_VERSION_MINOR * 100 + ANITET_VERSION_PATCH)

/** Marks the library's functions: default visibility (or dllexport/dllimport on Windows).
 * Define ANITET_STATIC before including the header to link a static build of the library. */
#if defined(ANITET_STATIC)
#define ANITET_API
#elif defined(_WIN32)
#if defined(ANITET_BUILDING_LIBRARY)
#define ANITET_API __declspec(dllexport)
#else
#define ANITET_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#define ANITET_API __attribute__((visibility("default")))
#else
#define ANITET_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Error codes. Equal to anitet::Error in src/core/status.hpp. Never renumbered.
 * ------------------------------------------------------------------------------------------- */
#define ANITET_OK 0                               /**< the call succeeded */
#define ANITET_ERR_INVALID_ARGUMENT (-1)          /**< NULL handle/pointer, bad size or option */
#define ANITET_ERR_FILE_NOT_FOUND (-2)            /**< cannot open a file to read or write */
#define ANITET_ERR_PARSE (-3)                     /**< malformed or truncated file contents */
#define ANITET_ERR_UNSUPPORTED_FORMAT (-4)        /**< unknown extension or format variant */
#define ANITET_ERR_EMPTY_INPUT (-5)               /**< no points, triangles or tets */
#define ANITET_ERR_BUFFER_TOO_SMALL (-6)          /**< a caller buffer is shorter than needed */
#define ANITET_ERR_NON_FINITE_COORDINATE (-10)    /**< a coordinate is NaN or infinite */
#define ANITET_ERR_DEGENERATE_TRIANGLE (-11)      /**< a triangle of zero area */
#define ANITET_ERR_DUPLICATE_TRIANGLE (-12)       /**< two triangles on the same three vertices */
#define ANITET_ERR_OPEN_BOUNDARY (-13)            /**< an edge of one triangle: not closed */
#define ANITET_ERR_NON_MANIFOLD_EDGE (-14)        /**< an edge of more than two triangles */
#define ANITET_ERR_NON_MANIFOLD_VERTEX (-15)      /**< a vertex whose triangles form 2+ fans */
#define ANITET_ERR_INCONSISTENT_ORIENTATION (-16) /**< mixed orientations, or an inward shell */
#define ANITET_ERR_SELF_INTERSECTION (-17)        /**< two triangles of the surface intersect */
#define ANITET_ERR_INTERSECTING_SHELLS (-18)      /**< two closed shells of the surface intersect */
#define ANITET_ERR_BAD_INDEX (-19)                /**< an index that is not a vertex */
#define ANITET_ERR_NOT_IMPLEMENTED (-30)          /**< not available in this version */
#define ANITET_ERR_CANCELLED (-31)                /**< a progress callback returned non-zero */
#define ANITET_ERR_DUPLICATE_POINT (-32)          /**< two input points at one place */
#define ANITET_ERR_RECOVERY_FAILED (-33)          /**< an input triangle not recovered */
#define ANITET_ERR_INVALID_MESH (-34)             /**< e.g. a face of more than two tets */
#define ANITET_ERR_OUT_OF_MEMORY (-40)            /**< an allocation failed */
#define ANITET_ERR_INTERNAL (-99)                 /**< a bug or an unexpected failure */

/* Log levels passed to anitet_log_fn. */
#define ANITET_LOG_ERROR 0    /**< log level: an error (the call fails) */
#define ANITET_LOG_WARNING 1  /**< log level: a problem that does not stop the call */
#define ANITET_LOG_INFO 2     /**< log level: repairs, stages and their figures */
#define ANITET_LOG_DEBUG 3    /**< log level: details */

/* ---------------------------------------------------------------------------------------------
 * Opaque handles and callbacks.
 * ------------------------------------------------------------------------------------------- */
typedef struct anitet_surface anitet_surface; /**< a triangulated closed surface (the input) */
typedef struct anitet_mesh anitet_mesh;       /**< a tetrahedral mesh (read, given or meshed) */
typedef struct anitet_metric anitet_metric;   /**< a metric (sizing) field */
typedef struct anitet_geo_frame anitet_geo_frame; /**< a local Cartesian frame on WGS84 */

/** Progress: `fraction` in [0, 1] of the running call's work done, on entering the named stage
 * ("validate" for anitet_surface_validate, 0 then 1), and as "refine" and "optimize" go (the
 * same name again, the fraction growing). Return 0 to continue, non-zero to cancel: the running
 * call then returns ANITET_ERR_CANCELLED and creates nothing. Stages are not interrupted in the
 * middle: cancelling takes effect at the next stage, and the callback is not called again.
 * The mesher's stages: "validate" (0), "slide patches" (with options->bl_slide_patches),
 * "layers", "recovery", "coupling", "sizing", "refine", "optimize", "done" (1); later versions
 * may add stages, so do not rely on the list. */
typedef int (*anitet_progress_fn)(double fraction, const char* stage, void* user_data);
/** Log: one message (valid only during the call) at an ANITET_LOG_* level. */
typedef void (*anitet_log_fn)(int32_t level, const char* message, void* user_data);
/** Analytic metric at (x, y, z): fill m with the symmetric positive-definite tensor in the order
 * xx xy yy xz yz zz (Medit's); return 0, or non-zero when the point cannot be evaluated. */
typedef int (*anitet_metric_fn)(double x, double y, double z, double m[6], void* user_data);

/* ---------------------------------------------------------------------------------------------
 * Versioned options.
 * ------------------------------------------------------------------------------------------- */
/** The newest version of anitet_options this header declares. */
#define ANITET_OPTIONS_VERSION 5

/** Values of anitet_options.layer_scheme (version 2). */
#define ANITET_LAYERS_PUSH 0       /**< prism layers by vertex pushes only (the default) */
#define ANITET_LAYERS_FACE_PUSH 1  /**< the paper's two steps: face tets, then vertex pushes */

/** Values of anitet_options.recovery (version 3): stage 2's strategies. */
#define ANITET_RECOVERY_ALL 0    /**< split constraints, then the fuzzy-face ones when it fails */
#define ANITET_RECOVERY_SPLIT 1  /**< split constraints only (fast, every decision combinatorial) */
#define ANITET_RECOVERY_FUZZY 2  /**< the fuzzy-face strategies only */

/** Values of anitet_options.bl_cells (version 4): the cells the boundary layer is written as. */
#define ANITET_BL_CELLS_TETS 0    /**< each prism as the 3 tets the pipeline keeps (the default) */
#define ANITET_BL_CELLS_PRISMS 1  /**< each prism as one prism cell (anitet_mesh_get_prisms) */

/** Options of the validation and the mesher, a versioned struct: set it with
 * ANITET_OPTIONS_INIT or anitet_options_init(), then change fields. */
typedef struct anitet_options {
  int32_t version;                   /**< ANITET_OPTIONS_VERSION; 1 for callers of anitet 0.1 */
  int32_t num_threads;               /**< 0: the library's default */
  int32_t merge_duplicate_vertices;  /**< validation repair: merge equal vertices (default 1) */
  int32_t orient_shells;             /**< validation repair: flip inward shells (default 1) */
  int32_t check_self_intersections;  /**< exact self-intersection search (default 1) */
  int32_t reserved0;                 /**< keep 0 (alignment; may gain a meaning later) */
  anitet_progress_fn progress;       /**< may be NULL */
  void* progress_user_data;          /**< passed to progress untouched */
  anitet_log_fn log;                 /**< may be NULL */
  void* log_user_data;               /**< passed to log untouched */
  /* Version 2 (read only when version >= 2; a version 1 caller gets the defaults): */
  int32_t layers;                    /**< advancing-front layers of stage 1, >= 1 (default 1);
                                        not boundary layers (those are bl_*, version 3) */
  int32_t layer_scheme;              /**< ANITET_LAYERS_PUSH (default) or ANITET_LAYERS_FACE_PUSH */
  double recovery_max_seconds;       /**< time budget of the boundary recovery; 0: default (20) */
  int32_t refine;                    /**< 1: refine to the sizes (default), 0: skip the stage */
  int32_t optimize;                  /**< 1: optimize the quality (default), 0: skip the stage */
  double size_scale;                 /**< every target edge length times this (> 0; default 1;
                                        2 = a mesh twice as coarse) */
  /* Version 3 (read only when version >= 3; older callers get the defaults): the options of
   * `anitet mesh`. */
  double attempts_seconds;           /**< wall time for stages 1-2 and the coupling, run again
                                        with other layer counts and recovery strategies when the
                                        front is not recovered; no attempt starts after it
                                        (default 240; 0: no limit) */
  int32_t retry_layer_counts;        /**< 1 (default): those retries try other layer counts;
                                        0: the given count only */
  int32_t recovery;                  /**< ANITET_RECOVERY_ALL (default), _SPLIT or _FUZZY */
  double hmin;                       /**< smallest target edge length, absolute (0: no bound) */
  double hmax;                       /**< largest target edge length, absolute (0: no bound) */
  double hgrad;                      /**< gradation, > 1 (0: none, the default): the size grows
                                        by at most this factor per unit of metric length */
  double max_tets;                   /**< refuse to refine (INVALID_ARGUMENT) when the sizing
                                        field asks for more tets than this, estimated before
                                        refinement (0: no limit, the default) */
  int32_t anisotropic_cycles;        /**< with an anisotropic field, at most this many more
                                        rounds of refinement then optimization (0-10, default
                                        2); a round runs only after an optimization that
                                        raised the share of edges in range by 4.5 points or
                                        more, and they stop after a round that raised it by
                                        less than 1 point */
  int32_t bl_num_patches;            /**< boundary layer: the number of labels in bl_patches
                                        (0, the default: no boundary layer) */
  const int32_t* bl_patches;         /**< the surface's patch labels that are walls, each a
                                        whole shell; read during the call only (may be NULL
                                        when bl_num_patches is 0) */
  double bl_first_height;            /**< the first layer's height h0 (> 0 with walls) */
  double bl_growth;                  /**< growth ratio r >= 1: layer i is h0 r^i (default 1.2) */
  int32_t bl_layers;                 /**< number of boundary layers n, 1..1000 (default 10) */
  int32_t bl_sizing;                 /**< 1: the interior's sizes continue the layers' heights
                                        (an anisotropic metric near the walls; default 0) */
  int32_t push_tasks_min_vertices;   /**< stage 1 pushes a layer of at least this many front
                                        vertices on two tasks (the same mesh either way;
                                        0: one by one; default 2000) */
  int32_t bl_mitre;                  /**< 1 (`anitet mesh --bl-mitre`; needs walls,
                                        bl_num_patches > 0): at the walls' edges and corners
                                        each column is lengthened by 1/cos of its angle to the
                                        farthest wall normal there (at most 2), so that the
                                        layers keep their thickness across every wall; 0 (the
                                        default): a right-angled edge's layers are 0.71 as thick
                                        across each wall as along the column. In version 3's
                                        reserved1 slot (same layout, 0 the default and what old
                                        callers were told to keep): no new version was needed */
  /* Version 4 (read only when version >= 4; older callers get the defaults): */
  int32_t bl_num_slide_patches;      /**< boundary layer: the number of labels in
                                        bl_slide_patches (default 0: none); > 0 needs walls
                                        (bl_num_patches > 0) */
  int32_t bl_cells;                  /**< how anitet_mesh_write writes the boundary layer:
                                        ANITET_BL_CELLS_TETS (default: 3 tets per prism, every
                                        format) or ANITET_BL_CELLS_PRISMS (`anitet mesh
                                        --bl-cells prisms`: one prism cell each, .vtu and
                                        OpenFOAM polyMesh only; needs walls, bl_num_patches > 0;
                                        anitet_mesher_run only). In version 4's reserved2 slot
                                        (same layout, 0 the default): version 4 was not released
                                        before it, so no version 5 was needed */
  const int32_t* bl_slide_patches;   /**< the patch labels the walls meet that the layers'
                                        columns may slide along (`anitet mesh
                                        --bl-slide-patches`): a pipe's inlet and outlet, a
                                        symmetry plane. Each is triangulated again inside the
                                        band the layers cover, so the mesh's boundary triangles
                                        with these labels differ from the surface's (the others
                                        stay as given); planar where the layers slide. Read
                                        during the call only (may be NULL when
                                        bl_num_slide_patches is 0) */
  /* Version 5 (read only when version >= 5; older callers get the defaults): */
  double bl_sizing_growth;           /**< with bl_sizing (`anitet mesh --bl-sizing-growth`):
                                        above the layers' top the normal size grows at this
                                        rate instead of the layers' growth, so the interior
                                        reaches its own sizes in fewer tets (the first tets
                                        there still get the next layer's height; 1.3 is a
                                        good start). 0 (the default): the layers' growth
                                        bl_growth. Otherwise finite and >= bl_growth, and
                                        bl_sizing must be 1 (INVALID_ARGUMENT if not) */
  /* Version 6 and later append fields here. */
} anitet_options;

/** Initializer of an anitet_options of version ANITET_OPTIONS_VERSION with the defaults. */
#define ANITET_OPTIONS_INIT                                                                     \
  { ANITET_OPTIONS_VERSION, 0, 1, 1, 1, 0, 0, 0, 0, 0, 1, ANITET_LAYERS_PUSH, 0.0, 1, 1, 1.0, \
    240.0, 1, ANITET_RECOVERY_ALL, 0.0, 0.0, 0.0, 0.0, 2, 0, 0, 0.0, 1.2, 10, 0, 2000, 0, 0, 0, 0, \
    0.0 }

/** Fills the fields of `version` (1 .. ANITET_OPTIONS_VERSION) of *options with their defaults
 * and sets options->version; a struct of an older version is not written past its end.
 * Errors: INVALID_ARGUMENT (NULL options, unknown version). */
ANITET_API int anitet_options_init(anitet_options* options, int32_t version);

/* ---------------------------------------------------------------------------------------------
 * Library information and errors.
 * ------------------------------------------------------------------------------------------- */

/** The library's version, "major.minor.patch" (static storage). */
ANITET_API const char* anitet_version(void);
/** The library's version as major*10000 + minor*100 + patch. */
ANITET_API int32_t anitet_version_number(void);
/** Message of the last int-returning call on this thread; "" after a success. The pointer stays
 * valid until the next anitet_* call on the same thread. Never NULL. */
ANITET_API const char* anitet_last_error_message(void);
/** Stable short name of an error code ("open_boundary"); "unknown_error" for other values. */
ANITET_API const char* anitet_error_name(int32_t code);

/* ---------------------------------------------------------------------------------------------
 * Surfaces.
 * ------------------------------------------------------------------------------------------- */

/** A surface from caller arrays, copied: xyz (3*num_points), tri (3*num_triangles, vertex
 * indices counter-clockwise seen from outside, counted from index_base), patch (num_triangles
 * labels, or NULL for all 0). Errors: INVALID_ARGUMENT (NULL pointer, negative count,
 * index_base not 0 or 1), EMPTY_INPUT (no point or no triangle), BAD_INDEX. */
ANITET_API int anitet_surface_create(const double* xyz, int64_t num_points, const int32_t* tri,
                                     int64_t num_triangles, const int32_t* patch,
                                     int32_t index_base, anitet_surface** out);
/** A surface from a file (.off .obj .stl .ply .mesh .meshb .msh by extension).
 * Errors: INVALID_ARGUMENT, FILE_NOT_FOUND, PARSE, UNSUPPORTED_FORMAT, EMPTY_INPUT, BAD_INDEX. */
ANITET_API int anitet_surface_read(const char* path, anitet_surface** out);
/** Frees a surface; NULL is accepted. */
ANITET_API void anitet_surface_destroy(anitet_surface* surface);

/** Numbers of points and triangles (after repairs when it was validated). */
ANITET_API int anitet_surface_get_counts(const anitet_surface* surface, int64_t* num_points,
                                         int64_t* num_triangles);
/** Fills xyz (xyz_len >= 3*num_points). */
ANITET_API int anitet_surface_get_points(const anitet_surface* surface, double* xyz,
                                         int64_t xyz_len);
/** Fills tri (tri_len >= 3*num_triangles) with indices counted from index_base. */
ANITET_API int anitet_surface_get_triangles(const anitet_surface* surface, int32_t* tri,
                                            int64_t tri_len, int32_t index_base);
/** Fills patch (patch_len >= num_triangles). */
ANITET_API int anitet_surface_get_patches(const anitet_surface* surface, int32_t* patch,
                                          int64_t patch_len);

/** Validates the surface and applies the safe repairs (merging equal vertices, flipping inward
 * shells) to it; options may be NULL for the defaults. Returns ANITET_OK for a clean closed
 * oriented surface, else the first problem's code (OPEN_BOUNDARY, SELF_INTERSECTION, ...) with
 * a message naming the elements. The report is kept in the surface for the queries below.
 * Calls options->progress ("validate", 0 then 1) and options->log (repairs, problems). */
ANITET_API int anitet_surface_validate(anitet_surface* surface, const anitet_options* options);
/** Instances of the problem `code` found by the last validation (0 when absent). Errors:
 * INVALID_ARGUMENT (NULL, or the surface was not validated). */
ANITET_API int anitet_surface_problem_count(const anitet_surface* surface, int32_t code,
                                            int64_t* count);
/** The last validation report as JSON text into buf (buf_len bytes, NUL included); *needed gets
 * the size needed. buf == NULL with buf_len == 0 asks for the size only and succeeds. */
ANITET_API int anitet_surface_validation_json(const anitet_surface* surface, char* buf,
                                              int64_t buf_len, int64_t* needed);

/* ---------------------------------------------------------------------------------------------
 * Metric fields.
 * ------------------------------------------------------------------------------------------- */

/** The isotropic metric of edge length `size` (> 0, finite) everywhere. */
ANITET_API int anitet_metric_create_uniform(double size, anitet_metric** out);
/** An analytic metric: callback is called (possibly from several threads at once) with
 * user_data, which must stay valid while the metric is in use. */
ANITET_API int anitet_metric_create_analytic(anitet_metric_fn callback, void* user_data,
                                             anitet_metric** out);
/** A metric read from a file, chosen by the extension of `path` (case-insensitive):
 *  - ".vdb": an OpenVDB file; background_mesh_path must be NULL. It holds either one scalar grid
 *    "size" (the edge length h, interpolated trilinearly in h; the metric is I/h^2), or the six
 *    scalar grids "log_metric_xx" "log_metric_xy" "log_metric_yy" "log_metric_xz"
 *    "log_metric_yz" "log_metric_zz" (the components of log M), or the six grids "metric_xx" ..
 *    "metric_zz" (M itself), tried in that order; float or double grids, one uniform linear
 *    transform shared by all. Tensors are interpolated in log space (log-Euclidean, always
 *    positive definite). Points outside the grids' active box take the value at the box's edge.
 *  - ".sol" or ".solb": an ASCII Medit .sol (MeshVersionFormatted 1 or 2, Dimension 3) or a
 *    binary GMF .solb (libMeshb versions 1 to 4, either byte order), with one SolAtVertices
 *    field of type 1, a size per vertex, or type 3, the tensor xx xy yy xz yz zz per vertex, on
 *    the tetrahedral mesh at background_mesh_path (.mesh .meshb .msh .node/.ele .vtu, as
 *    anitet_mesh_read), one value set per vertex of it, in its vertex order. Inside a tet sizes
 *    are interpolated linearly (barycentric), tensors in log space; points outside the mesh take
 *    the value at the closest point of its boundary. A Dimension 2 .sol (sizes, or xx xy yy
 *    tensors) on a 2D Medit .mesh background (triangles) gives a 2D field, for
 *    anitet_mesh2d_run.
 *
 * Units: sizes are edge lengths in the coordinates' unit; a tensor M measures a vector e as
 * sqrt(e^T M e), so M = I/h^2 for the size h (unit: 1/length^2). The file is read and closed by
 * the call: the metric keeps its own copy (of the grids, or of the background mesh and values).
 *
 * Errors: INVALID_ARGUMENT (NULL path or out; a .sol without background_mesh_path or a .vdb
 * with one; a .sol whose number of values is not the background's number of vertices; a size
 * <= 0 or a tensor that is not positive definite), FILE_NOT_FOUND (path or background missing or
 * unreadable), PARSE (not a .vdb, malformed .sol or mesh), UNSUPPORTED_FORMAT (another
 * extension; a .sol field of another type; a .vdb without the grids above or with a non-uniform
 * transform), EMPTY_INPUT (a background without tets, a .sol without a field), BAD_INDEX,
 * INVALID_MESH (a background face shared by more than two tets). */
ANITET_API int anitet_metric_read(const char* path, const char* background_mesh_path,
                                  anitet_metric** out);
/** A metric given by values at the points of a background tetrahedral mesh: `components` values
 * per point of `background`, in the order of its points (anitet_mesh_get_points; no index is
 * passed, so there is no index_base), num_values == components * (number of points) doubles in
 * all. components 1: the size h (> 0, an edge length in the coordinates' unit) per point;
 * components 6: the tensor xx xy yy xz yz zz (symmetric positive definite, 1/length^2) per
 * point. Interpolation and points outside the mesh: as for a .sol in anitet_metric_read.
 * The values and the background's points and tets are copied: `background` and `values` may be
 * destroyed or changed after the call. The background's own per-vertex metric is not used.
 * Errors: INVALID_ARGUMENT (NULL background, values or out; components not 1 or 6; num_values
 * not components times the number of points; a value not finite, a size <= 0, a tensor that is
 * not positive definite: the message names the 0-based point), EMPTY_INPUT (no tet),
 * INVALID_MESH (a face shared by more than two tets). */
ANITET_API int anitet_metric_create_from_points(const anitet_mesh* background,
                                                const double* values, int64_t num_values,
                                                int32_t components, anitet_metric** out);
/** Frees a metric; NULL is accepted. The meshes made with it keep their per-vertex tensors. */
ANITET_API void anitet_metric_destroy(anitet_metric* metric);
/** The tensor at (x, y, z) into m[6] (xx xy yy xz yz zz). Errors: INVALID_ARGUMENT (NULL
 * metric or m; a coordinate that is not finite, for a metric read from a file or created from
 * points), and the analytic callback's failure as INVALID_ARGUMENT naming its return value. */
ANITET_API int anitet_metric_evaluate(const anitet_metric* metric, double x, double y, double z,
                                      double m[6]);
/** The sizing field anitet_mesher_run follows when it is given no metric: an OpenVDB grid over
 * the surface's box built from its triangles' sizes, bounded and graded by options->hmin, hmax
 * and hgrad (options may be NULL: none). The surface is validated first, with the options'
 * repairs, as anitet_mesher_run does (`surface` itself is not changed). Give it to
 * anitet_mesher_run to mesh to it, to anitet_metric_write to look at it (`anitet mesh
 * --write-sizing`), or to anitet_mesh_sample_metric. Errors: INVALID_ARGUMENT (NULL surface or
 * out, bad options), the validation's codes, OUT_OF_MEMORY. */
ANITET_API int anitet_metric_create_surface_sizing(const anitet_surface* surface,
                                                   const anitet_options* options,
                                                   anitet_metric** out);
/** A .sol or .solb metric (as in anitet_metric_read) on a background mesh in memory, e.g. one
 * moved to a local frame by anitet_mesh_to_local, or the mesh of the last adaptation pass. The
 * background's points and tets are copied. Errors: as anitet_metric_read. */
ANITET_API int anitet_metric_read_on_mesh(const char* path, const anitet_mesh* background,
                                          anitet_metric** out);
/** Writes `metric` as OpenVDB grids (.vdb, the path's extension), which anitet_metric_read and
 * `anitet mesh --metric` read back (`anitet mesh --write-sizing`): a grid metric (read from a
 * .vdb, or made by anitet_metric_create_surface_sizing) as it is, any other sampled on a lattice
 * over the bounding box of the surface `box_of` (required then, else it may be NULL), spaced at
 * its mean edge length (coarser when the box would pass 2^24 points). Errors: INVALID_ARGUMENT (NULL metric or path; box_of
 * NULL when it is needed; a failing metric callback), UNSUPPORTED_FORMAT (not .vdb),
 * FILE_NOT_FOUND (cannot create the file). */
ANITET_API int anitet_metric_write(const anitet_metric* metric, const anitet_surface* box_of,
                                   const char* path);

/* ---------------------------------------------------------------------------------------------
 * Meshing.
 * ------------------------------------------------------------------------------------------- */

/** Meshes the inside of `surface` into a new mesh *out (*out is NULL after any error). The call
 * validates a copy of the surface with the options' repairs (`surface` itself is not changed),
 * then runs the stages: advancing-front layers (with a boundary layer first on the walls
 * options->bl_patches names, its columns sliding along the patches options->bl_slide_patches
 * names where a wall meets them), Delaunay with conforming boundary recovery, coupling, refinement
 * to the sizes and quality optimization (options may skip the last two), every stage in one
 * task arena of options->num_threads threads (0: the library's default, all cores).
 * Sizes: refinement and optimization follow `metric` when not NULL (evaluated wherever they
 * need it; the mesh then carries its tensors at the vertices, see anitet_mesh_get_metric), else
 * a sizing field built from the surface's triangles; options->hmin, hmax and hgrad bound and
 * grade it, then options->size_scale scales it. The front layers follow the surface's edge
 * lengths. What the run did is kept with the mesh (anitet_mesh_get_run_stats,
 * anitet_mesh_run_json), including what it did otherwise than asked (notices).
 * The mesh: the (repaired) surface's points first and in order, positive tets, a region label
 * per body, the surface's triangles as boundary triangles with their patch labels (with slide
 * patches: the triangles of the other patches first, in order, then the slide patches' new
 * triangulation; the layers' new points on them follow the surface's points). Same inputs
 * and options, same mesh, bit for bit. options may be NULL for the defaults; options->progress
 * is called on entering each stage and may cancel; options->log gets the repairs and problems
 * of the validation and one line per stage.
 * Errors: INVALID_ARGUMENT (NULL surface or out, bad options version or value, a wall label no
 * triangle has, a wall meeting a patch that is not a slide patch (the message names the label
 * to add to bl_slide_patches), a label both a wall and a slide patch, more tets than
 * options->max_tets; a metric callback that fails or returns a tensor that is not positive
 * definite: the message names the point), the validation's codes (OPEN_BOUNDARY,
 * SELF_INTERSECTION, ...), NOT_IMPLEMENTED (a slide patch not planar where the layers slide on
 * it, a column sliding along two edges), CANCELLED, RECOVERY_FAILED, INTERNAL (a stage failed),
 * OUT_OF_MEMORY. */
ANITET_API int anitet_mesher_run(const anitet_surface* surface, const anitet_metric* metric,
                                 const anitet_options* options, anitet_mesh** out);
/** Stage 1 alone (`anitet mesh --stop-after layers`), to look at the layers: validates a copy of
 * the surface as anitet_mesher_run does, builds the advancing-front layers (options->layers,
 * layer_scheme, push_tasks_min_vertices and the boundary layer's bl_* fields, slide patches
 * included; the other fields of version 2 and 3 are not used) at the surface's own sizes, audits
 * them, and returns T1 in *out: the surface's points first and in order (those of no triangle
 * dropped), the surface's triangles as boundary triangles under their labels (the slide
 * patches' as anitet_mesher_run gives them), the new front S1's triangles under one
 * more label (the largest label + 1, at least 1), the boundary layer's tets in region 1 and the
 * others in region 0. anitet_mesh_get_run_stats gives layers_used and the boundary layer's
 * figures measured on T1; anitet_mesh_run_json the stage's figures. Errors: as
 * anitet_mesher_run (INTERNAL when the layers fail their audit: a bug). */
ANITET_API int anitet_layers_run(const anitet_surface* surface, const anitet_options* options,
                                 anitet_mesh** out);
/** The first boundary-layer height h0 for a target y+ (`anitet mesh --bl-yplus`), from the
 * flat-plate estimate: Cf = 0.026 Re^(-1/7), h0 = y+ L / (Re sqrt(Cf / 2)), with the Reynolds
 * number Re = U L / nu and the reference length L (in the coordinates' unit). Errors:
 * INVALID_ARGUMENT (NULL h0; an argument not finite or <= 0). */
ANITET_API int anitet_bl_first_height(double yplus, double reynolds, double ref_length, double* h0);

/* ---------------------------------------------------------------------------------------------
 * Volume meshes.
 * ------------------------------------------------------------------------------------------- */

/** A mesh from caller arrays, copied: xyz (3*num_points), tets (4*num_tets, positively oriented),
 * regions (num_tets, or NULL for 0), boundary triangles bnd_tri (3*num_boundary_triangles, NULL
 * when 0) with bnd_patch (num_boundary_triangles, or NULL for 0); indices counted from
 * index_base. Errors: INVALID_ARGUMENT, EMPTY_INPUT (no tet), BAD_INDEX. */
ANITET_API int anitet_mesh_create(const double* xyz, int64_t num_points, const int32_t* tets,
                                  int64_t num_tets, const int32_t* regions,
                                  const int32_t* bnd_tri, int64_t num_boundary_triangles,
                                  const int32_t* bnd_patch, int32_t index_base,
                                  anitet_mesh** out);
/** A mesh from a file (.mesh .meshb .msh .node/.ele .vtu by extension). */
ANITET_API int anitet_mesh_read(const char* path, anitet_mesh** out);
/** Frees a mesh; NULL is accepted. */
ANITET_API void anitet_mesh_destroy(anitet_mesh* mesh);
/** Writes by extension: .mesh (Medit), .meshb (binary Medit, GMF), .msh (Gmsh 4.1), .vtu, or
 *  for solvers .su2, .cgns, .exo/.e (Exodus II) and a path ending in polyMesh (an OpenFOAM
 *  polyMesh directory). The boundary patches carry the names of anitet_mesh_set_patch_name
 *  (others patch<label>) and, in OpenFOAM, CGNS and Exodus II, the types of
 *  anitet_mesh_set_patch_type. Errors: INVALID_ARGUMENT (NULL; two labels with one name;
 *  boundary triangles that are not faces of the tets), UNSUPPORTED_FORMAT (another extension;
 *  a mesh with prism cells, anitet_mesh_get_prism_count > 0, to a format other than .vtu and
 *  polyMesh: the message says so),
 *  FILE_NOT_FOUND (cannot create the file), NOT_IMPLEMENTED for .cgns or .exo when the library
 *  was built without CGNS or Exodus II. Nothing is written after an error. */
ANITET_API int anitet_mesh_write(const anitet_mesh* mesh, const char* path);
/** Writes the per-vertex metric as a Medit .sol (a binary GMF .solb when the path ends in .solb).
 *  INVALID_ARGUMENT when the mesh has none. */
ANITET_API int anitet_mesh_write_metric(const anitet_mesh* mesh, const char* path);
/** Writes the boundary layer's columns as CSV (`anitet mesh --bl-columns`, the same bytes): a
 *  header line "x,y,z,layers,first_height,total_height,normal_share,patches", then one line per
 *  wall vertex in the surface's order: its point, the layers its column reaches, its first and
 *  total height (0 when it reaches none), its normal share (the least cosine between the column
 *  and its wall triangles' normals: 1 on a flat wall, about 0.71 at a right-angled edge) and the
 *  labels of the patches it is on, space-separated. For a mesh of anitet_mesher_run or
 *  anitet_layers_run with walls (options->bl_num_patches > 0). Errors: INVALID_ARGUMENT (NULL;
 *  a mesh not made by a run, or made without walls: the message says which), FILE_NOT_FOUND
 *  (cannot create the file). */
ANITET_API int anitet_mesh_write_bl_columns(const anitet_mesh* mesh, const char* path);

/** Counts; any output pointer may be NULL. */
ANITET_API int anitet_mesh_get_counts(const anitet_mesh* mesh, int64_t* num_points,
                                      int64_t* num_tets, int64_t* num_boundary_triangles);
/** Fills xyz (xyz_len >= 3*num_points). */
ANITET_API int anitet_mesh_get_points(const anitet_mesh* mesh, double* xyz, int64_t xyz_len);
/** Fills tets (tets_len >= 4*num_tets) with indices counted from index_base. */
ANITET_API int anitet_mesh_get_tets(const anitet_mesh* mesh, int32_t* tets, int64_t tets_len,
                                    int32_t index_base);
/** Fills regions (regions_len >= num_tets). */
ANITET_API int anitet_mesh_get_regions(const anitet_mesh* mesh, int32_t* regions,
                                       int64_t regions_len);
/** Fills tri (tri_len >= 3*num_boundary_triangles) with indices counted from index_base. */
ANITET_API int anitet_mesh_get_boundary_triangles(const anitet_mesh* mesh, int32_t* tri,
                                                  int64_t tri_len, int32_t index_base);
/** Fills patch (patch_len >= num_boundary_triangles). */
ANITET_API int anitet_mesh_get_boundary_patches(const anitet_mesh* mesh, int32_t* patch,
                                                int64_t patch_len);
/* Prism cells (a mesh of anitet_mesher_run with options->bl_cells ANITET_BL_CELLS_PRISMS): the
 * mesh keeps every tet (anitet_mesh_get_tets, the quality, partition and field transfer work on
 * them); anitet_mesh_write writes each boundary-layer prism's 3 tets as one prism cell instead,
 * the other tets as tets (a BL tet with no exact prism, where a column stopped, stays a tet; the
 * ABI makes no pyramid cells, so the prisms of that layer beside it stay tets too). */
/** The number of prism cells into *num_prisms: 0 for a mesh without (bl_cells TETS, read or
 * created from arrays). */
ANITET_API int anitet_mesh_get_prism_count(const anitet_mesh* mesh, int64_t* num_prisms);
/** Fills prisms (prisms_len >= 6*num_prisms) with indices counted from index_base: per prism the
 * wall-side triangle a b c, then the triangle its columns reach, a' b' c' (edges a-a', b-b',
 * c-c'); a b c is counter-clockwise seen from a' b' c', so the tet a b c a' is positive (VTK's
 * wedge is a c b a' c' b'). */
ANITET_API int anitet_mesh_get_prisms(const anitet_mesh* mesh, int32_t* prisms, int64_t prisms_len,
                                      int32_t index_base);
/** Fills tet_prism (tet_prism_len >= num_tets): per tet of anitet_mesh_get_tets, the prism it is
 * one of the 3 tets of, counted from index_base, or -1 for a tet written as a tet. A prism's
 * region is its tets'. */
ANITET_API int anitet_mesh_get_tet_prisms(const anitet_mesh* mesh, int32_t* tet_prism,
                                          int64_t tet_prism_len, int32_t index_base);
/** Values per vertex of the mesh's metric: 0 (none), 1 (size) or 6 (xx xy yy xz yz zz). */
ANITET_API int anitet_mesh_get_metric_components(const anitet_mesh* mesh, int32_t* components);
/** Fills values (values_len >= components*num_points). */
ANITET_API int anitet_mesh_get_metric(const anitet_mesh* mesh, double* values,
                                      int64_t values_len);
/** Names the boundary patch `label` (1-32 letters, digits or '_', starting with a letter) in the
 * files anitet_mesh_write writes: SU2 markers, OpenFOAM patches, CGNS and Exodus names, Gmsh
 * physical names (unnamed labels are patch<label>). NULL name removes the name. The name is
 * copied. Errors: INVALID_ARGUMENT (NULL mesh, an invalid name, no boundary triangle with the
 * label). */
ANITET_API int anitet_mesh_set_patch_name(anitet_mesh* mesh, int32_t label, const char* name);

/* The boundary condition a patch stands for (anitet_mesh_set_patch_type, `anitet mesh
 * --patch-types`), as the solver formats type their patches:
 *   type      OpenFOAM (boundary file)            CGNS               Exodus II side-set property
 *   WALL      wall                                BCWall             WALL
 *   INLET     patch                               BCInflow           INLET
 *   OUTLET    patch                               BCOutflow          OUTLET
 *   FARFIELD  patch                               BCFarfield         FARFIELD
 *   SYMMETRY  symmetryPlane (symmetry if curved)  BCSymmetryPlane    SYMMETRY
 *   PATCH     patch                               BCGeneral          PATCH
 * The other formats have no patch types. A label without a type set gets the one its name
 * implies: a name containing "inlet" or "inflow" (any case) an inlet, "outlet" or "outflow" an
 * outlet, "farfield" a farfield, "symmetry" a symmetry plane; any other name (patch<label> too)
 * a wall. */
#define ANITET_PATCH_TYPE_FROM_NAME (-1) /**< no type set: the one the patch's name implies */
#define ANITET_PATCH_TYPE_WALL 0         /**< a wall (OpenFOAM wall, CGNS BCWall) */
#define ANITET_PATCH_TYPE_INLET 1        /**< an inlet (OpenFOAM patch, CGNS BCInflow) */
#define ANITET_PATCH_TYPE_OUTLET 2       /**< an outlet (OpenFOAM patch, CGNS BCOutflow) */
#define ANITET_PATCH_TYPE_FARFIELD 3     /**< a far field (OpenFOAM patch, CGNS BCFarfield) */
#define ANITET_PATCH_TYPE_SYMMETRY 4     /**< a symmetry plane (OpenFOAM symmetryPlane) */
#define ANITET_PATCH_TYPE_PATCH 5        /**< any other open boundary (CGNS BCGeneral) */

/** Sets the type (ANITET_PATCH_TYPE_*) of the boundary patch `label` in the files
 * anitet_mesh_write writes; ANITET_PATCH_TYPE_FROM_NAME removes it (the name then implies the
 * type). Errors: INVALID_ARGUMENT (NULL mesh, an unknown type, no boundary triangle with the
 * label). */
ANITET_API int anitet_mesh_set_patch_type(anitet_mesh* mesh, int32_t label, int32_t type);
/** The type anitet_mesh_write gives the patch `label` into *type: the one set, else the one its
 * name (given or patch<label>) implies; never ANITET_PATCH_TYPE_FROM_NAME. Errors:
 * INVALID_ARGUMENT (NULL, no boundary triangle with the label). */
ANITET_API int anitet_mesh_get_patch_type(const anitet_mesh* mesh, int32_t label, int32_t* type);

/** Replaces the per-vertex metric: components 1 (size, > 0) or 6 (xx xy yy xz yz zz) values per
 * point, values_len == components*num_points, all finite; components 0 removes it (values may
 * be NULL). Errors: INVALID_ARGUMENT. */
ANITET_API int anitet_mesh_set_metric(anitet_mesh* mesh, const double* values, int64_t values_len,
                                      int32_t components);
/** Sets the mesh's per-vertex metric to `metric`'s values at its points, as `anitet mesh
 * --write-metric` samples the sizing field: components 1 (sizes) when every tensor is
 * isotropic, else 6. anitet_mesh_write_metric then writes it as a .sol/.solb. Errors:
 * INVALID_ARGUMENT (NULL mesh or metric; a failing metric callback, naming the point: the mesh's
 * metric is then unchanged). */
ANITET_API int anitet_mesh_sample_metric(anitet_mesh* mesh, const anitet_metric* metric);

/* ---------------------------------------------------------------------------------------------
 * Per-vertex fields (a solver's solution, a metric) and their transfer from one mesh to another
 * (docs/gmf-and-fields.md has the method). An anitet_fields holds any number of fields given at
 * the vertices of some mesh, vertex by vertex: one record per vertex holding every field's
 * components in field order, as a Medit .sol / GMF .solb SolAtVertices block holds them.
 * ------------------------------------------------------------------------------------------- */
typedef struct anitet_fields anitet_fields; /**< per-vertex fields (values at a mesh's vertices) */

/* Kinds of a field (the GMF type codes of a .sol/.solb). */
#define ANITET_FIELD_KIND_SCALAR 1     /**< 1 component */
#define ANITET_FIELD_KIND_VECTOR 2     /**< 3 components: x y z */
#define ANITET_FIELD_KIND_SYM_TENSOR 3 /**< 6 components: xx xy yy xz yz zz (Medit's order) */

/* How anitet_mesh_transfer_fields interpolates the symmetric tensor fields. */
#define ANITET_TENSORS_AUTO 0          /**< in log space when every tensor of the field is
                                            positive definite (a metric), else linearly */
#define ANITET_TENSORS_LOG_EUCLIDEAN 1 /**< in log space (exp of the weighted mean of log M:
                                            always SPD); a tensor that is not SPD is an error */
#define ANITET_TENSORS_LINEAR 2        /**< component by component (stresses) */

/** Fields from caller arrays, copied: num_fields kinds (ANITET_FIELD_KIND_*) and num_values
 * values, a whole number of records (the sum of the kinds' components per vertex). Errors:
 * INVALID_ARGUMENT (NULL out, kinds or values; num_fields < 1; an unknown kind; num_values
 * negative or not a whole number of records), EMPTY_INPUT (no value). */
ANITET_API int anitet_fields_create(const int32_t* kinds, int32_t num_fields, const double* values,
                                    int64_t num_values, anitet_fields** out);
/** Fields from a Medit .sol (ASCII, Dimension 3) or a GMF .solb (binary, libMeshb versions 1 to
 * 4, either byte order), by extension: its SolAtVertices block. Errors: INVALID_ARGUMENT,
 * FILE_NOT_FOUND, PARSE (malformed or truncated: the message names the line or the keyword),
 * UNSUPPORTED_FORMAT (another extension, Dimension 2, a full-matrix field), EMPTY_INPUT (no
 * SolAtVertices). */
ANITET_API int anitet_fields_read(const char* path, anitet_fields** out);
/** Writes the fields as a Medit .sol (every double written so that it reads back to the same
 * bits) or a GMF .solb, by extension. Errors: INVALID_ARGUMENT (NULL), UNSUPPORTED_FORMAT,
 * FILE_NOT_FOUND (cannot create the file). */
ANITET_API int anitet_fields_write(const anitet_fields* fields, const char* path);
/** Frees fields; NULL is accepted. */
ANITET_API void anitet_fields_destroy(anitet_fields* fields);
/** The number of fields, the components per vertex (the record size) and the number of
 * vertices (records); any output pointer may be NULL. */
ANITET_API int anitet_fields_get_counts(const anitet_fields* fields, int32_t* num_fields,
                                        int32_t* record_size, int64_t* num_vertices);
/** Fills kinds (kinds_len >= num_fields) with the fields' ANITET_FIELD_KIND_* values. */
ANITET_API int anitet_fields_get_kinds(const anitet_fields* fields, int32_t* kinds,
                                       int64_t kinds_len);
/** Fills values (values_len >= record_size * num_vertices) with the records, vertex by vertex. */
ANITET_API int anitet_fields_get_values(const anitet_fields* fields, double* values,
                                        int64_t values_len);
/** Lends the values without a copy: *data points to *count doubles (the records, vertex by
 * vertex), valid and unchanged while `fields` lives. Read only. Errors: INVALID_ARGUMENT (NULL). */
ANITET_API int anitet_fields_get_data(const anitet_fields* fields, const double** data,
                                      int64_t* count);

/** Carries `fields`, given at the vertices of `from` (one record per vertex, in its point order),
 * to the vertices of `to`: a new anitet_fields *out (NULL after any error) with the same kinds
 * and one record per point of `to`. Each point of `to` is located in `from`'s tets and every
 * field interpolated with its barycentric weights: linearly for scalars and vectors (a linear
 * field is carried exactly, to rounding), symmetric tensors as `tensors` says
 * (ANITET_TENSORS_AUTO, _LOG_EUCLIDEAN or _LINEAR). A point outside `from` (a boundary that
 * moved onto the curved geometry) takes the value at the closest point of `from`'s boundary;
 * such points are counted (anitet_fields_get_transfer_report). `from`, `fields` and `to` are
 * only read. Runs on every core (anitet_mesh_transfer_fields_ext takes a thread count); the
 * result does not depend on the number of threads. Errors: INVALID_ARGUMENT (NULL; an
 * unknown `tensors`; fields without one record per point of `from`, "a field of another mesh";
 * a tensor that is not SPD with ANITET_TENSORS_LOG_EUCLIDEAN, naming its vertex; a point of `to`
 * that is not finite), EMPTY_INPUT (`from` has no tet), BAD_INDEX, INVALID_MESH (a face of
 * `from` shared by more than two tets), OUT_OF_MEMORY. */
ANITET_API int anitet_mesh_transfer_fields(const anitet_mesh* from, const anitet_fields* fields,
                                           const anitet_mesh* to, int32_t tensors,
                                           anitet_fields** out);
/** anitet_mesh_transfer_fields in a task arena of num_threads threads (0: the library's
 * default, all cores; the same result on any number). Errors: as anitet_mesh_transfer_fields,
 * and INVALID_ARGUMENT for a negative num_threads. */
ANITET_API int anitet_mesh_transfer_fields_ext(const anitet_mesh* from, const anitet_fields* fields,
                                               const anitet_mesh* to, int32_t tensors,
                                               int32_t num_threads, anitet_fields** out);
/** What the transfer that made `fields` found (any output pointer may be NULL): the points
 * outside the old mesh and their largest distance to it, and per field (log_euclidean_len >=
 * num_fields, or NULL) 1 when it was interpolated in log space, else 0. Errors:
 * INVALID_ARGUMENT (NULL fields; fields not made by a transfer: anitet_mesh_transfer_fields,
 * _ext, or anitet_adapt's out_fields), BUFFER_TOO_SMALL. */
ANITET_API int anitet_fields_get_transfer_report(const anitet_fields* fields, int64_t* outside,
                                                 double* max_outside_distance,
                                                 int32_t* log_euclidean,
                                                 int64_t log_euclidean_len);

/* ---------------------------------------------------------------------------------------------
 * What a meshing run did (meshes made by anitet_mesher_run).
 * ------------------------------------------------------------------------------------------- */
/** The newest version of anitet_run_stats this header declares. */
#define ANITET_RUN_STATS_VERSION 3

/** Figures of the run that made a mesh (anitet_mesh_get_run_stats), a versioned struct: set its
 * version with ANITET_RUN_STATS_INIT. Everything else the run measured (each stage's time and
 * tets, the notices' sentences, the boundary layer's columns) is in anitet_mesh_run_json. */
typedef struct anitet_run_stats {
  int32_t version;                 /**< ANITET_RUN_STATS_VERSION (3; 1 or 2 for those
                                      versions' fields only), set by the caller */
  int32_t layers_used;             /**< stage-1 front layers of the attempt that worked */
  int32_t layers_retries;          /**< attempts before it (other layer counts or strategies) */
  int32_t recovery_strategy;       /**< ANITET_RECOVERY_SPLIT or _FUZZY: the one that worked
                                      (0: no recovery ran, anitet_layers_run) */
  int32_t refine_passes;           /**< refinement passes (0: not run) */
  int32_t refine_stopped_at_pass_cap; /**< 1: refinement ran out of passes before settling */
  int32_t anisotropic_cycles;      /**< extra refine + optimize rounds run */
  int32_t num_notices;             /**< what was done otherwise than asked (see the JSON) */
  int64_t vertices;                /**< of the mesh */
  int64_t tets;                    /**< of the mesh */
  int64_t steiner_on_front_edges;  /**< stage 2's points on the front's edges */
  int64_t steiner_on_front_faces;  /**< stage 2's points inside the front's faces */
  int64_t refine_splits;           /**< edges split */
  int64_t refine_collapses;        /**< edges collapsed */
  int64_t flat_tets_left;          /**< tets left flat to double rounding */
  int64_t metric_not_spd;          /**< vertices whose metric was measured as Euclidean */
  double seconds;                  /**< the whole run */
  double estimated_tets;           /**< the refinement's tets estimated before it (0: none) */
  double edges_in_range;           /**< share of edges of metric length in [1/sqrt2, sqrt2] */
  double metric_radius_ratio_mean; /**< in the metric, anisotropic fields only (else 0) */
  double metric_radius_ratio_min;  /**< in the metric, anisotropic fields only (else 0) */
  int32_t bl_layers;               /**< boundary layers built (0: no boundary layer) */
  int32_t reserved0;               /**< 0 */
  int64_t bl_wall_vertices;        /**< input vertices on the walls */
  int64_t bl_full_columns;         /**< wall vertices whose column reaches every layer */
  int64_t bl_nominal_columns;      /**< full columns with every height within 10% of h0 r^i */
  int64_t bl_reduced_vertices;     /**< wall vertices with a reduced layer */
  int64_t bl_tets;                 /**< tets of the boundary layer */
  double bl_first_height_min;      /**< over the full columns */
  double bl_first_height_mean;     /**< over the full columns */
  double bl_first_height_max;      /**< over the full columns */
  double bl_growth_mean;           /**< the columns' mean growth ratio */
  double bl_max_height_error;      /**< max |h / (h0 r^i) - 1| over the nominal columns */
  /* Version 2: the slide patches (options->bl_slide_patches; 0 without them). */
  int64_t slide_junction_columns;  /**< wall vertices on a slide patch: columns that slide */
  int64_t slide_lowered_columns;   /**< of those, columns lowered below 90% of h0 r^i */
  int64_t slide_triangles_added;   /**< the slide patches' triangles in the mesh minus the
                                      surface's (the band the layers cover re-triangulated) */
  /* Version 3: the prism cells (options->bl_cells ANITET_BL_CELLS_PRISMS; 0 otherwise). */
  int64_t bl_prisms;               /**< prism cells made, 3 boundary-layer tets each
                                      (anitet_mesh_get_prism_count) */
  int64_t bl_prism_tets_left;      /**< boundary-layer tets left as tets (no exact prism: a
                                      column that stopped in a layer, a partial push) */
  /* Version 4 and later append fields here. */
} anitet_run_stats;

/** Initializer of an anitet_run_stats of version ANITET_RUN_STATS_VERSION, all figures 0. */
#define ANITET_RUN_STATS_INIT \
  { ANITET_RUN_STATS_VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, \
    0, 0, 0, 0, 0, 0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0, 0, 0, 0 }

/** The figures of the run that made `mesh`. out->version must be 1 .. ANITET_RUN_STATS_VERSION;
 * the fields of that version are filled. Errors: INVALID_ARGUMENT (NULL, an unknown version, a
 * mesh not made by anitet_mesher_run: read or created from arrays). */
ANITET_API int anitet_mesh_get_run_stats(const anitet_mesh* mesh, anitet_run_stats* out);
/** The run's whole report as JSON text into buf (buf_len bytes, NUL included), as `anitet mesh
 * --json` gives it without the quality part: stages (name, seconds, tets), layers, recovery,
 * coupling, refine, optimize, metric_quality, boundary_layer (with columns_reaching), notices
 * (kind, message), seconds. *needed gets the size needed; buf == NULL with buf_len == 0 asks for
 * the size only and succeeds. Errors: as anitet_mesh_get_run_stats, BUFFER_TOO_SMALL. */
ANITET_API int anitet_mesh_run_json(const anitet_mesh* mesh, char* buf, int64_t buf_len,
                                    int64_t* needed);

/* ---------------------------------------------------------------------------------------------
 * Adaptation (`anitet adapt`; docs/adapt.md has the method): a volume mesh and a metric in, a new
 * mesh whose edges have unit length in the metric out, by local operations on the given mesh
 * (edges longer than sqrt 2 in the metric split, shorter than 1/sqrt 2 collapsed, edge and face
 * swaps, vertex moves), the surface adapted with the volume on its smooth reconstruction (ridges
 * and corners kept) unless keep_surface is set. The output is the input of the next pass: a
 * solver's loop is solve, metric from the solution, anitet_adapt, carry the fields, repeat.
 * ------------------------------------------------------------------------------------------- */
/** The newest version of anitet_adapt_options this header declares. */
#define ANITET_ADAPT_OPTIONS_VERSION 1

/** Options of anitet_adapt and anitet_adapt_to_metric (`anitet adapt`'s), a versioned struct:
 * set it with ANITET_ADAPT_OPTIONS_INIT or anitet_adapt_options_init(), then change fields. */
typedef struct anitet_adapt_options {
  int32_t version;             /**< ANITET_ADAPT_OPTIONS_VERSION */
  int32_t num_threads;         /**< the task arena of the call (0: the library's default, all
                                    cores): the fields' transfer and the measures run in it; the
                                    adaptation's sweeps are serial (the same mesh on any number) */
  int32_t keep_surface;        /**< 1: keep the input's boundary triangles exactly, no point
                                    added, moved or removed on the surface (`--keep-surface`);
                                    0 (default): the surface is adapted too */
  int32_t max_cycles;          /**< refinement/coarsening cycles at most, 0..1000 (default 30;
                                    `--max-cycles`); they stop earlier once a cycle changes
                                    under 0.1% of the tets or the changes stop falling */
  double ridge_angle_deg;      /**< boundary edges whose faces meet at a dihedral angle over
                                    this (degrees, 0..180; default 45) are ridges
                                    (`--ridge-angle`) */
  int32_t optimize_cycles;     /**< swap and smoothing sweeps after the cycles, 0..100
                                    (default 3) */
  int32_t tensors;             /**< how `fields`' symmetric tensors are carried to the new mesh:
                                    ANITET_TENSORS_AUTO (default), _LOG_EUCLIDEAN or _LINEAR */
  anitet_progress_fn progress; /**< may be NULL: called between sweeps with the stage
                                    ("adapt, cycle 3", "optimize, sweep 1", "transfer",
                                    "measure", "done") and a rough fraction; non-zero cancels */
  void* progress_user_data;    /**< passed to progress untouched */
  anitet_log_fn log;           /**< may be NULL: one ANITET_LOG_INFO line per sweep
                                    (operations, tets, time; `anitet adapt -v`) */
  void* log_user_data;         /**< passed to log untouched */
  /* Version 2 and later append fields here. */
} anitet_adapt_options;

/** Initializer of an anitet_adapt_options of version ANITET_ADAPT_OPTIONS_VERSION with the
 * defaults. */
#define ANITET_ADAPT_OPTIONS_INIT \
  { ANITET_ADAPT_OPTIONS_VERSION, 0, 0, 30, 45.0, 3, ANITET_TENSORS_AUTO, 0, 0, 0, 0 }

/** Fills *options with the defaults of `version` (1 .. ANITET_ADAPT_OPTIONS_VERSION).
 * Errors: INVALID_ARGUMENT (NULL options, unknown version). */
ANITET_API int anitet_adapt_options_init(anitet_adapt_options* options, int32_t version);

/** The newest version of anitet_adapt_stats this header declares. */
#define ANITET_ADAPT_STATS_VERSION 1

/** What an adaptation did and the UGAWG measures of its output in the metric (`anitet adapt
 * --json`), a versioned struct: set its version with ANITET_ADAPT_STATS_INIT. Edge lengths are
 * UGAWG's l = (la - lb) / ln(la / lb) in the metric at the ends; the mean ratio of a tet is
 * taken in the metric of its finest corner (1: the regular tet of the metric). */
typedef struct anitet_adapt_stats {
  int32_t version;              /**< ANITET_ADAPT_STATS_VERSION (1), set by the caller */
  int32_t cycles;               /**< refinement/coarsening cycles run */
  int64_t vertices_in;          /**< of the input mesh */
  int64_t tets_in;              /**< of the input mesh */
  int64_t boundary_triangles_in; /**< of the input mesh */
  int64_t vertices;             /**< of the new mesh */
  int64_t tets;                 /**< of the new mesh */
  int64_t boundary_triangles;   /**< of the new mesh */
  int64_t ridge_edges;          /**< ridge edges found in the input's surface */
  int64_t corners;              /**< corners found in the input's surface */
  int64_t splits;               /**< edges split (on the surface included) */
  int64_t surface_splits;       /**< of those, on the surface */
  int64_t collapses;            /**< edges collapsed */
  int64_t surface_collapses;    /**< of those, on the surface */
  int64_t swaps;                /**< edge and face swaps */
  int64_t surface_swaps;        /**< of those, on the surface */
  int64_t moves;                /**< vertex moves */
  int64_t surface_moves;        /**< of those, on the surface */
  int64_t splits_refused;       /**< splits not made (a tet would have been inverted) */
  int64_t collapses_refused;    /**< collapses not made */
  int64_t edges;                /**< edges of the new mesh */
  double edges_in_range;        /**< share of edges of metric length in [1/sqrt2, sqrt2] */
  double edges_shorter;         /**< share below 1/sqrt2 */
  double edges_longer;          /**< share above sqrt2 */
  double edge_length_min;       /**< smallest metric edge length */
  double edge_length_mean;      /**< mean metric edge length */
  double edge_length_max;       /**< largest metric edge length */
  double mean_ratio_min;        /**< smallest tet mean ratio in the metric */
  double mean_ratio_mean;       /**< mean tet mean ratio in the metric */
  double seconds;               /**< the whole call */
  double seconds_adapt;         /**< the adaptation (setup, sweeps, output) */
  double seconds_split;         /**< of which the splits */
  double seconds_collapse;      /**< of which the collapses */
  double seconds_swap;          /**< of which the swaps */
  double seconds_smooth;        /**< of which the moves */
  double seconds_transfer;      /**< carrying the fields (0 without) */
  double seconds_measure;       /**< the measures above */
  /* Version 2 and later append fields here. */
} anitet_adapt_stats;

/** Initializer of an anitet_adapt_stats of version ANITET_ADAPT_STATS_VERSION, all figures 0. */
#define ANITET_ADAPT_STATS_INIT \
  { ANITET_ADAPT_STATS_VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, \
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 }

/** Adapts `mesh` to the metric given at its points: `metric` holds `components` values per point
 * of the mesh, in its point order (no index is passed, so there is no index_base), metric_len ==
 * components * (number of points): components 1, the size h (> 0, an edge length) per point;
 * components 6, the tensor xx xy yy xz yz zz (symmetric positive definite, 1/length^2) per point,
 * as anitet_metric_create_from_points and anitet_mesh_set_metric take them. New points take the
 * metric interpolated in the input mesh (log-Euclidean).
 *
 * Outputs: *out, a new mesh (the caller's, freed with anitet_mesh_destroy; NULL after any error):
 * positive tets with their regions, boundary triangles with their patch labels, the input's
 * patch names and types, and the metric at its points (anitet_mesh_get_metric, 6 components;
 * anitet_mesh_write_metric is `--write-metric`); it has no run stats and no prism cells (the
 * input's prisms, if any, are adapted as their tets). `fields` (may be NULL: then out_fields
 * must be NULL too) holds per-vertex fields of `mesh` (one record per point) carried to the new
 * mesh's points into *out_fields (the caller's; anitet_fields_get_transfer_report applies), as
 * anitet_mesh_transfer_fields carries them (`--field`). `stats` (may be NULL) gets the
 * figures of its version. `mesh`, `metric` and `fields` are only read. options may be NULL for
 * the defaults. The same inputs and options give the same mesh, bit for bit, on any number of
 * threads. Threads: see options->num_threads; the callbacks are called on the calling thread.
 *
 * Errors: INVALID_ARGUMENT (NULL mesh, metric or out; fields given without out_fields or
 * out_fields without fields; components not 1 or 6; metric_len not components times the points;
 * a value not finite, a size <= 0 or a tensor that is not positive definite: the message names
 * the 0-based point; an options version outside 1 .. ANITET_ADAPT_OPTIONS_VERSION or an option
 * out of its range; a stats version outside 1 .. ANITET_ADAPT_STATS_VERSION; fields without one
 * record per point; an inverted or flat tet, named), EMPTY_INPUT (no tet), INVALID_MESH (a face
 * of three tets or more), CANCELLED, INTERNAL, OUT_OF_MEMORY. Nothing is returned after an
 * error. */
ANITET_API int anitet_adapt(const anitet_mesh* mesh, const double* metric, int64_t metric_len,
                            int32_t components, const anitet_fields* fields,
                            const anitet_adapt_options* options, anitet_mesh** out,
                            anitet_fields** out_fields, anitet_adapt_stats* stats);
/** anitet_adapt to a metric handle evaluated wherever a point goes (exactly at every new point,
 * not interpolated): an analytic callback (anitet_metric_create_analytic, called on the calling
 * thread), a .vdb or .sol read with anitet_metric_read, a uniform size. The new mesh carries the
 * metric's values at its points. Errors: as anitet_adapt (a NULL metric; a callback that fails
 * or returns a tensor that is not positive definite: INVALID_ARGUMENT naming the point). */
ANITET_API int anitet_adapt_to_metric(const anitet_mesh* mesh, const anitet_metric* metric,
                                      const anitet_fields* fields,
                                      const anitet_adapt_options* options, anitet_mesh** out,
                                      anitet_fields** out_fields, anitet_adapt_stats* stats);

/* ---------------------------------------------------------------------------------------------
 * Quality report.
 * ------------------------------------------------------------------------------------------- */
/** The newest version of anitet_quality this header declares. */
#define ANITET_QUALITY_VERSION 1

/** Quality figures of a tetrahedral mesh (anitet_mesh_quality), a versioned struct: set its
 * version with ANITET_QUALITY_INIT. */
typedef struct anitet_quality {
  int32_t version;              /**< ANITET_QUALITY_VERSION (1), set by the caller */
  int32_t valid;                /**< 1: no non-positive tet, no face shared by more than 2 tets */
  int32_t boundary_constrained; /**< 1: every input triangle is a boundary face, no Steiner point
                                   on the boundary (0 when no input surface was given) */
  int32_t reserved0;            /**< 0 */
  int64_t vertices;             /**< number of vertices */
  int64_t tets;                 /**< number of tets */
  int64_t nonpositive_tets;     /**< exact orient3d <= 0 */
  double radius_ratio_mean;     /**< 3 * inradius / circumradius: 1 regular, 0 flat */
  double radius_ratio_min;      /**< smallest radius ratio */
  double mean_ratio_mean;       /**< 12 (3|V|)^(2/3) / sum of squared edge lengths */
  double mean_ratio_min;        /**< smallest mean ratio */
  double min_dihedral_deg;      /**< smallest dihedral angle, in degrees */
  double max_dihedral_deg;      /**< largest dihedral angle, in degrees */
  double good_fraction;         /**< share of tets with radius ratio > 0.4 */
  double bad_fraction;          /**< share of tets with radius ratio < 0.1 */
  /* Version 2 and later append fields here. */
} anitet_quality;

/** Initializer of an anitet_quality of version ANITET_QUALITY_VERSION, all figures 0. */
#define ANITET_QUALITY_INIT { ANITET_QUALITY_VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 }

/** The quality of `mesh`, against `input` (may be NULL) for boundary_constrained. out->version
 * must be 1 .. ANITET_QUALITY_VERSION; the fields of that version are filled.
 * Errors: INVALID_ARGUMENT, BAD_INDEX, NON_FINITE_COORDINATE. */
ANITET_API int anitet_mesh_quality(const anitet_mesh* mesh, const anitet_surface* input,
                                   anitet_quality* out);
/** The full quality report as JSON text into buf (buf_len bytes, NUL included); *needed gets the
 * size needed. buf == NULL with buf_len == 0 asks for the size only and succeeds. The text is
 * the same for the same inputs (its "seconds" field is 0), so a size query then a fill agree. */
ANITET_API int anitet_mesh_quality_json(const anitet_mesh* mesh, const anitet_surface* input,
                                        char* buf, int64_t buf_len, int64_t* needed);

/* ---------------------------------------------------------------------------------------------
 * Geographic coordinates (`anitet mesh --geodetic`): points given as longitude, latitude (degrees)
 * and ellipsoidal height (metres) on WGS84, in that order (x = lon, y = lat, z = h), are meshed
 * in a local Cartesian frame in metres: move the surface (and a background mesh) to the frame,
 * mesh, and move the mesh back if wanted. Conversions use GeographicLib.
 * ------------------------------------------------------------------------------------------- */
/** Values of the frame kind. */
#define ANITET_GEO_ENU 0 /**< east-north-up tangent frame at the origin (exact round trip) */
#define ANITET_GEO_UTM 1 /**< UTM easting/northing of the origin's zone, the height as z */

/** A frame of `kind` at the origin (lat, lon in degrees, height in metres). Errors:
 * INVALID_ARGUMENT (NULL out, unknown kind, a value not finite, |lat| > 90, |lon| > 540). */
ANITET_API int anitet_geo_frame_create(int32_t kind, double lat, double lon, double height,
                                       anitet_geo_frame** out);
/** A frame of `kind` at the centre of the bounding box of the surface's points (lon, lat, h;
 * longitudes unwrapped around the first point's, for data across the antimeridian), as
 * `anitet mesh --geodetic` without --origin. Errors: INVALID_ARGUMENT (NULL, unknown kind, a
 * point out of range), EMPTY_INPUT (no point). */
ANITET_API int anitet_geo_frame_create_centred(int32_t kind, const anitet_surface* surface,
                                               anitet_geo_frame** out);
/** Frees a frame; NULL is accepted. */
ANITET_API void anitet_geo_frame_destroy(anitet_geo_frame* frame);
/** The frame's origin (lat, lon, h) and, for UTM, its zone (1-60) and hemisphere (1: north);
 * any output pointer may be NULL. Errors: INVALID_ARGUMENT (NULL frame). */
ANITET_API int anitet_geo_frame_get(const anitet_geo_frame* frame, double* lat, double* lon,
                                    double* height, int32_t* utm_zone, int32_t* utm_north);
/** Moves the surface's points from (lon, lat, h) to the frame's x, y, z in metres, in place.
 * Errors: INVALID_ARGUMENT (NULL; a point out of range, named: then no point is moved). A
 * surface moved this way must be validated again (anitet_surface_validate) before its report is
 * read; anitet_mesher_run validates by itself. */
ANITET_API int anitet_surface_to_local(anitet_surface* surface, const anitet_geo_frame* frame);
/** The same for a mesh's points (a background mesh of a .sol metric, say; its metric values are
 * not converted). Errors: as anitet_surface_to_local. */
ANITET_API int anitet_mesh_to_local(anitet_mesh* mesh, const anitet_geo_frame* frame);
/** Moves the mesh's points from the frame back to (lon, lat, h), longitudes in [-180, 180]
 * (`anitet mesh --geodetic-output`). A round trip through the frame loses rounding, so when
 * `geodetic_surface` is not NULL it must be the surface, before anitet_surface_to_local, that
 * the mesh was made from by anitet_mesher_run: the mesh's points that are its points get its
 * coordinates back exactly. Errors: INVALID_ARGUMENT (NULL mesh or frame; a point out of range;
 * geodetic_surface given for a mesh not made by anitet_mesher_run, or whose run had another
 * number of surface points, e.g. after a repair merged some). */
ANITET_API int anitet_mesh_to_geodetic(anitet_mesh* mesh, const anitet_geo_frame* frame,
                                       const anitet_surface* geodetic_surface);

/* ---------------------------------------------------------------------------------------------
 * Partitions: a mesh in parts for the ranks of a solver (docs/partitions.md has an example).
 *
 * anitet_mesh_partition cuts a mesh with METIS (k-way, on the dual graph: tets sharing a face)
 * and builds every part: what one rank of a finite-volume or finite-element solver holds. A
 * part is self-contained: its local vertices and tets, their global ids (int64_t, the vertex
 * and tet numbers of the whole mesh), the owner part of each, its ghost layers, its boundary
 * triangles, and for each neighbour part the halo lists in an agreed order, so that an exchange
 * needs no negotiation between the ranks. anitet_mesh_scatter (anitet_mpi.h) sends each MPI
 * rank its part.
 *
 * Orders and definitions (the same in every part, so two ranks agree without talking):
 *  - A vertex belongs to (is owned by) the lowest-numbered part among the parts of its tets;
 *    a boundary triangle to the lowest part among the parts of the tets it is a face of.
 *  - Ghost layer 1 of a part: every tet of another part that shares a vertex with one of its
 *    own tets; layer k: every tet not yet held that shares a vertex with layer k - 1. Every
 *    ghost tet is an own tet of the part named as its owner.
 *  - Local vertices: the part's own vertices first, then the others; each group by ascending
 *    global id. Local tets: own tets first, then ghost layer 1, 2, ...; each group by ascending
 *    global id. Local boundary triangles: those that are a face of a local tet, own first, each
 *    group by ascending global id (the index among the mesh's boundary triangles).
 *  - Neighbours: the parts this part sends to or receives from, ascending. The four halo lists
 *    (ANITET_HALO_*) hold local ids grouped by neighbour, each group by ascending global id:
 *    RECV from q: the local vertices (tets) owned by q; SEND to q: the own vertices (tets) that
 *    q holds. Part p's SEND list to q and part q's RECV list from p name the same global ids in
 *    the same order: a halo update sends the values at SEND[q] and writes what q sent into
 *    RECV[q]; an assembly (a sum over the parts) goes the other way.
 *  - Part numbers (owners, neighbours, a part's index) are 0-based whatever the index_base: they
 *    are MPI ranks. Global ids and local ids follow the index_base of the call.
 *
 * A mesh in pieces that share no face (two bodies; regions meeting at an edge or a vertex only)
 * is partitioned as a whole: parts are balanced over all the tets, a part may hold tets of
 * several pieces and a piece may be split. Ghost layers follow shared vertices, so they cross
 * where pieces touch at a vertex or an edge and stop at a gap. A vertex in no tet is in no part.
 * Debian's METIS has 32-bit indices: a mesh whose dual graph has more than 2^31 - 1 adjacency
 * entries (about 5 * 10^8 tets) gives ANITET_ERR_NOT_IMPLEMENTED.
 *
 * Ownership: anitet_mesh_partition returns an anitet_partition the caller frees with
 * anitet_partition_destroy; its parts (anitet_partition_get_part) are borrowed and live as long
 * as it does. A part from anitet_part_deserialize or anitet_mesh_scatter is the caller's, freed
 * with anitet_part_destroy. Threads: a partition and its parts are not changed after they are
 * made, so every function taking a const pointer below may be called from several threads at
 * once on the same handle. The METIS call inside anitet_mesh_partition is serialized within the
 * process (METIS swaps process-wide signal handlers while it runs).
 * ------------------------------------------------------------------------------------------- */
typedef struct anitet_partition anitet_partition; /**< a mesh cut into parts (all of them) */
typedef struct anitet_part anitet_part;           /**< one part: what one rank holds */

/** The newest version of anitet_partition_options this header declares. */
#define ANITET_PARTITION_OPTIONS_VERSION 1

/** Options of anitet_mesh_partition, a versioned struct: set it with
 * ANITET_PARTITION_OPTIONS_INIT or anitet_partition_options_init(), then change fields. */
typedef struct anitet_partition_options {
  int32_t version;            /**< ANITET_PARTITION_OPTIONS_VERSION */
  int32_t num_threads;        /**< threads building the parts (METIS's cut is serial); 0: the
                                   library's default */
  int32_t ghost_layers;       /**< layers of ghost tets, >= 0 (default 1) */
  int32_t reserved0;          /**< keep 0 (alignment; may gain a meaning later) */
  double imbalance;           /**< heaviest part <= (1 + imbalance) * mean part, in (0, 1]
                                   (default 0.03) */
  const double* tet_weights;  /**< NULL (every tet weighs 1) or one weight per tet of the mesh,
                                   finite, >= 0, one > 0; read during the call only. METIS gets
                                   them rounded to integers relative to the largest (1000 steps,
                                   fewer past 2 million tets so that their sum stays below
                                   2^31; a positive weight at least 1) */
  int64_t num_tet_weights;    /**< the length of tet_weights (the mesh's tets), 0 with NULL */
  /* Version 2 and later append fields here. */
} anitet_partition_options;

/** Initializer of an anitet_partition_options of version ANITET_PARTITION_OPTIONS_VERSION with
 * the defaults. */
#define ANITET_PARTITION_OPTIONS_INIT { ANITET_PARTITION_OPTIONS_VERSION, 0, 1, 0, 0.03, 0, 0 }

/** Fills the fields of `version` (1 .. ANITET_PARTITION_OPTIONS_VERSION) of *options with their
 * defaults and sets options->version; a struct of an older version is not written past its end.
 * Errors: INVALID_ARGUMENT (NULL options, unknown version). */
ANITET_API int anitet_partition_options_init(anitet_partition_options* options, int32_t version);

/** The newest version of anitet_partition_info this header declares. */
#define ANITET_PARTITION_INFO_VERSION 1

/** The figures of a partition (anitet_partition_get_info), a versioned struct: set its version
 * with ANITET_PARTITION_INFO_INIT. */
typedef struct anitet_partition_info {
  int32_t version;             /**< ANITET_PARTITION_INFO_VERSION (1), set by the caller */
  int32_t num_parts;           /**< the parts asked for */
  int32_t ghost_layers;        /**< the ghost layers asked for */
  int32_t empty_parts;         /**< parts without an own tet (possible only when the parts are
                                    nearly as many as the tets) */
  int64_t num_tets;            /**< the mesh's tets */
  int64_t edge_cut;            /**< faces between tets of different parts (the cut edges of the
                                    dual graph) */
  int64_t interface_vertices;  /**< vertices whose tets are in more than one part */
  double imbalance;            /**< heaviest part's weight / mean part weight - 1 */
  double total_weight;         /**< the sum of the tets' weights (the tet count without weights) */
  double max_part_weight;      /**< the heaviest part's weight */
  /* Version 2 and later append fields here. */
} anitet_partition_info;

/** Initializer of an anitet_partition_info of version ANITET_PARTITION_INFO_VERSION, all 0. */
#define ANITET_PARTITION_INFO_INIT { ANITET_PARTITION_INFO_VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0 }

/* The halo lists of a part (anitet_part_get_halo). */
#define ANITET_HALO_VERTEX_SEND 0  /**< per neighbour q: own vertices that q holds */
#define ANITET_HALO_VERTEX_RECV 1  /**< per neighbour q: local vertices owned by q */
#define ANITET_HALO_TET_SEND 2     /**< per neighbour q: own tets that q holds as ghosts */
#define ANITET_HALO_TET_RECV 3     /**< per neighbour q: ghost tets owned by q */

/* Element types of the arrays of anitet_part_get_array. */
#define ANITET_TYPE_INT32 1   /**< int32_t elements */
#define ANITET_TYPE_INT64 2   /**< int64_t elements */
#define ANITET_TYPE_DOUBLE 3  /**< double elements */

/* The arrays of a part that anitet_part_get_array lends (element type; 0-based ids). */
#define ANITET_PART_POINTS 0                 /**< double, 3 per local vertex */
#define ANITET_PART_VERTEX_GLOBAL_IDS 1      /**< int64_t per local vertex */
#define ANITET_PART_VERTEX_OWNERS 2          /**< int32_t per local vertex: its owner part */
#define ANITET_PART_TETS 3                   /**< int32_t, 4 local vertices per local tet */
#define ANITET_PART_TET_GLOBAL_IDS 4         /**< int64_t per local tet */
#define ANITET_PART_TET_OWNERS 5             /**< int32_t per local tet: its owner part */
#define ANITET_PART_TET_LAYERS 6             /**< int32_t per local tet: 0 own, k ghost layer k */
#define ANITET_PART_REGIONS 7                /**< int32_t per local tet */
#define ANITET_PART_BOUNDARY_TRIANGLES 8     /**< int32_t, 3 local vertices per triangle */
#define ANITET_PART_BOUNDARY_PATCHES 9       /**< int32_t per boundary triangle */
#define ANITET_PART_BOUNDARY_GLOBAL_IDS 10   /**< int64_t per boundary triangle */
#define ANITET_PART_NEIGHBOURS 11            /**< int32_t per neighbour part, ascending */
#define ANITET_PART_VERTEX_SEND_OFFSETS 12   /**< int64_t, neighbours + 1: the vertex send list
                                                  of neighbour i is at [offsets[i], offsets[i+1]) */
#define ANITET_PART_VERTEX_SEND 13           /**< int32_t local vertex ids */
#define ANITET_PART_VERTEX_RECV_OFFSETS 14   /**< int64_t, neighbours + 1 */
#define ANITET_PART_VERTEX_RECV 15           /**< int32_t local vertex ids */
#define ANITET_PART_TET_SEND_OFFSETS 16      /**< int64_t, neighbours + 1 */
#define ANITET_PART_TET_SEND 17              /**< int32_t local tet ids */
#define ANITET_PART_TET_RECV_OFFSETS 18      /**< int64_t, neighbours + 1 */
#define ANITET_PART_TET_RECV 19              /**< int32_t local tet ids */

/** Cuts `mesh` into num_parts parts (1 .. the mesh's tets) and builds each part (*out is NULL
 * after any error). options may be NULL for the defaults. The same mesh and options give the
 * same partition, whatever num_threads. `mesh` is only read, and may be destroyed afterwards.
 * Errors: INVALID_ARGUMENT (NULL mesh or out; num_parts < 1 or more than the tets; an options
 * version outside 1 .. ANITET_PARTITION_OPTIONS_VERSION; ghost_layers < 0, num_threads < 0,
 * imbalance outside (0, 1], num_tet_weights not the tet count, a weight not finite or < 0, all
 * weights 0), EMPTY_INPUT (a mesh without tets), BAD_INDEX, INVALID_MESH (a face of more than
 * two tets), NOT_IMPLEMENTED (a mesh too large for METIS's 32-bit indices, or a part with
 * 2^31 - 1 local vertices or tets), OUT_OF_MEMORY. */
ANITET_API int anitet_mesh_partition(const anitet_mesh* mesh, int32_t num_parts,
                                     const anitet_partition_options* options,
                                     anitet_partition** out);
/** Frees a partition and the parts it lends; NULL is accepted. */
ANITET_API void anitet_partition_destroy(anitet_partition* partition);
/** The partition's figures into *info; info->version must be 1 .. ANITET_PARTITION_INFO_VERSION
 * and the fields of that version are filled. Errors: INVALID_ARGUMENT. */
ANITET_API int anitet_partition_get_info(const anitet_partition* partition,
                                         anitet_partition_info* info);
/** Fills parts (parts_len >= the mesh's tets) with the part of each tet of the mesh. */
ANITET_API int anitet_partition_get_tet_parts(const anitet_partition* partition, int32_t* parts,
                                              int64_t parts_len);
/** Lends part `index` (0 .. num_parts - 1) in *part: valid until the partition is destroyed; do
 * not pass it to anitet_part_destroy (that call ignores it). Errors: INVALID_ARGUMENT. */
ANITET_API int anitet_partition_get_part(const anitet_partition* partition, int32_t index,
                                         const anitet_part** part);

/** Frees a part the caller owns (from anitet_part_deserialize or anitet_mesh_scatter); NULL and
 * parts lent by a partition are accepted and left alone. */
ANITET_API void anitet_part_destroy(anitet_part* part);
/** The part's number (0-based: its rank), the number of parts, its neighbours and its ghost
 * layers; any output pointer may be NULL. */
ANITET_API int anitet_part_get_index(const anitet_part* part, int32_t* index, int32_t* num_parts,
                                     int32_t* num_neighbours, int32_t* ghost_layers);
/** Counts of local vertices, tets and boundary triangles and of the own ones among them (which
 * come first); any output pointer may be NULL. */
ANITET_API int anitet_part_get_counts(const anitet_part* part, int64_t* num_vertices,
                                      int64_t* num_owned_vertices, int64_t* num_tets,
                                      int64_t* num_owned_tets, int64_t* num_boundary_triangles,
                                      int64_t* num_owned_boundary_triangles);
/** Fills xyz (xyz_len >= 3*num_vertices) with the local vertices' coordinates. */
ANITET_API int anitet_part_get_points(const anitet_part* part, double* xyz, int64_t xyz_len);
/** Fills tets (tets_len >= 4*num_tets) with local vertex ids counted from index_base, each tet
 * oriented as in the mesh. */
ANITET_API int anitet_part_get_tets(const anitet_part* part, int32_t* tets, int64_t tets_len,
                                    int32_t index_base);
/** Fills regions (regions_len >= num_tets) with the local tets' region labels. */
ANITET_API int anitet_part_get_regions(const anitet_part* part, int32_t* regions,
                                       int64_t regions_len);
/** Fills ids (ids_len >= num_vertices) with the local vertices' vertex numbers in the whole
 * mesh, counted from index_base. */
ANITET_API int anitet_part_get_vertex_global_ids(const anitet_part* part, int64_t* ids,
                                                 int64_t ids_len, int32_t index_base);
/** Fills owners (owners_len >= num_vertices) with the owner part of each local vertex. */
ANITET_API int anitet_part_get_vertex_owners(const anitet_part* part, int32_t* owners,
                                             int64_t owners_len);
/** Fills ids (ids_len >= num_tets) with the local tets' tet numbers in the whole mesh, counted
 * from index_base. */
ANITET_API int anitet_part_get_tet_global_ids(const anitet_part* part, int64_t* ids,
                                              int64_t ids_len, int32_t index_base);
/** Fills owners (owners_len >= num_tets) with the owner part of each local tet. */
ANITET_API int anitet_part_get_tet_owners(const anitet_part* part, int32_t* owners,
                                          int64_t owners_len);
/** Fills layers (layers_len >= num_tets): 0 for an own tet, k for a tet of ghost layer k. */
ANITET_API int anitet_part_get_tet_layers(const anitet_part* part, int32_t* layers,
                                          int64_t layers_len);
/** Fills tri (tri_len >= 3*num_boundary_triangles) with local vertex ids counted from
 * index_base, each triangle as in the mesh. */
ANITET_API int anitet_part_get_boundary_triangles(const anitet_part* part, int32_t* tri,
                                                  int64_t tri_len, int32_t index_base);
/** Fills patch (patch_len >= num_boundary_triangles) with the triangles' patch labels. */
ANITET_API int anitet_part_get_boundary_patches(const anitet_part* part, int32_t* patch,
                                                int64_t patch_len);
/** Fills ids (ids_len >= num_boundary_triangles) with each triangle's index among the whole
 * mesh's boundary triangles, counted from index_base. */
ANITET_API int anitet_part_get_boundary_global_ids(const anitet_part* part, int64_t* ids,
                                                   int64_t ids_len, int32_t index_base);
/** Fills neighbours (neighbours_len >= num_neighbours) with the neighbour parts, ascending. */
ANITET_API int anitet_part_get_neighbours(const anitet_part* part, int32_t* neighbours,
                                          int64_t neighbours_len);
/** The number of items of halo list `list` (ANITET_HALO_*) over all neighbours.
 * Errors: INVALID_ARGUMENT (NULL, unknown list). */
ANITET_API int anitet_part_get_halo_size(const anitet_part* part, int32_t list, int64_t* size);
/** Halo list `list` (ANITET_HALO_*): offsets (offsets_len >= num_neighbours + 1) and items
 * (items_len >= its size). The items of neighbour i (anitet_part_get_neighbours' i-th, counted
 * from 0) are items[offsets[i] - index_base .. offsets[i+1] - index_base), local vertex or tet
 * ids counted from index_base; offsets[0] is index_base (so that with 1, Fortran's
 * items(offsets(i) : offsets(i+1) - 1) is neighbour i's list). */
ANITET_API int anitet_part_get_halo(const anitet_part* part, int32_t list, int64_t* offsets,
                                    int64_t offsets_len, int32_t* items, int64_t items_len,
                                    int32_t index_base);
/** Lends the part's own array `array` (ANITET_PART_*) without a copy: *data points to *count
 * elements of type *element_type (ANITET_TYPE_*; element_type may be NULL), ids 0-based, valid
 * and unchanged while the part lives (a lent part: while its partition lives). Read only. An
 * empty array gives *count 0 and a *data that must not be read. Errors: INVALID_ARGUMENT (NULL,
 * unknown array). */
ANITET_API int anitet_part_get_array(const anitet_part* part, int32_t array, const void** data,
                                     int64_t* count, int32_t* element_type);

/** The part as bytes into buf (buf_len bytes); *needed gets the size needed. buf == NULL with
 * buf_len == 0 asks for the size only and succeeds. The bytes are for anitet_part_deserialize
 * on a machine of the same byte order (the ranks of one job). */
ANITET_API int anitet_part_serialize(const anitet_part* part, void* buf, int64_t buf_len,
                                     int64_t* needed);
/** A part from the bytes of anitet_part_serialize (size bytes), checked: sizes, ids, owners and
 * offsets in range. Errors: INVALID_ARGUMENT (NULL bytes or out, negative size), PARSE (not the
 * bytes of a part, truncated, or inconsistent), OUT_OF_MEMORY. */
ANITET_API int anitet_part_deserialize(const void* bytes, int64_t size, anitet_part** out);

/* ---------------------------------------------------------------------------------------------
 * For libraries layered on this ABI (anitet_mpi.h's libanitet_mpi).
 * ------------------------------------------------------------------------------------------- */
/** Sets the calling thread's last error message (anitet_last_error_message) to `message` (NULL:
 * "") and returns `code` unchanged, so that a layered library reports its errors where the
 * caller of anitet looks for them: `return anitet_set_last_error(ANITET_ERR_..., "...");`. */
ANITET_API int anitet_set_last_error(int32_t code, const char* message);

/* ---------------------------------------------------------------------------------------------
 * 2D meshes: planar straight-line graphs (PSLGs) and coastlines, meshed by the paper's stages in
 * 2D (a front layer on the segments, conforming Delaunay recovery of the new front, coupling,
 * metric refinement, CVT and flips). docs/mesh2d.md has the method and the formats.
 * ------------------------------------------------------------------------------------------- */
typedef struct anitet_pslg anitet_pslg;     /**< a planar straight-line graph (the 2D input) */
typedef struct anitet_mesh2d anitet_mesh2d; /**< a triangle mesh of the 2D mesher */

/** A PSLG from caller arrays, copied: xy (2*num_points), segments (2*num_segments point indices
 * counted from index_base), labels (num_segments, or NULL for all 0), holes (2*num_holes points
 * whose face is not meshed, or NULL when num_holes is 0). The unbounded face and the faces
 * holding a hole point are outside; every other face of the segments is meshed. Points on no
 * segment become mesh vertices. The checks (crossing segments, open loops, holes outside) run
 * in anitet_mesh2d_run. Errors: INVALID_ARGUMENT, EMPTY_INPUT (fewer than 3 segments),
 * BAD_INDEX. */
ANITET_API int anitet_pslg_create(const double* xy, int64_t num_points, const int32_t* segments,
                                  int64_t num_segments, const int32_t* labels, const double* holes,
                                  int64_t num_holes, int32_t index_base, anitet_pslg** out);
/** A PSLG from a file, by extension: Triangle .poly (with its .node when it lists 0 points; holes
 * and regional attributes read), 2D Medit .mesh (its Edges, with their references as labels), or
 * GeoJSON .geojson/.json (Polygon and MultiPolygon geometries in longitude, latitude; set
 * anitet_mesh2d_options.geodetic to mesh them in metres). Errors: INVALID_ARGUMENT, FILE_NOT_FOUND,
 * PARSE, UNSUPPORTED_FORMAT, EMPTY_INPUT, BAD_INDEX (messages name the file, line and element). */
ANITET_API int anitet_pslg_read(const char* path, anitet_pslg** out);
/** Frees a PSLG; NULL is accepted. */
ANITET_API void anitet_pslg_destroy(anitet_pslg* pslg);
/** Numbers of points, segments and hole points; any output pointer may be NULL. */
ANITET_API int anitet_pslg_get_counts(const anitet_pslg* pslg, int64_t* num_points,
                                      int64_t* num_segments, int64_t* num_holes);

/** The newest version of anitet_mesh2d_options this header declares. */
#define ANITET_MESH2D_OPTIONS_VERSION 1

/** Options of the 2D mesher, a versioned struct: set it with ANITET_MESH2D_OPTIONS_INIT or
 * anitet_mesh2d_options_init(), then change fields. */
typedef struct anitet_mesh2d_options {
  int32_t version;            /**< ANITET_MESH2D_OPTIONS_VERSION */
  int32_t split_segments;     /**< 0 (default): every segment stays whole, no point on it; 1:
                                 points may be added on segments (better triangles at small
                                 input angles) */
  int32_t layers;             /**< front layers of stage 1, 1..20 (default 1) */
  int32_t refine;             /**< 1: refine to the sizes (default), 0: skip */
  int32_t optimize;           /**< 1: CVT, flips and clean-up (default), 0: skip */
  int32_t geodetic;           /**< 1: the PSLG's x, y are longitude, latitude (degrees, WGS84):
                                 meshed in a local frame in metres (sizes in metres), the mesh
                                 returned in longitude, latitude with the input's points exactly
                                 as given; 0 (default): planar */
  int32_t geo_frame;          /**< ANITET_GEO_ENU (default) or ANITET_GEO_UTM (geodetic only), at the input's centre */
  int32_t reserved0;          /**< keep 0 */
  double hsize;               /**< a constant target edge length; 0 (default): from the input's
                                 segment lengths, smoothed inside (or the metric's) */
  double size_scale;          /**< every target length times this (> 0; default 1) */
  double hmin;                /**< smallest target length (0: none) */
  double hmax;                /**< largest target length (0: none) */
  double hgrad;               /**< gradation > 1 (0: none) */
  anitet_progress_fn progress; /**< may be NULL; stages "validate", "sizing", "front", "refine",
                                  "optimize", "done" */
  void* progress_user_data;   /**< passed to progress untouched */
  /* Version 2 and later append fields here. */
} anitet_mesh2d_options;

/** Initializer of an anitet_mesh2d_options of version ANITET_MESH2D_OPTIONS_VERSION. */
#define ANITET_MESH2D_OPTIONS_INIT \
  { ANITET_MESH2D_OPTIONS_VERSION, 0, 1, 1, 1, 0, ANITET_GEO_ENU, 0, 0.0, 1.0, 0.0, 0.0, 0.0, 0, 0 }

/** Fills *options with the defaults of `version` (1 .. ANITET_MESH2D_OPTIONS_VERSION).
 * Errors: INVALID_ARGUMENT (NULL options, unknown version). */
ANITET_API int anitet_mesh2d_options_init(anitet_mesh2d_options* options, int32_t version);

/** Meshes the PSLG into a new triangle mesh *out (*out is NULL after any error). metric: NULL
 * for the options' sizes, or a metric evaluated at z = 0 (a 2D tensor is its xx xy yy block;
 * an analytic callback gets z = 0), intersected with hsize when both are given; geodetic
 * inputs take the metric in the local frame's metres. The mesh: the PSLG's points first and in
 * order, counter-clockwise triangles, a region attribute per triangle (a .poly's regional
 * attribute, a GeoJSON polygon's number), and the pieces of the segments as edges with their
 * labels. Errors: the input's (SELF_INTERSECTION: crossing segments; OPEN_BOUNDARY: an open
 * loop; DUPLICATE_POINT; INVALID_ARGUMENT: a hole or region outside the domain, bad options;
 * each message names the elements), CANCELLED, RECOVERY_FAILED, INTERNAL, OUT_OF_MEMORY. */
ANITET_API int anitet_mesh2d_run(const anitet_pslg* pslg, const anitet_metric* metric,
                                 const anitet_mesh2d_options* options, anitet_mesh2d** out);
/** Frees a triangle mesh; NULL is accepted. */
ANITET_API void anitet_mesh2d_destroy(anitet_mesh2d* mesh);
/** Numbers of points, triangles and edges (the segments' pieces); any pointer may be NULL. */
ANITET_API int anitet_mesh2d_get_counts(const anitet_mesh2d* mesh, int64_t* num_points,
                                        int64_t* num_triangles, int64_t* num_edges);
/** Fills xy (xy_len >= 2*num_points). */
ANITET_API int anitet_mesh2d_get_points(const anitet_mesh2d* mesh, double* xy, int64_t xy_len);
/** Fills tri (tri_len >= 3*num_triangles) with indices counted from index_base. */
ANITET_API int anitet_mesh2d_get_triangles(const anitet_mesh2d* mesh, int32_t* tri,
                                           int64_t tri_len, int32_t index_base);
/** Fills attributes (attributes_len >= num_triangles) with each triangle's region attribute. */
ANITET_API int anitet_mesh2d_get_attributes(const anitet_mesh2d* mesh, double* attributes,
                                            int64_t attributes_len);
/** Fills edges (edges_len >= 2*num_edges) with indices counted from index_base. */
ANITET_API int anitet_mesh2d_get_edges(const anitet_mesh2d* mesh, int32_t* edges,
                                       int64_t edges_len, int32_t index_base);
/** Fills labels (labels_len >= num_edges) with each edge's segment label. */
ANITET_API int anitet_mesh2d_get_edge_labels(const anitet_mesh2d* mesh, int32_t* labels,
                                             int64_t labels_len);
/** Writes by extension: .mesh (Medit, Dimension 2), .msh (Gmsh 4.1), .vtu, or .14 / fort.14
 * (ADCIRC, every labelled boundary a land boundary). */
ANITET_API int anitet_mesh2d_write(const anitet_mesh2d* mesh, const char* path);
/** Quality figures (any pointer may be NULL): the smallest angle in degrees, the smallest over
 * the triangles with no vertex among the input's points (180 when there is none), the mean
 * radius ratio 2r/R (1 for an equilateral triangle) and the share of edges whose length in the
 * sizing field's metric lies in [1/sqrt2, sqrt2] (measured in the local frame for geodetic
 * inputs). */
ANITET_API int anitet_mesh2d_quality(const anitet_mesh2d* mesh, double* min_angle_deg,
                                     double* min_angle_off_input_deg, double* mean_radius_ratio,
                                     double* edges_in_range);

#ifdef __cplusplus
}
#endif

#endif /**< ANITET_H */
