#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "io/surface_io.hpp"
#include "metric/metric_field.hpp"
#include "metric/surface_sizing.hpp"

namespace anitet {
namespace metric {
namespace {

TEST(TriangleBox, CutsAndMisses) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  const double inside[3] = {0.2, 0.2, 0.0}, above[3] = {0.2, 0.2, 0.6};
  const double touching[3] = {0.2, 0.2, 0.5}, beyond_hyp[3] = {0.9, 0.9, 0.0};
  EXPECT_TRUE(triangle_cuts_box(a, b, c, inside, 0.1));
  EXPECT_FALSE(triangle_cuts_box(a, b, c, above, 0.5 - 1e-3));
  EXPECT_TRUE(triangle_cuts_box(a, b, c, touching, 0.5));
  // Separated only by the hypotenuse's edge-cross axis, not by the face normals.
  EXPECT_FALSE(triangle_cuts_box(a, b, c, beyond_hyp, 0.3));
  EXPECT_TRUE(triangle_cuts_box(a, b, c, beyond_hyp, 0.45));
  // A huge triangle through a small box.
  const double A[3] = {-100, -100, 0.01}, B[3] = {100, -100, 0.01}, C[3] = {0, 100, 0.01};
  const double o[3] = {0, 0, 0};
  EXPECT_TRUE(triangle_cuts_box(A, B, C, o, 0.02));
  EXPECT_FALSE(triangle_cuts_box(A, B, C, o, 0.005));
}

// The distance from p to the closed triangle abc, computed another way than closest_point.hpp's
// region test: the foot on the plane when it lies inside (barycentric signs), else the nearest of
// the three edges.
double segment_distance(const double* p, const double* a, const double* b) {
  double ab[3], ap[3], l2 = 0, t = 0;
  for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k], l2 += ab[k] * ab[k], t += ab[k] * ap[k];
  t = l2 > 0 ? std::min(std::max(t / l2, 0.0), 1.0) : 0.0;
  double d = 0;
  for (int k = 0; k < 3; ++k) d += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
  return std::sqrt(d);
}
double triangle_distance(const double* p, const double* a, const double* b, const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (nn > 0) {
    const double h = ((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2]) / nn;
    const double f[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
    const double* t[3] = {a, b, c};
    bool inside = true;
    for (int e = 0; e < 3 && inside; ++e) {  // f on the inner side of every edge
      const double* x = t[e];
      const double* y = t[(e + 1) % 3];
      const double xy[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]}, xf[3] = {f[0] - x[0], f[1] - x[1], f[2] - x[2]};
      const double cr[3] = {xy[1] * xf[2] - xy[2] * xf[1], xy[2] * xf[0] - xy[0] * xf[2], xy[0] * xf[1] - xy[1] * xf[0]};
      inside = cr[0] * n[0] + cr[1] * n[1] + cr[2] * n[2] >= 0;
    }
    if (inside) return std::fabs(h) * std::sqrt(nn);
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

// The pinned values an independent pass computes: min triangle size over the triangles pinning
// each voxel (cutting its cube, or within half a voxel of its centre; infinity where none does).
// Band voxels whose distance lies within 1e-6 h of the band's edge are marked NaN: two roundings
// of the distance may decide them differently.
std::vector<double> expected_pinned(const SurfaceMesh& s, const Lattice& lat, TriangleSize kind,
                                    Pinning pinning) {
  std::vector<double> v(lat.num_nodes(), std::numeric_limits<double>::infinity());
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    const double* p[3] = {s.point(s.tri[3 * t]), s.point(s.tri[3 * t + 1]), s.point(s.tri[3 * t + 2])};
    double l[3];
    for (int e = 0; e < 3; ++e)
      l[e] = std::sqrt(std::pow(p[e][0] - p[(e + 1) % 3][0], 2) +
                       std::pow(p[e][1] - p[(e + 1) % 3][1], 2) +
                       std::pow(p[e][2] - p[(e + 1) % 3][2], 2));
    const double size = kind == TriangleSize::Shortest ? std::min({l[0], l[1], l[2]})
                                                       : (l[0] + l[1] + l[2]) / 3.0;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const double mn = std::min({p[0][k], p[1][k], p[2][k]}), mx = std::max({p[0][k], p[1][k], p[2][k]});
      lo[k] = std::max(0, int(std::floor((mn - lat.origin[k]) / lat.spacing)) - 1);
      hi[k] = std::min(lat.dims[k] - 1, int(std::ceil((mx - lat.origin[k]) / lat.spacing)) + 1);
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          double c[3];
          lat.position(i, j, k, c);
          double& value = v[lat.node(i, j, k)];
          if (pinning == Pinning::CutCube) {
            if (triangle_cuts_box(p[0], p[1], p[2], c, 0.5 * lat.spacing)) value = std::min(value, size);
            continue;
          }
          const double d = triangle_distance(c, p[0], p[1], p[2]);
          if (std::fabs(d - 0.5 * lat.spacing) < 1e-6 * lat.spacing) value = NAN;
          else if (d < 0.5 * lat.spacing && !std::isnan(value)) value = std::min(value, size);
        }
  }
  return v;
}

void check_surface(const std::string& file, const SurfaceSizingOptions& opt) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/" + file);
  ASSERT_TRUE(s.ok()) << s.status().message();
  SurfaceSizingStats st;
  const auto t0 = std::chrono::steady_clock::now();
  Result<Lattice> lat = surface_sizing(s.value(), opt, &st);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(lat.ok()) << lat.status().message();
  EXPECT_TRUE(st.converged) << "last change " << st.last_change;
  EXPECT_LE(st.voxels, opt.max_voxels);
  EXPECT_GT(st.pinned, 0u);
  // Pinned voxels hold exactly their triangle size; the others lie between the pinned extremes
  // (the smoothing is an averaging: maximum principle).
  const std::vector<double> want =
      expected_pinned(s.value(), lat.value(), opt.triangle_size, opt.pinning);
  double pmin = HUGE_VAL, pmax = 0.0;
  size_t pinned = 0, undecided = 0;
  for (size_t n = 0; n < want.size(); ++n)
    if (std::isnan(want[n])) {
      ++undecided;
    } else if (std::isfinite(want[n])) {
      // Equal up to the rounding of the edge lengths (computed here in another order).
      ASSERT_NEAR(lat->values[n], want[n], 1e-14 * want[n]) << "pinned voxel " << n;
      pmin = std::min(pmin, want[n]);
      pmax = std::max(pmax, want[n]);
      ++pinned;
    }
  EXPECT_GE(st.pinned, pinned);
  EXPECT_LE(st.pinned, pinned + undecided);
  EXPECT_LE(undecided, pinned / 1000);
  for (size_t n = 0; n < want.size(); ++n) {
    if (std::isnan(want[n])) continue;
    ASSERT_GE(lat->values[n], pmin * (1 - 1e-12));
    ASSERT_LE(lat->values[n], pmax * (1 + 1e-12));
  }
  const auto t1 = std::chrono::steady_clock::now();
  Result<MetricField> f = MetricField::from_lattice(lat.value(), opt.prune_tolerance);
  const double vdb_secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  ASSERT_TRUE(f.ok()) << f.status().message();
  // The sparse field keeps the pinned values where no leaf was collapsed, and stays within the
  // prune tolerance of the lattice everywhere.
  MetricField::Sampler sampler(f.value());
  size_t stored = 0;
  for (int k = 0; k < lat->dims[2]; ++k)
    for (int j = 0; j < lat->dims[1]; ++j)
      for (int i = 0; i < lat->dims[0]; ++i) {
        const size_t n = lat->node(i, j, k);
        if (!lat->active.empty() && !lat->active[n]) continue;  // dropped outside voxel
        double p[3], m[6];
        lat->position(i, j, k, p);
        sampler.metric(p, m);
        ASSERT_NEAR(1.0 / std::sqrt(m[0]), lat->values[n],
                    opt.prune_tolerance * lat->values[n] * 1.01);
        ++stored;
      }
  EXPECT_EQ(stored, st.voxels - st.dropped);
  EXPECT_EQ(f->active_voxels(), stored);
  if (opt.drop_outside) {
    EXPECT_GT(st.dropped, st.voxels / 10);
  }
  std::printf(
      "[sizing] %s (%s, %s): %zu triangles, lattice %dx%dx%d = %zu voxels (h %.4g), %zu pinned, %zu dropped outside, "
      "%d iterations, last change %.2e, %.3f s, working memory %.1f MB; OpenVDB field (prune %g): "
      "%zu leaves, %.1f MB (dense doubles %.1f MB), built in %.3f s\n",
      file.c_str(), opt.smoothing == Smoothing::Laplacian ? "Laplacian" : "Gaussian",
      opt.triangle_size == TriangleSize::Shortest ? "shortest edge" : "mean edge",
      s->num_triangles(), lat->dims[0], lat->dims[1], lat->dims[2], st.voxels, st.voxel_size,
      st.pinned, st.dropped, st.iterations, st.last_change, secs, st.working_bytes / 1048576.0,
      opt.prune_tolerance, f->leaf_count(), f->memory_bytes() / 1048576.0, st.voxels * 8.0 / 1048576.0, vdb_secs);
  ::testing::Test::RecordProperty("iterations", st.iterations);
}

