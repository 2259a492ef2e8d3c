/* The C ABI's versions 3 to 5 of anitet_options (the options of `anitet mesh`: boundary layer,
 * its slide patches and sizing, size bounds, recovery strategy, retries, tet cap) and what a run
 * returns (anitet_run_stats, anitet_mesh_run_json), patch names and types for the written
 * files; every documented error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"
#include "sphere_surface.h" /* examples/c: the surface every example meshes */

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

/* The unit sphere (patches 1-3) inside the box [-3, 3]^3 (patch 4): the sphere is a wall. */
enum { BOX_NPOINTS = SPHERE_NPOINTS + 8, BOX_NTRI = SPHERE_NTRI + 12 };
static double g_xyz[3 * BOX_NPOINTS];
static int32_t g_tri[3 * BOX_NTRI], g_patch[BOX_NTRI];

static anitet_surface* make_sphere_in_box(void) {
  static const int32_t box_tri[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  anitet_surface* s = NULL;
  int i;
  sphere_build(g_xyz, g_tri, g_patch);
  for (i = 0; i < 8; ++i) {
    double* p = &g_xyz[3 * (SPHERE_NPOINTS + i)];
    p[0] = (i & 1) ? 3.0 : -3.0, p[1] = (i & 2) ? 3.0 : -3.0, p[2] = (i & 4) ? 3.0 : -3.0;
  }
  for (i = 0; i < 36; ++i) g_tri[3 * SPHERE_NTRI + i] = SPHERE_NPOINTS + box_tri[i];
  for (i = 0; i < 12; ++i) g_patch[SPHERE_NTRI + i] = 4;
  assert_int_equal(anitet_surface_create(g_xyz, BOX_NPOINTS, g_tri, BOX_NTRI, g_patch, 0, &s), ANITET_OK);
  return s;
}

static anitet_mesh* run_ok(const anitet_surface* s, const anitet_options* o) {
  anitet_mesh* m = NULL;
  const int rc = anitet_mesher_run(s, NULL, o, &m);
  if (rc != ANITET_OK) fail_msg("anitet_mesher_run: %s", anitet_last_error_message());
  assert_non_null(m);
  return m;
}

static int64_t tets_of(const anitet_mesh* m) {
  int64_t nt = 0;
  assert_int_equal(anitet_mesh_get_counts(m, NULL, &nt, NULL), ANITET_OK);
  return nt;
}

static char* run_json(const anitet_mesh* m) {
  int64_t needed = 0;
  char* text;
  assert_int_equal(anitet_mesh_run_json(m, NULL, 0, &needed), ANITET_OK);
  assert_true(needed > 1);
  text = malloc((size_t)needed);
  assert_non_null(text);
  assert_int_equal(anitet_mesh_run_json(m, text, needed - 1, NULL), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_run_json(m, text, needed, NULL), ANITET_OK);
  assert_int_equal((int64_t)strlen(text) + 1, needed);
  return text;
}

/* ---- options, version 3 --------------------------------------------------------------------- */

static void test_options_v3_defaults(void** state) {
  anitet_options a = ANITET_OPTIONS_INIT, b;
  (void)state;
  memset(&b, 0x5a, sizeof b);
  assert_int_equal(anitet_options_init(&b, 3), ANITET_OK);
  assert_int_equal(b.version, 3);
  assert_true(b.attempts_seconds == 240.0);
  assert_int_equal(b.retry_layer_counts, 1);
  assert_int_equal(b.recovery, ANITET_RECOVERY_ALL);
  assert_true(b.hmin == 0.0 && b.hmax == 0.0 && b.hgrad == 0.0 && b.max_tets == 0.0);
  assert_int_equal(b.anisotropic_cycles, 2);
  assert_int_equal(b.bl_num_patches, 0);
  assert_null(b.bl_patches);
  assert_true(b.bl_first_height == 0.0 && b.bl_growth == 1.2);
  assert_int_equal(b.bl_layers, 10);
  assert_int_equal(b.bl_sizing, 0);
  assert_int_equal(b.push_tasks_min_vertices, 2000);
  assert_int_equal(b.bl_mitre, 0);
  assert_int_equal(a.push_tasks_min_vertices, 2000);
  /* The initializer and the function agree field by field. */
  assert_true(a.attempts_seconds == b.attempts_seconds && a.bl_growth == b.bl_growth);
  assert_int_equal(a.retry_layer_counts, b.retry_layer_counts);
  assert_int_equal(a.anisotropic_cycles, b.anisotropic_cycles);
  assert_int_equal(a.bl_layers, b.bl_layers);
  assert_null(a.bl_patches);
}

/* A caller compiled against version 2: its struct ends after size_scale. The library writes
 * nothing past it and reads nothing past it (garbage there, which would be invalid as version 3
 * fields, does not matter: a version 2 caller gets version 3's defaults). */
static void test_options_v2_caller(void** state) {
  const size_t v2_size = offsetof(anitet_options, attempts_seconds);
  anitet_options o;
  const unsigned char* bytes = (const unsigned char*)&o;
  anitet_surface* s = make_sphere_in_box();
  anitet_mesh *a, *b;
  size_t i;
  (void)state;
  assert_int_equal(v2_size, offsetof(anitet_options, size_scale) + sizeof(double));
  memset(&o, 0xff, sizeof o);
  assert_int_equal(anitet_options_init(&o, 2), ANITET_OK);
  assert_int_equal(o.version, 2);
  assert_true(o.size_scale == 1.0);
  for (i = v2_size; i < sizeof o; ++i) assert_int_equal(bytes[i], 0xff);
  a = run_ok(s, &o);
  b = run_ok(s, NULL);
  assert_int_equal(tets_of(a), tets_of(b));
  anitet_mesh_destroy(a);
  anitet_mesh_destroy(b);
  anitet_surface_destroy(s);
}

static void expect_bad(const anitet_surface* s, const anitet_options* o, const char* words) {
  anitet_mesh* m = (anitet_mesh*)1;
  assert_int_equal(anitet_mesher_run(s, NULL, o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  if (!contains(anitet_last_error_message(), words))
    fail_msg("message '%s' lacks '%s'", anitet_last_error_message(), words);
}

static void test_options_v3_errors(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3}, unknown_wall[1] = {7};
  anitet_options o = ANITET_OPTIONS_INIT;
  (void)state;
  o.attempts_seconds = -1.0;
  expect_bad(s, &o, "attempts_seconds");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.recovery = 3;
  expect_bad(s, &o, "recovery is 3");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.hmin = 2.0, o.hmax = 1.0;
  expect_bad(s, &o, "hmin");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.hgrad = 0.5;
  expect_bad(s, &o, "hgrad");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.hmax = NAN;
  expect_bad(s, &o, "hmax");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.max_tets = -1.0;
  expect_bad(s, &o, "max_tets");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.anisotropic_cycles = 11;
  expect_bad(s, &o, "anisotropic_cycles is 11");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.bl_num_patches = -1;
  expect_bad(s, &o, "bl_num_patches");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.bl_num_patches = 3, o.bl_patches = NULL, o.bl_first_height = 0.02;
  expect_bad(s, &o, "bl_patches is NULL");
  o.bl_patches = walls, o.bl_first_height = 0.0;
  expect_bad(s, &o, "bl_first_height");
  o.bl_first_height = 0.02, o.bl_growth = 0.5;
  expect_bad(s, &o, "bl_growth");
  o.bl_growth = 1.2, o.bl_layers = 0;
  expect_bad(s, &o, "bl_layers");
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.bl_sizing = 1;
  expect_bad(s, &o, "bl_sizing");
  /* A wall label that no triangle has is an error, not ignored. */
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.bl_num_patches = 1, o.bl_patches = unknown_wall, o.bl_first_height = 0.02;
  expect_bad(s, &o, "wall patch label 7");
  /* A tet cap below what the field asks for: refused before refinement, with the estimate. */
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.hmax = 0.2, o.max_tets = 100.0;
  expect_bad(s, &o, "100");
  anitet_surface_destroy(s);
}

/* ---- what a run did ------------------------------------------------------------------------- */

static void test_run_stats_plain(void** state) {
  anitet_surface* s = make_sphere_in_box();
  anitet_mesh* m = run_ok(s, NULL);
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  int64_t np = 0, nt = 0;
  char* json;
  (void)state;
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_string_equal(anitet_last_error_message(), "");
  assert_int_equal(st.version, ANITET_RUN_STATS_VERSION);
  assert_int_equal(anitet_mesh_get_counts(m, &np, &nt, NULL), ANITET_OK);
  assert_int_equal(st.vertices, np);
  assert_int_equal(st.tets, nt);
  assert_int_equal(st.layers_used, 1);
  assert_true(st.recovery_strategy == ANITET_RECOVERY_SPLIT || st.recovery_strategy == ANITET_RECOVERY_FUZZY);
  assert_true(st.refine_passes >= 1);
  assert_true(st.seconds > 0.0);
  assert_true(st.edges_in_range > 0.0 && st.edges_in_range <= 1.0);
  assert_int_equal(st.bl_layers, 0);
  assert_int_equal(st.bl_wall_vertices, 0);
  json = run_json(m);
  assert_true(json[0] == '{');
  assert_true(contains(json, "\"stages\""));
  assert_true(contains(json, "\"recovery\""));
  assert_true(contains(json, "\"notices\""));
  free(json);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

/* A caller compiled against version 1 of anitet_run_stats: nothing written past its end, the
 * same version 1 figures; version 2's slide figures 0 without slide patches. */
static void test_run_stats_v1_caller(void** state) {
  anitet_surface* s = NULL;
  anitet_mesh* m;
  anitet_run_stats v1, v2, v3 = ANITET_RUN_STATS_INIT;
  const size_t v1_size = offsetof(anitet_run_stats, slide_junction_columns);
  const size_t v2_size = offsetof(anitet_run_stats, bl_prisms);
  const unsigned char* bytes = (const unsigned char*)&v1;
  size_t i;
  (void)state;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 12, kCubePatch, 0, &s), ANITET_OK);
  m = run_ok(s, NULL);
  assert_int_equal(ANITET_RUN_STATS_VERSION, 3);
  assert_int_equal(v1_size, offsetof(anitet_run_stats, bl_max_height_error) + sizeof(double));
  memset(&v1, 0xff, sizeof v1);
  v1.version = 1;
  assert_int_equal(anitet_mesh_get_run_stats(m, &v1), ANITET_OK);
  assert_int_equal(anitet_mesh_get_run_stats(m, &v3), ANITET_OK);
  for (i = v1_size; i < sizeof v1; ++i) assert_int_equal(bytes[i], 0xff);
  assert_int_equal(v1.version, 1);
  v1.version = 3;
  assert_memory_equal(&v1, &v3, v1_size);
  /* A version 2 caller: nothing written past slide_triangles_added. */
  memset(&v2, 0xff, sizeof v2);
  v2.version = 2;
  assert_int_equal(anitet_mesh_get_run_stats(m, &v2), ANITET_OK);
  for (i = v2_size; i < sizeof v2; ++i) assert_int_equal(((const unsigned char*)&v2)[i], 0xff);
  v2.version = 3;
  assert_memory_equal(&v2, &v3, v2_size);
  assert_int_equal(v3.slide_junction_columns, 0);
  assert_int_equal(v3.slide_lowered_columns, 0);
  assert_int_equal(v3.slide_triangles_added, 0);
  assert_int_equal(v3.bl_prisms, 0);
  assert_int_equal(v3.bl_prism_tets_left, 0);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

static void test_run_stats_errors(void** state) {
  anitet_surface* s = make_sphere_in_box();
  anitet_mesh *m = run_ok(s, NULL), *made = NULL;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  int64_t needed = -1;
  char buf[8];
  (void)state;
  assert_int_equal(anitet_mesh_get_run_stats(NULL, &st), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "mesh is NULL"));
  assert_int_equal(anitet_mesh_get_run_stats(m, NULL), ANITET_ERR_INVALID_ARGUMENT);
  st.version = 0;
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "version 0"));
  st.version = ANITET_RUN_STATS_VERSION + 1;
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_run_json(NULL, buf, sizeof buf, &needed), ANITET_ERR_INVALID_ARGUMENT);
  /* A mesh from arrays was made by no run. */
  assert_int_equal(anitet_mesh_create(kCubeXyz, 8, (const int32_t[]){0, 1, 3, 4}, 1, NULL, NULL, 0, NULL, 0, &made),
                   ANITET_OK);
  st.version = ANITET_RUN_STATS_VERSION;
  assert_int_equal(anitet_mesh_get_run_stats(made, &st), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not made by anitet_mesher_run"));
  assert_int_equal(anitet_mesh_run_json(made, buf, sizeof buf, &needed), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh_destroy(made);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

/* A boundary layer on the sphere: its report through the stats and the JSON. */
static void test_boundary_layer(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_quality q = ANITET_QUALITY_INIT;
  anitet_mesh* m;
  char* json;
  (void)state;
  o.bl_num_patches = 3, o.bl_patches = walls;
  o.bl_first_height = 0.02, o.bl_growth = 1.25, o.bl_layers = 4;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.bl_layers, 4);
  assert_int_equal(st.bl_wall_vertices, SPHERE_NPOINTS);
  assert_int_equal(st.bl_full_columns, SPHERE_NPOINTS);
  assert_true(st.bl_nominal_columns >= SPHERE_NPOINTS * 9 / 10);
  assert_true(st.bl_tets >= 3 * 4 * SPHERE_NTRI);
  assert_true(fabs(st.bl_first_height_mean - 0.02) < 0.002);
  assert_true(st.bl_first_height_min > 0.0 && st.bl_first_height_min <= st.bl_first_height_max);
  assert_true(fabs(st.bl_growth_mean - 1.25) < 0.05);
  assert_true(st.bl_max_height_error <= 0.1);
  json = run_json(m);
  assert_true(contains(json, "\"boundary_layer\""));
  assert_true(contains(json, "\"columns_reaching\""));
  free(json);
  assert_int_equal(anitet_mesh_quality(m, s, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

/* hmax, the recovery strategy and the retry switch reach the pipeline. */
static void test_options_v3_used(void** state) {
  anitet_surface* s = make_sphere_in_box();
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_mesh *plain = run_ok(s, NULL), *m;
  (void)state;
  o.hmax = 0.4;
  m = run_ok(s, &o);
  assert_true(tets_of(m) > 2 * tets_of(plain));
  anitet_mesh_destroy(m);
  o = (anitet_options)ANITET_OPTIONS_INIT;
  o.recovery = ANITET_RECOVERY_FUZZY;
  o.retry_layer_counts = 0;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.recovery_strategy, ANITET_RECOVERY_FUZZY);
  assert_int_equal(st.layers_retries, 0);
  anitet_mesh_destroy(m);
  o.recovery = ANITET_RECOVERY_SPLIT;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.recovery_strategy, ANITET_RECOVERY_SPLIT);
  anitet_mesh_destroy(m);
  anitet_mesh_destroy(plain);
  anitet_surface_destroy(s);
}

/* ---- patch names ---------------------------------------------------------------------------- */

static int64_t read_file(const char* path, char* text, size_t size) {
  FILE* f = fopen(path, "rb");
  size_t n;
  if (!f) return -1;
  n = fread(text, 1, size - 1, f);
  fclose(f);
  text[n] = '\0';
  return (int64_t)n;
}

static int file_contains(const char* path, const char* part) {
  static char text[1 << 20];
  return read_file(path, text, sizeof text) >= 0 && contains(text, part);
}

static void test_patch_names(void** state) {
  anitet_surface* s = make_sphere_in_box();
  anitet_mesh* m = run_ok(s, NULL);
  char path[4096];
  (void)state;
  snprintf(path, sizeof path, "%s/capi_patch_names.su2", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_set_patch_name(m, 4, "farfield"), ANITET_OK);
  assert_int_equal(anitet_mesh_set_patch_name(m, 2, "sphere_band"), ANITET_OK);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  assert_true(file_contains(path, "MARKER_TAG= farfield"));
  assert_true(file_contains(path, "MARKER_TAG= sphere_band"));
  assert_true(file_contains(path, "MARKER_TAG= patch1"));
  /* NULL removes a name. */
  assert_int_equal(anitet_mesh_set_patch_name(m, 2, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  assert_true(file_contains(path, "MARKER_TAG= patch2"));
  assert_false(file_contains(path, "sphere_band"));
  /* Errors: NULL mesh, an invalid name, a label no boundary triangle has. */
  assert_int_equal(anitet_mesh_set_patch_name(NULL, 4, "farfield"), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_name(m, 4, "9lives"), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_name(m, 4, "far field"), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_name(m, 4, ""), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_name(m, 9, "wall"), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "9"));
  /* Two labels with one name: the write says so and writes nothing. */
  assert_int_equal(anitet_mesh_set_patch_name(m, 1, "farfield"), ANITET_OK);
  remove(path);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "farfield"));
  assert_false(file_contains(path, "NELEM"));
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

/* ---- patch types ---------------------------------------------------------------------------- */

/* The OpenFOAM boundary file's entry of `patch` has type `type`. */
static void expect_foam_type(const char* boundary, const char* patch, const char* type) {
  char entry[256];
  snprintf(entry, sizeof entry, "    %s\n    {\n        type            %s;\n", patch, type);
  if (!contains(boundary, entry)) fail_msg("no '%s' of type %s in:\n%s", patch, type, boundary);
}

/* The box of tests/data/io/box.mesh: six planar faces, patches 1-6. */
static void test_patch_types(void** state) {
  anitet_mesh* m = NULL;
  static char boundary[1 << 16];
  char dir[4096], path[4200];
  int32_t type = -7;
  (void)state;
  snprintf(path, sizeof path, "%s/io/box.mesh", ANITET_TEST_DATA_DIR);
  assert_int_equal(anitet_mesh_read(path, &m), ANITET_OK);
  /* Without a type: the one the name implies (patch<label>: a wall). */
  assert_int_equal(anitet_mesh_get_patch_type(m, 4, &type), ANITET_OK);
  assert_int_equal(type, ANITET_PATCH_TYPE_WALL);
  assert_int_equal(anitet_mesh_set_patch_name(m, 4, "farfield"), ANITET_OK);
  assert_int_equal(anitet_mesh_get_patch_type(m, 4, &type), ANITET_OK);
  assert_int_equal(type, ANITET_PATCH_TYPE_FARFIELD);
  /* A type set wins over the name, FROM_NAME removes it. */
  assert_int_equal(anitet_mesh_set_patch_type(m, 4, ANITET_PATCH_TYPE_SYMMETRY), ANITET_OK);
  assert_int_equal(anitet_mesh_get_patch_type(m, 4, &type), ANITET_OK);
  assert_int_equal(type, ANITET_PATCH_TYPE_SYMMETRY);
  assert_int_equal(anitet_mesh_set_patch_type(m, 1, ANITET_PATCH_TYPE_INLET), ANITET_OK);
  assert_int_equal(anitet_mesh_set_patch_type(m, 3, ANITET_PATCH_TYPE_PATCH), ANITET_OK);
  assert_int_equal(anitet_mesh_set_patch_type(m, 3, ANITET_PATCH_TYPE_FROM_NAME), ANITET_OK);
  assert_int_equal(anitet_mesh_get_patch_type(m, 3, &type), ANITET_OK);
  assert_int_equal(type, ANITET_PATCH_TYPE_WALL);
  /* In the written files: OpenFOAM's boundary (face 4 is planar: a symmetry plane). */
  snprintf(dir, sizeof dir, "%s/capi_patch_types/constant/polyMesh", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, dir), ANITET_OK);
  snprintf(path, sizeof path, "%s/boundary", dir);
  assert_true(read_file(path, boundary, sizeof boundary) > 0);
  expect_foam_type(boundary, "farfield", "symmetryPlane");
  expect_foam_type(boundary, "patch1", "patch");
  expect_foam_type(boundary, "patch2", "wall");
  expect_foam_type(boundary, "patch3", "wall");
  /* Errors: NULLs, an unknown type, a label no boundary triangle has. */
  assert_int_equal(anitet_mesh_set_patch_type(NULL, 4, ANITET_PATCH_TYPE_WALL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_type(m, 4, 6), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "type is 6"));
  assert_int_equal(anitet_mesh_set_patch_type(m, 4, -2), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_set_patch_type(m, 9, ANITET_PATCH_TYPE_WALL), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "patch label 9"));
  assert_int_equal(anitet_mesh_get_patch_type(m, 9, &type), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_patch_type(m, 4, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_patch_type(NULL, 4, &type), ANITET_ERR_INVALID_ARGUMENT);
  /* The type stays as set after a failed call. */
  assert_int_equal(anitet_mesh_get_patch_type(m, 4, &type), ANITET_OK);
  assert_int_equal(type, ANITET_PATCH_TYPE_SYMMETRY);
  anitet_mesh_destroy(m);
}

/* ---- options, version 4: slide patches ------------------------------------------------------ */

static void test_options_v4_defaults(void** state) {
  anitet_options a = ANITET_OPTIONS_INIT, b, v3;
  const size_t v3_size = offsetof(anitet_options, bl_num_slide_patches);
  const unsigned char* bytes = (const unsigned char*)&v3;
  size_t i;
  (void)state;
  memset(&b, 0x5a, sizeof b);
  assert_int_equal(anitet_options_init(&b, 4), ANITET_OK);
  assert_int_equal(b.version, 4);
  assert_int_equal(b.bl_num_slide_patches, 0);
  assert_int_equal(b.bl_cells, ANITET_BL_CELLS_TETS);
  assert_int_equal(a.bl_cells, ANITET_BL_CELLS_TETS);
  assert_null(b.bl_slide_patches);
  assert_int_equal(a.bl_num_slide_patches, 0);
  assert_null(a.bl_slide_patches);
  assert_int_equal(b.push_tasks_min_vertices, a.push_tasks_min_vertices);
  /* Version 3: nothing written past its end. */
  assert_int_equal(v3_size, offsetof(anitet_options, bl_mitre) + sizeof(int32_t));
  memset(&v3, 0xff, sizeof v3);
  assert_int_equal(anitet_options_init(&v3, 3), ANITET_OK);
  assert_int_equal(v3.version, 3);
  for (i = v3_size; i < sizeof v3; ++i) assert_int_equal(bytes[i], 0xff);
}

static void expect_same_mesh(const anitet_mesh* a, const anitet_mesh* b) {
  int64_t np = 0, nt = 0, np2 = 0, nt2 = 0;
  double *xa, *xb;
  int32_t *ta, *tb;
  assert_int_equal(anitet_mesh_get_counts(a, &np, &nt, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(b, &np2, &nt2, NULL), ANITET_OK);
  assert_int_equal(np, np2);
  assert_int_equal(nt, nt2);
  xa = malloc((size_t)(3 * np) * sizeof *xa), xb = malloc((size_t)(3 * np) * sizeof *xb);
  ta = malloc((size_t)(4 * nt) * sizeof *ta), tb = malloc((size_t)(4 * nt) * sizeof *tb);
  assert_true(xa && xb && ta && tb);
  assert_int_equal(anitet_mesh_get_points(a, xa, 3 * np), ANITET_OK);
  assert_int_equal(anitet_mesh_get_points(b, xb, 3 * np), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tets(a, ta, 4 * nt, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tets(b, tb, 4 * nt, 0), ANITET_OK);
  assert_memory_equal(xa, xb, (size_t)(3 * np) * sizeof *xa);
  assert_memory_equal(ta, tb, (size_t)(4 * nt) * sizeof *ta);
  free(xa), free(xb), free(ta), free(tb);
}

/* A caller compiled against version 3: garbage past its struct's end is not read, and its
 * boundary layer gives the same layers (stage 1 alone), bit for bit, as the same options of
 * version 4. */
static void test_options_v3_caller(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options v3, v4 = ANITET_OPTIONS_INIT;
  anitet_mesh *a = NULL, *b = NULL;
  (void)state;
  memset(&v3, 0xff, sizeof v3);
  assert_int_equal(anitet_options_init(&v3, 3), ANITET_OK);
  v3.bl_num_patches = v4.bl_num_patches = 3, v3.bl_patches = v4.bl_patches = walls;
  v3.bl_first_height = v4.bl_first_height = 0.02, v3.bl_layers = v4.bl_layers = 3;
  assert_int_equal(anitet_layers_run(s, &v3, &a), ANITET_OK);
  assert_int_equal(anitet_layers_run(s, &v4, &b), ANITET_OK);
  expect_same_mesh(a, b);
  anitet_mesh_destroy(a);
  anitet_mesh_destroy(b);
  anitet_surface_destroy(s);
}

/* A pipe along z (radius 1, length 2, 16 segments, 6 rings apart): wall 1, inlet 2 (z = 0) and
 * outlet 3 (z = 2), each cap a fan around its centre. */
enum { PIPE_N = 16, PIPE_RINGS = 7, PIPE_NPOINTS = PIPE_N * PIPE_RINGS + 2,
       PIPE_NTRI = 2 * PIPE_N * (PIPE_RINGS - 1) + 2 * PIPE_N };

static anitet_surface* make_pipe(void) {
  static double xyz[3 * PIPE_NPOINTS];
  static int32_t tri[3 * PIPE_NTRI], patch[PIPE_NTRI];
  const int32_t c0 = PIPE_N * PIPE_RINGS, c1 = c0 + 1, top = PIPE_N * (PIPE_RINGS - 1);
  anitet_surface* s = NULL;
  int i, j, t = 0;
  for (j = 0; j < PIPE_RINGS; ++j)
    for (i = 0; i < PIPE_N; ++i) {
      const double a = 2.0 * 3.141592653589793 * i / PIPE_N;
      double* p = &xyz[3 * (j * PIPE_N + i)];
      p[0] = cos(a), p[1] = sin(a), p[2] = 2.0 * j / (PIPE_RINGS - 1);
    }
  xyz[3 * c0] = xyz[3 * c0 + 1] = xyz[3 * c0 + 2] = 0.0;
  xyz[3 * c1] = xyz[3 * c1 + 1] = 0.0, xyz[3 * c1 + 2] = 2.0;
  for (j = 0; j + 1 < PIPE_RINGS; ++j)
    for (i = 0; i < PIPE_N; ++i) {
      const int32_t a = j * PIPE_N + i, b = j * PIPE_N + (i + 1) % PIPE_N;
      const int32_t q[6] = {a, b, b + PIPE_N, a, b + PIPE_N, a + PIPE_N};
      memcpy(&tri[3 * t], q, sizeof q);
      patch[t] = patch[t + 1] = 1;
      t += 2;
    }
  for (i = 0; i < PIPE_N; ++i, t += 2) {
    const int32_t q[6] = {i, c0, (i + 1) % PIPE_N, top + i, top + (i + 1) % PIPE_N, c1};
    memcpy(&tri[3 * t], q, sizeof q);
    patch[t] = 2, patch[t + 1] = 3;
  }
  assert_int_equal(t, PIPE_NTRI);
  assert_int_equal(anitet_surface_create(xyz, PIPE_NPOINTS, tri, PIPE_NTRI, patch, 0, &s), ANITET_OK);
  return s;
}

static void test_slide_patches(void** state) {
  anitet_surface* s = make_pipe();
  const int32_t wall[1] = {1}, caps[2] = {2, 3}, wall_and_cap[2] = {1, 2};
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_quality q = ANITET_QUALITY_INIT;
  anitet_mesh *m, *t1 = NULL;
  int64_t np = 0, nb = 0, i, on_caps = 0, on_wall = 0;
  int32_t* patch;
  char* json;
  (void)state;
  o.bl_num_patches = 1, o.bl_patches = wall;
  o.bl_first_height = 0.01, o.bl_growth = 1.2, o.bl_layers = 4;
  /* The wall meets the caps: refused without slide patches, naming the field and the label. */
  expect_bad(s, &o, "options->bl_slide_patches 2");
  o.bl_num_slide_patches = 2, o.bl_slide_patches = caps;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.bl_layers, 4);
  assert_int_equal(st.bl_wall_vertices, PIPE_N * PIPE_RINGS);
  assert_int_equal(st.bl_full_columns, PIPE_N * PIPE_RINGS);
  assert_int_equal(st.slide_junction_columns, 2 * PIPE_N);
  assert_int_equal(st.slide_lowered_columns, 0);
  json = run_json(m);
  assert_true(contains(json, "\"slide_patches\""));
  assert_true(contains(json, "\"junction_vertices\": 32") || contains(json, "\"junction_vertices\":32"));
  free(json);
  /* The wall's triangles as given, first; the caps triangulated again around the columns. */
  assert_int_equal(anitet_mesh_get_counts(m, &np, NULL, &nb), ANITET_OK);
  assert_true(np > PIPE_NPOINTS);
  patch = malloc((size_t)nb * sizeof *patch);
  assert_non_null(patch);
  assert_int_equal(anitet_mesh_get_boundary_patches(m, patch, nb), ANITET_OK);
  for (i = 0; i < nb; ++i) {
    on_wall += patch[i] == 1;
    on_caps += patch[i] == 2 || patch[i] == 3;
  }
  for (i = 0; i < 2 * PIPE_N * (PIPE_RINGS - 1); ++i) assert_int_equal(patch[i], 1);
  assert_int_equal(on_wall, 2 * PIPE_N * (PIPE_RINGS - 1));
  assert_true(on_caps > 2 * PIPE_N);
  assert_int_equal(st.slide_triangles_added, on_caps - 2 * PIPE_N);
  assert_int_equal(on_wall + on_caps, nb);
  free(patch);
  assert_int_equal(anitet_mesh_quality(m, NULL, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  anitet_mesh_destroy(m);
  /* Stage 1 alone with slide patches. */
  assert_int_equal(anitet_layers_run(s, &o, &t1), ANITET_OK);
  json = run_json(t1);
  assert_true(contains(json, "\"slide_patches\""));
  free(json);
  anitet_mesh_destroy(t1);
  /* Errors: a negative count, NULL labels, slide patches without walls, a label both. */
  o.bl_num_slide_patches = -1;
  expect_bad(s, &o, "bl_num_slide_patches is negative");
  o.bl_num_slide_patches = 2, o.bl_slide_patches = NULL;
  expect_bad(s, &o, "bl_slide_patches is NULL");
  o.bl_slide_patches = caps, o.bl_num_patches = 0;
  expect_bad(s, &o, "needs boundary-layer walls");
  o.bl_num_patches = 1, o.bl_slide_patches = wall_and_cap;
  expect_bad(s, &o, "both as a wall and as a slide patch");
  anitet_surface_destroy(s);
}

/* ---- stage 1 alone, y+ ------------------------------------------------------------------------ */

static void test_layers_run(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_mesh *t1 = NULL, *t1_one_by_one = NULL;
  int64_t np = 0, nt = 0, nb = 0, nt2 = 0, i, front = 0;
  int32_t* patch;
  char* json;
  (void)state;
  o.bl_num_patches = 3, o.bl_patches = walls;
  o.bl_first_height = 0.02, o.bl_growth = 1.25, o.bl_layers = 3;
  assert_int_equal(anitet_layers_run(s, &o, &t1), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(t1, &np, &nt, &nb), ANITET_OK);
  /* The input's triangles, then S1's under label 5 (the largest, 4, plus one). */
  assert_true(nb > BOX_NTRI);
  patch = malloc((size_t)nb * sizeof *patch);
  assert_non_null(patch);
  assert_int_equal(anitet_mesh_get_boundary_patches(t1, patch, nb), ANITET_OK);
  for (i = 0; i < BOX_NTRI; ++i) assert_int_equal(patch[i], g_patch[i]);
  for (i = BOX_NTRI; i < nb; ++i) front += patch[i] == 5;
  assert_int_equal(front, nb - BOX_NTRI);
  free(patch);
  /* Its figures: the layers used, the boundary layer measured on T1, no recovery. */
  assert_int_equal(anitet_mesh_get_run_stats(t1, &st), ANITET_OK);
  assert_int_equal(st.layers_used, 1);
  assert_int_equal(st.recovery_strategy, 0);
  assert_int_equal(st.refine_passes, 0);
  assert_int_equal(st.tets, nt);
  assert_int_equal(st.bl_layers, 3);
  assert_int_equal(st.bl_wall_vertices, SPHERE_NPOINTS);
  assert_int_equal(st.bl_full_columns, SPHERE_NPOINTS);
  assert_true(st.bl_tets > 0 && st.bl_tets < nt);
  assert_true(fabs(st.bl_first_height_mean - 0.02) < 0.002);
  json = run_json(t1);
  assert_true(contains(json, "\"layers\""));
  free(json);
  /* Pushes one by one: the same T1. */
  o.push_tasks_min_vertices = 0;
  assert_int_equal(anitet_layers_run(s, &o, &t1_one_by_one), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(t1_one_by_one, NULL, &nt2, NULL), ANITET_OK);
  assert_int_equal(nt2, nt);
  anitet_mesh_destroy(t1_one_by_one);
  /* Errors: NULLs, a bad option, an open surface. */
  assert_int_equal(anitet_layers_run(NULL, &o, &t1_one_by_one), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_layers_run(s, &o, NULL), ANITET_ERR_INVALID_ARGUMENT);
  o.push_tasks_min_vertices = -1;
  assert_int_equal(anitet_layers_run(s, &o, &t1_one_by_one), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "push_tasks_min_vertices"));
  assert_null(t1_one_by_one);
  anitet_mesh_destroy(t1);
  anitet_surface_destroy(s);
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 11, NULL, 0, &s), ANITET_OK);
  assert_int_equal(anitet_layers_run(s, NULL, &t1), ANITET_ERR_OPEN_BOUNDARY);
  assert_null(t1);
  anitet_surface_destroy(s);
}

/* ---- options, version 5: bl_sizing_growth -------------------------------------------------- */

static void test_options_v5_defaults(void** state) {
  anitet_options a = ANITET_OPTIONS_INIT, b, v4;
  const size_t v4_size = offsetof(anitet_options, bl_sizing_growth);
  const unsigned char* bytes = (const unsigned char*)&v4;
  size_t i;
  (void)state;
  assert_int_equal(ANITET_OPTIONS_VERSION, 5);
  memset(&b, 0x5a, sizeof b);
  assert_int_equal(anitet_options_init(&b, 5), ANITET_OK);
  assert_int_equal(b.version, 5);
  assert_true(b.bl_sizing_growth == 0.0 && a.bl_sizing_growth == 0.0);
  /* Version 4: nothing written past its end. */
  assert_int_equal(v4_size, offsetof(anitet_options, bl_slide_patches) + sizeof(void*));
  memset(&v4, 0xff, sizeof v4);
  assert_int_equal(anitet_options_init(&v4, 4), ANITET_OK);
  assert_int_equal(v4.version, 4);
  for (i = v4_size; i < sizeof v4; ++i) assert_int_equal(bytes[i], 0xff);
  assert_int_equal(anitet_options_init(&b, 6), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "version 6"));
}

