// The whole pipeline (validate, layers, recovery, coupling) on closed surfaces, checked with the
// independent quality report: valid (exact orientation, conformity), boundary constrained (every
// input triangle a boundary face, no other boundary face, no Steiner point on the surface), and the
// enclosed volume kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <string>
#include <vector>

#include "core/sizing.hpp"
#include "core/tet_mesh.hpp"
#include "io/surface_io.hpp"
#include "layers/layers.hpp"
#include "layers/shapes.hpp"
#include "metric/metric_field.hpp"
#include "pipeline/mesher.hpp"
#include "pipeline/stage1.hpp"
#include "quality/quality_report.hpp"
#include "recovery/recovery.hpp"
#include "refine/stretched_box.hpp"

using namespace anitet;

namespace {

void expect_boundary_constrained(const SurfaceMesh& surface, const MesherResult& r, const std::string& what) {
  Result<QualityReport> q = compute_quality_report(r.mesh, &surface);
  ASSERT_TRUE(q.ok()) << what << ": " << q.status().message();
  EXPECT_TRUE(q->valid) << what << ": " << q->nonpositive_tets << " non-positive tets, "
                        << q->faces_shared_by_more_than_two << " faces shared by more than two tets";
  EXPECT_EQ(q->surface.input_triangles_missing, 0u) << what;
  EXPECT_EQ(q->surface.boundary_faces_not_in_input, 0u) << what;
  EXPECT_EQ(q->surface.steiner_points_on_boundary, 0u) << what;
  EXPECT_EQ(q->surface.vertices_on_input_surface, 0u) << what;
  EXPECT_TRUE(q->surface.boundary_constrained) << what;
  EXPECT_LT(q->surface.volume_rel_error, 1e-9) << what;
  EXPECT_EQ(q->unused_vertices, 0u) << what;
  // The input's vertices come first, unchanged.
  for (size_t i = 0; i < surface.xyz.size(); ++i) ASSERT_EQ(r.mesh.xyz[i], surface.xyz[i]) << what;
  // And the mesh's own audit agrees.
  TetMesh tm = TetMesh::from_volume_mesh(r.mesh);
  ASSERT_TRUE(tm.build_adjacency().ok()) << what;
  Status st = check_mesh(tm, {});
  EXPECT_TRUE(st.ok()) << what << ": " << st.message();
}

Result<MesherResult> mesh(const SurfaceMesh& s, int layers = 2) {
  MesherOptions options;
  options.layers.layers = layers;
  return Mesher(options).run(s);
}

}  // namespace

TEST(Pipeline, CoarseCube) {
  const SurfaceMesh s = test::coarse_cube();
  for (int layers : {1, 2}) {
    Result<MesherResult> r = mesh(s, layers);
    ASSERT_TRUE(r.ok()) << r.status().message();
    expect_boundary_constrained(s, r.value(), "coarse cube, layers " + std::to_string(layers));
  }
}

// What the run did otherwise than asked is told: refinement stopped at its pass cap (one pass
// here) is a notice, and a run that did everything as asked has none.
TEST(Pipeline, NoticesTellWhatWasLessThanAsked) {
  const SurfaceMesh s = test::icosphere(3);
  Result<MesherResult> full = Mesher().run(s);
  ASSERT_TRUE(full.ok()) << full.status().message();
  EXPECT_FALSE(full->refine.stopped_at_pass_cap);
  for (const Notice& n : full->notices) EXPECT_NE(n.kind, "refinement_pass_cap") << n.message;
  MesherOptions capped;
  capped.refine.max_passes = 1;
  capped.anisotropic_cycles = 0;
  Result<MesherResult> r = Mesher(capped).run(s);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->refine.stopped_at_pass_cap);
  bool told = false;
  for (const Notice& n : r->notices) told = told || (n.kind == "refinement_pass_cap" && n.message.find("cap of 1 passes") != std::string::npos);
  EXPECT_TRUE(told);
}