TEST(SurfaceSizing, FandiskConverges) {
  SurfaceSizingOptions opt;
  check_surface("fandisk.off", opt);
}

TEST(SurfaceSizing, FandiskWholeBoxConverges) {
  SurfaceSizingOptions opt;
  opt.drop_outside = false;
  check_surface("fandisk.off", opt);
}

TEST(SurfaceSizing, FandiskGaussianMeanEdgeConverges) {
  SurfaceSizingOptions opt;
  opt.smoothing = Smoothing::Gaussian;
  opt.triangle_size = TriangleSize::Mean;
  check_surface("fandisk.off", opt);
}

TEST(SurfaceSizing, FandiskCutCubeConverges) {
  SurfaceSizingOptions opt;
  opt.pinning = Pinning::CutCube;
  check_surface("fandisk.off", opt);
}

// The unit cube's 12 triangles, turned by the rotation R (rows) about its centre.
SurfaceMesh turned_cube(const double R[3][3]) {
  SurfaceMesh cube;
  for (int v = 0; v < 8; ++v) {
    const double p[3] = {(v & 1) - 0.5, ((v >> 1) & 1) - 0.5, ((v >> 2) & 1) - 0.5};
    cube.add_vertex(R[0][0] * p[0] + R[0][1] * p[1] + R[0][2] * p[2],
                    R[1][0] * p[0] + R[1][1] * p[1] + R[1][2] * p[2],
                    R[2][0] * p[0] + R[2][1] * p[1] + R[2][2] * p[2]);
  }
  const uint32_t f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f) cube.add_triangle(t[0], t[1], t[2]);
  return cube;
}

