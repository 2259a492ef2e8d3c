/* Per-vertex fields through the C ABI: anitet_fields from arrays and .sol/.solb files, and their
 * transfer from one mesh to another's vertices (anitet_mesh_transfer_fields); every documented
 * error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "anitet.h"
#include "capi_mesh_util.h"
#include "test_boxes.h"

/* A scalar 1 + 2x - y + 3z, a vector (x, y - z, 2z) and a tensor (SPD, varying linearly, so its
 * linear interpolation is exact) per point: 10 values a record. */
enum { RECORD = 10 };
static const int32_t kKinds[3] = {ANITET_FIELD_KIND_SCALAR, ANITET_FIELD_KIND_VECTOR,
                                  ANITET_FIELD_KIND_SYM_TENSOR};

static void linear_record(const double* p, double* r) {
  const double x = p[0], y = p[1], z = p[2];
  r[0] = 1.0 + 2.0 * x - y + 3.0 * z;
  r[1] = x, r[2] = y - z, r[3] = 2.0 * z;
  r[4] = 10.0 + x, r[5] = 0.5, r[6] = 10.0 + y, r[7] = 0.0, r[8] = 0.25 * z, r[9] = 10.0 + z;
}

static anitet_fields* linear_fields(const anitet_mesh* m) {
  const int64_t np = points_of(m);
  double* xyz = points(m);
  double* values = malloc((size_t)(RECORD * np) * sizeof *values);
  anitet_fields* f = NULL;
  int64_t i;
  assert_non_null(values);
  for (i = 0; i < np; ++i) linear_record(&xyz[3 * i], &values[RECORD * i]);
  assert_int_equal(anitet_fields_create(kKinds, 3, values, RECORD * np, &f), ANITET_OK);
  free(values), free(xyz);
  return f;
}

static void test_create_and_get(void** state) {
  const double values[2 * RECORD] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20};
  anitet_fields* f = NULL;
  int32_t nf = 0, record = 0, kinds[3] = {0, 0, 0};
  int64_t nv = 0, count = 0;
  const double* data = NULL;
  double copy[2 * RECORD];
  (void)state;
  assert_int_equal(anitet_fields_create(kKinds, 3, values, 2 * RECORD, &f), ANITET_OK);
  assert_int_equal(anitet_fields_get_counts(f, &nf, &record, &nv), ANITET_OK);
  assert_int_equal(nf, 3);
  assert_int_equal(record, RECORD);
  assert_int_equal(nv, 2);
  assert_int_equal(anitet_fields_get_counts(f, NULL, NULL, NULL), ANITET_OK);
  assert_int_equal(anitet_fields_get_kinds(f, kinds, 2), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_fields_get_kinds(f, kinds, 3), ANITET_OK);
  assert_memory_equal(kinds, kKinds, sizeof kinds);
  assert_int_equal(anitet_fields_get_values(f, copy, 2 * RECORD - 1), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_fields_get_values(f, copy, 2 * RECORD), ANITET_OK);
  assert_memory_equal(copy, values, sizeof copy);
  /* Lent: the library's own memory, the same values. */
  assert_int_equal(anitet_fields_get_data(f, &data, &count), ANITET_OK);
  assert_int_equal(count, 2 * RECORD);
  assert_memory_equal(data, values, sizeof values);
  assert_int_equal(anitet_fields_get_data(f, NULL, &count), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_get_data(NULL, &data, &count), ANITET_ERR_INVALID_ARGUMENT);
  /* A transfer report only for fields made by a transfer. */
  assert_int_equal(anitet_fields_get_transfer_report(f, &count, NULL, NULL, 0), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("not made by anitet_mesh_transfer_fields");
  anitet_fields_destroy(f);
  anitet_fields_destroy(NULL);
}