TEST(Pipeline, GridCubeAndSphere) {
  for (const auto& [name, s] : {std::pair{std::string("grid cube"), test::grid_cube(4)},
                                std::pair{std::string("icosphere"), test::icosphere(2)}}) {
    Result<MesherResult> r = mesh(s);
    ASSERT_TRUE(r.ok()) << name << ": " << r.status().message();
    expect_boundary_constrained(s, r.value(), name);
    EXPECT_EQ(r->stages.size(), 7u);  // layers recovery coupling sizing refine optimize output
#if defined(__linux__)
    // Each stage's peak memory so far: known on Linux. (Not checked to grow: the kernel updates
    // VmHWM lazily, and memory handed back can lower it by a page or so.)
    for (const StageReport& st : r->stages) EXPECT_GT(st.peak_bytes, 0.0) << name << ", stage " << st.name;
#endif
  }
}

TEST(Pipeline, NestedCubesLeaveTheCavityEmpty) {
  const SurfaceMesh s = test::nested_cubes();
  Result<MesherResult> r = mesh(s);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_boundary_constrained(s, r.value(), "nested cubes");  // the volume check sees a filled cavity
}

TEST(Pipeline, SharedKnight) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok()) << s.status().message();
  // One layer: with two, stage 2 does not yet recover this S1 (recovery's known limits).
  Result<MesherResult> r = mesh(s.value(), 1);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_boundary_constrained(s.value(), r.value(), "decimated-knight.off");
}

// The attempts' time budget: with stage 2 made to fail (no pass allowed), every layer count and
// strategy is tried without a budget, and only the first one with a budget already spent.
TEST(Pipeline, AttemptsStopWhenTheirBudgetRunsOut) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok()) << s.status().message();
  MesherOptions o;
  o.recovery.max_passes = 0;
  o.attempts_seconds = 0;
  Result<MesherResult> all = Mesher(o).run(s.value());
  ASSERT_FALSE(all.ok());
  EXPECT_NE(all.status().message().find("(6 of 6 attempts"), std::string::npos) << all.status().message();
  o.attempts_seconds = 1e-9;
  Result<MesherResult> one = Mesher(o).run(s.value());
  ASSERT_FALSE(one.ok());
  EXPECT_EQ(one.status().code(), Error::RecoveryFailed);
  EXPECT_NE(one.status().message().find("(1 of 6 attempts"), std::string::npos) << one.status().message();
  EXPECT_NE(one.status().message().find("budget"), std::string::npos) << one.status().message();
  // Without layer-count retries: the given count with each strategy family only.
  o.attempts_seconds = 0;
  o.retry_layer_counts = false;
  Result<MesherResult> no_retries = Mesher(o).run(s.value());
  ASSERT_FALSE(no_retries.ok());
  EXPECT_NE(no_retries.status().message().find("(2 of 2 attempts"), std::string::npos)
      << no_retries.status().message();
}

TEST(Pipeline, SameInputSameMeshBitForBit) {
  const SurfaceMesh s = test::icosphere(2);
  Result<MesherResult> a = mesh(s), b = mesh(s);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->mesh.xyz, b->mesh.xyz);
  EXPECT_EQ(a->mesh.tet, b->mesh.tet);
  EXPECT_EQ(a->mesh.region, b->mesh.region);
}

TEST(Pipeline, ProgressReportsStagesAndCancels) {
  const SurfaceMesh s = test::coarse_cube();
  std::vector<std::string> seen;
  MesherOptions options;
  options.progress = [&](const std::string& stage, double fraction) {
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    seen.push_back(stage);
    return stage != "recovery";
  };
  Result<MesherResult> r = Mesher(options).run(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::Cancelled);
  EXPECT_EQ(seen, (std::vector<std::string>{"validate", "layers", "recovery"}));
}

TEST(Pipeline, InvalidSurfaceGivesItsValidationError) {
  SurfaceMesh s = test::coarse_cube();
  s.tri.resize(s.tri.size() - 3);  // an open box
  s.patch.pop_back();
  Result<MesherResult> r = mesh(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::OpenBoundary);
}

