#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <nlohmann/json.hpp>

#include "predicates/predicates.hpp"
#include "quality/quality_report.hpp"
#include "quality/report_detail.hpp"
#include "test_meshes.hpp"

namespace anitet {
namespace {

QualityReport report_of(const VolumeMesh& m, const SurfaceMesh* s, bool parallel = true) {
  QualityOptions o;
  o.parallel = parallel;
  Result<QualityReport> r = compute_quality_report(m, s, o);
  EXPECT_TRUE(r.ok()) << r.status().message();
  return r.ok() ? r.value() : QualityReport{};
}

TEST(QualityReport, CubeWithItsSurfaceIsBoundaryConstrained) {
  const VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  ASSERT_EQ(surface.num_triangles(), 12u);
  const QualityReport r = report_of(cube, &surface);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(r.tets, 6u);
  EXPECT_EQ(r.unused_vertices, 0u);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.nonpositive_tets, 0u);
  EXPECT_EQ(r.faces_shared_by_more_than_two, 0u);
  EXPECT_EQ(r.boundary_faces, 12u);
  EXPECT_NEAR(r.volume, 1.0, 1e-15);
  // Six congruent Kuhn tets: (0,0,0) (1,0,0) (1,1,0) (1,1,1), V = 1/6, sum l^2 = 1+2+3+1+2+1 = 10.
  EXPECT_NEAR(r.mean_ratio.mean, 12.0 * std::cbrt(0.25) / 10.0, 1e-14);
  EXPECT_NEAR(r.mean_ratio.min, r.mean_ratio.max, 1e-14);
  EXPECT_NEAR(r.min_dihedral_deg, 45.0, 1e-12);
  EXPECT_NEAR(r.max_dihedral_deg, 90.0, 1e-12);
  const SurfaceMatchReport& s = r.surface;
  EXPECT_TRUE(s.present);
  EXPECT_EQ(s.matched_exact, 8u);
  EXPECT_EQ(s.matched_tolerance, 0u);
  EXPECT_EQ(s.input_triangles, 12u);
  EXPECT_EQ(s.input_triangles_missing, 0u);
  EXPECT_EQ(s.boundary_faces_not_in_input, 0u);
  EXPECT_EQ(s.steiner_points_on_boundary, 0u);
  EXPECT_EQ(s.vertices_on_input_surface, 0u);
  EXPECT_NEAR(s.surface_volume, 1.0, 1e-15);
  EXPECT_LT(s.volume_rel_error, 1e-14);
  EXPECT_TRUE(s.boundary_constrained);
  EXPECT_EQ(s.touching_surface.tets, 6u);
  EXPECT_EQ(s.interior.tets, 0u);
}

TEST(QualityReport, FlippedDiagonalMeansMissingAndExtraFaces) {
  const VolumeMesh cube = test::kuhn_grid(1);
  SurfaceMesh surface = test::boundary_surface(cube);
  // Re-cut the bottom face (z = 0) along its other diagonal in the input surface.
  SurfaceMesh other;
  other.xyz = surface.xyz;
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    const uint32_t* v = &surface.tri[3 * t];
    if (surface.point(v[0])[2] == 0 && surface.point(v[1])[2] == 0 && surface.point(v[2])[2] == 0) continue;
    other.add_triangle(v[0], v[1], v[2]);
  }
  ASSERT_EQ(other.num_triangles(), 10u);
  // Vertex ids x + 2y + 4z: the bottom corners are 0 1 2 3; the Kuhn cut uses diagonal 0-3.
  other.add_triangle(0, 2, 1);  // outward normal -z
  other.add_triangle(1, 2, 3);
  const QualityReport r = report_of(cube, &other);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.surface.input_triangles_missing, 2u);
  EXPECT_EQ(r.surface.missing_triangle_examples.size(), 2u);
  EXPECT_EQ(r.surface.boundary_faces_not_in_input, 2u);
  EXPECT_EQ(r.surface.steiner_points_on_boundary, 0u);
  EXPECT_FALSE(r.surface.boundary_constrained);
}

