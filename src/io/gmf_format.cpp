// Binary Medit (GMF, libMeshb) .meshb and .solb: the keyword table, the blocks anitet keeps, and
// the writer. The layout is described in gmf_format.hpp. Data is decoded from memory with every
// size checked before the loop that reads it (the loops then run without bounds checks).
#include "io/gmf_format.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

constexpr int32_t kPrisms = 9, kHexahedra = 10, kPyramids = 49;  // cells a tet mesh cannot hold
constexpr uint64_t kInt32Max = uint64_t(std::numeric_limits<int32_t>::max());

// Word sizes of a version (see the table in gmf_format.hpp).
struct Words {
  size_t real, integer, position;
  explicit Words(int version)
      : real(version == 1 ? 4 : 8), integer(version == 4 ? 8 : 4), position(version >= 3 ? 8 : 4) {}
};

const char* keyword_name(int32_t code) {
  switch (code) {
    case gmf::kDimension: return "Dimension";
    case gmf::kVertices: return "Vertices";
    case gmf::kEdges: return "Edges";
    case gmf::kTriangles: return "Triangles";
    case gmf::kQuadrilaterals: return "Quadrilaterals";
    case gmf::kTetrahedra: return "Tetrahedra";
    case kPrisms: return "Prisms";
    case kHexahedra: return "Hexahedra";
    case kPyramids: return "Pyramids";
    case gmf::kEnd: return "End";
    case gmf::kSolAtVertices: return "SolAtVertices";
    default: return "keyword";
  }
}

// ------------------------------------------------------------------------------------------------
// Reading.

// A value of the file's byte order at p (the host is little-endian, as ByteReader assumes).
template <class T>
T load(const char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof b);
  if (swap) std::reverse(b, b + sizeof b);
  T v;
  std::memcpy(&v, b, sizeof v);
  return v;
}

struct Keyword {
  int32_t code = 0;
  size_t at = 0;    // offset of its code
  size_t data = 0;  // offset of its data (after the next-keyword position)
  size_t end = 0;   // the next keyword's position, or the end of the file
};

// The header and the keyword table of a GMF file.
class GmfFile {
 public:
  GmfFile(std::string_view data, const std::string& name) : data_(data), name_(name) {}

  Status scan();
  int version() const { return version_; }
  bool swap() const { return swap_; }
  const Words& words() const { return words_; }
  const std::vector<Keyword>& keywords() const { return keywords_; }
  const std::string& name() const { return name_; }
  std::string_view data() const { return data_; }

  Status error(size_t offset, const std::string& message, Error code = Error::Parse) const {
    return Status(code, name_ + ": byte offset " + std::to_string(offset) + ": " + message);
  }
  // An integer (int32, or int64 in version 4) or a position (int32 in versions 1-2) at `at`,
  // which must leave `size` bytes before `end`; false when it does not.
  bool integer(size_t at, size_t end, int64_t& v) const { return word(at, end, words_.integer, v); }
  bool position(size_t at, size_t end, int64_t& v) const { return word(at, end, words_.position, v); }
  bool int32(size_t at, size_t end, int32_t& v) const {
    if (at > end || end - at < 4) return false;
    v = load<int32_t>(data_.data() + at, swap_);
    return true;
  }
  double real(const char* p) const {
    return words_.real == 4 ? double(load<float>(p, swap_)) : load<double>(p, swap_);
  }
  int64_t integer(const char* p) const {
    return words_.integer == 4 ? int64_t(load<int32_t>(p, swap_)) : load<int64_t>(p, swap_);
  }

 private:
  bool word(size_t at, size_t end, size_t size, int64_t& v) const {
    if (at > end || end - at < size) return false;
    v = size == 4 ? int64_t(load<int32_t>(data_.data() + at, swap_)) : load<int64_t>(data_.data() + at, swap_);
    return true;
  }
  Status header();

  std::string_view data_;
  const std::string& name_;
  int version_ = 0;
  bool swap_ = false;
  Words words_{2};
  std::vector<Keyword> keywords_;
};

