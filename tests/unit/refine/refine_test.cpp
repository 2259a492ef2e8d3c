// Refinement/coarsening on coupled meshes: S is kept (every input triangle stays a protected
// facet, no vertex of S moves), the mesh stays valid after every pass (check_each_pass), and the
// normalized edge lengths converge to [1/sqrt2, sqrt2].
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/closest_point.hpp"
#include "delaunay/delaunay.hpp"
#include "io/surface_io.hpp"
#include "layers/shapes.hpp"
#include "metric/surface_sizing.hpp"
#include "refine/coupled_fixture.hpp"
#include "refine/edges.hpp"
#include "refine/mesh_ops.hpp"
#include "refine/refine.hpp"
#include "refine/stretched_box.hpp"

using namespace anitet;

namespace {

metric::SurfaceSizingOptions MesherDefaults() {
  metric::SurfaceSizingOptions o;
  o.triangle_size = metric::TriangleSize::Mean;
  return o;
}

TetMesh coupled_sphere() {
  Result<CoupledMesh> c = test::coupled_mesh(test::icosphere(2));
  EXPECT_TRUE(c.ok()) << c.status().message();
  return c.ok() ? std::move(c->mesh) : TetMesh{};
}

// Two copies of the coupled sphere refined to `first` (when positive), then to `size` with the
// default threads (m[0]) and with one thread (m[1]): the same mesh, and more than at_least of
// `count` in the second refinement.
void refine_with_one_thread_or_many(TetMesh (&m)[2], double first, double size, size_t RefineStats::*count,
                                    size_t at_least) {
  for (int k = 0; k < 2; ++k) {
    m[k] = coupled_sphere();
    RefineOptions o;
    if (first > 0.0) {
      ASSERT_TRUE(refine_mesh(m[k], test::ConstantSizing(first), o).ok());
    }
    o.num_threads = k == 0 ? 0 : 1;
    Result<RefineStats> r = refine_mesh(m[k], test::ConstantSizing(size), o);
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_GT(r.value().*count, at_least);
  }
  EXPECT_EQ(m[0].xyz, m[1].xyz);
  EXPECT_EQ(m[0].tet_v, m[1].tet_v);
}

}  // namespace

TEST(Refine, KeepsSurfaceAndValidityAfterEveryPass) {
  const SurfaceMesh s = test::icosphere(2);
  TetMesh mesh = coupled_sphere();
  RefineOptions o;
  o.check_each_pass = true;
  Result<RefineStats> r = refine_mesh(mesh, test::ConstantSizing(0.15), o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->splits, 100u);
  test::expect_surface_kept(s, mesh, "sphere h=0.15");
  EXPECT_TRUE(check_mesh(mesh).ok());
}

