// Readers on every truncation of the small test files, on random mutations of them and on
// random bytes: each call must return an error with a message or a consistent mesh, never crash
// or hang (these tests also run under AddressSanitizer and UBSan).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "io_test_util.hpp"

namespace anitet {
namespace {

using ReaderCheck = std::function<void(const std::string& data)>;

template <class Mesh>
void expect_sane(const Result<Mesh>& result, const char* name);

template <>
void expect_sane(const Result<SurfaceMesh>& result, const char* name) {
  if (result.ok()) {
    ASSERT_TRUE(check_surface_arrays(result.value()).ok()) << name;
    ASSERT_GT(result->num_triangles(), 0u) << name;
  } else {
    ASSERT_NE(result.status().code(), Error::Ok);
    ASSERT_NE(result.status().message().find(name), std::string::npos) << result.status().message();
  }
}

template <>
void expect_sane(const Result<VolumeMesh>& result, const char* name) {
  if (result.ok()) {
    ASSERT_TRUE(check_volume_arrays(result.value()).ok()) << name;
    ASSERT_EQ(result->region.size(), result->num_tets()) << name;
    ASSERT_GT(result->num_tets(), 0u) << name;
  } else {
    ASSERT_NE(result.status().code(), Error::Ok);
    ASSERT_NE(result.status().message().find(name), std::string::npos) << result.status().message();
  }
}

template <class Mesh>
ReaderCheck checker(Result<Mesh> (*read)(std::string_view, const std::string&)) {
  return [read](const std::string& data) { expect_sane(read(data, "fuzzed"), "fuzzed"); };
}
// A reader that also gives the file's patch names: asked for them, so that the naming runs too.
template <class Mesh>
ReaderCheck checker(Result<Mesh> (*read)(std::string_view, const std::string&, PatchNames*)) {
  return [read](const std::string& data) {
    PatchNames names;
    expect_sane(read(data, "fuzzed", &names), "fuzzed");
  };
}

// The readers that apply to a test file, by extension.
std::vector<ReaderCheck> readers_for(const std::string& file) {
  const std::string ext = lower_extension(file);
  if (ext == "off") return {checker(&read_off)};
  if (ext == "obj") return {checker(&read_obj)};
  if (ext == "stl") return {checker(&read_stl)};
  if (ext == "ply") return {checker(&read_ply)};
  if (ext == "mesh") return {checker(&read_medit_surface), checker(&read_medit_volume)};
  if (ext == "msh") return {checker(&read_gmsh_surface), checker(&read_gmsh_volume)};
  if (ext == "vtu") return {checker(&read_vtu)};
  // TetGen: the fuzzed text replaces one of the three files of box_base1.
  const std::string base = test::io_data("box_base1");
  const std::string node = test::load(base + ".node"), ele = test::load(base + ".ele"),
                    face = test::load(base + ".face");
  auto tetgen = [](std::string n, std::string e, std::string f) {
    expect_sane(read_tetgen(n, e, f, "fuzzed"), "fuzzed");
  };
  if (ext == "node") return {[=](const std::string& d) { tetgen(d, ele, face); }};
  if (ext == "ele") return {[=](const std::string& d) { tetgen(node, d, face); }};
  if (ext == "face") return {[=](const std::string& d) { tetgen(node, ele, d); }};
  ADD_FAILURE() << "no reader for " << file;
  return {};
}

const char* const kFiles[] = {"box_quads.off",
                              "box_inline_header.off",
                              "box_groups.obj",
                              "box_ascii.stl",
                              "box_two_solids.stl",
                              "box_binary_solid_header.stl",
                              "box_ascii.ply",
                              "box_binary_le.ply",
                              "box_binary_be.ply",
                              "box.mesh",
                              "box41.msh",
                              "box41_binary.msh",
                              "box22.msh",
                              "box_base1.node",
                              "box_base1.ele",
                              "box_base1.face",
                              "box.vtu"};

TEST(Robustness, EveryTruncation) {
  for (const char* file : kFiles) {
    const std::string data = test::load(test::io_data(file));
    ASSERT_LT(data.size(), 4096u) << file;
    for (const ReaderCheck& check : readers_for(file)) {
      for (size_t size = 0; size < data.size(); ++size) {
        SCOPED_TRACE(std::string(file) + " truncated to " + std::to_string(size) + " bytes");
        check(data.substr(0, size));
        if (HasFatalFailure()) return;
      }
    }
  }
}

// A random edit of the kind that breaks parsers: bytes changed, ranges removed or repeated,
// numbers made huge, negative or non-finite.
std::string mutate(const std::string& data, std::mt19937& rng) {
  std::string out = data;
  auto pick = [&](size_t n) { return n == 0 ? size_t{0} : static_cast<size_t>(rng() % n); };
  static const char* const kInserts[] = {"4294967295",
                                         "18446744073709551615",
                                         "99999999999999999999",
                                         "-1",
                                         "0",
                                         "1e999",
                                         "nan",
                                         "-inf",
                                         "\n",
                                         " ",
                                         "$",
                                         "#",
                                         "\"",
                                         "<",
                                         "/>",
                                         "9",
                                         "-",
                                         "."};
  const int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 6) {
      case 0:
        if (!out.empty()) out[pick(out.size())] = static_cast<char>(rng());
        break;
      case 1:
        if (!out.empty()) out[pick(out.size())] = "0123456789- \n."[rng() % 14];
        break;
      case 2: {
        size_t at = pick(out.size()), len = 1 + pick(32);
        out.erase(at, len);
        break;
      }
      case 3: {
        size_t at = pick(out.size()), len = 1 + pick(64);
        out.insert(pick(out.size()), out.substr(at, len));
        break;
      }
      case 4:
        out.insert(pick(out.size() + 1), kInserts[rng() % (sizeof kInserts / sizeof kInserts[0])]);
        break;
      default: {
        // Replace a run of digits by a huge count.
        size_t at = pick(out.size());
        while (at < out.size() && !(out[at] >= '0' && out[at] <= '9')) ++at;
        size_t end = at;
        while (end < out.size() && out[end] >= '0' && out[end] <= '9') ++end;
        out.replace(at, end - at, rng() % 2 ? "2147483647" : "123456789012");
        break;
      }
    }
  }
  return out;
}