static void test_create_errors(void** state) {
  const double values[RECORD] = {0};
  const int32_t bad_kind[1] = {4};
  anitet_fields* f = (anitet_fields*)1;
  (void)state;
  assert_int_equal(anitet_fields_create(kKinds, 3, values, RECORD, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_create(kKinds, 0, values, RECORD, &f), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(f);
  expect_message("num_fields is 0");
  assert_int_equal(anitet_fields_create(NULL, 3, values, RECORD, &f), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_create(kKinds, 3, NULL, RECORD, &f), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_create(bad_kind, 1, values, 1, &f), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("kind 0 is 4");
  assert_int_equal(anitet_fields_create(kKinds, 3, values, RECORD - 1, &f), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("whole number of records of 10");
  assert_int_equal(anitet_fields_create(kKinds, 3, values, -1, &f), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_create(kKinds, 3, values, 0, &f), ANITET_ERR_EMPTY_INPUT);
  assert_null(f);
}

/* .sol and .solb: written and read back to the same bits. */
static void test_files(void** state) {
  const double values[2 * RECORD] = {0.1, -2e-300, 1.0 / 3.0, 4e300, 5, 6, 7, 8, 9, 10,
                                     11, 12, 13, 14, 15, 16, 17, 18, 19, 3.141592653589793};
  const char* const extensions[2] = {"sol", "solb"};
  anitet_fields *f = NULL, *back = NULL;
  char path[4096];
  int e;
  (void)state;
  assert_int_equal(anitet_fields_create(kKinds, 3, values, 2 * RECORD, &f), ANITET_OK);
  for (e = 0; e < 2; ++e) {
    double copy[2 * RECORD];
    int32_t kinds[3];
    snprintf(path, sizeof path, "%s/capi_fields.%s", ANITET_TEST_OUTPUT_DIR, extensions[e]);
    assert_int_equal(anitet_fields_write(f, path), ANITET_OK);
    assert_int_equal(anitet_fields_read(path, &back), ANITET_OK);
    assert_int_equal(anitet_fields_get_kinds(back, kinds, 3), ANITET_OK);
    assert_memory_equal(kinds, kKinds, sizeof kinds);
    assert_int_equal(anitet_fields_get_values(back, copy, 2 * RECORD), ANITET_OK);
    assert_memory_equal(copy, values, sizeof copy);
    anitet_fields_destroy(back);
  }
  /* Errors: another extension, a missing file, a malformed one, NULLs. */
  snprintf(path, sizeof path, "%s/capi_fields.txt", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_fields_write(f, path), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_int_equal(anitet_fields_read(path, &back), ANITET_ERR_UNSUPPORTED_FORMAT);
  assert_null(back);
  snprintf(path, sizeof path, "%s/no_such_dir/capi_fields.sol", ANITET_TEST_OUTPUT_DIR);
  assert_int_equal(anitet_fields_write(f, path), ANITET_ERR_FILE_NOT_FOUND);
  assert_int_equal(anitet_fields_read(path, &back), ANITET_ERR_FILE_NOT_FOUND);
  snprintf(path, sizeof path, "%s/capi_fields_bad.sol", ANITET_TEST_OUTPUT_DIR);
  {
    FILE* file = fopen(path, "w");
    assert_non_null(file);
    fputs("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n1 1\n0.5\n", file);
    fclose(file);
  }
  assert_int_equal(anitet_fields_read(path, &back), ANITET_ERR_PARSE);
  assert_null(back);
  assert_int_equal(anitet_fields_read(NULL, &back), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_write(NULL, path), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_fields_write(f, NULL), ANITET_ERR_INVALID_ARGUMENT);
  anitet_fields_destroy(f);
}

/* Linear fields on a 4^3 grid of cubes carried to the points of a 3^3 one inside it: exact to
 * rounding, the tensor in log space (AUTO: every tensor SPD), then linearly. */
static void test_transfer_linear(void** state) {
  anitet_mesh *from = test_boxes(1, 4, 4, 4, 0), *to = test_boxes(1, 3, 3, 3, 0);
  anitet_fields *f, *moved = NULL;
  int64_t np_to, nv = 0, outside = -1, i;
  double *xyz, *values, max_distance = -1.0, worst = 0.0, worst_tensor = 0.0;
  int32_t log_flags[3] = {-1, -1, -1}, nf = 0;
  int k;
  (void)state;
  assert_non_null(from);
  assert_non_null(to);
  f = linear_fields(from);
  np_to = points_of(to);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, ANITET_TENSORS_LINEAR, &moved), ANITET_OK);
  assert_int_equal(anitet_fields_get_counts(moved, &nf, NULL, &nv), ANITET_OK);
  assert_int_equal(nf, 3);
  assert_int_equal(nv, np_to);
  xyz = points(to);
  values = malloc((size_t)(RECORD * np_to) * sizeof *values);
  assert_non_null(values);
  assert_int_equal(anitet_fields_get_values(moved, values, RECORD * np_to), ANITET_OK);
  for (i = 0; i < np_to; ++i) {
    double expected[RECORD];
    linear_record(&xyz[3 * i], expected);
    for (k = 0; k < RECORD; ++k) worst = fmax(worst, fabs(values[RECORD * i + k] - expected[k]));
  }
  assert_true(worst < 1e-12);
  assert_int_equal(anitet_fields_get_transfer_report(moved, &outside, &max_distance, log_flags, 3), ANITET_OK);
  assert_int_equal(outside, 0);
  assert_true(max_distance == 0.0);
  assert_int_equal(log_flags[0], 0);
  assert_int_equal(log_flags[2], 0);
  assert_int_equal(anitet_fields_get_transfer_report(moved, NULL, NULL, log_flags, 2), ANITET_ERR_BUFFER_TOO_SMALL);
  anitet_fields_destroy(moved);
  /* AUTO: the tensors are SPD, so in log space (not exact for a linear tensor, but close: the
   * tensors vary by a few percent over a cell); scalars and vectors still exact. */
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, ANITET_TENSORS_AUTO, &moved), ANITET_OK);
  assert_int_equal(anitet_fields_get_transfer_report(moved, NULL, NULL, log_flags, 3), ANITET_OK);
  assert_int_equal(log_flags[0], 0);
  assert_int_equal(log_flags[1], 0);
  assert_int_equal(log_flags[2], 1);
  assert_int_equal(anitet_fields_get_values(moved, values, RECORD * np_to), ANITET_OK);
  worst = 0.0;
  for (i = 0; i < np_to; ++i) {
    double expected[RECORD];
    linear_record(&xyz[3 * i], expected);
    for (k = 0; k < 4; ++k) worst = fmax(worst, fabs(values[RECORD * i + k] - expected[k]));
    for (k = 4; k < RECORD; ++k) worst_tensor = fmax(worst_tensor, fabs(values[RECORD * i + k] - expected[k]));
  }
  assert_true(worst < 1e-12);
  assert_true(worst_tensor < 1e-2);
  anitet_fields_destroy(moved);
  free(values), free(xyz);
  anitet_fields_destroy(f);
  anitet_mesh_destroy(to);
  anitet_mesh_destroy(from);
}

/* Points outside the old mesh take the value at its closest boundary point, and are counted. */
static void test_transfer_outside(void** state) {
  anitet_mesh *from = test_boxes(1, 4, 4, 4, 0), *to = test_boxes(1, 5, 1, 1, 0);
  anitet_fields *f, *moved = NULL;
  int64_t outside = 0;
  double max_distance = 0.0;
  (void)state;
  f = linear_fields(from);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, ANITET_TENSORS_AUTO, &moved), ANITET_OK);
  assert_int_equal(anitet_fields_get_transfer_report(moved, &outside, &max_distance, NULL, 0), ANITET_OK);
  assert_int_equal(outside, 4); /* x = 5 on the 2 x 2 points of the last column */
  assert_true(fabs(max_distance - 1.0) < 1e-12);
  anitet_fields_destroy(moved);
  anitet_fields_destroy(f);
  anitet_mesh_destroy(to);
  anitet_mesh_destroy(from);
}

