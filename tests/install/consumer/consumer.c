/* A program outside the project, built against an installed anitet (find_package or
 * pkg-config): it must compile, link, mesh and run with nothing but the installed files. */
#include <stdio.h>
#include <string.h>

#include <anitet.h>

#include "sphere_surface.h" /* examples/c */

int main(void) {
  static double xyz[3 * SPHERE_NPOINTS];
  static int32_t tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI];
  anitet_surface* s = NULL;
  anitet_mesh* m = NULL;
  anitet_quality q = ANITET_QUALITY_INIT;
  int64_t np = 0, nt = 0;
  int rc;
  if (strcmp(anitet_version(), ANITET_VERSION_STRING) != 0) return 1;
  sphere_build(xyz, tri, patch);
  if (anitet_surface_create(xyz, SPHERE_NPOINTS, tri, SPHERE_NTRI, patch, 0, &s) != ANITET_OK) return 2;
  rc = anitet_mesher_run(s, NULL, NULL, &m);
  if (rc != ANITET_OK) {
    fprintf(stderr, "%s\n", anitet_last_error_message());
    anitet_surface_destroy(s);
    return 3;
  }
  rc = anitet_mesh_get_counts(m, &np, &nt, NULL) || anitet_mesh_quality(m, s, &q);
  anitet_mesh_destroy(m);
  anitet_surface_destroy(s);
  if (rc != 0 || !q.valid || !q.boundary_constrained || nt <= 0) return 4;
  printf("anitet %s: consumer meshed %lld vertices, %lld tets\n", anitet_version(), (long long)np,
         (long long)nt);
  return 0;
}