Status GmfFile::header() {
  int32_t code = 0;
  if (!int32(0, data_.size(), code)) return error(0, "expected the GMF byte-order word 1 (the file ends)");
  if (code == 1) {
    swap_ = false;
  } else if (code == 0x01000000) {
    swap_ = true;
  } else {
    if (data_.substr(0, 20).find("MeshVersion") != std::string_view::npos) {
      return error(0, "this is an ASCII Medit file (give it the extension .mesh or .sol)");
    }
    return error(0, "expected the GMF byte-order word 1 (little- or big-endian), found " + std::to_string(code));
  }
  int32_t version = 0;
  if (!int32(4, data_.size(), version)) return error(4, "expected the GMF version (the file ends)");
  if (version < 1 || version > 4) {
    return error(4, "GMF version " + std::to_string(version) + " (versions 1 to 4 are read)",
                 Error::UnsupportedFormat);
  }
  version_ = version;
  words_ = Words(version);
  return Status::success();
}

// Keywords from offset 8, each pointing to the next (strictly increasing, inside the file), until
// End or a zero position; the first must be Dimension.
Status GmfFile::scan() {
  if (Status s = header(); !s.ok()) return s;
  size_t at = 8;
  for (;;) {
    Keyword k;
    k.at = at;
    if (!int32(at, data_.size(), k.code)) return error(at, "expected a keyword code (the file ends)");
    int64_t next = 0;
    if (!position(at + 4, data_.size(), next)) {
      return error(at + 4, std::string("expected the position of the keyword after ") + keyword_name(k.code) +
                               " (the file ends)");
    }
    if (keywords_.empty() && k.code != gmf::kDimension) {
      return error(at, "expected the Dimension keyword (code 3) first, found code " + std::to_string(k.code));
    }
    k.data = at + 4 + words_.position;
    if (next != 0 && (next <= int64_t(at) || uint64_t(next) > data_.size())) {
      return error(at + 4, "the next keyword's position " + std::to_string(next) + " is not between this keyword's (" +
                               std::to_string(at) + ") and the end of the file (" + std::to_string(data_.size()) + ")");
    }
    k.end = next == 0 ? data_.size() : size_t(next);
    keywords_.push_back(k);
    if (next == 0 || k.code == gmf::kEnd) break;
    at = size_t(next);
  }
  return Status::success();
}

// The count of a keyword's lines at `at` and the offset after it; each line takes `line_bytes`,
// and they must all fit before the keyword's end.
Status read_count(const GmfFile& f, const Keyword& k, size_t at, size_t line_bytes, uint64_t max,
                  uint64_t& count) {
  int64_t n = 0;
  if (!f.integer(at, k.end, n)) {
    return f.error(at, std::string("expected the number of ") + keyword_name(k.code) +
                           " (the keyword ends at byte " + std::to_string(k.end) + ")");
  }
  const size_t first = at + f.words().integer;
  if (n < 0 || uint64_t(n) > max) {
    return f.error(at, std::string("expected the number of ") + keyword_name(k.code) + ", found " + std::to_string(n));
  }
  if (line_bytes > 0 && uint64_t(n) > (k.end - first) / line_bytes) {
    return f.error(first, std::to_string(n) + " " + keyword_name(k.code) + " of " + std::to_string(line_bytes) +
                              " bytes do not fit before the keyword's end at byte " + std::to_string(k.end));
  }
  count = uint64_t(n);
  return Status::success();
}

// A ref (int32, or int64 in version 4 that must fit in 32 bits).
bool to_ref(int64_t v, int32_t& ref) {
  if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max()) return false;
  ref = int32_t(v);
  return true;
}

Status read_vertices(const GmfFile& f, const Keyword& k, GmfMesh& out) {
  const size_t line = 3 * f.words().real + f.words().integer;
  uint64_t n = 0;
  if (Status s = read_count(f, k, k.data, line, kMaxVertices, n); !s.ok()) return s;
  const size_t first = k.data + f.words().integer;
  out.xyz.resize(3 * n);
  out.vertex_ref.resize(n);
  const char* p = f.data().data() + first;
  for (size_t v = 0; v < n; ++v, p += line) {
    for (size_t c = 0; c < 3; ++c) out.xyz[3 * v + c] = f.real(p + c * f.words().real);
    if (!to_ref(f.integer(p + 3 * f.words().real), out.vertex_ref[v])) {
      return f.error(first + v * line + 3 * f.words().real,
                     "the ref of vertex " + std::to_string(v + 1) + " does not fit in 32 bits");
    }
  }
  return Status::success();
}

