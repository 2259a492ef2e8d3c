/* libanitet_mpi (include/anitet_mpi.h), run under mpirun on 3 ranks: anitet_mesh_scatter from
 * the first and from the last rank (and with the Fortran handle), each rank's part checked
 * (its own tets sum to the mesh's volume and count over the ranks), halo exchanges of vertex and
 * tet fields giving every rank the owners' values, and the errors every rank must see alike. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "anitet_mpi.h"
#include "test_boxes.h"

static int g_rank, g_size;

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

static double volume(const double* xyz, const int32_t* t) {
  const double *a = xyz + 3 * t[0], *b = xyz + 3 * t[1], *c = xyz + 3 * t[2], *d = xyz + 3 * t[3];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
               w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
}

static const void* lent(const anitet_part* part, int32_t array, int64_t* count) {
  const void* data = NULL;
  assert_int_equal(anitet_part_get_array(part, array, &data, count, NULL), ANITET_OK);
  return data;
}

/* Own items get f(global id); the others NaN; after the exchange all must hold f(global id). */
static void check_exchange(const anitet_part* part, int32_t where) {
  int64_t n = 0, owned = 0, i;
  const int64_t* global = lent(part, where == ANITET_FIELD_ON_VERTICES ? ANITET_PART_VERTEX_GLOBAL_IDS
                                                                         : ANITET_PART_TET_GLOBAL_IDS, &n);
  double* values = malloc((size_t)(2 * n + 1) * sizeof *values);
  if (where == ANITET_FIELD_ON_VERTICES)
    assert_int_equal(anitet_part_get_counts(part, NULL, &owned, NULL, NULL, NULL, NULL), ANITET_OK);
  else
    assert_int_equal(anitet_part_get_counts(part, NULL, NULL, NULL, &owned, NULL, NULL), ANITET_OK);
  for (i = 0; i < n; ++i) {
    values[2 * i] = i < owned ? 3.0 * (double)global[i] + 0.5 : NAN;
    values[2 * i + 1] = i < owned ? -(double)global[i] : NAN;
  }
  assert_int_equal(anitet_part_exchange(part, MPI_COMM_WORLD, where, values, 2), ANITET_OK);
  for (i = 0; i < n; ++i) {
    assert_true(values[2 * i] == 3.0 * (double)global[i] + 0.5);
    assert_true(values[2 * i + 1] == -(double)global[i]);
  }
  free(values);
}

