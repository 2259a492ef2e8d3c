#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "io/volume_io.hpp"
#include "metric/sol_field.hpp"
#include "metric/spd.hpp"
#include "test_util.hpp"

namespace anitet {
namespace metric {
namespace {

std::string temp_path(const std::string& name) {
  return std::string(::testing::TempDir()) + "anitet_metric_" + name;
}

TEST(Sol, ParsesScalarAndTensorFields) {
  Result<SolField> s = parse_sol(
      "MeshVersionFormatted 2\n# comment\nDimension 3\nSolAtVertices\n2\n1 1\n0.5\n0.25\nEnd\n", "a.sol");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->components, 1);
  ASSERT_EQ(s->values.size(), 2u);
  EXPECT_EQ(s->values[1], 0.25);
  s = parse_sol("MeshVersionFormatted 1 Dimension 3 SolAtVertices 1 1 3 1 0 2 0 0 3 End", "b.sol");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->components, 6);
  EXPECT_EQ(s->values[5], 3.0);
  // 2D (the 2D mesher's): tensors xx xy yy.
  s = parse_sol("MeshVersionFormatted 2 Dimension 2 SolAtVertices 1 1 3 1 0.5 2 End", "c.sol");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->dimension, 2);
  EXPECT_EQ(s->components, 3);
  EXPECT_EQ(s->values[2], 2.0);
}

TEST(Sol, ReportsBadInput) {
  EXPECT_EQ(parse_sol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n3\n1 1\n0.5\n", "t.sol")
                .status().code(), Error::Parse);  // truncated
  EXPECT_EQ(parse_sol("SolAtVertices\n1\n1 1\nabc\n", "t.sol").status().code(), Error::Parse);
  EXPECT_EQ(parse_sol("SolAtVertices\n1\n1 2\n1 2 3\n", "t.sol").status().code(),
            Error::UnsupportedFormat);  // vector field
  EXPECT_EQ(parse_sol("Dimension 4\n", "t.sol").status().code(), Error::UnsupportedFormat);
  EXPECT_EQ(parse_sol("MeshVersionFormatted 2\nEnd\n", "t.sol").status().code(), Error::EmptyInput);
  EXPECT_EQ(read_sol(temp_path("missing.sol")).status().code(), Error::FileNotFound);
}

TEST(Sol, ScalarRoundTripAndLinearInterpolation) {
  VolumeMesh mesh = test::cube_mesh(4);
  auto h = [](const double* p) { return 0.5 + 0.1 * p[0] + 0.05 * p[1] - 0.02 * p[2]; };
  for (size_t v = 0; v < mesh.num_vertices(); ++v) mesh.vertex_metric.push_back(h(mesh.point(v)));
  const std::string path = temp_path("scalar.sol");
  ASSERT_TRUE(write_sol(mesh, path).ok());
  Result<SolField> sol = read_sol(path);
  ASSERT_TRUE(sol.ok()) << sol.status().message();
  ASSERT_EQ(sol->values, mesh.vertex_metric);  // bit-exact through the text
  Result<BackgroundMeshField> f = BackgroundMeshField::create(mesh, sol.value());
  ASSERT_TRUE(f.ok()) << f.status().message();
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    double m[6];
    f->metric(mesh.point(v), m);
    ASSERT_NEAR(1.0 / std::sqrt(m[0]), mesh.vertex_metric[v], 1e-14);
  }
  std::mt19937_64 rng(20);
  std::uniform_real_distribution<double> u(0.0, 4.0);
  for (int n = 0; n < 5000; ++n) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    double m[6];
    f->metric(p, m);
    ASSERT_NEAR(1.0 / std::sqrt(m[0]), h(p), 1e-13);
  }
  // Outside the mesh: the nearest tet's clamped value, still a valid size.
  const double far[3] = {10.0, -3.0, 2.0};
  double m[6];
  f->metric(far, m);
  EXPECT_TRUE(is_spd(m));
  std::remove(path.c_str());
}

TEST(Sol, TensorRoundTrip) {
  VolumeMesh mesh = test::cube_mesh(3);
  std::mt19937_64 rng(21);
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    double m[6];
    test::random_spd(rng, 0.01, 1.0, m);
    mesh.vertex_metric.insert(mesh.vertex_metric.end(), m, m + 6);
  }
  const std::string path = temp_path("tensor.sol");
  ASSERT_TRUE(write_sol(mesh, path).ok());
  Result<SolField> sol = read_sol(path);
  ASSERT_TRUE(sol.ok()) << sol.status().message();
  EXPECT_EQ(sol->components, 6);
  ASSERT_EQ(sol->values, mesh.vertex_metric);
  Result<BackgroundMeshField> f = BackgroundMeshField::create(mesh, sol.value());
  ASSERT_TRUE(f.ok()) << f.status().message();
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    double m[6];
    f->metric(mesh.point(v), m);
    ASSERT_LT(test::max_rel_diff(m, &mesh.vertex_metric[6 * v]), 1e-11) << v;
  }
  // Between vertices: SPD.
  std::uniform_real_distribution<double> u(0.0, 3.0);
  for (int n = 0; n < 2000; ++n) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    double m[6];
    f->metric(p, m);
    ASSERT_TRUE(is_spd(m));
  }
  std::remove(path.c_str());
}

TEST(Sol, SampledFieldRoundTrips) {
  // A MetricField-like analytic field sampled at the vertices, written, read back and
  // interpolated at the vertices again.
  VolumeMesh mesh = test::cube_mesh(2);
  struct Stretched final : SizingField {
    void metric(const double p[3], double m[6]) const override {
      const double hx = 0.1 + 0.05 * p[0], hy = 0.2, hz = 0.3 + 0.01 * p[2];
      m[0] = 1 / (hx * hx);
      m[2] = 1 / (hy * hy);
      m[5] = 1 / (hz * hz);
      m[1] = 0.1 * m[0];
      m[3] = 0.0;
      m[4] = 0.0;
    }
  } field;
  sample_at_vertices(field, mesh);
  ASSERT_EQ(mesh.vertex_metric.size(), 6 * mesh.num_vertices());
  const std::string path = temp_path("sampled.sol");
  ASSERT_TRUE(write_sol(mesh, path).ok());
  Result<SolField> sol = read_sol(path);
  ASSERT_TRUE(sol.ok()) << sol.status().message();
  Result<BackgroundMeshField> f = BackgroundMeshField::create(mesh, sol.value());
  ASSERT_TRUE(f.ok()) << f.status().message();
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    double m[6], want[6];
    f->metric(mesh.point(v), m);
    field.metric(mesh.point(v), want);
    ASSERT_LT(test::max_rel_diff(m, want), 1e-11);
  }
  std::remove(path.c_str());
}

TEST(Sol, RejectsMismatchedField) {
  VolumeMesh mesh = test::cube_mesh(1);
  SolField s;
  s.components = 1;
  s.values.assign(3, 1.0);
  EXPECT_EQ(BackgroundMeshField::create(mesh, s).status().code(), Error::InvalidArgument);
  s.values.assign(mesh.num_vertices(), -1.0);
  EXPECT_EQ(BackgroundMeshField::create(mesh, s).status().code(), Error::InvalidArgument);
}

}  // namespace
}  // namespace metric
}  // namespace anitet
