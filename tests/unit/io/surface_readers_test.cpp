// Each surface reader on the small box files of tests/data/io and on hand-made inputs.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "io/surface_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

using test::box_coord;
using test::io_data;
using test::kBoxPatches;
using test::kBoxTris;
using test::load;

Result<SurfaceMesh> read_box(const std::string& file) { return read_surface(io_data(file)); }

// Corner k of triangle t has the coordinates of box vertex kBoxTris[3t+k] (after `round`).
template <class Round>
void expect_box_triangles(const SurfaceMesh& mesh, Round round) {
  ASSERT_EQ(mesh.num_triangles(), 12u);
  ASSERT_EQ(mesh.patch.size(), 12u);
  for (size_t t = 0; t < 12; ++t) {
    for (int k = 0; k < 3; ++k) {
      const double* p = mesh.point(mesh.tri[3 * t + k]);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(p[c], round(box_coord(static_cast<int>(kBoxTris[3 * t + k]), c)))
            << "triangle " << t << " corner " << k;
      }
    }
  }
}
void expect_box_triangles(const SurfaceMesh& mesh) {
  expect_box_triangles(mesh, [](double v) { return v; });
}

void expect_box_vertices(const SurfaceMesh& mesh) {
  ASSERT_EQ(mesh.num_vertices(), 8u);
  EXPECT_EQ(mesh.xyz, test::box_xyz());
}

TEST(OffReader, QuadsCommentsAndHeaderOnItsOwnLine) {
  Result<SurfaceMesh> mesh = read_box("box_quads.off");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  ASSERT_EQ(mesh->num_triangles(), 12u);
  // Quad (0 4 6 2) becomes the fan (0 4 6), (0 6 2).
  EXPECT_EQ(std::vector<uint32_t>(mesh->tri.begin(), mesh->tri.begin() + 6),
            (std::vector<uint32_t>{0, 4, 6, 0, 6, 2}));
  EXPECT_EQ(mesh->patch, std::vector<int32_t>(12, 0));
}

TEST(OffReader, CountsOnTheHeaderLineColoursAndCrlf) {
  Result<SurfaceMesh> mesh = read_box("box_inline_header.off");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
}

TEST(OffReader, HeaderlessCountsAndNonFiniteCoordinates) {
  Result<SurfaceMesh> mesh =
      read_off("3 1 0\nnan inf -inf\n1e400 -1e-400 +2\n0 0 0\n3 0 1 2\n", "t.off");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_TRUE(std::isnan(mesh->xyz[0]));
  EXPECT_EQ(mesh->xyz[1], std::numeric_limits<double>::infinity());
  EXPECT_EQ(mesh->xyz[2], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(mesh->xyz[3], std::numeric_limits<double>::infinity());
  EXPECT_EQ(mesh->xyz[4], 0.0);
  EXPECT_EQ(mesh->xyz[5], 2.0);
}

TEST(OffReader, ErrorsNameFileLineAndWhat) {
  Result<SurfaceMesh> bad = read_off("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "bad.off");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), Error::Parse);
  EXPECT_NE(bad.status().message().find("bad.off:4:"), std::string::npos) << bad.status().message();
  EXPECT_NE(bad.status().message().find("coordinate of vertex 1"), std::string::npos);
  EXPECT_NE(bad.status().message().find("'x'"), std::string::npos);

  Result<SurfaceMesh> index =
      read_off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "i.off");
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), Error::BadIndex);
  EXPECT_NE(index.status().message().find("triangle 1"), std::string::npos)
      << index.status().message();

  Result<SurfaceMesh> truncated =
      read_off("OFF\n3 1 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n3 0 1", "t.off");
  ASSERT_FALSE(truncated.ok());
  EXPECT_NE(truncated.status().message().find("end of file"), std::string::npos);

  Result<SurfaceMesh> empty = read_off("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "e.off");
  EXPECT_EQ(empty.status().code(), Error::EmptyInput);

  // A bogus count is rejected before anything is allocated for it.
  Result<SurfaceMesh> huge = read_off("OFF\n4000000000 4000000000 0\n0 0 0\n", "h.off");
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.status().code(), Error::Parse);

  EXPECT_EQ(read_off("4OFF\n", "4.off").status().code(), Error::UnsupportedFormat);
  EXPECT_EQ(read_off("OFF BINARY\n", "b.off").status().code(), Error::UnsupportedFormat);
}