TEST(SurfaceSizing, HalfVoxelBandPinsAsManyVoxelsTurned) {
  // A band of constant width pins about area / h^2 voxels however the faces lie; the cube test
  // pins up to sqrt(3) times more on oblique faces. Voxel 0.02, so ~6 * 2500 per orientation.
  const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Rotation by 1 rad about (1, 2, 3)/|.| (Rodrigues), far from any axis.
  const double k[3] = {1 / std::sqrt(14.0), 2 / std::sqrt(14.0), 3 / std::sqrt(14.0)};
  const double c = std::cos(1.0), s = std::sin(1.0);
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + (1 - c) * k[i] * k[j];
  R[0][1] -= s * k[2], R[0][2] += s * k[1], R[1][0] += s * k[2];
  R[1][2] -= s * k[0], R[2][0] -= s * k[1], R[2][1] += s * k[0];
  size_t pinned[2][2];
  for (int pin = 0; pin < 2; ++pin)
    for (int turned = 0; turned < 2; ++turned) {
      SurfaceSizingOptions opt;
      opt.voxel_size = 0.02;
      opt.pinning = pin == 0 ? Pinning::HalfVoxelBand : Pinning::CutCube;
      SurfaceSizingStats st;
      ASSERT_TRUE(surface_sizing(turned_cube(turned ? R : I), opt, &st).ok());
      pinned[pin][turned] = st.pinned;
    }
  std::printf("[sizing] unit cube, voxel 0.02: band pins %zu as given, %zu turned; cut cube %zu, %zu\n",
              pinned[0][0], pinned[0][1], pinned[1][0], pinned[1][1]);
  EXPECT_NEAR(double(pinned[0][1]) / double(pinned[0][0]), 1.0, 0.03);
  EXPECT_GT(double(pinned[1][1]) / double(pinned[1][0]), 1.2);  // what the band avoids
}