static void test_transfer_errors(void** state) {
  anitet_mesh *from = test_boxes(1, 2, 2, 2, 0), *to = test_boxes(1, 1, 1, 1, 0);
  anitet_fields *f = linear_fields(to), *moved = (anitet_fields*)1, *g;
  const int32_t tensor_kind[1] = {ANITET_FIELD_KIND_SYM_TENSOR};
  double* not_spd;
  int64_t np = points_of(from), i;
  (void)state;
  /* Fields of another mesh. */
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, ANITET_TENSORS_AUTO, &moved), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(moved);
  expect_message("another mesh");
  anitet_fields_destroy(f);
  /* NULLs and an unknown tensor mode. */
  f = linear_fields(from);
  assert_int_equal(anitet_mesh_transfer_fields(NULL, f, to, 0, &moved), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_transfer_fields(from, NULL, to, 0, &moved), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, NULL, 0, &moved), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, 0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, 3, &moved), ANITET_ERR_INVALID_ARGUMENT);
  expect_message("tensors is 3");
  anitet_fields_destroy(f);
  /* A tensor that is not SPD: an error in log space, linear with AUTO. */
  not_spd = calloc((size_t)(6 * np), sizeof *not_spd);
  assert_non_null(not_spd);
  for (i = 0; i < np; ++i) not_spd[6 * i] = not_spd[6 * i + 2] = not_spd[6 * i + 5] = 1.0;
  not_spd[6 * 3 + 5] = -1.0;
  assert_int_equal(anitet_fields_create(tensor_kind, 1, not_spd, 6 * np, &g), ANITET_OK);
  assert_int_equal(anitet_mesh_transfer_fields(from, g, to, ANITET_TENSORS_LOG_EUCLIDEAN, &moved),
                   ANITET_ERR_INVALID_ARGUMENT);
  expect_message("vertex 4 (counting from 1) is not positive definite");
  assert_null(moved);
  assert_int_equal(anitet_mesh_transfer_fields(from, g, to, ANITET_TENSORS_AUTO, &moved), ANITET_OK);
  {
    int32_t flag = -1;
    assert_int_equal(anitet_fields_get_transfer_report(moved, NULL, NULL, &flag, 1), ANITET_OK);
    assert_int_equal(flag, 0);
  }
  anitet_fields_destroy(moved);
  anitet_fields_destroy(g);
  free(not_spd);
  anitet_mesh_destroy(to);
  anitet_mesh_destroy(from);
}

