// adapt_mesh (issue 46) on the UGAWG cube (cube-linear-00: 64 vertices, 162 tets, 108 boundary
// triangles with labels 1..6) and its anisotropic metric: the working mesh checked after every
// sweep (AdaptMesh::check), the output valid with the cube's volume, its surface on the cube's
// faces with the labels kept, --keep-surface's triangles the input's, and bad input refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "adapt/adapt.hpp"
#include "core/metric_measures.hpp"
#include "core/sizing.hpp"
#include "io/volume_io.hpp"
#include "metric/sol_field.hpp"
#include "predicates/predicates.hpp"

namespace anitet {
namespace {

const std::string kCube = std::string(ANITET_UGAWG_DIR) + "/cube-linear-00";

struct Cube {
  VolumeMesh mesh;
  std::vector<double> metric;
};

Cube load_cube() {
  Cube c;
  Result<VolumeMesh> m = read_volume_mesh(kCube + ".mesh");
  EXPECT_TRUE(m.ok()) << m.status().message();
  Result<metric::SolField> s = metric::read_sol(kCube + ".sol");
  EXPECT_TRUE(s.ok()) << s.status().message();
  if (m.ok()) c.mesh = m.value();
  if (s.ok()) c.metric = s.value().values;
  return c;
}

// Every tet positive (exact); the sum of their volumes.
double checked_volume(const VolumeMesh& m) {
  double v = 0.0;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &m.xyz[3 * size_t(m.tet[4 * t + size_t(k)])];
    EXPECT_GT(predicates::orient3d(p[0], p[1], p[2], p[3]), 0.0) << "tet " << t;
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) a[k] = p[1][k] - p[0][k], b[k] = p[2][k] - p[0][k], c[k] = p[3][k] - p[0][k];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  return v;
}

// The boundary triangles as sorted triples of points (numbering-free).
std::set<std::array<std::array<double, 3>, 3>> triangle_set(const VolumeMesh& m) {
  std::set<std::array<std::array<double, 3>, 3>> out;
  for (size_t f = 0; f < m.num_boundary_triangles(); ++f) {
    std::array<std::array<double, 3>, 3> t;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) t[size_t(k)][size_t(c)] = m.xyz[3 * size_t(m.bnd_tri[3 * f + size_t(k)]) + size_t(c)];
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

// The edges of the tets, each once (smaller end first).
std::set<std::pair<uint32_t, uint32_t>> edges_of(const VolumeMesh& m) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const uint32_t a = m.tet[4 * t + size_t(i)], b = m.tet[4 * t + size_t(j)];
        edges.insert({std::min(a, b), std::max(a, b)});
      }
  return edges;
}

