// Binary Medit (GMF) .meshb / .solb: the UGAWG files against their ASCII twins, byte-exact round
// trips in versions 1 to 4, big-endian files, skipped keywords, and bad bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "io/gmf_format.hpp"
#include "io/sol_io.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

std::string ugawg(const std::string& file) { return std::string(ANITET_UGAWG_DIR) + "/" + file; }

// An independent GMF encoder (the layout of gmf_format.hpp's table) in either byte order.
class GmfBytes {
 public:
  GmfBytes(int version, bool big_endian) : version_(version), big_(big_endian) {
    i32(1);
    i32(version);
  }
  void i32(int32_t v) { put(&v, 4); }
  void integer(int64_t v) {
    if (version_ == 4) put(&v, 8);
    else i32(int32_t(v));
  }
  void real(double v) {
    if (version_ == 1) {
      const auto f = float(v);
      put(&f, 4);
    } else {
      put(&v, 8);
    }
  }
  void keyword(int32_t code) {
    if (last_ != std::string::npos) patch(last_);
    i32(code);
    last_ = bytes.size();
    if (version_ >= 3) put(&zero64_, 8);
    else i32(0);
  }
  std::string finish() {
    keyword(gmf::kEnd);
    return bytes;
  }
  std::string bytes;

 private:
  std::string word(const void* p, size_t n) const {
    std::string w(static_cast<const char*>(p), n);
    if (big_) std::reverse(w.begin(), w.end());
    return w;
  }
  void put(const void* p, size_t n) { bytes += word(p, n); }
  void patch(size_t at) {
    const int64_t pos = int64_t(bytes.size());
    const auto pos32 = int32_t(pos);
    bytes.replace(at, version_ >= 3 ? 8 : 4, version_ >= 3 ? word(&pos, 8) : word(&pos32, 4));
  }
  int version_;
  bool big_;
  size_t last_ = std::string::npos;
  int64_t zero64_ = 0;
};

// The test box (io_test_util.hpp) as a .meshb (vertex refs 0 1 0 1 ...), with a Corners keyword
// before Tetrahedra when asked.
std::string box_meshb(int version, bool big_endian, bool with_corners = false) {
  GmfBytes g(version, big_endian);
  g.keyword(gmf::kDimension);
  g.i32(3);
  g.keyword(gmf::kVertices);
  g.integer(8);
  for (int v = 0; v < 8; ++v) {
    for (int k = 0; k < 3; ++k) g.real(test::box_coord(v, k));
    g.integer(v % 2);
  }
  g.keyword(gmf::kTriangles);
  g.integer(12);
  for (size_t t = 0; t < 12; ++t) {
    for (int k = 0; k < 3; ++k) g.integer(test::kBoxTris[3 * t + size_t(k)] + 1);
    g.integer(test::kBoxPatches[t]);
  }
  if (with_corners) {  // Corners (13): vertex indices, skipped by the reader
    g.keyword(13);
    g.integer(2);
    g.integer(1);
    g.integer(8);
  }
  g.keyword(gmf::kTetrahedra);
  g.integer(6);
  for (size_t t = 0; t < 6; ++t) {
    for (int k = 0; k < 4; ++k) g.integer(test::kBoxTets[4 * t + size_t(k)] + 1);
    g.integer(test::kBoxRegions[t]);
  }
  return g.finish();
}

void expect_box(const VolumeMesh& m, int version) {
  ASSERT_EQ(m.num_vertices(), 8u);
  for (int v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) {
      const double want = version == 1 ? double(float(test::box_coord(v, k))) : test::box_coord(v, k);
      EXPECT_TRUE(test::same_bits(m.xyz[3 * size_t(v) + size_t(k)], want)) << v << " " << k;
    }
  EXPECT_EQ(m.tet, test::kBoxTets);
  EXPECT_EQ(m.region, test::kBoxRegions);
  EXPECT_EQ(m.bnd_tri, test::kBoxTris);
  EXPECT_EQ(m.bnd_patch, test::kBoxPatches);
}