// Stage 2 on a real front: casting's S1 (two layers) is recovered by the split strategy alone.
// A missing triangle whose edges are present first gets an edge removal: with the flips off its
// splits cascade (as hammer's and skull's did). Missing edges are split where a walk shows the
// piece joined to its end: fewer Steiner points than the midpoint rule.
// Stage 1 on a shared surface (default options) and the split-only recovery options for its S1,
// with the T1 apexes as the pipeline gives them.
struct Front {
  SurfaceMesh s1;
  RecoveryOptions options;
};
// S1 after stage 1 with 2 layers: the fronts the tests below describe (stage 1's default is 1).
Front front_of(const char* name) {
  Front f;
  Result<SurfaceMesh> r = read_surface(std::string(ANITET_SURFACES_DIR) + "/" + name);
  EXPECT_TRUE(r.ok()) << r.status().message();
  if (!r.ok()) return f;
  const SurfaceMesh surface = std::move(r).value();
  const IsotropicSurfaceSizing sizing(surface);
  LayersOptions two;
  two.layers = 2;
  Result<LayersOutput> layers = build_layers(surface, sizing, two);
  EXPECT_TRUE(layers.ok()) << layers.status().message();
  if (!layers.ok()) return f;
  f.s1 = front_surface(layers.value());
  f.options.fuzzy_faces = false;
  f.options.face_apex.resize(3 * f.s1.num_triangles());
  for (size_t i = 0; i < f.s1.num_triangles(); ++i) {
    const uint32_t apex = layers->mesh.vertex(layers->front_tet[i], int(layers->front_facet[i]));
    std::copy(layers->mesh.point(apex), layers->mesh.point(apex) + 3, &f.options.face_apex[3 * i]);
  }
  return f;
}

TEST(Stage2, CastingFrontIsRecoveredBySplittingAndFlips) {
  const Front f = front_of("casting.off");
  ASSERT_GT(f.s1.num_triangles(), 0u);
  const SurfaceMesh& s1 = f.s1;
  const RecoveryOptions& o = f.options;
  Result<RecoveryOutput> walked = recover_boundary(s1, o);
  ASSERT_TRUE(walked.ok()) << walked.status().message();
  EXPECT_GT(walked->stats.walk_splits, 0u);
  std::printf("casting S1: %zu triangles, %zu Steiner points (%zu placed by a walk), %zu flips, %.3f s\n",
              s1.num_triangles(), walked->steiner.size(), walked->stats.walk_splits, walked->stats.flips,
              walked->stats.seconds_total);
  RecoveryOptions midpoints = o;
  midpoints.split_walk = false;
  Result<RecoveryOutput> mid = recover_boundary(s1, midpoints);
  ASSERT_TRUE(mid.ok()) << mid.status().message();
  EXPECT_LT(walked->steiner.size(), mid->steiner.size());
  // Flips save points: without them it needs more than 3x as many (2357 against 171 measured), or
  // fails (as it did before edges were defended).
  RecoveryOptions no_flips = o;
  no_flips.split_flips = false;
  Result<RecoveryOutput> unflipped = recover_boundary(s1, no_flips);
  if (unflipped.ok()) {
    EXPECT_GT(unflipped->steiner.size(), 3 * walked->steiner.size());
  }
}

// turbine's S1 is recovered at the first try (it took the retry that removes crossing edges three
// times before edges were defended and the face flips ran to the end). Defended subsegments and the
// forced walk each save Steiner points there: 1479 with both, 2679 with neither.
TEST(Stage2, TurbineFrontIsRecoveredAtTheFirstTry) {
  const Front f = front_of("turbine.off");
  ASSERT_GT(f.s1.num_triangles(), 0u);
  RecoveryOptions once = f.options;
  once.retry_strategies = false;
  Result<RecoveryOutput> out = recover_boundary(f.s1, once);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out->stats.strategy, 3u) << recovery_strategy_name(out->stats.strategy);
  std::printf("turbine S1: %zu triangles, %zu Steiner points, %zu flips, %.3f s\n", f.s1.num_triangles(),
              out->steiner.size(), out->stats.flips, out->stats.seconds_total);
  RecoveryOptions neither = once;
  neither.split_forced_walk = false;
  neither.split_defend_edges = false;
  Result<RecoveryOutput> plain = recover_boundary(f.s1, neither);
  ASSERT_TRUE(plain.ok()) << plain.status().message();
  std::printf("  without defended edges and forced walk: %zu Steiner points\n", plain->steiner.size());
  EXPECT_LT(out->steiner.size(), plain->steiner.size());
}