TEST(Adapt, CubeStaysValidAfterEverySweep) {
  Cube c = load_cube();
  AdaptOptions o;
  o.check_each_sweep = true;  // AdaptMesh::check() after every sweep: an Error::Internal otherwise
  o.max_cycles = 4;
  Result<AdaptResult> r = adapt_mesh(c.mesh, c.metric, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const VolumeMesh& out = r.value().mesh;
  EXPECT_GT(out.num_tets(), 10 * c.mesh.num_tets());
  EXPECT_NEAR(checked_volume(out), 1.0, 1e-12);
  // The surface adapted on the cube's faces, labels 1..6 kept, every face labelled by its plane.
  EXPECT_GT(out.num_boundary_triangles(), 10 * c.mesh.num_boundary_triangles());
  std::set<int32_t> labels(out.bnd_patch.begin(), out.bnd_patch.end());
  EXPECT_EQ(labels, (std::set<int32_t>{1, 2, 3, 4, 5, 6}));
  for (size_t v = 0; v < out.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = out.xyz[3 * v + size_t(k)];
      EXPECT_TRUE(x >= -1e-12 && x <= 1.0 + 1e-12) << "vertex " << v << " outside the cube";
    }
  for (size_t f = 0; f < out.num_boundary_triangles(); ++f) {
    // The coordinates all three points have at 0 or 1 (to rounding: new points are placed on
    // the smooth surface's curves, 4e-15 off the plane at most).
    int on_plane = 0;
    for (double side : {0.0, 1.0})
      for (int k = 0; k < 3; ++k) {
        bool on = true;
        for (int j = 0; j < 3; ++j)
          on = on && std::fabs(out.xyz[3 * size_t(out.bnd_tri[3 * f + size_t(j)]) + size_t(k)] - side) < 1e-12;
        on_plane += on;
      }
    EXPECT_EQ(on_plane, 1) << "boundary triangle " << f << " is not on a face of the cube";
  }
  // The metric at the output's vertices (6 per vertex, SPD) comes with it.
  EXPECT_EQ(out.vertex_metric.size(), 6 * out.num_vertices());
}

TEST(Adapt, KeepSurfaceKeepsEveryBoundaryTriangle) {
  Cube c = load_cube();
  AdaptOptions o;
  o.keep_surface = true;
  o.max_cycles = 4;
  Result<AdaptResult> r = adapt_mesh(c.mesh, c.metric, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r.value().mesh.num_tets(), 10 * c.mesh.num_tets());
  EXPECT_EQ(triangle_set(r.value().mesh), triangle_set(c.mesh));
  EXPECT_EQ(r.value().stats.surface_splits + r.value().stats.surface_collapses + r.value().stats.surface_moves, 0u);
  EXPECT_NEAR(checked_volume(r.value().mesh), 1.0, 1e-12);
}

// Edges from the kept faces into the volume are not split: their splits crowded inner points
// against the coarse kept faces (0.003 from them after one pass, 1e-4 after five), where no
// edge can follow the metric, whose size across the cube's faces is 0.1.
TEST(Adapt, KeepSurfaceLeavesNoInnerPointAgainstTheKeptFaces) {
  Cube c = load_cube();
  AdaptOptions o;
  o.keep_surface = true;
  Result<AdaptResult> r = adapt_mesh(c.mesh, c.metric, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const VolumeMesh& m = r.value().mesh;
  std::vector<bool> on(m.num_vertices(), false);
  for (uint32_t v : m.bnd_tri) on[v] = true;
  double nearest = 1.0;
  for (size_t v = 0; v < m.num_vertices(); ++v)
    if (!on[v])
      for (int k = 0; k < 3; ++k) nearest = std::min({nearest, m.xyz[3 * v + size_t(k)], 1.0 - m.xyz[3 * v + size_t(k)]});
  EXPECT_GT(nearest, 0.01);
}

TEST(Adapt, BadInputIsRefusedNamingTheProblem) {
  Cube c = load_cube();
  std::vector<double> short_metric(c.metric.begin(), c.metric.end() - 6);
  Result<AdaptResult> r = adapt_mesh(c.mesh, short_metric);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::InvalidArgument);

  std::vector<double> not_spd = c.metric;
  not_spd[6 * 9] = -1.0;  // vertex 10 (1-based)
  r = adapt_mesh(c.mesh, not_spd);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::InvalidArgument);
  EXPECT_NE(r.status().message().find("vertex 10"), std::string::npos) << r.status().message();

  VolumeMesh inverted = c.mesh;
  std::swap(inverted.tet[0], inverted.tet[1]);
  r = adapt_mesh(inverted, c.metric);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("tet 1 is inverted"), std::string::npos) << r.status().message();

  std::vector<double> zero_size(c.mesh.num_vertices(), 0.1);
  zero_size[3] = 0.0;
  r = adapt_mesh(c.mesh, zero_size);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::InvalidArgument);
}