TEST(Gmf, UgawgCubeMatchesItsAsciiTwin) {
  Result<VolumeMesh> ascii = read_volume_mesh(ugawg("cube-linear-00.mesh"));
  ASSERT_TRUE(ascii.ok()) << ascii.status().message();
  GmfFileInfo info;
  Result<VolumeMesh> binary = read_meshb_volume(test::load(ugawg("cube-linear-00.meshb")), "cube.meshb", &info);
  ASSERT_TRUE(binary.ok()) << binary.status().message();
  EXPECT_EQ(info.version, 2);
  EXPECT_FALSE(info.big_endian);
  EXPECT_TRUE(info.skipped.empty());
  EXPECT_EQ(binary->num_vertices(), 64u);
  EXPECT_EQ(binary->num_tets(), 162u);
  EXPECT_EQ(binary->num_boundary_triangles(), 108u);
  EXPECT_EQ(binary->tet, ascii->tet);
  EXPECT_EQ(binary->region, ascii->region);
  EXPECT_EQ(binary->bnd_tri, ascii->bnd_tri);
  EXPECT_EQ(binary->bnd_patch, ascii->bnd_patch);
  ASSERT_EQ(binary->xyz.size(), ascii->xyz.size());
  // The .mesh prints 15 significant digits (0.333333333333333).
  for (size_t i = 0; i < binary->xyz.size(); ++i) EXPECT_NEAR(binary->xyz[i], ascii->xyz[i], 1e-15) << i;
  // Through the path readers too (volume and surface).
  Result<VolumeMesh> by_path = read_volume_mesh(ugawg("cube-linear-00.meshb"));
  ASSERT_TRUE(by_path.ok()) << by_path.status().message();
  EXPECT_EQ(by_path->xyz, binary->xyz);
  Result<SurfaceMesh> surface = read_surface(ugawg("cube-linear-00.meshb"));
  ASSERT_TRUE(surface.ok()) << surface.status().message();
  EXPECT_EQ(surface->tri, ascii->bnd_tri);
  EXPECT_EQ(surface->patch, ascii->bnd_patch);
}

TEST(Gmf, UgawgSolbMatchesItsAsciiTwin) {
  Result<VertexFields> ascii = read_vertex_fields(ugawg("cube-linear-00.sol"));
  ASSERT_TRUE(ascii.ok()) << ascii.status().message();
  GmfFileInfo info;
  Result<VertexFields> binary = read_vertex_fields(ugawg("cube-linear-00.solb"), &info);
  ASSERT_TRUE(binary.ok()) << binary.status().message();
  EXPECT_EQ(info.version, 2);
  ASSERT_EQ(binary->kinds, std::vector<FieldKind>{FieldKind::SymTensor});
  EXPECT_EQ(ascii->kinds, binary->kinds);
  ASSERT_EQ(binary->values.size(), 64u * 6u);
  ASSERT_EQ(ascii->values.size(), binary->values.size());
  // The .sol prints 16 significant digits: the same values to the last bit but one.
  for (size_t i = 0; i < ascii->values.size(); ++i) {
    EXPECT_NEAR(binary->values[i], ascii->values[i], 4e-16 * std::abs(ascii->values[i])) << i;
  }
}

TEST(Gmf, UgawgFilesRoundTripToTheSameBytes) {
  const std::string mesh_bytes = test::load(ugawg("cube-linear-00.meshb"));
  Result<VolumeMesh> mesh = read_meshb_volume(mesh_bytes, "cube.meshb");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  Result<std::string> again = to_meshb(mesh.value(), 2);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_TRUE(again.value() == mesh_bytes);
  EXPECT_TRUE(to_meshb(mesh.value()).value() == mesh_bytes);  // automatic: version 2
  Result<GmfMesh> gmf = read_gmf_mesh(mesh_bytes, "cube.meshb");
  ASSERT_TRUE(gmf.ok());
  EXPECT_TRUE(to_gmf_mesh(gmf.value(), 2).value() == mesh_bytes);
  // Written through write_volume_mesh.
  const std::string path = test::temp_dir() + "/cube.meshb";
  ASSERT_TRUE(write_volume_mesh(mesh.value(), path).ok());
  EXPECT_TRUE(test::load(path) == mesh_bytes);

  const std::string sol_bytes = test::load(ugawg("cube-linear-00.solb"));
  Result<VertexFields> sol = read_solb(sol_bytes, "cube.solb");
  ASSERT_TRUE(sol.ok()) << sol.status().message();
  EXPECT_TRUE(to_solb(sol.value(), 2).value() == sol_bytes);
  const std::string sol_path = test::temp_dir() + "/cube.solb";
  ASSERT_TRUE(write_vertex_fields(sol.value(), sol_path).ok());
  EXPECT_TRUE(test::load(sol_path) == sol_bytes);
}

