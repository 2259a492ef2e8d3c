// Each volume reader on the box files of tests/data/io, and the .sol writer.
#include "io/number_text.hpp"
#include "io/parallel_text.hpp"
#include "io/volume_io.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io_test_util.hpp"

namespace anitet {
namespace {

using test::io_data;
using test::kBoxPatches;
using test::kBoxRegions;
using test::kBoxTets;
using test::kBoxTris;

void expect_box(const Result<VolumeMesh>& mesh, const std::vector<int32_t>& regions,
                const std::vector<int32_t>& patches) {
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->xyz, test::box_xyz());
  EXPECT_EQ(mesh->tet, kBoxTets);
  EXPECT_EQ(mesh->region, regions);
  EXPECT_EQ(mesh->bnd_tri, kBoxTris);
  EXPECT_EQ(mesh->bnd_patch, patches);
}

// In the Gmsh files volume 1 has physical tag 10, surface 1 physical tag 101; the other entities
// have none, so their entity tag is the label.
const std::vector<int32_t> kGmshRegions = {10, 10, 10, 2, 2, 2};
const std::vector<int32_t> kGmshPatches = {101, 101, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6};

TEST(VolumeReaders, Medit) {
  expect_box(read_volume_mesh(io_data("box.mesh")), kBoxRegions, kBoxPatches);
}

TEST(VolumeReaders, Gmsh41Ascii) {
  expect_box(read_volume_mesh(io_data("box41.msh")), kGmshRegions, kGmshPatches);
}

TEST(VolumeReaders, Gmsh41Binary) {
  expect_box(read_volume_mesh(io_data("box41_binary.msh")), kGmshRegions, kGmshPatches);
}

TEST(VolumeReaders, Gmsh22Ascii) {
  expect_box(read_volume_mesh(io_data("box22.msh")), kGmshRegions, kGmshPatches);
}

TEST(VolumeReaders, TetGenFromEleOrNodeWithEitherFirstIndex) {
  expect_box(read_volume_mesh(io_data("box_base1.ele")), kBoxRegions, kBoxPatches);
  expect_box(read_volume_mesh(io_data("box_base0.node")), kBoxRegions, kBoxPatches);
}

TEST(VolumeReaders, TetGenWithoutFaceFile) {
  std::string node = test::load(io_data("box_base1.node"));
  std::string ele = test::load(io_data("box_base1.ele"));
  Result<VolumeMesh> mesh = read_tetgen(node, ele, "", "box");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->tet, kBoxTets);
  EXPECT_TRUE(mesh->bnd_tri.empty());
  std::string bad = ele;
  bad.replace(bad.find("\n1 "), 3, "\n1 9");  // tet 0's first node becomes 90-something
  Result<VolumeMesh> index = read_tetgen(node, bad, "", "box");
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), Error::BadIndex);
  EXPECT_NE(index.status().message().find("box.ele:2:"), std::string::npos)
      << index.status().message();
  EXPECT_NE(index.status().message().find("tetrahedron 0"), std::string::npos);
}

TEST(VolumeReaders, Vtu) {
  expect_box(read_volume_mesh(io_data("box.vtu")), kBoxRegions, kBoxPatches);
}

TEST(VolumeReaders, VtuRejectsBadBinaryAndMismatchedCounts) {
  std::string text = test::load(io_data("box.vtu"));
  std::string binary = text;  // ascii numbers declared binary: not base64
  binary.replace(binary.find("format=\"ascii\">0.0"), 14, "format=\"binary\"");
  EXPECT_EQ(read_vtu(binary, "b.vtu").status().code(), Error::Parse);
  for (const char* form : {"byte_order=\"BigEndian\"", "compressor=\"vtkLZ4DataCompressor\""}) {
    std::string other = binary;
    other.replace(other.find("<VTKFile ") + 9, 0, std::string(form) + " ");
    const Status st = read_vtu(other, "o.vtu").status();
    EXPECT_EQ(st.code(), Error::UnsupportedFormat) << form;
    EXPECT_NE(st.message().find(std::string(form).substr(0, 5) == "byte_" ? "big-endian" : "vtkLZ4"), std::string::npos)
        << st.message();
  }
  std::string count = text;
  count.replace(count.find("NumberOfPoints=\"8\""), 18, "NumberOfPoints=\"9\"");
  EXPECT_EQ(read_vtu(count, "c.vtu").status().code(), Error::Parse);
  std::string index = text;
  index.replace(index.find(">0 1 3 7"), 8, ">8 1 3 7");
  EXPECT_EQ(read_vtu(index, "i.vtu").status().code(), Error::BadIndex);
}

