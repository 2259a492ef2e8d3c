#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "test_points.hpp"

namespace anitet {
namespace {

using Triangle = std::array<uint32_t, 3>;

std::set<Triangle> protected_facets(const TetMesh& m) {
  std::set<Triangle> out;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      if (!m.facet_protected(t, i)) continue;
      Triangle f = {m.vertex(t, kFacetVertex[i][0]), m.vertex(t, kFacetVertex[i][1]), m.vertex(t, kFacetVertex[i][2])};
      std::sort(f.begin(), f.end());
      out.insert(f);
    }
  }
  return out;
}

// The Delaunay mesh of n random points in [0.25, 0.75]^3 without its ghosts (as refinement's
// meshes are), about one interior facet in `one_in` protected (0: none).
TetMesh base_mesh(size_t n, uint64_t seed, unsigned one_in) {
  std::vector<double> xyz = test::random_cube(n, seed);
  for (double& c : xyz) c = 0.25 + 0.5 * c;
  TetMesh full;
  EXPECT_TRUE(delaunay_tetrahedralize(full, xyz.data(), n).ok());
  TetMesh mesh = TetMesh::from_volume_mesh(full.to_volume_mesh(false));
  EXPECT_TRUE(mesh.build_adjacency().ok());
  std::mt19937_64 rng(seed);
  for (uint32_t t = 0; one_in > 0 && t < mesh.num_tet_slots(); ++t)
    for (int i = 0; i < 4; ++i) {
      const uint32_t nb = mesh.neighbour(t, i);
      if (nb == TetMesh::kNone || rng() % one_in != 0) continue;
      mesh.set_facet_protected(t, i, true);
      mesh.set_facet_protected(nb, mesh.neighbour_facet(t, i), true);
    }
  return mesh;
}

struct Batch {
  std::vector<double> points;
  std::vector<uint32_t> hints;
};

// n random points in [0.2, 0.8]^3 (some beyond the mesh), each with a random live tet as its hint
// or none.
Batch random_batch(const TetMesh& mesh, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  Batch b;
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) b.points.push_back(u(rng));
    const auto t = static_cast<uint32_t>(rng() % (mesh.num_tet_slots() + 1));
    b.hints.push_back(t < mesh.num_tet_slots() && !mesh.is_deleted(t) ? t : TetMesh::kNone);
  }
  return b;
}

BatchInsertion run(TetMesh& mesh, const Batch& b, int partitions, int threads, size_t parallel_min = 256) {
  tbb::global_control arena(tbb::global_control::max_allowed_parallelism, size_t(threads));
  BatchInserter inserter(mesh, partitions, parallel_min);
  BatchInsertion out;
  inserter.insert(b.points.data(), b.hints.data(), b.hints.size(), InsertOptions{}, out);
  return out;
}

size_t count(const BatchInsertion& out, InsertStatus s) {
  return size_t(std::count(out.status.begin(), out.status.end(), s));
}