// `nodes` 1-based indices and a ref per line; an index outside 1..kMaxVertices becomes UINT32_MAX
// (checked against the vertex count once every keyword is read).
Status read_elements(const GmfFile& f, const Keyword& k, int nodes, std::vector<uint32_t>& vertices,
                     std::vector<int32_t>& refs) {
  const size_t w = f.words().integer, line = size_t(nodes + 1) * w;
  uint64_t n = 0;
  if (Status s = read_count(f, k, k.data, line, std::numeric_limits<uint32_t>::max(), n); !s.ok()) return s;
  const size_t first = k.data + w;
  vertices.resize(size_t(nodes) * n);
  refs.resize(n);
  const char* p = f.data().data() + first;
  for (size_t e = 0; e < n; ++e, p += line) {
    for (int i = 0; i < nodes; ++i) {
      const int64_t v = f.integer(p + size_t(i) * w);
      vertices[size_t(nodes) * e + size_t(i)] = v >= 1 && uint64_t(v) <= kMaxVertices ? uint32_t(v - 1) : UINT32_MAX;
    }
    if (!to_ref(f.integer(p + size_t(nodes) * w), refs[e])) {
      return f.error(first + e * line + size_t(nodes) * w, std::string("the ref of ") + keyword_name(k.code) + " " +
                                                               std::to_string(e + 1) + " does not fit in 32 bits");
    }
  }
  return Status::success();
}

Status read_dimension(const GmfFile& f, const Keyword& k) {
  int32_t dim = 0;
  if (!f.int32(k.data, k.end, dim)) return f.error(k.data, "expected the dimension (the keyword ends)");
  if (dim != 3) return f.error(k.data, "Dimension " + std::to_string(dim) + ": only 3D files are read", Error::UnsupportedFormat);
  return Status::success();
}

Status check_indices(const GmfFile& f, const char* what, int nodes, const std::vector<uint32_t>& vertices,
                     size_t num_vertices) {
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (vertices[i] >= num_vertices) {
      return Status(Error::BadIndex, f.name() + ": " + what + " " + std::to_string(i / size_t(nodes) + 1) +
                                         " refers to a vertex outside 1.." + std::to_string(num_vertices));
    }
  }
  return Status::success();
}

void fill_info(const GmfFile& f, const std::vector<int32_t>& skipped, GmfFileInfo* info) {
  if (!info) return;
  info->version = f.version();
  info->big_endian = f.swap();
  info->skipped = skipped;
}

// A kept keyword seen twice is an error (libMeshb would silently keep the last).
Status check_once(const GmfFile& f, const Keyword& k, std::vector<std::pair<int32_t, size_t>>& seen) {
  for (const auto& [code, at] : seen) {
    if (code == k.code) {
      return f.error(k.at, std::string("a second ") + keyword_name(k.code) + " keyword (the first at byte offset " +
                               std::to_string(at) + ")");
    }
  }
  seen.emplace_back(k.code, k.at);
  return Status::success();
}

