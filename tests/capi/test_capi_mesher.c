/* The C ABI's mesher entry point: success on the example sphere (and the cube), with and without
 * a metric, determinism, progress/log callbacks, cancellation at every stage, versioned options,
 * and every documented error (NULL handles, bad options, open and self-intersecting surfaces,
 * failing metric callbacks). */
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

#ifndef ANITET_SURFACES_DIR
#error "ANITET_SURFACES_DIR must be defined"
#endif

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

static double g_xyz[3 * SPHERE_NPOINTS];
static int32_t g_tri[3 * SPHERE_NTRI], g_patch[SPHERE_NTRI];

static anitet_surface* make_sphere(void) {
  anitet_surface* s = NULL;
  sphere_build(g_xyz, g_tri, g_patch);
  assert_int_equal(anitet_surface_create(g_xyz, SPHERE_NPOINTS, g_tri, SPHERE_NTRI, g_patch, 0, &s), ANITET_OK);
  return s;
}

static anitet_mesh* run_ok(const anitet_surface* s, const anitet_options* o) {
  anitet_mesh* m = NULL;
  const int rc = anitet_mesher_run(s, NULL, o, &m);
  if (rc != ANITET_OK) fail_msg("anitet_mesher_run: %s", anitet_last_error_message());
  assert_non_null(m);
  assert_string_equal(anitet_last_error_message(), "");
  return m;
}

/* ---- success -------------------------------------------------------------------------------- */