TEST(ObjReader, GroupsFaceFormsAndNegativeIndices) {
  Result<SurfaceMesh> mesh = read_box("box_groups.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
  EXPECT_EQ(mesh->patch, kBoxPatches);  // groups side1..side6 in order of appearance
}

TEST(ObjReader, PolygonsAndNoGroups) {
  const char* text =
      "# quad\nv 0 0 0\nv 1 0 0 1\nv 1 1 0 0.5 0.5 0.5\n\nv 0 1 0\nvn 0 0 1\nf 1 2 3 4\n"
      "s off\nl 1 2\nf -4 -2 -1\n";
  Result<SurfaceMesh> mesh = read_obj(text, "q.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_vertices(), 4u);
  EXPECT_EQ(mesh->tri, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3}));
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{0, 0, 0}));
}

TEST(ObjReader, SameGroupNameKeepsItsLabel) {
  const char* text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng a\nf 1 2 3\ng b\nf 1 2 3\ng a\nf 1 2 3\n";
  Result<SurfaceMesh> mesh = read_obj(text, "g.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{0, 1, 2, 1}));
}

TEST(ObjReader, BadIndicesAndParseErrors) {
  Result<SurfaceMesh> zero = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "z.obj");
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.status().code(), Error::BadIndex);
  EXPECT_NE(zero.status().message().find("z.obj:4:"), std::string::npos) << zero.status().message();

  Result<SurfaceMesh> large = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", "l.obj");
  ASSERT_FALSE(large.ok());
  EXPECT_EQ(large.status().code(), Error::BadIndex);
  EXPECT_NE(large.status().message().find("triangle 1"), std::string::npos)
      << large.status().message();

  Result<SurfaceMesh> relative = read_obj("v 0 0 0\nf -1 -2 -3\n", "r.obj");
  EXPECT_EQ(relative.status().code(), Error::BadIndex);

  Result<SurfaceMesh> word = read_obj("v 0 0 0\nv 1 0 zero\n", "w.obj");
  ASSERT_FALSE(word.ok());
  EXPECT_EQ(word.status().code(), Error::Parse);
  EXPECT_NE(word.status().message().find("w.obj:2:"), std::string::npos);

  EXPECT_EQ(read_obj("v 0 0 0\n", "n.obj").status().code(), Error::EmptyInput);
}

TEST(StlReader, AsciiMergesCornersExactly) {
  Result<SurfaceMesh> mesh = read_box("box_ascii.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_vertices(), 8u);
  expect_box_triangles(mesh.value());
  EXPECT_EQ(mesh->patch, std::vector<int32_t>(12, 0));
}

TEST(StlReader, AsciiErrorsNameTheLine) {
  std::string text = load(io_data("box_ascii.stl"));
  Result<SurfaceMesh> truncated = read_stl(text.substr(0, 300), "t.stl");
  ASSERT_FALSE(truncated.ok());
  EXPECT_EQ(truncated.status().code(), Error::Parse);
  EXPECT_NE(truncated.status().message().find("t.stl:18: expected"), std::string::npos)
      << truncated.status().message();
  text.replace(text.find("endloop"), 7, "endlop");
  Result<SurfaceMesh> typo = read_stl(text, "t.stl");
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.status().message().find("t.stl:7: expected 'endloop', found 'endlop'"),
            std::string::npos)
      << typo.status().message();
}

TEST(StlReader, SeveralSolidsBecomeNamedPatches) {
  PatchNames names;
  Result<SurfaceMesh> mesh = read_surface(io_data("box_two_solids.stl"), &names);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_vertices(), 8u);
  expect_box_triangles(mesh.value());
  std::vector<int32_t> expected(12, 2);
  std::fill(expected.begin(), expected.begin() + 4, 1);
  EXPECT_EQ(mesh->patch, expected);
  // "solid x ends": the space is no patch-name character.
  EXPECT_EQ(names, (PatchNames{{1, "x_ends"}, {2, "sides"}}));
}

