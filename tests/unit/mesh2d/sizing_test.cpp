// The 2D sizing fields: the lattice field's interpolation, ESRI ASCII grids, a .sol on a 2D
// background mesh, and the field each option makes (the boundary's sizes, gradation, distance,
// bathymetry); and what refinement and optimization make of them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "mesh2d/domain.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/metric2.hpp"
#include "mesh2d/quality2.hpp"
#include "mesh2d/sizing2.hpp"

namespace anitet::mesh2d {
namespace {

double size_at(const SizingField& f, double x, double y) { return 1.0 / std::sqrt(metric_at(f, x, y).xx); }

// The square [0, 4]^2, 16 segments of length 1 (points counter-clockwise from the origin).
Pslg square16() {
  Pslg p;
  for (int s = 0; s < 4; ++s)
    for (int i = 0; i < 4; ++i) {
      const double t = i;
      const double xy[4][2] = {{t, 0}, {4, t}, {4 - t, 4}, {0, 4 - t}};
      p.xy.insert(p.xy.end(), {xy[s][0], xy[s][1]});
    }
  for (uint32_t i = 0; i < 16; ++i) p.seg.insert(p.seg.end(), {i, (i + 1) % 16});
  p.label.assign(16, 1);
  return p;
}

TEST(Mesh2dSizing, LatticeFieldIsBilinearInSizes) {
  metric::Lattice l;
  l.origin[0] = -1, l.origin[1] = 2, l.spacing = 0.5;
  l.dims[0] = 5, l.dims[1] = 4, l.dims[2] = 1;
  l.components = 1;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) l.values.push_back(1.0 + 0.1 * (-1 + 0.5 * i) + 0.2 * (2 + 0.5 * j));
  const LatticeField2 f(std::move(l));
  EXPECT_TRUE(f.isotropic());
  for (double x : {-1.0, -0.3, 0.77, 1.0})
    for (double y : {2.0, 2.6, 3.5})
      EXPECT_NEAR(size_at(f, x, y), 1.0 + 0.1 * x + 0.2 * y, 1e-12) << x << " " << y;
  EXPECT_NEAR(size_at(f, 5.0, 2.0), 1.0 + 0.1 * 1.0 + 0.2 * 2.0, 1e-12);  // clamped to the box
}

TEST(Mesh2dSizing, AsciiGridValuesAndNoData) {
  Result<Raster> r = parse_ascii_grid(
      "ncols 3\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 2\nNODATA_value -9999\n"
      "1 2 -9999\n3 4 5\n", "d.asc");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->x0, 11.0);  // cell centres
  EXPECT_EQ(r->value(11, 21), 3.0);  // the bottom row is the file's last
  EXPECT_EQ(r->value(11, 23), 1.0);
  EXPECT_NEAR(r->value(12, 22), 2.5, 1e-12);
  EXPECT_TRUE(std::isnan(r->value(14, 22.5)));  // next to the no-data cell
  EXPECT_TRUE(std::isnan(r->value(0, 0)));       // outside
  Status bad = parse_ascii_grid("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 x 6\n", "d.asc").status();
  EXPECT_EQ(bad.code(), Error::Parse);
  EXPECT_NE(bad.message().find("d.asc:7:"), std::string::npos) << bad.message();
  EXPECT_EQ(parse_ascii_grid("ncols 3\n1 2\n", "d.asc").status().code(), Error::Parse);
}

TEST(Mesh2dSizing, BackgroundMeshFieldIsLinearInTriangles) {
  // Two triangles over [0, 2] x [0, 1]; sizes 1 + x + y at the vertices.
  std::vector<double> xy = {0, 0, 2, 0, 2, 1, 0, 1};
  std::vector<double> h;
  for (int v = 0; v < 4; ++v) h.push_back(1 + xy[2 * size_t(v)] + xy[2 * size_t(v) + 1]);
  Result<std::unique_ptr<Background2Field>> f = Background2Field::create(xy, {0, 1, 2, 0, 2, 3}, h, 1);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.5, 0.25), 1.75, 1e-12);
  EXPECT_NEAR(size_at(*f.value(), 1.9, 0.9), 3.8, 1e-12);
  // Outside: the nearest triangle's values, barycentric weights clamped (between its edge's).
  EXPECT_GT(size_at(*f.value(), 3.0, 0.5), 3.0);
  EXPECT_LT(size_at(*f.value(), 3.0, 0.5), 4.0);
  EXPECT_EQ(Background2Field::create(xy, {0, 1, 2}, {1, 1, 1}, 1).status().code(), Error::InvalidArgument);
  EXPECT_EQ(Background2Field::create(xy, {0, 1, 2, 0, 2, 3}, {1, 1, 0, 1}, 1).status().code(), Error::InvalidArgument);
}

