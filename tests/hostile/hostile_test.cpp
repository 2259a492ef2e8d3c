// Hostile inputs (issue 11): every case builds its input in code (or writes a small file to a
// temporary directory), runs it through a public entry point (the surface readers, validation,
// the Mesher or the C ABI) and checks the outcome a user would want: a clear error code with a
// message naming the problem, or a correct result. Never a crash, a hang or a silent success.
// Every input is tiny; the Mesher only runs on tetrahedra and cubes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "anitet.h"
#include "io/file_bytes.hpp"
#include "io/surface_io.hpp"
#include "pipeline/mesher.hpp"
#include "validate/validate.hpp"

namespace anitet {
namespace {

// ------------------------------------------------------------------------------------------------
// Inputs.

// The unit tetrahedron, outward counter-clockwise.
SurfaceMesh tetrahedron(double scale = 1.0, double ox = 0.0) {
  SurfaceMesh m;
  m.add_vertex(ox, 0, 0);
  m.add_vertex(ox + scale, 0, 0);
  m.add_vertex(ox, scale, 0);
  m.add_vertex(ox, 0, scale);
  m.add_triangle(0, 2, 1);
  m.add_triangle(0, 1, 3);
  m.add_triangle(0, 3, 2);
  m.add_triangle(1, 2, 3);
  return m;
}

// Appends the axis-aligned box [lo, hi]^3 (12 outward triangles) to `m`.
void add_cube(SurfaceMesh& m, double lo, double hi) {
  const uint32_t b = static_cast<uint32_t>(m.num_vertices());
  for (int i = 0; i < 8; ++i) {
    m.add_vertex(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo);
  }
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.add_triangle(b + q[0], b + q[1], b + q[2]);
    m.add_triangle(b + q[0], b + q[2], b + q[3]);
  }
}

SurfaceMesh cube(double lo = 0.0, double hi = 1.0) {
  SurfaceMesh m;
  add_cube(m, lo, hi);
  return m;
}

void flip_all(SurfaceMesh& m) {
  for (size_t t = 0; t < m.num_triangles(); ++t) std::swap(m.tri[3 * t + 1], m.tri[3 * t + 2]);
}

const char kTetOff[] =
    "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char kTetObj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const char kTetPly[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string tet_stl_ascii() {
  return "solid tet\n"
         "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\n"
         "endfacet\n"
         "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\n"
         "endfacet\n"
         "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\n"
         "endfacet\n"
         "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\n"
         "endfacet\n"
         "endsolid tet\n";
}

std::string tet_stl_binary() {
  Result<std::string> bytes = to_stl_binary(tetrahedron());
  EXPECT_TRUE(bytes.ok()) << bytes.status().message();
  return bytes.ok() ? bytes.value() : std::string();
}

std::string tet_medit() {
  Result<std::string> text = to_medit(tetrahedron());
  EXPECT_TRUE(text.ok()) << text.status().message();
  return text.ok() ? text.value() : std::string();
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

// ------------------------------------------------------------------------------------------------
// Expectations.

// A failure with `code` and a message that names the input.
template <class T>
void expect_error(const Result<T>& r, Error code, const std::string& name) {
  ASSERT_FALSE(r.ok()) << name << ": accepted";
  EXPECT_EQ(r.status().code(), code)
      << name << ": " << error_name(r.status().code()) << ": " << r.status().message();
  EXPECT_NE(r.status().message().find(name), std::string::npos) << r.status().message();
}

// A failure of any kind, with a message (for inputs where several codes are reasonable).
template <class T>
void expect_some_error(const Result<T>& r, const std::string& name) {
  ASSERT_FALSE(r.ok()) << name << ": accepted";
  EXPECT_NE(r.status().code(), Error::Ok);
  EXPECT_FALSE(r.status().message().empty());
}

void expect_tetrahedron(const Result<SurfaceMesh>& r) {
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->num_vertices(), 4u);
  EXPECT_EQ(r->num_triangles(), 4u);
  EXPECT_TRUE(check_surface_arrays(r.value()).ok());
  SurfaceMesh copy = r.value();
  ValidationReport report = validate_surface(copy);
  EXPECT_TRUE(report.ok()) << report.summary();
}

// The report fails with `code` as one of its problems, and its message is not empty.
void expect_problem(const ValidationReport& report, Error code) {
  EXPECT_FALSE(report.ok()) << "accepted";
  EXPECT_FALSE(report.status().ok());
  EXPECT_FALSE(report.status().message().empty());
  EXPECT_GT(report.count(code), 0u) << "no " << error_name(code) << " in\n" << report.summary();
  const Problem* p = report.find(error_name(code));
  ASSERT_NE(p, nullptr);
  EXPECT_FALSE(p->message.empty());
  EXPECT_FALSE(p->examples.empty());
}

ValidationReport validate(SurfaceMesh m, const ValidationOptions& options = {}) {
  return validate_surface(m, options);
}

// A fast Mesher: the surface sizing as usual; tiny inputs only.
MesherOptions fast_options() {
  MesherOptions o;
  o.validation.num_threads = 1;
  return o;
}

double mesh_volume(const VolumeMesh& mesh) {
  double sum = 0.0;
  for (size_t t = 0; t < mesh.num_tets(); ++t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &mesh.xyz[3 * mesh.tet[4 * t + k]];
    double a[3], b[3], c[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = p[1][i] - p[0][i];
      b[i] = p[2][i] - p[0][i];
      c[i] = p[3][i] - p[0][i];
    }
    sum += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) /
           6.0;
  }
  return sum;
}