static void test_mesher_sphere(void** state) {
  anitet_surface* s = make_sphere();
  anitet_mesh* m = run_ok(s, NULL);
  anitet_quality q = ANITET_QUALITY_INIT;
  int64_t np = 0, nt = 0, nb = 0, i;
  double* xyz;
  int32_t *tets, *tets1, *regions, tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI], comps = -1;
  (void)state;
  assert_int_equal(anitet_mesh_get_counts(m, &np, &nt, &nb), ANITET_OK);
  assert_true(np >= SPHERE_NPOINTS);
  assert_true(nt > np);
  assert_int_equal(nb, SPHERE_NTRI);
  /* The input's points first and in order, its triangles and patches as the boundary. */
  xyz = malloc((size_t)(3 * np) * sizeof *xyz);
  tets = malloc((size_t)(4 * nt) * sizeof *tets);
  tets1 = malloc((size_t)(4 * nt) * sizeof *tets1);
  regions = malloc((size_t)nt * sizeof *regions);
  assert_true(xyz && tets && tets1 && regions);
  assert_int_equal(anitet_mesh_get_points(m, xyz, 3 * np), ANITET_OK);
  assert_memory_equal(xyz, g_xyz, sizeof g_xyz);
  assert_int_equal(anitet_mesh_get_boundary_triangles(m, tri, 3 * nb, 0), ANITET_OK);
  assert_memory_equal(tri, g_tri, sizeof tri);
  assert_int_equal(anitet_mesh_get_boundary_patches(m, patch, nb), ANITET_OK);
  assert_memory_equal(patch, g_patch, sizeof patch);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 4 * nt, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tets(m, tets1, 4 * nt, 1), ANITET_OK);
  for (i = 0; i < 4 * nt; ++i) {
    assert_true(tets[i] >= 0 && tets[i] < np);
    assert_int_equal(tets1[i], tets[i] + 1);
  }
  /* One body: one region label. */
  assert_int_equal(anitet_mesh_get_regions(m, regions, nt), ANITET_OK);
  for (i = 1; i < nt; ++i) assert_int_equal(regions[i], regions[0]);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 0);
  /* Short buffers on a meshed result: nothing written, BUFFER_TOO_SMALL. */
  assert_int_equal(anitet_mesh_get_points(m, xyz, 3 * np - 1), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 4 * nt - 1, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_regions(m, regions, nt - 1), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_boundary_triangles(m, tri, 3 * nb - 1, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh_get_boundary_patches(m, patch, nb - 1), ANITET_ERR_BUFFER_TOO_SMALL);
  /* A valid, boundary-constrained mesh without inverted tets; the surface is unchanged. */
  assert_int_equal(anitet_mesh_quality(m, s, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  assert_int_equal(q.nonpositive_tets, 0);
  assert_int_equal(q.tets, nt);
  assert_true(q.radius_ratio_min > 0.0);
  assert_int_equal(anitet_surface_get_counts(s, &np, &nt), ANITET_OK);
  assert_int_equal(np, SPHERE_NPOINTS);
  free(regions);
  free(tets1);
  free(tets);
  free(xyz);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

static void test_mesher_cube_and_file(void** state) {
  anitet_surface* s = NULL;
  anitet_mesh* m;
  anitet_quality q = ANITET_QUALITY_INIT;
  int32_t tri1[36];
  int i;
  (void)state;
  /* The cube from 1-based arrays. */
  for (i = 0; i < 36; ++i) tri1[i] = kCubeTri[i] + 1;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, tri1, 12, kCubePatch, 1, &s), ANITET_OK);
  m = run_ok(s, NULL);
  assert_int_equal(anitet_mesh_quality(m, s, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  assert_int_equal(q.nonpositive_tets, 0);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
  /* A surface read from a file. */
  assert_int_equal(anitet_surface_read(ANITET_TEST_DATA_DIR "/io/box_ascii.stl", &s), ANITET_OK);
  m = run_ok(s, NULL);
  assert_int_equal(anitet_mesh_quality(m, s, &q), ANITET_OK);
  assert_int_equal(q.boundary_constrained, 1);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

static void test_mesher_deterministic(void** state) {
  anitet_surface* s = make_sphere();
  anitet_mesh* a = run_ok(s, NULL);
  anitet_mesh* b = run_ok(s, NULL);
  int64_t na = 0, nb = 0, ta = 0, tb = 0;
  double *xa, *xb;
  int32_t *ka, *kb;
  (void)state;
  assert_int_equal(anitet_mesh_get_counts(a, &na, &ta, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(b, &nb, &tb, NULL), ANITET_OK);
  assert_int_equal(na, nb);
  assert_int_equal(ta, tb);
  xa = malloc((size_t)(3 * na) * sizeof *xa);
  xb = malloc((size_t)(3 * na) * sizeof *xb);
  ka = malloc((size_t)(4 * ta) * sizeof *ka);
  kb = malloc((size_t)(4 * ta) * sizeof *kb);
  assert_true(xa && xb && ka && kb);
  assert_int_equal(anitet_mesh_get_points(a, xa, 3 * na), ANITET_OK);
  assert_int_equal(anitet_mesh_get_points(b, xb, 3 * na), ANITET_OK);
  assert_memory_equal(xa, xb, (size_t)(3 * na) * sizeof *xa);
  assert_int_equal(anitet_mesh_get_tets(a, ka, 4 * ta, 0), ANITET_OK);
  assert_int_equal(anitet_mesh_get_tets(b, kb, 4 * ta, 0), ANITET_OK);
  assert_memory_equal(ka, kb, (size_t)(4 * ta) * sizeof *ka);
  free(kb);
  free(ka);
  free(xb);
  free(xa);
  anitet_mesh_destroy(b);
  anitet_mesh_destroy(a);
  anitet_surface_destroy(s);
}

/* ---- callbacks ------------------------------------------------------------------------------ */

struct progress_log {
  int calls;
  int cancel_at; /* cancel on this call (1-based); 0: never */
  int decreasing; /* a fraction below the previous one was seen */
  double first, last;
  char stages[128]; /* stage names, space-separated */
  char last_stage[32];
  int logs, stage_lines, error_lines;
};

static int on_progress(double fraction, const char* stage, void* user_data) {
  struct progress_log* r = (struct progress_log*)user_data;
  if (r->calls == 0) r->first = fraction;
  else if (fraction < r->last) r->decreasing = 1;
  r->last = fraction;
  r->calls++;
  /* A stage may report several times as it goes (refine, optimize): its name is kept once. */
  if (strcmp(stage, r->last_stage) != 0 && strlen(r->stages) + strlen(stage) + 2 < sizeof r->stages) {
    strcat(r->stages, stage);
    strcat(r->stages, " ");
  }
  strncpy(r->last_stage, stage, sizeof r->last_stage - 1);
  return r->calls == r->cancel_at ? 1 : 0;
}

static void on_log(int32_t level, const char* message, void* user_data) {
  struct progress_log* r = (struct progress_log*)user_data;
  assert_non_null(message);
  assert_true(level >= ANITET_LOG_ERROR && level <= ANITET_LOG_DEBUG);
  r->logs++;
  if (contains(message, "stage ")) r->stage_lines++;
  if (level == ANITET_LOG_ERROR) r->error_lines++;
}

static anitet_options with_callbacks(struct progress_log* r) {
  anitet_options o = ANITET_OPTIONS_INIT;
  memset(r, 0, sizeof *r);
  o.progress = on_progress;
  o.progress_user_data = r;
  o.log = on_log;
  o.log_user_data = r;
  return o;
}

static void test_mesher_progress_and_log(void** state) {
  anitet_surface* s = make_sphere();
  struct progress_log r;
  anitet_options o = with_callbacks(&r);
  anitet_mesh* m;
  (void)state;
  m = run_ok(s, &o);
  /* The stages of this version in order (later ones may add stages between them). */
  assert_true(strncmp(r.stages, "validate layers recovery coupling ", 34) == 0);
  assert_true(contains(r.stages, " refine optimize done "));
  assert_true(r.calls >= 5);
  assert_true(r.first == 0.0);
  assert_true(r.last == 1.0);
  assert_int_equal(r.decreasing, 0);
  assert_true(r.stage_lines >= 3); /* layers, recovery, coupling (and output) */
  assert_int_equal(r.error_lines, 0);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
}

static void test_mesher_cancel_at_every_stage(void** state) {
  anitet_surface* s = make_sphere();
  struct progress_log r;
  anitet_options o = with_callbacks(&r);
  anitet_mesh* m;
  char stages[128];
  int at, calls;
  (void)state;
  /* A run without cancelling counts the calls, then each call in turn cancels. Refinement and
   * optimization are skipped here: the other stages are enough and the test stays fast. */
  o.refine = 0;
  o.optimize = 0;
  m = run_ok(s, &o);
  anitet_mesh_destroy(m);
  calls = r.calls;
  memcpy(stages, r.stages, sizeof stages);
  assert_true(calls >= 5);
  assert_true(strncmp(stages, "validate layers recovery coupling ", 34) == 0);
  for (at = 1; at <= calls; ++at) {
    memset(&r, 0, sizeof r);
    r.cancel_at = at;
    m = (anitet_mesh*)1;
    assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_CANCELLED);
    assert_null(m);
    assert_int_equal(r.calls, at); /* no call after the cancelling one */
    assert_true(contains(anitet_last_error_message(), "cancel"));
    assert_true(strncmp(stages, r.stages, strlen(r.stages)) == 0);
  }
  anitet_surface_destroy(s);
}

/* ---- options -------------------------------------------------------------------------------- */

/* A caller compiled against version 1 of the header: its struct ends after log_user_data. */
struct options_v1 {
  int32_t version, num_threads, merge_duplicate_vertices, orient_shells, check_self_intersections,
      reserved0;
  anitet_progress_fn progress;
  void* progress_user_data;
  anitet_log_fn log;
  void* log_user_data;
};
struct options_v1_guarded {
  struct options_v1 options;
  unsigned char guard[64];
};

static void test_options_versions(void** state) {
  anitet_options o;
  struct options_v1_guarded v1;
  unsigned char zeros[64];
  anitet_surface* s = make_sphere();
  anitet_mesh *a, *b;
  int64_t ta = 0, tb = 0;
  (void)state;
  /* Version 2 defaults (version 3's to 5's: test_capi_run.c). */
  memset(&o, 0x5a, sizeof o);
  assert_int_equal(anitet_options_init(&o, ANITET_OPTIONS_VERSION), ANITET_OK);
  assert_int_equal(o.version, 5);
  assert_int_equal(o.layers, 1);
  assert_int_equal(o.layer_scheme, ANITET_LAYERS_PUSH);
  assert_true(o.recovery_max_seconds == 0.0);
  assert_int_equal(o.refine, 1);
  assert_int_equal(o.optimize, 1);
  assert_true(o.size_scale == 1.0);
  /* Version 1: the library writes nothing past the v1 struct... */
  assert_int_equal(offsetof(anitet_options, layers), sizeof(struct options_v1));
  memset(&v1, 0, sizeof v1);
  memset(zeros, 0, sizeof zeros);
  assert_int_equal(anitet_options_init((anitet_options*)(void*)&v1.options, 1), ANITET_OK);
  assert_int_equal(v1.options.version, 1);
  assert_int_equal(v1.options.merge_duplicate_vertices, 1);
  assert_memory_equal(v1.guard, zeros, sizeof zeros);
  /* ...and reads nothing past it: garbage there does not matter, the v2 fields get defaults. */
  memset(v1.guard, 0xff, sizeof v1.guard);
  a = run_ok(s, (const anitet_options*)(const void*)&v1.options);
  b = run_ok(s, NULL);
  assert_int_equal(anitet_mesh_get_counts(a, NULL, &ta, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(b, NULL, &tb, NULL), ANITET_OK);
  assert_int_equal(ta, tb);
  anitet_mesh_destroy(a);
  /* Version 2 fields are used: two layers give another mesh. */
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.layers = 2;
  a = run_ok(s, &o);
  assert_int_equal(anitet_mesh_get_counts(a, NULL, &ta, NULL), ANITET_OK);
  assert_true(ta != tb);
  anitet_mesh_destroy(a);
  anitet_mesh_destroy(b);
  anitet_surface_destroy(s);
}

static void test_mesher_bad_options(void** state) {
  anitet_surface* s = make_sphere();
  anitet_options o = ANITET_OPTIONS_INIT;
  anitet_mesh* m = (anitet_mesh*)1;
  (void)state;
  o.version = 0;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "options version 0"));
  o.version = ANITET_OPTIONS_VERSION + 1;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.layers = 0;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "layers is 0"));
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.layer_scheme = 7;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "layer_scheme is 7"));
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.recovery_max_seconds = -1.0;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  o.recovery_max_seconds = NAN;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.size_scale = 0.0;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "size_scale"));
  anitet_options_init(&o, ANITET_OPTIONS_VERSION);
  o.num_threads = -2;
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  anitet_surface_destroy(s);
}