TEST(Gmf, EveryVersionAndByteOrderIsRead) {
  for (int version = 1; version <= 4; ++version) {
    for (bool big : {false, true}) {
      SCOPED_TRACE("version " + std::to_string(version) + (big ? " big-endian" : " little-endian"));
      const std::string bytes = box_meshb(version, big);
      GmfFileInfo info;
      Result<VolumeMesh> m = read_meshb_volume(bytes, "box.meshb", &info);
      ASSERT_TRUE(m.ok()) << m.status().message();
      EXPECT_EQ(info.version, version);
      EXPECT_EQ(info.big_endian, big);
      expect_box(m.value(), version);
      Result<GmfMesh> gmf = read_gmf_mesh(bytes, "box.meshb");
      ASSERT_TRUE(gmf.ok());
      EXPECT_EQ(gmf->vertex_ref, (std::vector<int32_t>{0, 1, 0, 1, 0, 1, 0, 1}));
      // Written again in the version read: the independent encoder's little-endian bytes.
      Result<std::string> again = to_gmf_mesh(gmf.value(), version);
      ASSERT_TRUE(again.ok()) << again.status().message();
      EXPECT_TRUE(again.value() == box_meshb(version, false));
    }
  }
}

// Every version written by anitet, read back, written again: the same bytes, the same values
// (bit for bit from version 2; version 1 holds floats).
TEST(Gmf, VolumeMeshRoundTripsInEveryVersion) {
  VolumeMesh mesh;
  mesh.xyz = test::box_xyz();
  mesh.xyz[0] = 0.1;  // not a float
  mesh.xyz[5] = -1.0 / 3.0;
  mesh.tet = test::kBoxTets;
  mesh.region = test::kBoxRegions;
  mesh.bnd_tri = test::kBoxTris;
  mesh.bnd_patch = test::kBoxPatches;
  for (int version = 1; version <= 4; ++version) {
    SCOPED_TRACE("version " + std::to_string(version));
    Result<std::string> bytes = to_meshb(mesh, version);
    ASSERT_TRUE(bytes.ok()) << bytes.status().message();
    GmfFileInfo info;
    Result<VolumeMesh> back = read_meshb_volume(bytes.value(), "m.meshb", &info);
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(info.version, version);
    for (size_t i = 0; i < mesh.xyz.size(); ++i) {
      const double want = version == 1 ? double(float(mesh.xyz[i])) : mesh.xyz[i];
      EXPECT_TRUE(test::same_bits(back->xyz[i], want)) << i;
    }
    EXPECT_EQ(back->tet, mesh.tet);
    EXPECT_EQ(back->region, mesh.region);
    EXPECT_EQ(back->bnd_tri, mesh.bnd_tri);
    EXPECT_EQ(back->bnd_patch, mesh.bnd_patch);
    EXPECT_TRUE(to_meshb(back.value(), version).value() == bytes.value());
  }
  // Regions left empty are written as 0.
  mesh.region.clear();
  Result<VolumeMesh> back = read_meshb_volume(to_meshb(mesh).value(), "m.meshb");
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->region, std::vector<int32_t>(6, 0));
}

