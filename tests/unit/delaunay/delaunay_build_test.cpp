#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/task_arena.h>

#include "delaunay/delaunay.hpp"
#include "test_points.hpp"

namespace anitet {
namespace {

using test::kScale;

// The mesh is a valid Delaunay tetrahedralization of xyz: structure, exact orientation, local
// Delaunay facets, convex hull; every input point is a vertex or a reported duplicate of one.
void expect_delaunay_of(const TetMesh& mesh, const std::vector<double>& xyz, const DelaunayStats& stats) {
  MeshCheckOptions check;
  check.check_delaunay = true;
  const Status st = check_mesh(mesh, check);
  ASSERT_TRUE(st.ok()) << st.message();

  const size_t n = xyz.size() / 3;
  ASSERT_EQ(mesh.num_vertices(), n);
  std::vector<char> used(n, 0);
  size_t real = 0, ghost = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    (mesh.is_ghost(t) ? ghost : real) += 1;
    for (int k = 0; k < 4; ++k)
      if (mesh.vertex(t, k) != TetMesh::kGhost) used[mesh.vertex(t, k)] = 1;
  }
  EXPECT_EQ(stats.num_tets, real);
  EXPECT_EQ(stats.num_ghost_tets, ghost);
  std::vector<char> duplicate(n, 0);
  for (const DuplicatePoint& d : stats.duplicates) {
    ASSERT_LT(d.point, n);
    ASSERT_LT(d.same_as, n);
    EXPECT_EQ(xyz[3 * d.point], xyz[3 * d.same_as]);
    EXPECT_EQ(xyz[3 * d.point + 1], xyz[3 * d.same_as + 1]);
    EXPECT_EQ(xyz[3 * d.point + 2], xyz[3 * d.same_as + 2]);
    EXPECT_TRUE(used[d.same_as]) << "duplicate " << d.point << " refers to unused point " << d.same_as;
    duplicate[d.point] = 1;
  }
  for (size_t i = 0; i < n; ++i)
    ASSERT_NE(bool(used[i]), bool(duplicate[i])) << "point " << i << (used[i] ? " is used and a duplicate" : " is missing");
  EXPECT_EQ(stats.num_inserted + stats.duplicates.size(), n);
}

Result<DelaunayStats> build(TetMesh& mesh, const std::vector<double>& xyz, const DelaunayOptions& options = {}) {
  return delaunay_tetrahedralize(mesh, xyz.data(), xyz.size() / 3, options);
}

TEST(Delaunay, RandomPointsInACube) {
  const std::vector<double> xyz = test::random_cube(100000 / kScale, 1);
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, xyz, r.value());
  EXPECT_TRUE(r->duplicates.empty());
  // About 6.7 tets per point for uniform random points.
  EXPECT_GT(r->num_tets, 6 * xyz.size() / 3);
  EXPECT_LT(r->num_tets, 7 * xyz.size() / 3);
  EXPECT_EQ(r->walk_fallbacks, 0u);
}

TEST(Delaunay, SameInputSameMeshBitForBit) {
  const std::vector<double> xyz = test::random_cube(20000 / kScale, 2);
  TetMesh a, b;
  ASSERT_TRUE(build(a, xyz).ok());
  ASSERT_TRUE(build(b, xyz).ok());
  EXPECT_EQ(a.tet_v, b.tet_v);
  EXPECT_EQ(a.tet_adj, b.tet_adj);
  EXPECT_EQ(a.free_tets, b.free_tets);
  DelaunayOptions other;
  other.seed = 12345;
  TetMesh c;
  auto r = build(c, xyz, other);
  ASSERT_TRUE(r.ok());
  expect_delaunay_of(c, xyz, r.value());
    // Points in general position have one Delaunay tetrahedralization, whatever the order.
  EXPECT_EQ(r->num_tets + r->num_ghost_tets, a.num_live_tets());
}

TEST(Delaunay, PointsOnASphere) {
  const std::vector<double> xyz = test::random_sphere(20000 / kScale, 3);
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, xyz, r.value());
}

// All 8 corners of each cell cospherical, faces coplanar: every tie goes to SoS.
TEST(Delaunay, IntegerGrid) {
  const int k = kScale == 1 ? 20 : 8;
  const std::vector<double> xyz = test::grid(k);
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, xyz, r.value());
  EXPECT_GT(r->sos_ties, 0u);
  // The tets tile the cube [0, k-1]^3 exactly (integer volumes: exact in doubles).
  EXPECT_EQ(test::mesh_volume6(mesh), 6.0 * (k - 1) * (k - 1) * (k - 1));
}