/* ---- errors --------------------------------------------------------------------------------- */

static void test_mesher_null_arguments(void** state) {
  anitet_surface* s = make_sphere();
  anitet_mesh* m = (anitet_mesh*)1;
  (void)state;
  assert_int_equal(anitet_mesher_run(NULL, NULL, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "surface is NULL"));
  assert_int_equal(anitet_mesher_run(s, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "out is NULL"));
  anitet_surface_destroy(s);
}

static int stretched(double x, double y, double z, double m[6], void* user_data) {
  const double h = *(const double*)user_data;
  (void)x, (void)y, (void)z;
  m[0] = 1.0 / (h * h), m[1] = 0.0, m[2] = 4.0 / (h * h), m[3] = 0.0, m[4] = 0.0, m[5] = 1.0 / (h * h);
  return 0;
}

static int fails_below_zero(double x, double y, double z, double m[6], void* user_data) {
  (void)x, (void)y, (void)user_data;
  if (z < -0.5) return 7;
  m[0] = 16.0, m[1] = 0.0, m[2] = 16.0, m[3] = 0.0, m[4] = 0.0, m[5] = 16.0;
  return 0;
}

static int not_positive(double x, double y, double z, double m[6], void* user_data) {
  (void)x, (void)y, (void)z, (void)user_data;
  m[0] = 1.0, m[1] = 2.0, m[2] = 1.0, m[3] = 0.0, m[4] = 0.0, m[5] = 1.0; /* eigenvalue -1 */
  return 0;
}