// Slabs on two threads: a valid mesh that keeps every protected facet, the new vertices numbered
// in batch order with no gap, every one of them in a tet; the special points get their own
// statuses; and the same mesh, bit for bit, on one thread.
TEST(BatchInserter, SlabsKeepProtectedFacetsAndDoNotDependOnTheThreads) {
  const TetMesh base = base_mesh(3000, 41, 10);
  const std::set<Triangle> wall = protected_facets(base);
  ASSERT_GT(wall.size(), 500u);
  Batch b = random_batch(base, 20000, 42);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const size_t i_nan = 7, i_dup_vertex = 11, i_dup_batch = 13;
  b.points[3 * i_nan] = nan;
  std::copy_n(base.point(5), 3, &b.points[3 * i_dup_vertex]);
  std::copy_n(&b.points[3 * 12], 3, &b.points[3 * i_dup_batch]);  // point 12 again
  const size_t n0 = base.num_vertices();

  TetMesh two = base, one = base;
  const BatchInsertion out = run(two, b, 2, 2);
  const BatchInsertion out1 = run(one, b, 2, 1);
  EXPECT_EQ(two.tet_v, one.tet_v);
  EXPECT_EQ(two.xyz, one.xyz);
  EXPECT_EQ(out.status, out1.status);

  const Status st = check_mesh(two);
  ASSERT_TRUE(st.ok()) << st.message();
  const std::set<Triangle> now = protected_facets(two);
  EXPECT_TRUE(std::includes(now.begin(), now.end(), wall.begin(), wall.end())) << "a protected facet was destroyed";
  EXPECT_EQ(out.status[i_nan], InsertStatus::kInvalidPoint);
  EXPECT_EQ(out.status[i_dup_vertex], InsertStatus::kDuplicate);
  if (out.status[12] == InsertStatus::kInserted) {
    EXPECT_EQ(out.status[i_dup_batch], InsertStatus::kDuplicate);
  }
  EXPECT_GT(count(out, InsertStatus::kOutsideMesh), 100u);  // [0.2, 0.8] reaches past the hull
  const size_t inserted = count(out, InsertStatus::kInserted);
  EXPECT_GT(inserted, 20000u * 4 / 10);
  EXPECT_GT(out.parallel, inserted * 7 / 10);
  EXPECT_GT(out.deferred, 0u);

  ASSERT_EQ(two.num_vertices(), n0 + inserted);
  uint32_t expect = static_cast<uint32_t>(n0);
  for (size_t i = 0; i < out.vertex.size(); ++i) {
    if (out.status[i] != InsertStatus::kInserted) {
      EXPECT_EQ(out.vertex[i], TetMesh::kNone);
      continue;
    }
    ASSERT_EQ(out.vertex[i], expect++);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(two.point(out.vertex[i])[k], b.points[3 * i + size_t(k)]);
    EXPECT_GT(out.created_end(i) - out.created_begin(i), 0);
  }
  // Every live tet holding a new vertex was made by the batch: it is in some point's created
  // list (the lists of both slab phases and of the one-by-one inserts).
  std::set<uint32_t> listed;
  for (size_t i = 0; i < out.vertex.size(); ++i)
    if (out.status[i] == InsertStatus::kInserted)
      for (const uint32_t* t = out.created_begin(i); t != out.created_end(i); ++t) {
        ASSERT_LT(*t, two.num_tet_slots());
        listed.insert(*t);
      }
  for (uint32_t t = 0; t < two.num_tet_slots(); ++t) {
    if (two.is_deleted(t)) continue;
    bool holds_new = false;
    for (int k = 0; k < 4; ++k) holds_new |= two.vertex(t, k) >= n0;
    if (holds_new) {
      ASSERT_TRUE(listed.count(t)) << "tet " << t << " holds a new vertex and is in no created list";
    }
  }
  std::vector<uint8_t> used(two.num_vertices(), 0);
  for (uint32_t t = 0; t < two.num_tet_slots(); ++t)
    if (!two.is_deleted(t))
      for (int k = 0; k < 4; ++k) used[two.vertex(t, k)] = 1;
  EXPECT_EQ(size_t(std::count(used.begin(), used.end(), 0)), 0u) << "a vertex in no tet";
}

// Without protected facets the kernel is Delaunay's: the slabs and the points they leave give a
// Delaunay mesh too.
TEST(BatchInserter, WithoutConstraintsTheSlabsGiveADelaunayMesh) {
  const TetMesh base = base_mesh(2000, 51, 0);
  const Batch b = random_batch(base, 10000, 52);
  TetMesh mesh = base;
  const BatchInsertion out = run(mesh, b, 2, 2);
  EXPECT_GT(out.parallel, 0u);
  EXPECT_GT(out.deferred, 0u);
  MeshCheckOptions o;
  o.check_delaunay = true;
  const Status st = check_mesh(mesh, o);
  EXPECT_TRUE(st.ok()) << st.message();
}

// One partition is PointInserter point after point: the same mesh when every point goes in.
TEST(BatchInserter, OnePartitionIsPointInserterOneByOne) {
  const TetMesh base = base_mesh(2000, 61, 8);
  std::mt19937_64 rng(62);
  std::uniform_real_distribution<double> u(0.3, 0.7);  // inside the hull
  Batch b;
  for (int i = 0; i < 3000; ++i) {
    for (int k = 0; k < 3; ++k) b.points.push_back(u(rng));
    b.hints.push_back(TetMesh::kNone);
  }
  TetMesh batched = base, single = base;
  const BatchInsertion out = run(batched, b, 1, 2);
  PointInserter inserter(single);
  for (size_t i = 0; i < b.hints.size(); ++i) {
    const InsertResult r = inserter.insert(&b.points[3 * i]);
    ASSERT_EQ(r.status, out.status[i]) << "point " << i;
  }
  ASSERT_EQ(count(out, InsertStatus::kInserted), b.hints.size()) << "the comparison needs every point in";
  EXPECT_EQ(out.parallel, 0u);
  EXPECT_EQ(batched.tet_v, single.tet_v);
  EXPECT_EQ(batched.tet_adj, single.tet_adj);
  EXPECT_EQ(batched.xyz, single.xyz);
}

}  // namespace
}  // namespace anitet
