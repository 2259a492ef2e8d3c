/* The C ABI's metric fields from files and from per-point values on a background mesh:
 * anitet_metric_read (.vdb; .sol + background mesh) and anitet_metric_create_from_points, their
 * values, their use by anitet_mesher_run, and each documented error. The .vdb files come from the
 * fixture make_metric_vdb (ANITET_METRIC_VDB_DIR); the .sol files and background meshes are
 * written here through the C ABI itself, or by hand for the malformed ones. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"

#if !defined(ANITET_TEST_OUTPUT_DIR) || !defined(ANITET_METRIC_VDB_DIR)
#error "ANITET_TEST_OUTPUT_DIR and ANITET_METRIC_VDB_DIR must be defined"
#endif
#define VDB(name) ANITET_METRIC_VDB_DIR "/" name
#define OUT(name) ANITET_TEST_OUTPUT_DIR "/capi_metric_" name

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

static int near(double a, double b, double rel) { return fabs(a - b) <= rel * fabs(b); }

/* The isotropic tensor of size h, compared component-wise. */
static void assert_isotropic(const double m[6], double h, double rel) {
  const double d = 1.0 / (h * h);
  assert_true(near(m[0], d, rel) && near(m[2], d, rel) && near(m[5], d, rel));
  assert_true(fabs(m[1]) <= rel * d && fabs(m[3]) <= rel * d && fabs(m[4]) <= rel * d);
}

static void write_text(const char* path, const char* text) {
  FILE* f = fopen(path, "w");
  assert_non_null(f);
  assert_true(fputs(text, f) >= 0);
  assert_int_equal(fclose(f), 0);
}

/* ---- the background mesh: the box [-0.25, 1.25]^3 as 6 tets around its diagonal ------------ */

#define BG_LO (-0.25)
#define BG_HI 1.25

static void bg_point(int v, double p[3]) {
  p[0] = (v & 1) ? BG_HI : BG_LO;
  p[1] = (v & 2) ? BG_HI : BG_LO;
  p[2] = (v & 4) ? BG_HI : BG_LO;
}

static double orient(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* 8 points, 6 positive tets (0-based); `sizes` (8 values, or NULL) becomes its metric. */
static anitet_mesh* make_background(const double* sizes) {
  static const int axes[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};
  double xyz[24];
  int32_t tets[24];
  anitet_mesh* mesh = NULL;
  int t, v;
  for (v = 0; v < 8; ++v) bg_point(v, &xyz[3 * v]);
  for (t = 0; t < 6; ++t) {
    int32_t* q = &tets[4 * t];
    q[0] = 0;
    q[1] = axes[t][0];
    q[2] = axes[t][0] + axes[t][1];
    q[3] = 7;
    if (orient(&xyz[3 * q[0]], &xyz[3 * q[1]], &xyz[3 * q[2]], &xyz[3 * q[3]]) < 0) {
      const int32_t swap = q[1];
      q[1] = q[2];
      q[2] = swap;
    }
  }
  assert_int_equal(anitet_mesh_create(xyz, 8, tets, 6, NULL, NULL, 0, NULL, 0, &mesh), ANITET_OK);
  if (sizes) assert_int_equal(anitet_mesh_set_metric(mesh, sizes, 8, 1), ANITET_OK);
  return mesh;
}

/* h = 0.2 + 0.1 x at the background's points. */
static void linear_sizes(double sizes[8]) {
  int v;
  for (v = 0; v < 8; ++v) {
    double p[3];
    bg_point(v, p);
    sizes[v] = 0.2 + 0.1 * p[0];
  }
}

/* Writes the background (8 points, 6 tets) as .mesh and its per-point sizes as .sol. */
static void write_background(const char* mesh_path, const char* sol_path, const double sizes[8]) {
  anitet_mesh* mesh = make_background(sizes);
  assert_int_equal(anitet_mesh_write(mesh, mesh_path), ANITET_OK);
  assert_int_equal(anitet_mesh_write_metric(mesh, sol_path), ANITET_OK);
  anitet_mesh_destroy(mesh);
}

static anitet_surface* make_cube(void) {
  anitet_surface* s = NULL;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, kCubePatch, 0, &s), ANITET_OK);
  return s;
}

/* Meshes the unit cube with `metric`: the tet count; the mesh is valid, and carries the metric's
 * tensors at its vertices. */