Result<GmfMesh> parse_gmf_mesh(std::string_view data, const std::string& name, GmfFileInfo* info) {
  GmfFile f(data, name);
  if (Status s = f.scan(); !s.ok()) return s;
  GmfMesh mesh;
  std::vector<int32_t> skipped;
  std::vector<std::pair<int32_t, size_t>> seen;
  for (const Keyword& k : f.keywords()) {
    Status s;
    if (k.code == gmf::kDimension || k.code == gmf::kVertices || k.code == gmf::kEdges ||
        k.code == gmf::kTriangles || k.code == gmf::kQuadrilaterals || k.code == gmf::kTetrahedra) {
      s = check_once(f, k, seen);
    }
    if (!s.ok()) return s;
    switch (k.code) {
      case gmf::kDimension: s = read_dimension(f, k); break;
      case gmf::kVertices: s = read_vertices(f, k, mesh); break;
      case gmf::kEdges: s = read_elements(f, k, 2, mesh.edge, mesh.edge_ref); break;
      case gmf::kTriangles: s = read_elements(f, k, 3, mesh.tri, mesh.tri_ref); break;
      case gmf::kQuadrilaterals: s = read_elements(f, k, 4, mesh.quad, mesh.quad_ref); break;
      case gmf::kTetrahedra: s = read_elements(f, k, 4, mesh.tet, mesh.tet_ref); break;
      case gmf::kEnd: break;
      default: skipped.push_back(k.code); break;
    }
    if (!s.ok()) return s;
  }
  const size_t nv = mesh.vertex_ref.size();
  Status s = check_indices(f, "edge", 2, mesh.edge, nv);
  if (s.ok()) s = check_indices(f, "triangle", 3, mesh.tri, nv);
  if (s.ok()) s = check_indices(f, "quadrilateral", 4, mesh.quad, nv);
  if (s.ok()) s = check_indices(f, "tetrahedron", 4, mesh.tet, nv);
  if (!s.ok()) return s;
  fill_info(f, skipped, info);
  return mesh;
}

Status read_sol_at_vertices(const GmfFile& f, const Keyword& k, VertexFields& out) {
  int64_t n = 0;
  if (!f.integer(k.data, k.end, n) || n < 0 || uint64_t(n) > kMaxVertices) {
    return f.error(k.data, "expected the number of SolAtVertices lines");
  }
  size_t at = k.data + f.words().integer;
  int32_t num_fields = 0;
  if (!f.int32(at, k.end, num_fields) || num_fields < 1 || uint64_t(num_fields) > (k.end - at - 4) / 4) {
    return f.error(at, "expected the number of fields of SolAtVertices (at least 1, their types before the "
                       "keyword's end at byte " + std::to_string(k.end) + ")");
  }
  at += 4;
  out.kinds.clear();
  for (int32_t i = 0; i < num_fields; ++i, at += 4) {
    int32_t type = 0;
    f.int32(at, k.end, type);  // (in the file: the count was checked against the keyword's end)
    if (type < 1 || type > 4) {
      return f.error(at, "field " + std::to_string(i + 1) + " of SolAtVertices has type " + std::to_string(type) +
                             " (expected 1 scalar, 2 vector, 3 symmetric tensor or 4 matrix)");
    }
    if (type == 4) {
      return f.error(at, "field " + std::to_string(i + 1) + " of SolAtVertices is a full matrix (type 4): anitet "
                             "reads scalars (1), vectors (2) and symmetric tensors (3)", Error::UnsupportedFormat);
    }
    out.kinds.push_back(FieldKind(type));
  }
  const size_t record = out.record_size(), line = record * f.words().real;
  if (uint64_t(n) > (k.end - at) / line) {
    return f.error(at, std::to_string(n) + " SolAtVertices lines of " + std::to_string(line) +
                           " bytes do not fit before the keyword's end at byte " + std::to_string(k.end));
  }
  out.values.resize(size_t(n) * record);
  const char* p = f.data().data() + at;
  for (size_t i = 0; i < out.values.size(); ++i, p += f.words().real) out.values[i] = f.real(p);
  return Status::success();
}

Result<VertexFields> parse_solb(std::string_view data, const std::string& name, GmfFileInfo* info) {
  GmfFile f(data, name);
  if (Status s = f.scan(); !s.ok()) return s;
  VertexFields fields;
  std::vector<int32_t> skipped;
  std::vector<std::pair<int32_t, size_t>> seen;
  for (const Keyword& k : f.keywords()) {
    Status s;
    if (k.code == gmf::kDimension || k.code == gmf::kSolAtVertices) s = check_once(f, k, seen);
    if (!s.ok()) return s;
    if (k.code == gmf::kDimension) s = read_dimension(f, k);
    else if (k.code == gmf::kSolAtVertices) s = read_sol_at_vertices(f, k, fields);
    else if (k.code != gmf::kEnd) skipped.push_back(k.code);
    if (!s.ok()) return s;
  }
  if (fields.kinds.empty()) return Status(Error::EmptyInput, name + ": the file has no SolAtVertices");
  fill_info(f, skipped, info);
  return fields;
}

