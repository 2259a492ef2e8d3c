#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"
#include "metric/spd.hpp"
#include "test_util.hpp"

namespace anitet {
namespace metric {
namespace {

// A size lattice of dims n^3 on [0, (n-1) dx]^3 from a function of position.
template <class F>
Lattice size_lattice(int n, double dx, F&& h) {
  Lattice lat;
  lat.origin[0] = -1.0;
  lat.origin[1] = 0.5;
  lat.origin[2] = 2.0;
  lat.spacing = dx;
  lat.dims[0] = lat.dims[1] = lat.dims[2] = n;
  lat.components = 1;
  lat.values.resize(lat.num_nodes());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double p[3];
        lat.position(i, j, k, p);
        lat.values[lat.node(i, j, k)] = h(p);
      }
  return lat;
}

void random_point(std::mt19937_64& rng, const Lattice& lat, double margin, double p[3]) {
  for (int k = 0; k < 3; ++k) {
    std::uniform_real_distribution<double> u(lat.origin[k] - margin,
                                             lat.origin[k] + lat.spacing * (lat.dims[k] - 1) + margin);
    p[k] = u(rng);
  }
}

TEST(MetricField, ConstantSizeIsExact) {
  const Lattice lat = size_lattice(20, 0.1, [](const double*) { return 0.3; });
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(f->kind(), MetricField::Kind::Isotropic);
  std::mt19937_64 rng(5);
  double want[6];
  isotropic_metric(0.3, want);
  for (int n = 0; n < 10000; ++n) {
    double p[3], m[6];
    random_point(rng, lat, 0.5, p);  // also outside: clamped
    f->metric(p, m);
    for (int c = 0; c < 6; ++c) ASSERT_EQ(m[c], want[c]);
  }
}

// Fields built on two threads while the module is being opened by a third (the pipeline's
// order: VdbModulePreload, then the grid) all succeed and are the same field.
TEST(VdbModulePreload, FieldsBuiltWhileItRunsAreTheSame) {
  const Lattice lat = size_lattice(12, 0.1, [](const double* p) { return 0.2 + 0.05 * p[0]; });
  std::optional<Result<MetricField>> a, b;
  {
    VdbModulePreload preload;
    std::thread other([&] { b.emplace(MetricField::from_lattice(lat)); });
    a.emplace(MetricField::from_lattice(lat));
    other.join();
  }
  ASSERT_TRUE(a->ok()) << a->status().message();
  ASSERT_TRUE(b->ok()) << b->status().message();
  std::mt19937_64 rng(7);
  for (int n = 0; n < 100; ++n) {
    double p[3], ma[6], mb[6];
    random_point(rng, lat, 0.0, p);
    a->value().metric(p, ma);
    b->value().metric(p, mb);
    for (int c = 0; c < 6; ++c) ASSERT_EQ(ma[c], mb[c]);
  }
}

TEST(MetricField, LinearSizeIsExact) {
  auto h = [](const double* p) { return 2.0 + 0.3 * p[0] - 0.2 * p[1] + 0.1 * p[2]; };
  const Lattice lat = size_lattice(24, 0.125, h);
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok()) << f.status().message();
  std::mt19937_64 rng(6);
  std::vector<double> pts(3 * 10000), m(6 * 10000);
  for (size_t n = 0; n < 10000; ++n) random_point(rng, lat, 0.0, &pts[3 * n]);
  f->metrics(pts.data(), 10000, m.data());
  for (size_t n = 0; n < 10000; ++n) {
    const double got = 1.0 / std::sqrt(m[6 * n]);
    ASSERT_NEAR(got, h(&pts[3 * n]), 1e-13 * h(&pts[3 * n]));
    ASSERT_EQ(m[6 * n + 1], 0.0);
    ASSERT_EQ(m[6 * n], m[6 * n + 5]);
  }
}

TEST(MetricField, LogLinearTensorIsExact) {
  // log M(p) = L0 + x L1 + y L2 + z L3: trilinear interpolation in log space reproduces it.
  const double l0[6] = {1, 0.2, 2, -0.1, 0.3, 0.5}, lx[6] = {0.5, 0.1, -0.2, 0, 0.05, 0.1};
  const double ly[6] = {-0.3, 0, 0.2, 0.1, 0, 0.4}, lz[6] = {0.1, -0.2, 0, 0.3, 0.1, -0.5};
  auto log_at = [&](const double* p, double* l) {
    for (int c = 0; c < 6; ++c) l[c] = l0[c] + p[0] * lx[c] + p[1] * ly[c] + p[2] * lz[c];
  };
  const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1.5, 1};
  Result<MetricField> f = MetricField::from_function(
      [&](const double p[3], double m[6]) {
        double l[6];
        log_at(p, l);
        sym_exp(l, m);
      },
      lo, hi, 0.1);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(f->kind(), MetricField::Kind::Tensor);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MetricField::Sampler s(f.value());
  for (int n = 0; n < 10000; ++n) {
    double p[3], l[6], want[6], m[6];
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + u(rng) * (hi[k] - lo[k]);
    log_at(p, l);
    sym_exp(l, want);
    s.metric(p, m);
    ASSERT_LT(test::max_rel_diff(m, want), 1e-12);
  }
}