TEST(Gmf, SolbWithSeveralFieldsRoundTripsInEveryVersion) {
  VertexFields f;
  f.kinds = {FieldKind::Scalar, FieldKind::Vector, FieldKind::SymTensor, FieldKind::Scalar};
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  f.values.resize(5 * f.record_size());
  for (double& x : f.values) x = u(rng);
  for (int version = 1; version <= 4; ++version) {
    SCOPED_TRACE("version " + std::to_string(version));
    Result<std::string> bytes = to_solb(f, version);
    ASSERT_TRUE(bytes.ok()) << bytes.status().message();
    GmfFileInfo info;
    Result<VertexFields> back = read_solb(bytes.value(), "f.solb", &info);
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(info.version, version);
    EXPECT_EQ(back->kinds, f.kinds);
    ASSERT_EQ(back->values.size(), f.values.size());
    for (size_t i = 0; i < f.values.size(); ++i) {
      const double want = version == 1 ? double(float(f.values[i])) : f.values[i];
      EXPECT_TRUE(test::same_bits(back->values[i], want)) << i;
    }
    EXPECT_TRUE(to_solb(back.value(), version).value() == bytes.value());
  }
  // The same fields through the ASCII .sol, bit for bit.
  Result<std::string> text = to_sol(f);
  ASSERT_TRUE(text.ok());
  EXPECT_NE(text->find("SolAtVertices\n5\n4 1 2 3 1\n"), std::string::npos) << text.value();
  Result<VertexFields> back = read_medit_sol(text.value(), "f.sol");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->kinds, f.kinds);
  for (size_t i = 0; i < f.values.size(); ++i) EXPECT_TRUE(test::same_bits(back->values[i], f.values[i])) << i;
}

TEST(Gmf, UnknownKeywordsAreSkippedAndListed) {
  for (int version : {2, 4}) {
    GmfFileInfo info;
    Result<VolumeMesh> m = read_meshb_volume(box_meshb(version, true, true), "c.meshb", &info);
    ASSERT_TRUE(m.ok()) << m.status().message();
    expect_box(m.value(), version);
    EXPECT_EQ(info.skipped, std::vector<int32_t>{13});
  }
  // A mesh file read as a solution has no SolAtVertices; a solution read as a mesh has no tets.
  EXPECT_EQ(read_solb(box_meshb(2, false), "b.solb").status().code(), Error::EmptyInput);
  VertexFields f = VertexFields::single(FieldKind::Scalar, {1.0, 2.0});
  EXPECT_EQ(read_meshb_volume(to_solb(f).value(), "f.meshb").status().code(), Error::EmptyInput);
}

TEST(Gmf, BadFilesGetErrorsNamingTheOffset) {
  const std::string good = box_meshb(2, false);
  auto code = [](const std::string& bytes) { return read_meshb_volume(bytes, "bad.meshb").status(); };
  Status s = code("MeshVersionFormatted 2\nDimension 3\n");
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find("ASCII"), std::string::npos) << s.message();
  std::string bad = good;
  bad[4] = 7;  // version 7
  EXPECT_EQ(code(bad).code(), Error::UnsupportedFormat);
  bad = good;
  bad[16] = 2;  // Dimension 2
  EXPECT_EQ(code(bad).code(), Error::UnsupportedFormat);
  bad = good;
  bad[13] = 0x7f;  // the next keyword's position beyond the file
  s = code(bad);
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find("bad.meshb: byte offset 12:"), std::string::npos) << s.message();
  // A vertex count too large for the keyword's room.
  bad = good;
  bad[28] = 9;
  s = code(bad);
  EXPECT_EQ(s.code(), Error::Parse);
  EXPECT_NE(s.message().find("do not fit"), std::string::npos) << s.message();
  // A triangle index beyond the vertices.
  GmfMesh m = read_gmf_mesh(good, "g").value();
  m.tri[0] = 8;
  EXPECT_EQ(to_gmf_mesh(m).status().code(), Error::BadIndex);
  bad = good;
  const size_t first_triangle = 8 + 12 + 12 + 8 * 28 + 12;
  bad[first_triangle] = 9;
  s = code(bad);
  EXPECT_EQ(s.code(), Error::BadIndex);
  EXPECT_NE(s.message().find("triangle 1"), std::string::npos) << s.message();
  // Writers: versions and limits.
  EXPECT_EQ(to_meshb(read_meshb_volume(good, "g").value(), 5).status().code(), Error::InvalidArgument);
  EXPECT_EQ(to_solb(VertexFields(), 2).status().code(), Error::InvalidArgument);
}