TEST(Robustness, RandomMutationsOfGoodFiles) {
  std::mt19937 rng(12345);
  int runs = 0;
  for (const char* file : kFiles) {
    const std::string data = test::load(test::io_data(file));
    for (const ReaderCheck& check : readers_for(file)) {
      for (int i = 0; i < 800; ++i) {
        const std::string mutated = mutate(data, rng);
        SCOPED_TRACE(std::string(file) + " mutation " + std::to_string(i));
        check(mutated);
        ++runs;
        if (HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GT(runs, 15000);
}

TEST(Robustness, RandomBytesBehindPlausibleHeaders) {
  static const char kBinaryGmsh[] = "$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n$Elements\n";
  const std::vector<std::string> headers = {
      "",
      "OFF\n",
      "OFF 3 1 0\n",
      "v 1 2 3\nf ",
      "solid x\n facet normal 0 0 0\n outer loop\n",
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
      "MeshVersionFormatted 2\nDimension 3\nVertices\n",
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n",
      std::string(kBinaryGmsh, sizeof kBinaryGmsh - 1),
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n",
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"4\" "
      "NumberOfCells=\"1\"><Points><DataArray format=\"ascii\">"};
  const std::vector<std::pair<const char*, ReaderCheck>> readers = {
      {"off", checker(&read_off)},           {"obj", checker(&read_obj)},
      {"stl", checker(&read_stl)},           {"ply", checker(&read_ply)},
      {"mesh", checker(&read_medit_volume)}, {"msh", checker(&read_gmsh_volume)},
      {"msh", checker(&read_gmsh_surface)},  {"vtu", checker(&read_vtu)}};
  std::mt19937 rng(777);
  for (const std::string& header : headers) {
    for (int i = 0; i < 150; ++i) {
      std::string data = header;
      const size_t size = rng() % 300;
      const bool text = rng() % 2;
      for (size_t k = 0; k < size; ++k) {
        data += text ? " \n0123456789-.e"[rng() % 15] : static_cast<char>(rng());
      }
      for (const auto& [name, check] : readers) {
        SCOPED_TRACE(std::string(name) + " on random data " + std::to_string(i));
        check(data);
        if (HasFatalFailure()) return;
      }
    }
  }
  // Binary STL-sized random data: 84 + 50 n bytes with a matching count.
  for (int i = 0; i < 50; ++i) {
    uint32_t n = rng() % 20;
    std::string data(84 + 50 * n, '\0');
    for (char& c : data) c = static_cast<char>(rng());
    std::memcpy(&data[80], &n, 4);
    checker (&read_stl)(data);
  }
}

}  // namespace
}  // namespace anitet

namespace anitet {
namespace {

// Output safety: a write goes to PATH.part-PID and is renamed, so no partial file is left
// behind, a failed write leaves the old file whole, and no .part file survives either way.
TEST(FileBytes, WritesAreRenamedIntoPlaceAndFailuresLeaveTheOldFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("anitet-write-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "mesh.mesh").string();
  ASSERT_TRUE(write_file_bytes(path, "old contents").ok());
  ASSERT_TRUE(write_file_bytes(path, "new contents").ok());
  EXPECT_EQ(read_file_bytes(path).value(), "new contents");
  // The temporary name is taken by a directory: the write fails and the old file stays.
  std::filesystem::create_directory(path + ".part-" + std::to_string(getpid()));
  const Status failed = write_file_bytes(path, "newer");
  EXPECT_EQ(failed.code(), Error::FileNotFound);
  EXPECT_NE(failed.message().find(path), std::string::npos) << failed.message();
  EXPECT_EQ(read_file_bytes(path).value(), "new contents");
  std::filesystem::remove(path + ".part-" + std::to_string(getpid()));
  // A directory cannot be replaced by a file: refused, nothing left beside it.
  std::filesystem::create_directory(dir / "sub");
  EXPECT_FALSE(write_file_bytes((dir / "sub").string(), "x").ok());
  size_t entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(e.path().string().find(".part-"), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 2u);  // mesh.mesh and sub
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace anitet
