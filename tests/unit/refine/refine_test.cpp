// Refinement/coarsening on coupled meshes: S is kept (every input triangle stays a protected
// facet, no vertex of S moves), the mesh stays valid after every pass (check_each_pass), and the
// normalized edge lengths converge to [1/sqrt2, sqrt2].
#include <gtest/gtest.h>

#include <string>

#include "io/surface_io.hpp"
#include "layers/shapes.hpp"
#include "metric/surface_sizing.hpp"
#include "refine/coupled_fixture.hpp"
#include "refine/mesh_ops.hpp"
#include "refine/refine.hpp"

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

TEST(MeshOps, ShapeQualityOfRegularAndFlatTets) {
  const double a[3] = {1, 1, 1}, b[3] = {1, -1, -1}, c[3] = {-1, 1, -1}, d[3] = {-1, -1, 1};
  EXPECT_NEAR(meshops::radius_ratio(b, a, c, d), 1.0, 1e-12);
  EXPECT_NEAR(meshops::shape_quality(b, a, c, d), 1.0, 1e-12);
  EXPECT_LT(meshops::shape_quality(a, b, c, d), 0.0);  // inverted
  const double e[3] = {0, 0, 1e-3};                     // a sliver: four points nearly on a plane
  const double f0[3] = {1, 0, 0}, f1[3] = {0, 1, 0}, f2[3] = {-1, 0, 0};
  EXPECT_LT(meshops::shape_quality(f0, f1, f2, e), 0.01);
}