// A temporary directory, removed (with the files the test put there) at the end.
class TempDir {
 public:
  TempDir() {
    char templ[] = "/tmp/anitet_hostile_XXXXXX";
    const char* made = mkdtemp(templ);
    EXPECT_NE(made, nullptr);
    if (made) path_ = made;
  }
  ~TempDir() {
    for (const std::string& f : files_) std::remove(f.c_str());
    for (const std::string& d : dirs_) rmdir(d.c_str());
    if (!path_.empty()) rmdir(path_.c_str());
  }
  std::string write(const std::string& name, const std::string& bytes) {
    const std::string p = path_ + "/" + name;
    EXPECT_TRUE(write_file_bytes(p, bytes).ok()) << p;
    files_.push_back(p);
    return p;
  }
  std::string mkdir(const std::string& name) {
    const std::string p = path_ + "/" + name;
    EXPECT_EQ(::mkdir(p.c_str(), 0700), 0) << p;
    dirs_.push_back(p);
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> files_, dirs_;
};

// ------------------------------------------------------------------------------------------------
// Files: empty, missing, directories, names.

TEST(HostileFiles, EmptyDataEveryFormatIsAnError) {
  for (SurfaceFormat f : {SurfaceFormat::Off, SurfaceFormat::Obj, SurfaceFormat::Stl,
                          SurfaceFormat::Ply, SurfaceFormat::Medit, SurfaceFormat::Gmsh}) {
    SCOPED_TRACE(static_cast<int>(f));
    Result<SurfaceMesh> r = read_surface(std::string_view(), f, "empty.in");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(r.status().code() == Error::Parse || r.status().code() == Error::EmptyInput)
        << error_name(r.status().code());
    EXPECT_NE(r.status().message().find("empty.in"), std::string::npos) << r.status().message();
  }
}

TEST(HostileFiles, ZeroByteFileOnDisk) {
  TempDir dir;
  for (const char* name : {"zero.off", "zero.obj", "zero.stl", "zero.ply", "zero.mesh"}) {
    const std::string path = dir.write(name, "");
    Result<SurfaceMesh> r = read_surface(path);
    ASSERT_FALSE(r.ok()) << name;
    EXPECT_TRUE(r.status().code() == Error::Parse || r.status().code() == Error::EmptyInput)
        << name << ": " << error_name(r.status().code());
    EXPECT_NE(r.status().message().find(name), std::string::npos) << r.status().message();
  }
}

TEST(HostileFiles, WhitespaceOnlyFile) {
  expect_some_error(read_off(" \n\n\t \r\n", "blank.off"), "blank.off");
  expect_error(read_obj("\n\n# nothing\n\n", "blank.obj"), Error::EmptyInput, "blank.obj");
}

TEST(HostileFiles, NonexistentPath) {
  TempDir dir;
  expect_error(read_surface(dir.path() + "/missing.off"), Error::FileNotFound, "missing.off");
}

TEST(HostileFiles, DirectoryNamedLikeASurface) {
  TempDir dir;
  const std::string path = dir.mkdir("folder.off");
  expect_error(read_surface(path), Error::FileNotFound, "folder.off");
}

TEST(HostileFiles, UnknownExtension) {
  TempDir dir;
  const std::string path = dir.write("tet.xyz", kTetOff);
  expect_error(read_surface(path), Error::UnsupportedFormat, "tet.xyz");
  expect_some_error(read_surface(dir.path() + "/no_extension"), "no_extension");
}

TEST(HostileFiles, UnicodePathReads) {
  TempDir dir;
  const std::string path = dir.write(
      "t\xc3\xa9tra\xc3\xa8"
      "dre_\xe5\x9b\x9b\xe9\x9d\xa2.off",
      kTetOff);
  expect_tetrahedron(read_surface(path));
}

TEST(HostileFiles, UppercaseExtensionReads) {
  TempDir dir;
  expect_tetrahedron(read_surface(dir.write("TET.OFF", kTetOff)));
}

TEST(HostileFiles, BinaryGarbageEveryFormat) {
  std::mt19937 rng(11);
  std::string bytes(4096, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  for (SurfaceFormat f : {SurfaceFormat::Off, SurfaceFormat::Obj, SurfaceFormat::Stl,
                          SurfaceFormat::Ply, SurfaceFormat::Medit, SurfaceFormat::Gmsh}) {
    SCOPED_TRACE(static_cast<int>(f));
    expect_some_error(read_surface(bytes, f, "garbage"), "garbage");
  }
}

TEST(HostileFiles, NulBytesInsideText) {
  std::string text(kTetOff);
  text[text.find("1 0 0")] = '\0';
  expect_error(read_off(text, "nul.off"), Error::Parse, "nul.off");
}

// ------------------------------------------------------------------------------------------------
// Truncated and miscounted files.

TEST(HostileTruncated, OffEveryPrefix) {
  const std::string text = kTetOff;
  // Cut anywhere before the last face's last index: an error, never a partial mesh.
  const size_t last = text.rfind('3');
  for (size_t n = 0; n < last; ++n) {
    Result<SurfaceMesh> r = read_off(std::string_view(text).substr(0, n), "cut.off");
    EXPECT_FALSE(r.ok()) << "prefix of " << n << " bytes accepted";
  }
}

TEST(HostileTruncated, ObjMissingTriangleIsNotSilent) {
  // A truncated OBJ ends in the middle of a face line: "f 2 3" is a 2-vertex face.
  std::string text(kTetObj);
  text.resize(text.size() - 3);  // "f 2 3 4\n" -> "f 2 3"
  expect_error(read_obj(text, "cut.obj"), Error::Parse, "cut.obj");
}

TEST(HostileTruncated, ObjVertexWithTwoCoordinates) {
  expect_error(read_obj("v 0 0 0\nv 1 0 0\nv 0 1\n", "cut.obj"), Error::Parse, "cut.obj");
}

TEST(HostileTruncated, StlAsciiWithoutEndsolid) {
  std::string text = tet_stl_ascii();
  text.resize(text.find("endsolid"));
  expect_error(read_stl(text, "cut.stl"), Error::Parse, "cut.stl");
  text.resize(text.rfind("endloop"));  // and in the middle of a facet
  expect_error(read_stl(text, "cut.stl"), Error::Parse, "cut.stl");
}

TEST(HostileTruncated, StlBinaryShortOfItsCount) {
  const std::string bytes = tet_stl_binary();
  ASSERT_EQ(bytes.size(), 84u + 4 * 50u);
  expect_error(read_stl(std::string_view(bytes).substr(0, 84 + 2 * 50 + 17), "cut.stl"),
               Error::Parse, "cut.stl");
  expect_error(read_stl(std::string_view(bytes).substr(0, 60), "cut.stl"), Error::Parse, "cut.stl");
}

TEST(HostileTruncated, StlBinaryCountDisagreesWithSize) {
  std::string bytes = tet_stl_binary();
  const uint32_t lie = 1000000;
  std::memcpy(&bytes[80], &lie, 4);
  expect_error(read_stl(bytes, "count.stl"), Error::Parse, "count.stl");
  const uint32_t small = 3;  // one triangle's bytes left over
  std::memcpy(&bytes[80], &small, 4);
  expect_error(read_stl(bytes, "count.stl"), Error::Parse, "count.stl");
}

TEST(HostileTruncated, StlBinaryZeroTriangles) {
  std::string bytes(84, '\0');
  expect_error(read_stl(bytes, "none.stl"), Error::EmptyInput, "none.stl");
}

TEST(HostileTruncated, PlyAsciiMissingFaces) {
  std::string text(kTetPly);
  text.resize(text.rfind("3 1 2 3"));
  expect_error(read_ply(text, "cut.ply"), Error::Parse, "cut.ply");
}

TEST(HostileTruncated, PlyBinaryBodyShort) {
  std::string text =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4\n"
      "property list uchar int vertex_indices\nend_header\n";
  text.append(4 * 12 - 5, '\0');  // not even the vertices
  expect_error(read_ply(text, "cut.ply"), Error::Parse, "cut.ply");
}

TEST(HostileTruncated, PlyHeaderWithoutEnd) {
  std::string text(kTetPly);
  text.resize(text.find("end_header"));
  expect_error(read_ply(text, "cut.ply"), Error::Parse, "cut.ply");
}

TEST(HostileTruncated, MeditTruncated) {
  const std::string text = tet_medit();
  ASSERT_FALSE(text.empty());
  const size_t triangles = text.find("Triangles");
  ASSERT_NE(triangles, std::string::npos);
  // In the middle of the triangle block.
  expect_error(read_medit_surface(std::string_view(text).substr(0, triangles + 20), "cut.mesh"),
               Error::Parse, "cut.mesh");
  // Cut after the vertices: no triangle at all.
  Result<SurfaceMesh> r =
      read_medit_surface(std::string_view(text).substr(0, triangles), "cut.mesh");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.status().code() == Error::Parse || r.status().code() == Error::EmptyInput)
      << error_name(r.status().code());
}

TEST(HostileCounts, OffHeaderClaimsMoreVertices) {
  const std::string text = replace_all(kTetOff, "4 4 0", "5 4 0");
  expect_error(read_off(text, "count.off"), Error::Parse, "count.off");
}

TEST(HostileCounts, OffHeaderClaimsHugeCounts) {
  const std::string text = replace_all(kTetOff, "4 4 0", "4000000000 4000000000 0");
  expect_error(read_off(text, "count.off"), Error::Parse, "count.off");
  const std::string neg = replace_all(kTetOff, "4 4 0", "-4 4 0");
  expect_error(read_off(neg, "neg.off"), Error::Parse, "neg.off");
}

TEST(HostileCounts, OffHeaderClaimsFewerFaces) {
  // Faces left over after the counted ones: a user wants to hear about it, not a silent open mesh.
  const std::string text = replace_all(kTetOff, "4 4 0", "4 3 0");
  expect_error(read_off(text, "count.off"), Error::Parse, "count.off");
}

TEST(HostileCounts, OffFaceVertexCountWrong) {
  const std::string text = replace_all(kTetOff, "3 1 2 3", "4 1 2 3");
  expect_error(read_off(text, "face.off"), Error::Parse, "face.off");
  // A 2-gon (the file keeps its length, so the size check does not catch it first).
  const std::string two = replace_all(kTetOff, "3 1 2 3", "2 1 2  ");
  expect_error(read_off(two, "face.off"), Error::Parse, "face.off");
}

TEST(HostileCounts, PlyVertexCountWrong) {
  const std::string text = replace_all(kTetPly, "element vertex 4", "element vertex 6");
  expect_error(read_ply(text, "count.ply"), Error::Parse, "count.ply");
}

TEST(HostileCounts, PlyHeaderClaimsFewerFaces) {
  // As for OFF: faces after the announced ones are an error, not silently dropped.
  expect_error(read_ply(replace_all(kTetPly, "element face 4", "element face 3"), "count.ply"),
               Error::Parse, "count.ply");
}

TEST(HostileCounts, MeditVertexCountWrong) {
  std::string text = tet_medit();
  const size_t at = text.find("Vertices");
  ASSERT_NE(at, std::string::npos);
  const size_t num = text.find('4', at);
  ASSERT_NE(num, std::string::npos);
  text.replace(num, 1, "40");
  expect_error(read_medit_surface(text, "count.mesh"), Error::Parse, "count.mesh");
}

// ------------------------------------------------------------------------------------------------
// Indices.

TEST(HostileIndices, OffIndexOutOfRange) {
  expect_error(read_off(replace_all(kTetOff, "3 1 2 3", "3 1 2 4"), "idx.off"), Error::BadIndex,
               "idx.off");
  expect_error(read_off(replace_all(kTetOff, "3 1 2 3", "3 1 2 4294967299"), "idx.off"),
               Error::BadIndex, "idx.off");
}

TEST(HostileIndices, OffNegativeIndex) {
  Result<SurfaceMesh> r = read_off(replace_all(kTetOff, "3 1 2 3", "3 1 -2 3"), "neg.off");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.status().code() == Error::BadIndex || r.status().code() == Error::Parse)
      << error_name(r.status().code());
  EXPECT_NE(r.status().message().find("neg.off"), std::string::npos);
}