TEST(MetricField, InterpolationStaysSpdBetweenRandomSpdTensors) {
  // Random SPD tensors (sizes 1e-3 .. 1, anisotropy up to 1e3) at the nodes of a 5^3 lattice;
  // random segments across it. Log-Euclidean: every sample is SPD with eigenvalues between the
  // extreme eigenvalues of the nodes.
  std::mt19937_64 rng(8);
  Lattice lat;
  lat.dims[0] = lat.dims[1] = lat.dims[2] = 5;
  lat.components = 6;
  lat.values.resize(6 * lat.num_nodes());
  double lmin = HUGE_VAL, lmax = 0.0;
  for (size_t n = 0; n < lat.num_nodes(); ++n) {
    double m[6], val[3], vec[9];
    test::random_spd(rng, 1e-3, 1.0, m);
    ASSERT_TRUE(sym_log(m, &lat.values[6 * n]));
    sym_eigen(m, val, vec);
    lmin = std::min(lmin, val[0]);
    lmax = std::max(lmax, val[2]);
  }
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok()) << f.status().message();
  MetricField::Sampler s(f.value());
  std::uniform_real_distribution<double> u(0.0, 4.0);
  int samples = 0;
  for (int seg = 0; seg < 500; ++seg) {
    const double a[3] = {u(rng), u(rng), u(rng)}, b[3] = {u(rng), u(rng), u(rng)};
    for (int t = 0; t <= 50; ++t) {
      const double w = t / 50.0;
      const double p[3] = {a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]),
                           a[2] + w * (b[2] - a[2])};
      double m[6], val[3], vec[9];
      s.metric(p, m);
      ASSERT_TRUE(is_spd(m));
      sym_eigen(m, val, vec);
      ASSERT_GE(val[0], lmin * (1 - 1e-10));
      ASSERT_LE(val[2], lmax * (1 + 1e-10));
      ++samples;
    }
  }
  EXPECT_EQ(samples, 500 * 51);
}

