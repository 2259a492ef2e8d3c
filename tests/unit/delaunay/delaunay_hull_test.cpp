#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "test_points.hpp"

namespace anitet {
namespace {

std::set<std::array<uint32_t, 3>> canonical_set(const std::vector<std::array<uint32_t, 3>>& faces) {
  std::set<std::array<uint32_t, 3>> s;
  for (const auto& f : faces) s.insert(test::canonical(f));
  return s;
}

// Every tet's circumsphere is empty of all points (brute force, exact).
void expect_empty_spheres(const TetMesh& mesh) {
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    for (uint32_t q = 0; q < mesh.num_vertices(); ++q)
      ASSERT_LE(predicates::insphere(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                                     mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3)),
                                     mesh.point(q)),
                0)
          << "point " << q << " inside the sphere of tet " << t;
  }
}

TEST(DelaunayHull, GhostFacetsAreTheConvexHull) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const size_t n = 8 + 3 * seed;
    const std::vector<double> xyz = test::random_cube(n, seed);
    TetMesh mesh;
    auto r = delaunay_tetrahedralize(mesh, xyz.data(), n);
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_EQ(canonical_set(test::ghost_hull(mesh)), canonical_set(test::brute_force_hull(xyz)))
        << "seed " << seed;
    const double hull = test::hull_volume6(xyz, test::brute_force_hull(xyz));
    EXPECT_NEAR(test::mesh_volume6(mesh), hull, 1e-12 * hull) << "seed " << seed;
    expect_empty_spheres(mesh);
  }
}

TEST(DelaunayHull, AllPointsOnTheHull) {
  const std::vector<double> xyz = test::random_sphere(60, 9);
  TetMesh mesh;
  auto r = delaunay_tetrahedralize(mesh, xyz.data(), 60);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(canonical_set(test::ghost_hull(mesh)), canonical_set(test::brute_force_hull(xyz)));
  EXPECT_EQ(r->num_ghost_tets, 2 * 60u - 4);  // a triangulated sphere with 60 vertices
  expect_empty_spheres(mesh);
}

// Coplanar hull faces: the hull triangles are not unique, but each must support the point set,
// and together they must enclose exactly the cube.
TEST(DelaunayHull, GridHullSupportsAllPoints) {
  const std::vector<double> xyz = test::grid(5);
  TetMesh mesh;
  auto r = delaunay_tetrahedralize(mesh, xyz.data(), xyz.size() / 3);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const auto hull = test::ghost_hull(mesh);
  EXPECT_EQ(hull.size(), 6u * 4 * 4 * 2);  // two triangles per boundary square
  for (const auto& f : hull)
    for (uint32_t q = 0; q < mesh.num_vertices(); ++q)
      ASSERT_LE(predicates::orient3d(mesh.point(f[0]), mesh.point(f[1]), mesh.point(f[2]), mesh.point(q)), 0);
  EXPECT_EQ(test::hull_volume6(xyz, hull), 6.0 * 64);
  EXPECT_EQ(test::mesh_volume6(mesh), 6.0 * 64);
  expect_empty_spheres(mesh);
}

}  // namespace
}  // namespace anitet