static void test_mesher_with_metric(void** state) {
  anitet_surface* s = make_sphere();
  anitet_metric* metric = NULL;
  anitet_mesh *plain, *m = (anitet_mesh*)1;
  anitet_quality q = ANITET_QUALITY_INIT;
  int64_t np = 0, tets_plain = 0, tets_fine = 0, i;
  int32_t comps = 0;
  double h = 0.5, t[6], *values;
  (void)state;
  plain = run_ok(s, NULL);
  assert_int_equal(anitet_mesh_get_counts(plain, NULL, &tets_plain, NULL), ANITET_OK);
  anitet_mesh_destroy(plain);
  /* A uniform metric finer than the surface's edges: more tets, its tensor at every vertex. */
  assert_int_equal(anitet_metric_create_uniform(0.3, &metric), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, metric, NULL, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(m, &np, &tets_fine, NULL), ANITET_OK);
  assert_true(tets_fine > tets_plain);
  assert_int_equal(anitet_mesh_get_metric_components(m, &comps), ANITET_OK);
  assert_int_equal(comps, 6);
  values = malloc((size_t)(6 * np) * sizeof *values);
  assert_non_null(values);
  assert_int_equal(anitet_mesh_get_metric(m, values, 6 * np), ANITET_OK);
  assert_true(values[0] == 1.0 / (0.3 * 0.3) && values[6 * np - 1] == 1.0 / (0.3 * 0.3));
  assert_true(values[1] == 0.0);
  free(values);
  assert_int_equal(anitet_mesh_quality(m, s, &q), ANITET_OK);
  assert_int_equal(q.valid, 1);
  assert_int_equal(q.boundary_constrained, 1);
  anitet_mesh_destroy(m);
  anitet_metric_destroy(metric);
  /* An analytic (anisotropic) metric. */
  assert_int_equal(anitet_metric_create_analytic(stretched, &h, &metric), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, metric, NULL, &m), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(m, &np, NULL, NULL), ANITET_OK);
  assert_int_equal(anitet_metric_evaluate(metric, 0, 0, 0, t), ANITET_OK);
  values = malloc((size_t)(6 * np) * sizeof *values);
  assert_non_null(values);
  assert_int_equal(anitet_mesh_get_metric(m, values, 6 * np), ANITET_OK);
  for (i = 0; i < 6; ++i) assert_true(values[6 * (np - 1) + i] == t[i]);
  free(values);
  anitet_mesh_destroy(m);
  anitet_metric_destroy(metric);
  /* A callback that fails, and one that is not positive definite: INVALID_ARGUMENT naming it. */
  assert_int_equal(anitet_metric_create_analytic(fails_below_zero, NULL, &metric), ANITET_OK);
  m = (anitet_mesh*)1;
  assert_int_equal(anitet_mesher_run(s, metric, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "metric callback returned 7 at ("));
  anitet_metric_destroy(metric);
  assert_int_equal(anitet_metric_create_analytic(not_positive, NULL, &metric), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, metric, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "not positive definite"));
  anitet_metric_destroy(metric);
  anitet_surface_destroy(s);
}