// A tetrahedron in names.size() solid blocks (1 to 4): block i named names[i] holds facet i, the
// last block the facets left.
std::string tet_in_solids(const std::vector<std::string>& names) {
  static const char* const kFacets[4][3] = {
      {"0 0 0", "0 1 0", "1 0 0"}, {"0 0 0", "1 0 0", "0 0 1"}, {"1 0 0", "0 1 0", "0 0 1"}, {"0 0 0", "0 0 1", "0 1 0"}};
  std::string text;
  for (size_t f = 0; f < 4; ++f) {
    if (f < names.size()) text += "solid " + names[f] + "\n";
    text += "facet normal 0 0 0\nouter loop\n";
    for (const char* v : kFacets[f]) text += std::string("vertex ") + v + "\n";
    text += "endloop\nendfacet\n";
    if (f + 1 < names.size() || f == 3) text += "endsolid\n";
  }
  return text;
}

Result<SurfaceMesh> read_named_stl(const std::vector<std::string>& solids, PatchNames& names) {
  names.clear();
  return read_surface(tet_in_solids(solids), SurfaceFormat::Stl, "n.stl", &names);
}

TEST(StlReader, SolidNamesAreMadeValidUniquePatchNames) {
  PatchNames names;
  // Invalid characters (runs become one '_'), a leading digit, more than 32 characters, and two
  // texts that give the same name.
  Result<SurfaceMesh> mesh =
      read_named_stl({"Part1 - Body:1", "1002_tray", "a_very_long_name_from_a_cad_export_tool", "wall-2"}, names);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{1, 2, 3, 4}));
  EXPECT_EQ(names, (PatchNames{{1, "Part1_Body_1"},
                               {2, "patch_1002_tray"},
                               {3, "a_very_long_name_from_a_cad_expo"},
                               {4, "wall_2"}}));
  ASSERT_TRUE(read_named_stl({"wall 2", "wall:2", "wall_2", "x"}, names).ok());
  EXPECT_EQ(names, (PatchNames{{1, "wall_2"}, {2, "wall_2_2"}, {3, "wall_2_3"}, {4, "x"}}));
  for (const auto& [label, name] : names) EXPECT_TRUE(check_patch_name(name).ok()) << name;
}

TEST(StlReader, SolidsOfOneNameShareAPatchAndUnnamedOnesKeepTheDefault) {
  PatchNames names;
  Result<SurfaceMesh> mesh = read_named_stl({"wall", "inlet", "wall", ""}, names);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{1, 2, 1, 3}));
  EXPECT_EQ(names, (PatchNames{{1, "wall"}, {2, "inlet"}}));  // label 3: patch3
  // Nothing usable in a text: unnamed. A name equal to an unnamed label's default is renamed.
  mesh = read_named_stl({"patch2", "--", "ok"}, names);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{1, 2, 3, 3}));
  EXPECT_EQ(names, (PatchNames{{1, "patch2_2"}, {3, "ok"}}));
  // One patch in all (one block, or blocks of one name): label 0, no name.
  for (const auto& solids : {std::vector<std::string>{"wing"}, std::vector<std::string>{"wing", "wing"}}) {
    mesh = read_named_stl(solids, names);
    ASSERT_TRUE(mesh.ok()) << mesh.status().message();
    EXPECT_EQ(mesh->patch, std::vector<int32_t>(4, 0));
    EXPECT_TRUE(names.empty());
  }
  // Without `names` the labels are the same.
  Result<SurfaceMesh> unnamed = read_stl(tet_in_solids({"wall", "inlet", "wall", ""}), "n.stl");
  ASSERT_TRUE(unnamed.ok());
  EXPECT_EQ(unnamed->patch, (std::vector<int32_t>{1, 2, 1, 3}));
}