/* anitet_mesh_transfer_fields_ext: the same values on 1 thread and on 2 as on all cores; a
 * negative count refused. */
static void test_transfer_threads(void** state) {
  anitet_mesh *from = test_boxes(1, 4, 4, 4, 0), *to = test_boxes(1, 3, 3, 3, 0);
  anitet_fields *f, *all = NULL, *out = (anitet_fields*)&out;
  const double *a = NULL, *b = NULL;
  int64_t na = 0, nb = 0;
  int32_t threads;
  (void)state;
  f = linear_fields(from);
  assert_int_equal(anitet_mesh_transfer_fields(from, f, to, ANITET_TENSORS_AUTO, &all), ANITET_OK);
  assert_int_equal(anitet_fields_get_data(all, &a, &na), ANITET_OK);
  for (threads = 1; threads <= 2; ++threads) {
    anitet_fields* some = NULL;
    assert_int_equal(anitet_mesh_transfer_fields_ext(from, f, to, ANITET_TENSORS_AUTO, threads, &some), ANITET_OK);
    assert_int_equal(anitet_fields_get_data(some, &b, &nb), ANITET_OK);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, (size_t)na * sizeof *a);
    anitet_fields_destroy(some);
  }
  assert_int_equal(anitet_mesh_transfer_fields_ext(from, f, to, ANITET_TENSORS_AUTO, -1, &out),
                   ANITET_ERR_INVALID_ARGUMENT);
  expect_message("num_threads is -1");
  assert_null(out);
  anitet_fields_destroy(all);
  anitet_fields_destroy(f);
  anitet_mesh_destroy(from);
  anitet_mesh_destroy(to);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_create_and_get),  cmocka_unit_test(test_create_errors),
      cmocka_unit_test(test_files),           cmocka_unit_test(test_transfer_linear),
      cmocka_unit_test(test_transfer_outside), cmocka_unit_test(test_transfer_errors),
      cmocka_unit_test(test_transfer_threads),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
