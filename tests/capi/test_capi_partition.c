/* The C ABI's partitions (include/anitet.h, "Partitions"): anitet_mesh_partition on grids of
 * cubes and on the mesher's sphere, every accessor against the definitions of the header (every
 * tet own in one part, every ghost tet own on its owner, the halo lists of two neighbours naming
 * the same global ids), index_base 1, lent arrays, bytes, threads, and every documented error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"
#include "test_boxes.h"
#include "sphere_surface.h" /* examples/c: the surface every example meshes */

static int contains(const char* text, const char* part) { return strstr(text, part) != NULL; }

/* ---- meshes --------------------------------------------------------------------------------- */

static anitet_mesh* make_sphere_mesh(void) {
  static double xyz[3 * SPHERE_NPOINTS];
  static int32_t tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI];
  anitet_surface* s = NULL;
  anitet_mesh* m = NULL;
  sphere_build(xyz, tri, patch);
  assert_int_equal(anitet_surface_create(xyz, SPHERE_NPOINTS, tri, SPHERE_NTRI, patch, 0, &s), ANITET_OK);
  assert_int_equal(anitet_mesher_run(s, NULL, NULL, &m), ANITET_OK);
  anitet_surface_destroy(s);
  return m;
}

static anitet_partition* partition_ok(const anitet_mesh* m, int32_t parts, const anitet_partition_options* o) {
  anitet_partition* p = NULL;
  const int rc = anitet_mesh_partition(m, parts, o, &p);
  if (rc != ANITET_OK) fail_msg("anitet_mesh_partition: %s", anitet_last_error_message());
  assert_non_null(p);
  assert_string_equal(anitet_last_error_message(), "");
  return p;
}

static const void* lent(const anitet_part* part, int32_t array, int64_t* count, int32_t type) {
  const void* data = NULL;
  int32_t got = -1;
  assert_int_equal(anitet_part_get_array(part, array, &data, count, &got), ANITET_OK);
  assert_int_equal(got, type);
  return data;
}

static int has_own_tet(const anitet_part* part, int64_t global) {
  int64_t n = 0, owned = 0, lo = 0, hi;
  const int64_t* ids = lent(part, ANITET_PART_TET_GLOBAL_IDS, &n, ANITET_TYPE_INT64);
  assert_int_equal(anitet_part_get_counts(part, NULL, NULL, NULL, &owned, NULL, NULL), ANITET_OK);
  hi = owned;
  while (lo < hi) { /* own tets come first, ascending */
    const int64_t mid = (lo + hi) / 2;
    if (ids[mid] < global) lo = mid + 1;
    else hi = mid;
  }
  return lo < owned && ids[lo] == global;
}

