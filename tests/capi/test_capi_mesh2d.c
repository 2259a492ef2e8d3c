/* The C ABI's 2D mesher: PSLGs from arrays and files, anitet_mesh2d_run with the defaults, a
 * constant size, an analytic anisotropic metric and longitude/latitude input, the accessors,
 * the writers, cancellation, and each documented error on bad input (the element named). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "anitet.h"

#if !defined(ANITET_TEST_DATA_DIR) || !defined(ANITET_TEST_OUTPUT_DIR) || !defined(ANITET_SURFACES_DIR)
#error "ANITET_TEST_DATA_DIR, ANITET_TEST_OUTPUT_DIR and ANITET_SURFACES_DIR must be defined"
#endif
#define DATA(name) ANITET_TEST_DATA_DIR "/mesh2d/" name
#define OUT(name) ANITET_TEST_OUTPUT_DIR "/capi_mesh2d_" name

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

/* A 4 x 4 square with a 1 x 1 square hole in its middle (holes are outside). */
static const double kSquareXy[16] = {0, 0, 4, 0, 4, 4, 0, 4, 1.5, 1.5, 2.5, 1.5, 2.5, 2.5, 1.5, 2.5};
static const int32_t kSquareSeg[16] = {1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5};
static const int32_t kSquareLabel[8] = {1, 1, 1, 1, 2, 2, 2, 2};
static const double kSquareHole[2] = {2, 2};

/* Every triangle counter-clockwise; the total area equals the domain's. */
static void check_mesh(const anitet_mesh2d* m, double domain_area) {
  int64_t np = 0, nt = 0, ne = 0;
  assert_int_equal(anitet_mesh2d_get_counts(m, &np, &nt, &ne), ANITET_OK);
  assert_true(np > 0 && nt > 0 && ne > 0);
  double* xy = malloc(sizeof(double) * (size_t)(2 * np));
  int32_t* tri = malloc(sizeof(int32_t) * (size_t)(3 * nt));
  assert_int_equal(anitet_mesh2d_get_points(m, xy, 2 * np), ANITET_OK);
  assert_int_equal(anitet_mesh2d_get_triangles(m, tri, 3 * nt, 0), ANITET_OK);
  double total = 0;
  for (int64_t t = 0; t < nt; ++t) {
    const double* a = &xy[2 * tri[3 * t]];
    const double* b = &xy[2 * tri[3 * t + 1]];
    const double* c = &xy[2 * tri[3 * t + 2]];
    const double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    assert_true(area > 0);
    total += area;
  }
  assert_true(fabs(total - domain_area) <= 1e-9 * domain_area);
  free(xy);
  free(tri);
}

static void test_square_with_hole(void** state) {
  (void)state;
  anitet_pslg* p = NULL;
  assert_int_equal(anitet_pslg_create(kSquareXy, 8, kSquareSeg, 8, kSquareLabel, kSquareHole, 1, 1, &p), ANITET_OK);
  int64_t np = 0, ns = 0, nh = 0;
  assert_int_equal(anitet_pslg_get_counts(p, &np, &ns, &nh), ANITET_OK);
  assert_true(np == 8 && ns == 8 && nh == 1);
  /* The defaults: sizes from the segments' lengths. */
  anitet_mesh2d_options o = ANITET_MESH2D_OPTIONS_INIT;
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_OK);
  check_mesh(m, 15.0);
  /* The input's points first, exactly; each segment kept whole: 8 edges with their labels. */
  assert_int_equal(anitet_mesh2d_get_counts(m, &np, NULL, NULL), ANITET_OK);
  double* xy = malloc(sizeof(double) * (size_t)(2 * np));
  assert_int_equal(anitet_mesh2d_get_points(m, xy, 2 * np), ANITET_OK);
  assert_memory_equal(xy, kSquareXy, sizeof kSquareXy);
  free(xy);
  int64_t ne = 0;
  assert_int_equal(anitet_mesh2d_get_counts(m, NULL, NULL, &ne), ANITET_OK);
  assert_int_equal(ne, 8);
  int32_t edges[16], labels[8];
  assert_int_equal(anitet_mesh2d_get_edges(m, edges, 16, 1), ANITET_OK);
  assert_int_equal(anitet_mesh2d_get_edge_labels(m, labels, 8), ANITET_OK);
  for (int e = 0; e < 8; ++e) {
    assert_true(edges[2 * e] >= 1 && edges[2 * e] <= 8 && edges[2 * e + 1] >= 1 && edges[2 * e + 1] <= 8);
    assert_int_equal(labels[e], edges[2 * e] <= 4 ? 1 : 2);
  }
  /* Too small a buffer: nothing written. */
  int32_t small[4];
  assert_int_equal(anitet_mesh2d_get_edges(m, small, 4, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_mesh2d_get_triangles(m, small, 4, 2), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh2d_destroy(m);
  /* A size much below the segments' lengths: with points allowed on them, the sides get points
   * and the triangles can be good. */
  o.split_segments = 1;
  o.hsize = 0.25;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_OK);
  assert_int_equal(anitet_mesh2d_get_counts(m, NULL, NULL, &ne), ANITET_OK);
  assert_true(ne > 8);
  check_mesh(m, 15.0);
  double min_angle = 0, off = 0, rr = 0, in_range = 0;
  assert_int_equal(anitet_mesh2d_quality(m, &min_angle, &off, &rr, &in_range), ANITET_OK);
  assert_true(min_angle >= 25.0 && off >= 25.0 && rr >= 0.9 && in_range >= 0.95);
  anitet_mesh2d_destroy(m);
  anitet_pslg_destroy(p);
}