/* The sphere's boundary layer with bl_sizing on a cheap sized run (sizes twice as coarse, no
 * optimization, no anisotropic cycles). A version 4 caller (garbage past its struct: a NaN
 * bl_sizing_growth, refused if it were read) gets the layers' growth: the same mesh as version 5
 * with 0. bl_sizing_growth 1.3 (above the layers' 1.1) coarsens the interior faster: fewer tets. */
static void test_bl_sizing_growth(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options v4, o = ANITET_OPTIONS_INIT;
  anitet_mesh *old_caller, *layers_growth, *faster;
  (void)state;
  memset(&v4, 0xff, sizeof v4);
  assert_int_equal(anitet_options_init(&v4, 4), ANITET_OK);
  v4.bl_num_patches = o.bl_num_patches = 3, v4.bl_patches = o.bl_patches = walls;
  v4.bl_first_height = o.bl_first_height = 0.05, v4.bl_growth = o.bl_growth = 1.1;
  v4.bl_layers = o.bl_layers = 3, v4.bl_sizing = o.bl_sizing = 1;
  v4.optimize = o.optimize = 0, v4.anisotropic_cycles = o.anisotropic_cycles = 0;
  v4.size_scale = o.size_scale = 2.0;
  old_caller = run_ok(s, &v4);
  layers_growth = run_ok(s, &o);
  expect_same_mesh(old_caller, layers_growth);
  o.bl_sizing_growth = 1.3;
  faster = run_ok(s, &o);
  print_message("bl_sizing_growth 0: %lld tets, 1.3: %lld\n", (long long)tets_of(layers_growth),
                (long long)tets_of(faster));
  assert_true(tets_of(faster) < tets_of(layers_growth));
  anitet_mesh_destroy(old_caller);
  anitet_mesh_destroy(layers_growth);
  anitet_mesh_destroy(faster);
  anitet_surface_destroy(s);
}