TEST(Refine, LengthsConverge) {
  TetMesh mesh = coupled_sphere();
  RefineOptions o;
  Result<RefineStats> r = refine_mesh(mesh, test::ConstantSizing(0.12), o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_LT(r->passes, o.max_passes);
  EXPECT_GT(r->length_in_range, 0.85);
  EXPECT_NEAR(r->length_mean, 1.0, 0.15);
  EXPECT_GT(r->tets_after, 5 * r->tets_before);
}

// collect_edges (chunks of vertices on every core) against a plain scan of the tets: every edge
// once, a < b, grouped by a in ascending order, in the order the tets first list it, flagged
// when a protected facet holds it, with the length in the ends' metrics.
TEST(Refine, CollectEdgesMatchesAPlainScan) {
  TetMesh mesh = coupled_sphere();
  ASSERT_TRUE(refine_mesh(mesh, test::ConstantSizing(0.05), RefineOptions{}).ok());
  ASSERT_GT(mesh.num_vertices(), 3 * 8192u);  // several chunks
  std::vector<double> metrics(6 * mesh.num_vertices());
  for (uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    const double h = 0.05 + 0.01 * (v % 7);  // a different size per vertex
    const double m[6] = {1 / (h * h), 0, 1 / (h * h), 0, 0, 1 / (h * h)};
    std::copy_n(m, 6, &metrics[6 * size_t(v)]);
  }
  refine_detail::EdgeList edges;
  refine_detail::EdgeScratch scratch;
  refine_detail::collect_edges(mesh, metrics, edges, scratch);

  // The plain scan: first occurrence order per lower end, surface flags OR-ed.
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> by_a(mesh.num_vertices());  // (b, tet)
  std::map<std::pair<uint32_t, uint32_t>, bool> on_surface;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    for (int k = 0; k < 6; ++k) {
      const int i = kEdgeVertex[k][0], j = kEdgeVertex[k][1];
      uint32_t a = mesh.vertex(t, i), b = mesh.vertex(t, j);
      if (a > b) std::swap(a, b);
      bool surface = false;
      for (int f = 0; f < 4; ++f) surface |= f != i && f != j && mesh.facet_protected(t, f);
      auto [it, fresh] = on_surface.emplace(std::make_pair(a, b), surface);
      if (fresh) by_a[a].push_back({b, t});
      it->second = it->second || surface;
    }
  }
  size_t n = 0;
  for (uint32_t a = 0; a < mesh.num_vertices(); ++a)
    for (const auto& [b, t] : by_a[a]) {
      ASSERT_LT(n, edges.size());
      const refine_detail::Edge& e = edges[n++];
      ASSERT_EQ(e.a, a);
      ASSERT_EQ(e.b, b);
      EXPECT_EQ(e.tet, t);
      EXPECT_EQ(e.on_surface, on_surface.at({a, b}));
      const double *pa = mesh.point(a), *pb = mesh.point(b);
      const double len = std::sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]) +
                                   (pb[2] - pa[2]) * (pb[2] - pa[2]));
      const double ha = 0.05 + 0.01 * (a % 7), hb = 0.05 + 0.01 * (b % 7);
      EXPECT_NEAR(e.length, len / std::sqrt(ha * hb), 1e-12 * e.length);
    }
  EXPECT_EQ(n, edges.size());
}

// The split points are measured in parallel, chosen and inserted in one order: the same mesh
// with one thread as with the default.
TEST(Refine, SameMeshWithOneThreadOrMany) {
  TetMesh m[2];
  refine_with_one_thread_or_many(m, 0.0, 0.1, &RefineStats::splits, 1000);
  RefineOptions bad;
  bad.num_threads = -1;
  EXPECT_EQ(refine_mesh(m[0], test::ConstantSizing(0.1), bad).status().code(), Error::InvalidArgument);
}

TEST(Refine, SizeScaleMakesItCoarser) {
  TetMesh fine = coupled_sphere(), coarse = coupled_sphere();
  RefineOptions o;
  Result<RefineStats> a = refine_mesh(fine, test::ConstantSizing(0.1), o);
  o.size_scale = 2.0;
  Result<RefineStats> b = refine_mesh(coarse, test::ConstantSizing(0.1), o);
  ASSERT_TRUE(a.ok() && b.ok());
  // Twice the length: about 8 times fewer tets; the layers along S bound the ratio.
  EXPECT_GT(a->tets_after, 4 * b->tets_after);
}

TEST(Refine, CoarsensWithoutTouchingSurface) {
  const SurfaceMesh s = test::icosphere(2);
  TetMesh mesh = coupled_sphere();
  RefineOptions o;
  o.check_each_pass = true;
  ASSERT_TRUE(refine_mesh(mesh, test::ConstantSizing(0.12), o).ok());
  Result<RefineStats> r = refine_mesh(mesh, test::ConstantSizing(0.35), o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->collapses, 100u);
  EXPECT_LT(r->vertices_after, r->vertices_before / 2);
  test::expect_surface_kept(s, mesh, "sphere coarsened");
  Status st = check_mesh(mesh);  // exact orientation of every tet, adjacency, protected flags
  EXPECT_TRUE(st.ok()) << st.message();
}

