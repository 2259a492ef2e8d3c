/* Helpers of the C ABI tests that read meshes back: include after <cmocka.h> (they assert). */
#ifndef ANITET_CAPI_MESH_UTIL_H
#define ANITET_CAPI_MESH_UTIL_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "anitet.h"

/* The last error message holds `words`. */
static inline void expect_message(const char* words) {
  if (strstr(anitet_last_error_message(), words) == NULL)
    fail_msg("message '%s' lacks '%s'", anitet_last_error_message(), words);
}

static inline int64_t points_of(const anitet_mesh* m) {
  int64_t np = 0;
  assert_int_equal(anitet_mesh_get_counts(m, &np, NULL, NULL), ANITET_OK);
  return np;
}

/* The mesh's points, 3 per vertex; the caller frees them. */
static inline double* points(const anitet_mesh* m) {
  const int64_t np = points_of(m);
  double* xyz = malloc((size_t)(3 * np) * sizeof *xyz);
  assert_non_null(xyz);
  assert_int_equal(anitet_mesh_get_points(m, xyz, 3 * np), ANITET_OK);
  return xyz;
}

#endif