// adis16480's S1 (needle fans of 1e-5-wide triangles on 4e-2 edges, 2 layers): defended
// subsegments and the forced walk bring its missing edges to 0, the face flips run to the end and
// the missing face edges are flipped or split, so the split strategy recovers it (after the first
// try, with the retry), where before the edge phase grew to the Steiner cap.
TEST(Stage2, AdisFrontIsRecovered) {
  const Front f = front_of("adis16480.stl");
  ASSERT_GT(f.s1.num_triangles(), 0u);
  Result<RecoveryOutput> out = recover_boundary(f.s1, f.options);
  ASSERT_TRUE(out.ok()) << out.status().message();
  std::printf("adis16480 S1: %zu triangles, %zu Steiner points, strategy %s, %.2f s\n", f.s1.num_triangles(),
              out->steiner.size(), recovery_strategy_name(out->stats.strategy), out->stats.seconds_total);
  const Status valid = check_mesh(out->mesh);
  EXPECT_TRUE(valid.ok()) << valid.message();
  EXPECT_EQ(out->stats.regions, 1u);
  RecoveryOptions old = f.options;
  old.split_forced_walk = false;
  old.split_defend_edges = false;
  old.split_face_edges = false;
  old.retry_strategies = false;
  EXPECT_FALSE(recover_boundary(f.s1, old).ok()) << "recovered without them: they are no longer what this tests";
}

// Issue 5's CFD case through the Mesher (stages 1, 2 and the coupling): airplane.obj inside a
// farfield box 10x its size, walls on the airplane, h0 = 1e-3 x its size, r = 1.2, 15 BL layers.
// Stage 2 recovers S1 (it could not while pushes cut to 1e-12 of h0 left S1 vertices 1e-14
// apart), the mesh is valid and boundary constrained, and the heights are h0 r^i within 10% on
// the columns not reduced.
TEST(Pipeline, AirplaneInAFarfieldBoxWith15BoundaryLayers) {
  Result<SurfaceMesh> read = read_surface(std::string(ANITET_SURFACES_DIR) + "/airplane.obj");
  ASSERT_TRUE(read.ok()) << read.status().message();
  const SurfaceMesh body = std::move(read).value();
  double size = 0.0;
  const SurfaceMesh s = test::in_farfield_box(body, size);
  MesherOptions options;
  // Stages 1, 2 and the coupling are what this case tests (the BL is frozen afterwards); the CLI
  // run with refinement and optimization is in the README.
  options.run_refine = false;
  options.run_optimize = false;
  BoundaryLayerOptions& bl = options.layers.boundary_layer;
  bl.wall_patches = {test::kBodyWall};
  bl.first_height = 1e-3 * size;
  bl.growth = 1.2;
  bl.layers = 15;
  Result<MesherResult> r = Mesher(options).run(s);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_boundary_constrained(s, r.value(), "airplane in a farfield box, 15 BL layers");
  const BoundaryLayerReport& b = r->boundary_layer;
  EXPECT_EQ(b.layers, 15);
  EXPECT_EQ(b.wall_vertices, body.num_vertices());
  EXPECT_GT(b.nominal_columns, 0u);
  EXPECT_LT(b.max_height_error, 0.1);
  EXPECT_LT(double(b.reduced_vertices), 0.5 * double(b.wall_vertices));
  double stage1 = 0;
  for (const StageReport& st : r->stages)
    if (st.name.rfind("layers", 0) == 0) stage1 += st.seconds;
  std::printf("[airplane in farfield box, 15 BL layers] %zu tets in %.1f s (stage 1 %.1f s), layers used %d, "
              "full columns %zu of %zu, nominal %zu, reduced vertices %zu (%.1f%%), max height error %.3f\n",
              r->mesh.num_tets(), r->seconds, stage1, r->layers_used, b.full_columns, b.wall_vertices,
              b.nominal_columns, b.reduced_vertices, 100.0 * double(b.reduced_vertices) / double(b.wall_vertices),
              b.max_height_error);
}