// Two free points within rounding of each other (as a recovery leaves on needle fans) where the
// size is far below every edge: max_collapse_result refuses every collapse there, and the pair
// stayed. degenerate_length collapses it, creating no edge longer than the ends' old ones.
TEST(Refine, CollapsesPointsWithinRoundingOfEachOtherWhereEveryEdgeIsTooLong) {
  for (double degenerate : {0.01, 0.0}) {
    SCOPED_TRACE(degenerate);
    TetMesh mesh = coupled_sphere();
    uint32_t v = 0;
    while (v < mesh.num_vertices() && (mesh.vflags[v] & vflag::kOnInputSurface)) ++v;
    ASSERT_LT(v, mesh.num_vertices());
    const double p[3] = {mesh.point(v)[0] + 1e-9, mesh.point(v)[1], mesh.point(v)[2]};
    const InsertResult ins = insert_point(mesh, p);
    ASSERT_TRUE(ins.ok());
    // The shortest edge at least `above` long.
    auto shortest_edge = [&](double above) {
      double shortest = INFINITY;
      for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_deleted(t) && !mesh.is_ghost(t))
          for (const auto& e : kEdgeVertex) {
            const double* a = mesh.point(mesh.vertex(t, e[0]));
            const double* b = mesh.point(mesh.vertex(t, e[1]));
            const double d = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
            if (d >= above) shortest = std::min(shortest, d);
          }
      return shortest;
    };
    ASSERT_LT(shortest_edge(0.0), 1e-8);
    const double before = shortest_edge(1e-8);
    RefineOptions o;
    o.split_length = 1e9;  // collapses only
    o.degenerate_length = degenerate;
    o.check_each_pass = true;
    Result<RefineStats> r = refine_mesh(mesh, test::ConstantSizing(0.01), o);  // every other edge ~30
    ASSERT_TRUE(r.ok()) << r.status().message();
    if (degenerate > 0.0) {
      EXPECT_EQ(r->collapses, 1u);
      EXPECT_GT(shortest_edge(0.0), before - 1e-9);  // the pair is gone, nothing shorter made
    } else {
      EXPECT_EQ(r->collapses, 0u);
      EXPECT_LT(shortest_edge(0.0), 1e-8);
    }
    test::expect_surface_kept(test::icosphere(2), mesh, "sphere");
    EXPECT_TRUE(check_mesh(mesh).ok());
  }
}

// The decimated knight's sliver triangles: the collapses next to them would connect their
// vertices by edges longer than max_collapse_result, yet no longer than the vertices' own edges
// of S, which no split shortens. collapse_to_s_edge_length lets them (beside adis16480's sliver
// triangles nearly every collapse was refused so, and the recovery's Steiner points stayed).
TEST(Refine, CollapsesUpToTheLongestEdgeOfSAtItsVertices) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok()) << s.status().message();
  Result<metric::MetricField> field = metric::surface_sizing_field(s.value(), MesherDefaults());
  ASSERT_TRUE(field.ok()) << field.status().message();
  RefineStats stats[2];
  for (int allow = 0; allow < 2; ++allow) {
    SCOPED_TRACE(allow);
    Result<CoupledMesh> c = test::coupled_mesh(s.value());
    ASSERT_TRUE(c.ok()) << c.status().message();
    RefineOptions o;
    o.collapse_to_s_edge_length = allow == 1;
    o.check_each_pass = true;
    Result<RefineStats> r = refine_mesh(c->mesh, field.value(), o);
    ASSERT_TRUE(r.ok()) << r.status().message();
    stats[allow] = r.value();
    test::expect_surface_kept(s.value(), c->mesh, "knight");
    EXPECT_TRUE(check_mesh(c->mesh).ok());
  }
  EXPECT_GT(stats[1].collapses, stats[0].collapses);
  EXPECT_LT(stats[1].vertices_after, stats[0].vertices_after);
}

// A size growing along x, for a mesh scaled by `scale`, a power of two: h(scale p) = scale h(p)
// exactly.
class GradedAlongX final : public SizingField {
 public:
  explicit GradedAlongX(double scale) : scale_(scale) {}
  void metric(const double p[3], double m[6]) const override {
    isotropic_metric(scale_ * (0.12 + 0.05 * (p[0] / scale_ + 1.0)), m);
  }

 private:
  double scale_;
};