/* The CLI's errors: a value below bl_growth, NaN or infinite (the CLI's metric refuses that
 * too), or one without bl_sizing. */
static void test_bl_sizing_growth_errors(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  (void)state;
  o.bl_num_patches = 3, o.bl_patches = walls, o.bl_first_height = 0.02, o.bl_growth = 1.2;
  o.bl_sizing = 1, o.bl_sizing_growth = 1.1;
  expect_bad(s, &o, "bl_sizing_growth");
  o.bl_sizing_growth = -1.0;
  expect_bad(s, &o, "at least bl_growth");
  o.bl_sizing_growth = NAN;
  expect_bad(s, &o, "bl_sizing_growth");
  o.bl_sizing_growth = INFINITY;
  expect_bad(s, &o, "a finite value");
  o.bl_sizing_growth = 1.3, o.bl_sizing = 0;
  expect_bad(s, &o, "needs bl_sizing 1");
  anitet_surface_destroy(s);
}

/* ---- bl_cells: prism cells ------------------------------------------------------------------ */

/* The sphere's boundary layer as prism cells, on the cheapest run (2 layers, no refinement or
 * optimization): the mesh keeps every tet, each prism is 3 of them, the .vtu and polyMesh get the
 * prisms, a format of tets only refuses the mesh. */