TEST(MetricField, TwoTensorSegmentKeepsDeterminantGeometric) {
  // Between two nodes, det(M) = det(A)^(1-t) det(B)^t (no swelling, unlike linear interpolation).
  std::mt19937_64 rng(9);
  for (int rep = 0; rep < 100; ++rep) {
    double a[6], b[6];
    test::random_spd(rng, 1e-2, 1.0, a);
    test::random_spd(rng, 1e-2, 1.0, b);
    Lattice lat;
    lat.dims[0] = 2;
    lat.dims[1] = lat.dims[2] = 1;
    lat.components = 6;
    lat.values.resize(12);
    ASSERT_TRUE(sym_log(a, &lat.values[0]));
    ASSERT_TRUE(sym_log(b, &lat.values[6]));
    Result<MetricField> f = MetricField::from_lattice(lat);
    ASSERT_TRUE(f.ok()) << f.status().message();
    auto det = [](const double* m) {
      return m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
             m[3] * (m[1] * m[4] - m[2] * m[3]);
    };
    for (int t = 0; t <= 10; ++t) {
      const double p[3] = {t / 10.0, 0.0, 0.0};
      double m[6];
      f->metric(p, m);
      ASSERT_TRUE(is_spd(m));
      const double want = std::pow(det(a), 1 - t / 10.0) * std::pow(det(b), t / 10.0);
      ASSERT_NEAR(det(m), want, 1e-9 * want);
    }
  }
}

TEST(MetricField, OneSamplerPerThreadGivesTheSameResults) {
  std::mt19937_64 rng(14);
  Lattice lat;
  lat.dims[0] = lat.dims[1] = lat.dims[2] = 20;
  lat.spacing = 0.05;
  lat.components = 6;
  lat.values.resize(6 * lat.num_nodes());
  for (size_t v = 0; v < lat.num_nodes(); ++v) {
    double m[6];
    test::random_spd(rng, 0.01, 1.0, m);
    ASSERT_TRUE(sym_log(m, &lat.values[6 * v]));
  }
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok());
  const size_t n = 20000;
  std::vector<double> pts(3 * n);
  for (size_t i = 0; i < n; ++i) random_point(rng, lat, 0.05, &pts[3 * i]);
  std::vector<double> serial(6 * n);
  for (size_t i = 0; i < n; ++i) f->metric(&pts[3 * i], &serial[6 * i]);
  std::vector<std::vector<double>> out(4, std::vector<double>(6 * n));
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      MetricField::Sampler s(f.value());
      s.metrics(pts.data(), n, out[t].data());  // batched (sorted) path
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) ASSERT_EQ(out[t], serial);
}

TEST(MetricField, SingleQueriesFollowTheFieldTheyAreAskedOf) {
  // metric() keeps a per-thread sampler for the last field: alternating fields, and a field
  // rebuilt (possibly at the same address) after the previous one died, must not mix them up.
  const double p[3] = {0.0, 1.0, 2.5};
  double m[6];
  for (int rep = 0; rep < 3; ++rep) {
    Result<MetricField> a = MetricField::from_lattice(size_lattice(4, 0.5, [](const double*) { return 0.5; }));
    Result<MetricField> b = MetricField::from_lattice(size_lattice(4, 0.5, [](const double*) { return 0.25; }));
    ASSERT_TRUE(a.ok() && b.ok());
    for (int k = 0; k < 3; ++k) {
      a->metric(p, m);
      EXPECT_EQ(m[0], 4.0);
      b->metric(p, m);
      EXPECT_EQ(m[0], 16.0);
    }
  }
  auto c = std::make_unique<MetricField>(
      std::move(MetricField::from_lattice(size_lattice(4, 0.5, [](const double*) { return 1.0; })).value()));
  c->metric(p, m);
  EXPECT_EQ(m[0], 1.0);
  c.reset();
  c = std::make_unique<MetricField>(
      std::move(MetricField::from_lattice(size_lattice(4, 0.5, [](const double*) { return 2.0; })).value()));
  c->metric(p, m);
  EXPECT_EQ(m[0], 0.25);
}