TEST(SurfaceSizing, SurfaceBetweenTheNodesFallsBackToTheCubeTest) {
  // Two tets of edge 0.05 at opposite corners of a 3.9 box, voxel 1, no padding: the nodes sit at
  // 0.45 + i, 0.69 from either tet, so no half-voxel band holds a node; the cube test pins one
  // node for each.
  SurfaceMesh two;
  for (double o : {0.0, 3.85}) {
    const uint32_t b = uint32_t(two.num_vertices());
    two.add_vertex(o, o, o);
    two.add_vertex(o + 0.05, o, o);
    two.add_vertex(o, o + 0.05, o);
    two.add_vertex(o, o, o + 0.05);
    two.add_triangle(b, b + 2, b + 1);
    two.add_triangle(b, b + 1, b + 3);
    two.add_triangle(b, b + 3, b + 2);
    two.add_triangle(b + 1, b + 2, b + 3);
  }
  SurfaceSizingOptions opt;
  opt.voxel_size = 1.0;
  opt.padding = 0;
  SurfaceSizingStats st;
  Result<Lattice> lat = surface_sizing(two, opt, &st);
  ASSERT_TRUE(lat.ok()) << lat.status().message();
  EXPECT_EQ(lat->dims[0], 4);
  EXPECT_TRUE(st.cube_fallback);
  EXPECT_EQ(st.pinned, 2u);
  EXPECT_NEAR(lat->values[lat->node(0, 0, 0)], 0.05, 1e-12);
  EXPECT_NEAR(lat->values[lat->node(3, 3, 3)], 0.05, 1e-12);
  // The surfaces of the other tests hold nodes in their bands.
  opt.voxel_size = 0.0;
  Result<SurfaceMesh> fandisk = read_surface(std::string(ANITET_SURFACES_DIR) + "/fandisk.off");
  ASSERT_TRUE(fandisk.ok());
  ASSERT_TRUE(surface_sizing(fandisk.value(), opt, &st).ok());
  EXPECT_FALSE(st.cube_fallback);
}

TEST(SurfaceSizing, ArmadilloConverges) {
  SurfaceSizingOptions opt;
  check_surface("armadillo.obj", opt);
}

TEST(SurfaceSizing, DefaultFieldOnFandisk) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/fandisk.off");
  ASSERT_TRUE(s.ok());
  SurfaceSizingStats st;
  Result<MetricField> f = surface_sizing_field(s.value(), {}, &st);
  ASSERT_TRUE(f.ok()) << f.status().message();
  // Every value lies between the smallest and largest triangle size (maximum principle), up to
  // the 1% prune tolerance.
  double lo = HUGE_VAL, hi = 0.0;
  for (size_t t = 0; t < s->num_triangles(); ++t) {
    double shortest = HUGE_VAL;
    for (int e = 0; e < 3; ++e) {
      const double* a = s->point(s->tri[3 * t + e]);
      const double* b = s->point(s->tri[3 * t + (e + 1) % 3]);
      shortest = std::min(shortest, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) +
                                              (a[1] - b[1]) * (a[1] - b[1]) +
                                              (a[2] - b[2]) * (a[2] - b[2])));
    }
    lo = std::min(lo, shortest);
    hi = std::max(hi, shortest);
  }
  for (size_t v = 0; v < s->num_vertices(); ++v) {
    double m[6];
    f->metric(s->point(v), m);
    const double h = 1.0 / std::sqrt(m[0]);
    ASSERT_GE(h, lo * 0.99);
    ASSERT_LE(h, hi * 1.01);
  }
}