static void test_bl_cells_prisms(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_mesh* m;
  int64_t np = 0, nt = 0, nb = 0, nprisms = -1, i, kept = 0;
  int32_t *tets, *regions, *prisms, *tet_prism, *tet_prism0, *count;
  static char owner[1 << 12];
  char path[4096], note[128];
  (void)state;
  o.bl_num_patches = 3, o.bl_patches = walls;
  o.bl_first_height = 0.02, o.bl_growth = 1.25, o.bl_layers = 2;
  o.refine = 0, o.optimize = 0, o.bl_cells = ANITET_BL_CELLS_PRISMS;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_counts(m, &np, &nt, &nb), ANITET_OK);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.tets, nt); /* every tet kept */
  assert_int_equal(anitet_mesh_get_prism_count(m, &nprisms), ANITET_OK);
  assert_int_equal(nprisms, 2 * SPHERE_NTRI); /* every column full: one prism per wall triangle and layer */
  tets = malloc((size_t)(4 * nt) * sizeof *tets), regions = malloc((size_t)nt * sizeof *regions);
  prisms = malloc((size_t)(6 * nprisms) * sizeof *prisms), tet_prism = malloc((size_t)nt * sizeof *tet_prism);
  count = calloc((size_t)nprisms, sizeof *count), tet_prism0 = malloc((size_t)nt * sizeof *tet_prism0);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 4 * nt, 1), ANITET_OK);
  assert_int_equal(anitet_mesh_get_regions(m, regions, nt), ANITET_OK);
  assert_int_equal(anitet_mesh_get_prisms(m, prisms, 6 * nprisms, 1), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tet_prisms(m, tet_prism, nt, 0), ANITET_OK);
  for (i = 0; i < 6 * nprisms; ++i) assert_true(prisms[i] >= 1 && prisms[i] <= np);
  /* Each prism is 3 tets of the boundary layer (region 1) whose vertices are the prism's. */
  for (i = 0; i < nt; ++i) {
    int k, j, p = tet_prism[i];
    if (p < 0) {
      ++kept;
      continue;
    }
    assert_true(p < nprisms);
    ++count[p];
    assert_int_equal(regions[i], 1);
    for (k = 0; k < 4; ++k) {
      int found = 0;
      for (j = 0; j < 6; ++j) found |= prisms[6 * p + j] == tets[4 * i + k];
      assert_true(found);
    }
  }
  for (i = 0; i < nprisms; ++i) assert_int_equal(count[i], 3);
  assert_int_equal(kept, nt - 3 * nprisms);
  /* The merge's figures (run stats version 3): every BL tet in a prism or left. */
  assert_int_equal(st.bl_prisms, nprisms);
  assert_int_equal(3 * st.bl_prisms + st.bl_prism_tets_left, st.bl_tets);
  /* Buffer and argument errors. */
  assert_int_equal(anitet_mesh_get_prisms(m, prisms, 6 * nprisms - 1, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_prisms(m, prisms, 6 * nprisms, 2), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_tet_prisms(m, tet_prism, nt - 1, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  /* index_base 1: the same prisms counted from 1, -1 stays -1. */
  memcpy(tet_prism0, tet_prism, (size_t)nt * sizeof *tet_prism);
  assert_int_equal(anitet_mesh_get_tet_prisms(m, tet_prism, nt, 1), ANITET_OK);
  for (i = 0; i < nt; ++i) assert_int_equal(tet_prism[i], tet_prism0[i] < 0 ? -1 : tet_prism0[i] + 1);
  assert_int_equal(anitet_mesh_get_prism_count(m, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_get_prism_count(NULL, &nprisms), ANITET_ERR_INVALID_ARGUMENT);
  /* polyMesh: the prisms in place of their tets. */
  snprintf(path, sizeof path, "%s/capi_bl_prisms/constant/polyMesh", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  snprintf(path, sizeof path, "%s/capi_bl_prisms/constant/polyMesh/owner", ANITET_TEST_OUTPUT_DIR);
  assert_true(read_file(path, owner, sizeof owner) > 0);
  snprintf(note, sizeof note, "nCells:%lld", (long long)(kept + nprisms));
  if (!contains(owner, note)) fail_msg("no '%s' in:\n%s", note, owner);
  /* .vtu: VTK_WEDGE (13) cells. */
  snprintf(path, sizeof path, "%s/capi_bl_prisms.vtu", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_OK);
  snprintf(note, sizeof note, "NumberOfCells=\"%lld\"", (long long)(kept + nprisms + nb));
  assert_true(file_contains(path, note));
  assert_true(file_contains(path, "13 13 13"));
  /* A format of tets only: refused, nothing written. */
  snprintf(path, sizeof path, "%s/capi_bl_prisms.mesh", ANITET_TEST_OUTPUT_DIR);
  remove(path);
  assert_int_equal(anitet_mesh_write(m, path), ANITET_ERR_UNSUPPORTED_FORMAT);
  if (!contains(anitet_last_error_message(), "prisms"))
    fail_msg("message '%s' lacks 'prisms'", anitet_last_error_message());
  assert_false(file_contains(path, "Tetrahedra"));
  free(tets), free(regions), free(prisms), free(tet_prism), free(tet_prism0), free(count);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

/* A mesh without prism cells: 0 prisms, every tet -1. */
static void test_bl_cells_tets(void** state) {
  anitet_mesh* m = NULL;
  int64_t nprisms = -1;
  int32_t tet_prism[6] = {0, 0, 0, 0, 0, 0};
  int i;
  (void)state;
  assert_int_equal(anitet_mesh_create(kCubeXyz, 8, (const int32_t[]){0, 1, 3, 4}, 1, NULL, NULL, 0, NULL, 0, &m),
                   ANITET_OK);
  assert_int_equal(anitet_mesh_get_prism_count(m, &nprisms), ANITET_OK);
  assert_int_equal(nprisms, 0);
  assert_int_equal(anitet_mesh_get_prisms(m, NULL, 0, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tet_prisms(m, tet_prism, 6, 1), ANITET_OK);
  assert_int_equal(tet_prism[0], -1);
  for (i = 1; i < 6; ++i) assert_int_equal(tet_prism[i], 0);
  anitet_mesh_destroy(m);
}

/* bl_cells errors: an unknown value, prisms without walls (as `anitet mesh --bl-cells` without
 * --bl-patches), prisms for stage 1 alone. */
static void test_bl_cells_errors(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_mesh* m = (anitet_mesh*)1;
  (void)state;
  o.bl_cells = 2;
  expect_bad(s, &o, "bl_cells is 2");
  o.bl_cells = ANITET_BL_CELLS_PRISMS;
  expect_bad(s, &o, "needs boundary-layer walls");
  o.bl_num_patches = 3, o.bl_patches = walls, o.bl_first_height = 0.02;
  assert_int_equal(anitet_layers_run(s, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "anitet_mesher_run"));
  anitet_surface_destroy(s);
}

/* ---- bl_mitre and the columns' CSV ---------------------------------------------------------- */

/* The cube [0, 1]^3 (patch 1, 2 x 2 squares a face: 8 corners, 12 edge midpoints, 6 face centres)
 * inside the box [-2, 3]^3 (patch 2), as bl_mitre_check.sh's with fewer triangles. */
enum { CUBE_N = 2, CUBE_NPOINTS = 26 + 8, CUBE_NTRI = 6 * 2 * CUBE_N * CUBE_N + 12 };
static double c_xyz[3 * CUBE_NPOINTS];
static int32_t c_tri[3 * CUBE_NTRI], c_patch[CUBE_NTRI];

static int32_t cube_vertex(int32_t* ids, int* n, const int p[3]) {
  int32_t* id = &ids[(p[0] * (CUBE_N + 1) + p[1]) * (CUBE_N + 1) + p[2]];
  if (*id < 0) {
    int k;
    for (k = 0; k < 3; ++k) c_xyz[3 * *n + k] = (double)p[k] / CUBE_N;
    *id = (*n)++;
  }
  return *id;
}

static anitet_surface* make_cube_in_box(void) {
  static const int32_t box_tri[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  int32_t ids[(CUBE_N + 1) * (CUBE_N + 1) * (CUBE_N + 1)];
  anitet_surface* s = NULL;
  int n = 0, t = 0, axis, side, i, j, k;
  for (i = 0; i < (CUBE_N + 1) * (CUBE_N + 1) * (CUBE_N + 1); ++i) ids[i] = -1;
  for (axis = 0; axis < 3; ++axis)
    for (side = 0; side <= CUBE_N; side += CUBE_N)
      for (i = 0; i < CUBE_N; ++i)
        for (j = 0; j < CUBE_N; ++j) {
          int32_t q[4];
          for (k = 0; k < 4; ++k) {
            int p[3];
            p[axis] = side, p[(axis + 1) % 3] = i + (k == 1 || k == 2), p[(axis + 2) % 3] = j + (k >= 2);
            q[side ? k : 3 - k] = cube_vertex(ids, &n, p); /* outward normals */
          }
          c_tri[3 * t] = q[0], c_tri[3 * t + 1] = q[1], c_tri[3 * t + 2] = q[2], c_patch[t++] = 1;
          c_tri[3 * t] = q[0], c_tri[3 * t + 1] = q[2], c_tri[3 * t + 2] = q[3], c_patch[t++] = 1;
        }
  assert_int_equal(n, 26);
  for (i = 0; i < 8; ++i) {
    double* p = &c_xyz[3 * (n + i)];
    p[0] = (i & 1) ? 3.0 : -2.0, p[1] = (i & 2) ? 3.0 : -2.0, p[2] = (i & 4) ? 3.0 : -2.0;
  }
  for (i = 0; i < 36; ++i) c_tri[3 * t + i] = n + box_tri[i];
  for (i = 0; i < 12; ++i) c_patch[t + i] = 2;
  assert_int_equal(anitet_surface_create(c_xyz, CUBE_NPOINTS, c_tri, CUBE_NTRI, c_patch, 0, &s), ANITET_OK);
  return s;
}

/* The columns' CSV of a BL run on the cube, through anitet_mesh_write_bl_columns: the header, one
 * line per wall vertex on patch 1 only, every column full; the mean total height of the corner
 * columns over *corner_total and of the face centres' over *face_total. */
static void cube_columns(const anitet_surface* s, int32_t mitre, double* corner_total, double* face_total) {
  static char text[1 << 16];
  const int32_t wall = 1;
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_run_stats st = ANITET_RUN_STATS_INIT;
  anitet_mesh* m;
  char path[4096], *line;
  int rows = 0, corners = 0, faces = 0;
  o.bl_num_patches = 1, o.bl_patches = &wall, o.bl_mitre = mitre;
  o.bl_first_height = 0.01, o.bl_growth = 1.2, o.bl_layers = 3, o.refine = 0, o.optimize = 0;
  m = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_run_stats(m, &st), ANITET_OK);
  assert_int_equal(st.bl_wall_vertices, 26);
  assert_int_equal(st.bl_full_columns, 26);
  snprintf(path, sizeof path, "%s/capi_bl_columns_%d.csv", ANITET_TEST_OUTPUT_DIR, mitre);
  remove(path);
  assert_int_equal(anitet_mesh_write_bl_columns(m, path), ANITET_OK);
  assert_true(read_file(path, text, sizeof text) > 0);
  line = strstr(text, "\n");
  assert_non_null(line);
  assert_true(strncmp(text, "x,y,z,layers,first_height,total_height,normal_share,patches\n", (size_t)(line - text + 1)) == 0);
  *corner_total = *face_total = 0.0;
  for (++line; *line; ++rows) {
    double p[3], first, total, share;
    int layers, label, used = 0, on = 0, k;
    assert_int_equal(sscanf(line, "%lf,%lf,%lf,%d,%lf,%lf,%lf,%d%n", &p[0], &p[1], &p[2], &layers, &first, &total,
                            &share, &label, &used),
                     8);
    assert_int_equal(layers, 3);
    assert_int_equal(label, 1);
    assert_int_equal(line[used], '\n'); /* on the wall patch only */
    for (k = 0; k < 3; ++k) on += p[k] == 0.0 || p[k] == 1.0;
    if (on == 3) *corner_total += total, ++corners;
    if (on == 1) *face_total += total, ++faces;
    line += used + 1;
  }
  assert_int_equal(rows, 26);
  assert_int_equal(corners, 8);
  assert_int_equal(faces, 6);
  *corner_total /= corners, *face_total /= faces;
  anitet_mesh_destroy(m);
}

/* bl_mitre lengthens the corner columns (by up to 1/0.58 at a cube's corner) and keeps the face
 * columns; the CSV has a line per wall vertex. Then anitet_mesh_write_bl_columns' errors. */
static void test_bl_mitre_columns(void** state) {
  anitet_surface* s = make_cube_in_box();
  const double nominal = 0.01 * (1.0 + 1.2 + 1.44);
  double plain_corner, plain_face, mitre_corner, mitre_face;
  anitet_mesh* m = NULL;
  char path[4096];
  (void)state;
  cube_columns(s, 0, &plain_corner, &plain_face);
  cube_columns(s, 1, &mitre_corner, &mitre_face);
  if (!(fabs(plain_corner / nominal - 1.0) < 0.1 && mitre_corner > 1.3 * plain_corner))
    fail_msg("corner columns %g (plain), %g (mitre), nominal %g", plain_corner, mitre_corner, nominal);
  if (!(fabs(plain_face / nominal - 1.0) < 0.1 && fabs(mitre_face / plain_face - 1.0) < 0.05))
    fail_msg("face columns %g (plain), %g (mitre), nominal %g", plain_face, mitre_face, nominal);
  /* Errors: NULL, a mesh without a run, a run without walls, a file that cannot be created. */
  snprintf(path, sizeof path, "%s/capi_bl_columns_none.csv", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_mesh_write_bl_columns(NULL, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_create(kCubeXyz, 8, (const int32_t[]){0, 1, 3, 4}, 1, NULL, NULL, 0, NULL, 0, &m),
                   ANITET_OK);
  assert_int_equal(anitet_mesh_write_bl_columns(m, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_write_bl_columns(m, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not made by"));
  anitet_mesh_destroy(m);
  m = run_ok(s, NULL);
  assert_int_equal(anitet_mesh_write_bl_columns(m, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "no boundary layer"));
  anitet_mesh_destroy(m);
  {
    const int32_t wall = 1;
    anitet_options o = ANITET_OPTIONS_INIT;
    o.bl_num_patches = 1, o.bl_patches = &wall, o.bl_first_height = 0.01, o.bl_layers = 1;
    assert_int_equal(anitet_layers_run(s, &o, &m), ANITET_OK);
    snprintf(path, sizeof path, "%s/no-such-dir/columns.csv", ANITET_TEST_OUTPUT_DIR);
    assert_int_equal(anitet_mesh_write_bl_columns(m, path), ANITET_ERR_FILE_NOT_FOUND);
    snprintf(path, sizeof path, "%s/capi_bl_columns_layers.csv", ANITET_TEST_OUTPUT_DIR);
    assert_int_equal(anitet_mesh_write_bl_columns(m, path), ANITET_OK); /* stage 1 alone: T1's columns */
    assert_true(file_contains(path, "x,y,z,layers"));
    anitet_mesh_destroy(m);
  }
  anitet_surface_destroy(s);
}

/* bl_mitre errors: a value other than 0 and 1, no walls (as `anitet mesh --bl-mitre` without
 * --bl-patches). */
static void test_bl_mitre_errors(void** state) {
  anitet_surface* s = make_sphere_in_box();
  const int32_t walls[3] = {1, 2, 3};
  anitet_options o = ANITET_OPTIONS_INIT;
  (void)state;
  o.bl_mitre = 1;
  expect_bad(s, &o, "bl_mitre needs boundary-layer walls");
  o.bl_num_patches = 3, o.bl_patches = walls, o.bl_first_height = 0.02, o.bl_mitre = 2;
  expect_bad(s, &o, "bl_mitre is 2");
  anitet_surface_destroy(s);
}

static void test_bl_first_height(void** state) {
  double h0 = 0.0;
  (void)state;
  /* Re = 1e6, L = 1, y+ = 1: Cf = 0.026 * 1e6^(-1/7), h0 = 1 / (1e6 sqrt(Cf / 2)). */
  assert_int_equal(anitet_bl_first_height(1.0, 1e6, 1.0, &h0), ANITET_OK);
  assert_true(fabs(h0 - 1.0 / (1e6 * sqrt(0.026 * pow(1e6, -1.0 / 7.0) / 2.0))) < 1e-18);
  assert_int_equal(anitet_bl_first_height(0.0, 1e6, 1.0, &h0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_bl_first_height(1.0, NAN, 1.0, &h0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_bl_first_height(1.0, 1e6, -1.0, &h0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_bl_first_height(1.0, 1e6, 1.0, NULL), ANITET_ERR_INVALID_ARGUMENT);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_options_v3_defaults), cmocka_unit_test(test_options_v2_caller),
      cmocka_unit_test(test_options_v3_errors),   cmocka_unit_test(test_run_stats_plain),
      cmocka_unit_test(test_run_stats_errors),    cmocka_unit_test(test_boundary_layer),
      cmocka_unit_test(test_options_v3_used),     cmocka_unit_test(test_patch_names),
      cmocka_unit_test(test_layers_run),          cmocka_unit_test(test_bl_first_height),
      cmocka_unit_test(test_patch_types),         cmocka_unit_test(test_options_v4_defaults),
      cmocka_unit_test(test_options_v3_caller),   cmocka_unit_test(test_slide_patches),
      cmocka_unit_test(test_run_stats_v1_caller), cmocka_unit_test(test_bl_cells_prisms),
      cmocka_unit_test(test_bl_cells_tets),       cmocka_unit_test(test_bl_cells_errors),
      cmocka_unit_test(test_bl_mitre_columns),    cmocka_unit_test(test_bl_mitre_errors),
      cmocka_unit_test(test_options_v5_defaults), cmocka_unit_test(test_bl_sizing_growth),
      cmocka_unit_test(test_bl_sizing_growth_errors),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
