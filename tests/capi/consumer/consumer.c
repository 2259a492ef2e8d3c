/* A program outside the project, built against an installed anitet (find_package or
 * pkg-config): it must compile, link and run with nothing but the installed files. */
#include <stdio.h>
#include <string.h>

#include <anitet.h>

int main(void) {
  static const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const int32_t tri[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  anitet_surface* s = NULL;
  anitet_mesh* m = NULL;
  int rc;
  if (strcmp(anitet_version(), ANITET_VERSION_STRING) != 0) return 1;
  if (anitet_surface_create(xyz, 4, tri, 4, NULL, 0, &s) != ANITET_OK) return 2;
  if (anitet_surface_validate(s, NULL) != ANITET_OK) {
    fprintf(stderr, "%s\n", anitet_last_error_message());
    return 3;
  }
  rc = anitet_mesher_run(s, NULL, NULL, &m);
  anitet_surface_destroy(s);
  if (rc != ANITET_ERR_NOT_IMPLEMENTED || m != NULL) return 4;
  printf("anitet %s: consumer ok\n", anitet_version());
  return 0;
}