TEST(QualityReport, PointInsertedInAFaceIsASteinerPointOnTheSurface) {
  VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  // Find the tet with boundary face (0, 1, 3) (bottom, z = 0) and split it at the face's
  // centroid (1/3 and 2/3 are inexact, but z = 0 is: the point lies exactly on the face).
  size_t host = cube.num_tets();
  int apex = -1;
  for (size_t t = 0; t < cube.num_tets(); ++t) {
    int found = 0, other = -1;
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = cube.tet[4 * t + i];
      if (v == 0 || v == 1 || v == 3) ++found; else other = i;
    }
    if (found == 3) {
      host = t;
      apex = other;
    }
  }
  ASSERT_LT(host, cube.num_tets());
  const double p[3] = {(0.0 + 1.0 + 1.0) / 3.0, (0.0 + 0.0 + 1.0) / 3.0, 0.0};
  const uint32_t pid = uint32_t(cube.num_vertices());
  cube.xyz.insert(cube.xyz.end(), p, p + 3);
  const std::array<uint32_t, 4> old{cube.tet[4 * host], cube.tet[4 * host + 1], cube.tet[4 * host + 2],
                                    cube.tet[4 * host + 3]};
  bool first = true;
  for (int i = 0; i < 4; ++i) {
    if (i == apex) continue;
    std::array<uint32_t, 4> t = old;
    t[size_t(i)] = pid;  // replacing a base vertex by p keeps the orientation
    if (first) std::copy(t.begin(), t.end(), cube.tet.begin() + 4 * long(host));
    else cube.tet.insert(cube.tet.end(), t.begin(), t.end());
    first = false;
  }
  ASSERT_EQ(cube.num_tets(), 8u);
  const QualityReport r = report_of(cube, &surface);
  EXPECT_TRUE(r.valid) << quality_report_text(r);
  EXPECT_EQ(r.boundary_faces, 14u);
  EXPECT_EQ(r.surface.input_triangles_missing, 1u);
  EXPECT_EQ(r.surface.boundary_faces_not_in_input, 3u);
  EXPECT_EQ(r.surface.steiner_points_on_boundary, 1u);
  EXPECT_EQ(r.surface.vertices_on_input_surface, 1u);
  ASSERT_EQ(r.surface.on_surface_examples.size(), 1u);
  EXPECT_EQ(r.surface.on_surface_examples[0], pid);
  EXPECT_FALSE(r.surface.boundary_constrained);
  EXPECT_NEAR(r.volume, 1.0, 1e-15);
}

TEST(QualityReport, PointOnAnInputEdgeIsFoundExactly) {
  VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  const double mid[3] = {0.5, 0.5, 0.0};  // middle of the bottom diagonal 0-3
  const uint32_t pid = test::split_edge(cube, 0, 3, mid);
  const QualityReport r = report_of(cube, &surface);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.surface.input_triangles_missing, 2u);
  EXPECT_EQ(r.surface.boundary_faces_not_in_input, 4u);
  EXPECT_EQ(r.surface.steiner_points_on_boundary, 1u);
  EXPECT_EQ(r.surface.vertices_on_input_surface, 1u);
  ASSERT_FALSE(r.surface.on_surface_examples.empty());
  EXPECT_EQ(r.surface.on_surface_examples[0], pid);
  EXPECT_FALSE(r.surface.boundary_constrained);
}

TEST(QualityReport, InteriorPointIsNotOnTheSurface) {
  VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  const double centre[3] = {0.5, 0.5, 0.5};  // on the main diagonal 0-7, inside
  test::split_edge(cube, 0, 7, centre);
  const QualityReport r = report_of(cube, &surface);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.tets, 12u);
  EXPECT_EQ(r.surface.vertices_on_input_surface, 0u);
  EXPECT_EQ(r.surface.steiner_points_on_boundary, 0u);
  EXPECT_TRUE(r.surface.boundary_constrained);
  EXPECT_EQ(r.surface.touching_surface.tets, 12u);  // every tet still has a cube corner
}

TEST(QualityReport, InvertedTetMakesTheMeshInvalid) {
  VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  std::swap(cube.tet[4 * 2 + 0], cube.tet[4 * 2 + 1]);
  const QualityReport r = report_of(cube, &surface);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.nonpositive_tets, 1u);
  EXPECT_EQ(r.inverted_tets, 1u);
  EXPECT_EQ(r.flat_tets, 0u);
  ASSERT_EQ(r.nonpositive_examples.size(), 1u);
  EXPECT_EQ(r.nonpositive_examples[0], 2u);
  EXPECT_NEAR(r.volume, 4.0 / 6.0, 1e-15);
  EXPECT_NEAR(r.surface.volume_rel_error, 1.0 / 3.0, 1e-14);
  // The faces are unchanged as vertex sets: the boundary is still the input's.
  EXPECT_TRUE(r.surface.boundary_constrained);
}