TEST(VolumeReaders, NoTetsIsEmptyInput) {
  const char* surface =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n"
      "0 1 0 0\nTriangles\n1\n1 2 3 0\nEnd\n";
  EXPECT_EQ(read_medit_volume(surface, "s.mesh").status().code(), Error::EmptyInput);
  EXPECT_EQ(read_volume_mesh(io_data("box_quads.off")).status().code(), Error::UnsupportedFormat);
  EXPECT_EQ(read_volume_mesh(io_data("missing.mesh")).status().code(), Error::FileNotFound);
}

TEST(SolWriter, ScalarAndTensorInMeditOrder) {
  VolumeMesh mesh;
  mesh.xyz = {0, 0, 0, 1, 0, 0};
  mesh.vertex_metric = {0.5, 0.25};
  Result<std::string> scalar = to_sol(mesh);
  ASSERT_TRUE(scalar.ok()) << scalar.status().message();
  EXPECT_EQ(scalar.value(),
            "MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n2\n1 1\n0.5\n0.25\n\nEnd\n");
  mesh.vertex_metric = {1, 2, 3, 4, 5, 6, 0.1, 0, 0.2, 0, 0, 1e-300};
  Result<std::string> tensor = to_sol(mesh);
  ASSERT_TRUE(tensor.ok());
  EXPECT_NE(tensor->find("SolAtVertices\n2\n1 3\n1 2 3 4 5 6\n0.1 0 0.2 0 0 1e-300\n"),
            std::string::npos)
      << tensor.value();
  mesh.vertex_metric = {1, 2, 3};
  EXPECT_EQ(to_sol(mesh).status().code(), Error::InvalidArgument);
  mesh.vertex_metric = {0.5, 0.25};
  const std::string path = test::temp_dir() + "/m.sol";
  ASSERT_TRUE(write_sol(mesh, path).ok());
  EXPECT_EQ(test::load(path), scalar.value());
}

TEST(VolumeWriters, RejectInconsistentArrays) {
  VolumeMesh mesh;
  mesh.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  mesh.tet = {0, 1, 2, 4};
  EXPECT_EQ(to_medit(mesh).status().code(), Error::BadIndex);
  mesh.tet = {0, 1, 2, 3};
  mesh.region = {1, 2};
  EXPECT_EQ(to_gmsh(mesh).status().code(), Error::InvalidArgument);
  mesh.region = {1};
  EXPECT_EQ(to_vtu(mesh, {{"quality", {0.5, 0.5}}}).status().code(), Error::InvalidArgument);
  EXPECT_TRUE(to_vtu(mesh, {{"quality", {0.5}}}).ok());
  EXPECT_EQ(write_volume_mesh(mesh, test::temp_dir() + "/m.stl").code(), Error::UnsupportedFormat);
  EXPECT_EQ(write_volume_mesh(mesh, "/nonexistent_dir/m.mesh").code(), Error::FileNotFound);
}

}  // namespace
}  // namespace anitet

namespace anitet {
namespace {

// The parallel formatting gives one loop's text: over two windows of blocks and a short last
// block, and for no item at all.
TEST(ParallelText, AppendItemsIsOneLoopsText) {
  for (size_t count : {size_t(0), size_t(5), size_t(16384 * 16 + 16384 * 3 + 7)}) {
    std::string expected = "head\n", got = "head\n";
    for (size_t i = 0; i < count; ++i) append_line(expected, uint64_t{i}, 0.5 * double(i));
    append_items(got, count, [](std::string& text, size_t i) { append_line(text, uint64_t{i}, 0.5 * double(i)); });
    EXPECT_EQ(got, expected) << count << " items";
  }
}

}  // namespace
}  // namespace anitet