TEST(HostileIndices, ObjIndexZeroAndOutOfRange) {
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 0 3 4"), "zero.obj"), Error::BadIndex,
               "zero.obj");
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 2 3 5"), "big.obj"), Error::BadIndex,
               "big.obj");
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 2 3 -5"), "neg.obj"), Error::BadIndex,
               "neg.obj");
}

TEST(HostileIndices, ObjRelativeNegativeIndicesAreValid) {
  // -1 is the last vertex read so far: the same tetrahedron.
  const char text[] =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf -4 -2 -3\nf -4 -3 -1\nf -4 -1 -2\nf -3 -2 -1\n";
  expect_tetrahedron(read_obj(text, "rel.obj"));
}

TEST(HostileIndices, PlyIndexOutOfRangeAndNegative) {
  expect_error(read_ply(replace_all(kTetPly, "3 1 2 3", "3 1 2 9"), "idx.ply"), Error::BadIndex,
               "idx.ply");
  Result<SurfaceMesh> r = read_ply(replace_all(kTetPly, "3 1 2 3", "3 1 -2 3"), "neg.ply");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.status().code() == Error::BadIndex || r.status().code() == Error::Parse)
      << error_name(r.status().code());
}

TEST(HostileIndices, MeditIndexOutOfRange) {
  std::string text = tet_medit();
  const size_t tris = text.find("Triangles");
  ASSERT_NE(tris, std::string::npos);
  // The first triangle's first index (1-based "1") becomes 99.
  const size_t line = text.find('\n', text.find('\n', tris) + 1) + 1;
  text.replace(line, 1, "99");
  expect_error(read_medit_surface(text, "idx.mesh"), Error::BadIndex, "idx.mesh");
}