// Scaled by a power of two, a mesh and its field are the same in floating point: refinement
// gives the same mesh, scaled (the sizes once came from pow(det M, -1/6), which moved split
// points by an ulp).
TEST(Refine, SameMeshScaledByAPowerOfTwo) {
  for (int e : {-20, 20}) {
    SCOPED_TRACE(e);
    TetMesh a = coupled_sphere(), b = coupled_sphere();
    for (double& c : b.xyz) c = std::ldexp(c, e);
    ASSERT_TRUE(refine_mesh(a, GradedAlongX(1.0), RefineOptions{}).ok());
    ASSERT_TRUE(refine_mesh(b, GradedAlongX(std::ldexp(1.0, e)), RefineOptions{}).ok());
    ASSERT_EQ(a.xyz.size(), b.xyz.size());
    size_t moved = 0;
    for (size_t k = 0; k < a.xyz.size(); ++k) moved += std::ldexp(a.xyz[k], e) != b.xyz[k];
    EXPECT_EQ(moved, 0u);
    EXPECT_EQ(a.tet_v, b.tet_v);
  }
}

TEST(Refine, KnightWithSurfaceSizing) {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  ASSERT_TRUE(s.ok()) << s.status().message();
  Result<CoupledMesh> c = test::coupled_mesh(s.value());
  ASSERT_TRUE(c.ok()) << c.status().message();
  RefineOptions o;
  o.check_each_pass = true;
  // The pipeline's default field: the paper's smoothed grid of the triangles' mean edge lengths.
  Result<metric::MetricField> field = metric::surface_sizing_field(s.value(), MesherDefaults());
  ASSERT_TRUE(field.ok()) << field.status().message();
  Result<RefineStats> r = refine_mesh(c->mesh, field.value(), o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  test::expect_surface_kept(s.value(), c->mesh, "knight");
  EXPECT_LT(r->passes, o.max_passes);
  EXPECT_NEAR(r->length_mean, 1.0, 0.15);
  // The decimated knight's own edges (kept) range widely, so its edges from S cannot all fit.
  EXPECT_GT(r->length_in_range, 0.7);
}

// The unit cube's coupled mesh refined with `o` in `field` (every pass checked), its surface
// kept; `before` is its vertex count before refinement. Callers return on a fatal failure.
static void refine_cube(const SurfaceMesh& s, const SizingField& field, RefineOptions o, const char* label,
                        TetMesh& mesh, size_t& before) {
  Result<CoupledMesh> c = test::coupled_mesh(s);
  ASSERT_TRUE(c.ok()) << c.status().message();
  mesh = std::move(c->mesh);
  before = mesh.num_vertices();
  o.check_each_pass = true;
  Result<RefineStats> r = refine_mesh(mesh, field, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  test::expect_surface_kept(s, mesh, label);
  ASSERT_GT(mesh.num_vertices(), before);
}

TEST(Refine, KeepsNewPointsOffSurfaceTrianglesMuchLargerThanTheSize) {
  // The unit cube in 12 triangles (1.4 long), size 0.25: each split of an edge running along a
  // face used to halve its distance to the face again (points 1e-10 from it, flat tets). New
  // points stay facet_clearance (0.2 h) away; without the guard they do not.
  const SurfaceMesh s = test::grid_cube(1);
  auto nearest_to_surface = [&](const TetMesh& m, size_t first) {
    double d = HUGE_VAL;
    for (size_t v = first; v < m.num_vertices(); ++v)
      for (size_t t = 0; t < s.num_triangles(); ++t)
        d = std::min(d, point_triangle_distance(m.point(v), s.point(s.tri[3 * t]), s.point(s.tri[3 * t + 1]),
                                                s.point(s.tri[3 * t + 2])));
    return d;
  };
  for (double clearance : {0.2, 0.0}) {
    SCOPED_TRACE(clearance);
    RefineOptions o;
    o.facet_clearance = clearance;
    TetMesh mesh;
    size_t before = 0;
    refine_cube(s, test::ConstantSizing(0.25), o, "cube h=0.25", mesh, before);
    if (HasFatalFailure()) return;
    const double d = nearest_to_surface(mesh, before);
    if (clearance > 0.0) EXPECT_GE(d, 0.2 * 0.25 * (1.0 - 1e-9));
    else EXPECT_LT(d, 0.1 * 0.25);  // without it, well inside the clearance
  }
}

// The same with an anisotropic metric, whose clearance is anisotropic_facet_clearance (0.5 in
// the metric): the cube's 12 triangles are 4 to 18 sizes across here, and points nearer them
// only made flat tets that the optimizer collapsed again (the UGAWG cube: 1550 of ~4400 points).
TEST(Refine, KeepsNewPointsHalfASizeOffCoarseSurfaceTrianglesInAnAnisotropicMetric) {
  const SurfaceMesh s = test::grid_cube(1);
  const double h[3] = {0.25, 0.25, 0.08};
  // The metric distance to the cube's faces: the normal distance over the size along the normal.
  auto nearest_in_metric = [&](const TetMesh& m, size_t first) {
    double d = HUGE_VAL;
    for (size_t v = first; v < m.num_vertices(); ++v)
      for (int k = 0; k < 3; ++k)
        d = std::min({d, m.point(uint32_t(v))[k] / h[k], (1.0 - m.point(uint32_t(v))[k]) / h[k]});
    return d;
  };
  for (double clearance : {RefineOptions{}.anisotropic_facet_clearance, 0.2}) {
    SCOPED_TRACE(clearance);
    RefineOptions o;
    o.anisotropic_facet_clearance = clearance;
    TetMesh mesh;
    size_t before = 0;
    refine_cube(s, test::AxisSizing(h[0], h[1], h[2]), o, "cube, anisotropic", mesh, before);
    if (HasFatalFailure()) return;
    const double d = nearest_in_metric(mesh, before);
    std::printf("anisotropic_facet_clearance %.2f: %zu points, the nearest %.3f from S in the metric\n", clearance,
                mesh.num_vertices() - before, d);
    if (clearance == 0.5) EXPECT_GE(d, 0.5 * (1.0 - 1e-9));
    else EXPECT_LT(d, 0.5);  // 0.2: points inside half a size
  }
}

TEST(Refine, RejectsBadOptionsAndGhosts) {
  TetMesh mesh = coupled_sphere();
  RefineOptions o;
  o.size_scale = 0.0;
  EXPECT_EQ(refine_mesh(mesh, test::ConstantSizing(0.2), o).status().code(), Error::InvalidArgument);
  o.size_scale = 1.0;
  o.split_length = 0.5;
  EXPECT_EQ(refine_mesh(mesh, test::ConstantSizing(0.2), o).status().code(), Error::InvalidArgument);
}

TEST(MeshOps, ReplaceTetsRefusesInvertedOrOpenResultsAndLeavesMeshAlone) {
  TetMesh mesh = coupled_sphere();
  meshops::VertexTets vt;
  vt.build(mesh);
  meshops::ReplaceScratch scratch;
  const TetMesh before = mesh;
  uint32_t t = 0;
  while (mesh.is_deleted(t)) ++t;
  const std::vector<uint32_t> old = {t};
  // The same tet reversed: negative.
  const meshops::TetVerts rev = {mesh.vertex(t, 1), mesh.vertex(t, 0), mesh.vertex(t, 2), mesh.vertex(t, 3)};
  EXPECT_FALSE(meshops::replace_tets(mesh, old, {rev}, vt, scratch));
  // Nothing: the old boundary is left open.
  EXPECT_FALSE(meshops::replace_tets(mesh, old, {}, vt, scratch));
  EXPECT_EQ(mesh.tet_v, before.tet_v);
  EXPECT_EQ(mesh.tet_adj, before.tet_adj);
  EXPECT_EQ(mesh.tet_flags, before.tet_flags);
  // The same tet again: accepted, the mesh still valid and S still protected.
  const meshops::TetVerts same = {mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3)};
  EXPECT_TRUE(meshops::replace_tets(mesh, old, {same}, vt, scratch));
  EXPECT_TRUE(check_mesh(mesh).ok());
  EXPECT_EQ(count_protected_facets(mesh), count_protected_facets(before));
}

// The ball without marks (what collapse trials use on several threads) is the marked one.
TEST(MeshOps, UnmarkedBallIsTheBall) {
  TetMesh mesh = coupled_sphere();
  ASSERT_TRUE(refine_mesh(mesh, test::ConstantSizing(0.12), RefineOptions{}).ok());
  meshops::VertexTets vt;
  vt.build(mesh);
  const std::vector<uint16_t> flags = mesh.tet_flags;
  std::vector<uint32_t> marked, unmarked;
  size_t compared = 0;
  for (uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    const uint32_t t = vt.known_tet(mesh, v);
    if (t == TetMesh::kNone) continue;
    meshops::vertex_ball(mesh, v, t, marked);
    ASSERT_TRUE(meshops::vertex_ball_unmarked(mesh, v, t, unmarked, 256));
    ASSERT_EQ(marked, unmarked) << "vertex " << v;
    EXPECT_EQ(meshops::vertex_ball_unmarked(mesh, v, t, unmarked, marked.size() - 1), false);
    ++compared;
  }
  EXPECT_GT(compared, 1000u);
  EXPECT_EQ(mesh.tet_flags, flags);  // no scratch mark left behind
}

// replacement_fits says what replace_tets would do, for collapses of every kind of edge with the
// kept end at its place or moved to the edge's midpoint (a move that may invert tets).
TEST(MeshOps, ReplacementFitsTellsWhatReplaceTetsDoes) {
  TetMesh mesh = coupled_sphere();
  ASSERT_TRUE(refine_mesh(mesh, test::ConstantSizing(0.15), RefineOptions{}).ok());
  meshops::VertexTets vt;
  vt.build(mesh);
  meshops::ReplaceScratch scratch;
  std::vector<uint32_t> old, ball_w;
  std::vector<meshops::TetVerts> fresh;
  size_t fits = 0, refused = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots() && fits + refused < 4000; t += 7) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    const uint32_t v = mesh.vertex(t, 0), w = mesh.vertex(t, 1);
    for (bool moves : {false, true}) {
      ASSERT_TRUE(meshops::collapse_tets(mesh, vt, v, vt.tet_of(mesh, v), w, moves, old, fresh, ball_w));
      double q[3];
      for (int k = 0; k < 3; ++k) q[k] = moves ? 0.5 * (mesh.point(v)[k] + mesh.point(w)[k]) : mesh.point(w)[k];
      const bool said = meshops::replacement_fits(mesh, old, fresh, scratch, meshops::ConstrainedEdges::kRefuse, w, q);
      TetMesh copy = mesh;
      std::copy_n(q, 3, &copy.xyz[3 * size_t(w)]);
      meshops::VertexTets copy_vt = vt;
      EXPECT_EQ(said, meshops::replace_tets(copy, old, fresh, copy_vt, scratch)) << "edge " << v << " " << w;
      (said ? fits : refused) += 1;
    }
  }
  // Both answers occur (collapses onto S's vertices are refused by the protected facets).
  EXPECT_GT(fits, 100u);
  EXPECT_GT(refused, 100u);
}

