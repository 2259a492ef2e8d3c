/* Adaptation through the C ABI (anitet_adapt, anitet_adapt_to_metric): the UGAWG linear cube
 * adapted in two passes with the analytic metric evaluated again at the new vertices (>= 90% of
 * the edges in range, as `anitet adapt` reaches), fields carried, the metric handle variant and
 * every documented error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "anitet.h"
#include "capi_mesh_util.h"

static const char* cube_path(void) { return ANITET_UGAWG_DIR "/cube-linear-00.mesh"; }

static anitet_mesh* read_cube(void) {
  anitet_mesh* m = NULL;
  assert_int_equal(anitet_mesh_read(cube_path(), &m), ANITET_OK);
  return m;
}

/* UGAWG's linear metric: diag(h_x^-2, h_y^-2, h_z^-2), h_x = h_y = 0.1,
 * h_z = h0 + 2 (0.1 - h0) |z - 0.5|, h0 = 0.001 (../shared/data/ugawg/SOURCES.md). */
static void linear_metric_at(double z, double m[6]) {
  const double h0 = 0.001, hz = h0 + 2.0 * (0.1 - h0) * fabs(z - 0.5);
  m[0] = 100.0, m[1] = 0.0, m[2] = 100.0, m[3] = 0.0, m[4] = 0.0, m[5] = 1.0 / (hz * hz);
}

static int linear_metric(double x, double y, double z, double m[6], void* user_data) {
  (void)x, (void)y, (void)user_data;
  linear_metric_at(z, m);
  return 0;
}

/* The metric at every point of m: 6 values per point (the caller frees it). */
static double* metric_values(const anitet_mesh* m) {
  const int64_t np = points_of(m);
  double* xyz = points(m);
  double* values = malloc((size_t)(6 * np) * sizeof *values);
  int64_t i;
  assert_non_null(values);
  for (i = 0; i < np; ++i) linear_metric_at(xyz[3 * i + 2], &values[6 * i]);
  free(xyz);
  return values;
}

/* A linear scalar 1 + 2x - y + 3z and a vector (x, y, z) per point: carried exactly. */
static anitet_fields* linear_fields(const anitet_mesh* m) {
  static const int32_t kinds[2] = {ANITET_FIELD_KIND_SCALAR, ANITET_FIELD_KIND_VECTOR};
  const int64_t np = points_of(m);
  double* xyz = points(m);
  double* values = malloc((size_t)(4 * np) * sizeof *values);
  anitet_fields* f = NULL;
  int64_t i;
  assert_non_null(values);
  for (i = 0; i < np; ++i) {
    const double* p = &xyz[3 * i];
    values[4 * i] = 1.0 + 2.0 * p[0] - p[1] + 3.0 * p[2];
    memcpy(&values[4 * i + 1], p, 3 * sizeof *p);
  }
  assert_int_equal(anitet_fields_create(kinds, 2, values, 4 * np, &f), ANITET_OK);
  free(values), free(xyz);
  return f;
}

/* The largest difference between the carried fields and the linear ones at m's points. */
static double linear_error(const anitet_mesh* m, const anitet_fields* f) {
  const int64_t np = points_of(m);
  double* xyz = points(m);
  const double* data = NULL;
  int64_t count = 0, i;
  double worst = 0.0;
  assert_int_equal(anitet_fields_get_data(f, &data, &count), ANITET_OK);
  assert_int_equal(count, 4 * np);
  for (i = 0; i < np; ++i) {
    const double* p = &xyz[3 * i];
    const double* r = &data[4 * i];
    worst = fmax(worst, fabs(r[0] - (1.0 + 2.0 * p[0] - p[1] + 3.0 * p[2])));
    worst = fmax(worst, fmax(fabs(r[1] - p[0]), fmax(fabs(r[2] - p[1]), fabs(r[3] - p[2]))));
  }
  free(xyz);
  return worst;
}