// MesherOptions::boundary_layer_sizing: the interior continues the BL's heights. The interior tets
// standing on the BL's top facets are measured by their height over that facet against the last
// layer's h0 r^(n-1): without it they jump to the surface's sizes (measured 5.6x), with it they
// stay within 3x (2.4x; 16 s instead of 0.5 s).
namespace {
double median_height_on_bl_top(const VolumeMesh& m, int32_t interior_region) {
  std::map<std::array<uint32_t, 3>, std::vector<std::pair<size_t, uint32_t>>> faces;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<uint32_t, 3> f;
      int j = 0;
      for (int i = 0; i < 4; ++i)
        if (i != k) f[size_t(j++)] = m.tet[4 * t + size_t(i)];
      std::sort(f.begin(), f.end());
      faces[f].push_back({t, m.tet[4 * t + size_t(k)]});
    }
  std::vector<double> heights;
  auto pt = [&](uint32_t v) { return &m.xyz[3 * size_t(v)]; };
  for (const auto& [f, sides] : faces) {
    if (sides.size() != 2 || m.region[sides[0].first] == m.region[sides[1].first]) continue;
    const uint32_t apex = m.region[sides[0].first] == interior_region ? sides[0].second : sides[1].second;
    const double *a = pt(f[0]), *b = pt(f[1]), *c = pt(f[2]), *p = pt(apex);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    heights.push_back(std::abs(n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2])) / len);
  }
  if (heights.empty()) return 0.0;
  std::nth_element(heights.begin(), heights.begin() + std::ptrdiff_t(heights.size() / 2), heights.end());
  return heights[heights.size() / 2];
}
}  // namespace

TEST(Pipeline, BoundaryLayerSizingContinuesTheLayersHeights) {
  const double center[3] = {0, 0, 0};
  const SurfaceMesh s = test::body_in_box(test::icosphere(2), center, 2.5, 4);
  MesherOptions options;
  options.layers.layers = 1;
  BoundaryLayerOptions& bl = options.layers.boundary_layer;
  bl.wall_patches = {test::kBodyWall};
  bl.first_height = 0.002;
  bl.growth = 1.2;
  bl.layers = 15;
  const double last = 0.002 * std::pow(1.2, 14);
  double median[2] = {0, 0};
  for (int with = 0; with < 2; ++with) {
    options.boundary_layer_sizing = with == 1;
    Result<MesherResult> r = Mesher(options).run(s);
    ASSERT_TRUE(r.ok()) << r.status().message();
    expect_boundary_constrained(s, r.value(), with ? "with BL sizing" : "without BL sizing");
    median[with] = median_height_on_bl_top(r->mesh, 0);
    // The BL metric is anisotropic near the walls: the optimizer measures in it, and refinement
    // and optimization run up to MesherOptions::anisotropic_cycles more times (none here since
    // the optimizer keeps lengths in range: the first optimization gains less than
    // anisotropic_cycle_optimizer_gain).
    EXPECT_EQ(r->optimize.anisotropic, with == 1);
    if (with) {
      EXPECT_LE(r->anisotropic_cycles, options.anisotropic_cycles);
    } else {
      EXPECT_EQ(r->anisotropic_cycles, 0);
    }
    EXPECT_EQ(r->metric_quality.tets > 0, with == 1);
    EXPECT_EQ(std::count_if(r->stages.begin(), r->stages.end(), [](const StageReport& st) { return st.name == "cycles"; }),
              with ? 1 : 0);
    std::printf("[sphere in box, 15 BL layers, BL sizing %s] %zu tets in %.2f s; interior tets on the BL top: "
                "median height %.4f = %.2f x the last layer's %.4f\n",
                with ? "on" : "off", r->mesh.num_tets(), r->seconds, median[with], median[with] / last, last);
  }
  EXPECT_GT(median[0], 4.0 * last);
  EXPECT_LT(median[1], 3.0 * last);
  // Without a boundary layer the option is refused, not ignored.
  MesherOptions plain;
  plain.boundary_layer_sizing = true;
  EXPECT_EQ(Mesher(plain).run(test::coarse_cube()).status().code(), Error::InvalidArgument);
}