TEST(QualityReport, FlatTetIsNonPositiveByExactOrientation) {
  VolumeMesh m;
  // Coplanar up to the last bit: z = x + y holds exactly for these binary fractions.
  const double p[4][3] = {{0, 0, 0}, {0.5, 0, 0.5}, {0, 0.25, 0.25}, {0.125, 0.375, 0.5}};
  for (const auto& q : p) m.xyz.insert(m.xyz.end(), q, q + 3);
  m.tet = {0, 1, 2, 3};
  const QualityReport r = report_of(m, nullptr);
  EXPECT_EQ(r.flat_tets, 1u);
  EXPECT_EQ(r.nonpositive_tets, 1u);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.radius_ratio.max, 0.0);
  EXPECT_EQ(r.rr_histogram[0], 1u);
  EXPECT_FALSE(r.surface.present);
}

// Positive for the exact test but flat to rounding: valid, and counted apart.
TEST(QualityReport, TetFlatToRoundingIsValidButCounted) {
  VolumeMesh m;
  const double third = 1.0 / 3.0;  // rounded down: off the plane x + y + z = 1 by rounding only
  const double p[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {third, third, third}};
  for (const auto& q : p) m.xyz.insert(m.xyz.end(), q, q + 3);
  // (a c b d) is the positive order when d is on the origin's side of the plane.
  ASSERT_GT(predicates::orient3d(p[0], p[2], p[1], p[3]), 0);
  m.tet = {0, 2, 1, 3};
  const QualityReport r = report_of(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.nonpositive_tets, 0u);
  EXPECT_EQ(r.rounding_flat_tets, 1u);
}

TEST(QualityReport, DuplicatedTetBreaksConformity) {
  VolumeMesh cube = test::kuhn_grid(1);
  cube.tet.insert(cube.tet.end(), cube.tet.begin(), cube.tet.begin() + 4);
  const QualityReport r = report_of(cube, nullptr);
  EXPECT_FALSE(r.valid);
  // The copied tet's faces: its boundary faces now appear twice, its inner faces three times.
  EXPECT_GE(r.faces_shared_by_more_than_two, 1u);
  EXPECT_EQ(r.nonpositive_tets, 0u);
}

TEST(QualityReport, CoordinatesWrittenWithFewerDigitsMatchWithinTolerance) {
  VolumeMesh cube = test::kuhn_grid(2, 1.0 / 3.0);  // thirds: a 12-digit writer rounds them
  const SurfaceMesh surface = test::boundary_surface(cube);
  for (double& x : cube.xyz) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", x);
    x = std::strtod(buf, nullptr);
  }
  const QualityReport r = report_of(cube, &surface);
  // 26 grid points are on the surface; the centre is not (the surface lists it, unreferenced).
  EXPECT_EQ(r.surface.matched_exact + r.surface.matched_tolerance, 26u);
  EXPECT_GT(r.surface.matched_tolerance, 0u);
  EXPECT_EQ(r.surface.input_triangles_missing, 0u);
  EXPECT_EQ(r.surface.vertices_on_input_surface, 0u);
  EXPECT_TRUE(r.surface.boundary_constrained);
  EXPECT_EQ(r.surface.touching_surface.tets, r.tets);

  QualityOptions exact_only;
  exact_only.match_tolerance = 0.0;
  Result<QualityReport> e = compute_quality_report(cube, &surface, exact_only);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e.value().surface.matched_tolerance, 0u);
  EXPECT_FALSE(e.value().surface.boundary_constrained);
}

TEST(QualityReport, GridSplitAndParallelAgree) {
  const VolumeMesh grid = test::kuhn_grid(12);
  const SurfaceMesh surface = test::boundary_surface(grid);
  const QualityReport a = report_of(grid, &surface, true);
  const QualityReport b = report_of(grid, &surface, false);
  EXPECT_EQ(a.tets, 6u * 12 * 12 * 12);
  EXPECT_TRUE(a.valid);
  EXPECT_EQ(a.boundary_faces, 6u * 12 * 12 * 2);
  EXPECT_TRUE(a.surface.boundary_constrained);
  EXPECT_EQ(a.surface.matched_exact, 6u * 12 * 12 + 2);  // the 6*144 + 2 surface grid points
  EXPECT_EQ(a.surface.touching_surface.tets + a.surface.interior.tets, a.tets);
  EXPECT_GT(a.surface.interior.tets, 0u);
  EXPECT_EQ(a.radius_ratio.mean, b.radius_ratio.mean);
  EXPECT_EQ(a.rr_histogram, b.rr_histogram);
  EXPECT_EQ(a.surface.touching_surface.tets, b.surface.touching_surface.tets);
  EXPECT_EQ(std::accumulate(a.rr_histogram.begin(), a.rr_histogram.end(), size_t(0)), a.tets);
}

