// STL, ASCII or binary. Binary: 80-byte header, uint32 count, then per triangle 12 floats (normal,
// 3 corners) and a 2-byte attribute (not a label). Corners are merged by exact coordinates.
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "io/byte_reader.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"
#include "io/vertex_merger.hpp"

namespace anitet {

namespace {

constexpr size_t kBinaryHeader = 84;
constexpr size_t kBinaryTriangle = 50;

bool is_text_byte(unsigned char c) { return (c >= 32 && c < 127) || (c >= 9 && c <= 13); }

bool starts_with_solid(std::string_view data) {
  size_t i = 0;
  while (i < data.size() &&
         (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) {
    ++i;
  }
  return data.size() - i >= 5 && iequals(data.substr(i, 5), "solid");
}

bool all_text(std::string_view data) {
  for (unsigned char c : data) {
    if (!is_text_byte(c)) return false;
  }
  return true;
}

// Binary files often start with "solid" too: the size formula and the bytes decide. A file that
// starts with "solid" is ASCII unless its size fits the binary layout and it is not all text, or
// its first bytes are not text (a truncated binary file, reported as such).
bool is_binary_stl(std::string_view data) {
  if (!starts_with_solid(data)) return true;
  if (data.size() < kBinaryHeader) return false;
  uint32_t count;
  std::memcpy(&count, data.data() + 80, 4);
  if (uint64_t{count} * kBinaryTriangle + kBinaryHeader != data.size()) {
    return !all_text(data.substr(0, 1024));
  }
  return !all_text(data) || data.find("endsolid") == std::string_view::npos;
}

Result<SurfaceMesh> parse_binary_stl(std::string_view data, const std::string& name) {
  ByteReader in(data, name);
  uint32_t count = 0;
  if (!in.skip(80) || !in.read(count)) {
    return in.error(Error::Parse,
                    "expected the 80-byte header and the triangle count of a binary STL");
  }
  if (uint64_t{count} * kBinaryTriangle != in.remaining()) {
    return in.error(Error::Parse,
                    "binary STL with " + std::to_string(count) + " triangles needs " +
                        std::to_string(uint64_t{count} * kBinaryTriangle + kBinaryHeader) +
                        " bytes, but the file has " + std::to_string(data.size()));
  }
  if (count == 0) return Status(Error::EmptyInput, name + ": the STL file has no triangles");
  SurfaceMesh mesh;
  mesh.tri.reserve(3 * size_t{count});
  mesh.patch.assign(count, 0);
  mesh.xyz.reserve(3 * (size_t{count} / 2 + 3));
  ExactVertexMerger merger(mesh.xyz, count / 2 + 3);
  const char* p = data.data() + kBinaryHeader;
  for (uint32_t t = 0; t < count; ++t, p += kBinaryTriangle) {
    float f[9];
    std::memcpy(f, p + 12, sizeof f);  // skip the normal
    for (int k = 0; k < 3; ++k) {
      mesh.tri.push_back(merger.insert(f[3 * k], f[3 * k + 1], f[3 * k + 2]));
    }
  }
  return mesh;
}

// The patch label of each `solid` block: a named block shares the label of an earlier block of
// the same name (one patch exported in pieces), an unnamed one gets a label of its own.
class SolidLabels {
 public:
  int32_t label_of(std::string_view name) {
    if (!name.empty()) {
      auto [it, fresh] = by_name_.emplace(std::string(name), static_cast<int32_t>(texts_.size() + 1));
      if (!fresh) return it->second;
    }
    texts_.emplace_back(name);
    has_triangles_.push_back(false);
    return static_cast<int32_t>(texts_.size());
  }
  void add_triangles(int32_t label) { has_triangles_[static_cast<size_t>(label - 1)] = true; }
  // The labels with triangles, increasing, with their texts.
  std::map<int32_t, std::string> used() const {
    std::map<int32_t, std::string> out;
    for (size_t i = 0; i < texts_.size(); ++i) {
      if (has_triangles_[i]) out.emplace(static_cast<int32_t>(i + 1), texts_[i]);
    }
    return out;
  }

 private:
  std::vector<std::string> texts_;  // the name after `solid` of label i + 1, "" when none
  std::vector<bool> has_triangles_;
  std::map<std::string, int32_t> by_name_;
};

// One facet: [normal n n n] outer loop / vertex x y z (3 or more) / endloop / endfacet, after
// its `facet` keyword; fan-triangulated into `mesh` with `label`.
Status parse_facet(TextScanner& in, ExactVertexMerger& merger, std::vector<uint32_t>& polygon,
                   SurfaceMesh& mesh, int32_t label) {
  const size_t line = in.line();
  if (iequals(in.peek_token(), "normal")) {
    in.next_token();
    double n;
    for (int k = 0; k < 3; ++k) {
      if (!in.read_double(n)) return in.expected("a normal component");
    }
  }
  if (!in.read_keyword("outer")) return in.expected("'outer loop'");
  if (!in.read_keyword("loop")) return in.expected("'loop'");
  polygon.clear();
  while (iequals(in.peek_token(), "vertex")) {
    in.next_token();
    double p[3];
    for (double& c : p) {
      if (!in.read_double(c)) return in.expected("a vertex coordinate");
    }
    if (mesh.num_vertices() >= kMaxVertices) return in.error(Error::Parse, "too many vertices");
    polygon.push_back(merger.insert(p[0], p[1], p[2]));
  }
  if (polygon.size() < 3) return in.expected("'vertex' (a facet needs 3)");
  if (!in.read_keyword("endloop")) return in.expected("'endloop'");
  if (!in.read_keyword("endfacet")) return in.expected("'endfacet'");
  add_fan(mesh, polygon.data(), polygon.size(), label, line);
  return Status::success();
}

// With a single label in use, the file is one patch: label 0, unnamed (a lone solid's name is
// mostly the exporter's or the part's: "ascii", "Exported from ..."). Else each used label's
// `solid` name made a valid patch name (patch_names_from_text) into `names`.
void name_solids(SurfaceMesh& mesh, const SolidLabels& solids, PatchNames* names) {
  const std::map<int32_t, std::string> used = solids.used();
  if (used.size() == 1) {
    mesh.patch.assign(mesh.patch.size(), 0);
    return;
  }
  if (!names) return;
  for (auto& [label, name] : patch_names_from_text(used)) (*names)[label] = std::move(name);
}

// ASCII: solid name / facet ... / endsolid name, repeated; each block a patch (SolidLabels).
Result<SurfaceMesh> parse_ascii_stl(std::string_view data, const std::string& name, PatchNames* names) {
  TextScanner in(data, name, '\0');
  SurfaceMesh mesh;
  mesh.xyz.reserve(data.size() / 250 * 3);
  mesh.tri.reserve(data.size() / 250 * 3);
  ExactVertexMerger merger(mesh.xyz, data.size() / 500);
  std::vector<uint32_t> polygon;
  SolidLabels solids;
  while (in.skip_space()) {
    if (!in.read_keyword("solid")) return in.expected("'solid'");
    const int32_t label = solids.label_of(in.rest_of_line());
    for (;;) {
      std::string_view word = in.next_token();
      if (iequals(word, "endsolid")) {
        in.rest_of_line();
        break;
      }
      if (!iequals(word, "facet")) {
        return in.error(Error::Parse, "expected 'facet' or 'endsolid', found " +
                                          (word.empty() ? std::string("end of file")
                                                        : "'" + quote_token(word) + "'"));
      }
      if (Status s = parse_facet(in, merger, polygon, mesh, label); !s.ok()) return s;
      solids.add_triangles(label);
    }
  }
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the STL file has no triangles");
  name_solids(mesh, solids, names);
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_stl(std::string_view data, const std::string& name, PatchNames* names) {
  return catch_bad_alloc(name, [&] {
    return is_binary_stl(data) ? parse_binary_stl(data, name) : parse_ascii_stl(data, name, names);
  });
}

Result<std::string> to_stl_binary(const SurfaceMesh& mesh) {
  Status valid = check_surface_arrays(mesh);
  if (!valid.ok()) return valid;
  if (mesh.num_triangles() > UINT32_MAX) {
    return Status(Error::InvalidArgument, "too many triangles for a binary STL file");
  }
  std::string out(kBinaryHeader + kBinaryTriangle * mesh.num_triangles(), '\0');
  // The header must not start with "solid", or readers may take the file for ASCII.
  const char header[] = "binary STL written by anitet";
  std::memcpy(&out[0], header, sizeof header - 1);
  uint32_t count = static_cast<uint32_t>(mesh.num_triangles());
  std::memcpy(&out[80], &count, 4);
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const double* a = mesh.point(mesh.tri[3 * t]);
    const double* b = mesh.point(mesh.tri[3 * t + 1]);
    const double* c = mesh.point(mesh.tri[3 * t + 2]);
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    float f[12];
    for (int k = 0; k < 3; ++k) {
      f[k] = len > 0 ? static_cast<float>(n[k] / len) : 0.0f;
      f[3 + k] = static_cast<float>(a[k]);
      f[6 + k] = static_cast<float>(b[k]);
      f[9 + k] = static_cast<float>(c[k]);
    }
    std::memcpy(&out[kBinaryHeader + kBinaryTriangle * t], f, sizeof f);
  }
  return out;
}

}  // namespace anitet