// The collapses are tried on every core, then made in order: coarsening gives the same mesh with
// one thread as with the default.
TEST(Refine, CoarseningIsTheSameWithOneThreadOrMany) {
  TetMesh m[2];
  refine_with_one_thread_or_many(m, 0.15, 0.4, &RefineStats::collapses, 100);
}

// The collapse trials (on every core, against the mesh as each block of edges starts) make the
// collapses that trying each edge in turn makes. Two threads for the trials (on one, they are
// skipped); small blocks, so that a pass has many.
TEST(Refine, CollapseTrialsMakeTheCollapsesOneByOneMakes) {
  TetMesh m[2] = {coupled_sphere(), coupled_sphere()};
  size_t collapses[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    RefineOptions o;
    ASSERT_TRUE(refine_mesh(m[k], test::ConstantSizing(0.15), o).ok());
    o.collapse_trials = k == 0;
    o.collapse_trial_block = 64;
    o.num_threads = 2;
    Result<RefineStats> r = refine_mesh(m[k], test::ConstantSizing(0.4), o);
    ASSERT_TRUE(r.ok()) << r.status().message();
    collapses[k] = r->collapses;
  }
  EXPECT_GT(collapses[0], 100u);
  EXPECT_EQ(collapses[0], collapses[1]);
  EXPECT_EQ(m[0].xyz, m[1].xyz);
  EXPECT_EQ(m[0].tet_v, m[1].tet_v);
}