/* The header's promises, checked through the ABI alone. */
static void check_partition(const anitet_mesh* m, const anitet_partition* pt, int32_t num_parts, double max_imbalance) {
  int64_t np = 0, nt = 0, i, k;
  int32_t p, *tet_parts, *own;
  anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
  assert_int_equal(anitet_mesh_get_counts(m, &np, &nt, NULL), ANITET_OK);
  assert_int_equal(anitet_partition_get_info(pt, &info), ANITET_OK);
  assert_int_equal(info.num_parts, num_parts);
  assert_int_equal(info.num_tets, nt);
  assert_true(info.imbalance <= max_imbalance + 1e-12);
  assert_true(info.imbalance >= 0);
  tet_parts = malloc((size_t)nt * sizeof *tet_parts);
  own = calloc((size_t)nt, sizeof *own);
  assert_int_equal(anitet_partition_get_tet_parts(pt, tet_parts, nt), ANITET_OK);
  for (p = 0; p < num_parts; ++p) {
    const anitet_part* part = NULL;
    int32_t index = -1, n_parts = -1, n_nb = -1, layers = -1, list;
    int64_t nv = 0, nov = 0, ntl = 0, not_ = 0, nb = 0, nob = 0, c;
    const int64_t *tg, *vg;
    const int32_t *towner, *tlayer, *vowner, *nbs;
    int64_t* ids;
    assert_int_equal(anitet_partition_get_part(pt, p, &part), ANITET_OK);
    assert_int_equal(anitet_part_get_index(part, &index, &n_parts, &n_nb, &layers), ANITET_OK);
    assert_int_equal(index, p);
    assert_int_equal(n_parts, num_parts);
    assert_int_equal(layers, info.ghost_layers);
    assert_int_equal(anitet_part_get_counts(part, &nv, &nov, &ntl, &not_, &nb, &nob), ANITET_OK);
    tg = lent(part, ANITET_PART_TET_GLOBAL_IDS, &c, ANITET_TYPE_INT64);
    assert_int_equal(c, ntl);
    towner = lent(part, ANITET_PART_TET_OWNERS, &c, ANITET_TYPE_INT32);
    tlayer = lent(part, ANITET_PART_TET_LAYERS, &c, ANITET_TYPE_INT32);
    vg = lent(part, ANITET_PART_VERTEX_GLOBAL_IDS, &c, ANITET_TYPE_INT64);
    assert_int_equal(c, nv);
    vowner = lent(part, ANITET_PART_VERTEX_OWNERS, &c, ANITET_TYPE_INT32);
    nbs = lent(part, ANITET_PART_NEIGHBOURS, &c, ANITET_TYPE_INT32);
    assert_int_equal(c, n_nb);
    for (i = 0; i < ntl; ++i) {
      assert_int_equal(towner[i], tet_parts[tg[i]]);
      assert_int_equal(tlayer[i] == 0, i < not_);
      if (i < not_) {
        assert_int_equal(towner[i], p);
        ++own[tg[i]];
      } else { /* every ghost tet is own on its owner */
        const anitet_part* owner = NULL;
        assert_int_equal(anitet_partition_get_part(pt, towner[i], &owner), ANITET_OK);
        assert_true(has_own_tet(owner, tg[i]));
        assert_true(tlayer[i] >= 1 && tlayer[i] <= layers);
      }
      if (i > 0 && i != not_ && tlayer[i] == tlayer[i - 1]) assert_true(tg[i - 1] < tg[i]);
    }
    for (i = 0; i < nv; ++i) {
      assert_int_equal(vowner[i] == p, i < nov);
      if (i > 0 && i != nov) assert_true(vg[i - 1] < vg[i]);
    }
    /* The fill accessors agree with the lent arrays, +1 with index_base 1. */
    ids = malloc((size_t)(ntl + 1) * sizeof *ids);
    assert_int_equal(anitet_part_get_tet_global_ids(part, ids, ntl, 1), ANITET_OK);
    for (i = 0; i < ntl; ++i) assert_int_equal(ids[i], tg[i] + 1);
    free(ids);
    /* Halo lists: p's SEND to q names the global ids of q's RECV from p, in the same order. */
    for (list = ANITET_HALO_VERTEX_SEND; list <= ANITET_HALO_TET_SEND; list += 2) {
      const int is_vertex = list == ANITET_HALO_VERTEX_SEND;
      const int64_t* so = lent(part, is_vertex ? ANITET_PART_VERTEX_SEND_OFFSETS : ANITET_PART_TET_SEND_OFFSETS, &c,
                               ANITET_TYPE_INT64);
      const int32_t* si = lent(part, is_vertex ? ANITET_PART_VERTEX_SEND : ANITET_PART_TET_SEND, &c, ANITET_TYPE_INT32);
      const int64_t* mine = is_vertex ? vg : tg;
      assert_int_equal(so[0], 0);
      for (k = 0; k < n_nb; ++k) {
        const anitet_part* q = NULL;
        int64_t qn = 0, j, back = -1;
        const int32_t* qnb;
        const int64_t *ro, *qg;
        const int32_t* ri;
        assert_true(nbs[k] != p);
        if (k > 0) assert_true(nbs[k - 1] < nbs[k]);
        assert_int_equal(anitet_partition_get_part(pt, nbs[k], &q), ANITET_OK);
        qnb = lent(q, ANITET_PART_NEIGHBOURS, &qn, ANITET_TYPE_INT32);
        for (j = 0; j < qn; ++j)
          if (qnb[j] == p) back = j;
        assert_true(back >= 0);
        ro = lent(q, is_vertex ? ANITET_PART_VERTEX_RECV_OFFSETS : ANITET_PART_TET_RECV_OFFSETS, &c, ANITET_TYPE_INT64);
        ri = lent(q, is_vertex ? ANITET_PART_VERTEX_RECV : ANITET_PART_TET_RECV, &c, ANITET_TYPE_INT32);
        qg = lent(q, is_vertex ? ANITET_PART_VERTEX_GLOBAL_IDS : ANITET_PART_TET_GLOBAL_IDS, &c, ANITET_TYPE_INT64);
        assert_int_equal(so[k + 1] - so[k], ro[back + 1] - ro[back]);
        for (j = 0; j < so[k + 1] - so[k]; ++j) assert_int_equal(mine[si[so[k] + j]], qg[ri[ro[back] + j]]);
      }
    }
  }
  for (i = 0; i < nt; ++i) assert_int_equal(own[i], 1); /* the union of own tets is the mesh */
  free(tet_parts), free(own);
}