static void test_superior_default_and_writers(void** state) {
  (void)state;
  anitet_pslg* p = NULL;
  assert_int_equal(anitet_pslg_read(ANITET_SURFACES_DIR "/superior.poly", &p), ANITET_OK);
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, NULL, NULL, &m), ANITET_OK);
  double off = 0, rr = 0;
  assert_int_equal(anitet_mesh2d_quality(m, NULL, &off, &rr, NULL), ANITET_OK);
  assert_true(off >= 25.0 && rr >= 0.9);
  const char* outputs[] = {OUT("superior.mesh"), OUT("superior.msh"), OUT("superior.vtu"), OUT("superior.14")};
  for (int i = 0; i < 4; ++i) {
    remove(outputs[i]);
    assert_int_equal(anitet_mesh2d_write(m, outputs[i]), ANITET_OK);
    FILE* f = fopen(outputs[i], "r");
    assert_non_null(f);
    fclose(f);
  }
  assert_int_equal(anitet_mesh2d_write(m, OUT("superior.xyz")), ANITET_ERR_UNSUPPORTED_FORMAT);
  anitet_mesh2d_destroy(m);
  anitet_pslg_destroy(p);
}

/* The anisotropic case of docs/mesh2d.md: h_r = 0.001 + 2 (0.1 - 0.001) |r - 0.25| radially
 * about (0.5, 0.5), 0.1 tangentially. */
static int polar_metric(double x, double y, double z, double m[6], void* user_data) {
  (void)z;
  ++*(long*)user_data;
  const double dx = x - 0.5, dy = y - 0.5, r = sqrt(dx * dx + dy * dy);
  const double nx = r > 0 ? dx / r : 1, ny = r > 0 ? dy / r : 0;
  const double hr = 0.001 + 2 * (0.1 - 0.001) * fabs(r - 0.25), a = 1 / (hr * hr), b = 100.0;
  m[0] = a * nx * nx + b * ny * ny;
  m[1] = (a - b) * nx * ny;
  m[2] = a * ny * ny + b * nx * nx;
  m[3] = m[4] = 0;
  m[5] = b;
  return 0;
}

static void test_anisotropic_callback(void** state) {
  (void)state;
  anitet_pslg* p = NULL;
  assert_int_equal(anitet_pslg_read(DATA("square_minus_disk.poly"), &p), ANITET_OK);
  long calls = 0;
  anitet_metric* metric = NULL;
  assert_int_equal(anitet_metric_create_analytic(polar_metric, &calls, &metric), ANITET_OK);
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, metric, NULL, &m), ANITET_OK);
  assert_true(calls > 0);
  double in_range = 0;
  assert_int_equal(anitet_mesh2d_quality(m, NULL, NULL, NULL, &in_range), ANITET_OK);
  assert_true(in_range >= 0.97);
  anitet_mesh2d_destroy(m);
  anitet_metric_destroy(metric);
  anitet_pslg_destroy(p);
}

/* A 1 x 1 degree square at 45 N with a small island, points allowed on its long sides: sizes in
 * metres, the mesh in lon/lat with the input's points exactly as given. */
static void test_geodetic(void** state) {
  (void)state;
  const double xy[16] = {-63.5, 44.5, -62.5, 44.5, -62.5, 45.5, -63.5, 45.5,
                         -63.1, 44.9, -63.1, 45.1, -62.9, 45.1, -62.9, 44.9};
  const int32_t seg[16] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  const double hole[2] = {-63.0, 45.0};
  anitet_pslg* p = NULL;
  assert_int_equal(anitet_pslg_create(xy, 8, seg, 8, NULL, hole, 1, 0, &p), ANITET_OK);
  anitet_mesh2d_options o;
  assert_int_equal(anitet_mesh2d_options_init(&o, ANITET_MESH2D_OPTIONS_VERSION), ANITET_OK);
  o.geodetic = 1;
  o.split_segments = 1;
  o.hsize = 10000.0; /* metres */
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_OK);
  int64_t np = 0;
  assert_int_equal(anitet_mesh2d_get_counts(m, &np, NULL, NULL), ANITET_OK);
  double* out = malloc(sizeof(double) * (size_t)(2 * np));
  assert_int_equal(anitet_mesh2d_get_points(m, out, 2 * np), ANITET_OK);
  assert_memory_equal(out, xy, sizeof xy);
  /* The others in degrees too, in the square (the sides are straight in the local frame, not in
   * degrees: a side along 45.5 N bulges about 120 m, 0.001 degree, toward the pole). */
  for (int64_t v = 8; v < np; ++v)
    assert_true(out[2 * v] > -63.505 && out[2 * v] < -62.495 && out[2 * v + 1] > 44.495 && out[2 * v + 1] < 45.505);
  double in_range = 0;
  assert_int_equal(anitet_mesh2d_quality(m, NULL, NULL, NULL, &in_range), ANITET_OK);
  assert_true(in_range >= 0.95);
  free(out);
  anitet_mesh2d_destroy(m);
  anitet_pslg_destroy(p);
}