static int64_t mesh_cube(const anitet_metric* metric) {
  anitet_surface* s = make_cube();
  anitet_mesh* mesh = NULL;
  anitet_quality q = ANITET_QUALITY_INIT;
  int64_t np = 0, nt = 0;
  int32_t components = 0;
  double* values;
  double t[6];
  assert_int_equal(anitet_mesher_run(s, metric, NULL, &mesh), ANITET_OK);
  assert_int_equal(anitet_mesh_quality(mesh, s, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  assert_int_equal(q.nonpositive_tets, 0);
  assert_int_equal(anitet_mesh_get_counts(mesh, &np, &nt, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(mesh, &components), ANITET_OK);
  assert_int_equal(components, 6);
  values = (double*)malloc(sizeof(double) * 6 * (size_t)np);
  assert_non_null(values);
  assert_int_equal(anitet_mesh_get_metric(mesh, values, 6 * np), ANITET_OK);
  {
    /* The surface's points come first, in order: point 6 is the corner (1, 1, 1). */
    double* xyz = (double*)malloc(sizeof(double) * 3 * (size_t)np);
    int c;
    assert_non_null(xyz);
    assert_int_equal(anitet_mesh_get_points(mesh, xyz, 3 * np), ANITET_OK);
    assert_true(xyz[18] == 1.0 && xyz[19] == 1.0 && xyz[20] == 1.0);
    assert_int_equal(anitet_metric_evaluate(metric, 1, 1, 1, t), ANITET_OK);
    for (c = 0; c < 6; ++c) assert_true(fabs(values[6 * 6 + c] - t[c]) <= 1e-9 * fabs(t[0]));
    free(xyz);
  }
  free(values);
  anitet_mesh_destroy(mesh);
  anitet_surface_destroy(s);
  return nt;
}

/* The sizes of the success tests, and the tet counts of the unit cube meshed with the uniform
 * metrics of these sizes (anitet_metric_create_uniform), measured once. */
#define FINE 0.25
#define COARSE 0.5
static int64_t g_uniform_fine = -1, g_uniform_coarse = -1;

static void uniform_counts(void) {
  anitet_metric* m = NULL;
  if (g_uniform_fine >= 0) return;
  assert_int_equal(anitet_metric_create_uniform(FINE, &m), ANITET_OK);
  g_uniform_fine = mesh_cube(m);
  anitet_metric_destroy(m);
  assert_int_equal(anitet_metric_create_uniform(COARSE, &m), ANITET_OK);
  g_uniform_coarse = mesh_cube(m);
  anitet_metric_destroy(m);
}

/* A constant size read from a file or given per point is the uniform metric of that size: about
 * the same mesh, and half the size gives several times the tets. "About": the background mesh's
 * barycentric interpolation gives the size to within an ulp or two, and the mesher's decisions
 * may react to the last bits, so 15 % is allowed (measured: equal counts at h = 0.25 since
 * refinement keeps its points off the cube's large faces; before that, splits crowding them made
 * the count swing 9-40 %); a wrong reading (h^2 for h, 1/h for h) changes the count many times
 * over. */
static void check_counts(const char* what, int64_t n_fine, int64_t n_coarse) {
  uniform_counts();
  print_message("%s: h %.2f -> %lld tets (uniform %lld), h %.2f -> %lld tets (uniform %lld)\n",
                what, FINE, (long long)n_fine, (long long)g_uniform_fine, COARSE,
                (long long)n_coarse, (long long)g_uniform_coarse);
  assert_true(n_fine > 3 * n_coarse);
  assert_true(llabs(n_fine - g_uniform_fine) * 100 <= 15 * g_uniform_fine);
  assert_true(llabs(n_coarse - g_uniform_coarse) * 100 <= 15 * g_uniform_coarse);
}

/* ---- .vdb ------------------------------------------------------------------------------------ */

static void test_read_vdb_values(void** state) {
  anitet_metric* m = NULL;
  double t[6];
  (void)state;
  assert_int_equal(anitet_metric_read(VDB("size_linear.vdb"), NULL, &m), ANITET_OK);
  assert_non_null(m);
  assert_string_equal(anitet_last_error_message(), "");
  /* Sizes are interpolated linearly: a linear field is exact between the voxels. */
  assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.3, 0.7, t), ANITET_OK);
  assert_isotropic(t, 0.25, 1e-9);
  assert_int_equal(anitet_metric_evaluate(m, 0.1, 0.9, 0.2, t), ANITET_OK);
  assert_isotropic(t, 0.21, 1e-9);
  /* Outside the grid's box: clamped to it (x = 1.5). */
  assert_int_equal(anitet_metric_evaluate(m, 5.0, 0.5, 0.5, t), ANITET_OK);
  assert_isotropic(t, 0.35, 1e-9);
  anitet_metric_destroy(m);

  m = NULL;
  assert_int_equal(anitet_metric_read(VDB("tensor.vdb"), NULL, &m), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(m, 0.4, 0.6, 0.2, t), ANITET_OK);
  assert_true(near(t[0], 100.0, 1e-9) && near(t[2], 25.0, 1e-9) && near(t[5], 6.25, 1e-9));
  assert_true(fabs(t[1]) < 1e-9 && fabs(t[3]) < 1e-9 && fabs(t[4]) < 1e-9);
  anitet_metric_destroy(m);
}

static void test_read_vdb_mesh(void** state) {
  anitet_metric* fine = NULL;
  anitet_metric* coarse = NULL;
  int64_t n_fine, n_coarse;
  (void)state;
  assert_int_equal(anitet_metric_read(VDB("size_fine.vdb"), NULL, &fine), ANITET_OK);
  assert_int_equal(anitet_metric_read(VDB("size_coarse.vdb"), NULL, &coarse), ANITET_OK);
  n_fine = mesh_cube(fine);
  n_coarse = mesh_cube(coarse);
  check_counts("vdb", n_fine, n_coarse);
  anitet_metric_destroy(fine);
  anitet_metric_destroy(coarse);
}

/* ---- .sol + background mesh ----------------------------------------------------------------- */

static void test_read_sol_values(void** state) {
  double sizes[8], t[6];
  anitet_metric* m = NULL;
  (void)state;
  linear_sizes(sizes);
  write_background(OUT("bg.mesh"), OUT("bg.sol"), sizes);
  assert_int_equal(anitet_metric_read(OUT("bg.sol"), OUT("bg.mesh"), &m), ANITET_OK);
  assert_non_null(m);
  /* Barycentric interpolation of h inside the tets: exact for a linear size. */
  assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.5, 0.5, t), ANITET_OK);
  assert_isotropic(t, 0.25, 1e-12);
  assert_int_equal(anitet_metric_evaluate(m, 1.0, 0.1, 0.9, t), ANITET_OK);
  assert_isotropic(t, 0.3, 1e-12);
  /* Outside the background: the nearest tet's value (clamped), here x = 1.25. */
  assert_int_equal(anitet_metric_evaluate(m, 3.0, 0.5, 0.5, t), ANITET_OK);
  assert_isotropic(t, 0.325, 1e-12);
  anitet_metric_destroy(m);

  /* Other background formats by extension (.msh, .vtu). */
  {
    anitet_mesh* mesh = NULL;
    assert_int_equal(anitet_mesh_read(OUT("bg.mesh"), &mesh), ANITET_OK);
    assert_int_equal(anitet_mesh_write(mesh, OUT("bg.vtu")), ANITET_OK);
    anitet_mesh_destroy(mesh);
    assert_int_equal(anitet_metric_read(OUT("bg.sol"), OUT("bg.vtu"), &m), ANITET_OK);
    assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.5, 0.5, t), ANITET_OK);
    assert_isotropic(t, 0.25, 1e-12);
    anitet_metric_destroy(m);
  }

  /* A tensor .sol (type 3), written by hand, upper case extension. */
  write_text(OUT("tensor.SOL"),
             "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n8\n1 3\n"
             "100 0 25 0 0 6.25\n100 0 25 0 0 6.25\n100 0 25 0 0 6.25\n100 0 25 0 0 6.25\n"
             "100 0 25 0 0 6.25\n100 0 25 0 0 6.25\n100 0 25 0 0 6.25\n100 0 25 0 0 6.25\nEnd\n");
  assert_int_equal(anitet_metric_read(OUT("tensor.SOL"), OUT("bg.mesh"), &m), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(m, 0.2, 0.7, 0.4, t), ANITET_OK);
  assert_true(near(t[0], 100.0, 1e-12) && near(t[2], 25.0, 1e-12) && near(t[5], 6.25, 1e-12));
  assert_true(fabs(t[1]) < 1e-12 && fabs(t[3]) < 1e-12 && fabs(t[4]) < 1e-12);
  anitet_metric_destroy(m);
}