TEST(HostileIndices, ValidateRejectsBadIndexArrays) {
  SurfaceMesh m = tetrahedron();
  m.tri[5] = 17;
  ValidationReport report = validate(m);
  expect_problem(report, Error::BadIndex);
  SurfaceMesh sizes = tetrahedron();
  sizes.patch.pop_back();
  ValidationReport bad = validate(sizes);
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), Error::InvalidArgument) << bad.summary();
  Result<MesherResult> r = Mesher(fast_options()).run(sizes);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::InvalidArgument) << r.status().message();
}

// ------------------------------------------------------------------------------------------------
// Coordinates.

TEST(HostileCoordinates, NanAndInfFromTextAreReported) {
  for (const char* bad : {"nan", "inf", "-inf", "NaN"}) {
    SCOPED_TRACE(bad);
    // Readers keep non-finite values (surface_io.hpp); validation reports them.
    Result<SurfaceMesh> r =
        read_off(replace_all(kTetOff, "\n1 0 0\n", std::string("\n1 ") + bad + " 0\n"), "nan.off");
    ASSERT_TRUE(r.ok()) << r.status().message();
    ValidationReport report = validate(r.value());
    expect_problem(report, Error::NonFiniteCoordinate);
    EXPECT_EQ(report.status().code(), Error::NonFiniteCoordinate);
  }
}

TEST(HostileCoordinates, NanInMemoryFailsTheMesher) {
  SurfaceMesh m = tetrahedron();
  m.xyz[4] = std::numeric_limits<double>::quiet_NaN();
  expect_problem(validate(m), Error::NonFiniteCoordinate);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::NonFiniteCoordinate) << r.status().message();
}

TEST(HostileCoordinates, CoordinateOverflowingDouble) {
  // 1e400 does not fit a double: read as infinity, which validation reports.
  Result<SurfaceMesh> r = read_off(replace_all(kTetOff, "\n1 0 0\n", "\n1e400 0 0\n"), "big.off");
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_problem(validate(r.value()), Error::NonFiniteCoordinate);
}

TEST(HostileCoordinates, HugeCoordinatesValidate) {
  // 1e300: exact predicates keep the topology and orientation checks right.
  SurfaceMesh m = cube(-1e300, 1e300);
  ValidationReport report = validate(m);
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(HostileCoordinates, HugeCoordinatesMesherNeverLies) {
  // The Mesher either meshes the box (finite points) or says why it cannot; today it says why
  // (see LargeCoordinatesAreRefusedByRange below).
  SurfaceMesh m = cube(-1e300, 1e300);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  if (!r.ok()) {
    EXPECT_FALSE(r.status().message().empty());
    return;
  }
  EXPECT_GT(r->mesh.num_tets(), 0u);
  for (double c : r->mesh.xyz) EXPECT_TRUE(std::isfinite(c));
}

// A cube of half-side 1e100 (also 1e300) passes validation, but stage 1's floating-point tests
// overflow there: the Mesher meshes it scaled by a power of two (exact) and scales the mesh back,
// so it is the mesh of the scaled cube, scaled back bit for bit, and a notice says so.
TEST(HostileCoordinates, LargeCoordinatesAreMeshedScaledByAPowerOfTwo) {
  for (double h : {1e100, 1e300}) {
    Result<MesherResult> r = Mesher(fast_options()).run(cube(-h, h));
    ASSERT_TRUE(r.ok()) << r.status().message();
    const int k = -std::ilogb(2 * h);
    Result<MesherResult> scaled = Mesher(fast_options()).run(cube(-std::ldexp(h, k), std::ldexp(h, k)));
    ASSERT_TRUE(scaled.ok()) << scaled.status().message();
    ASSERT_EQ(r->mesh.tet, scaled->mesh.tet);
    ASSERT_EQ(r->mesh.xyz.size(), scaled->mesh.xyz.size());
    for (size_t i = 0; i < r->mesh.xyz.size(); ++i) ASSERT_EQ(r->mesh.xyz[i], std::ldexp(scaled->mesh.xyz[i], -k));
    ASSERT_FALSE(r->notices.empty());
    EXPECT_EQ(r->notices.back().kind, "scaled");
  }
}

// What no power of two brings into range exactly is refused, saying why: a coordinate that would
// lose bits below the smallest normal double when a box of extent 2e300 is scaled to about 1.
TEST(HostileCoordinates, CoordinatesNoExactScalingFitsAreRefused) {
  SurfaceMesh m = cube(-1e300, 1e300);
  m.xyz[0] = 4e-310;
  Result<MesherResult> r = Mesher(fast_options()).run_validated(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::NotImplemented);
  EXPECT_NE(r.status().message().find("no exact scaling by a power of two"), std::string::npos) << r.status().message();
}

// The largest the range allows: a cube of half-side 1e30 meshes.
TEST(HostileCoordinates, LargeCoordinatesMeshUpToTheRange) {
  Result<MesherResult> r = Mesher(fast_options()).run(cube(-1e30, 1e30));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->mesh.num_tets(), 0u);
}

// A cube of half-side 1e-30: the sizing grid's voxels are far below what an OpenVDB transform
// holds ("Non-zero scale values required" before); the field samples without it.
TEST(HostileCoordinates, SmallCoordinatesMesh) {
  Result<MesherResult> r = Mesher(fast_options()).run(cube(-1e-30, 1e-30));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->mesh.num_tets(), 0u);
}

// A cube of half-side 1e-100 passes validation (exact predicates), but stage 1's floating-point
// area test underflows there: meshed scaled by a power of two, like the large ones.
TEST(HostileCoordinates, TinyCoordinatesAreMeshedScaled) {
  Result<MesherResult> r = Mesher(fast_options()).run(cube(-1e-100, 1e-100));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GT(r->mesh.num_tets(), 0u);
  for (double c : r->mesh.xyz) EXPECT_LE(std::fabs(c), 1e-100);
}

TEST(HostileCoordinates, TinyCoordinatesValidate) {
  // A cube of side 1e-200: no underflow to a flat mesh.
  SurfaceMesh m = cube(0.0, 1e-200);
  ValidationReport report = validate(m);
  EXPECT_TRUE(report.ok()) << report.summary();
}

// ------------------------------------------------------------------------------------------------
// Topology and geometry defects, found by validation (and the Mesher).

TEST(HostileSurface, DegenerateRepeatedVertex) {
  SurfaceMesh m = tetrahedron();
  m.add_triangle(0, 0, 1);
  expect_problem(validate(m), Error::DegenerateTriangle);
}

TEST(HostileSurface, DegenerateCollinearZeroArea) {
  // A tetrahedron whose apex sits on an edge of the base: the side triangles are collinear.
  SurfaceMesh m = tetrahedron();
  m.xyz[9] = 0.5;  // vertex 3 -> (0.5, 0, 0): on edge 0-1
  m.xyz[11] = 0.0;
  ValidationReport report = validate(m);
  expect_problem(report, Error::DegenerateTriangle);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::DegenerateTriangle) << r.status().message();
}