// Many regions (past the few the report's scan collects before it sorts): each once, in order.
TEST(QualityReport, ManyRegionsAreEachReportedOnce) {
  VolumeMesh grid = test::kuhn_grid(3);
  ASSERT_GE(grid.num_tets(), 140u);
  grid.region.resize(grid.num_tets());
  for (size_t t = 0; t < grid.num_tets(); ++t) grid.region[t] = int32_t(69 - t % 70);
  const QualityReport r = report_of(grid, nullptr);
  ASSERT_EQ(r.by_region.size(), 70u);
  size_t tets = 0;
  for (size_t k = 0; k < 70; ++k) {
    EXPECT_EQ(r.by_region[k].region, int32_t(k));
    tets += r.by_region[k].quality.tets;
  }
  EXPECT_EQ(tets, r.tets);
}

TEST(QualityReport, QualityPerRegionOnlyWithTwoRegionsOrMore) {
  VolumeMesh grid = test::kuhn_grid(2);
  EXPECT_TRUE(report_of(grid, nullptr).by_region.empty());  // no region array: one region
  grid.region.assign(grid.num_tets(), 4);
  EXPECT_TRUE(report_of(grid, nullptr).by_region.empty());  // one region
  // Squash the top layer of vertices: the tets there (region 7) get worse, the rest stay Kuhn.
  for (size_t v = 0; v < grid.num_vertices(); ++v)
    if (grid.xyz[3 * v + 2] > 1.5) grid.xyz[3 * v + 2] = 1.1;
  size_t top = 0;
  for (size_t t = 0; t < grid.num_tets(); ++t) {
    bool high = false;
    for (int k = 0; k < 4; ++k) high = high || grid.xyz[3 * size_t(grid.tet[4 * t + k]) + 2] > 1.05;
    grid.region[t] = high ? 7 : 4;
    top += high;
  }
  const QualityReport r = report_of(grid, nullptr);
  ASSERT_EQ(r.by_region.size(), 2u);
  EXPECT_EQ(r.by_region[0].region, 4);
  EXPECT_EQ(r.by_region[1].region, 7);
  EXPECT_EQ(r.by_region[1].quality.tets, top);
  EXPECT_EQ(r.by_region[0].quality.tets + top, r.tets);
  EXPECT_NEAR(r.by_region[0].quality.radius_ratio.min, r.by_region[0].quality.radius_ratio.max, 1e-14);
  EXPECT_LT(r.by_region[1].quality.radius_ratio.max, r.by_region[0].quality.radius_ratio.min);
  const nlohmann::json j = nlohmann::json::parse(quality_report_json(r));
  ASSERT_EQ(j["quality_by_region"].size(), 2u);
  EXPECT_EQ(j["quality_by_region"][1]["region"], 7);
  EXPECT_EQ(j["quality_by_region"][1]["tets"], top);
  EXPECT_NE(quality_report_text(r).find("region 7: "), std::string::npos);
}

TEST(QualityReport, BadIndexAndNonFiniteCoordinateAreErrors) {
  VolumeMesh cube = test::kuhn_grid(1);
  cube.tet[5] = 99;
  Result<QualityReport> r = compute_quality_report(cube, nullptr);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::BadIndex);
  EXPECT_NE(r.status().message().find("99"), std::string::npos);

  VolumeMesh nan_mesh = test::kuhn_grid(1);
  nan_mesh.xyz[4] = std::nan("");
  r = compute_quality_report(nan_mesh, nullptr);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::NonFiniteCoordinate);
}

TEST(QualityReport, EmptyMeshGivesAnEmptyReport) {
  VolumeMesh m;
  Result<QualityReport> r = compute_quality_report(m, nullptr);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().tets, 0u);
  EXPECT_FALSE(quality_report_text(r.value()).empty());
}

TEST(QualityReport, UnusedVerticesAreCounted) {
  VolumeMesh cube = test::kuhn_grid(1);
  cube.xyz.insert(cube.xyz.end(), {5.0, 5.0, 5.0});
  EXPECT_EQ(report_of(cube, nullptr).unused_vertices, 1u);
}

TEST(QualityStats, PercentileFollowsNumpyLinearRule) {
  std::vector<double> v;
  for (int i = 10; i >= 1; --i) v.push_back(i);
  const Stats s = quality_detail::make_stats(v);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_NEAR(s.p01, 1.09, 1e-15);  // numpy.percentile(range(1, 11), 1)
  std::vector<double> w(101);
  std::iota(w.begin(), w.end(), 0.0);
  EXPECT_DOUBLE_EQ(quality_detail::make_stats(w).p01, 1.0);
  EXPECT_EQ(quality_detail::make_stats({}).count, 0u);
}