static void test_read_sol_mesh(void** state) {
  const double fine_sizes[8] = {FINE, FINE, FINE, FINE, FINE, FINE, FINE, FINE};
  const double coarse_sizes[8] = {COARSE, COARSE, COARSE, COARSE, COARSE, COARSE, COARSE, COARSE};
  anitet_metric* fine = NULL;
  anitet_metric* coarse = NULL;
  int64_t n_fine, n_coarse;
  (void)state;
  write_background(OUT("fine.mesh"), OUT("fine.sol"), fine_sizes);
  write_background(OUT("coarse.mesh"), OUT("coarse.sol"), coarse_sizes);
  assert_int_equal(anitet_metric_read(OUT("fine.sol"), OUT("fine.mesh"), &fine), ANITET_OK);
  assert_int_equal(anitet_metric_read(OUT("coarse.sol"), OUT("coarse.mesh"), &coarse), ANITET_OK);
  n_fine = mesh_cube(fine);
  n_coarse = mesh_cube(coarse);
  check_counts("sol", n_fine, n_coarse);
  anitet_metric_destroy(fine);
  anitet_metric_destroy(coarse);
}

static void test_read_errors(void** state) {
  anitet_metric* m = NULL;
  double sizes[8];
  (void)state;
  linear_sizes(sizes);
  write_background(OUT("err.mesh"), OUT("err.sol"), sizes);

  /* NULL arguments. */
  assert_int_equal(anitet_metric_read(VDB("size_fine.vdb"), NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "out is NULL"));
  m = (anitet_metric*)&sizes; /* must be reset to NULL by the failing call */
  assert_int_equal(anitet_metric_read(NULL, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "path is NULL"));

  /* Missing files. */
  m = (anitet_metric*)&sizes;
  assert_int_equal(anitet_metric_read(OUT("missing.vdb"), NULL, &m), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "missing.vdb"));
  assert_int_equal(anitet_metric_read(OUT("missing.sol"), OUT("err.mesh"), &m), ANITET_ERR_FILE_NOT_FOUND);
  assert_int_equal(anitet_metric_read(OUT("err.sol"), OUT("missing.mesh"), &m), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(m);

  /* Not a .vdb, not a .sol. */
  write_text(OUT("garbage.vdb"), "this is not an OpenVDB file\n");
  assert_int_equal(anitet_metric_read(OUT("garbage.vdb"), NULL, &m), ANITET_ERR_PARSE);
  assert_null(m);
  write_text(OUT("garbage.sol"), "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n8\n1 1\n0.1 0.1\n");
  assert_int_equal(anitet_metric_read(OUT("garbage.sol"), OUT("err.mesh"), &m), ANITET_ERR_PARSE);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "garbage.sol"));
  /* A .sol of vectors (type 2): valid Medit, not a metric. */
  write_text(OUT("vectors.sol"), "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 2\n1 2 3\nEnd\n");
  assert_int_equal(anitet_metric_read(OUT("vectors.sol"), OUT("err.mesh"), &m), ANITET_ERR_UNSUPPORTED_FORMAT);
  /* Neither extension (a mesh file, a directory). */
  assert_int_equal(anitet_metric_read(OUT("err.mesh"), NULL, &m), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_true(contains(anitet_last_error_message(), ".vdb, .sol or .solb"));
  assert_int_equal(anitet_metric_read(ANITET_TEST_OUTPUT_DIR, NULL, &m), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_null(m);

  /* Background mesh: needed by a .sol, refused with a .vdb. */
  assert_int_equal(anitet_metric_read(OUT("err.sol"), NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "background"));
  assert_int_equal(anitet_metric_read(VDB("size_fine.vdb"), OUT("err.mesh"), &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "background"));
  assert_null(m);

  /* Sizes mismatch: a .sol of 4 values for a background of 8 points. */
  write_text(OUT("four.sol"), "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n4\n1 1\n0.1\n0.1\n0.1\n0.1\nEnd\n");
  assert_int_equal(anitet_metric_read(OUT("four.sol"), OUT("err.mesh"), &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "4 values for a mesh of 8 vertices"));
  assert_null(m);
  /* A size <= 0, a tensor that is not positive definite. */
  write_text(OUT("negative.sol"),
             "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n8\n1 1\n0.1\n0.1\n0.1\n-0.1\n0.1\n0.1\n0.1\n0.1\nEnd\n");
  assert_int_equal(anitet_metric_read(OUT("negative.sol"), OUT("err.mesh"), &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "vertex 3"));
  write_text(OUT("indefinite.sol"),
             "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n8\n1 3\n"
             "1 0 1 0 0 1\n1 0 1 0 0 1\n1 0 1 0 0 1\n1 0 1 0 0 1\n1 0 1 0 0 1\n1 2 1 0 0 1\n"
             "1 0 1 0 0 1\n1 0 1 0 0 1\nEnd\n");
  assert_int_equal(anitet_metric_read(OUT("indefinite.sol"), OUT("err.mesh"), &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "vertex 5"));
  assert_null(m);
}

/* ---- per-point values on a background mesh ------------------------------------------------- */

static void test_from_points_values_and_ownership(void** state) {
  double sizes[8], tensors[48], t[6];
  anitet_mesh* bg = make_background(NULL);
  anitet_metric* m = NULL;
  anitet_metric* aniso = NULL;
  int v, c;
  (void)state;
  linear_sizes(sizes);
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 1, &m), ANITET_OK);
  assert_non_null(m);
  for (v = 0; v < 8; ++v) {
    const double tensor[6] = {100.0, 0.0, 25.0, 0.0, 0.0, 6.25};
    for (c = 0; c < 6; ++c) tensors[6 * v + c] = tensor[c];
  }
  assert_int_equal(anitet_metric_create_from_points(bg, tensors, 48, 6, &aniso), ANITET_OK);
  /* The values and the background are copied: both may go. */
  anitet_mesh_destroy(bg);
  memset(sizes, 0, sizeof sizes);
  memset(tensors, 0, sizeof tensors);

  assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.5, 0.5, t), ANITET_OK);
  assert_isotropic(t, 0.25, 1e-12);
  assert_int_equal(anitet_metric_evaluate(m, BG_HI, BG_LO, BG_HI, t), ANITET_OK); /* a point */
  assert_isotropic(t, 0.2 + 0.1 * BG_HI, 1e-12);
  assert_int_equal(anitet_metric_evaluate(aniso, 0.3, 0.3, 0.9, t), ANITET_OK);
  assert_true(near(t[0], 100.0, 1e-12) && near(t[2], 25.0, 1e-12) && near(t[5], 6.25, 1e-12));
  /* A point that is not finite. */
  assert_int_equal(anitet_metric_evaluate(m, NAN, 0.5, 0.5, t), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_evaluate(aniso, 0.5, INFINITY, 0.5, t), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not finite"));
  assert_int_equal(anitet_metric_evaluate(NULL, 0.5, 0.5, 0.5, t), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.5, 0.5, NULL), ANITET_ERR_INVALID_ARGUMENT);
  anitet_metric_destroy(m);
  anitet_metric_destroy(aniso);
}

