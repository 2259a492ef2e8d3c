// The boundary layer's report (pipeline/bl_report.hpp) on a hand-built column: one wall triangle
// pushed once by a BL layer and once more by an ordinary layer.
#include <gtest/gtest.h>

#include <array>

#include "pipeline/bl_report.hpp"

namespace anitet {
namespace {

// Wall triangle 0 1 2 (patch 1) at z = 0, its BL copy 3 4 5 at z = 0.1 (region 1 tets) and the
// ordinary layer's copy 6 7 8 at z = 0.5 (region 0 tets): as a vertex that stopped in the second
// BL layer and was pushed by the front layer above.
TEST(BoundaryLayerReport, AnOrdinaryLayersPushIsNoBlLayer) {
  SurfaceMesh s;
  s.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.tri = {0, 1, 2};
  s.patch = {1};
  TetMesh mesh;
  for (double z : {0.0, 0.1, 0.5})
    for (int i = 0; i < 3; ++i) {
      const double p[3] = {s.xyz[3 * i], s.xyz[3 * i + 1], z};
      mesh.add_vertex(p);
    }
  std::vector<uint32_t> origin(9, TetMesh::kNone);
  for (uint32_t v = 3; v < 9; ++v) origin[v] = v - 3;
  for (uint32_t k = 0; k < 2; ++k) {
    const uint32_t a = 3 * k, b = a + 1, c = a + 2;
    mesh.new_tet(a, b, c, a + 3, k == 0 ? 1 : 0);
    mesh.new_tet(a + 3, b, c, b + 3, k == 0 ? 1 : 0);
    mesh.new_tet(a + 3, b + 3, c, c + 3, k == 0 ? 1 : 0);
  }
  BoundaryLayerOptions bl;
  bl.wall_patches = {1};
  bl.first_height = 0.1;
  bl.growth = 1.2;
  BoundaryLayerReport r;
  measure_boundary_layer(s, bl, /*layers=*/2, origin, mesh.xyz, mesh, /*first_bl_region=*/1, r);
  EXPECT_EQ(r.wall_vertices, 3u);
  EXPECT_EQ(r.full_columns, 0u);
  EXPECT_EQ(r.columns_reaching, (std::vector<size_t>{0, 3, 0}));
  EXPECT_EQ(r.column_layers, (std::vector<int>{1, 1, 1}));
  EXPECT_NEAR(r.column_total[0], 0.1, 1e-12);
  EXPECT_EQ(r.max_neighbour_growth, 0.0);
  // With the top copy in a BL tet too, the columns are full.
  for (uint32_t t = 3; t < 6; ++t) mesh.tet_region[t] = 1;
  BoundaryLayerReport full;
  measure_boundary_layer(s, bl, 2, origin, mesh.xyz, mesh, 1, full);
  EXPECT_EQ(full.full_columns, 3u);
  EXPECT_NEAR(full.column_total[0], 0.5, 1e-12);
}

}  // namespace
}  // namespace anitet