TEST(SurfaceSizing, DropsOnlyTheOutsideOfACube) {
  // The unit cube, 12 triangles of shortest edge 1, voxel 0.1: the flood fill stops at the pinned
  // voxels, so the inside is kept and smoothed, and exactly the far outside is dropped.
  SurfaceMesh cube;
  for (int v = 0; v < 8; ++v) cube.add_vertex(v & 1, (v >> 1) & 1, (v >> 2) & 1);
  const uint32_t f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f) cube.add_triangle(t[0], t[1], t[2]);
  SurfaceSizingOptions opt;
  opt.voxel_size = 0.1;
  opt.padding = 3;
  SurfaceSizingStats st;
  Result<Lattice> lat = surface_sizing(cube, opt, &st);
  ASSERT_TRUE(lat.ok()) << lat.status().message();
  ASSERT_EQ(lat->dims[0], 17);  // 11 nodes across the cube + 2 * 3 padding
  // Pinned: the nodes within half a voxel of a face (x = 0 or 1 exactly at nodes 3 and 13).
  size_t inside = 0, kept = 0;
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const bool in = i > 3 && i < 13 && j > 3 && j < 13 && k > 3 && k < 13;
        const bool near = i >= 2 && i <= 14 && j >= 2 && j <= 14 && k >= 2 && k <= 14;
        const uint8_t a = lat->active[lat->node(i, j, k)];
        if (in) {
          ++inside;
          EXPECT_EQ(a, 1);
          EXPECT_NEAR(lat->values[lat->node(i, j, k)], 1.0, 1e-12);  // all pinned values are 1
        }
        EXPECT_EQ(a, near ? 1 : 0) << i << " " << j << " " << k;
        kept += a;
      }
  EXPECT_EQ(inside, 9u * 9u * 9u);
  EXPECT_EQ(st.dropped, 17u * 17u * 17u - kept);
}

TEST(SurfaceSizing, GradedFandiskFieldAndVdbRoundTrip) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/fandisk.off");
  ASSERT_TRUE(s.ok());
  Result<MetricField> f = surface_sizing_field(s.value());
  ASSERT_TRUE(f.ok()) << f.status().message();
  const double hgrad = 1.1;
  GradationStats gs;
  Result<MetricField> g = bound_and_grade(f.value(), 0.0, 0.0, hgrad, &gs);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_TRUE(gs.converged);
  EXPECT_EQ(g->active_voxels(), f->active_voxels());
  Result<Lattice> lat = g->to_lattice();
  ASSERT_TRUE(lat.ok());
  const double dx = lat->spacing;
  size_t pairs = 0;
  for (int k = 0; k + 1 < lat->dims[2]; ++k)
    for (int j = 0; j + 1 < lat->dims[1]; ++j)
      for (int i = 0; i + 1 < lat->dims[0]; ++i) {
        const size_t a = lat->node(i, j, k);
        const size_t nb[3] = {lat->node(i + 1, j, k), lat->node(i, j + 1, k), lat->node(i, j, k + 1)};
        for (size_t b : nb) {
          if (!lat->active.empty() && (!lat->active[a] || !lat->active[b])) continue;
          const double ha = lat->values[a], hb = lat->values[b];
          ASSERT_LE(hb, ha * std::pow(hgrad, dx / ha) * (1 + 1e-9));
          ASSERT_LE(ha, hb * std::pow(hgrad, dx / hb) * (1 + 1e-9));
          ++pairs;
        }
      }
  EXPECT_GT(pairs, 0u);
  const std::string path = std::string(::testing::TempDir()) + "anitet_metric_fandisk_sizing.vdb";
  ASSERT_TRUE(write_metric_vdb(g.value(), path).ok());
  Result<MetricField> r = read_metric_vdb(path);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->active_voxels(), g->active_voxels());
  for (size_t v = 0; v < s->num_vertices(); v += 7) {
    double m1[6], m2[6];
    g->metric(s->point(v), m1);
    r->metric(s->point(v), m2);
    ASSERT_NEAR(m1[0], m2[0], 1e-6 * m1[0]);  // float grids in the file
  }
  std::remove(path.c_str());
}

TEST(SurfaceSizing, MemoryBoundGrowsTheVoxel) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/fandisk.off");
  ASSERT_TRUE(s.ok());
  SurfaceSizingOptions opt;
  opt.max_voxels = 20000;
  SurfaceSizingStats st;
  Result<Lattice> lat = surface_sizing(s.value(), opt, &st);
  ASSERT_TRUE(lat.ok());
  EXPECT_LE(lat->num_nodes(), 20000u);
  EXPECT_TRUE(st.converged);
}