// ------------------------------------------------------------------------------------------------
// Writing.

// One block of a .meshb: vertices (xyz set) or elements of `nodes` vertices; refs may be null (0).
struct Block {
  int32_t code = 0;
  size_t count = 0;
  int nodes = 0;
  const double* xyz = nullptr;
  const uint32_t* vertices = nullptr;
  const int32_t* refs = nullptr;
};

size_t line_bytes(const Block& b, const Words& w) {
  return b.xyz ? 3 * w.real + w.integer : size_t(b.nodes + 1) * w.integer;
}

// The whole file's size: header, Dimension, the blocks, End (`sol_record`: reals per line of a
// SolAtVertices block of `sol_count` lines with `sol_fields` fields, when non-zero).
uint64_t file_size(const std::vector<Block>& blocks, int version, size_t sol_fields = 0, size_t sol_record = 0,
                   size_t sol_count = 0) {
  const Words w(version);
  uint64_t size = 8 + (4 + w.position + 4) + (4 + w.position);
  for (const Block& b : blocks) size += 4 + w.position + w.integer + uint64_t(b.count) * line_bytes(b, w);
  if (sol_fields) size += 4 + w.position + w.integer + 4 + 4 * sol_fields + uint64_t(sol_count) * sol_record * w.real;
  return size;
}

// The version to write: `asked`, checked, or the smallest of 2, 3, 4 that holds the data.
// size(v): the file's size in version v.
template <class Size>
Result<int> choose_version(int asked, Size&& size, uint64_t largest_count) {
  if (asked < 0 || asked > 4) {
    return Status(Error::InvalidArgument, "GMF version " + std::to_string(asked) + " (expected 1 to 4, or 0: automatic)");
  }
  const bool counts32 = largest_count <= kInt32Max;
  if (asked == 0) return size(2) <= kInt32Max && counts32 ? 2 : counts32 ? 3 : 4;
  if (asked <= 2 && size(asked) > kInt32Max) {
    return Status(Error::InvalidArgument, "a GMF version " + std::to_string(asked) + " file is limited to 2 GiB (this one needs " +
                                              std::to_string(size(asked)) + " bytes): use version 3 or 4");
  }
  if (asked <= 3 && !counts32) {
    return Status(Error::InvalidArgument, "GMF version " + std::to_string(asked) + " counts and indices are 32-bit (this data has " +
                                              std::to_string(largest_count) + "): use version 4");
  }
  return asked;
}

// Appends little-endian words to a buffer sized for the whole file, and links each keyword to
// the next as libMeshb does (a keyword's position is written when the next one starts).
class Writer {
 public:
  Writer(int version, uint64_t size) : words_(version) {
    out_.resize(size_t(size));
    put32(1);
    put32(version);
  }
  void keyword(int32_t code) {
    if (last_position_) put_at(*last_position_, words_.position, int64_t(at_));
    put32(code);
    last_position_ = at_;
    put(words_.position, 0);
  }
  void put32(int32_t v) { put(4, v); }
  void put_integer(int64_t v) { put(words_.integer, v); }
  void put_real(double v) {
    if (words_.real == 4) {
      const auto f = static_cast<float>(v);
      std::memcpy(&out_[at_], &f, 4);
    } else {
      std::memcpy(&out_[at_], &v, 8);
    }
    at_ += words_.real;
  }
  std::string finish() {
    keyword(gmf::kEnd);
    out_.resize(at_);  // (exactly the computed size)
    return std::move(out_);
  }