TEST(HostileSurface, DuplicateTriangle) {
  SurfaceMesh m = tetrahedron();
  m.add_triangle(1, 2, 3);
  expect_problem(validate(m), Error::DuplicateTriangle);
}

TEST(HostileSurface, DuplicateVerticesAreMerged) {
  // Vertex 4 repeats vertex 0's coordinates: the repair merges it and the surface is clean.
  SurfaceMesh m = tetrahedron();
  m.add_vertex(0, 0, 0);
  m.tri[3] = 4;  // triangle 1 uses the copy
  ValidationReport report = validate_surface(m);
  EXPECT_TRUE(report.ok()) << report.summary();
  ASSERT_FALSE(report.repairs.empty());
  EXPECT_EQ(report.repairs[0].kind, "merged_duplicate_vertices");
  EXPECT_EQ(m.num_vertices(), 4u);
  // Without the repair the copy leaves open edges.
  SurfaceMesh raw = tetrahedron();
  raw.add_vertex(0, 0, 0);
  raw.tri[3] = 4;
  ValidationOptions no_merge;
  no_merge.merge_duplicate_vertices = false;
  EXPECT_FALSE(validate(raw, no_merge).ok());
}

TEST(HostileSurface, UnreferencedVerticesWarnOnly) {
  SurfaceMesh m = tetrahedron();
  m.add_vertex(5, 5, 5);
  m.add_vertex(-5, 5, 5);
  ValidationReport report = validate(m);
  EXPECT_TRUE(report.ok()) << report.summary();
  const Problem* p = report.find("unreferenced_vertex");
  ASSERT_NE(p, nullptr) << report.summary();
  EXPECT_EQ(p->severity, Severity::Warning);
  EXPECT_EQ(p->count, 2u);
}

TEST(HostileSurface, OpenSurfaceOneTriangleRemoved) {
  SurfaceMesh m = cube();
  m.tri.resize(m.tri.size() - 3);
  m.patch.pop_back();
  expect_problem(validate(m), Error::OpenBoundary);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::OpenBoundary) << r.status().message();
}

TEST(HostileSurface, NonManifoldEdgeThreeTriangles) {
  // A fin: one more triangle on the tetrahedron's edge 0-1, which then carries 3 triangles.
  SurfaceMesh m = tetrahedron();
  m.add_vertex(0.5, -1, -1);
  m.add_triangle(0, 1, 4);
  expect_problem(validate(m), Error::NonManifoldEdge);
}

TEST(HostileSurface, NonManifoldVertexTwoTetsTouching) {
  // Two tetrahedra sharing only vertex 3 = (0, 0, 1): the second one stands on it, upside down.
  SurfaceMesh m = tetrahedron();
  m.add_vertex(0, 0, 2);    // 4
  m.add_vertex(1, 0, 2);    // 5
  m.add_vertex(0, 1, 2);    // 6
  m.add_triangle(4, 5, 6);  // top, normal +z
  m.add_triangle(3, 5, 4);
  m.add_triangle(3, 6, 5);
  m.add_triangle(3, 4, 6);
  ValidationReport report = validate(m);
  expect_problem(report, Error::NonManifoldVertex);
  EXPECT_EQ(report.count(Error::OpenBoundary), 0u) << report.summary();
}

// One triangle facing the other way on a closed orientable shell: reoriented to match its
// neighbours (a repair the report lists) and meshed; refused when that repair is off.
TEST(HostileSurface, InconsistentOrientationOneTriangleFlipped) {
  SurfaceMesh m = cube();
  std::swap(m.tri[4], m.tri[5]);
  SurfaceMesh kept = m;
  ValidationOptions no_repair;
  no_repair.orient_triangles = false;
  expect_problem(validate_surface(kept, no_repair), Error::InconsistentOrientation);
  SurfaceMesh repaired = m;
  const ValidationReport report = validate_surface(repaired);
  EXPECT_TRUE(report.ok()) << report.summary();
  ASSERT_EQ(report.repairs.size(), 1u);
  EXPECT_EQ(report.repairs[0].kind, "reoriented_triangles");
  EXPECT_EQ(repaired.tri, cube().tri);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  MesherOptions strict = fast_options();
  strict.validation.orient_triangles = false;
  Result<MesherResult> refused = Mesher(strict).run(m);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), Error::InconsistentOrientation) << refused.status().message();
}

TEST(HostileSurface, InvertedClosedSurfaceIsFlippedOrReported) {
  SurfaceMesh m = cube();
  flip_all(m);
  // Default: the safe repair flips the shell outward and the surface meshes.
  SurfaceMesh repaired = m;
  ValidationReport report = validate_surface(repaired);
  EXPECT_TRUE(report.ok()) << report.summary();
  ASSERT_FALSE(report.repairs.empty());
  EXPECT_EQ(report.repairs[0].kind, "flipped_shell");
  ASSERT_EQ(report.shells.size(), 1u);
  EXPECT_GT(report.shells[0].signed_volume, 0.0);
  // Without the repair: an orientation error.
  ValidationOptions keep;
  keep.orient_shells = false;
  expect_problem(validate(m, keep), Error::InconsistentOrientation);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 1.0, 1e-9);
}

TEST(HostileSurface, SelfIntersectingFoldedCube) {
  // Corner (1,1,1) pushed through the bottom face.
  SurfaceMesh m = cube();
  m.xyz[3 * 7 + 0] = 0.3;
  m.xyz[3 * 7 + 1] = 0.3;
  m.xyz[3 * 7 + 2] = -0.5;
  ValidationReport report = validate(m);
  expect_problem(report, Error::SelfIntersection);
  EXPECT_FALSE(report.intersecting_pairs.empty());
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::SelfIntersection) << r.status().message();
}

TEST(HostileSurface, TwoOverlappingShells) {
  SurfaceMesh m = cube(0.0, 1.0);
  add_cube(m, 0.5, 1.5);
  ValidationReport report = validate(m);
  expect_problem(report, Error::IntersectingShells);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::IntersectingShells) << r.status().message();
}