TEST(Delaunay, PointsOnAFewPlanesWithDuplicates) {
  const std::vector<double> xyz = test::points_on_planes(20000 / kScale, 4, 4);
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, xyz, r.value());
  EXPECT_FALSE(r->duplicates.empty());
}

TEST(Delaunay, DuplicatesAreReportedNotInserted) {
  std::vector<double> xyz = test::random_cube(1000, 5);
  for (size_t i = 0; i < 100; ++i)  // copies of points 0, 10, ..., 990, two copies of some
    for (int c = 0; c < 3; ++c) xyz.push_back(xyz[3 * (10 * i) + c]);
  for (size_t i = 0; i < 10; ++i)
    for (int c = 0; c < 3; ++c) xyz.push_back(xyz[3 * (10 * i) + c]);
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->duplicates.size(), 110u);
  EXPECT_EQ(r->num_inserted, 1000u);
  expect_delaunay_of(mesh, xyz, r.value());
}

// The live tets as sorted vertex sets: the same for any insertion order when the Delaunay
// tetrahedralization is unique (general position, or ties broken by SoS on the point ids).
// Coincident points are named by the first of them (which copy a build inserts depends on its
// order).
std::vector<std::array<uint32_t, 4>> tet_set(const TetMesh& mesh) {
  const size_t n = mesh.num_vertices();
  std::vector<uint32_t> by_point(n), first(n);
  for (uint32_t i = 0; i < n; ++i) by_point[i] = i;
  auto less = [&](uint32_t a, uint32_t b) {
    return std::lexicographical_compare(mesh.point(a), mesh.point(a) + 3, mesh.point(b), mesh.point(b) + 3);
  };
  std::stable_sort(by_point.begin(), by_point.end(), less);
  for (size_t i = 0; i < n; ++i)
    first[by_point[i]] = (i > 0 && !less(by_point[i - 1], by_point[i])) ? first[by_point[i - 1]] : by_point[i];
  auto name = [&](uint32_t v) { return v == TetMesh::kGhost ? v : first[v]; };
  std::vector<std::array<uint32_t, 4>> tets;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    std::array<uint32_t, 4> v{name(mesh.vertex(t, 0)), name(mesh.vertex(t, 1)), name(mesh.vertex(t, 2)),
                              name(mesh.vertex(t, 3))};
    std::sort(v.begin(), v.end());
    tets.push_back(v);
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

Result<DelaunayStats> build_on(int threads, TetMesh& mesh, const std::vector<double>& xyz, const DelaunayOptions& o) {
  tbb::task_arena arena(threads);
  return arena.execute([&] { return build(mesh, xyz, o); });
}

// The parallel build (slabs filled by tasks, then the points they left): a Delaunay
// tetrahedralization, the one the one-point-at-a-time build makes, the same arrays bit for bit on
// 1 and 2 threads, compact (no free slot), and most points inserted by the tasks (parallel_share
// of them; the small sets of the sanitizer builds have more points near the slab borders).
constexpr double kParallelShare = kScale == 1 ? 0.75 : 0.3;
void expect_parallel_build(const std::vector<double>& xyz, int partitions, size_t min_round,
                           double parallel_share = kParallelShare) {
  DelaunayOptions o;
  o.partitions = partitions;
  o.parallel_min_round = min_round;
  TetMesh one, two, serial;
  auto r1 = build_on(1, one, xyz, o);
  auto r2 = build_on(2, two, xyz, o);
  ASSERT_TRUE(r1.ok()) << r1.status().message();
  ASSERT_TRUE(r2.ok()) << r2.status().message();
  expect_delaunay_of(two, xyz, r2.value());
  EXPECT_EQ(one.tet_v, two.tet_v);
  EXPECT_EQ(one.tet_adj, two.tet_adj);
  EXPECT_TRUE(two.free_tets.empty());
  EXPECT_EQ(two.num_tet_slots(), two.num_live_tets());
  EXPECT_EQ(r1->duplicates.size(), r2->duplicates.size());
  EXPECT_GT(double(r2->parallel_points), parallel_share * double(r2->num_inserted));
  DelaunayOptions sequential;
  sequential.partitions = 1;
  auto rs = build(serial, xyz, sequential);
  ASSERT_TRUE(rs.ok());
  EXPECT_EQ(rs->parallel_points, 0u);
  EXPECT_EQ(rs->duplicates.size(), r2->duplicates.size());
  // With duplicates on ties, the copy inserted (its id) steers the SoS: another valid answer.
  if (rs->duplicates.empty() || rs->sos_ties == 0) {
    EXPECT_EQ(tet_set(serial), tet_set(two));
  }
}

TEST(DelaunayParallel, RandomCube) { expect_parallel_build(test::random_cube(200000 / kScale, 7), 2, 32768 / kScale); }
TEST(DelaunayParallel, FourPartitions) { expect_parallel_build(test::random_cube(100000 / kScale, 8), 4, 4096 / kScale); }
TEST(DelaunayParallel, PointsOnASphere) { expect_parallel_build(test::random_sphere(50000 / kScale, 9), 2, 4096 / kScale); }
// Cospherical and coplanar ties everywhere: the SoS makes the tetrahedralization unique.
TEST(DelaunayParallel, IntegerGrid) { expect_parallel_build(test::grid(kScale == 1 ? 30 : 14), 3, 2048 / kScale); }
TEST(DelaunayParallel, PointsOnPlanesWithDuplicates) {
  // 6,724 distinct lattice points on 4 planes, the rest copies: tets between the planes are long.
  expect_parallel_build(test::points_on_planes(50000 / kScale, 4, 10), 2, 1024 / kScale, kParallelShare * 2 / 3);
}

TEST(DelaunayParallel, PartitionsOutOfRangeAreRefused) {
  const std::vector<double> xyz = test::random_cube(100, 11);
  for (int partitions : {0, 65}) {
    DelaunayOptions o;
    o.partitions = partitions;
    TetMesh mesh;
    EXPECT_EQ(build(mesh, xyz, o).status().code(), Error::InvalidArgument);
  }
}

TEST(Delaunay, MinimalInputs) {
  TetMesh mesh;
  const std::vector<double> four = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  auto r = build(mesh, four);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->num_tets, 1u);
  EXPECT_EQ(r->num_ghost_tets, 4u);
  expect_delaunay_of(mesh, four, r.value());

  // Duplicates and collinear / coplanar points before the first volume.
  const std::vector<double> late = {0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1};
  r = build(mesh, late);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, late, r.value());
  EXPECT_EQ(r->duplicates.size(), 1u);
}