TEST(MetricField, EdgeLengthIntegratesAlongTheEdge) {
  // h = 1 + x along x: the exact normalized length of [0, L] is ln(1 + L).
  const Lattice lat = size_lattice(33, 0.125, [](const double* p) { return 2.0 + p[0]; });
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok());
  const double a[3] = {-1.0, 1.0, 3.0}, b[3] = {2.0, 1.0, 3.0}, c[3] = {-1.0, 1.0, 3.5};
  double len[2];
  const double as[6] = {a[0], a[1], a[2], a[0], a[1], a[2]};
  const double bs[6] = {b[0], b[1], b[2], c[0], c[1], c[2]};
  f->edge_lengths(as, bs, 2, len);
  EXPECT_NEAR(len[0], std::log(4.0), 4e-3);  // 3-point Gauss on 1/h, h 1..4: 0.19% off
  EXPECT_NEAR(len[1], 0.5, 1e-14);           // constant size along the edge: exact
  // The midpoint rule alone would give 3/2.5 = 1.2, 13% off ln 4.
  EXPECT_GT(std::fabs(1.2 - std::log(4.0)), 0.1);
}

TEST(MetricField, PruningMakesFarRegionsSparse) {
  // Size grows with x only beyond x = 2; near-constant leaves collapse to tiles.
  const Lattice lat = size_lattice(64, 0.1, [](const double* p) { return p[0] < 2.0 ? 1.0 : p[0] - 1.0; });
  Result<MetricField> dense = MetricField::from_lattice(lat);
  Result<MetricField> sparse = MetricField::from_lattice(lat, 1e-6);
  ASSERT_TRUE(dense.ok() && sparse.ok());
  EXPECT_LT(sparse->leaf_count(), dense->leaf_count());
  EXPECT_LT(sparse->memory_bytes(), dense->memory_bytes());
  EXPECT_EQ(sparse->active_voxels(), dense->active_voxels());
  std::mt19937_64 rng(10);
  for (int n = 0; n < 2000; ++n) {
    double p[3], m1[6], m2[6];
    random_point(rng, lat, 0.0, p);
    dense->metric(p, m1);
    sparse->metric(p, m2);
    ASSERT_NEAR(m1[0], m2[0], 1e-12 * m1[0]);
  }
}

TEST(MetricField, BatchedSizesOverTilesMatchSingleQueries) {
  // Leaves next to tiles: the batched path's direct leaf reads and its gather fallback.
  const Lattice lat = size_lattice(40, 0.1, [](const double* p) { return p[0] < 2.0 ? 1.0 : p[0] - 1.0; });
  Result<MetricField> sparse = MetricField::from_lattice(lat, 1e-6);
  Result<MetricField> dense = MetricField::from_lattice(lat);
  ASSERT_TRUE(sparse.ok() && dense.ok());
  std::mt19937_64 rng(12);
  const size_t n = 5000;
  std::vector<double> pts(3 * n), batched(6 * n), logs(6 * n);
  for (size_t i = 0; i < n; ++i) random_point(rng, lat, 0.1, &pts[3 * i]);
  MetricField::Sampler s(sparse.value());
  s.metrics(pts.data(), n, batched.data());
  s.log_metrics(pts.data(), n, logs.data());
  for (size_t i = 0; i < n; ++i) {
    double m[6];
    dense->metric(&pts[3 * i], m);
    for (int c = 0; c < 6; ++c) ASSERT_NEAR(batched[6 * i + c], m[c], 1e-12 * m[0]) << i;
    ASSERT_NEAR(logs[6 * i], std::log(m[0]), 1e-12);
  }
}