namespace {

// The box [0,1]^3 with each face a structured grid, n[k] cells along axis k, two triangles per
// cell, counter-clockwise seen from outside.
SurfaceMesh lattice_box(const int n[3]) {
  SurfaceMesh s;
  std::map<std::tuple<int, int, int>, uint32_t> id;
  auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    auto it = id.find(key);
    if (it != id.end()) return it->second;
    s.add_vertex(double(x) / n[0], double(y) / n[1], double(z) / n[2]);
    return id[key] = uint32_t(s.num_vertices() - 1);
  };
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // e_i x e_j = e_k
    for (int side = 0; side < 2; ++side)
      for (int a = 0; a < n[i]; ++a)
        for (int b = 0; b < n[j]; ++b) {
          uint32_t c[2][2];
          for (int da = 0; da < 2; ++da)
            for (int db = 0; db < 2; ++db) {
              int q[3];
              q[k] = side * n[k];
              q[i] = a + da;
              q[j] = b + db;
              c[da][db] = vertex(q[0], q[1], q[2]);
            }
          if (side == 1) {  // outward +e_k
            s.add_triangle(c[0][0], c[1][0], c[1][1]);
            s.add_triangle(c[0][0], c[1][1], c[0][1]);
          } else {
            s.add_triangle(c[0][0], c[1][1], c[1][0]);
            s.add_triangle(c[0][0], c[0][1], c[1][1]);
          }
        }
  }
  return s;
}

}  // namespace

// A user metric that is anisotropic drives every stage: stage 1 grows the layers to its heights
// and measures its directions in it (with the surface's own sizes, the layers on stretched
// triangles came out far too thin for refinement to recover), and refinement, optimization and
// their extra cycles follow it. The surface's triangles are unit triangles of the metric,
// stretched 12.5:1 in space.
TEST(Pipeline, AnisotropicUserMetricDrivesEveryStage) {
  const int n[3] = {4, 4, 50};
  const SurfaceMesh s = lattice_box(n);
  const test::AxisSizing field(0.25, 0.25, 0.02);
  MesherOptions options;
  options.sizing = &field;
  Result<MesherResult> r = Mesher(options).run(s);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_boundary_constrained(s, r.value(), "stretched box");
  EXPECT_TRUE(r->optimize.anisotropic);
  EXPECT_GE(r->anisotropic_cycles, 1);
  EXPECT_LE(r->anisotropic_cycles, options.anisotropic_cycles);
  TetMesh tm = TetMesh::from_volume_mesh(r->mesh);
  size_t tets = 0;
  const size_t bad = test::tets_below_in_metric(tm, field, 0.1, &tets);
  const size_t poor = test::tets_below_in_metric(tm, field, 0.4);
  std::printf("[stretched box] %zu tets in %.2f s (layers used %d); metric radius ratio < 0.1: %zu, < 0.4: %zu; "
              "edges in range %.4f\n",
              tets, r->seconds, r->layers_used, bad, poor, r->refine.length_in_range);
  EXPECT_LT(double(bad), 0.001 * double(tets));
  EXPECT_LT(double(poor), 0.02 * double(tets));
  // The result's own figures in the metric agree (the metric is constant here).
  EXPECT_EQ(r->metric_quality.tets, tets);
  EXPECT_EQ(r->metric_quality.below_01, bad);
  EXPECT_EQ(r->metric_quality.below_04, poor);
  EXPECT_GT(r->refine.length_in_range, 0.9);
}

