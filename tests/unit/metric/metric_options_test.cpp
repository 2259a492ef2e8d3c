// app/metric_options: the CLI options and the sizing field they build (compiled in directly).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/metric_options.hpp"
#include "io/volume_io.hpp"
#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"
#include "metric/sol_field.hpp"

namespace anitet::cli {
namespace {

// The cube [0, s]^3 with an n x n grid of squares (2 triangles each) per face, outward.
SurfaceMesh cube_surface(int n, double s) {
  SurfaceMesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const uint32_t base = uint32_t(m.num_vertices());
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          double p[3];
          p[axis] = side * s;
          p[u] = s * i / n;
          p[v] = s * j / n;
          m.add_vertex(p[0], p[1], p[2]);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const uint32_t a = base + uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1),
                         d = c + 1;
          if (side == 1) {
            m.add_triangle(a, b, d);
            m.add_triangle(a, d, c);
          } else {
            m.add_triangle(a, d, b);
            m.add_triangle(a, c, d);
          }
        }
    }
  return m;
}

// 6 Kuhn tets in the cube [0, s]^3 (positive orientation).
VolumeMesh one_cube_mesh(double s) {
  VolumeMesh m;
  for (int k = 0; k < 8; ++k) {
    m.xyz.push_back(s * (k & 1));
    m.xyz.push_back(s * ((k >> 1) & 1));
    m.xyz.push_back(s * ((k >> 2) & 1));
  }
  const uint32_t tets[6][4] = {{0, 1, 3, 7}, {0, 1, 7, 5}, {0, 2, 7, 3},
                               {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 7, 6}};
  for (const auto& t : tets) {
    m.tet.insert(m.tet.end(), t, t + 4);
    m.region.push_back(0);
  }
  return m;
}

std::string temp_path(const std::string& name) {
  return std::string(::testing::TempDir()) + "anitet_metric_options_" + name;
}

double size_at(const SizingField& f, double x, double y, double z) {
  const double p[3] = {x, y, z};
  double m[6];
  f.metric(p, m);
  return 1.0 / std::sqrt(m[0]);
}

bool parse(CLI::App& app, std::vector<std::string> args) {
  std::vector<const char*> argv = {"anitet"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return false;
  }
  return true;
}

TEST(MetricOptions, RegistersAndParsesEveryOption) {
  const std::string vdb = temp_path("parse.vdb");
  { std::FILE* f = std::fopen(vdb.c_str(), "w"); ASSERT_TRUE(f); std::fclose(f); }
  CLI::App app;
  MetricCliOptions o;
  add_metric_options(app, o);
  ASSERT_TRUE(parse(app, {"--metric", vdb, "--hmin", "0.1", "--hmax", "2", "--hgrad", "1.3",
                          "--geodetic", "--origin", "47.5,-87.5,183", "--geo-frame", "utm",
                          "--geodetic-output", "--write-metric", "out.sol", "--write-sizing",
                          "out.vdb"}));
  EXPECT_EQ(o.metric, vdb);
  EXPECT_EQ(o.hmin, 0.1);
  EXPECT_EQ(o.hmax, 2.0);
  EXPECT_EQ(o.hgrad, 1.3);
  EXPECT_TRUE(o.geodetic);
  EXPECT_EQ(o.origin, (std::vector<double>{47.5, -87.5, 183.0}));
  EXPECT_EQ(o.geo_frame, "utm");
  EXPECT_TRUE(o.geodetic_output);
  EXPECT_EQ(o.write_metric, "out.sol");
  EXPECT_EQ(o.write_sizing, "out.vdb");
  const std::string help = app.help();
  for (const char* name : {"--metric", "--background", "--hmin", "--hmax", "--hgrad", "--geodetic",
                           "--origin", "--write-metric", "--write-sizing"})
    EXPECT_NE(help.find(name), std::string::npos) << name;
  CLI::App south;  // a negative latitude is a value, not an option
  MetricCliOptions o3;
  add_metric_options(south, o3);
  ASSERT_TRUE(parse(south, {"--geodetic", "--origin", "-33.9,151.2,0"}));
  EXPECT_EQ(o3.origin, (std::vector<double>{-33.9, 151.2, 0.0}));
  CLI::App bad;
  MetricCliOptions o2;
  add_metric_options(bad, o2);
  EXPECT_FALSE(parse(bad, {"--geo-frame", "lambert"}));
  EXPECT_FALSE(parse(bad, {"--hmin", "-1"}));
  EXPECT_FALSE(parse(bad, {"--metric", temp_path("missing.vdb")}));
}

