/* A mesh of grids of cubes for the partition tests (C ABI and MPI). */
#ifndef ANITET_TEST_BOXES_H
#define ANITET_TEST_BOXES_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "anitet.h"

/* Boxes of nx x ny x nz unit cubes side by side along x, `gap` cubes apart (0: sharing a face),
 * each cube in 6 positive tets around its diagonal; region b+1 for box b; no boundary triangles.
 * NULL when anitet_mesh_create fails. */
static anitet_mesh* test_boxes(int boxes, int nx, int ny, int nz, int gap) {
  const int px = nx + 1, py = ny + 1, pz = nz + 1;
  const int64_t np = (int64_t)boxes * px * py * pz, nt = (int64_t)boxes * 6 * nx * ny * nz;
  double* xyz = malloc((size_t)(3 * np) * sizeof *xyz);
  int32_t* tets = malloc((size_t)(4 * nt) * sizeof *tets);
  int32_t* regions = malloc((size_t)nt * sizeof *regions);
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  int64_t v = 0, t = 0;
  int b, i, j, k, p, s;
  anitet_mesh* m = NULL;
  for (b = 0; b < boxes; ++b) {
    const int32_t first = (int32_t)(b * px * py * pz);
    for (k = 0; k < pz; ++k)
      for (j = 0; j < py; ++j)
        for (i = 0; i < px; ++i, ++v) {
          xyz[3 * v] = b * (nx + gap) + i;
          xyz[3 * v + 1] = j;
          xyz[3 * v + 2] = k;
        }
    for (k = 0; k < nz; ++k)
      for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i)
          for (p = 0; p < 6; ++p, ++t) {
            int c[3];
            int32_t q[4];
            c[0] = i, c[1] = j, c[2] = k;
            q[0] = first + (c[2] * py + c[1]) * px + c[0];
            for (s = 0; s < 3; ++s) {
              ++c[perms[p][s]];
              q[s + 1] = first + (c[2] * py + c[1]) * px + c[0];
            }
            if (p == 1 || p == 2 || p == 5) { /* odd permutations: swap to stay positive */
              const int32_t w = q[2];
              q[2] = q[3], q[3] = w;
            }
            memcpy(&tets[4 * t], q, sizeof q);
            regions[t] = b + 1;
          }
  }
  if (anitet_mesh_create(xyz, np, tets, nt, regions, NULL, 0, NULL, 0, &m) != ANITET_OK) m = NULL;
  free(xyz), free(tets), free(regions);
  return m;
}

#endif