TEST(Gradation, BoundsIsotropicGrowthBetweenNeighbours) {
  // A small size at one node in a coarse field: after grading, h_b <= h_a hgrad^(dx / h_a) for
  // every pair of neighbours, in every direction.
  Lattice lat = size_lattice(24, 0.1, [](const double*) { return 2.0; });
  lat.values[lat.node(12, 5, 17)] = 0.01;
  lat.values[lat.node(2, 20, 3)] = 0.05;
  const std::vector<double> before = lat.values;
  const double hgrad = 1.3;
  Result<GradationStats> st = grade(lat, hgrad);
  ASSERT_TRUE(st.ok()) << st.status().message();
  EXPECT_TRUE(st->converged);
  EXPECT_GT(st->changed, 0u);
  size_t pairs = 0;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) {
        const size_t a = lat.node(i, j, k);
        ASSERT_LE(lat.values[a], before[a]);  // gradation only refines
        const int nb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const auto& d : nb) {
          const int x = i + d[0], y = j + d[1], z = k + d[2];
          if (x < 0 || y < 0 || z < 0 || x >= 24 || y >= 24 || z >= 24) continue;
          const double ha = lat.values[a], hb = lat.values[lat.node(x, y, z)];
          ASSERT_LE(hb, ha * std::pow(hgrad, 0.1 / ha) * (1 + 1e-9));
          ++pairs;
        }
      }
  EXPECT_EQ(pairs, size_t(6 * 24 * 24 * 23));
  // The small sizes themselves are untouched.
  EXPECT_EQ(lat.values[lat.node(12, 5, 17)], 0.01);
}

TEST(Gradation, BoundsTensorGrowthBetweenNeighbours) {
  std::mt19937_64 rng(11);
  Lattice lat;
  const int n = 8;
  lat.dims[0] = lat.dims[1] = lat.dims[2] = n;
  lat.spacing = 0.05;
  lat.components = 6;
  lat.values.resize(6 * lat.num_nodes());
  for (size_t v = 0; v < lat.num_nodes(); ++v) {
    double m[6];
    test::random_spd(rng, 0.02, 1.0, m);
    ASSERT_TRUE(sym_log(m, &lat.values[6 * v]));
  }
  const double hgrad = 1.5;
  Result<GradationStats> st = grade(lat, hgrad);
  ASSERT_TRUE(st.ok()) << st.status().message();
  EXPECT_TRUE(st->converged);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double ma[6];
        lat.node_metric(lat.node(i, j, k), ma);
        const int nb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const auto& d : nb) {
          const int x = i + d[0], y = j + d[1], z = k + d[2];
          if (x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n) continue;
          double mb[6], grown[6];
          lat.node_metric(lat.node(x, y, z), mb);
          const int axis = d[0] ? 0 : d[1] ? 1 : 2;
          const double diag = axis == 0 ? ma[0] : axis == 1 ? ma[2] : ma[5];
          scale(ma, std::pow(hgrad, -2.0 * lat.spacing * std::sqrt(diag)), grown);
          // M_b contains the grown M_a: M_b - grown is positive semi-definite.
          ASSERT_GT(test::min_eig_diff(mb, grown), -1e-8) << i << " " << j << " " << k;
        }
      }
}

TEST(Gradation, BoundSizes) {
  Lattice lat = size_lattice(4, 1.0, [](const double* p) { return std::fabs(p[0]) + 0.01; });
  ASSERT_TRUE(bound_sizes(lat, 0.1, 1.5).ok());
  for (double h : lat.values) {
    EXPECT_GE(h, 0.1);
    EXPECT_LE(h, 1.5);
  }
  EXPECT_FALSE(bound_sizes(lat, 2.0, 1.0).ok());
}

TEST(Gradation, FieldLevelBoundAndGrade) {
  Lattice lat = size_lattice(16, 0.1, [](const double*) { return 1.0; });
  lat.values[lat.node(8, 8, 8)] = 0.001;
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok());
  GradationStats gs;
  Result<MetricField> g = bound_and_grade(f.value(), 0.01, 0.5, 1.2, &gs);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_TRUE(gs.converged);
  double p[3];
  lat.position(8, 8, 8, p);
  double m[6];
  g->metric(p, m);
  EXPECT_NEAR(1.0 / std::sqrt(m[0]), 0.01, 1e-12);  // hmin
  lat.position(0, 0, 0, p);
  g->metric(p, m);
  EXPECT_LE(1.0 / std::sqrt(m[0]), 0.5 + 1e-12);  // hmax and gradation
}