TEST(MetricOptions, DefaultIsTheSurfaceSizingGridWithBounds) {
  const SurfaceMesh cube = cube_surface(8, 1.0);  // edges 0.125 .. 0.177
  MetricCliOptions o;
  Result<std::unique_ptr<SizingField>> f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  const double h = size_at(*f.value(), 0.5, 0.5, 0.5);
  EXPECT_GT(h, 0.1);
  EXPECT_LT(h, 0.2);
  EXPECT_FALSE(wants_sizing_field(o));
  // The mesher's default sizing options are passed through (mean edge instead of shortest).
  metric::SurfaceSizingOptions mean;
  mean.triangle_size = metric::TriangleSize::Mean;
  Result<std::unique_ptr<SizingField>> fm = build_sizing_field(o, cube, nullptr, mean);
  ASSERT_TRUE(fm.ok()) << fm.status().message();
  EXPECT_GT(size_at(*fm.value(), 0.5, 0.5, 0.0), size_at(*f.value(), 0.5, 0.5, 0.0) * 1.05);
  o.hmax = 0.05;
  EXPECT_TRUE(wants_sizing_field(o));
  f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  for (double x : {0.0, 0.3, 0.5, 1.0}) EXPECT_NEAR(size_at(*f.value(), x, 0.5, 0.5), 0.05, 1e-12);
  o.hmax = 0.0;
  o.hmin = 0.5;
  o.hgrad = 1.5;
  f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_GE(size_at(*f.value(), 0.5, 0.5, 0.5), 0.5 - 1e-12);
}

TEST(MetricOptions, VdbFieldIsReadAndBounded) {
  metric::Lattice lat;
  lat.spacing = 0.25;
  lat.dims[0] = lat.dims[1] = lat.dims[2] = 6;
  lat.values.assign(lat.num_nodes(), 0.3);
  Result<metric::MetricField> grid = metric::MetricField::from_lattice(lat);
  ASSERT_TRUE(grid.ok());
  const std::string path = temp_path("size.vdb");
  ASSERT_TRUE(metric::write_metric_vdb(grid.value(), path, true).ok());
  MetricCliOptions o;
  o.metric = path;
  const SurfaceMesh cube = cube_surface(2, 1.0);
  Result<std::unique_ptr<SizingField>> f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.4, 0.6, 0.7), 0.3, 1e-12);
  o.hmin = 0.5;
  f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.4, 0.6, 0.7), 0.5, 1e-12);
  o.background = path;
  EXPECT_EQ(build_sizing_field(o, cube).status().code(), Error::InvalidArgument);
}

TEST(MetricOptions, SolOnBackgroundMeshBoundedAndGraded) {
  VolumeMesh bg = one_cube_mesh(1.0);
  for (size_t v = 0; v < bg.num_vertices(); ++v) bg.vertex_metric.push_back(0.1 + 0.2 * bg.xyz[3 * v]);
  const std::string sol = temp_path("bg.sol"), mesh = temp_path("bg.mesh");
  ASSERT_TRUE(write_sol(bg, sol).ok());
  bg.vertex_metric.clear();
  ASSERT_TRUE(write_volume_mesh(bg, mesh).ok());
  const SurfaceMesh cube = cube_surface(4, 1.0);
  MetricCliOptions o;
  o.metric = sol;
  EXPECT_EQ(build_sizing_field(o, cube).status().code(), Error::InvalidArgument);  // no mesh
  o.background = mesh;
  Result<std::unique_ptr<SizingField>> f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.5, 0.2, 0.9), 0.2, 1e-12);  // linear: exact
  o.hmax = 0.15;
  f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.5, 0.2, 0.9), 0.15, 1e-12);
  EXPECT_NEAR(size_at(*f.value(), 0.1, 0.2, 0.9), 0.12, 1e-12);
  o.hmax = 0.0;
  o.hgrad = 1.1;  // sampled on a lattice, then graded: the coarse side shrinks
  f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_NEAR(size_at(*f.value(), 0.0, 0.5, 0.5), 0.1, 1e-9);
  EXPECT_LT(size_at(*f.value(), 1.0, 0.5, 0.5), 0.29);
  o.metric = temp_path("field.txt");
  EXPECT_EQ(build_sizing_field(o, cube).status().code(), Error::UnsupportedFormat);
}