/* ---- success -------------------------------------------------------------------------------- */

static void test_partition_options_init(void** state) {
  anitet_partition_options a = ANITET_PARTITION_OPTIONS_INIT, b;
  (void)state;
  memset(&b, 0x5a, sizeof b);
  assert_int_equal(anitet_partition_options_init(&b, ANITET_PARTITION_OPTIONS_VERSION), ANITET_OK);
  assert_int_equal(memcmp(&a, &b, sizeof a), 0);
  assert_int_equal(b.ghost_layers, 1);
  assert_true(b.imbalance == 0.03);
  assert_null(b.tet_weights);
  assert_int_equal(anitet_partition_options_init(&b, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "version 0"));
  assert_int_equal(anitet_partition_options_init(&b, ANITET_PARTITION_OPTIONS_VERSION + 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_options_init(NULL, 1), ANITET_ERR_INVALID_ARGUMENT);
}

static void test_partition_grid(void** state) {
  anitet_mesh* m = test_boxes(1, 8, 6, 5, 0); /* 1440 tets */
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  int32_t n, depth;
  (void)state;
  for (depth = 0; depth <= 2; ++depth)
    for (n = 1; n <= 8; n *= 2) {
      anitet_partition* pt;
      anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
      o.ghost_layers = depth;
      pt = partition_ok(m, n, &o);
      check_partition(m, pt, n, 0.03);
      assert_int_equal(anitet_partition_get_info(pt, &info), ANITET_OK);
      assert_int_equal(info.ghost_layers, depth);
      assert_int_equal(info.empty_parts, 0);
      assert_true(info.total_weight == 1440.0);
      if (n == 1) assert_int_equal(info.edge_cut, 0);
      else assert_true(info.edge_cut > 0 && info.interface_vertices > 0);
      anitet_partition_destroy(pt);
    }
  anitet_mesh_destroy(m);
}

static void test_partition_sphere_mesh(void** state) {
  anitet_mesh* m = make_sphere_mesh();
  anitet_partition* pt = partition_ok(m, 3, NULL);
  int64_t nb = 0, owned = 0, total = 0, i;
  int32_t p;
  (void)state;
  check_partition(m, pt, 3, 0.03);
  /* Every boundary triangle is own in exactly one part, with the mesh's patch. */
  assert_int_equal(anitet_mesh_get_counts(m, NULL, NULL, &nb), ANITET_OK);
  for (p = 0; p < 3; ++p) {
    const anitet_part* part = NULL;
    int64_t count = 0, own_b = 0, c;
    const int32_t* patches;
    assert_int_equal(anitet_partition_get_part(pt, p, &part), ANITET_OK);
    assert_int_equal(anitet_part_get_counts(part, NULL, NULL, NULL, NULL, &count, &own_b), ANITET_OK);
    patches = lent(part, ANITET_PART_BOUNDARY_PATCHES, &c, ANITET_TYPE_INT32);
    assert_int_equal(c, count);
    for (i = 0; i < count; ++i) assert_true(patches[i] >= 1 && patches[i] <= 3);
    owned += own_b;
    total += count;
  }
  assert_int_equal(owned, nb);
  assert_true(total > nb); /* ghost tets bring the triangles of their neighbours' */
  anitet_partition_destroy(pt);
  anitet_mesh_destroy(m);
}

static void test_partition_disconnected_boxes(void** state) {
  anitet_mesh* m = test_boxes(2, 4, 3, 3, 2); /* two boxes two cubes apart: no vertex shared */
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  int32_t n;
  (void)state;
  o.ghost_layers = 2;
  for (n = 2; n <= 5; ++n) {
    anitet_partition* pt = partition_ok(m, n, &o);
    int32_t p;
    check_partition(m, pt, n, 0.03);
    /* Ghosts stop at the gap: a part holds ghost tets of a box only where it owns tets. */
    for (p = 0; p < n; ++p) {
      const anitet_part* part = NULL;
      int64_t nt = 0, owned = 0, i, c;
      int own_region[3] = {0, 0, 0};
      const int32_t* regions;
      assert_int_equal(anitet_partition_get_part(pt, p, &part), ANITET_OK);
      assert_int_equal(anitet_part_get_counts(part, NULL, NULL, &nt, &owned, NULL, NULL), ANITET_OK);
      regions = lent(part, ANITET_PART_REGIONS, &c, ANITET_TYPE_INT32);
      for (i = 0; i < owned; ++i) own_region[regions[i]] = 1;
      for (i = owned; i < nt; ++i) assert_true(own_region[regions[i]]);
    }
    anitet_partition_destroy(pt);
  }
  anitet_mesh_destroy(m);
}

static void test_partition_weights_and_threads(void** state) {
  anitet_mesh* m = test_boxes(1, 10, 6, 6, 0);
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  anitet_partition *a, *b;
  anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
  int64_t nt = 0, i;
  double* w;
  double load[4] = {0, 0, 0, 0}, total = 0, max = 0;
  int32_t *pa, *pb, *tets;
  (void)state;
  assert_int_equal(anitet_mesh_get_counts(m, NULL, &nt, NULL), ANITET_OK);
  w = malloc((size_t)nt * sizeof *w);
  tets = malloc((size_t)(4 * nt) * sizeof *tets);
  pa = malloc((size_t)nt * sizeof *pa);
  pb = malloc((size_t)nt * sizeof *pb);
  assert_int_equal(anitet_mesh_get_tets(m, tets, 4 * nt, 0), ANITET_OK);
  for (i = 0; i < nt; ++i) w[i] = tets[4 * i] % 11 < 5 ? 4.0 : 1.0;
  o.tet_weights = w;
  o.num_tet_weights = nt;
  o.num_threads = 1;
  a = partition_ok(m, 4, &o);
  o.num_threads = 2;
  b = partition_ok(m, 4, &o);
  assert_int_equal(anitet_partition_get_tet_parts(a, pa, nt), ANITET_OK);
  assert_int_equal(anitet_partition_get_tet_parts(b, pb, nt), ANITET_OK);
  assert_int_equal(memcmp(pa, pb, (size_t)nt * sizeof *pa), 0); /* the same whatever the threads */
  for (i = 0; i < nt; ++i) load[pa[i]] += w[i], total += w[i];
  for (i = 0; i < 4; ++i) max = load[i] > max ? load[i] : max;
  assert_int_equal(anitet_partition_get_info(a, &info), ANITET_OK);
  assert_true(fabs(info.total_weight - total) < 1e-9);
  assert_true(fabs(info.max_part_weight - max) < 1e-9);
  assert_true(max * 4 / total <= 1.03 + 1e-9);
  check_partition(m, a, 4, 0.03);
  anitet_partition_destroy(a), anitet_partition_destroy(b), anitet_mesh_destroy(m);
  free(w), free(tets), free(pa), free(pb);
}

static void test_part_fill_accessors(void** state) {
  anitet_mesh* m = test_boxes(1, 4, 4, 3, 0);
  anitet_partition* pt = partition_ok(m, 3, NULL);
  const anitet_part* part = NULL;
  int64_t nv, nt, nb, i, c, n_items = 0, *off, *off1;
  int32_t n_nb = 0, list, *items, *items1, *tets, *tets1;
  double* xyz;
  const double* lxyz;
  (void)state;
  assert_int_equal(anitet_partition_get_part(pt, 1, &part), ANITET_OK);
  assert_int_equal(anitet_part_get_counts(part, &nv, NULL, &nt, NULL, &nb, NULL), ANITET_OK);
  assert_int_equal(anitet_part_get_index(part, NULL, NULL, &n_nb, NULL), ANITET_OK);
  assert_int_equal(nb, 0); /* the grid has no boundary triangles */
  xyz = malloc((size_t)(3 * nv) * sizeof *xyz);
  assert_int_equal(anitet_part_get_points(part, xyz, 3 * nv), ANITET_OK);
  lxyz = lent(part, ANITET_PART_POINTS, &c, ANITET_TYPE_DOUBLE);
  assert_int_equal(c, 3 * nv);
  assert_int_equal(memcmp(xyz, lxyz, (size_t)c * sizeof *xyz), 0);
  tets = malloc((size_t)(4 * nt) * sizeof *tets);
  tets1 = malloc((size_t)(4 * nt) * sizeof *tets1);
  assert_int_equal(anitet_part_get_tets(part, tets, 4 * nt, 0), ANITET_OK);
  assert_int_equal(anitet_part_get_tets(part, tets1, 4 * nt, 1), ANITET_OK);
  for (i = 0; i < 4 * nt; ++i) assert_int_equal(tets1[i], tets[i] + 1);
  /* A short buffer: BUFFER_TOO_SMALL and nothing written. */
  tets[0] = -7;
  assert_int_equal(anitet_part_get_tets(part, tets, 4 * nt - 1, 0), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(tets[0], -7);
  assert_int_equal(anitet_part_get_tets(part, tets, 4 * nt, 2), ANITET_ERR_INVALID_ARGUMENT);
  for (list = ANITET_HALO_VERTEX_SEND; list <= ANITET_HALO_TET_RECV; ++list) {
    assert_int_equal(anitet_part_get_halo_size(part, list, &n_items), ANITET_OK);
    off = malloc((size_t)(n_nb + 1) * sizeof *off);
    off1 = malloc((size_t)(n_nb + 1) * sizeof *off1);
    items = malloc((size_t)(n_items + 1) * sizeof *items);
    items1 = malloc((size_t)(n_items + 1) * sizeof *items1);
    assert_int_equal(anitet_part_get_halo(part, list, off, n_nb + 1, items, n_items, 0), ANITET_OK);
    assert_int_equal(anitet_part_get_halo(part, list, off1, n_nb + 1, items1, n_items, 1), ANITET_OK);
    assert_int_equal(off[0], 0);
    assert_int_equal(off[n_nb], n_items);
    for (i = 0; i <= n_nb; ++i) assert_int_equal(off1[i], off[i] + 1);
    for (i = 0; i < n_items; ++i) assert_int_equal(items1[i], items[i] + 1);
    off[0] = -7;
    assert_int_equal(anitet_part_get_halo(part, list, off, n_nb, items, n_items, 0), ANITET_ERR_BUFFER_TOO_SMALL);
    if (n_items > 0)
      assert_int_equal(anitet_part_get_halo(part, list, off, n_nb + 1, items, n_items - 1, 0),
                       ANITET_ERR_BUFFER_TOO_SMALL);
    assert_int_equal(off[0], -7);
    free(off), free(off1), free(items), free(items1);
  }
  assert_true(n_nb >= 1);
  free(xyz), free(tets), free(tets1);
  anitet_partition_destroy(pt);
  anitet_mesh_destroy(m);
}

static void test_part_bytes(void** state) {
  anitet_mesh* m = make_sphere_mesh();
  anitet_partition* pt = partition_ok(m, 2, NULL);
  const anitet_part* part = NULL;
  anitet_part* copy = NULL;
  int64_t needed = 0, again = 0, n;
  unsigned char* bytes;
  unsigned char* bytes2;
  (void)state;
  assert_int_equal(anitet_partition_get_part(pt, 1, &part), ANITET_OK);
  assert_int_equal(anitet_part_serialize(part, NULL, 0, &needed), ANITET_OK);
  assert_true(needed > 100);
  bytes = malloc((size_t)needed);
  bytes2 = malloc((size_t)needed);
  assert_int_equal(anitet_part_serialize(part, bytes, needed - 1, &again), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_part_serialize(part, bytes, needed, &again), ANITET_OK);
  assert_int_equal(again, needed);
  assert_int_equal(anitet_part_deserialize(bytes, needed, &copy), ANITET_OK);
  assert_int_equal(anitet_part_serialize(copy, bytes2, needed, NULL), ANITET_OK);
  assert_int_equal(memcmp(bytes, bytes2, (size_t)needed), 0);
  anitet_part_destroy(copy);
  /* Truncated or damaged bytes: PARSE, no part. */
  for (n = 0; n < needed; n += needed / 37 + 1) {
    copy = (anitet_part*)bytes; /* any non-NULL value: it must be reset */
    assert_int_equal(anitet_part_deserialize(bytes, n, &copy), ANITET_ERR_PARSE);
    assert_null(copy);
  }
  bytes[0] = 'X';
  assert_int_equal(anitet_part_deserialize(bytes, needed, &copy), ANITET_ERR_PARSE);
  assert_true(contains(anitet_last_error_message(), "magic"));
  assert_int_equal(anitet_part_deserialize(NULL, 10, &copy), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_deserialize(bytes, -1, &copy), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_deserialize(bytes, needed, NULL), ANITET_ERR_INVALID_ARGUMENT);
  free(bytes), free(bytes2);
  anitet_partition_destroy(pt);
  anitet_mesh_destroy(m);
}

/* ---- errors --------------------------------------------------------------------------------- */

static void expect_partition_error(const anitet_mesh* m, int32_t parts, const anitet_partition_options* o, int code,
                                   const char* message_part) {
  anitet_partition* pt = (anitet_partition*)m; /* any non-NULL value: it must be reset */
  assert_int_equal(anitet_mesh_partition(m, parts, o, &pt), code);
  assert_null(pt);
  if (!contains(anitet_last_error_message(), message_part))
    fail_msg("message \"%s\" lacks \"%s\"", anitet_last_error_message(), message_part);
}

static void test_partition_errors(void** state) {
  anitet_mesh* m = test_boxes(1, 2, 1, 1, 0); /* 12 tets */
  anitet_partition_options o = ANITET_PARTITION_OPTIONS_INIT;
  anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
  anitet_partition* pt = NULL;
  double w[12];
  int i;
  (void)state;
  expect_partition_error(m, 0, NULL, ANITET_ERR_INVALID_ARGUMENT, "num_parts is 0");
  expect_partition_error(m, -3, NULL, ANITET_ERR_INVALID_ARGUMENT, "num_parts is -3");
  expect_partition_error(m, 13, NULL, ANITET_ERR_INVALID_ARGUMENT, "not in [1, 12]");
  pt = partition_ok(m, 12, NULL); /* one tet each is allowed, if not always balanced */
  assert_int_equal(anitet_partition_get_info(pt, &info), ANITET_OK);
  print_message("12 tets in 12 parts: %d empty, imbalance %g\n", info.empty_parts, info.imbalance);
  check_partition(m, pt, 12, 11.0);
  anitet_partition_destroy(pt);
  expect_partition_error(NULL, 2, NULL, ANITET_ERR_INVALID_ARGUMENT, "mesh is NULL");
  assert_int_equal(anitet_mesh_partition(m, 2, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* Options of an unknown version, before anything else of them is read. */
  o.version = 0;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "version 0");
  o.version = ANITET_PARTITION_OPTIONS_VERSION + 1;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "is not supported");
  o.version = 1000;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "version 1000");
  o.version = ANITET_PARTITION_OPTIONS_VERSION;
  o.ghost_layers = -1;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "ghost_layers");
  o.ghost_layers = 1;
  o.num_threads = -2;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "num_threads");
  o.num_threads = 0;
  o.imbalance = 0;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "imbalance");
  o.imbalance = 0.03;
  for (i = 0; i < 12; ++i) w[i] = 1.0;
  o.tet_weights = w;
  o.num_tet_weights = 11;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "num_tet_weights is 11");
  o.num_tet_weights = 12;
  w[3] = -1;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "weight of tet 3");
  w[3] = NAN;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "weight of tet 3");
  for (i = 0; i < 12; ++i) w[i] = 0.0;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "every tet weight is 0");
  o.tet_weights = NULL;
  expect_partition_error(m, 2, &o, ANITET_ERR_INVALID_ARGUMENT, "tet_weights is NULL");
  anitet_mesh_destroy(m);
}