TEST(Delaunay, DegenerateInputsFail) {
  TetMesh mesh;
  EXPECT_EQ(delaunay_tetrahedralize(mesh, nullptr, 0).status().code(), Error::EmptyInput);
  const std::vector<double> three = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_EQ(build(mesh, three).status().code(), Error::InvalidArgument);
  std::vector<double> flat = test::random_cube(100, 6);
  for (size_t i = 2; i < flat.size(); i += 3) flat[i] = 0.5;
  EXPECT_EQ(build(mesh, flat).status().code(), Error::InvalidArgument);
  std::vector<double> line;
  for (int i = 0; i < 10; ++i) line.insert(line.end(), {double(i), 2.0 * i, -1.0 * i});
  EXPECT_EQ(build(mesh, line).status().code(), Error::InvalidArgument);
  const std::vector<double> same(30, 1.0);
  EXPECT_EQ(build(mesh, same).status().code(), Error::InvalidArgument);
  std::vector<double> nan = test::random_cube(10, 7);
  nan[13] = std::numeric_limits<double>::quiet_NaN();
  const auto r = build(mesh, nan);
  EXPECT_EQ(r.status().code(), Error::NonFiniteCoordinate);
  EXPECT_NE(r.status().message().find("point 4"), std::string::npos) << r.status().message();
}

// Coordinates far from the origin and tiny spacing: the filters fail often and the exact
// arithmetic decides.
TEST(Delaunay, ClusteredFarFromOrigin) {
  std::vector<double> xyz = test::random_cube(5000 / kScale, 8);
  for (size_t i = 0; i < xyz.size(); ++i) xyz[i] = 1e6 + xyz[i] * 1e-6;
  TetMesh mesh;
  auto r = build(mesh, xyz);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_delaunay_of(mesh, xyz, r.value());
}

}  // namespace
}  // namespace anitet