// Every truncation and random byte edits: an error with the file's name or a consistent mesh.
TEST(Gmf, TruncatedAndMutatedFilesNeverCrash) {
  std::vector<std::string> files;
  for (int version = 1; version <= 4; ++version) files.push_back(box_meshb(version, version % 2 == 0, true));
  VertexFields f;
  f.kinds = {FieldKind::Vector, FieldKind::SymTensor};
  f.values.assign(3 * 9, 0.5);
  files.push_back(to_solb(f, 3).value());
  auto check = [](const std::string& bytes) {
    Result<VolumeMesh> m = read_meshb_volume(bytes, "fuzzed");
    if (m.ok()) {
      EXPECT_TRUE(check_volume_arrays(m.value()).ok());
    } else {
      EXPECT_NE(m.status().message().find("fuzzed"), std::string::npos) << m.status().message();
    }
    Result<VertexFields> s = read_solb(bytes, "fuzzed");
    if (s.ok()) {
      EXPECT_EQ(s->values.size() % s->record_size(), 0u);
    } else {
      EXPECT_NE(s.status().message().find("fuzzed"), std::string::npos) << s.status().message();
    }
  };
  for (const std::string& file : files) {
    for (size_t size = 0; size < file.size(); ++size) check(file.substr(0, size));
  }
  std::mt19937 rng(4646);
  for (int round = 0; round < 3000; ++round) {
    std::string bytes = files[size_t(round) % files.size()];
    for (int e = 0; e < 1 + int(rng() % 3); ++e) {
      const size_t at = rng() % bytes.size();
      switch (rng() % 3) {
        case 0: bytes[at] = char(rng()); break;
        case 1: {  // a word made extreme
          const int32_t extremes[] = {0, -1, INT32_MAX, INT32_MIN, 1 << 24};
          const int32_t v = extremes[rng() % 5];
          std::memcpy(&bytes[std::min(at, bytes.size() - 4)], &v, 4);
          break;
        }
        default: bytes.erase(at, rng() % 16); break;
      }
      if (bytes.size() < 8) break;
    }
    check(bytes);
    if (HasFailure()) return;
  }
}

// A Dimension 2 .sol (the 2D mesher's fields): read with its own component counts and written
// back the same; the by-extension reader, which feeds 3D meshes, refuses it by name.
TEST(Gmf, TwoDimensionalSolIsReadButNotForThreeDimensions) {
  const std::string text = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n2 1 3\n0.5 1 0 2\n0.25 3 0.5 4\nEnd\n";
  Result<VertexFields> f = read_medit_sol(text, "f2.sol");
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(f->dimension, 2);
  EXPECT_EQ(f->record_size(), 4u);
  EXPECT_EQ(f->num_vertices(), 2u);
  EXPECT_EQ(f->offset(1), 1u);
  EXPECT_EQ(f->values[7], 4.0);
  Result<std::string> back = to_sol(f.value());
  ASSERT_TRUE(back.ok());
  EXPECT_NE(back->find("Dimension 2\n"), std::string::npos) << back.value();
  EXPECT_EQ(read_medit_sol(back.value(), "b.sol").value().values, f->values);
  EXPECT_EQ(read_medit_sol("Dimension 4\n", "d.sol").status().code(), Error::UnsupportedFormat);
  const std::string path = test::temp_dir() + "/f2.sol";
  ASSERT_TRUE(write_vertex_fields(f.value(), path).ok());
  Status s = read_vertex_fields(path).status();
  EXPECT_EQ(s.code(), Error::UnsupportedFormat);
  EXPECT_NE(s.message().find("Dimension 2"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace anitet