TEST(HostileSurface, TwoShellsTouchingFaceToFace) {
  // Coplanar touching faces: the boxes share the plane x = 1 (distinct vertices).
  SurfaceMesh m = cube(0.0, 1.0);
  SurfaceMesh other = cube(0.0, 1.0);
  const uint32_t base = static_cast<uint32_t>(m.num_vertices());
  for (size_t v = 0; v < other.num_vertices(); ++v) {
    m.add_vertex(other.xyz[3 * v] + 1.0, other.xyz[3 * v + 1] + 0.25, other.xyz[3 * v + 2]);
  }
  for (size_t t = 0; t < other.num_triangles(); ++t) {
    m.add_triangle(base + other.tri[3 * t], base + other.tri[3 * t + 1],
                   base + other.tri[3 * t + 2]);
  }
  expect_problem(validate(m), Error::IntersectingShells);
}

TEST(HostileSurface, FewerThanFourTriangles) {
  for (size_t keep : {1u, 2u, 3u}) {
    SurfaceMesh m = tetrahedron();
    m.tri.resize(3 * keep);
    m.patch.resize(keep);
    SCOPED_TRACE(keep);
    expect_problem(validate(m), Error::OpenBoundary);
  }
  SurfaceMesh none = tetrahedron();
  none.tri.clear();
  none.patch.clear();
  ValidationReport report = validate(none);
  EXPECT_EQ(report.status().code(), Error::EmptyInput) << report.summary();
}

TEST(HostileSurface, TwoTrianglesBackToBack) {
  // A closed "surface" of zero volume: two triangles on the same vertices.
  SurfaceMesh m;
  m.add_vertex(0, 0, 0);
  m.add_vertex(1, 0, 0);
  m.add_vertex(0, 1, 0);
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 2, 1);
  expect_problem(validate(m), Error::DuplicateTriangle);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  expect_some_error(r, "");
  EXPECT_EQ(r.status().code(), Error::DuplicateTriangle) << r.status().message();
}

TEST(HostileSurface, FlatClosedSurfaceZeroVolume) {
  // The tetrahedron with its apex pushed into the base plane: closed, but no volume.
  SurfaceMesh m = tetrahedron();
  m.xyz[9] = 0.25;
  m.xyz[10] = 0.25;
  m.xyz[11] = 0.0;
  ValidationReport report = validate(m);
  // Its four triangles overlap in the plane z = 0.
  expect_problem(report, Error::SelfIntersection);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  expect_some_error(r, "");
  EXPECT_EQ(r.status().code(), Error::SelfIntersection) << r.status().message();
}

// ------------------------------------------------------------------------------------------------
// Valid surfaces that look suspicious: they must mesh.

TEST(HostileValid, SingleTetrahedronMeshes) {
  Result<MesherResult> r = Mesher(fast_options()).run(tetrahedron());
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_GE(r->mesh.num_tets(), 1u);
  EXPECT_NEAR(mesh_volume(r->mesh), 1.0 / 6.0, 1e-12);
}

TEST(HostileValid, NeedleTetrahedronMeshes) {
  // Base 1e-3, height 1: aspect ratio 1000.
  SurfaceMesh m;
  m.add_vertex(0, 0, 0);
  m.add_vertex(1e-3, 0, 0);
  m.add_vertex(0, 1e-3, 0);
  m.add_vertex(0, 0, 1);
  SurfaceMesh t = tetrahedron();
  m.tri = t.tri;
  m.patch = t.patch;
  ValidationReport report = validate(m);
  ASSERT_TRUE(report.ok()) << report.summary();
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 1e-6 / 6.0, 1e-16);
}

TEST(HostileValid, NestedShellsMeshWithACavity) {
  SurfaceMesh m = cube(-1.0, 2.0);  // outer, volume 27
  add_cube(m, 0.0, 1.0);            // inner, outward as given: the repair turns it into a cavity
  ValidationReport report = validate(m);
  ASSERT_TRUE(report.ok()) << report.summary();
  ASSERT_EQ(report.shells.size(), 2u);
  EXPECT_EQ(report.num_regions, 1u);
  EXPECT_EQ(report.shells[1].depth, 1);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 26.0, 1e-9);
}

TEST(HostileValid, TriangleSizeRatioOfAMillion) {
  // The cube's top face as a fan around a point 1e-6 from corner 4: areas 5e-7 next to 0.5.
  SurfaceMesh m = cube();
  m.tri.erase(m.tri.begin() + 6, m.tri.begin() + 12);  // the two top triangles (quad 4 5 7 6)
  m.patch.resize(10);
  m.add_vertex(1e-6, 1e-6, 1.0);  // 8
  m.add_triangle(4, 5, 8);
  m.add_triangle(5, 7, 8);
  m.add_triangle(7, 6, 8);
  m.add_triangle(6, 4, 8);
  ValidationReport report = validate(m);
  ASSERT_TRUE(report.ok()) << report.summary();
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 1.0, 1e-9);
}

TEST(HostileSurface, ZeroThicknessWallInsideACube) {
  // An internal wall (the diagonal plane x = y) glued to the cube's edges: its edges 0-4 and
  // 3-7 each carry 3 triangles.
  SurfaceMesh m = cube();
  m.add_triangle(0, 3, 7);
  m.add_triangle(0, 7, 4);
  ValidationReport report = validate(m);
  expect_problem(report, Error::NonManifoldEdge);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), report.status().code()) << r.status().message();
}

TEST(HostileValid, CubeFarFromOrigin) {
  SurfaceMesh m = cube(1e6, 1e6 + 1.0);
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 1.0, 1e-3);
}

// ------------------------------------------------------------------------------------------------
// Text variants that are valid.

TEST(HostileText, CrlfLineEndings) {
  expect_tetrahedron(read_off(replace_all(kTetOff, "\n", "\r\n"), "crlf.off"));
  expect_tetrahedron(read_obj(replace_all(kTetObj, "\n", "\r\n"), "crlf.obj"));
  expect_tetrahedron(read_ply(replace_all(kTetPly, "\n", "\r\n"), "crlf.ply"));
  expect_tetrahedron(read_stl(replace_all(tet_stl_ascii(), "\n", "\r\n"), "crlf.stl"));
}

TEST(HostileText, CommentsAndBlankLines) {
  const char off[] =
      "# a tetrahedron\nOFF\n\n# counts\n4 4 0\n\n0 0 0 # origin\n1 0 0\n\n0 1 0\n0 0 1\n"
      "# faces\n3 0 2 1\n3 0 1 3\n\n3 0 3 2\n3 1 2 3\n# end\n";
  expect_tetrahedron(read_off(off, "comments.off"));
  const char obj[] =
      "# made by hand\n\nmtllib none.mtl\nv 0 0 0\nv 1 0 0 # x\n\nv 0 1 0\nv 0 0 1\n"
      "vn 0 0 1\n# faces\nf 1 3 2\nf 1 2 4\n\nf 1 4 3\nf 2 3 4\n";
  expect_tetrahedron(read_obj(obj, "comments.obj"));
}