TEST(MetricOptions, WritesTheFieldAtTheVerticesAndAsGrids) {
  const SurfaceMesh cube = cube_surface(4, 1.0);
  MetricCliOptions o;
  o.hmax = 0.2;
  Result<std::unique_ptr<SizingField>> f = build_sizing_field(o, cube);
  ASSERT_TRUE(f.ok()) << f.status().message();
  VolumeMesh mesh = one_cube_mesh(1.0);
  o.write_metric = temp_path("out.sol");
  o.write_sizing = temp_path("out.vdb");
  ASSERT_TRUE(write_metric_outputs(o, *f.value(), cube, mesh).ok());
  Result<metric::SolField> sol = metric::read_sol(o.write_metric);
  ASSERT_TRUE(sol.ok()) << sol.status().message();
  ASSERT_EQ(sol->components, 1);  // isotropic: sizes
  ASSERT_EQ(sol->num_vertices(), mesh.num_vertices());
  for (size_t v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_NEAR(sol->values[v], size_at(*f.value(), mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2]), 1e-9);
  Result<metric::MetricField> grid = metric::read_metric_vdb(o.write_sizing);
  ASSERT_TRUE(grid.ok()) << grid.status().message();
  EXPECT_EQ(grid->kind(), metric::MetricField::Kind::Isotropic);
  EXPECT_NEAR(size_at(grid.value(), 0.5, 0.5, 0.5), size_at(*f.value(), 0.5, 0.5, 0.5), 1e-6);
}

TEST(MetricOptions, GeodeticRoundTripThroughTheCommandSteps) {
  SurfaceMesh s = cube_surface(2, 0.01);  // 0.01 degrees ~ 1.1 km
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    s.xyz[3 * v] += -87.5;
    s.xyz[3 * v + 1] += 47.5;
    s.xyz[3 * v + 2] *= 1e5;  // heights 0 .. 1000 m
  }
  const SurfaceMesh original = s;
  MetricCliOptions o;
  Result<std::optional<geo::GeoFrame>> none = prepare_geodetic(o, s);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none.value().has_value());
  o.geodetic = true;
  o.geodetic_output = true;
  Result<std::optional<geo::GeoFrame>> frame = prepare_geodetic(o, s);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  ASSERT_TRUE(frame.value().has_value());
  double extent = 0.0;
  for (size_t v = 0; v < s.num_vertices(); ++v) extent = std::max(extent, std::fabs(s.xyz[3 * v]));
  EXPECT_GT(extent, 300.0);  // metres east of the centre
  EXPECT_LT(extent, 500.0);
  VolumeMesh mesh;
  mesh.xyz = s.xyz;
  ASSERT_TRUE(restore_geodetic(o, frame.value(), mesh).ok());
  for (size_t i = 0; i < mesh.xyz.size(); ++i)
    EXPECT_NEAR(mesh.xyz[i], original.xyz[i], i % 3 == 2 ? 1e-6 : 1e-9);
  o.origin = {1.0, 2.0};
  EXPECT_EQ(prepare_geodetic(o, s).status().code(), Error::InvalidArgument);
}

}  // namespace
}  // namespace anitet::cli