TEST(MeshOps, ShapeQualityOfRegularAndFlatTets) {
  const double a[3] = {1, 1, 1}, b[3] = {1, -1, -1}, c[3] = {-1, 1, -1}, d[3] = {-1, -1, 1};
  EXPECT_NEAR(meshops::radius_ratio(b, a, c, d), 1.0, 1e-12);
  EXPECT_NEAR(meshops::shape_quality(b, a, c, d), 1.0, 1e-12);
  EXPECT_LT(meshops::shape_quality(a, b, c, d), 0.0);  // inverted
  const double e[3] = {0, 0, 1e-3};                     // a sliver: four points nearly on a plane
  const double f0[3] = {1, 0, 0}, f1[3] = {0, 1, 0}, f2[3] = {-1, 0, 0};
  EXPECT_LT(meshops::shape_quality(f0, f1, f2, e), 0.01);
}

using test::AxisSizing;

TEST(MeshOps, MetricShapeQualityAndMaxSize) {
  // The regular tet stretched by (0.5, 2, 0.01) is regular in the metric of those sizes.
  const double r[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  double p[4][3];
  for (int i = 0; i < 4; ++i) {
    p[i][0] = 0.5 * r[i][0];
    p[i][1] = 2.0 * r[i][1];
    p[i][2] = 0.01 * r[i][2];
  }
  double m[6];
  AxisSizing(0.5, 2.0, 0.01).metric(p[0], m);
  const meshops::MetricMap map = meshops::MetricMap::of(m);
  EXPECT_FALSE(map.identity);
  EXPECT_NEAR(meshops::metric_shape_quality(map, p[1], p[0], p[2], p[3]), 1.0, 1e-9);
  EXPECT_LT(meshops::shape_quality(p[1], p[0], p[2], p[3]), 0.05);
  EXPECT_NEAR(meshops::metric_max_size(m), 2.0, 1e-9);
  // Isotropic: the identity map, the Euclidean figure bit for bit.
  isotropic_metric(0.3, m);
  EXPECT_TRUE(meshops::MetricMap::of(m).identity);
  EXPECT_EQ(meshops::metric_shape_quality(meshops::MetricMap::of(m), p[1], p[0], p[2], p[3]),
            meshops::shape_quality(p[1], p[0], p[2], p[3]));
  EXPECT_NEAR(meshops::metric_max_size(m), 0.3, 1e-12);
  // A rotated metric (sizes 0.1, 0.4, 0.2 along rotated axes): the largest size is 0.4.
  const double c = std::cos(0.7), s = std::sin(0.7);
  const double e[3] = {1.0 / (0.1 * 0.1), 1.0 / (0.4 * 0.4), 1.0 / (0.2 * 0.2)};
  // R = rotation about z by 0.7: M = R diag(e) R^T.
  m[0] = c * c * e[0] + s * s * e[1];
  m[1] = c * s * (e[0] - e[1]);
  m[2] = s * s * e[0] + c * c * e[1];
  m[3] = 0.0;
  m[4] = 0.0;
  m[5] = e[2];
  EXPECT_NEAR(meshops::metric_max_size(m), 0.4, 1e-9);
}

// The box [0,1]^2 x [0,1] with the metric of sizes (0.25, 0.25, 0.04): the initial mesh is the
// Delaunay tetrahedralization of the box's boundary lattice points (spacing = the metric's
// sizes, so S's triangles are unit triangles in the metric, stretched in space); S = the hull
// facets. The metric kernel and the metric flips run, S is kept, and the lengths and metric shapes
// come out mostly right. (The full case with a varying metric is bench/aniso_cube.)
TEST(Refine, AnisotropicMetricKernelAndFlips) {
  const int n[3] = {4, 4, 25};
  std::vector<double> pts;
  TetMesh mesh = test::stretched_box_mesh(n, pts);
  const size_t protected_before = count_protected_facets(mesh);

  const AxisSizing field(0.25, 0.25, 0.04);
  RefineOptions o;
  o.check_each_pass = true;
  Result<RefineStats> r = refine_mesh(mesh, field, o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->splits, 100u);
  EXPECT_GT(r->metric_flips, 0u);
  EXPECT_EQ(count_protected_facets(mesh), protected_before);
  for (size_t v = 0; v < pts.size() / 3; ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mesh.point(uint32_t(v))[k], pts[3 * v + k]);
  EXPECT_TRUE(check_mesh(mesh).ok());
  EXPECT_GT(r->length_in_range, 0.8);  // measured 0.85 (Euclidean kernel: far lower)
  size_t tets = 0;
  const size_t bad = test::tets_below_in_metric(mesh, field, 0.1, &tets);
  EXPECT_LT(double(bad), 0.02 * double(tets)) << bad << " of " << tets;  // measured 0.9%
}

// order_for_locality: the same mesh (the same tets by their points, the same flags, protected
// facets and regions), valid, the vertices before first_vertex unmoved, no deleted slots left,
// and the vertices of each tet closer in id than refinement left them.
TEST(OrderForLocality, SameMeshCloserIds) {
  const SurfaceMesh s = test::icosphere(2);
  TetMesh mesh = coupled_sphere();
  const auto first = static_cast<uint32_t>(mesh.num_vertices());
  ASSERT_TRUE(refine_mesh(mesh, test::ConstantSizing(0.08)).ok());
  ASSERT_GT(mesh.num_vertices(), size_t(first) + 1000);
  // Each live tet as the sorted rows (point, vertex flags, protected facet opposite), then its
  // region and whether it has constrained edges; all tets sorted.
  auto tets_by_points = [](const TetMesh& m) {
    std::vector<std::vector<double>> out;
    for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
      if (m.is_deleted(t)) continue;
      std::vector<std::array<double, 4>> rows;
      for (int i = 0; i < 4; ++i) {
        const double* p = m.point(m.vertex(t, i));
        rows.push_back({p[0], p[1], p[2], double(m.vflags[m.vertex(t, i)]) + 256.0 * double((m.tet_flags[t] >> i) & 1u)});
      }
      std::sort(rows.begin(), rows.end());
      std::vector<double> flat;
      for (const auto& r : rows) flat.insert(flat.end(), r.begin(), r.end());
      flat.push_back(double(m.tet_region[t]));
      flat.push_back((m.tet_flags[t] & tflag::kEdgeConstrainedMask) ? 1.0 : 0.0);
      out.push_back(flat);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  auto mean_id_spread = [](const TetMesh& m) {
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
      if (m.is_deleted(t)) continue;
      const uint32_t* v = &m.tet_v[4 * size_t(t)];
      sum += double(*std::max_element(v, v + 4)) - double(*std::min_element(v, v + 4));
      ++n;
    }
    return sum / double(n);
  };
  for (size_t v = first; v < mesh.num_vertices(); v += 3) mesh.vflags[v] |= vflag::kLocked;  // flags to carry
  TetMesh before = mesh;
  order_for_locality(mesh, first);
  ASSERT_TRUE(check_mesh(mesh).ok()) << check_mesh(mesh).message();
  EXPECT_TRUE(mesh.free_tets.empty());
  EXPECT_EQ(mesh.num_tet_slots(), before.num_live_tets());
  EXPECT_EQ(mesh.num_vertices(), before.num_vertices());
  for (uint32_t v = 0; v < first; ++v) {
    EXPECT_EQ(mesh.vflags[v], before.vflags[v]);
    EXPECT_TRUE(std::equal(mesh.point(v), mesh.point(v) + 3, before.point(v))) << "vertex " << v;
  }
  EXPECT_EQ(count_protected_facets(mesh), count_protected_facets(before));
  EXPECT_TRUE(tets_by_points(mesh) == tets_by_points(before));
  test::expect_surface_kept(s, mesh, "sphere reordered");
  EXPECT_LT(mean_id_spread(mesh), 0.5 * mean_id_spread(before));
}