TEST(HostileText, ObjQuadsAreFanTriangulated) {
  const char obj[] =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
      "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  Result<SurfaceMesh> r = read_obj(obj, "quads.obj");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->num_triangles(), 12u);
  SurfaceMesh m = r.value();
  ValidationReport report = validate_surface(m);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_TRUE(report.repairs.empty());
}

TEST(HostileText, ObjSlashFormsAndGarbageTokens) {
  const char ok[] =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n"
      "f 1/1/1 3/1/1 2/1/1\nf 1//1 2//1 4//1\nf 1/1 4/1 3/1\nf 2 3 4\n";
  expect_tetrahedron(read_obj(ok, "slash.obj"));
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 2 3 x"), "bad.obj"), Error::Parse,
               "bad.obj");
  expect_error(read_obj(replace_all(kTetObj, "v 0 0 1", "v 0 0 zz"), "bad.obj"), Error::Parse,
               "bad.obj");
}

TEST(HostileText, OffWrongKeyword) {
  expect_error(read_off(replace_all(kTetOff, "OFF", "PFF"), "kw.off"), Error::Parse, "kw.off");
  expect_error(read_off(replace_all(kTetOff, "OFF", "4OFF"), "kw.off"), Error::UnsupportedFormat,
               "kw.off");
}

TEST(HostileText, StlSolidHeaderWithBinaryContent) {
  std::string bytes = tet_stl_binary();
  const char header[] = "solid exported by a CAD system";
  std::memcpy(&bytes[0], header, sizeof header - 1);
  Result<SurfaceMesh> r = read_stl(bytes, "solid.stl");
  expect_tetrahedron(r);
}

TEST(HostileText, StlAsciiNonNumericVertex) {
  expect_error(read_stl(replace_all(tet_stl_ascii(), "vertex 0 0 1", "vertex 0 zero 1"), "bad.stl"),
               Error::Parse, "bad.stl");
}

TEST(HostileText, PlyUnsupportedOrWrongFormatLine) {
  Result<SurfaceMesh> r = read_ply(
      replace_all(kTetPly, "format ascii 1.0", "format binary_middle_endian 1.0"), "f.ply");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.status().code() == Error::UnsupportedFormat || r.status().code() == Error::Parse)
      << error_name(r.status().code());
  expect_error(read_ply(replace_all(kTetPly, "ply\n", "plx\n"), "m.ply"), Error::Parse, "m.ply");
}

TEST(HostileText, ObjVerticesOnly) {
  expect_error(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "pts.obj"), Error::EmptyInput, "pts.obj");
}

TEST(HostileText, ObjFaceWithOneOrTwoVertices) {
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 2"), "one.obj"), Error::Parse,
               "one.obj");
  expect_error(read_obj(replace_all(kTetObj, "f 2 3 4", "f 2 3"), "two.obj"), Error::Parse,
               "two.obj");
}

TEST(HostileText, StlAsciiSolidOnly) {
  Result<SurfaceMesh> r = read_stl("solid empty\nendsolid empty\n", "empty.stl");
  expect_error(r, Error::EmptyInput, "empty.stl");
  expect_error(read_stl("solid", "bare.stl"), Error::Parse, "bare.stl");
}

TEST(HostileText, PlyHugeElementCounts) {
  // Counts that cannot fit the file must fail at once, not allocate or loop.
  expect_error(
      read_ply(replace_all(kTetPly, "element vertex 4", "element vertex 4000000000"), "huge.ply"),
      Error::Parse, "huge.ply");
  std::string bin =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4000000000\n"
      "property list uchar int vertex_indices\nend_header\n";
  bin.append(64, '\0');
  expect_error(read_ply(bin, "huge.ply"), Error::Parse, "huge.ply");
}

TEST(HostileText, PlyFaceListCountTooSmallOrHuge) {
  expect_error(read_ply(replace_all(kTetPly, "3 1 2 3", "2 1 2"), "two.ply"), Error::Parse,
               "two.ply");
  expect_error(read_ply(replace_all(kTetPly, "3 1 2 3", "200 1 2 3"), "many.ply"), Error::Parse,
               "many.ply");
}

TEST(HostileText, GmshTruncated) {
  const char msh[] = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n";
  expect_error(read_gmsh_surface(msh, "cut.msh"), Error::Parse, "cut.msh");
  expect_error(read_gmsh_surface("$MeshFormat\n9.9 0 8\n$EndMeshFormat\n", "v.msh"),
               Error::UnsupportedFormat, "v.msh");
}

TEST(HostileText, MeditTwoDimensional) {
  const char mesh2d[] =
      "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\n"
      "Triangles\n1\n1 2 3 0\nEnd\n";
  expect_error(read_medit_surface(mesh2d, "flat.mesh"), Error::UnsupportedFormat, "flat.mesh");
}

TEST(HostileText, HugeTokenAndLongLine) {
  // One megabyte of digits as a coordinate: an error, quickly.
  std::string text = "OFF\n4 4 0\n";
  text += std::string(1 << 20, '7');
  text += " 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  Result<SurfaceMesh> r = read_off(text, "long.off");
  // 7777...7 overflows a double: read as infinity (kept, surface_io.hpp), reported by validation.
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_problem(validate(r.value()), Error::NonFiniteCoordinate);
  std::string obj = "f";
  for (int i = 0; i < 100000; ++i) obj += " 1";
  expect_error(read_obj(obj, "longface.obj"), Error::BadIndex, "longface.obj");
}

TEST(HostileSurface, SliverButValidTetrahedron) {
  // Apex 1e-9 above the base plane: tiny volume, nonzero; valid, and it meshes.
  SurfaceMesh m = tetrahedron();
  m.xyz[9] = 0.3;
  m.xyz[10] = 0.3;
  m.xyz[11] = 1e-9;
  ValidationReport report = validate(m);
  EXPECT_TRUE(report.ok()) << report.summary();
  Result<MesherResult> r = Mesher(fast_options()).run(m);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(mesh_volume(r->mesh), 1e-9 / 6.0, 1e-20);
}

// ------------------------------------------------------------------------------------------------
// Options out of range.

TEST(HostileOptions, MesherNegativeOrNanSizeScale) {
  for (double s : {-1.0, 0.0, std::numeric_limits<double>::quiet_NaN()}) {
    SCOPED_TRACE(s);
    MesherOptions o = fast_options();
    o.refine.size_scale = s;
    Result<MesherResult> r = Mesher(o).run(tetrahedron());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), Error::InvalidArgument) << r.status().message();
  }
}