std::string temp_path(const std::string& name) {
  return std::string(::testing::TempDir()) + "anitet_metric_" + name;
}

TEST(VdbIo, SizeGridRoundTrip) {
  const Lattice lat = size_lattice(20, 0.1, [](const double* p) { return 1.0 + p[0] * p[0]; });
  Result<MetricField> f = MetricField::from_lattice(lat, 1e-6);
  ASSERT_TRUE(f.ok());
  const std::string path = temp_path("size.vdb");
  ASSERT_TRUE(write_metric_vdb(f.value(), path, true).ok());
  Result<MetricField> g = read_metric_vdb(path);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ(g->kind(), MetricField::Kind::Isotropic);
  // OpenVDB stores the transform as a map: the voxel size comes back to rounding.
  EXPECT_NEAR(g->voxel_size(), f->voxel_size(), 1e-15);
  EXPECT_EQ(g->active_voxels(), f->active_voxels());
  Result<Lattice> back = g->to_lattice();
  ASSERT_TRUE(back.ok());
  ASSERT_EQ(back->values, f->to_lattice()->values);  // every voxel bit-exact in double precision
  std::mt19937_64 rng(12);
  for (int n = 0; n < 2000; ++n) {
    double p[3], a[6], b[6];
    random_point(rng, lat, 0.1, p);
    f->metric(p, a);
    g->metric(p, b);
    for (int c = 0; c < 6; ++c) ASSERT_NEAR(a[c], b[c], 1e-12 * a[0]);
  }
  // Float grids (the default, for viewers): single precision.
  ASSERT_TRUE(write_metric_vdb(f.value(), path).ok());
  g = read_metric_vdb(path);
  ASSERT_TRUE(g.ok()) << g.status().message();
  for (int n = 0; n < 2000; ++n) {
    double p[3], a[6], b[6];
    random_point(rng, lat, 0.1, p);
    f->metric(p, a);
    g->metric(p, b);
    ASSERT_NEAR(a[0], b[0], 1e-6 * a[0]);
  }
  std::remove(path.c_str());
}

TEST(VdbIo, LogMetricGridsRoundTrip) {
  std::mt19937_64 rng(13);
  Lattice lat;
  lat.dims[0] = 9;
  lat.dims[1] = 10;
  lat.dims[2] = 11;
  lat.spacing = 0.25;
  lat.origin[0] = 3.0;
  lat.components = 6;
  lat.values.resize(6 * lat.num_nodes());
  for (size_t v = 0; v < lat.num_nodes(); ++v) {
    double m[6];
    test::random_spd(rng, 0.01, 1.0, m);
    ASSERT_TRUE(sym_log(m, &lat.values[6 * v]));
  }
  Result<MetricField> f = MetricField::from_lattice(lat);
  ASSERT_TRUE(f.ok());
  const std::string path = temp_path("tensor.vdb");
  ASSERT_TRUE(write_metric_vdb(f.value(), path, true).ok());
  Result<MetricField> g = read_metric_vdb(path);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ(g->kind(), MetricField::Kind::Tensor);
  Result<Lattice> back = g->to_lattice();
  ASSERT_TRUE(back.ok());
  ASSERT_EQ(back->values.size(), lat.values.size());
  for (size_t i = 0; i < lat.values.size(); ++i) ASSERT_EQ(back->values[i], lat.values[i]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back->origin[k], lat.origin[k], 1e-12);
  std::remove(path.c_str());
}

TEST(VdbIo, Errors) {
  Result<MetricField> r = read_metric_vdb(temp_path("does-not-exist.vdb"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::FileNotFound);
  const std::string path = temp_path("garbage.vdb");
  {
    std::ofstream out(path);
    out << "this is not a vdb file\n";
  }
  r = read_metric_vdb(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::Parse);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace metric
}  // namespace anitet