static void test_mesher_open_surface(void** state) {
  anitet_surface* s = NULL;
  anitet_mesh* m = (anitet_mesh*)1;
  struct progress_log r;
  anitet_options o = with_callbacks(&r);
  (void)state;
  assert_int_equal(anitet_surface_create(kCubeXyz, 8, kCubeTri, 11, NULL, 0, &s), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, NULL, &o, &m), ANITET_ERR_OPEN_BOUNDARY);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "anitet_mesher_run"));
  assert_true(r.error_lines >= 1); /* the problem went to the log */
  assert_string_equal(r.stages, "validate ");
  anitet_surface_destroy(s);
}

static void test_mesher_self_intersection(void** state) {
  anitet_surface* s = NULL;
  anitet_mesh* m = (anitet_mesh*)1;
  double xyz[48];
  int32_t tri[72];
  int i, rc;
  (void)state;
  /* One shell crossing itself: a closed, manifold surface with 10 intersecting pairs. */
  assert_int_equal(anitet_surface_read(ANITET_SURFACES_DIR "/bimba_selfx.obj", &s), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, NULL, NULL, &m), ANITET_ERR_SELF_INTERSECTION);
  assert_null(m);
  assert_true(contains(anitet_last_error_message(), "intersect"));
  anitet_surface_destroy(s);
  /* Two cubes crossing each other. */
  for (i = 0; i < 24; ++i) xyz[i] = kCubeXyz[i], xyz[24 + i] = kCubeXyz[i] + 0.5;
  for (i = 0; i < 36; ++i) tri[i] = kCubeTri[i], tri[36 + i] = kCubeTri[i] + 8;
  assert_int_equal(anitet_surface_create(xyz, 16, tri, 24, NULL, 0, &s), ANITET_OK);
  rc = anitet_mesher_run(s, NULL, NULL, &m);
  assert_true(rc == ANITET_ERR_INTERSECTING_SHELLS || rc == ANITET_ERR_SELF_INTERSECTION);
  assert_null(m);
  anitet_surface_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_mesher_sphere),
      cmocka_unit_test(test_mesher_cube_and_file),
      cmocka_unit_test(test_mesher_deterministic),
      cmocka_unit_test(test_mesher_progress_and_log),
      cmocka_unit_test(test_mesher_cancel_at_every_stage),
      cmocka_unit_test(test_options_versions),
      cmocka_unit_test(test_mesher_bad_options),
      cmocka_unit_test(test_mesher_null_arguments),
      cmocka_unit_test(test_mesher_with_metric),
      cmocka_unit_test(test_mesher_open_surface),
      cmocka_unit_test(test_mesher_self_intersection),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