static void scatter_and_check(int root, int fortran_handle) {
  anitet_mesh* mesh = g_rank == root ? test_boxes(1, 6, 4, 4, 0) : NULL; /* 576 tets, volume 96 */
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  anitet_part* local = NULL;
  int32_t index = -1, parts = -1, layers = -1;
  int64_t nv = 0, nt = 0, own = 0, own_all = 0, i, c;
  double vol = 0, vol_all = 0;
  const double* xyz;
  const int32_t* tets;
  int rc;
  o.ghost_layers = 2;
  if (g_rank == root) assert_non_null(mesh);
  rc = fortran_handle ? anitet_mesh_scatter_f(mesh, MPI_Comm_c2f(MPI_COMM_WORLD), root, &o, &local)
                      : anitet_mesh_scatter(mesh, MPI_COMM_WORLD, root, &o, &local);
  if (rc != ANITET_OK) fail_msg("scatter: %s", anitet_last_error_message());
  assert_non_null(local);
  assert_int_equal(anitet_part_get_index(local, &index, &parts, NULL, &layers), ANITET_OK);
  assert_int_equal(index, g_rank);
  assert_int_equal(parts, g_size);
  assert_int_equal(layers, 2);
  assert_int_equal(anitet_part_get_counts(local, &nv, NULL, &nt, &own, NULL, NULL), ANITET_OK);
  xyz = lent(local, ANITET_PART_POINTS, &c);
  tets = lent(local, ANITET_PART_TETS, &c);
  for (i = 0; i < own; ++i) vol += volume(xyz, tets + 4 * i);
  MPI_Allreduce(&own, &own_all, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&vol, &vol_all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  assert_int_equal(own_all, 576);
  assert_true(fabs(vol_all - 96.0) <= 1e-12 * 96.0);
  check_exchange(local, ANITET_FIELD_ON_VERTICES);
  check_exchange(local, ANITET_FIELD_ON_TETS);
  anitet_part_destroy(local);
  anitet_mesh_destroy(mesh);
}

static void test_scatter_from_first_rank(void** state) {
  (void)state;
  scatter_and_check(0, 0);
}

static void test_scatter_from_last_rank(void** state) {
  (void)state;
  scatter_and_check(g_size - 1, 0);
}

static void test_scatter_with_fortran_handle(void** state) {
  (void)state;
  scatter_and_check(0, 1);
}

static void test_scatter_on_one_rank(void** state) {
  /* MPI_COMM_SELF: every rank is its own root and holds the whole mesh, without neighbours. */
  anitet_mesh* mesh = test_boxes(1, 2, 2, 2, 0);
  anitet_part* local = NULL;
  int32_t index = -1, parts = -1, neighbours = -1;
  int64_t nt = 0, own = 0;
  double values[27 * 2];
  (void)state;
  assert_int_equal(anitet_mesh_scatter(mesh, MPI_COMM_SELF, 0, NULL, &local), ANITET_OK);
  assert_int_equal(anitet_part_get_index(local, &index, &parts, &neighbours, NULL), ANITET_OK);
  assert_int_equal(index, 0);
  assert_int_equal(parts, 1);
  assert_int_equal(neighbours, 0);
  assert_int_equal(anitet_part_get_counts(local, NULL, NULL, &nt, &own, NULL, NULL), ANITET_OK);
  assert_int_equal(nt, 48);
  assert_int_equal(own, 48);
  assert_int_equal(anitet_part_exchange(local, MPI_COMM_SELF, ANITET_FIELD_ON_VERTICES, values, 2), ANITET_OK);
  /* A part of one rank's communicator is not a part of MPI_COMM_WORLD's ranks. */
  assert_int_equal(anitet_part_exchange(local, MPI_COMM_WORLD, ANITET_FIELD_ON_VERTICES, values, 2),
                   g_size == 1 ? ANITET_OK : ANITET_ERR_INVALID_ARGUMENT);
  if (g_size > 1) assert_true(contains(anitet_last_error_message(), "not this rank's part"));
  assert_int_equal(anitet_part_exchange(local, MPI_COMM_SELF, ANITET_FIELD_ON_VERTICES, NULL, 2),
                   ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_exchange(local, MPI_COMM_SELF, ANITET_FIELD_ON_VERTICES, values, 0),
                   ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_exchange(local, MPI_COMM_SELF, 7, values, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_exchange(NULL, MPI_COMM_SELF, ANITET_FIELD_ON_TETS, values, 1),
                   ANITET_ERR_INVALID_ARGUMENT);
  anitet_part_destroy(local);
  anitet_mesh_destroy(mesh);
}

/* Every rank gets `code`; the message names the root's problem on the root and the root
 * elsewhere. */
static void expect_scatter_error(const anitet_mesh* mesh, int root, const anitet_partition_options* o, int code,
                                 const char* root_message) {
  anitet_part* local = (anitet_part*)o; /* any non-NULL value: it must be reset */
  assert_int_equal(anitet_mesh_scatter(mesh, MPI_COMM_WORLD, root, o, &local), code);
  assert_null(local);
  if (g_rank == root && !contains(anitet_last_error_message(), root_message))
    fail_msg("root message \"%s\" lacks \"%s\"", anitet_last_error_message(), root_message);
  if (g_rank != root && !contains(anitet_last_error_message(), "the root (rank"))
    fail_msg("message \"%s\" does not name the root", anitet_last_error_message());
}

static void test_scatter_errors(void** state) {
  static const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const int32_t tet[4] = {0, 1, 2, 3};
  anitet_mesh* one_tet = NULL;
  anitet_mesh* mesh = g_rank == 0 ? test_boxes(1, 2, 2, 2, 0) : NULL;
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  anitet_part* local = NULL;
  (void)state;
  /* Seen by every rank alone: no communication. */
  assert_int_equal(anitet_mesh_scatter(mesh, MPI_COMM_WORLD, g_size, NULL, &local), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "is not a rank of comm"));
  assert_int_equal(anitet_mesh_scatter(mesh, MPI_COMM_WORLD, -1, NULL, &local), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_scatter(mesh, MPI_COMM_WORLD, 0, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* The root's problems reach every rank. */
  expect_scatter_error(NULL, 0, NULL, ANITET_ERR_INVALID_ARGUMENT, "mesh is NULL on the root");
  o.version = 99;
  expect_scatter_error(mesh, 0, &o, ANITET_ERR_INVALID_ARGUMENT, "version 99");
  o.version = ANITET_PARTITION_OPTIONS_VERSION;
  o.ghost_layers = -1;
  expect_scatter_error(mesh, 0, &o, ANITET_ERR_INVALID_ARGUMENT, "ghost_layers");
  if (g_size > 1) {
    assert_int_equal(anitet_mesh_create(xyz, 4, tet, 1, NULL, NULL, 0, NULL, 0, &one_tet), ANITET_OK);
    expect_scatter_error(g_rank == 0 ? one_tet : NULL, 0, NULL, ANITET_ERR_INVALID_ARGUMENT, "not in [1, 1]");
    anitet_mesh_destroy(one_tet);
  }
  anitet_mesh_destroy(mesh);
}

int main(int argc, char** argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_scatter_from_first_rank),
      cmocka_unit_test(test_scatter_from_last_rank),
      cmocka_unit_test(test_scatter_with_fortran_handle),
      cmocka_unit_test(test_scatter_on_one_rank),
      cmocka_unit_test(test_scatter_errors),
  };
  int failed;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  failed = cmocka_run_group_tests(tests, NULL, NULL);
  MPI_Finalize();
  return failed;
}
