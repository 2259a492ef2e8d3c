/* anitet from C: a boundary layer. The example sphere (patches 1-3) inside the box [-3, 3]^3
 * (patch 4), meshed with a boundary layer on the sphere; the patches named; the run's
 * boundary-layer report read through anitet_mesh_get_run_stats and printed. The Fortran and
 * Python examples (examples/fortran/boundary_layer.f90, examples/python/boundary_layer.py) print
 * the same text and write the same file.
 *
 *   boundary_layer [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.su2 (markers named) when given
 *
 * The sphere is the one of sphere_surface.h. */
#include <stdio.h>

#include "anitet.h"

#include "sphere_surface.h"

enum { NPOINTS = SPHERE_NPOINTS + 8, NTRI = SPHERE_NTRI + 12 };

/* The sphere, then the box's 8 corners and 12 triangles (patch 4), 0-based, counter-clockwise
 * seen from outside. The sphere is a cavity of the box: the validation's repairs (on by default)
 * turn it inward. */
static void sphere_in_box(double* xyz, int32_t* tri, int32_t* patch) {
  static const int32_t box_tri[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  int i;
  sphere_build(xyz, tri, patch);
  for (i = 0; i < 8; ++i) {
    double* p = &xyz[3 * (SPHERE_NPOINTS + i)];
    p[0] = (i & 1) ? 3.0 : -3.0, p[1] = (i & 2) ? 3.0 : -3.0, p[2] = (i & 4) ? 3.0 : -3.0;
  }
  for (i = 0; i < 36; ++i) tri[3 * SPHERE_NTRI + i] = SPHERE_NPOINTS + box_tri[i];
  for (i = 0; i < 12; ++i) patch[SPHERE_NTRI + i] = 4;
}

static int fail(const char* what, int code) {
  fprintf(stderr, "%s: %s (%s)\n", what, anitet_last_error_message(), anitet_error_name(code));
  return 1;
}

static void print_report(const anitet_run_stats* s) {
  printf("boundary layer: %d layers, %lld wall vertices, %lld full columns, %lld nominal columns,"
         " %lld reduced vertices, %lld tets\n",
         (int)s->bl_layers, (long long)s->bl_wall_vertices, (long long)s->bl_full_columns,
         (long long)s->bl_nominal_columns, (long long)s->bl_reduced_vertices, (long long)s->bl_tets);
  printf("first height: min %.6f, mean %.6f, max %.6f\n", s->bl_first_height_min,
         s->bl_first_height_mean, s->bl_first_height_max);
  printf("growth: mean %.6f; max height error %.6f\n", s->bl_growth_mean, s->bl_max_height_error);
}

int main(int argc, char** argv) {
  static double xyz[3 * NPOINTS];
  static int32_t tri[3 * NTRI], patch[NTRI];
  static const int32_t walls[3] = {1, 2, 3};
  static const char* const names[4] = {"sphere_south", "sphere_band", "sphere_north", "farfield"};
  anitet_surface* surface = NULL;
  anitet_mesh* mesh = NULL;
  anitet_options options = ANITET_OPTIONS_INIT;
  anitet_run_stats stats = ANITET_RUN_STATS_INIT;
  anitet_quality quality = ANITET_QUALITY_INIT;
  int64_t np = 0, nt = 0, nb = 0;
  int rc, i, status = 1;

  sphere_in_box(xyz, tri, patch);
  if ((rc = anitet_surface_create(xyz, NPOINTS, tri, NTRI, patch, 0, &surface)) != ANITET_OK)
    return fail("surface", rc);
  /* The walls: read during anitet_mesher_run only. */
  options.bl_num_patches = 3;
  options.bl_patches = walls;
  options.bl_first_height = 0.02;
  options.bl_growth = 1.25;
  options.bl_layers = 5;
  options.hgrad = 1.3;
  if ((rc = anitet_mesher_run(surface, NULL, &options, &mesh)) != ANITET_OK) {
    status = fail("mesher", rc);
    goto done;
  }
  if ((rc = anitet_mesh_get_run_stats(mesh, &stats)) != ANITET_OK ||
      (rc = anitet_mesh_get_counts(mesh, &np, &nt, &nb)) != ANITET_OK ||
      (rc = anitet_mesh_quality(mesh, surface, &quality)) != ANITET_OK) {
    status = fail("report", rc);
    goto done;
  }
  printf("surface: %d points, %d triangles\n", NPOINTS, NTRI);
  printf("mesh: %lld vertices, %lld tets, %lld boundary triangles\n", (long long)np, (long long)nt,
         (long long)nb);
  printf("quality: valid %d, boundary constrained %d\n", (int)quality.valid,
         (int)quality.boundary_constrained);
  print_report(&stats);
  for (i = 0; i < 4; ++i) {
    if ((rc = anitet_mesh_set_patch_name(mesh, i + 1, names[i])) != ANITET_OK) {
      status = fail("patch name", rc);
      goto done;
    }
    printf("patch %d: %s\n", i + 1, names[i]);
  }
  if (argc > 1) {
    char path[4096];
    snprintf(path, sizeof path, "%s.su2", argv[1]);
    if ((rc = anitet_mesh_write(mesh, path)) != ANITET_OK) {
      status = fail("write", rc);
      goto done;
    }
  }
  status = 0;
done:
  anitet_mesh_destroy(mesh);
  anitet_surface_destroy(surface);
  return status;
}