TEST(Mesh2dSizing, DefaultFollowsTheSegmentsAndGradationBoundsGrowth) {
  Pslg p = square16();
  // Refine one side: 8 segments of 0.5 instead of 4 of 1 along y = 0.
  Pslg q;
  for (int i = 0; i < 8; ++i) q.xy.insert(q.xy.end(), {0.5 * i, 0.0});
  for (int k = 4; k < 16; ++k) q.xy.insert(q.xy.end(), {p.xy[2 * size_t(k)], p.xy[2 * size_t(k) + 1]});
  const uint32_t n = uint32_t(q.xy.size() / 2);
  for (uint32_t i = 0; i < n; ++i) q.seg.insert(q.seg.end(), {i, (i + 1) % n});
  q.label.assign(n, 1);
  Result<Domain> d = analyse_domain(q);
  ASSERT_TRUE(d.ok()) << d.status().message();
  SizingStats2 st;
  Result<std::unique_ptr<SizingField>> f = build_sizing2(q, d.value(), SizingOptions2{}, &st);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(st.source, "boundary");
  EXPECT_NEAR(size_at(*f.value(), 2.0, 0.0), 0.5, 1e-9);
  EXPECT_NEAR(size_at(*f.value(), 2.0, 4.0), 1.0, 1e-9);
  const double mid = size_at(*f.value(), 2.0, 2.0);
  EXPECT_GT(mid, 0.55);
  EXPECT_LT(mid, 0.95);
  // With hmax and a constant size, graded from a fine corner: growth bounded by hgrad.
  SizingOptions2 o;
  o.distance_h0 = 0.05, o.distance_rate = 10.0;  // steep growth away from the segments
  o.hmax = 2.0, o.hgrad = 1.2;
  Result<std::unique_ptr<SizingField>> g = build_sizing2(q, d.value(), o, &st);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_NEAR(size_at(*g.value(), 0.0, 2.0), 0.05, 1e-9);
  const double h1 = size_at(*g.value(), 0.5, 2.0);
  EXPECT_LT(h1, 0.05 + 0.5 * std::log(1.2) * 1.3 + 0.2);  // h grows about (hgrad - 1) per unit length
  EXPECT_LT(h1, 0.05 + 10.0 * 0.5);                       // far below the ungraded 5.05
  EXPECT_LE(size_at(*g.value(), 2.0, 2.0), 2.0 + 1e-9);
}

TEST(Mesh2dSizing, BathymetrySizesFollowTheWavelengthRule) {
  Pslg p = square16();
  Result<Domain> d = analyse_domain(p);
  ASSERT_TRUE(d.ok());
  // Depth 10 m on the left half, 40 m on the right: sizes T sqrt(g d) / N.
  Raster r;
  r.ncols = 5, r.nrows = 5, r.x0 = 0, r.y0 = 0, r.dx = r.dy = 1;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) r.values.push_back(i < 2 ? 10.0 : 40.0);
  SizingOptions2 o;
  o.bathymetry = &r;
  o.wave_period = 1.0, o.points_per_wavelength = 20.0;
  Result<std::unique_ptr<SizingField>> f = build_sizing2(p, d.value(), o);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.5, 2.0), std::sqrt(9.80665 * 10) / 20.0, 1e-6);
  EXPECT_NEAR(size_at(*f.value(), 3.5, 2.0), std::sqrt(9.80665 * 40) / 20.0, 1e-6);
}

TEST(Mesh2dSizing, RefinementReachesAConstantSizeWithGoodTriangles) {
  Pslg p = square16();
  Mesh2dOptions o;
  o.sizing.hsize = 0.25;
  o.split_segments = true;
  Mesh2dStats st;
  Result<TriMesh2> m = mesh_pslg(p, o, &st);
  ASSERT_TRUE(m.ok()) << m.status().message();
  const Quality2 q = measure_quality(m.value());
  EXPECT_GE(q.in_range, 0.98);
  EXPECT_GE(q.min_angle_deg, 28.0);
  EXPECT_GE(q.mean_radius_ratio, 0.95);
  // About 16 / (sqrt(3)/4 0.25^2) = 591 triangles.
  EXPECT_GT(q.triangles, 400u);
  EXPECT_LT(q.triangles, 800u);
  EXPECT_GT(st.refine.segment_splits, 0u);
}

}  // namespace
}  // namespace anitet::mesh2d
