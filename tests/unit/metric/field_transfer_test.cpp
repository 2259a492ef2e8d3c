// Field transfer (issue 46): linear fields carried exactly, smooth ones with an h^2 error,
// metrics in log space, points outside the old mesh, non-convex meshes, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <tbb/task_arena.h>

#include "metric/field_transfer.hpp"
#include "metric/spd.hpp"
#include "metric/tet_locator.hpp"
#include "test_util.hpp"

namespace anitet {
namespace metric {
namespace {

double signed_volume(const VolumeMesh& m, size_t t) {
  const double* a = m.point(m.tet[4 * t]);
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) e[i][k] = m.point(m.tet[4 * t + size_t(i) + 1])[k] - a[k];
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

// The Kuhn cube mesh of [0, 1]^3 with n cells a side, its interior vertices moved at random by up
// to `jitter` cells (every tet stays positive).
VolumeMesh unit_cube(int n, double jitter, unsigned seed) {
  VolumeMesh m = test::cube_mesh(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    bool interior = true;
    for (int k = 0; k < 3; ++k) interior = interior && m.xyz[3 * v + size_t(k)] > 0 && m.xyz[3 * v + size_t(k)] < n;
    for (int k = 0; k < 3; ++k) m.xyz[3 * v + size_t(k)] = (m.xyz[3 * v + size_t(k)] + (interior ? u(rng) : 0.0)) / n;
  }
  for (size_t t = 0; t < m.num_tets(); ++t) EXPECT_GT(signed_volume(m, t), 0.0) << t;
  return m;
}

std::vector<double> random_points(size_t n, double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> xyz(3 * n);
  for (double& x : xyz) x = u(rng);
  return xyz;
}

// One scalar, one vector and one tensor field, each given by f(p, out).
template <class F>
VertexFields sample(const VolumeMesh& m, const std::vector<FieldKind>& kinds, F&& f) {
  VertexFields out;
  out.kinds = kinds;
  out.values.resize(m.num_vertices() * out.record_size());
  for (size_t v = 0; v < m.num_vertices(); ++v) f(m.point(v), &out.values[out.record_size() * v]);
  return out;
}

double linear(const double* p) { return 1 + 2 * p[0] - 3 * p[1] + 0.5 * p[2]; }
void linear_scalar(const double* p, double* out) { out[0] = linear(p); }
// A scalar, (x + y, 2z - 1, 3x) and a tensor linear in p.
void linear_fields(const double* p, double* out) {
  out[0] = linear(p);
  out[1] = p[0] + p[1];
  out[2] = 2 * p[2] - 1;
  out[3] = 3 * p[0];
  for (int c = 0; c < 6; ++c) out[4 + c] = 0.5 * c - p[0] + (c + 1) * p[1] - 0.25 * p[2];
}
const std::vector<FieldKind> kLinearKinds = {FieldKind::Scalar, FieldKind::Vector, FieldKind::SymTensor};

TEST(FieldTransfer, LinearFieldsAreCarriedExactly) {
  const VolumeMesh old_mesh = unit_cube(5, 0.25, 1);
  const VertexFields fields = sample(old_mesh, kLinearKinds, linear_fields);
  // Random points, the old vertices themselves, and points on the cube's faces.
  std::vector<double> xyz = random_points(3000, 0.0, 1.0, 2);
  xyz.insert(xyz.end(), old_mesh.xyz.begin(), old_mesh.xyz.end());
  for (double s : {0.0, 1.0}) xyz.insert(xyz.end(), {s, 0.3, 0.7, 0.2, s, 0.9, 0.5, 0.5, s});
  TransferReport report;
  Result<VertexFields> moved = transfer_fields(old_mesh, fields, xyz, TensorInterpolation::Linear, &report);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_EQ(report.outside, 0u);
  EXPECT_EQ(moved->kinds, fields.kinds);
  ASSERT_EQ(moved->num_vertices(), xyz.size() / 3);
  double worst = 0.0;
  for (size_t i = 0; i < xyz.size() / 3; ++i) {
    double want[10];
    linear_fields(&xyz[3 * i], want);
    for (int c = 0; c < 10; ++c) worst = std::max(worst, std::abs(moved->values[10 * i + size_t(c)] - want[c]));
  }
  EXPECT_LT(worst, 1e-13);
}

// The interpolation error of a smooth field on three meshes h, h/2, h/4: order 2.
TEST(FieldTransfer, SmoothFieldErrorFallsAsHSquared) {
  auto f = [](const double* p, double* out) { out[0] = std::sin(2 * p[0]) * std::cos(3 * p[1]) * std::exp(p[2]); };
  const std::vector<double> xyz = random_points(20000, 0.0, 1.0, 3);
  double rms[3], worst[3];
  const int sizes[3] = {4, 8, 16};
  for (int level = 0; level < 3; ++level) {
    const VolumeMesh m = unit_cube(sizes[level], 0.15, 10 + unsigned(level));
    Result<VertexFields> moved = transfer_fields(m, sample(m, {FieldKind::Scalar}, f), xyz);
    ASSERT_TRUE(moved.ok()) << moved.status().message();
    double sum = 0.0;
    worst[level] = 0.0;
    for (size_t i = 0; i < xyz.size() / 3; ++i) {
      double want;
      f(&xyz[3 * i], &want);
      const double e = moved->values[i] - want;
      sum += e * e;
      worst[level] = std::max(worst[level], std::abs(e));
    }
    rms[level] = std::sqrt(sum / double(xyz.size() / 3));
  }
  for (int level = 0; level < 2; ++level) {
    const double order = std::log2(rms[level] / rms[level + 1]);
    const double order_max = std::log2(worst[level] / worst[level + 1]);
    std::printf("h = 1/%d -> 1/%d: RMS error %.3e -> %.3e (order %.2f), max %.3e -> %.3e (order %.2f)\n",
                sizes[level], sizes[level + 1], rms[level], rms[level + 1], order, worst[level],
                worst[level + 1], order_max);
    EXPECT_GT(order, 1.85);
    EXPECT_LT(order, 2.15);
  }
}

TEST(FieldTransfer, MetricsAreInterpolatedInLogSpace) {
  const VolumeMesh old_mesh = unit_cube(4, 0.2, 4);
  std::mt19937_64 rng(5);
  VertexFields metrics;
  metrics.kinds = {FieldKind::SymTensor};
  for (size_t v = 0; v < old_mesh.num_vertices(); ++v) {
    double m[6];
    test::random_spd(rng, 0.001, 1.0, m);
    metrics.values.insert(metrics.values.end(), m, m + 6);
  }
  const std::vector<double> xyz = random_points(5000, -0.1, 1.1, 6);  // some outside
  TransferReport report;
  Result<VertexFields> moved = transfer_fields(old_mesh, metrics, xyz, TensorInterpolation::LogEuclidean, &report);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  ASSERT_EQ(report.log_euclidean, std::vector<bool>{true});
  EXPECT_GT(report.outside, 0u);
  for (size_t i = 0; i < xyz.size() / 3; ++i) ASSERT_TRUE(is_spd(&moved->values[6 * i])) << i;
  // At an edge's midpoint: the geometric mean of the two ends' metrics (a I and b I).
  VertexFields iso = sample(old_mesh, {FieldKind::SymTensor}, [](const double* p, double* m) {
    const double s = std::exp(4.0 * p[0]);
    const double v[6] = {s, 0, s, 0, 0, s};
    std::copy(v, v + 6, m);
  });
  const uint32_t a = old_mesh.tet[0], b = old_mesh.tet[1];
  const std::vector<double> mid = {0.5 * (old_mesh.point(a)[0] + old_mesh.point(b)[0]),
                                   0.5 * (old_mesh.point(a)[1] + old_mesh.point(b)[1]),
                                   0.5 * (old_mesh.point(a)[2] + old_mesh.point(b)[2])};
  Result<VertexFields> at_mid = transfer_fields(old_mesh, iso, mid);
  ASSERT_TRUE(at_mid.ok());
  const double want = std::sqrt(iso.values[6 * a] * iso.values[6 * b]);
  EXPECT_NEAR(at_mid->values[0], want, 1e-12 * want);
  // A constant metric stays itself everywhere, outside points included.
  const double c[6] = {4.0, 1.0, 9.0, 0.5, -2.0, 25.0};
  VertexFields constant = sample(old_mesh, {FieldKind::SymTensor}, [&](const double*, double* m) { std::copy(c, c + 6, m); });
  moved = transfer_fields(old_mesh, constant, xyz);
  ASSERT_TRUE(moved.ok());
  for (size_t i = 0; i < xyz.size() / 3; ++i) ASSERT_LT(test::max_rel_diff(&moved->values[6 * i], c), 1e-13) << i;
}

TEST(FieldTransfer, TensorsThatAreNotSpdAreLinearOrRefused) {
  const VolumeMesh old_mesh = unit_cube(2, 0.0, 7);
  VertexFields stress = sample(old_mesh, {FieldKind::SymTensor}, [](const double* p, double* m) {
    const double v[6] = {p[0] - 0.5, 1, 2, 0, 0, -1};
    std::copy(v, v + 6, m);
  });
  TransferReport report;
  const std::vector<double> xyz = {0.25, 0.5, 0.75};
  Result<VertexFields> moved = transfer_fields(old_mesh, stress, xyz, TensorInterpolation::Auto, &report);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_EQ(report.log_euclidean, std::vector<bool>{false});
  EXPECT_NEAR(moved->values[0], -0.25, 1e-15);
  Result<VertexFields> refused = transfer_fields(old_mesh, stress, xyz, TensorInterpolation::LogEuclidean);
  EXPECT_EQ(refused.status().code(), Error::InvalidArgument);
  EXPECT_NE(refused.status().message().find("the tensor of vertex 1 "), std::string::npos) << refused.status().message();
  // A field of another mesh, points that are not finite.
  VertexFields wrong = VertexFields::single(FieldKind::Scalar, {1.0, 2.0});
  EXPECT_EQ(transfer_fields(old_mesh, wrong, xyz).status().code(), Error::InvalidArgument);
  const std::vector<double> nan_point = {0.5, std::nan(""), 0.5};
  EXPECT_EQ(transfer_fields(old_mesh, sample(old_mesh, {FieldKind::Scalar}, linear_scalar), nan_point).status().code(),
            Error::InvalidArgument);
}

// Points off the mesh take the value at the closest boundary point and are counted.
TEST(FieldTransfer, PointsOutsideTakeTheClosestBoundaryValue) {
  const VolumeMesh old_mesh = unit_cube(3, 0.2, 8);
  const VertexFields fields = sample(old_mesh, {FieldKind::Scalar}, linear_scalar);
  std::vector<double> xyz = {1.2, 0.5, 0.5, 0.3, -0.05, 0.6, 0.5, 0.5, 1.0 + 1e-6, -1, -2, -3, 0.5, 0.5, 0.5};
  TransferReport report;
  Result<VertexFields> moved = transfer_fields(old_mesh, fields, xyz, TensorInterpolation::Auto, &report);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_EQ(report.outside, 4u);
  EXPECT_NEAR(report.max_outside_distance, std::sqrt(1 + 4 + 9.0), 1e-12);
  for (size_t i = 0; i < xyz.size() / 3; ++i) {
    double q[3];
    for (int k = 0; k < 3; ++k) q[k] = std::min(1.0, std::max(0.0, xyz[3 * i + size_t(k)]));
    EXPECT_NEAR(moved->values[i], linear(q), 1e-13) << i;
  }
}

// An L-shaped mesh: walks that leave it through the notch still find the points beyond.
TEST(FieldTransfer, NonConvexMeshes) {
  VolumeMesh cube = test::cube_mesh(4);
  VolumeMesh l_shape;
  l_shape.xyz = cube.xyz;
  for (size_t t = 0; t < cube.num_tets(); ++t) {
    double c[2] = {0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 2; ++k) c[k] += 0.25 * cube.point(cube.tet[4 * t + size_t(i)])[k];
    if (c[0] > 2 && c[1] > 2) continue;
    l_shape.tet.insert(l_shape.tet.end(), &cube.tet[4 * t], &cube.tet[4 * t] + 4);
  }
  Result<TetLocator> locator = TetLocator::create(l_shape);
  ASSERT_TRUE(locator.ok()) << locator.status().message();
  const VertexFields fields = sample(l_shape, {FieldKind::Scalar}, linear_scalar);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 4.0);
  std::vector<double> inside, notch;
  while (inside.size() < 3 * 2000 || notch.size() < 3 * 200) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    std::vector<double>& to = p[0] > 2 && p[1] > 2 ? notch : inside;
    to.insert(to.end(), p, p + 3);
  }
  Result<PointLocations> where = locate_points(locator.value(), inside.data(), inside.size() / 3);
  ASSERT_TRUE(where.ok());
  EXPECT_EQ(where->outside, 0u);
  Result<VertexFields> moved = interpolate_fields(locator.value(), fields, where.value());
  ASSERT_TRUE(moved.ok());
  for (size_t i = 0; i < inside.size() / 3; ++i) {
    ASSERT_NEAR(moved->values[i], linear(&inside[3 * i]), 1e-12) << i;
  }
  // In the notch: outside, at the distance of the nearer of its two walls.
  where = locate_points(locator.value(), notch.data(), notch.size() / 3);
  ASSERT_TRUE(where.ok());
  EXPECT_EQ(where->outside, notch.size() / 3);
  for (size_t i = 0; i < notch.size() / 3; ++i) {
    const TetLocator::Location loc = locator->locate(&notch[3 * i]);
    EXPECT_TRUE(loc.outside);
    EXPECT_NEAR(loc.distance, std::min(notch[3 * i] - 2, notch[3 * i + 1] - 2), 1e-12);
  }
}

TEST(FieldTransfer, SameResultOnOneThreadAndOnAll) {
  const VolumeMesh old_mesh = unit_cube(8, 0.25, 11);
  const VertexFields fields = sample(old_mesh, kLinearKinds, linear_fields);
  const std::vector<double> xyz = random_points(50000, -0.05, 1.05, 12);
  Result<VertexFields> one = Status(Error::Internal, "not run");
  tbb::task_arena single(1);
  single.execute([&] { one = transfer_fields(old_mesh, fields, xyz); });
  Result<VertexFields> all = transfer_fields(old_mesh, fields, xyz);
  ASSERT_TRUE(one.ok() && all.ok());
  EXPECT_TRUE(std::memcmp(one->values.data(), all->values.data(), one->values.size() * sizeof(double)) == 0);
}

}  // namespace
}  // namespace metric
}  // namespace anitet
