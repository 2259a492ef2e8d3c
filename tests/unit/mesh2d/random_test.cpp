// Random inputs through the whole 2D pipeline: star-shaped polygons (spiky, with near-collinear
// runs of points and sharp corners) with star-shaped islands, meshed in both modes; every mesh
// valid, every segment kept, the domain's area covered exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh2d/domain.hpp"
#include "mesh2d/mesher2.hpp"

namespace anitet::mesh2d {
namespace {

// A star-shaped loop of n points about (cx, cy), counter-clockwise (or clockwise for holes).
void add_star(Pslg& p, std::mt19937_64& rng, double cx, double cy, double r, int n, bool hole, int32_t label) {
  std::uniform_real_distribution<double> u(0, 1);
  const uint32_t first = uint32_t(p.num_points());
  std::vector<double> angle(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) angle[size_t(i)] = 2 * M_PI * (i + 0.8 * u(rng)) / n;
  for (int i = 0; i < n; ++i) {
    const int k = hole ? n - 1 - i : i;
    double radius = r * (0.35 + 0.65 * u(rng));
    if (u(rng) < 0.15) radius = r;          // runs of near-equal radii: near-collinear points
    if (u(rng) < 0.1) radius = 0.4 * r;     // deep notches: sharp corners
    p.xy.push_back(cx + radius * std::cos(angle[size_t(k)]));
    p.xy.push_back(cy + radius * std::sin(angle[size_t(k)]));
  }
  for (int i = 0; i < n; ++i) {
    p.seg.push_back(first + uint32_t(i));
    p.seg.push_back(first + uint32_t((i + 1) % n));
    p.label.push_back(label);
  }
  if (hole) p.holes.insert(p.holes.end(), {cx, cy});
}

double mesh_area(const TriMesh2& m) {
  double total = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double* a = &m.xy[2 * size_t(m.tri[3 * t])];
    const double* b = &m.xy[2 * size_t(m.tri[3 * t + 1])];
    const double* c = &m.xy[2 * size_t(m.tri[3 * t + 2])];
    total += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  return total;
}

double loop_area(const Pslg& p, size_t first, size_t n) {
  double s = 0;
  for (size_t i = 0; i < n; ++i) {
    const double* a = p.point(first + i);
    const double* b = p.point(first + (i + 1) % n);
    s += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * s;
}

// `trials` random inputs scaled by `scale` about the point (ox, oy): UTM-like offsets put the
// coordinates' leading digits far from the features' sizes.
void random_inputs(uint64_t seed, int trials, double scale, double ox, double oy) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int meshed = 0;
  for (int trial = 0; trial < trials; ++trial) {
    Pslg p;
    p.name = "random" + std::to_string(trial);
    const int n = 10 + int(u(rng) * 40);
    add_star(p, rng, ox, oy, 10 * scale, n, false, 1);
    double area = loop_area(p, 0, size_t(n));
    // Islands on a ring well inside the outer loop (its chords stay beyond radius 3): no crossings.
    const int islands = int(u(rng) * 3);
    for (int i = 0; i < islands; ++i) {
      const size_t first = p.num_points();
      const double a = 2 * M_PI * (i + 0.5 * u(rng)) / 3;
      add_star(p, rng, ox + 1.2 * scale * std::cos(a), oy + 1.2 * scale * std::sin(a), 0.6 * scale, 5 + int(u(rng) * 8), true, 2);
      area += loop_area(p, first, p.num_points() - first);
    }
    for (const bool split : {false, true}) {
      Mesh2dOptions o;
      o.split_segments = split;
      o.sizing.hsize = (0.6 + u(rng)) * scale;
      Result<TriMesh2> m = mesh_pslg(p, o);
      ASSERT_TRUE(m.ok()) << p.name << (split ? " split: " : ": ") << m.status().message();
      EXPECT_NEAR(mesh_area(m.value()), area, (ox != 0 ? 1e-6 : 1e-9) * area) << p.name;
      // Every segment kept: as one edge (default) or as pieces covering it.
      size_t pieces = 0;
      for (uint32_t s : m->edge_segment) pieces += s < p.num_segments();
      if (!split) EXPECT_EQ(m->edge_label.size(), p.num_segments()) << p.name;
      else EXPECT_GE(pieces, p.num_segments()) << p.name;
      ++meshed;
    }
  }
  EXPECT_EQ(meshed, 2 * trials);
}

TEST(Mesh2dRandom, StarPolygonsWithIslandsInBothModes) { random_inputs(2026, 40, 1.0, 0.0, 0.0); }

TEST(Mesh2dRandom, TheSameInMetresFarFromTheOrigin) { random_inputs(7, 10, 1000.0, 512345.678, 5012345.678); }

}  // namespace
}  // namespace anitet::mesh2d