 private:
  void put(size_t size, int64_t v) {
    put_at(at_, size, v);
    at_ += size;
  }
  void put_at(size_t at, size_t size, int64_t v) {
    if (size == 4) {
      const auto v32 = int32_t(v);
      std::memcpy(&out_[at], &v32, 4);
    } else {
      std::memcpy(&out_[at], &v, 8);
    }
  }

  Words words_;
  std::string out_;
  size_t at_ = 0;
  std::optional<size_t> last_position_;
};

void write_dimension(Writer& w) {
  w.keyword(gmf::kDimension);
  w.put32(3);
}

void write_block(Writer& w, const Block& b) {
  w.keyword(b.code);
  w.put_integer(int64_t(b.count));
  for (size_t i = 0; i < b.count; ++i) {
    if (b.xyz) {
      for (size_t c = 0; c < 3; ++c) w.put_real(b.xyz[3 * i + c]);
    } else {
      for (size_t k = 0; k < size_t(b.nodes); ++k) w.put_integer(int64_t(b.vertices[size_t(b.nodes) * i + k]) + 1);
    }
    w.put_integer(b.refs ? b.refs[i] : 0);
  }
}

// The blocks that have lines, in the order of the list.
Result<std::string> write_mesh(std::vector<Block> blocks, size_t num_vertices, int version) {
  blocks.erase(std::remove_if(blocks.begin(), blocks.end(), [](const Block& b) { return b.count == 0; }), blocks.end());
  uint64_t largest = num_vertices;
  for (const Block& b : blocks) largest = std::max<uint64_t>(largest, b.count);
  Result<int> v = choose_version(version, [&](int w) { return file_size(blocks, w); }, largest);
  if (!v.ok()) return v.status();
  Writer w(v.value(), file_size(blocks, v.value()));
  write_dimension(w);
  for (const Block& b : blocks) write_block(w, b);
  return w.finish();
}

Block vertex_block(const std::vector<double>& xyz, const int32_t* refs) {
  Block b;
  b.code = gmf::kVertices;
  b.count = xyz.size() / 3;
  b.xyz = xyz.data();
  b.refs = refs;
  return b;
}

Block element_block(int32_t code, int nodes, const std::vector<uint32_t>& vertices, const std::vector<int32_t>& refs) {
  Block b;
  b.code = code;
  b.nodes = nodes;
  b.count = vertices.size() / size_t(nodes);
  b.vertices = vertices.data();
  b.refs = refs.empty() ? nullptr : refs.data();
  return b;
}

// Refs may be empty (all 0).
Status check_gmf_mesh(const GmfMesh& m) {
  const size_t nv = m.xyz.size() / 3;
  bool sizes = m.xyz.size() % 3 == 0 && (m.vertex_ref.empty() || m.vertex_ref.size() == nv);
  auto check = [&](const std::vector<uint32_t>& v, const std::vector<int32_t>& refs, size_t nodes) {
    sizes = sizes && v.size() % nodes == 0 && (refs.empty() || refs.size() == v.size() / nodes);
    for (const uint32_t i : v) {
      if (i >= nv) return Status(Error::BadIndex, "an element refers to vertex " + std::to_string(i) + " of " + std::to_string(nv));
    }
    return Status::success();
  };
  for (Status s : {check(m.edge, m.edge_ref, 2), check(m.tri, m.tri_ref, 3), check(m.quad, m.quad_ref, 4),
                   check(m.tet, m.tet_ref, 4)}) {
    if (!s.ok()) return s;
  }
  if (!sizes) return Status(Error::InvalidArgument, "GMF mesh arrays of inconsistent sizes");
  return Status::success();
}

}  // namespace

Result<GmfMesh> read_gmf_mesh(std::string_view data, const std::string& name, GmfFileInfo* info) {
  return catch_bad_alloc(name, [&] { return parse_gmf_mesh(data, name, info); });
}

Result<std::string> to_gmf_mesh(const GmfMesh& mesh, int version) {
  if (Status s = check_gmf_mesh(mesh); !s.ok()) return s;
  return write_mesh({vertex_block(mesh.xyz, mesh.vertex_ref.empty() ? nullptr : mesh.vertex_ref.data()), element_block(gmf::kEdges, 2, mesh.edge, mesh.edge_ref),
                     element_block(gmf::kTriangles, 3, mesh.tri, mesh.tri_ref),
                     element_block(gmf::kQuadrilaterals, 4, mesh.quad, mesh.quad_ref),
                     element_block(gmf::kTetrahedra, 4, mesh.tet, mesh.tet_ref)},
                    mesh.xyz.size() / 3, version);
}

