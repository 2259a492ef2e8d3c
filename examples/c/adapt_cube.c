/* anitet from C: a solver's adaptation loop. The UGAWG linear cube is adapted three times to the
 * analytic metric of the UGAWG benchmark, evaluated at the vertices of each new mesh, with a
 * field carried from mesh to mesh, and the measures printed. The Fortran and Python examples
 * (examples/fortran, examples/python) do the same and must print the same text and write the
 * same files.
 *
 *   adapt_cube CUBE_MESH [OUTPUT_PREFIX]   CUBE_MESH: ../shared/data/ugawg/cube-linear-00.mesh;
 *                                          writes OUTPUT_PREFIX.meshb and OUTPUT_PREFIX.solb */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "anitet.h"

/* UGAWG's linear metric: h_x = h_y = 0.1, h_z = 0.001 + 2 (0.1 - 0.001) |z - 0.5|. */
static void linear_metric(double z, double m[6]) {
  const double hz = 0.001 + 2.0 * (0.1 - 0.001) * fabs(z - 0.5);
  m[0] = 100.0, m[1] = 0.0, m[2] = 100.0, m[3] = 0.0, m[4] = 0.0, m[5] = 1.0 / (hz * hz);
}

static int fail(const char* what, int code) {
  fprintf(stderr, "%s: %s (%s)\n", what, anitet_last_error_message(), anitet_error_name(code));
  return 1;
}

/* The metric at the mesh's points (6 values each) and a solution: the field 1 + 2x - y + 3z. */
static int evaluate(const anitet_mesh* mesh, double** metric, anitet_fields** solution, int64_t* np) {
  static const int32_t kind = ANITET_FIELD_KIND_SCALAR;
  double *xyz, *u;
  int64_t i;
  int rc;
  anitet_mesh_get_counts(mesh, np, NULL, NULL);
  xyz = malloc((size_t)(3 * *np) * sizeof *xyz);
  *metric = malloc((size_t)(6 * *np) * sizeof **metric);
  u = malloc((size_t)*np * sizeof *u);
  if (!xyz || !*metric || !u) return ANITET_ERR_OUT_OF_MEMORY;
  anitet_mesh_get_points(mesh, xyz, 3 * *np);
  for (i = 0; i < *np; ++i) {
    linear_metric(xyz[3 * i + 2], &(*metric)[6 * i]);
    u[i] = 1.0 + 2.0 * xyz[3 * i] - xyz[3 * i + 1] + 3.0 * xyz[3 * i + 2];
  }
  rc = *solution ? ANITET_OK : anitet_fields_create(&kind, 1, u, *np, solution);
  free(xyz), free(u);
  return rc;
}

int main(int argc, char** argv) {
  anitet_mesh *mesh = NULL, *next = NULL;
  anitet_fields *solution = NULL, *carried = NULL;
  anitet_adapt_options options = ANITET_ADAPT_OPTIONS_INIT;
  double* metric = NULL;
  int64_t np = 0;
  int pass, rc, status = 1;

  if (argc < 2) {
    fprintf(stderr, "usage: adapt_cube CUBE_MESH [OUTPUT_PREFIX]\n");
    return 2;
  }
  if ((rc = anitet_mesh_read(argv[1], &mesh)) != ANITET_OK) return fail("read", rc);
  options.num_threads = 1; /* the sweeps are serial: one thread for the transfer and measures too */
  for (pass = 1; pass <= 3; ++pass) {
    anitet_adapt_stats stats = ANITET_ADAPT_STATS_INIT;
    /* A solver would compute its solution and its metric here; the example's are analytic, and
     * the solution is only set on the first mesh and carried after. */
    if ((rc = evaluate(mesh, &metric, &solution, &np)) != ANITET_OK) {
      status = fail("metric", rc);
      goto done;
    }
    rc = anitet_adapt(mesh, metric, 6 * np, 6, solution, &options, &next, &carried, &stats);
    free(metric), metric = NULL;
    if (rc != ANITET_OK) {
      status = fail("adapt", rc);
      goto done;
    }
    anitet_mesh_destroy(mesh), anitet_fields_destroy(solution);
    mesh = next, solution = carried, next = NULL, carried = NULL;
    printf("pass %d: %lld splits, %lld collapses, %lld swaps, %lld moves in %d cycles\n", pass,
           (long long)stats.splits, (long long)stats.collapses, (long long)stats.swaps, (long long)stats.moves,
           (int)stats.cycles);
    printf("mesh: %lld vertices, %lld tets, %lld boundary triangles\n", (long long)stats.vertices,
           (long long)stats.tets, (long long)stats.boundary_triangles);
    printf("edges in range: %.2f%%, mean ratio min %.3f mean %.3f\n", 100.0 * stats.edges_in_range,
           stats.mean_ratio_min, stats.mean_ratio_mean);
  }
  if (argc > 2) {
    char path[4096];
    snprintf(path, sizeof path, "%s.meshb", argv[2]);
    if ((rc = anitet_mesh_write(mesh, path)) != ANITET_OK) {
      status = fail("write mesh", rc);
      goto done;
    }
    snprintf(path, sizeof path, "%s.solb", argv[2]);
    if ((rc = anitet_fields_write(solution, path)) != ANITET_OK) {
      status = fail("write solution", rc);
      goto done;
    }
  }
  status = 0;
done:
  free(metric);
  anitet_fields_destroy(solution);
  anitet_mesh_destroy(mesh);
  return status;
}
