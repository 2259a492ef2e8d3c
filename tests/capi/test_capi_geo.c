/* The C ABI's geographic frames: a surface given in longitude, latitude and height meshed in a
 * local frame and moved back (`anitet mesh --geodetic --geodetic-output`), and every error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

/* The unit cube as a box of 0.01 deg x 0.01 deg x 1000 m at (lon 7.44, lat 46.95). */
static double g_lonlat[24];

static anitet_surface* make_geo_box(void) {
  anitet_surface* s = NULL;
  int i;
  for (i = 0; i < 8; ++i) {
    g_lonlat[3 * i] = 7.44 + 0.01 * kCubeXyz[3 * i];
    g_lonlat[3 * i + 1] = 46.95 + 0.01 * kCubeXyz[3 * i + 1];
    g_lonlat[3 * i + 2] = 1000.0 * kCubeXyz[3 * i + 2];
  }
  assert_int_equal(anitet_surface_create(g_lonlat, 8, kCubeTri, 12, kCubePatch, 0, &s), ANITET_OK);
  return s;
}

static void test_mesh_in_a_local_frame(void** state) {
  anitet_surface *geo = make_geo_box(), *local = make_geo_box();
  anitet_geo_frame* frame = NULL;
  anitet_mesh* mesh = NULL;
  anitet_metric* size = NULL;
  double xyz[24], lat = 0, lon = 0, h = -1, *pts;
  int64_t np = 0, i;
  int32_t zone = -1, north = -1;
  (void)state;
  assert_int_equal(anitet_geo_frame_create_centred(ANITET_GEO_ENU, local, &frame), ANITET_OK);
  assert_int_equal(anitet_geo_frame_get(frame, &lat, &lon, &h, &zone, &north), ANITET_OK);
  assert_true(fabs(lat - 46.955) < 1e-9 && fabs(lon - 7.445) < 1e-9 && fabs(h - 500.0) < 1e-9);
  assert_int_equal(zone, 0);
  assert_int_equal(anitet_surface_to_local(local, frame), ANITET_OK);
  /* Metres: the box is about 760 m east-west, 1110 m north-south, 1000 m high. */
  assert_int_equal(anitet_surface_get_points(local, xyz, 24), ANITET_OK);
  assert_true(fabs(xyz[3] - xyz[0] - 760.0) < 10.0);
  assert_true(fabs(xyz[10] - xyz[1] - 1112.0) < 10.0);
  assert_true(fabs(xyz[14] - xyz[2] - 1000.0) < 1.0);
  assert_int_equal(anitet_metric_create_uniform(300.0, &size), ANITET_OK);
  assert_int_equal(anitet_mesher_run(local, size, NULL, &mesh), ANITET_OK);
  /* Back to (lon, lat, h): the surface's points exactly as given, the others near the box. */
  assert_int_equal(anitet_mesh_to_geodetic(mesh, frame, geo), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(mesh, &np, NULL, NULL), ANITET_OK);
  assert_true(np > 8);
  pts = malloc((size_t)(3 * np) * sizeof *pts);
  assert_non_null(pts);
  assert_int_equal(anitet_mesh_get_points(mesh, pts, 3 * np), ANITET_OK);
  assert_memory_equal(pts, g_lonlat, sizeof g_lonlat);
  for (i = 8; i < np; ++i) {
    assert_true(pts[3 * i] > 7.44 - 1e-9 && pts[3 * i] < 7.45 + 1e-9);
    assert_true(pts[3 * i + 1] > 46.95 - 1e-9 && pts[3 * i + 1] < 46.96 + 1e-9);
    assert_true(pts[3 * i + 2] > -1.0 && pts[3 * i + 2] < 1001.0);
  }
  free(pts);
  anitet_mesh_destroy(mesh);
  anitet_metric_destroy(size);
  anitet_geo_frame_destroy(frame);
  /* UTM: the origin's zone (32 north at 7.44 E). */
  assert_int_equal(anitet_geo_frame_create(ANITET_GEO_UTM, 46.95, 7.44, 0.0, &frame), ANITET_OK);
  assert_int_equal(anitet_geo_frame_get(frame, NULL, NULL, NULL, &zone, &north), ANITET_OK);
  assert_int_equal(zone, 32);
  assert_int_equal(north, 1);
  anitet_geo_frame_destroy(frame);
  anitet_surface_destroy(local);
  anitet_surface_destroy(geo);
}

static void test_geo_errors(void** state) {
  anitet_surface* s = make_geo_box();
  anitet_geo_frame* frame = (anitet_geo_frame*)1;
  anitet_mesh* made = NULL;
  const int32_t tet[4] = {0, 1, 3, 4};
  double bad[24];
  (void)state;
  assert_int_equal(anitet_geo_frame_create(7, 46.0, 7.0, 0.0, &frame), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(frame);
  assert_true(contains(anitet_last_error_message(), "kind is 7"));
  assert_int_equal(anitet_geo_frame_create(ANITET_GEO_ENU, 95.0, 7.0, 0.0, &frame), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_geo_frame_create(ANITET_GEO_ENU, NAN, 7.0, 0.0, &frame), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_geo_frame_create(ANITET_GEO_ENU, 46.0, 7.0, 0.0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_geo_frame_create_centred(ANITET_GEO_ENU, NULL, &frame), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_geo_frame_get(NULL, NULL, NULL, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* A point out of range: named, nothing moved. */
  memcpy(bad, g_lonlat, sizeof bad);
  bad[3 * 5 + 1] = 120.0;
  {
    anitet_surface* b = NULL;
    double after[24];
    assert_int_equal(anitet_surface_create(bad, 8, kCubeTri, 12, NULL, 0, &b), ANITET_OK);
    assert_int_equal(anitet_geo_frame_create_centred(ANITET_GEO_ENU, b, &frame), ANITET_ERR_INVALID_ARGUMENT);
    assert_int_equal(anitet_geo_frame_create(ANITET_GEO_ENU, 46.95, 7.44, 0.0, &frame), ANITET_OK);
    assert_int_equal(anitet_surface_to_local(b, frame), ANITET_ERR_INVALID_ARGUMENT);
    assert_int_equal(anitet_surface_get_points(b, after, 24), ANITET_OK);
    assert_memory_equal(after, bad, sizeof bad);
    anitet_surface_destroy(b);
  }
  assert_int_equal(anitet_surface_to_local(NULL, frame), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_surface_to_local(s, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* geodetic_surface for a mesh no run made. */
  assert_int_equal(anitet_mesh_create(g_lonlat, 8, tet, 1, NULL, NULL, 0, NULL, 0, &made), ANITET_OK);
  assert_int_equal(anitet_mesh_to_local(made, frame), ANITET_OK);
  assert_int_equal(anitet_mesh_to_geodetic(made, frame, s), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "not made by anitet_mesher_run"));
  assert_int_equal(anitet_mesh_to_geodetic(made, frame, NULL), ANITET_OK);
  assert_int_equal(anitet_mesh_to_geodetic(NULL, frame, NULL), ANITET_ERR_INVALID_ARGUMENT);
  anitet_mesh_destroy(made);
  anitet_geo_frame_destroy(frame);
  anitet_geo_frame_destroy(NULL);
  anitet_surface_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_mesh_in_a_local_frame),
      cmocka_unit_test(test_geo_errors),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