TEST(StlReader, BinaryWhoseHeaderStartsWithSolid) {
  std::string bytes = load(io_data("box_binary_solid_header.stl"));
  ASSERT_EQ(bytes.substr(0, 5), "solid");
  Result<SurfaceMesh> mesh = read_stl(bytes, "b.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_vertices(), 8u);
  expect_box_triangles(mesh.value(), [](double v) { return double(float(v)); });
  EXPECT_EQ(mesh->patch, std::vector<int32_t>(12, 0));  // the attribute word is no label
}

TEST(StlReader, MergesOnlyBitEqualPointsAndTreatsSignedZerosAlike) {
  std::string bytes(84, '\0');
  uint32_t count = 2;
  std::memcpy(&bytes[80], &count, 4);
  auto add = [&](std::initializer_list<float> corners) {
    float f[12] = {0, 0, 0};
    std::copy(corners.begin(), corners.end(), f + 3);
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
    bytes.append(2, '\0');
  };
  add({0, 0, 0, 1, 0, 0, 0, 1, 0});
  add({-0.0f, 0, 0, 0, 1, 0, std::nextafter(1.0f, 2.0f), 0, 0});
  Result<SurfaceMesh> mesh = read_stl(bytes, "m.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_vertices(), 4u);
  EXPECT_EQ(mesh->tri, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(StlReader, BinaryErrorsNameTheByteOffset) {
  std::string bytes = load(io_data("box_binary_solid_header.stl"));
  bytes.resize(bytes.size() - 7);
  // Starts with "solid", but the bytes are not text: reported as a truncated binary file.
  for (char first : {'s', 'x'}) {
    bytes[0] = first;
    Result<SurfaceMesh> truncated = read_stl(bytes, "t.stl");
    ASSERT_FALSE(truncated.ok());
    EXPECT_EQ(truncated.status().code(), Error::Parse);
    EXPECT_NE(
        truncated.status().message().find("t.stl: byte offset 84: binary STL with 12 triangles"),
        std::string::npos)
        << truncated.status().message();
  }
  std::string empty(84, '\0');
  EXPECT_EQ(read_stl(empty, "e.stl").status().code(), Error::EmptyInput);
}

TEST(PlyReader, AsciiWithExtraPropertiesElementsAndAQuad) {
  Result<SurfaceMesh> mesh = read_box("box_ascii.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  ASSERT_EQ(mesh->num_triangles(), 12u);
  EXPECT_EQ(std::vector<uint32_t>(mesh->tri.end() - 6, mesh->tri.end()),
            (std::vector<uint32_t>{0, 4, 6, 0, 6, 2}));
}

TEST(PlyReader, BinaryLittleEndianDoublesAndLists) {
  Result<SurfaceMesh> mesh = read_box("box_binary_le.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
}

TEST(PlyReader, BinaryBigEndianFloatsAndUintIndices) {
  Result<SurfaceMesh> mesh = read_box("box_binary_be.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  ASSERT_EQ(mesh->num_vertices(), 8u);
  for (int v = 0; v < 8; ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh->xyz[3 * v + k], double(float(box_coord(v, k))));
  }
  EXPECT_EQ(mesh->tri, kBoxTris);
}

TEST(PlyReader, Errors) {
  std::string bytes = load(io_data("box_binary_le.ply"));
  Result<SurfaceMesh> truncated = read_ply(bytes.substr(0, bytes.size() - 20), "t.ply");
  ASSERT_FALSE(truncated.ok());
  EXPECT_NE(truncated.status().message().find("byte offset"), std::string::npos)
      << truncated.status().message();
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_TRUE(read_ply(head + "3 0 1 2\n", "ok.ply").ok());
  Result<SurfaceMesh> index = read_ply(head + "3 0 1 3\n", "i.ply");
  EXPECT_EQ(index.status().code(), Error::BadIndex);
  Result<SurfaceMesh> text = read_ply(head + "3 0 one 2\n", "p.ply");
  ASSERT_FALSE(text.ok());
  EXPECT_NE(text.status().message().find("p.ply:13:"), std::string::npos)
      << text.status().message();
  EXPECT_EQ(read_ply("ply\nformat binary_middle_endian 1.0\nend_header\n", "f.ply").status().code(),
            Error::UnsupportedFormat);
  Result<SurfaceMesh> huge = read_ply(
      "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n",
      "h.ply");
  EXPECT_EQ(huge.status().code(), Error::Parse);
}

TEST(MeditReader, SurfaceWithPatchRefs) {
  Result<SurfaceMesh> mesh = read_box("box.mesh");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
  EXPECT_EQ(mesh->patch, kBoxPatches);
}

TEST(MeditReader, QuadsAndErrors) {
  const char* quads =
      "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n"
      "Quadrilaterals\n1\n1 2 3 4 7\nEnd\n";
  Result<SurfaceMesh> mesh = read_medit_surface(quads, "q.mesh");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->tri, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(mesh->patch, (std::vector<int32_t>{7, 7}));

  const char* bad =
      "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
      "Triangles\n2\n1 2 3 1\n1 2 4 1\nEnd\n";
  Result<SurfaceMesh> index = read_medit_surface(bad, "b.mesh");
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), Error::BadIndex);
  EXPECT_NE(index.status().message().find("triangle 2"), std::string::npos)
      << index.status().message();
  EXPECT_EQ(read_medit_surface("MeshVersionFormatted 1\nDimension 2\n", "d.mesh").status().code(),
            Error::UnsupportedFormat);
  EXPECT_EQ(read_medit_surface(std::string("\x01\0\0\0", 4), "b.meshb").status().code(),
            Error::UnsupportedFormat);
}

// The patch of a triangle is its surface's first physical tag (surface 1 is the physical group
// 101 "left"), else the entity (elementary) tag: the same rule as the volume reader's, so that a
// Gmsh user's physical groups are the patches and their names the patch names.
const std::vector<int32_t> kGmshSurfacePatches = {101, 101, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6};

TEST(GmshReader, Surface41AsciiPatchIsThePhysicalTag) {
  Result<SurfaceMesh> mesh = read_box("box41.msh");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
  EXPECT_EQ(mesh->patch, kGmshSurfacePatches);
  PatchNames names;
  ASSERT_TRUE(read_surface(io_data("box41.msh"), &names).ok());
  EXPECT_EQ(names, (PatchNames{{101, "left"}}));  // "solid" names a volume
}

TEST(GmshReader, Surface41Binary) {
  Result<SurfaceMesh> mesh = read_box("box41_binary.msh");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
  EXPECT_EQ(mesh->patch, kGmshSurfacePatches);
}

TEST(GmshReader, Surface22PatchIsThePhysicalTag) {
  Result<SurfaceMesh> mesh = read_box("box22.msh");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  expect_box_vertices(mesh.value());
  EXPECT_EQ(mesh->tri, kBoxTris);
  EXPECT_EQ(mesh->patch, kGmshSurfacePatches);
}

TEST(GmshReader, Errors) {
  std::string text = load(io_data("box41.msh"));
  std::string missing = text;
  missing.replace(missing.find("\n1 10 70 30\n"), 12, "\n1 10 70 31\n");
  Result<SurfaceMesh> index = read_gmsh_surface(missing, "m.msh");
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), Error::BadIndex);
  EXPECT_NE(index.status().message().find("node 31"), std::string::npos)
      << index.status().message();

  std::string no_section = text;
  no_section.erase(no_section.find("$Elements\n"), 10);
  Result<SurfaceMesh> bad = read_gmsh_surface(no_section, "s.msh");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), Error::Parse);

  EXPECT_EQ(read_gmsh_surface("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "v.msh").status().code(),
            Error::UnsupportedFormat);
  EXPECT_EQ(read_gmsh_surface("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n", "v.msh").status().code(),
            Error::UnsupportedFormat);
  EXPECT_EQ(read_gmsh_surface("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", "e.msh").status().code(),
            Error::EmptyInput);
}

TEST(ReadSurface, DispatchesOnExtensionAndReportsMissingFiles) {
  EXPECT_TRUE(read_surface(io_data("box_quads.off")).ok());
  EXPECT_EQ(read_surface(io_data("box_quads.xyz")).status().code(), Error::UnsupportedFormat);
  Result<SurfaceMesh> missing = read_surface(io_data("no_such_file.obj"));
  EXPECT_EQ(missing.status().code(), Error::FileNotFound);
  EXPECT_NE(missing.status().message().find("no_such_file.obj"), std::string::npos);
  const std::string dir = test::temp_dir() + "/directory.obj";
  mkdir(dir.c_str(), 0700);
  EXPECT_EQ(read_surface(dir).status().code(), Error::FileNotFound);
  Result<SurfaceFormat> upper = surface_format_from_path("/a.b/MODEL.STL");
  ASSERT_TRUE(upper.ok());
  EXPECT_EQ(upper.value(), SurfaceFormat::Stl);
}

}  // namespace
}  // namespace anitet
