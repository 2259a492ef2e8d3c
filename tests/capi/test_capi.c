/* The C ABI (include/anitet.h): every entry point, its success and its documented errors. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"

#ifndef ANITET_TEST_DATA_DIR
#error "ANITET_TEST_DATA_DIR must be defined"
#endif
#define BOX_MESH ANITET_TEST_DATA_DIR "/io/box.mesh"
#define BOX_STL ANITET_TEST_DATA_DIR "/io/box_ascii.stl"

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

static anitet_surface* make_cube(void) {
  anitet_surface* s = NULL;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, kCubePatch, 0, &s), ANITET_OK);
  assert_non_null(s);
  return s;
}

/* ---- library information -------------------------------------------------------------------- */

static void test_version(void** state) {
  (void)state;
  assert_string_equal(anitet_version(), ANITET_VERSION_STRING);
  assert_int_equal(anitet_version_number(), ANITET_VERSION_NUMBER);
}

static void test_error_names(void** state) {
  (void)state;
  assert_string_equal(anitet_error_name(ANITET_OK), "ok");
  assert_string_equal(anitet_error_name(ANITET_ERR_OPEN_BOUNDARY), "open_boundary");
  assert_string_equal(anitet_error_name(ANITET_ERR_BUFFER_TOO_SMALL), "buffer_too_small");
  assert_string_equal(anitet_error_name(ANITET_ERR_NOT_IMPLEMENTED), "not_implemented");
  assert_string_equal(anitet_error_name(-12345), "unknown_error");
  /* The numbers are part of the ABI: a renumbering must fail here. */
  assert_int_equal(ANITET_ERR_INVALID_ARGUMENT, -1);
  assert_int_equal(ANITET_ERR_BUFFER_TOO_SMALL, -6);
  assert_int_equal(ANITET_ERR_SELF_INTERSECTION, -17);
  assert_int_equal(ANITET_ERR_BAD_INDEX, -19);
  assert_int_equal(ANITET_ERR_NOT_IMPLEMENTED, -30);
  assert_int_equal(ANITET_ERR_CANCELLED, -31);
  assert_int_equal(ANITET_ERR_INTERNAL, -99);
}

static void test_options_init(void** state) {
  anitet_options a = ANITET_OPTIONS_INIT;
  anitet_options b;
  (void)state;
  memset(&b, 0x5a, sizeof b);
  assert_int_equal(anitet_options_init(&b, ANITET_OPTIONS_VERSION), ANITET_OK);
  assert_string_equal(anitet_last_error_message(), "");
  assert_int_equal(b.version, a.version);
  assert_int_equal(b.num_threads, 0);
  assert_int_equal(b.merge_duplicate_vertices, 1);
  assert_int_equal(b.orient_shells, 1);
  assert_int_equal(b.check_self_intersections, 1);
  assert_null(b.progress);
  assert_null(b.log);
  assert_int_equal(b.layers, 1);
  assert_int_equal(b.layer_scheme, ANITET_LAYERS_PUSH);
  assert_int_equal(anitet_options_init(&b, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "version 0"));
  assert_int_equal(anitet_options_init(&b, ANITET_OPTIONS_VERSION + 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_options_init(NULL, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "options is NULL"));
}

/* ---- surfaces ------------------------------------------------------------------------------- */

static void test_surface_create_and_read_back(void** state) {
  anitet_surface* s = make_cube();
  int64_t np = -1, nt = -1;
  double xyz[24];
  int32_t tri[36], patch[12];
  int i;
  (void)state;
  assert_int_equal(anitet_surface_get_counts(s, &np, &nt), ANITET_OK);
  assert_int_equal(np, 8);
  assert_int_equal(nt, 12);
  assert_int_equal(anitet_surface_get_points(s, xyz, 24), ANITET_OK);
  assert_memory_equal(xyz, kCubeXyz, sizeof xyz);
  assert_int_equal(anitet_surface_get_triangles(s, tri, 36, 0), ANITET_OK);
  assert_memory_equal(tri, kCubeTri, sizeof tri);
  assert_int_equal(anitet_surface_get_triangles(s, tri, 36, 1), ANITET_OK);
  for (i = 0; i < 36; ++i) assert_int_equal(tri[i], kCubeTri[i] + 1);
  assert_int_equal(anitet_surface_get_patches(s, patch, 12), ANITET_OK);
  assert_memory_equal(patch, kCubePatch, sizeof patch);
  anitet_surface_destroy(s);
}

static void test_surface_create_index_base_1(void** state) {
  int32_t tri1[36], tri[36];
  anitet_surface* s = NULL;
  int i;
  (void)state;
  for (i = 0; i < 36; ++i) tri1[i] = kCubeTri[i] + 1;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, tri1, 12, NULL, 1, &s), ANITET_OK);
  assert_int_equal(anitet_surface_get_triangles(s, tri, 36, 0), ANITET_OK);
  assert_memory_equal(tri, kCubeTri, sizeof tri);
  assert_int_equal(anitet_surface_get_patches(s, tri, 12), ANITET_OK);
  for (i = 0; i < 12; ++i) assert_int_equal(tri[i], 0); /* NULL patch: all 0 */
  anitet_surface_destroy(s);
  /* 0-based data read as 1-based: vertex 0 does not exist. */
  s = (anitet_surface*)1;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, NULL, 1, &s), ANITET_ERR_BAD_INDEX);
  assert_null(s);
  assert_true(contains(anitet_last_error_message(), "triangle 1 refers to vertex 0"));
}