Result<VolumeMesh> read_meshb_volume(std::string_view data, const std::string& name, GmfFileInfo* info) {
  GmfFileInfo local;
  Result<GmfMesh> read = read_gmf_mesh(data, name, &local);
  if (!read.ok()) return read.status();
  for (const int32_t code : local.skipped) {
    if (code == kPrisms || code == kHexahedra || code == kPyramids) {
      return Status(Error::UnsupportedFormat, name + ": the file has " + keyword_name(code) +
                                                  ": anitet reads tetrahedral meshes only");
    }
  }
  GmfMesh& m = read.value();
  if (m.tet.empty()) return Status(Error::EmptyInput, name + ": the file has no tetrahedra");
  VolumeMesh mesh;
  mesh.xyz = std::move(m.xyz);
  mesh.tet = std::move(m.tet);
  mesh.region = std::move(m.tet_ref);
  mesh.bnd_tri = std::move(m.tri);
  mesh.bnd_patch = std::move(m.tri_ref);
  if (info) *info = std::move(local);
  return mesh;
}

Result<SurfaceMesh> read_meshb_surface(std::string_view data, const std::string& name, GmfFileInfo* info) {
  Result<GmfMesh> read = read_gmf_mesh(data, name, info);
  if (!read.ok()) return read.status();
  GmfMesh& m = read.value();
  SurfaceMesh mesh;
  mesh.xyz = std::move(m.xyz);
  mesh.tri = std::move(m.tri);
  mesh.patch = std::move(m.tri_ref);
  for (size_t q = 0; q < m.quad_ref.size(); ++q) add_fan(mesh, &m.quad[4 * q], 4, m.quad_ref[q]);
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the file has no triangles");
  return mesh;
}

Result<std::string> to_meshb(const VolumeMesh& mesh, int version) {
  if (Status s = check_volume_arrays(mesh); !s.ok()) return s;
  return write_mesh({vertex_block(mesh.xyz, nullptr), element_block(gmf::kTriangles, 3, mesh.bnd_tri, mesh.bnd_patch),
                     element_block(gmf::kTetrahedra, 4, mesh.tet, mesh.region)},
                    mesh.num_vertices(), version);
}

Result<std::string> to_meshb(const SurfaceMesh& mesh, int version) {
  if (Status s = check_surface_arrays(mesh); !s.ok()) return s;
  return write_mesh({vertex_block(mesh.xyz, nullptr), element_block(gmf::kTriangles, 3, mesh.tri, mesh.patch)},
                    mesh.num_vertices(), version);
}

Result<VertexFields> read_solb(std::string_view data, const std::string& name, GmfFileInfo* info) {
  return catch_bad_alloc(name, [&] { return parse_solb(data, name, info); });
}

Result<std::string> to_solb(const VertexFields& fields, int version) {
  const size_t record = fields.record_size();
  if (record == 0 || fields.values.size() % record != 0) {
    return Status(Error::InvalidArgument, "vertex fields: " + std::to_string(fields.values.size()) +
                                              " values are not a whole number of records of " + std::to_string(record));
  }
  const size_t n = fields.values.size() / record, nf = fields.kinds.size();
  Result<int> v = choose_version(version, [&](int w) { return file_size({}, w, nf, record, n); }, n);
  if (!v.ok()) return v.status();
  Writer w(v.value(), file_size({}, v.value(), nf, record, n));
  write_dimension(w);
  w.keyword(gmf::kSolAtVertices);
  w.put_integer(int64_t(n));
  w.put32(int32_t(nf));
  for (const FieldKind k : fields.kinds) w.put32(int32_t(k));
  for (const double x : fields.values) w.put_real(x);
  return w.finish();
}

}  // namespace anitet
