// Boundary-layer metric on the unit cube whose bottom face (patch 1) is the wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "metric/boundary_layer.hpp"
#include "metric/combine.hpp"
#include "metric/spd.hpp"

namespace anitet {
namespace metric {
namespace {

// The unit cube, outward triangles; the bottom face (z = 0) is patch 1, the others patch 2.
SurfaceMesh unit_cube() {
  SurfaceMesh s;
  for (int k = 0; k < 8; ++k) s.add_vertex(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  s.add_triangle(0, 2, 3, 1);
  s.add_triangle(0, 3, 1, 1);
  s.add_triangle(4, 5, 7, 2);
  s.add_triangle(4, 7, 6, 2);
  s.add_triangle(0, 1, 5, 2);
  s.add_triangle(0, 5, 4, 2);
  s.add_triangle(2, 6, 7, 2);
  s.add_triangle(2, 7, 3, 2);
  s.add_triangle(0, 4, 6, 2);
  s.add_triangle(0, 6, 2, 2);
  s.add_triangle(1, 3, 7, 2);
  s.add_triangle(1, 7, 5, 2);
  return s;
}

AnalyticField isotropic(double h) {
  return AnalyticField([h](const double*, double m[6]) { isotropic_metric(h, m); });
}

TEST(ClosestPoint, RegionsOfATriangle) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  const double inside[3] = {0.2, 0.3, 5.0}, vertex[3] = {-1, -1, 1}, edge[3] = {0.5, -2, 0};
  double q[3], w[3];
  closest_point_on_triangle(inside, a, b, c, q, w);
  EXPECT_NEAR(q[0], 0.2, 1e-15);
  EXPECT_NEAR(q[1], 0.3, 1e-15);
  EXPECT_EQ(q[2], 0.0);
  EXPECT_NEAR(w[0], 0.5, 1e-15);
  closest_point_on_triangle(vertex, a, b, c, q, w);
  EXPECT_EQ(w[0], 1.0);
  closest_point_on_triangle(edge, a, b, c, q, w);
  EXPECT_NEAR(q[0], 0.5, 1e-15);
  EXPECT_EQ(q[1], 0.0);
}

TEST(BoundaryLayer, NormalSizeGrowsLinearlyAndTangentialFollowsTheWall) {
  const SurfaceMesh cube = unit_cube();
  const AnalyticField bg = isotropic(10.0);  // coarse: the layer metric shows through
  BoundaryLayerOptions o;
  o.first_height = 1e-3;
  o.growth = 1.2;
  o.wall_patches = {1};
  o.far_size = 5.0;
  BoundaryLayerStats stats;
  Result<BoundaryLayerField> f = BoundaryLayerField::create(cube, bg, o, &stats);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(stats.wall_triangles, 2u);
  EXPECT_NEAR(stats.band_distance, (5.0 - 1e-3) / 0.2, 1e-12);
  for (double z : {0.0, 1e-3, 0.01, 0.1, 0.3, 0.7}) {
    const double p[3] = {0.4, 0.35, z};
    double m[6];
    f->metric(p, m);
    const double hn = 1e-3 + 0.2 * z;
    EXPECT_NEAR(m[5], 1.0 / (hn * hn), 1e-9 / (hn * hn)) << z;
    EXPECT_NEAR(m[3], 0.0, 1e-9 * m[5]);
    EXPECT_NEAR(m[4], 0.0, 1e-9 * m[5]);
    // Tangential: the wall's vertex sizes interpolated: 1 off the diagonal, (1 + sqrt 2)/2 on
    // it (its edges counted once per triangle).
    const double ht = 1.0 / std::sqrt(m[0]);
    EXPECT_GE(ht, 1.0 - 1e-9) << z;
    EXPECT_LE(ht, (1.0 + std::sqrt(2.0)) / 2.0 + 1e-9) << z;
    EXPECT_GT(ht, 1.0 + 1e-3) << z;  // (0.4, 0.35) is not on an edge's vertex
    EXPECT_NEAR(m[0], m[2], 1e-9 * m[0]);
    double d, q[3];
    ASSERT_TRUE(f->wall_distance(p, d, q));
    EXPECT_NEAR(d, z, 1e-12);
  }
  // Below the wall (outside the cube) the distance is unsigned: the same layer metric.
  const double below[3] = {0.5, 0.5, -0.05};
  double m[6];
  f->metric(below, m);
  EXPECT_NEAR(m[5], 1.0 / std::pow(1e-3 + 0.2 * 0.05, 2), 1e-6 * m[5]);
}

TEST(BoundaryLayer, BeyondTheLayersTheNormalSizeGrowsAtTheInteriorGrowth) {
  const SurfaceMesh cube = unit_cube();
  const AnalyticField bg = isotropic(10.0);
  BoundaryLayerOptions o;
  o.first_height = 1e-3;
  o.growth = 1.2;
  o.wall_patches = {1};
  o.far_size = 5.0;
  o.layers_thickness = 0.05;
  o.interior_growth = 1.5;
  BoundaryLayerStats stats;
  Result<BoundaryLayerField> f = BoundaryLayerField::create(cube, bg, o, &stats);
  ASSERT_TRUE(f.ok()) << f.status().message();
  const double top = 1e-3 + 0.2 * 0.05;  // the normal size on the layers' top
  EXPECT_NEAR(stats.band_distance, 0.05 + (5.0 - top) / 0.5, 1e-12);
  for (double z : {0.0, 0.01, 0.05, 0.06, 0.2, 0.7}) {
    const double p[3] = {0.4, 0.35, z};
    double m[6];
    f->metric(p, m);
    const double hn = z <= 0.05 ? 1e-3 + 0.2 * z : top + 0.5 * (z - 0.05);
    EXPECT_NEAR(m[5], 1.0 / (hn * hn), 1e-9 / (hn * hn)) << z;
  }
  // An interior growth below the layers' growth is refused.
  o.interior_growth = 1.1;
  EXPECT_EQ(BoundaryLayerField::create(cube, bg, o).status().code(), Error::InvalidArgument);
}

TEST(BoundaryLayer, MeetsTheBackgroundWithoutAJump) {
  const SurfaceMesh cube = unit_cube();
  const AnalyticField bg = isotropic(0.1);
  BoundaryLayerOptions o;
  o.first_height = 1e-3;
  o.growth = 1.25;
  o.wall_patches = {1};  // far_size by default: twice the background's size, 0.2
  Result<BoundaryLayerField> f = BoundaryLayerField::create(cube, bg, o);
  ASSERT_TRUE(f.ok()) << f.status().message();
  double bgm[6];
  const double origin[3] = {0, 0, 0};
  bg.metric(origin, bgm);
  // Along the vertical through the cube: the normal size grows at most at rate r - 1, is never
  // coarser than the background, and becomes the background once h0 + (r-1) d >= 0.1.
  double last = 0.0;
  const int steps = 400;
  for (int s = 0; s <= steps; ++s) {
    const double z = 1.2 * s / steps - 0.1;
    const double p[3] = {0.3, 0.6, z};
    double m[6];
    f->metric(p, m);
    ASSERT_TRUE(is_spd(m));
    const double hz = 1.0 / std::sqrt(m[5]);
    EXPECT_LE(hz, 0.1 * (1 + 1e-9));
    EXPECT_NEAR(1.0 / std::sqrt(m[0]), 0.1, 1e-9);  // tangential: the background's
    const double d = std::fabs(z);
    const double want = std::min(0.1, 1e-3 + 0.25 * d);
    EXPECT_NEAR(hz, want, 1e-9 * want) << z;
    if (s > 0 && z > 0.0) {
      EXPECT_LE(std::fabs(hz - last), 0.25 * 1.2 / steps + 1e-12) << z;
    }
    last = hz;
  }
}

TEST(BoundaryLayer, OnlyTheWallPatchesCount) {
  const SurfaceMesh cube = unit_cube();
  const AnalyticField bg = isotropic(0.1);
  BoundaryLayerOptions o;
  o.first_height = 1e-3;
  o.wall_patches = {1};
  Result<BoundaryLayerField> f = BoundaryLayerField::create(cube, bg, o);
  ASSERT_TRUE(f.ok());
  const double near_top[3] = {0.5, 0.5, 0.99};  // 0.01 from a non-wall face
  double m[6], want[6];
  f->metric(near_top, m);
  bg.metric(near_top, want);
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(m[c], want[c], 1e-9 * want[0]);
  // With every patch a wall, the top face makes the layer there too.
  o.wall_patches.clear();
  Result<BoundaryLayerField> all = BoundaryLayerField::create(cube, bg, o);
  ASSERT_TRUE(all.ok());
  all->metric(near_top, m);
  EXPECT_NEAR(m[5], 1.0 / std::pow(1e-3 + 0.2 * 0.01, 2), 1e-6 * m[5]);
}

TEST(BoundaryLayer, BadOptions) {
  const SurfaceMesh cube = unit_cube();
  const AnalyticField bg = isotropic(0.1);
  BoundaryLayerOptions o;
  EXPECT_EQ(BoundaryLayerField::create(cube, bg, o).status().code(), Error::InvalidArgument);
  o.first_height = 1e-3;
  o.growth = 1.0;
  EXPECT_EQ(BoundaryLayerField::create(cube, bg, o).status().code(), Error::InvalidArgument);
  o.growth = 1.2;
  o.wall_patches = {7};
  EXPECT_EQ(BoundaryLayerField::create(cube, bg, o).status().code(), Error::EmptyInput);
}

}  // namespace
}  // namespace metric
}  // namespace anitet