static void test_partition_accessor_errors(void** state) {
  anitet_mesh* m = test_boxes(1, 2, 2, 1, 0);
  anitet_partition* pt = partition_ok(m, 2, NULL);
  const anitet_part* part = NULL;
  anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
  const void* data = NULL;
  int64_t count = 0, size = 0, off[4];
  int32_t parts[24], items[1];
  (void)state;
  assert_int_equal(anitet_partition_get_part(pt, 2, &part), ANITET_ERR_INVALID_ARGUMENT);
  assert_null(part);
  assert_int_equal(anitet_partition_get_part(pt, -1, &part), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_part(NULL, 0, &part), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_part(pt, 0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_tet_parts(pt, parts, 23), ANITET_ERR_BUFFER_TOO_SMALL);
  assert_int_equal(anitet_partition_get_tet_parts(pt, NULL, 24), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_tet_parts(NULL, parts, 24), ANITET_ERR_INVALID_ARGUMENT);
  info.version = 0;
  assert_int_equal(anitet_partition_get_info(pt, &info), ANITET_ERR_INVALID_ARGUMENT);
  info.version = ANITET_PARTITION_INFO_VERSION + 1;
  assert_int_equal(anitet_partition_get_info(pt, &info), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_info(pt, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_info(NULL, &info), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_partition_get_part(pt, 0, &part), ANITET_OK);
  assert_int_equal(anitet_part_get_array(part, 20, &data, &count, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_array(part, -1, &data, &count, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_array(part, ANITET_PART_TETS, NULL, &count, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_array(part, ANITET_PART_TETS, &data, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_array(NULL, ANITET_PART_TETS, &data, &count, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_halo_size(part, 4, &size), ANITET_ERR_INVALID_ARGUMENT);
  assert_true(contains(anitet_last_error_message(), "ANITET_HALO_"));
  assert_int_equal(anitet_part_get_halo_size(part, 0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_halo(part, -1, off, 4, items, 1, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_halo(part, 0, NULL, 4, items, 1, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_halo(part, 0, off, 4, items, 1, 5), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_counts(NULL, NULL, NULL, NULL, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_index(NULL, NULL, NULL, NULL, NULL), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_points(NULL, NULL, 0), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_get_vertex_global_ids(part, NULL, 0, 3), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(anitet_part_serialize(NULL, NULL, 0, NULL), ANITET_ERR_INVALID_ARGUMENT);
  /* A lent part is the partition's: destroying it is ignored, the part stays usable. */
  anitet_part_destroy((anitet_part*)part);
  assert_int_equal(anitet_part_get_counts(part, &count, NULL, NULL, NULL, NULL, NULL), ANITET_OK);
  assert_true(count > 0);
  anitet_part_destroy(NULL);
  anitet_partition_destroy(NULL);
  anitet_partition_destroy(pt);
  anitet_mesh_destroy(m);
}

static void test_set_last_error(void** state) {
  (void)state;
  assert_int_equal(anitet_set_last_error(ANITET_ERR_INTERNAL, "layered: it broke"), ANITET_ERR_INTERNAL);
  assert_string_equal(anitet_last_error_message(), "layered: it broke");
  assert_int_equal(anitet_set_last_error(ANITET_OK, NULL), ANITET_OK);
  assert_string_equal(anitet_last_error_message(), "");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_partition_options_init),
      cmocka_unit_test(test_partition_grid),
      cmocka_unit_test(test_partition_sphere_mesh),
      cmocka_unit_test(test_partition_disconnected_boxes),
      cmocka_unit_test(test_partition_weights_and_threads),
      cmocka_unit_test(test_part_fill_accessors),
      cmocka_unit_test(test_part_bytes),
      cmocka_unit_test(test_partition_errors),
      cmocka_unit_test(test_partition_accessor_errors),
      cmocka_unit_test(test_set_last_error),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
