#include <gtest/gtest.h>

#include "core/tet_mesh.hpp"
#include "predicates/predicates.hpp"

using namespace anitet;

namespace {

// A unit cube split into 6 positive tets around the diagonal 0-6.
TetMesh cube_mesh() {
  TetMesh m;
  const double p[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (auto& q : p) m.add_vertex(q);
  const uint32_t ring[6] = {1, 2, 3, 7, 4, 5};  // the cycle of vertices around the diagonal 0-6
  for (int k = 0; k < 6; ++k) {
    uint32_t a = ring[k], b = ring[(k + 1) % 6];
    uint32_t t = m.new_tet(0, a, b, 6);
    if (predicates::orient3d(m.point(0), m.point(a), m.point(b), m.point(6)) < 0) {
      m.tet_v[4 * t + 1] = b;
      m.tet_v[4 * t + 2] = a;
    }
  }
  return m;
}

}  // namespace

TEST(TetMesh, FacetTableFacesInward) {
  TetMesh m;
  const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto& q : p) m.add_vertex(q);
  ASSERT_GT(predicates::orient3d(p[0], p[1], p[2], p[3]), 0);
  for (int i = 0; i < 4; ++i)
    EXPECT_GT(predicates::orient3d(p[kFacetVertex[i][0]], p[kFacetVertex[i][1]], p[kFacetVertex[i][2]], p[i]), 0)
        << "facet " << i;
}

TEST(TetMesh, BuildAdjacencyAndCheck) {
  TetMesh m = cube_mesh();
  ASSERT_TRUE(m.build_adjacency().ok());
  Status s = check_mesh(m, {});
  EXPECT_TRUE(s.ok()) << s.message();
  // 6 tets, 24 facets: 6 interior facets matched twice, 12 on the cube's surface.
  size_t open = 0;
  size_t none = 0;
  for (uint32_t a : m.tet_adj) open += (a == TetMesh::kNoNeighbour);
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    for (int i = 0; i < 4; ++i) none += m.neighbour(t, i) == TetMesh::kNone;
  EXPECT_EQ(open, 12u);
  // Across an open facet there is no tet (kNone), not the tet id the packed value would give.
  EXPECT_EQ(none, 12u);
  EXPECT_FALSE(check_mesh(m, {false, true}).ok()) << "require_closed must see the open facets";
}

TEST(TetMesh, CheckFindsInvertedTet) {
  TetMesh m = cube_mesh();
  std::swap(m.tet_v[1], m.tet_v[2]);
  ASSERT_TRUE(m.build_adjacency().ok());
  Status s = check_mesh(m, {});
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("not positively oriented"), std::string::npos) << s.message();
}

TEST(TetMesh, CheckFindsAsymmetricAdjacency) {
  TetMesh m = cube_mesh();
  ASSERT_TRUE(m.build_adjacency().ok());
  for (int i = 0; i < 4; ++i)
    if (m.tet_adj[i] != TetMesh::kNoNeighbour) {
      m.tet_adj[i] = TetMesh::kNoNeighbour;
      break;
    }
  EXPECT_FALSE(check_mesh(m, {}).ok());
}

TEST(TetMesh, CheckFindsOneSidedProtection) {
  TetMesh m = cube_mesh();
  ASSERT_TRUE(m.build_adjacency().ok());
  for (int i = 0; i < 4; ++i)
    if (m.tet_adj[i] != TetMesh::kNoNeighbour) {
      m.set_facet_protected(0, i, true);
      break;
    }
  Status s = check_mesh(m, {});
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("protected on one side"), std::string::npos) << s.message();
}

TEST(TetMesh, RejectsFacetSharedByThreeTets) {
  TetMesh m;
  const double p[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 2}};
  for (auto& q : p) m.add_vertex(q);
  m.new_tet(0, 1, 2, 3);
  m.new_tet(0, 1, 2, 4);  // overlaps the first: facet 012 is now claimed three times below
  m.new_tet(0, 2, 1, 3);
  EXPECT_EQ(m.build_adjacency().code(), Error::InvalidMesh);
}