static int cancel_at_refine(double fraction, const char* stage, void* user_data) {
  (void)fraction;
  ++*(int*)user_data;
  return strcmp(stage, "refine") == 0;
}

static void test_cancel(void** state) {
  (void)state;
  anitet_pslg* p = NULL;
  assert_int_equal(anitet_pslg_create(kSquareXy, 8, kSquareSeg, 8, NULL, kSquareHole, 1, 1, &p), ANITET_OK);
  anitet_mesh2d_options o = ANITET_MESH2D_OPTIONS_INIT;
  int calls = 0;
  o.progress = cancel_at_refine;
  o.progress_user_data = &calls;
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_ERR_CANCELLED);
  assert_null(m);
  assert_true(calls >= 4);
  anitet_pslg_destroy(p);
}

static void test_bad_input_named(void** state) {
  (void)state;
  struct {
    const char* file;
    int code;
    const char* named;
  } cases[] = {
      {DATA("crossing.poly"), ANITET_ERR_SELF_INTERSECTION, "segment 2 (line 9) and segment 4 (line 11)"},
      {DATA("open_loop.poly"), ANITET_ERR_OPEN_BOUNDARY, "segment 1 (line 8)"},
      {DATA("hole_outside.poly"), ANITET_ERR_INVALID_ARGUMENT, "hole 1 (line 21)"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    anitet_pslg* p = NULL;
    assert_int_equal(anitet_pslg_read(cases[i].file, &p), ANITET_OK);
    anitet_mesh2d* m = (anitet_mesh2d*)p; /* must be reset to NULL */
    assert_int_equal(anitet_mesh2d_run(p, NULL, NULL, &m), cases[i].code);
    assert_null(m);
    assert_true(contains(anitet_last_error_message(), cases[i].named));
    anitet_pslg_destroy(p);
  }
  /* Arrays: a segment to a missing point, too few segments, NULL pointers, bad options. */
  anitet_pslg* p = NULL;
  const int32_t bad_seg[16] = {1, 2, 2, 3, 3, 4, 4, 9, 5, 6, 6, 7, 7, 8, 8, 5};
  assert_int_equal(anitet_pslg_create(kSquareXy, 8, bad_seg, 8, NULL, NULL, 0, 1, &p), ANITET_ERR_BAD_INDEX);
  assert_true(contains(anitet_last_error_message(), "segment 4"));
  assert_int_equal(anitet_pslg_create(kSquareXy, 8, kSquareSeg, 2, NULL, NULL, 0, 1, &p), ANITET_ERR_EMPTY_INPUT);
  assert_int_equal(anitet_pslg_create(NULL, 8, kSquareSeg, 8, NULL, NULL, 0, 1, &p), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_pslg_read(DATA("missing.poly"), &p), ANITET_ERR_FILE_NOT_FOUND);
  assert_null(p);
  assert_int_equal(anitet_pslg_create(kSquareXy, 8, kSquareSeg, 8, NULL, kSquareHole, 1, 1, &p), ANITET_OK);
  anitet_mesh2d_options o = ANITET_MESH2D_OPTIONS_INIT;
  o.version = 0;
  anitet_mesh2d* m = NULL;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  o.version = ANITET_MESH2D_OPTIONS_VERSION;
  o.hgrad = 0.5;
  assert_int_equal(anitet_mesh2d_run(p, NULL, &o, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "hgrad"));
  assert_int_equal(anitet_mesh2d_run(NULL, NULL, NULL, &m), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh2d_options_init(&o, 99), ANITET_ERR_INVALID_ARGUMENT);
  anitet_pslg_destroy(p);
  anitet_pslg_destroy(NULL);
  anitet_mesh2d_destroy(NULL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_square_with_hole),   cmocka_unit_test(test_superior_default_and_writers),
      cmocka_unit_test(test_anisotropic_callback), cmocka_unit_test(test_geodetic),
      cmocka_unit_test(test_cancel),             cmocka_unit_test(test_bad_input_named),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
