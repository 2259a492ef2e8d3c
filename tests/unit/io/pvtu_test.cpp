// The pieces of anitet-mpi's .pvtu output: written, read back, joined; pieces that do not fit
// are refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/process_memory.hpp"
#include "io/pvtu_format.hpp"
#include "io/volume_io.hpp"

using namespace anitet;

namespace {

// Two tets sharing the facet of global vertices 1 2 3: piece 0 has tet 0 1 2 3 and piece 1 tet
// 1 2 3 4 (local numbering of their own); the outer facets are boundary triangles.
std::vector<VtuPiece> two_pieces() {
  const double x[5][3] = {{0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}};
  VtuPiece a, b;
  for (int v : {0, 1, 2, 3}) {
    a.xyz.insert(a.xyz.end(), x[v], x[v] + 3);
    a.node_id.push_back(v);
  }
  a.tet = {0, 1, 3, 2};
  a.region = {0};
  a.tet_id = {0};
  a.tri = {0, 1, 2, 0, 2, 3, 0, 3, 1};
  a.patch = {1, 1, 1};
  for (int v : {4, 3, 2, 1}) {
    b.xyz.insert(b.xyz.end(), x[v], x[v] + 3);
    b.node_id.push_back(v);
  }
  b.tet = {3, 2, 1, 0};
  b.region = {0};
  b.tet_id = {1};
  b.tri = {0, 1, 2, 0, 2, 3, 0, 3, 1};
  b.patch = {2, 2, 2};
  b.owner = 1;
  return {a, b};
}

// The writer checks a piece as every writer checks its mesh: a boundary triangle that is no face
// of the piece's tets (the interface facet 1 2 3 given by piece 0) or an index past its vertices
// is refused, and nothing is written.
TEST(Pvtu, PieceWhoseTrianglesAreNotItsFacesIsNotWritten) {
  const std::string path = ::testing::TempDir() + "/pv_bad.vtu";
  std::remove(path.c_str());
  VtuPiece p = two_pieces()[0];
  p.tri[3 * 2 + 0] = 1, p.tri[3 * 2 + 1] = 2, p.tri[3 * 2 + 2] = 3;  // 1 2 3 is a face: allowed
  ASSERT_TRUE(write_vtu_piece(path, p).ok());
  std::remove(path.c_str());
  p.tri = {0, 1, 2, 0, 2, 3, 0, 1, 1};  // a degenerate triangle, no face of the tet
  Status st = write_vtu_piece(path, p);
  EXPECT_EQ(st.code(), Error::InvalidMesh) << st.message();
  EXPECT_NE(st.message().find("not faces of the tetrahedra"), std::string::npos) << st.message();
  p.tri = {0, 1, 2, 0, 2, 3, 0, 3, 4};
  st = write_vtu_piece(path, p);
  EXPECT_EQ(st.code(), Error::BadIndex) << st.message();
  EXPECT_EQ(std::fopen(path.c_str(), "rb"), nullptr);
}

TEST(Pvtu, PiecesRoundTripAndJoin) {
  const std::string dir = ::testing::TempDir();
  std::vector<VtuPiece> pieces = two_pieces();
  ASSERT_TRUE(write_vtu_piece(dir + "/pv_0.vtu", pieces[0]).ok());
  ASSERT_TRUE(write_vtu_piece(dir + "/pv_1.vtu", pieces[1]).ok());
  ASSERT_TRUE(write_pvtu_index(dir + "/pv.pvtu", {"pv_0.vtu", "pv_1.vtu"}).ok());
  Result<std::vector<std::string>> paths = read_pvtu_index(dir + "/pv.pvtu");
  ASSERT_TRUE(paths.ok()) << paths.status().message();
  ASSERT_EQ(paths->size(), 2u);
  std::vector<VtuPiece> back;
  for (const std::string& p : paths.value()) {
    Result<VtuPiece> piece = read_vtu_piece(p);
    ASSERT_TRUE(piece.ok()) << piece.status().message();
    back.push_back(piece.value());
  }
  EXPECT_EQ(back[1].xyz, pieces[1].xyz);
  EXPECT_EQ(back[1].node_id, pieces[1].node_id);
  EXPECT_EQ(back[1].tet, pieces[1].tet);
  EXPECT_EQ(back[1].tri, pieces[1].tri);
  EXPECT_EQ(back[1].patch, pieces[1].patch);
  EXPECT_EQ(back[1].owner, 1);
  Result<VolumeMesh> joined = join_pieces(back);
  ASSERT_TRUE(joined.ok()) << joined.status().message();
  EXPECT_EQ(joined->num_vertices(), 5u);
  EXPECT_EQ(joined->num_tets(), 2u);
  EXPECT_EQ(joined->num_boundary_triangles(), 6u);
  EXPECT_TRUE(check_joined(joined.value()).ok()) << check_joined(joined.value()).message();
}

TEST(Pvtu, PiecesThatDoNotFitAreRefused) {
  std::vector<VtuPiece> moved = two_pieces();
  moved[1].xyz[3] += 1e-3;  // shared vertex 3 at two positions
  EXPECT_EQ(join_pieces(moved).status().code(), Error::InvalidMesh);
  std::vector<VtuPiece> twice = two_pieces();
  twice[1].tet_id = {0};  // two tets with one id
  EXPECT_EQ(join_pieces(twice).status().code(), Error::InvalidMesh);
  std::vector<VtuPiece> overlap = two_pieces();
  overlap.push_back(overlap[1]);  // a third tet on facet 1 2 3
  overlap[2].tet_id = {2};
  Result<VolumeMesh> joined = join_pieces(overlap);
  ASSERT_TRUE(joined.ok()) << joined.status().message();
  EXPECT_EQ(check_joined(joined.value()).code(), Error::InvalidMesh);
  std::vector<VtuPiece> gap = two_pieces();
  gap[1].tri.clear();  // piece 1's outer facets without boundary triangles
  gap[1].patch.clear();
  Result<VolumeMesh> open = join_pieces(gap);
  ASSERT_TRUE(open.ok());
  EXPECT_EQ(check_joined(open.value()).code(), Error::InvalidMesh);
}

// One reader serves both: a piece is a .vtu any tool reads, anitet's volume reader included.
TEST(Pvtu, APieceReadsAsAVtuVolumeMesh) {
  const std::string path = ::testing::TempDir() + "/pv_as_vtu.vtu";
  const VtuPiece p = two_pieces()[1];
  ASSERT_TRUE(write_vtu_piece(path, p).ok());
  Result<VolumeMesh> mesh = read_volume_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->xyz, p.xyz);
  EXPECT_EQ(mesh->tet, p.tet);
  EXPECT_EQ(mesh->bnd_tri, p.tri);
  EXPECT_EQ(mesh->bnd_patch, p.patch);
  EXPECT_EQ(mesh->region, p.region);
}