TEST(QualityFormat, JsonUsesMeshcheckKeys) {
  const VolumeMesh cube = test::kuhn_grid(1);
  const SurfaceMesh surface = test::boundary_surface(cube);
  const QualityReport r = report_of(cube, &surface);
  const nlohmann::json j = nlohmann::json::parse(quality_report_json(r));
  EXPECT_EQ(j.at("tets").get<int>(), 6);
  EXPECT_EQ(j.at("vertices").get<int>(), 8);
  EXPECT_TRUE(j.at("valid").get<bool>());
  EXPECT_TRUE(j.at("boundary_constrained").get<bool>());
  for (const char* key : {"unused_vertices", "nonpositive_tets", "inverted_tets", "faces_shared_by_more_than_two",
                          "boundary_faces", "volume", "steiner_points_on_boundary", "input_triangles",
                          "input_triangles_missing", "boundary_faces_not_in_input", "surface_volume",
                          "volume_rel_error", "quality_touching_surface", "input_triangle_quality_min"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const auto& q = j.at("quality");
  for (const char* key : {"min_dihedral_deg", "max_dihedral_deg", "dihedral_p01_deg", "good_fraction_rr_gt_0.4",
                          "bad_fraction_rr_lt_0.1", "tets_dihedral_lt_5deg", "tets_dihedral_lt_10deg"}) {
    EXPECT_TRUE(q.contains(key)) << key;
  }
  EXPECT_NEAR(q.at("radius_ratio").at("mean").get<double>(), r.radius_ratio.mean, 1e-15);
  const std::string csv = quality_histogram_csv(r);
  EXPECT_EQ(csv.rfind("lo,hi,count\n0.00,0.05,", 0), 0u);
  EXPECT_NE(quality_report_text(r).find("boundary constrained: YES"), std::string::npos);
}

}  // namespace
}  // namespace anitet

namespace anitet {
namespace {

// The UGAWG measures of a mesh with a vertex metric: the regular tet of edge h is 1 in the metric
// I / h^2 by both measures; stretching the metric along x changes the lengths along x only.
TEST(QualityReport, MetricMeasuresFollowUgawg) {
  VolumeMesh tet;
  const double h = 0.25;
  tet.xyz = {0, 0, 0, h, 0, 0, h / 2, h * std::sqrt(3.0) / 2, 0, h / 2, h * std::sqrt(3.0) / 6, h * std::sqrt(2.0 / 3.0)};
  test::add_positive_tet(tet, 0, 1, 2, 3);
  tet.vertex_metric.assign(4, h);  // sizes
  QualityReport r = report_of(tet, nullptr);
  ASSERT_TRUE(r.metric.present);
  EXPECT_EQ(r.metric.edges, 6u);
  EXPECT_NEAR(r.metric.edge_length.min, 1.0, 1e-12);
  EXPECT_NEAR(r.metric.edge_length.max, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.metric.in_range, 1.0);
  EXPECT_NEAR(r.metric.mean_ratio.min, 1.0, 1e-12);
  // Tensors: x twice as fine at vertex 1 only. Edge 0-1 along x: la = 1, lb = 2, l = 1 / ln 2.
  tet.vertex_metric.assign(24, 0.0);
  for (int v = 0; v < 4; ++v) {
    double* m = &tet.vertex_metric[6 * size_t(v)];
    m[0] = (v == 1 ? 4.0 : 1.0) / (h * h);
    m[2] = m[5] = 1.0 / (h * h);
  }
  r = report_of(tet, nullptr);
  EXPECT_NEAR(r.metric.edge_length.max, 1.0 / std::log(2.0), 1e-12);
  EXPECT_EQ(r.metric.length_histogram.size(), r.metric.length_bin_edges.size());
  EXPECT_EQ(std::accumulate(r.metric.length_histogram.begin(), r.metric.length_histogram.end(), size_t(0)), 6u);
  EXPECT_LT(r.metric.mean_ratio.min, 1.0);  // measured in vertex 1's metric, where it is stretched
  const nlohmann::json j = nlohmann::json::parse(quality_report_json(r));
  EXPECT_EQ(j["metric"]["edges"], 6);
  EXPECT_NE(quality_report_text(r).find("UGAWG"), std::string::npos);
  // A tensor that is not SPD is named.
  tet.vertex_metric[6 * 2 + 0] = -1.0;
  const Result<QualityReport> bad = compute_quality_report(tet, nullptr);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("vertex 3"), std::string::npos);
}

}  // namespace
}  // namespace anitet