TEST(HostileOptions, MesherZeroLayers) {
  MesherOptions o = fast_options();
  o.layers.layers = 0;
  Result<MesherResult> r = Mesher(o).run(tetrahedron());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::InvalidArgument) << r.status().message();
}

TEST(HostileOptions, MesherCancelledAtOnce) {
  MesherOptions o = fast_options();
  o.progress = [](const std::string&, double) { return false; };
  Result<MesherResult> r = Mesher(o).run(tetrahedron());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Error::Cancelled) << r.status().message();
}

// ------------------------------------------------------------------------------------------------
// The C ABI.

struct CSurface {
  anitet_surface* s = nullptr;
  ~CSurface() { anitet_surface_destroy(s); }
};
struct CMesh {
  anitet_mesh* m = nullptr;
  ~CMesh() { anitet_mesh_destroy(m); }
};

int c_tetrahedron(CSurface& out) {
  const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return anitet_surface_create(xyz, 4, tri, 4, nullptr, 0, &out.s);
}

TEST(HostileCApi, SurfaceCreateBadArguments) {
  const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  const int32_t bad_tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, -3};
  anitet_surface* s = nullptr;
  EXPECT_EQ(anitet_surface_create(nullptr, 4, tri, 4, nullptr, 0, &s), ANITET_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(anitet_surface_create(xyz, -4, tri, 4, nullptr, 0, &s), ANITET_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(anitet_surface_create(xyz, 4, tri, 4, nullptr, 2, &s), ANITET_ERR_INVALID_ARGUMENT);
  EXPECT_STRNE(anitet_last_error_message(), "");
  EXPECT_EQ(anitet_surface_create(xyz, 4, tri, 0, nullptr, 0, &s), ANITET_ERR_EMPTY_INPUT);
  EXPECT_EQ(anitet_surface_create(xyz, 4, bad_tri, 4, nullptr, 0, &s), ANITET_ERR_BAD_INDEX);
  EXPECT_EQ(anitet_surface_create(xyz, 4, tri, 4, nullptr, 1, &s), ANITET_ERR_BAD_INDEX);
  EXPECT_EQ(s, nullptr);
}

TEST(HostileCApi, SurfaceReadMissingAndGarbage) {
  TempDir dir;
  anitet_surface* s = nullptr;
  EXPECT_EQ(anitet_surface_read(nullptr, &s), ANITET_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(anitet_surface_read((dir.path() + "/none.stl").c_str(), &s), ANITET_ERR_FILE_NOT_FOUND);
  EXPECT_EQ(anitet_surface_read(dir.write("junk.off", "OFF\n4 4 0\n0 0 0\n").c_str(), &s),
            ANITET_ERR_PARSE);
  EXPECT_NE(std::strstr(anitet_last_error_message(), "junk.off"), nullptr)
      << anitet_last_error_message();
  EXPECT_EQ(s, nullptr);
}

TEST(HostileCApi, ValidateReportsOpenSurface) {
  const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2};
  CSurface s;
  ASSERT_EQ(anitet_surface_create(xyz, 4, tri, 3, nullptr, 0, &s.s), ANITET_OK);
  EXPECT_EQ(anitet_surface_validate(s.s, nullptr), ANITET_ERR_OPEN_BOUNDARY);
  int64_t count = 0;
  ASSERT_EQ(anitet_surface_problem_count(s.s, ANITET_ERR_OPEN_BOUNDARY, &count), ANITET_OK);
  EXPECT_EQ(count, 3);
  CMesh mesh;
  EXPECT_EQ(anitet_mesher_run(s.s, nullptr, nullptr, &mesh.m), ANITET_ERR_OPEN_BOUNDARY);
  EXPECT_EQ(mesh.m, nullptr);
}

TEST(HostileCApi, MesherOptionsOutOfRange) {
  CSurface s;
  ASSERT_EQ(c_tetrahedron(s), ANITET_OK);
  struct Case {
    const char* what;
    void (*set)(anitet_options&);
  };
  const Case cases[] = {
      {"negative size_scale", [](anitet_options& o) { o.size_scale = -1.0; }},
      {"zero size_scale", [](anitet_options& o) { o.size_scale = 0.0; }},
      {"NaN size_scale", [](anitet_options& o) { o.size_scale = std::nan(""); }},
      {"infinite size_scale",
       [](anitet_options& o) { o.size_scale = std::numeric_limits<double>::infinity(); }},
      {"zero layers", [](anitet_options& o) { o.layers = 0; }},
      {"negative layers", [](anitet_options& o) { o.layers = -3; }},
      {"unknown layer scheme", [](anitet_options& o) { o.layer_scheme = 7; }},
      {"NaN recovery time", [](anitet_options& o) { o.recovery_max_seconds = std::nan(""); }},
      {"negative recovery time", [](anitet_options& o) { o.recovery_max_seconds = -1.0; }},
      {"unknown version", [](anitet_options& o) { o.version = 99; }},
      {"version 0", [](anitet_options& o) { o.version = 0; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    anitet_options o = ANITET_OPTIONS_INIT;
    c.set(o);
    CMesh mesh;
    EXPECT_EQ(anitet_mesher_run(s.s, nullptr, &o, &mesh.m), ANITET_ERR_INVALID_ARGUMENT);
    EXPECT_STRNE(anitet_last_error_message(), "");
    EXPECT_EQ(mesh.m, nullptr);
  }
  EXPECT_EQ(anitet_options_init(nullptr, ANITET_OPTIONS_VERSION), ANITET_ERR_INVALID_ARGUMENT);
  anitet_options o;
  EXPECT_EQ(anitet_options_init(&o, 0), ANITET_ERR_INVALID_ARGUMENT);
}

TEST(HostileCApi, MesherRunsOnATetrahedron) {
  CSurface s;
  ASSERT_EQ(c_tetrahedron(s), ANITET_OK);
  anitet_options o = ANITET_OPTIONS_INIT;
  o.num_threads = 1;
  CMesh mesh;
  ASSERT_EQ(anitet_mesher_run(s.s, nullptr, &o, &mesh.m), ANITET_OK) << anitet_last_error_message();
  int64_t np = 0, nt = 0, nb = 0;
  ASSERT_EQ(anitet_mesh_get_counts(mesh.m, &np, &nt, &nb), ANITET_OK);
  EXPECT_EQ(nb, 4);
  EXPECT_GE(np, 4);
  EXPECT_GE(nt, 1);
  CMesh none;  // a failed call sets *out to NULL
  EXPECT_EQ(anitet_mesher_run(nullptr, nullptr, &o, &none.m), ANITET_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(none.m, nullptr);
}

}  // namespace
}  // namespace anitet