TEST(Pvtu, NotAnIndexIsAParseError) {
  const std::string path = ::testing::TempDir() + "/not.pvtu";
  ASSERT_TRUE(write_vtu_piece(path, two_pieces()[0]).ok());  // a piece, not an index
  EXPECT_EQ(read_pvtu_index(path).status().code(), Error::Parse);
}

}  // namespace

namespace {

// n^3 unit cubes, 6 tets each around the diagonal from (0,0,0) to (1,1,1): a conformal piece.
VtuPiece cube_grid_piece(uint32_t n) {
  VtuPiece p;
  auto id = [n](uint32_t i, uint32_t j, uint32_t k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (uint32_t k = 0; k <= n; ++k)
    for (uint32_t j = 0; j <= n; ++j)
      for (uint32_t i = 0; i <= n; ++i) {
        p.xyz.insert(p.xyz.end(), {double(i), double(j), double(k)});
        p.node_id.push_back(int64_t(p.node_id.size()));
      }
  const uint32_t steps[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i)
        for (const auto& step : steps) {
          uint32_t corner = 0;
          p.tet.push_back(id(i, j, k));
          for (uint32_t s : step) {
            corner |= s;
            p.tet.push_back(id(i + (corner & 1), j + (corner >> 1 & 1), k + (corner >> 2 & 1)));
          }
          p.region.push_back(1);
          p.tet_id.push_back(int64_t(p.tet_id.size()));
        }
  return p;
}

}  // namespace

// The writer streams a piece's arrays to the file instead of building the file in memory: it
// held 342 bytes per tet above the piece when it built the cell arrays, their copies and the
// whole file (31 after, the boundary check's face census), which made writing the largest
// rank's piece its peak (1,309 MB against 633 MB for the rounds: armadillo at 10^7 tets on 4
// ranks). The peak (VmHWM; each test runs in a process of its own under ctest) may rise by no
// more than 120 bytes per tet, and the piece reads back whole.
TEST(Pvtu, WritingAPieceHoldsLittleMoreThanThePiece) {
  const VtuPiece p = cube_grid_piece(40);  // 384,000 tets
  const std::string path = ::testing::TempDir() + "/pv_grid.vtu";
  const double before = peak_resident_bytes();
  if (before <= 0.0) GTEST_SKIP() << "no VmHWM on this system";
  ASSERT_TRUE(write_vtu_piece(path, p).ok());
  const double per_tet = (peak_resident_bytes() - before) / double(p.region.size());
  EXPECT_LT(per_tet, 120.0);
  Result<VtuPiece> back = read_vtu_piece(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->tet, p.tet);
  EXPECT_EQ(back->xyz, p.xyz);
  EXPECT_EQ(back->tet_id, p.tet_id);
  std::remove(path.c_str());
}