static void test_surface_create_errors(void** state) {
  anitet_surface* s = NULL;
  int32_t bad[36];
  (void)state;
  memcpy(bad, kCubeTri, sizeof bad);
  bad[7] = 8;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, bad, 12, NULL, 0, &s), ANITET_ERR_BAD_INDEX);
  assert_true(contains(anitet_last_error_message(), "triangle 2 refers to vertex 8"));
  bad[7] = -1;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, bad, 12, NULL, 0, &s), ANITET_ERR_BAD_INDEX);
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, NULL, 2, &s), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "index_base"));
  assert_int_equal(anitet_surface_create(NULL, 8, kCubeTri, 12, NULL, 0, &s), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, NULL, 12, NULL, 0, &s), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, NULL, 0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_create(kCubeXyz, 0, kCubeTri, 12, NULL, 0, &s), ANITET_ERR_EMPTY_INPUT);
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 0, NULL, 0, &s), ANITET_ERR_EMPTY_INPUT);
  assert_int_equal(anitet_surface_create(kCubeXyz, -8, kCubeTri, 12, NULL, 0, &s), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(s);
}

static void test_surface_accessor_errors(void** state) {
  anitet_surface* s = make_cube();
  double xyz[24];
  int32_t tri[36];
  int64_t n;
  (void)state;
  assert_int_equal(anitet_surface_get_counts(NULL, &n, &n), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "surface is NULL"));
  assert_int_equal(anitet_surface_get_counts(s, NULL, NULL), ANITET_OK);
  assert_int_equal(anitet_surface_get_points(s, xyz, 23), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_true(contains(anitet_last_error_message(), "24 needed"));
  assert_int_equal(anitet_surface_get_points(s, NULL, 24), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_get_points(NULL, xyz, 24), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_get_triangles(s, tri, 35, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_surface_get_triangles(s, tri, 36, -1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_get_triangles(NULL, tri, 36, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_get_patches(s, tri, 11), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_surface_get_patches(NULL, tri, 12), ANITET_ERR_INVALID_ARGUMENT);
  anitet_surface_destroy(s);
  anitet_surface_destroy(NULL);
}

static void test_surface_read(void** state) {
  anitet_surface* s = NULL;
  int64_t np = 0, nt = 0;
  (void)state;
  assert_int_equal(anitet_surface_read(BOX_STL, &s), ANITET_OK);
  assert_int_equal(anitet_surface_get_counts(s, &np, &nt), ANITET_OK);
  assert_int_equal(np, 8);
  assert_int_equal(nt, 12);
  assert_int_equal(anitet_surface_validate(s, NULL), ANITET_OK);
  anitet_surface_destroy(s);
  s = NULL;
  assert_int_equal(anitet_surface_read(ANITET_TEST_DATA_DIR "/io/no_such_file.off", &s), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(s);
  assert_true(contains(anitet_last_error_message(), "no_such_file.off"));
  assert_int_equal(anitet_surface_read(ANITET_TEST_DATA_DIR "/io/box.unknown", &s), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_int_equal(anitet_surface_read(NULL, &s), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_read(BOX_STL, NULL), ANITET_ERR_INVALID_ARGUMENT);
}

static void test_surface_validate_clean(void** state) {
  anitet_surface* s = make_cube();
  int64_t count = -1, needed = 0, needed2 = 0;
  char small[4];
  char* json;
  (void)state;
  assert_int_equal(anitet_surface_problem_count(s, ANITET_ERR_OPEN_BOUNDARY, &count), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not validated"));
  assert_int_equal(anitet_surface_validation_json(s, NULL, 0, &needed), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_validate(s, NULL), ANITET_OK);
  assert_string_equal(anitet_last_error_message(), "");
  assert_int_equal(anitet_surface_problem_count(s, ANITET_ERR_OPEN_BOUNDARY, &count), ANITET_OK);
  assert_int_equal(count, 0);
  assert_int_equal(anitet_surface_problem_count(s, ANITET_ERR_OPEN_BOUNDARY, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_problem_count(NULL, ANITET_ERR_OPEN_BOUNDARY, &count), ANITET_ERR_INVALID_ARGUMENT);
  /* JSON: size query, short buffer, fill. */
  assert_int_equal(anitet_surface_validation_json(s, NULL, 0, &needed), ANITET_OK);
  assert_true(needed > 10);
  assert_int_equal(anitet_surface_validation_json(s, small, sizeof small, &needed2), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(needed2, needed);
  json = malloc((size_t)needed);
  assert_non_null(json);
  assert_int_equal(anitet_surface_validation_json(s, json, needed, NULL), ANITET_OK);
  assert_int_equal((int64_t)strlen(json) + 1, needed);
  assert_true(json[0] == '{');
  free(json);
  assert_int_equal(anitet_surface_validation_json(NULL, NULL, 0, &needed), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_validate(NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  anitet_surface_destroy(s);
}

static void test_surface_validate_open(void** state) {
  anitet_surface* s = NULL;
  int64_t count = 0;
  (void)state;
  /* The cube without its last triangle: three open edges. */
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 11, NULL, 0, &s), ANITET_OK);
  assert_int_equal(anitet_surface_validate(s, NULL), ANITET_ERR_OPEN_BOUNDARY);
  assert_true(strlen(anitet_last_error_message()) > 0);
  assert_int_equal(anitet_surface_problem_count(s, ANITET_ERR_OPEN_BOUNDARY, &count), ANITET_OK);
  assert_int_equal(count, 3);
  anitet_surface_destroy(s);
}

static void test_surface_validate_intersection(void** state) {
  /* Two unit cubes in one surface, the second shifted by (0.5, 0.5, 0.5): the shells cross. */
  double xyz[48];
  int32_t tri[72];
  anitet_surface* s = NULL;
  int64_t count = 0;
  int i, rc;
  (void)state;
  for (i = 0; i < 24; ++i) {
    xyz[i] = kCubeXyz[i];
    xyz[24 + i] = kCubeXyz[i] + 0.5;
  }
  for (i = 0; i < 36; ++i) {
    tri[i] = kCubeTri[i];
    tri[36 + i] = kCubeTri[i] + 8;
  }
  assert_int_equal(anitet_surface_create(xyz, 16, tri, 24, NULL, 0, &s), ANITET_OK);
  rc = anitet_surface_validate(s, NULL);
  assert_true(rc == ANITET_ERR_INTERSECTING_SHELLS || rc == ANITET_ERR_SELF_INTERSECTION);
  assert_int_equal(anitet_surface_problem_count(s, rc, &count), ANITET_OK);
  assert_true(count > 0);
  anitet_surface_destroy(s);
}

static void test_surface_validate_bad_options_version(void** state) {
  anitet_surface* s = make_cube();
  anitet_options o = ANITET_OPTIONS_INIT;
  (void)state;
  o.version = 99;
  assert_int_equal(anitet_surface_validate(s, &o), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "version 99"));
  anitet_surface_destroy(s);
}

struct progress_record {
  int calls;
  int cancel_at; /* cancel on this call (1-based), 0: never */
  double last_fraction;
  char stage[32];
};

static int record_progress(double fraction, const char* stage, void* user_data) {
  struct progress_record* r = (struct progress_record*)user_data;
  r->calls++;
  r->last_fraction = fraction;
  strncpy(r->stage, stage, sizeof r->stage - 1);
  return r->calls == r->cancel_at;
}

static void count_log(int32_t level, const char* message, void* user_data) {
  (void)level;
  assert_non_null(message);
  (*(int*)user_data)++;
}

static void test_callbacks_progress_log_cancel(void** state) {
  anitet_surface* s = make_cube();
  anitet_surface* inverted = NULL;
  anitet_options o = ANITET_OPTIONS_INIT;
  struct progress_record rec;
  int logs = 0, i;
  int32_t flipped[36];
  (void)state;
  memset(&rec, 0, sizeof rec);
  o.progress = record_progress;
  o.progress_user_data = &rec;
  assert_int_equal(anitet_surface_validate(s, &o), ANITET_OK);
  assert_int_equal(rec.calls, 2);
  assert_true(rec.last_fraction == 1.0);
  assert_string_equal(rec.stage, "validate");
  /* Cancel on the first call, then on the last one. */
  memset(&rec, 0, sizeof rec);
  rec.cancel_at = 1;
  assert_int_equal(anitet_surface_validate(s, &o), ANITET_ERR_CANCELLED);
  assert_true(contains(anitet_last_error_message(), "cancelled"));
  memset(&rec, 0, sizeof rec);
  rec.cancel_at = 2;
  assert_int_equal(anitet_surface_validate(s, &o), ANITET_ERR_CANCELLED);
  /* Log: an inside-out cube is flipped, and the repair is logged. */
  for (i = 0; i < 12; ++i) {
    flipped[3 * i] = kCubeTri[3 * i];
    flipped[3 * i + 1] = kCubeTri[3 * i + 2];
    flipped[3 * i + 2] = kCubeTri[3 * i + 1];
  }
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, flipped, 12, NULL, 0, &inverted), ANITET_OK);
  o.progress = NULL;
  o.log = count_log;
  o.log_user_data = &logs;
  assert_int_equal(anitet_surface_validate(inverted, &o), ANITET_OK);
  assert_true(logs >= 1);
  assert_int_equal(anitet_surface_get_triangles(inverted, flipped, 36, 0), ANITET_OK);
  assert_memory_equal(flipped, kCubeTri, sizeof flipped);
  anitet_surface_destroy(inverted);
  anitet_surface_destroy(s);
}

/* ---- metrics (the mesher: test_capi_mesher.c) ----------------------------------------------- */

static int stretched(double x, double y, double z, double m[6], void* user_data) {
  const double k = *(const double*)user_data;
  (void)y;
  if (z < 0) return 7;
  m[0] = k * (1.0 + x);
  m[1] = 0;
  m[2] = 1;
  m[3] = 0;
  m[4] = 0;
  m[5] = 1;
  return 0;
}

static void test_metric(void** state) {
  anitet_metric* m = NULL;
  double t[6];
  double k = 4.0;
  anitet_mesh* box = NULL;
  const double values[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  (void)state;
  assert_int_equal(anitet_metric_create_uniform(0.5, &m), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(m, 1, 2, 3, t), ANITET_OK);
  assert_true(t[0] == 4.0 && t[2] == 4.0 && t[5] == 4.0 && t[1] == 0.0 && t[3] == 0.0 && t[4] == 0.0);
  assert_int_equal(anitet_metric_evaluate(m, 1, 2, 3, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_evaluate(NULL, 1, 2, 3, t), ANITET_ERR_INVALID_ARGUMENT);
  anitet_metric_destroy(m);
  m = (anitet_metric*)1;
  assert_int_equal(anitet_metric_create_uniform(0.0, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_int_equal(anitet_metric_create_uniform(-1.0, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_create_uniform(1.0, NULL), ANITET_ERR_INVALID_ARGUMENT);

  assert_int_equal(anitet_metric_create_analytic(stretched, &k, &m), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(m, 1, 0, 0, t), ANITET_OK);
  assert_true(t[0] == 8.0 && t[2] == 1.0);
  assert_int_equal(anitet_metric_evaluate(m, 1, 0, -1, t), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "returned 7"));
  anitet_metric_destroy(m);
  assert_int_equal(anitet_metric_create_analytic(NULL, &k, &m), ANITET_ERR_INVALID_ARGUMENT);

  /* Files and per-point values: test_capi_metric.c has the full tests. */
  assert_int_equal(anitet_metric_read(ANITET_TEST_DATA_DIR "/no_such_size.vdb", NULL, &m), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "no_such_size.vdb"));
  assert_int_equal(anitet_metric_read(NULL, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_read(BOX_MESH, &box), ANITET_OK);
  assert_int_equal(anitet_metric_create_from_points(box, values, 8, 1, &m), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(m, 0.5, 0.05, 1.0, t), ANITET_OK);
  assert_true(fabs(t[0] - 1.0) < 1e-12 && fabs(t[2] - 1.0) < 1e-12 && fabs(t[5] - 1.0) < 1e-12);
  anitet_metric_destroy(m);
  m = NULL;
  assert_int_equal(anitet_metric_create_from_points(box, values, 8, 3, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_metric_create_from_points(NULL, values, 8, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh_destroy(box);
  anitet_metric_destroy(NULL);
}

/* ---- volume meshes -------------------------------------------------------------------------- */

static void test_mesh_read_and_fill(void** state) {
  anitet_mesh* m = NULL;
  int64_t np = 0, nt = 0, nb = 0;
  double xyz[24];
  int32_t tets[24], tets1[24], regions[6], tri[36], patch[12], comps = -1;
  int i;
  (void)state;
  assert_int_equal(anitet_mesh_read(BOX_MESH, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(m, &np, &nt, &nb), ANITET_OK);
  assert_int_equal(np, 8);
  assert_int_equal(nt, 6);
  assert_int_equal(nb, 12);
  assert_int_equal(anitet_mesh_get_counts(m, NULL, NULL, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_points(m, xyz, 24), ANITET_OK);
  assert_true(xyz[3] == 1.5 && xyz[2] == -0.25);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 24, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tets(m, tets1, 24, 1), ANITET_OK);
  /* The file's first tet is "1 2 4 8" (1-based). */
  assert_int_equal(tets1[0], 1);
  assert_int_equal(tets1[3], 8);
  for (i = 0; i < 24; ++i) assert_int_equal(tets1[i], tets[i] + 1);
  assert_int_equal(anitet_mesh_get_regions(m, regions, 6), ANITET_OK);
  assert_int_equal(regions[0], 1);
  assert_int_equal(regions[5], 2);
  assert_int_equal(anitet_mesh_get_boundary_triangles(m, tri, 36, 1), ANITET_OK);
  assert_int_equal(tri[0], 1);
  assert_int_equal(tri[1], 7);
  assert_int_equal(anitet_mesh_get_boundary_patches(m, patch, 12), ANITET_OK);
  assert_int_equal(patch[0], 1);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 0);
  assert_int_equal(anitet_mesh_get_metric(m, NULL, 0), ANITET_OK);
  anitet_mesh_destroy(m);
}

static void test_mesh_accessor_errors(void** state) {
  anitet_mesh* m = NULL;
  double xyz[24];
  int32_t buf[36];
  (void)state;
  assert_int_equal(anitet_mesh_read(BOX_MESH, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_get_points(m, xyz, 23), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_points(m, NULL, 24), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_tets(m, buf, 23, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_true(contains(anitet_last_error_message(), "24 needed"));
  assert_int_equal(anitet_mesh_get_tets(m, buf, 24, 2), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_regions(m, buf, 5), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_boundary_triangles(m, buf, 35, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_boundary_triangles(m, buf, 36, 7), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_boundary_patches(m, buf, 11), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_metric_components(m, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_counts(NULL, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_points(NULL, xyz, 24), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_tets(NULL, buf, 24, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_regions(NULL, buf, 6), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_boundary_triangles(NULL, buf, 36, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_boundary_patches(NULL, buf, 12), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_metric_components(NULL, buf), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_metric(NULL, xyz, 8), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh_destroy(m);
  anitet_mesh_destroy(NULL);
  m = (anitet_mesh*)1;
  assert_int_equal(anitet_mesh_read(ANITET_TEST_DATA_DIR "/io/missing.mesh", &m), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(m);
  assert_int_equal(anitet_mesh_read(NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_read(BOX_MESH, NULL), ANITET_ERR_INVALID_ARGUMENT);
}

/* One regular-ish tet, 1-based, with its four faces as boundary triangles. */
static const double kTetXyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const int32_t kTet1[4] = {1, 2, 3, 4};
static const int32_t kTetFaces1[12] = {1, 3, 2, 1, 2, 4, 2, 3, 4, 1, 4, 3};

static void test_mesh_create(void** state) {
  anitet_mesh* m = NULL;
  int32_t tets[4], regions[1], bad[4] = {1, 2, 3, 5}, bad_tri[3] = {1, 2, 9};
  int64_t nb = -1;
  (void)state;
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, NULL, 0, NULL, 1, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(m, NULL, NULL, &nb), ANITET_OK);
  assert_int_equal(nb, 0);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 4, 0), ANITET_OK);
  assert_int_equal(tets[0], 0);
  assert_int_equal(tets[3], 3);
  assert_int_equal(anitet_mesh_get_regions(m, regions, 1), ANITET_OK);
  assert_int_equal(regions[0], 0);
  anitet_mesh_destroy(m);
  m = (anitet_mesh*)1;
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, bad, 1, NULL, NULL, 0, NULL, 1, &m), ANITET_ERR_BAD_INDEX);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "tet 1 refers to vertex 5"));
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, NULL, 0, NULL, 0, &m), ANITET_ERR_BAD_INDEX);
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, bad_tri, 1, NULL, 1, &m), ANITET_ERR_BAD_INDEX);
  assert_true(contains(anitet_last_error_message(), "boundary triangle 1 refers to vertex 9"));
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, NULL, 1, NULL, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 0, NULL, NULL, 0, NULL, 1, &m), ANITET_ERR_EMPTY_INPUT);
  assert_int_equal(anitet_mesh_create(NULL, 4, kTet1, 1, NULL, NULL, 0, NULL, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, NULL, 1, NULL, NULL, 0, NULL, 1, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, NULL, 0, NULL, 3, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, NULL, 0, NULL, 1, NULL), ANITET_ERR_INVALID_ARGUMENT);
}

static void test_mesh_write(void** state) {
  anitet_mesh* m = NULL;
  anitet_mesh* back = NULL;
  char path[512];
  int64_t np = 0, nt = 0;
  (void)state;
  assert_int_equal(anitet_mesh_read(BOX_MESH, &m), ANITET_OK);
  snprintf(path, sizeof path, "%s/capi_write_test.vtu", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  assert_int_equal(anitet_mesh_read(path, &back), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(back, &np, &nt, NULL), ANITET_OK);
  assert_int_equal(np, 8);
  assert_int_equal(nt, 6);
  remove(path);
  snprintf(path, sizeof path, "%s/capi_write_test.xyz", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_int_equal(anitet_mesh_write(m, "/nonexistent-dir/x.mesh"), ANITET_ERR_FILE_NOT_FOUND);
  assert_int_equal(anitet_mesh_write(m, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_write(NULL, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_write_metric(m, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "no per-vertex metric"));
  assert_int_equal(anitet_mesh_write_metric(NULL, path), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh_destroy(back);
  anitet_mesh_destroy(m);
}

static void test_mesh_metric(void** state) {
  anitet_mesh* m = NULL;
  anitet_mesh* back = NULL;
  double sizes[8] = {1, 2, 3, 4, 5, 6, 7, 8}, got[8], tensors[48];
  int32_t comps = -1;
  char path[512];
  int i;
  (void)state;
  assert_int_equal(anitet_mesh_read(BOX_MESH, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_set_metric(m, sizes, 8, 1), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 1);
  assert_int_equal(anitet_mesh_get_metric(m, got, 7), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_metric(m, got, 8), ANITET_OK);
  assert_memory_equal(got, sizes, sizeof got);
  snprintf(path, sizeof path, "%s/capi_metric_test.sol", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write_metric(m, path), ANITET_OK);
  remove(path);
  /* Errors: wrong length, wrong components, non-positive size, NaN tensor. */
  assert_int_equal(anitet_mesh_set_metric(m, sizes, 7, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "8 expected"));
  assert_int_equal(anitet_mesh_set_metric(m, sizes, 8, 3), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_metric(m, NULL, 8, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_metric(NULL, sizes, 8, 1), ANITET_ERR_INVALID_ARGUMENT);
  sizes[3] = 0.0;
  assert_int_equal(anitet_mesh_set_metric(m, sizes, 8, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "point 3"));
  for (i = 0; i < 48; ++i) tensors[i] = (i % 6 == 0 || i % 6 == 2 || i % 6 == 5) ? 1.0 : 0.0;
  assert_int_equal(anitet_mesh_set_metric(m, tensors, 48, 6), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 6);
  /* The metric travels with the mesh through a .vtu (written as point data). */
  snprintf(path, sizeof path, "%s/capi_metric_test.vtu", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  assert_int_equal(anitet_mesh_read(path, &back), ANITET_OK);
  remove(path);
  anitet_mesh_destroy(back);
  tensors[13] = NAN;
  assert_int_equal(anitet_mesh_set_metric(m, tensors, 48, 6), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not finite"));
  assert_int_equal(anitet_mesh_set_metric(m, NULL, 0, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 0);
  anitet_mesh_destroy(m);
}

static void test_quality(void** state) {
  anitet_mesh* m = NULL;
  anitet_surface* faces = NULL;
  anitet_quality q = ANITET_QUALITY_INIT;
  int64_t needed = 0, needed2 = 0;
  char small[8];
  char* json;
  (void)state;
  assert_int_equal(anitet_mesh_create(kTetXyz, 4, kTet1, 1, NULL, kTetFaces1, 4, NULL, 1, &m), ANITET_OK);
  assert_int_equal(anitet_surface_create(kTetXyz, 4, kTetFaces1, 4, NULL, 1, &faces), ANITET_OK);
  assert_int_equal(anitet_mesh_quality(m, faces, &q), ANITET_OK);
  assert_int_equal(q.version, ANITET_QUALITY_VERSION);
  assert_int_equal(q.tets, 1);
  assert_int_equal(q.vertices, 4);
  assert_int_equal(q.nonpositive_tets, 0);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  /* The corner tet: radius ratio 3(sqrt(3)-1)/... ~ 0.732, right dihedral angles of 90 degrees. */
  assert_true(q.radius_ratio_min > 0.7 && q.radius_ratio_min < 0.75);
  assert_true(q.radius_ratio_mean == q.radius_ratio_min);
  assert_true(q.max_dihedral_deg > 89.9 && q.max_dihedral_deg < 90.1);
  assert_true(q.min_dihedral_deg > 54.0 && q.min_dihedral_deg < 55.0);
  assert_true(q.good_fraction == 1.0 && q.bad_fraction == 0.0);
  assert_true(q.mean_ratio_min > 0.0 && q.mean_ratio_min <= 1.0);
  /* Without the input surface, nothing is claimed about it. */
  assert_int_equal(anitet_mesh_quality(m, NULL, &q), ANITET_OK);
  assert_int_equal(q.boundary_constrained, 0);
  q.version = 0;
  assert_int_equal(anitet_mesh_quality(m, NULL, &q), ANITET_ERR_INVALID_ARGUMENT);
  q.version = ANITET_QUALITY_VERSION + 1;
  assert_int_equal(anitet_mesh_quality(m, NULL, &q), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_quality(NULL, NULL, &q), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_quality(m, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* JSON. */
  assert_int_equal(anitet_mesh_quality_json(m, faces, NULL, 0, &needed), ANITET_OK);
  assert_true(needed > 10);
  assert_int_equal(anitet_mesh_quality_json(m, faces, small, sizeof small, &needed2), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(needed2, needed);
  assert_int_equal(anitet_mesh_quality_json(m, faces, NULL, 5, &needed2), ANITET_ERR_INVALID_ARGUMENT);
  json = malloc((size_t)needed);
  assert_non_null(json);
  assert_int_equal(anitet_mesh_quality_json(m, faces, json, needed, NULL), ANITET_OK);
  assert_int_equal((int64_t)strlen(json) + 1, needed);
  assert_true(contains(json, "\"tets\""));
  free(json);
  assert_int_equal(anitet_mesh_quality_json(NULL, NULL, NULL, 0, &needed), ANITET_ERR_INVALID_ARGUMENT);
  anitet_surface_destroy(faces);
  anitet_mesh_destroy(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_version),
      cmocka_unit_test(test_error_names),
      cmocka_unit_test(test_options_init),
      cmocka_unit_test(test_surface_create_and_read_back),
      cmocka_unit_test(test_surface_create_index_base_1),
      cmocka_unit_test(test_surface_create_errors),
      cmocka_unit_test(test_surface_accessor_errors),
      cmocka_unit_test(test_surface_read),
      cmocka_unit_test(test_surface_validate_clean),
      cmocka_unit_test(test_surface_validate_open),
      cmocka_unit_test(test_surface_validate_intersection),
      cmocka_unit_test(test_surface_validate_bad_options_version),
      cmocka_unit_test(test_callbacks_progress_log_cancel),
      cmocka_unit_test(test_metric),
      cmocka_unit_test(test_mesh_read_and_fill),
      cmocka_unit_test(test_mesh_accessor_errors),
      cmocka_unit_test(test_mesh_create),
      cmocka_unit_test(test_mesh_write),
      cmocka_unit_test(test_mesh_metric),
      cmocka_unit_test(test_quality),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