// An isotropic size: the surface and volume refined to it, most edges of unit metric length.
TEST(Adapt, UniformSizeIsFollowed) {
  Cube c = load_cube();
  const double h = 0.2;
  Result<AdaptResult> r = adapt_mesh(c.mesh, std::vector<double>(c.mesh.num_vertices(), h));
  ASSERT_TRUE(r.ok()) << r.status().message();
  const VolumeMesh& out = r.value().mesh;
  const std::set<std::pair<uint32_t, uint32_t>> edges = edges_of(out);
  size_t in_range = 0;
  for (const auto& [a, b] : edges) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(out.xyz[3 * size_t(a) + size_t(k)] - out.xyz[3 * size_t(b) + size_t(k)], 2);
    const double l = std::sqrt(d2) / h;
    in_range += l >= std::sqrt(0.5) && l <= std::sqrt(2.0);
  }
  EXPECT_GT(double(in_range) / double(edges.size()), 0.9) << in_range << " of " << edges.size();
  EXPECT_NEAR(checked_volume(out), 1.0, 1e-12);
}

// A metric whose strong direction turns: fine (h_r) across the sphere |x - c| = R that cuts the
// cube, coarse (h_t) along it, as the sphere case of issue 46 on a small scale. A tangential edge
// of length l has a normal part l^2/2R at its ends, so the lengths in range span a factor 1.4 in
// l, not 2; the moves towards ideal tets left the spacing uneven (short and long edges side by
// side). With the balancing moves (smooth.cpp) 74.4% of the edges are in range, 68.5% without;
// cutting edges in thirds where halves miss and thirds fit (split.cpp) 74.5%, some 1 300 such
// splits; with the tet quality the worst over its corners' metrics (remesher.cpp) 79.1% (78.4%
// without the thirds).
class TurningShellMetric final : public SizingField {
 public:
  void metric(const double p[3], double m[6]) const override {
    const double d[3] = {p[0] - kC[0], p[1] - kC[1], p[2] - kC[2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double n[3] = {d[0] / r, d[1] / r, d[2] / r};
    const double hr = 0.003 + 0.2 * std::fabs(r - kR), ht = 0.2;
    const double a = 1.0 / (hr * hr) - 1.0 / (ht * ht), b = 1.0 / (ht * ht);
    const int idx[6][2] = {{0, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}, {2, 2}};  // xx xy yy xz yz zz
    for (int k = 0; k < 6; ++k) m[k] = a * n[idx[k][0]] * n[idx[k][1]] + (idx[k][0] == idx[k][1] ? b : 0.0);
  }
  static constexpr double kC[3] = {0.5, 0.5, -0.5};
  static constexpr double kR = 1.0;
};

TEST(Adapt, TurningMetricEdgesAreBalanced) {
  Cube c = load_cube();
  const TurningShellMetric field;
  Result<AdaptResult> r = adapt_mesh(c.mesh, field);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const VolumeMesh& out = r.value().mesh;
  const std::set<std::pair<uint32_t, uint32_t>> edges = edges_of(out);
  std::vector<double> met(6 * out.num_vertices());
  for (size_t v = 0; v < out.num_vertices(); ++v) field.metric(&out.xyz[3 * v], &met[6 * v]);
  size_t in_range = 0;
  for (const auto& [a, b] : edges) {
    const double l = ugawg_edge_length(&out.xyz[3 * size_t(a)], &out.xyz[3 * size_t(b)], &met[6 * size_t(a)],
                                       &met[6 * size_t(b)]);
    in_range += l >= std::sqrt(0.5) && l <= std::sqrt(2.0);
  }
  const double share = double(in_range) / double(edges.size());
  std::printf("%zu tets, %.1f%% of %zu edges in range, %zu splits in thirds\n", out.num_tets(), 100 * share,
              edges.size(), r.value().stats.splits_in_thirds);
  EXPECT_GT(share, 0.77);
  EXPECT_GT(r.value().stats.splits_in_thirds, 100u);
  EXPECT_NEAR(checked_volume(out), 1.0, 1e-12);
}

}  // namespace
}  // namespace anitet