static void test_from_points_mesh(void** state) {
  double fine_sizes[8], coarse_sizes[8];
  anitet_mesh* bg = make_background(NULL);
  anitet_metric* fine = NULL;
  anitet_metric* coarse = NULL;
  int64_t n_fine, n_coarse;
  int v;
  (void)state;
  for (v = 0; v < 8; ++v) {
    fine_sizes[v] = FINE;
    coarse_sizes[v] = COARSE;
  }
  assert_int_equal(anitet_metric_create_from_points(bg, fine_sizes, 8, 1, &fine), ANITET_OK);
  assert_int_equal(anitet_metric_create_from_points(bg, coarse_sizes, 8, 1, &coarse), ANITET_OK);
  anitet_mesh_destroy(bg);
  n_fine = mesh_cube(fine);
  n_coarse = mesh_cube(coarse);
  check_counts("points", n_fine, n_coarse);
  anitet_metric_destroy(fine);
  anitet_metric_destroy(coarse);
}

static void test_from_points_errors(void** state) {
  double sizes[8], tensors[48];
  anitet_mesh* bg = make_background(NULL);
  anitet_metric* m = NULL;
  int v, c;
  (void)state;
  for (v = 0; v < 8; ++v) {
    sizes[v] = 0.2;
    for (c = 0; c < 6; ++c) tensors[6 * v + c] = (c == 0 || c == 2 || c == 5) ? 1.0 : 0.0;
  }
  /* NULL arguments. */
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 1, NULL), ANITET_ERR_INVALID_ARGUMENT);
  m = (anitet_metric*)&sizes;
  assert_int_equal(anitet_metric_create_from_points(NULL, sizes, 8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "background is NULL"));
  assert_int_equal(anitet_metric_create_from_points(bg, NULL, 8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "values is NULL"));
  /* components. */
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 3, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "components is 3"));
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 0, &m), ANITET_ERR_INVALID_ARGUMENT);
  /* Sizes mismatch: too few, too many, negative, 6 components with the count of 1. */
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 7, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "num_values is 7"));
  assert_int_equal(anitet_metric_create_from_points(bg, tensors, 9, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, -8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_create_from_points(bg, tensors, 8, 6, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "(48)"));
  assert_null(m);
  /* Bad values: a size <= 0, a NaN, a tensor that is not positive definite. */
  sizes[5] = 0.0;
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "point 5"));
  sizes[5] = NAN;
  assert_int_equal(anitet_metric_create_from_points(bg, sizes, 8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  tensors[6 * 2 + 4] = INFINITY;
  assert_int_equal(anitet_metric_create_from_points(bg, tensors, 48, 6, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "point 2"));
  tensors[6 * 2 + 4] = 2.0; /* yz = 2 with yy = zz = 1: indefinite */
  assert_int_equal(anitet_metric_create_from_points(bg, tensors, 48, 6, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "vertex 2"));
  assert_null(m);
  anitet_mesh_destroy(bg);
}

/* ---- the surface's own field, writing a metric, sampling it at a mesh's points ---------------- */

static void test_surface_sizing_and_write(void** state) {
  anitet_surface* s = make_cube();
  anitet_metric *field = NULL, *bounded = NULL, *back = NULL, *uniform = NULL;
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_mesh *plain = NULL, *with_field = NULL;
  int64_t n_plain = 0, n_field = 0;
  double a[6], b[6];
  (void)state;
  /* The field anitet_mesher_run follows without a metric: meshing to it gives the same mesh. */
  assert_int_equal(anitet_metric_create_surface_sizing(s, NULL, &field), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, NULL, NULL, &plain), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, field, NULL, &with_field), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(plain, NULL, &n_plain, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(with_field, NULL, &n_field, NULL), ANITET_OK);
  assert_true(llabs(n_field - n_plain) * 100 <= 15 * n_plain);
  /* hmax bounds it. */
  o.hmax = 0.1;
  assert_int_equal(anitet_metric_create_surface_sizing(s, &o, &bounded), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(bounded, 0.5, 0.5, 0.5, a), ANITET_OK);
  assert_true(a[0] >= 1.0 / (0.1 * 0.1) * (1 - 1e-6));
  /* Written as a .vdb and read back: the same values (a grid, written as it is). */
  assert_int_equal(anitet_metric_write(bounded, NULL, OUT("surface_sizing.vdb")), ANITET_OK);
  assert_int_equal(anitet_metric_read(OUT("surface_sizing.vdb"), NULL, &back), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(back, 0.5, 0.5, 0.5, b), ANITET_OK);
  assert_true(near(b[0], a[0], 1e-5) && near(b[2], a[2], 1e-5) && near(b[5], a[5], 1e-5));
  anitet_metric_destroy(back);
  /* Any other metric is sampled over a surface's box, which must then be given. */
  assert_int_equal(anitet_metric_create_uniform(0.3, &uniform), ANITET_OK);
  assert_int_equal(anitet_metric_write(uniform, NULL, OUT("uniform.vdb")), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "box_of"));
  assert_int_equal(anitet_metric_write(uniform, s, OUT("uniform.vdb")), ANITET_OK);
  assert_int_equal(anitet_metric_read(OUT("uniform.vdb"), NULL, &back), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(back, 0.2, 0.9, 0.4, b), ANITET_OK);
  assert_isotropic(b, 0.3, 1e-5);
  anitet_metric_destroy(back);
  /* Errors. */
  assert_int_equal(anitet_metric_write(uniform, s, OUT("uniform.sol")), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_int_equal(anitet_metric_write(NULL, s, OUT("x.vdb")), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_create_surface_sizing(NULL, NULL, &back), ANITET_ERR_INVALID_ARGUMENT);
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.hgrad = 0.5;
  assert_int_equal(anitet_metric_create_surface_sizing(s, &o, &back), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(back);
  anitet_metric_destroy(uniform);
  anitet_metric_destroy(bounded);
  anitet_metric_destroy(field);
  anitet_mesh_destroy(with_field);
  anitet_mesh_destroy(plain);
  anitet_surface_destroy(s);
}

static int stretched_x(double x, double y, double z, double m[6], void* user_data) {
  (void)y, (void)z, (void)user_data;
  if (x > 1.5) return 3;
  m[0] = 100.0, m[1] = 0.0, m[2] = 4.0, m[3] = 0.0, m[4] = 0.0, m[5] = 4.0;
  return 0;
}

static void test_sample_and_read_on_mesh(void** state) {
  anitet_mesh* bg = make_background(NULL);
  anitet_metric *uniform = NULL, *stretched = NULL, *on_mesh = NULL;
  int32_t components = -1;
  double values[48], t[6];
  (void)state;
  /* Isotropic: sizes (1 component); anisotropic: tensors (6). */
  assert_int_equal(anitet_metric_create_uniform(0.25, &uniform), ANITET_OK);
  assert_int_equal(anitet_mesh_sample_metric(bg, uniform), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(bg, &components), ANITET_OK);
  assert_int_equal(components, 1);
  assert_int_equal(anitet_mesh_get_metric(bg, values, 8), ANITET_OK);
  assert_true(near(values[7], 0.25, 1e-15));
  assert_int_equal(anitet_metric_create_analytic(stretched_x, NULL, &stretched), ANITET_OK);
  assert_int_equal(anitet_mesh_sample_metric(bg, stretched), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(bg, &components), ANITET_OK);
  assert_int_equal(components, 6);
  assert_int_equal(anitet_mesh_get_metric(bg, values, 48), ANITET_OK);
  assert_true(values[0] == 100.0 && values[2] == 4.0);
  /* Its .sol read back on the mesh in memory. */
  assert_int_equal(anitet_mesh_write_metric(bg, OUT("sampled.sol")), ANITET_OK);
  assert_int_equal(anitet_metric_read_on_mesh(OUT("sampled.sol"), bg, &on_mesh), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(on_mesh, 0.5, 0.5, 0.5, t), ANITET_OK);
  assert_true(near(t[0], 100.0, 1e-9) && near(t[2], 4.0, 1e-9));
  anitet_metric_destroy(on_mesh);
  /* A callback failing at a point: an error naming it, the mesh's metric unchanged. */
  {
    anitet_mesh* far = NULL;
    double xyz[24];
    int32_t tet[4] = {0, 1, 2, 3};
    int i;
    for (i = 0; i < 24; ++i) xyz[i] = kCubeXyz[i] * 2.0;
    assert_int_equal(anitet_mesh_create(xyz, 8, tet, 1, NULL, NULL, 0, NULL, 0, &far), ANITET_OK);
    assert_int_equal(anitet_mesh_sample_metric(far, uniform), ANITET_OK);
    assert_int_equal(anitet_mesh_sample_metric(far, stretched), ANITET_ERR_INVALID_ARGUMENT);
    assert_true(contains(anitet_last_error_message(), "returned 3"));
    assert_int_equal(anitet_mesh_get_metric_components(far, &components), ANITET_OK);
    assert_int_equal(components, 1);
    anitet_mesh_destroy(far);
  }
  assert_int_equal(anitet_mesh_sample_metric(NULL, uniform), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_sample_metric(bg, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_read_on_mesh(OUT("sampled.vdb"), bg, &on_mesh), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_int_equal(anitet_metric_read_on_mesh(OUT("no-such.sol"), bg, &on_mesh), ANITET_ERR_FILE_NOT_FOUND);
  assert_int_equal(anitet_metric_read_on_mesh(OUT("sampled.sol"), NULL, &on_mesh), ANITET_ERR_INVALID_ARGUMENT);
  anitet_metric_destroy(stretched);
  anitet_metric_destroy(uniform);
  anitet_mesh_destroy(bg);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_read_vdb_values),
      cmocka_unit_test(test_read_vdb_mesh),
      cmocka_unit_test(test_read_sol_values),
      cmocka_unit_test(test_read_sol_mesh),
      cmocka_unit_test(test_read_errors),
      cmocka_unit_test(test_from_points_values_and_ownership),
      cmocka_unit_test(test_from_points_mesh),
      cmocka_unit_test(test_from_points_errors),
      cmocka_unit_test(test_surface_sizing_and_write),
      cmocka_unit_test(test_sample_and_read_on_mesh),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
