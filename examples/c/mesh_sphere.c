/* anitet from C: build a surface in memory, mesh it to an analytic metric (a callback), print
 * the quality report. The Fortran and Python examples (examples/fortran, examples/python) do the
 * same with the same numbers and must print the same text and write the same files.
 *
 *   mesh_sphere [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.mesh and OUTPUT_PREFIX.sol when given
 *
 * The surface is the sphere of sphere_surface.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "anitet.h"

#include "sphere_surface.h"

/* The sizing a solver would supply: edges of hx along x and of hx + 0.2 |z| across it (hx is
 * the user data). Returns non-zero outside the box [-2, 2]^3, where it is not defined. */
static int stretched_metric(double x, double y, double z, double m[6], void* user_data) {
  const double hx = *(const double*)user_data, h = hx + 0.2 * fabs(z);
  if (fabs(x) > 2.0 || fabs(y) > 2.0 || fabs(z) > 2.0) return 1;
  m[0] = 1.0 / (hx * hx), m[1] = 0.0, m[2] = 1.0 / (h * h);
  m[3] = 0.0, m[4] = 0.0, m[5] = 1.0 / (h * h);
  return 0;
}

static int fail(const char* what, int code) {
  fprintf(stderr, "%s: %s (%s)\n", what, anitet_last_error_message(), anitet_error_name(code));
  return 1;
}

int main(int argc, char** argv) {
  static double xyz[3 * SPHERE_NPOINTS];
  static int32_t tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI];
  double hx = 0.25;
  anitet_surface* surface = NULL;
  anitet_metric* metric = NULL;
  anitet_mesh* mesh = NULL;
  anitet_options options = ANITET_OPTIONS_INIT;
  int64_t np = 0, nt = 0, nb = 0, needed = 0;
  int32_t components = 0;
  char* json = NULL;
  int rc, status = 1;

  sphere_build(xyz, tri, patch);
  if ((rc = anitet_surface_create(xyz, SPHERE_NPOINTS, tri, SPHERE_NTRI, patch, 0, &surface)) != ANITET_OK)
    return fail("surface", rc);
  if ((rc = anitet_metric_create_analytic(stretched_metric, &hx, &metric)) != ANITET_OK) {
    status = fail("metric", rc);
    goto done;
  }
  options.layers = 2;
  if ((rc = anitet_mesher_run(surface, metric, &options, &mesh)) != ANITET_OK) {
    status = fail("mesher", rc);
    goto done;
  }
  anitet_mesh_get_counts(mesh, &np, &nt, &nb);
  anitet_mesh_get_metric_components(mesh, &components);
  printf("surface: %d points, %d triangles\n", SPHERE_NPOINTS, SPHERE_NTRI);
  printf("mesh: %lld vertices, %lld tets, %lld boundary triangles, metric of %d components\n",
         (long long)np, (long long)nt, (long long)nb, (int)components);

  /* The quality report: size query, then the text. */
  anitet_mesh_quality_json(mesh, surface, NULL, 0, &needed);
  json = malloc((size_t)needed);
  if (!json || (rc = anitet_mesh_quality_json(mesh, surface, json, needed, NULL)) != ANITET_OK) {
    status = fail("quality", rc);
    goto done;
  }
  printf("quality: %s\n", json);

  if (argc > 1) {
    char path[4096];
    snprintf(path, sizeof path, "%s.mesh", argv[1]);
    if ((rc = anitet_mesh_write(mesh, path)) != ANITET_OK) {
      status = fail("write mesh", rc);
      goto done;
    }
    snprintf(path, sizeof path, "%s.sol", argv[1]);
    if ((rc = anitet_mesh_write_metric(mesh, path)) != ANITET_OK) {
      status = fail("write metric", rc);
      goto done;
    }
  }
  status = 0;
done:
  free(json);
  anitet_mesh_destroy(mesh);
  anitet_metric_destroy(metric);
  anitet_surface_destroy(surface);
  return status;
}