static int count_progress(double fraction, const char* stage, void* user_data) {
  int* calls = (int*)user_data;
  (void)stage;
  assert_true(fraction >= 0.0 && fraction <= 1.0);
  ++*calls;
  return 0;
}

static void test_options_init(void** state) {
  anitet_adapt_options o = ANITET_ADAPT_OPTIONS_INIT, d;
  (void)state;
  memset(&d, 0xff, sizeof d);
  assert_int_equal(anitet_adapt_options_init(&d, ANITET_ADAPT_OPTIONS_VERSION), ANITET_OK);
  assert_memory_equal(&o, &d, sizeof o);
  assert_int_equal(o.max_cycles, 30);
  assert_true(o.ridge_angle_deg == 45.0);
  assert_int_equal(anitet_adapt_options_init(&d, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_adapt_options_init(&d, ANITET_ADAPT_OPTIONS_VERSION + 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_adapt_options_init(NULL, 1), ANITET_ERR_INVALID_ARGUMENT);
}

/* Two passes of a solver's loop on the UGAWG cube: the metric evaluated at the vertices of each
 * mesh, the fields carried along. */
static void test_cube_two_passes(void** state) {
  anitet_mesh* mesh = read_cube();
  anitet_fields* fields = linear_fields(mesh);
  anitet_adapt_options options = ANITET_ADAPT_OPTIONS_INIT;
  anitet_adapt_stats stats = ANITET_ADAPT_STATS_INIT;
  anitet_quality q = ANITET_QUALITY_INIT;
  int pass, calls = 0;
  (void)state;
  options.progress = count_progress;
  options.progress_user_data = &calls;
  for (pass = 1; pass <= 2; ++pass) {
    anitet_mesh* next = NULL;
    anitet_fields* carried = NULL;
    double* metric = metric_values(mesh);
    int64_t np = points_of(mesh), nt = 0, nb = 0;
    int32_t components = 0;
    const int rc = anitet_adapt(mesh, metric, 6 * np, 6, fields, &options, &next, &carried, &stats);
    if (rc != ANITET_OK) fail_msg("pass %d: %s", pass, anitet_last_error_message());
    free(metric);
    assert_int_equal(stats.vertices_in, np);
    assert_int_equal(anitet_mesh_get_counts(next, &np, &nt, &nb), ANITET_OK);
    assert_int_equal(stats.vertices, np);
    assert_int_equal(stats.tets, nt);
    assert_int_equal(stats.boundary_triangles, nb);
    assert_true(stats.splits > 0 && stats.swaps > 0 && stats.moves > 0 && stats.cycles >= 1);
    assert_true(stats.edges > nt / 2 && stats.edge_length_min > 0.0);
    assert_true(stats.mean_ratio_min > 0.0 && stats.mean_ratio_mean > stats.mean_ratio_min);
    assert_true(stats.seconds >= stats.seconds_adapt && stats.seconds_adapt > 0.0 && stats.seconds_transfer > 0.0);
    assert_true(fabs(stats.edges_in_range + stats.edges_shorter + stats.edges_longer - 1.0) < 1e-12);
    printf("pass %d: %lld vertices, %lld tets, %.2f%% of edges in range, mean ratio min %.3f mean %.3f, %.2f s\n",
           pass, (long long)np, (long long)nt, 100.0 * stats.edges_in_range, stats.mean_ratio_min,
           stats.mean_ratio_mean, stats.seconds);
    /* The new mesh carries the metric at its points, and the fields' records. */
    assert_int_equal(anitet_mesh_get_metric_components(next, &components), ANITET_OK);
    assert_int_equal(components, 6);
    assert_true(linear_error(next, carried) < 1e-9);
    assert_int_equal(anitet_mesh_quality(next, NULL, &q), ANITET_OK);
    assert_int_equal(q.valid, 1);
    anitet_mesh_destroy(mesh);
    anitet_fields_destroy(fields);
    mesh = next, fields = carried;
  }
  assert_true(stats.edges_in_range >= 0.90);
  assert_true(calls > 4);
  anitet_fields_destroy(fields);
  anitet_mesh_destroy(mesh);
}

/* The analytic metric as a handle (evaluated at every new point), keep_surface, fewer cycles;
 * the same mesh on 1 thread and on 2. */
static void test_metric_handle(void** state) {
  anitet_mesh* cube = read_cube();
  anitet_metric* metric = NULL;
  anitet_mesh *a = NULL, *b = NULL;
  anitet_adapt_options options = ANITET_ADAPT_OPTIONS_INIT;
  anitet_adapt_stats stats = ANITET_ADAPT_STATS_INIT;
  int64_t nb_in = 0, np = 0, nt = 0, nb = 0, np2 = 0, nt2 = 0;
  double *pa, *pb;
  (void)state;
  assert_int_equal(anitet_metric_create_analytic(linear_metric, NULL, &metric), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(cube, NULL, NULL, &nb_in), ANITET_OK);
  options.keep_surface = 1;
  options.max_cycles = 4;
  options.num_threads = 1;
  assert_int_equal(anitet_adapt_to_metric(cube, metric, NULL, &options, &a, NULL, &stats), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(a, &np, &nt, &nb), ANITET_OK);
  assert_int_equal(nb, nb_in); /* the surface kept */
  assert_int_equal(stats.surface_splits + stats.surface_collapses + stats.surface_moves, 0);
  assert_true(stats.cycles <= 4 && np > 64);
  options.num_threads = 2;
  assert_int_equal(anitet_adapt_to_metric(cube, metric, NULL, &options, &b, NULL, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(b, &np2, &nt2, NULL), ANITET_OK);
  assert_int_equal(np, np2);
  assert_int_equal(nt, nt2);
  pa = points(a), pb = points(b);
  assert_memory_equal(pa, pb, (size_t)(3 * np) * sizeof *pa);
  free(pa), free(pb);
  anitet_mesh_destroy(a);
  anitet_mesh_destroy(b);
  anitet_metric_destroy(metric);
  anitet_mesh_destroy(cube);
}

static int failing_metric(double x, double y, double z, double m[6], void* user_data) {
  (void)user_data;
  if (z > 0.6) return 7;
  linear_metric(x, y, z, m, NULL);
  return 0;
}

static int cancel_at_second(double fraction, const char* stage, void* user_data) {
  int* calls = (int*)user_data;
  (void)fraction, (void)stage;
  return ++*calls >= 2;
}

static void test_errors(void** state) {
  anitet_mesh* cube = read_cube();
  anitet_mesh* out = (anitet_mesh*)&out; /* not NULL: each failure must clear it */
  anitet_fields* out_fields = NULL;
  anitet_fields* fields = linear_fields(cube);
  anitet_fields* wrong = NULL;
  anitet_metric* failing = NULL;
  anitet_adapt_options options = ANITET_ADAPT_OPTIONS_INIT;
  anitet_adapt_stats stats = ANITET_ADAPT_STATS_INIT;
  const int64_t np = points_of(cube);
  double* metric = metric_values(cube);
  double sizes[64];
  static const int32_t scalar = ANITET_FIELD_KIND_SCALAR;
  static const double three[3] = {1, 2, 3};
  int calls = 0, i;
  (void)state;
  assert_int_equal(np, 64);
  for (i = 0; i < 64; ++i) sizes[i] = 0.2;

  /* NULL handles and outputs. */
  assert_int_equal(anitet_adapt(NULL, metric, 6 * np, 6, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(out);
  expect_message("mesh is NULL");
  assert_int_equal(anitet_adapt(cube, NULL, 6 * np, 6, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("metric is NULL");
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 6, NULL, NULL, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("out is NULL");
  assert_int_equal(anitet_adapt_to_metric(cube, NULL, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("metric is NULL");
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 6, fields, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("out_fields is NULL");
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 6, NULL, NULL, &out, &out_fields, NULL),
                   ANITET_ERR_INVALID_ARGUMENT);
  expect_message("fields is NULL");

  /* Metric of the wrong length or kind, non-SPD tensors and sizes <= 0 named by point. */
  assert_int_equal(anitet_adapt(cube, metric, 6 * np - 6, 6, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("metric_len is 378, not 6 per point of the mesh (384)");
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 3, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("components is 3");
  metric[6 * 5 + 5] = -1.0;
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 6, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("point 5 (0-based) is not a finite positive-definite tensor");
  metric[6 * 5 + 5] = NAN;
  assert_int_equal(anitet_adapt(cube, metric, 6 * np, 6, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("point 5 (0-based)");
  sizes[9] = 0.0;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("point 9 (0-based) is not a finite size > 0");
  assert_null(out);

  /* Options and stats of unknown versions, options out of range. */
  for (i = 0; i < 64; ++i) sizes[i] = 0.5;
  options.version = 0;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("options version 0 is not supported");
  options.version = ANITET_ADAPT_OPTIONS_VERSION + 1;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  options.version = ANITET_ADAPT_OPTIONS_VERSION;
  options.max_cycles = -1;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("max_cycles is -1");
  options.max_cycles = 30, options.ridge_angle_deg = 200.0;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("ridge_angle_deg");
  options.ridge_angle_deg = 45.0, options.tensors = 7;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("tensors is 7");
  options.tensors = ANITET_TENSORS_AUTO, options.num_threads = -2;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, &options, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("num_threads is negative");
  options.num_threads = 0;
  stats.version = 99;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, NULL, NULL, &out, NULL, &stats), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("stats version 99 is not supported");
  assert_null(out);

  /* Fields of another mesh. */
  assert_int_equal(anitet_fields_create(&scalar, 1, three, 3, &wrong), ANITET_OK);
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, wrong, NULL, &out, &out_fields, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("a field of another mesh");
  assert_null(out_fields);

  /* A failing analytic metric is named; a cancel leaves nothing. */
  assert_int_equal(anitet_metric_create_analytic(failing_metric, NULL, &failing), ANITET_OK);
  assert_int_equal(anitet_adapt_to_metric(cube, failing, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("the metric callback returned 7 at (");
  assert_null(out);
  options.progress = cancel_at_second;
  options.progress_user_data = &calls;
  assert_int_equal(anitet_adapt(cube, sizes, np, 1, fields, &options, &out, &out_fields, NULL), ANITET_ERR_CANCELLED);
  assert_null(out);
  assert_null(out_fields);
  assert_int_equal(calls, 2);

  anitet_metric_destroy(failing);
  anitet_fields_destroy(wrong);
  anitet_fields_destroy(fields);
  free(metric);
  anitet_mesh_destroy(cube);
}

/* A mesh with an inverted tet, and one without tets' worth of input. */
static void test_bad_meshes(void** state) {
  static const double xyz[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  static const int32_t inverted[8] = {0, 1, 2, 3, 1, 3, 2, 4};
  static const double sizes[5] = {0.5, 0.5, 0.5, 0.5, 0.5};
  anitet_mesh *bad = NULL, *out = NULL;
  (void)state;
  assert_int_equal(anitet_mesh_create(xyz, 5, inverted, 2, NULL, NULL, 0, NULL, 0, &bad), ANITET_OK);
  assert_int_equal(anitet_adapt(bad, sizes, 5, 1, NULL, NULL, &out, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("tet 2 is inverted");
  assert_null(out);
  anitet_mesh_destroy(bad);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_options_init),  cmocka_unit_test(test_cube_two_passes),
      cmocka_unit_test(test_metric_handle), cmocka_unit_test(test_errors),
      cmocka_unit_test(test_bad_meshes),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