// The default voxel is the mean edge length, but at most twice the median one: adis16480's needle
// fans (edges of 40 mm beside a median of 0.26 mm) made the mean 3.2 mm, coarser than most of
// its triangles, and its rotated copy then got 60% fewer tets.
TEST(SurfaceSizing, DefaultVoxelIsTheMeanEdgeAtMostTwiceTheMedian) {
  for (const char* name : {"fandisk.off", "adis16480.stl"}) {
    SCOPED_TRACE(name);
    Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/" + name);
    ASSERT_TRUE(s.ok());
    std::vector<double> lengths;
    double sum = 0.0;
    for (size_t t = 0; t < s->num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const double* a = s->point(s->tri[3 * t + k]);
        const double* b = s->point(s->tri[3 * t + (k + 1) % 3]);
        lengths.push_back(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
        sum += lengths.back();
      }
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    const double mean = sum / double(lengths.size()), median = lengths[lengths.size() / 2];
    SurfaceSizingStats st;
    ASSERT_TRUE(surface_sizing(s.value(), SurfaceSizingOptions{}, &st).ok());
    if (std::string(name) == "fandisk.off") {
      EXPECT_LT(mean, 2.0 * median);
      EXPECT_NEAR(st.voxel_size, mean, 1e-12 * mean);
    } else {
      EXPECT_GT(mean, 10.0 * median);
      EXPECT_DOUBLE_EQ(st.voxel_size, 2.0 * median);
    }
  }
}

// Scaled by a power of two, the surface is the same in floating point: the field scales exactly
// (every size times the factor, at the scaled points), so the mesh does too.
TEST(SurfaceSizing, FieldScalesExactlyWithAPowerOfTwo) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok());
  for (int e : {-20, 20}) {
    SCOPED_TRACE(e);
    SurfaceMesh scaled = s.value();
    for (double& c : scaled.xyz) c = std::ldexp(c, e);
    Result<MetricField> a = surface_sizing_field(s.value());
    Result<MetricField> b = surface_sizing_field(scaled);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(std::ldexp(a->voxel_size(), e), b->voxel_size());
    MetricField::Sampler sa(a.value()), sb(b.value());
    size_t differ = 0;
    for (size_t v = 0; v + 2 < s->num_vertices(); v += 3) {
      double p[3], q[3], ma[6], mb[6];
      for (int k = 0; k < 3; ++k) {  // a point between three surface vertices: inside voxels
        p[k] = (s->point(v)[k] + s->point(v + 1)[k] + s->point(v + 2)[k]) / 3.0;
        q[k] = std::ldexp(p[k], e);
      }
      sa.metric(p, ma);
      sb.metric(q, mb);
      differ += std::ldexp(mb[0], 2 * e) != ma[0];
    }
    EXPECT_EQ(differ, 0u);
  }
}

TEST(SurfaceSizing, Errors) {
  SurfaceMesh empty;
  EXPECT_EQ(surface_sizing(empty).status().code(), Error::EmptyInput);
  SurfaceMesh bad;
  bad.add_vertex(0, 0, 0);
  bad.add_vertex(1, 0, 0);
  bad.add_vertex(0, NAN, 0);
  bad.add_triangle(0, 1, 2);
  EXPECT_EQ(surface_sizing(bad).status().code(), Error::InvalidArgument);
}

// A model 10^4 times smaller than the knight: voxels under OpenVDB's smallest transform scale.
// The field still samples the same sizes (scaled), and refuses to be written as .vdb.
TEST(SurfaceSizing, TinyModelSamplesButIsNotWrittenAsVdb) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok());
  SurfaceMesh tiny = s.value();
  for (double& c : tiny.xyz) c *= 1e-4;
  Result<MetricField> big = surface_sizing_field(s.value());
  Result<MetricField> small = surface_sizing_field(tiny);
  ASSERT_TRUE(big.ok()) << big.status().message();
  ASSERT_TRUE(small.ok()) << small.status().message();
  EXPECT_LT(small->voxel_size(), 1.4e-5);
  MetricField::Sampler sb(big.value()), ss(small.value());
  for (size_t v = 0; v < s->num_vertices(); v += 17) {
    double mb[6], ms[6];
    sb.metric(s->point(v), mb);
    ss.metric(tiny.point(v), ms);
    // M = I / h^2: the tiny model's metric is 10^8 times the big one's.
    EXPECT_NEAR(ms[0] * 1e-8, mb[0], 1e-9 * mb[0]) << "vertex " << v;
  }
  const std::string path = ::testing::TempDir() + "/tiny_sizing.vdb";
  const Status w = write_metric_vdb(small.value(), path);
  EXPECT_EQ(w.code(), Error::InvalidArgument);
  EXPECT_NE(w.message().find("OpenVDB transform"), std::string::npos) << w.message();
}

}  // namespace
}  // namespace metric
}  // namespace anitet