TEST(TetMesh, ReportsTheFirstFacetSharedByThreeTetsInVertexOrder) {
  // Two such facets, on vertices 9000.. and 100..: the groups are paired in chunks on every
  // core, and the error named is the one a single loop over the vertices meets first.
  TetMesh m;
  for (int v = 0; v < 9010; ++v) {
    const double q[3] = {double(v), double(v % 7), double(v % 11)};
    m.add_vertex(q);
  }
  for (uint32_t b : {9000u, 100u}) {
    m.new_tet(b, b + 1, b + 2, b + 3);
    m.new_tet(b, b + 1, b + 2, b + 4);
    m.new_tet(b, b + 2, b + 1, b + 5);
  }
  const Status s = m.build_adjacency();
  EXPECT_EQ(s.code(), Error::InvalidMesh);
  EXPECT_NE(s.message().find("facet (100, 101, 102)"), std::string::npos) << s.message();
}

TEST(TetMesh, RejectsAVertexThatDoesNotExist) {
  TetMesh m;
  const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto& q : p) m.add_vertex(q);
  m.new_tet(0, 1, 2, 3);
  m.new_tet(4, 5, 6, 7);
  const Status s = m.build_adjacency();
  EXPECT_EQ(s.code(), Error::InvalidMesh);
  EXPECT_NE(s.message().find("tet 1 refers to vertex"), std::string::npos) << s.message();
}

TEST(TetMesh, FreeListReusesSlotsAndExportSkipsThem) {
  TetMesh m = cube_mesh();
  m.delete_tet(2);
  EXPECT_EQ(m.num_live_tets(), 5u);
  ASSERT_TRUE(m.build_adjacency().ok());
  EXPECT_TRUE(check_mesh(m, {}).ok());
  VolumeMesh v = m.to_volume_mesh();
  EXPECT_EQ(v.num_tets(), 5u);
  uint32_t t = m.new_tet(0, 1, 2, 6);
  EXPECT_EQ(t, 2u) << "a deleted slot is reused first";
  EXPECT_EQ(m.num_live_tets(), 6u);
}

TEST(TetMesh, VolumeMeshRoundTrip) {
  TetMesh m = cube_mesh();
  VolumeMesh v = m.to_volume_mesh();
  ASSERT_EQ(v.num_vertices(), 8u);
  TetMesh back = TetMesh::from_volume_mesh(v);
  ASSERT_TRUE(back.build_adjacency().ok());
  EXPECT_TRUE(check_mesh(back, {}).ok());
  EXPECT_EQ(back.num_live_tets(), 6u);
}

// take_volume_mesh compacts the mesh's own arrays in place: the same VolumeMesh as
// to_volume_mesh, deleted slots, ghosts and unused vertices dropped, the boundary renumbered.
TEST(TetMesh, TakeVolumeMeshGivesWhatToVolumeMeshGives) {
  TetMesh m = cube_mesh();
  const double far[3] = {5, 5, 5}, unused[3] = {9, 9, 9};
  m.add_vertex(unused);  // vertex 8: in no tet, dropped
  const uint32_t g = m.add_vertex(far);  // vertex 9: only in the ghost-free tet below
  m.tet_region[1] = 7;
  m.delete_tet(2);
  m.new_tet(0, 1, 5, TetMesh::kGhost);  // reuses slot 2: a ghost, not exported
  const uint32_t apex = m.new_tet(1, 2, 6, g, 3);  // slot 6
  if (predicates::orient3d(m.point(1), m.point(2), m.point(6), m.point(g)) < 0) std::swap(m.tet_v[4 * apex + 1], m.tet_v[4 * apex + 2]);
  m.delete_tet(4);
  const std::vector<uint32_t> bnd_tri = {0, 1, 9, 1, 2, 6};
  const std::vector<int32_t> bnd_patch = {4, 5};
  std::vector<uint32_t> map_copy, map_taken;
  const VolumeMesh copy = m.to_volume_mesh(true, bnd_tri, bnd_patch, &map_copy);
  const VolumeMesh taken = m.take_volume_mesh(true, bnd_tri, bnd_patch, &map_taken);
  EXPECT_EQ(copy.num_tets(), 5u);  // 6 - 1 deleted + 1 new; the ghost not exported
  EXPECT_EQ(copy.num_vertices(), 9u);  // the unused vertex dropped
  EXPECT_EQ(taken.xyz, copy.xyz);
  EXPECT_EQ(taken.tet, copy.tet);
  EXPECT_EQ(taken.region, copy.region);
  EXPECT_EQ(taken.bnd_tri, copy.bnd_tri);
  EXPECT_EQ(taken.bnd_patch, copy.bnd_patch);
  EXPECT_EQ(map_taken, map_copy);
  EXPECT_EQ(m.num_vertices(), 0u);
  EXPECT_EQ(m.num_tet_slots(), 0u);
}