// tray_bottom's sliver triangles hold the free vertices near them: before the optimizer's rescue
// (optimize.hpp) one of its few tets off S stayed at radius ratio 0.049, every move of its vertices
// lowering some tet on S, which the sliver climbs never allow. Issue 49 asks >= 0.05 there.
TEST(Pipeline, TetsOffSurfaceOfTrayBottomAreNoSlivers) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/tray_bottom.stl");
  ASSERT_TRUE(s.ok()) << s.status().message();
  Result<MesherResult> r = Mesher(MesherOptions{}).run(s.value());
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_boundary_constrained(s.value(), r.value(), "tray_bottom");
  Result<QualityReport> q = compute_quality_report(r->mesh, &s.value());
  ASSERT_TRUE(q.ok()) << q.status().message();
  const QualitySplit& in = q->surface.interior;
  std::printf("[tray_bottom] %zu tets off S, radius ratio min %.4f mean %.4f; on S min %.6f mean %.4f\n", in.tets,
              in.radius_ratio.min, in.radius_ratio.mean, q->surface.touching_surface.radius_ratio.min,
              q->surface.touching_surface.radius_ratio.mean);
  ASSERT_GT(in.tets, 0u);
  EXPECT_GE(in.radius_ratio.min, 0.05);
}

namespace {

// Per input vertex of the box's face z = 0 or z = 1 (not on its edges): the metric length (in
// `m`, constant) of the step from it to the point stage 1 pushed it to (one layer: its only
// pushed copy).
std::vector<double> top_bottom_heights(const SurfaceMesh& s, const LayersOutput& layers, const double m[6]) {
  std::vector<double> out;
  const TetMesh& t1 = layers.mesh;
  for (uint32_t v = uint32_t(s.num_vertices()); v < t1.num_vertices(); ++v) {
    const uint32_t from = layers.vertex_origin[v];
    if (from == TetMesh::kNone || from >= s.num_vertices()) continue;
    const double* p = s.point(from);
    auto inside = [](double x) { return x > 1e-9 && x < 1.0 - 1e-9; };
    if (!(inside(p[0]) && inside(p[1]) && !inside(p[2]))) continue;
    const double* q = t1.point(v);
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    out.push_back(metric_norm(m, d));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// Stage 1 reads the user's OpenVDB field (issue 46, item 5): with the constant metric of sizes
// 0.1, 0.1, 0.01 along x, y, z as a MetricField (the --metric .vdb field refinement and CVT follow),
// the first layer's heights off the faces z = 0 and z = 1, measured in the metric, are about the
// push step's target (LayersOptions::push_height in metric units: 0.8, of which the chosen height
// keeps at least min_height_fraction = 0.5); with the surface's own isotropic sizes (no metric) the
// same layer stands ~0.07 tall there, 7 in the metric, and refinement has to cut it into seven.
TEST(Stage1, FirstLayerFollowsAnAnisotropicVdbMetric) {
  const int n[3] = {10, 10, 100};  // unit triangles of the metric, 0.1 x 0.01 on the sides
  const SurfaceMesh s = lattice_box(n);
  const double m[6] = {100.0, 0.0, 100.0, 0.0, 0.0, 10000.0};
  const double lo[3] = {-0.1, -0.1, -0.1}, hi[3] = {1.1, 1.1, 1.1};
  Result<metric::MetricField> field = metric::MetricField::from_function(
      [&](const double*, double out[6]) { std::copy_n(m, 6, out); }, lo, hi, 0.1);
  ASSERT_TRUE(field.ok()) << field.status().message();
  ASSERT_EQ(field->kind(), metric::MetricField::Kind::Tensor);
  const LayersOptions options;
  const double target = options.push_height;
  Result<Stage1Result> aniso = run_stage1(s, options, &field.value());
  ASSERT_TRUE(aniso.ok()) << aniso.status().message();
  Result<Stage1Result> iso = run_stage1(s, options);
  ASSERT_TRUE(iso.ok()) << iso.status().message();
  const std::vector<double> ha = top_bottom_heights(s, aniso->layers, m);
  const std::vector<double> hs = top_bottom_heights(s, iso->layers, m);
  ASSERT_EQ(ha.size(), size_t(2 * 9 * 9));
  ASSERT_EQ(hs.size(), ha.size());
  auto at = [](const std::vector<double>& h, double q) { return h[size_t(q * double(h.size() - 1))]; };
  auto share_near = [&](const std::vector<double>& h) {
    return double(std::count_if(h.begin(), h.end(), [&](double x) { return x >= 0.5 * target && x <= 1.25 * target; })) /
           double(h.size());
  };
  std::printf("[stage 1, metric 0.1/0.1/0.01] first-layer heights in the metric off z = 0, 1 (target %.2f), "
              "min p10 median p90 max, share in [0.5, 1.25] x target: OpenVDB metric %.3f %.3f %.3f %.3f %.3f, %.1f%%; "
              "surface sizes %.3f %.3f %.3f %.3f %.3f, %.1f%%\n",
              target, ha.front(), at(ha, 0.1), at(ha, 0.5), at(ha, 0.9), ha.back(), 100.0 * share_near(ha),
              hs.front(), at(hs, 0.1), at(hs, 0.5), at(hs, 0.9), hs.back(), 100.0 * share_near(hs));
  // The metric's: median within 5% of the target, 80% of them within [0.5, 1.25] x target (the
  // others are vertices that the improvement passes moved further in, or whose planned point the
  // tangential smoothing moved, near the box's edges). The surface sizes': median above 4x, and
  // fewer than 5% in that range.
  EXPECT_NEAR(at(ha, 0.5), target, 0.05 * target);
  EXPECT_GE(share_near(ha), 0.8);  // 84.6% when written
  EXPECT_GT(at(hs, 0.5), 4.0 * target);
  EXPECT_LT(share_near(hs), 0.05);
}

// The anisotropic cycles stop after a round whose refinement gained less than min_gain of edges
// in range (no round can gain a whole 1.0), none runs after an optimization that gained less
// than min_optimizer_gain, and all of them run with both 0. The box
// [0,1]^2 x [0,1] with the metric of sizes (0.25, 0.25, 0.04), from the Delaunay mesh of its
// boundary lattice points.
TEST(Pipeline, AnisotropicCyclesStopWithoutGain) {
  const int n[3] = {4, 4, 25};
  const test::AxisSizing field(0.25, 0.25, 0.04);
  struct Case {
    double min_gain, min_optimizer_gain;
    int rounds;
  };
  for (const Case& c : {Case{0.0, 0.0, 3}, Case{1.0, 0.0, 1}, Case{0.0, 1.0, 0}}) {
    std::vector<double> pts;
    TetMesh mesh = test::stretched_box_mesh(n, pts);
    RefineStats refine;
    OptimizeStats optimize;
    Result<RefineStats> r = refine_mesh(mesh, field, RefineOptions());
    ASSERT_TRUE(r.ok()) << r.status().message();
    refine = r.value();
    Result<OptimizeStats> o = optimize_mesh(mesh, field, OptimizeOptions());
    ASSERT_TRUE(o.ok()) << o.status().message();
    optimize = o.value();
    int ran = -1;
    ASSERT_TRUE(refine_optimize_cycles(mesh, field, RefineOptions(), OptimizeOptions(), 3, refine, optimize,
                                       c.min_gain, &ran, c.min_optimizer_gain)
                    .ok());
    EXPECT_EQ(ran, c.rounds) << "min_gain " << c.min_gain << ", min_optimizer_gain " << c.min_optimizer_gain;
    EXPECT_TRUE(check_mesh(mesh).ok());
  }
}
