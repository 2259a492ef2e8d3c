// Gmsh .msh reader: format 4.1 (ASCII and binary) and 2.x (ASCII). Sections other than
// $MeshFormat, $PhysicalNames, $Entities, $Nodes and $Elements are skipped. Node tags may be
// sparse.
#include <algorithm>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/byte_reader.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

// Nodes per element type (Gmsh's numbering), 0 for unknown types.
int nodes_per_element(int64_t type) {
  static const int kNodes[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                               8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  if (type >= 1 && type < static_cast<int64_t>(sizeof kNodes / sizeof kNodes[0])) {
    return kNodes[type];
  }
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

constexpr int64_t kTriangle = 2;
constexpr int64_t kTetrahedron = 4;

// Elements kept from the file, with node tags (resolved to indices at the end).
struct GmshContent {
  std::vector<double> xyz;
  std::vector<uint64_t> node_tag;
  std::vector<uint64_t> tri_nodes, tet_nodes;
  std::vector<int32_t> tri_entity, tet_entity;      // entity (elementary) tag
  std::vector<int32_t> tri_physical, tet_physical;  // first physical tag, 0 when none
};

// $PhysicalNames: a count, then lines `dim tag "name"` (the name may hold spaces); those of
// dimension 2 are kept.
Status read_physical_names(std::string_view text, size_t first_line, const std::string& name,
                           std::vector<std::pair<int32_t, std::string>>& surface_names) {
  size_t line_no = first_line, pos = 0;
  bool have_count = false;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    const size_t at = line_no++;
    pos = eol + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    if (line.empty()) continue;
    if (!have_count) {
      have_count = true;
      continue;
    }
    const size_t quote = line.find('"');
    const size_t end = quote == std::string_view::npos ? std::string_view::npos : line.find('"', quote + 1);
    char* stop = nullptr;
    const std::string head(line.substr(0, quote));
    const long dim = std::strtol(head.c_str(), &stop, 10);
    const long tag = std::strtol(stop, &stop, 10);
    if (end == std::string_view::npos || tag < INT32_MIN || tag > INT32_MAX) {
      return Status(Error::Parse, name + ":" + std::to_string(at) + ": expected a physical name line (dim tag \"name\")");
    }
    if (dim == 2) surface_names.emplace_back(int32_t(tag), std::string(line.substr(quote + 1, end - quote - 1)));
  }
  return Status::success();
}

// Reads the numbers of a section, from text or from binary (4.1 binary: int = 4 bytes,
// size_t = 8 bytes, double = 8 bytes, little-endian).
class GmshSource {
 public:
  GmshSource(std::string_view data, size_t start, bool binary, size_t line, const std::string& name)
      : data_(data),
        start_(start),
        binary_(binary),
        text_(data.substr(start), name, '\0', line),
        bytes_(data, name, start) {}

  bool binary() const { return binary_; }
  size_t remaining() const { return binary_ ? bytes_.remaining() : text_.remaining(); }
  size_t offset() const { return binary_ ? bytes_.offset() : start_ + text_.offset(); }

  bool size(uint64_t& out, uint64_t max = UINT64_MAX / 4) {
    if (!binary_) return text_.read_count(max, out);
    return bytes_.read(out) && out <= max;
  }
  bool integer(int64_t& out) {
    if (!binary_) return text_.read_int(out);
    int32_t v;
    if (!bytes_.read(v)) return false;
    out = v;
    return true;
  }
  bool tag(int32_t& out) {
    int64_t v = 0;
    if (!integer(v) || v < INT32_MIN || v > INT32_MAX) return false;
    out = static_cast<int32_t>(v);
    return true;
  }
  bool real(double& out) { return binary_ ? bytes_.read(out) : text_.read_double(out); }
  // In 4.1 binary, element and node tags are size_t; in text they are plain integers.
  bool node_tag(uint64_t& out) { return size(out, UINT64_MAX); }

  // Bytes one item of `numbers` values takes at least (text: a digit and a separator each).
  bool fits_items(uint64_t count, uint64_t numbers, uint64_t binary_bytes) const {
    return fits(count, binary_ ? binary_bytes : 2 * numbers, remaining() + 1);
  }

  Status expected(const std::string& what) {
    if (!binary_) return text_.expected(what);
    return bytes_.error(Error::Parse, "expected " + what + ", found " +
                                          (bytes_.remaining() ? "too few bytes" : "end of file"));
  }
  Status error(Error code, const std::string& message) {
    return binary_ ? bytes_.error(code, message) : text_.error(code, message);
  }

 private:
  std::string_view data_;
  size_t start_;
  bool binary_;
  TextScanner text_;
  ByteReader bytes_;
};

using PhysicalMap = std::unordered_map<int32_t, int32_t>;  // entity tag -> first physical tag

// $Entities (4.1): points, curves, surfaces, volumes with their physical tags.
Status read_entities(GmshSource& in, PhysicalMap physical[4]) {
  uint64_t counts[4];
  for (uint64_t& c : counts) {
    if (!in.size(c)) return in.expected("the entity counts");
  }
  for (int dim = 0; dim < 4; ++dim) {
    if (!in.fits_items(counts[dim], 5, 36)) return in.error(Error::Parse, "entity count too large");
    for (uint64_t e = 0; e < counts[dim]; ++e) {
      int32_t tag = 0;
      if (!in.tag(tag)) return in.expected("an entity tag");
      double box;
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) {
        if (!in.real(box)) return in.expected("an entity bounding box coordinate");
      }
      uint64_t num_physical = 0;
      if (!in.size(num_physical) || !in.fits_items(num_physical, 1, 4)) {
        return in.expected("the number of physical tags");
      }
      for (uint64_t p = 0; p < num_physical; ++p) {
        int32_t phys = 0;
        if (!in.tag(phys)) return in.expected("a physical tag");
        if (p == 0) physical[dim][tag] = phys;
      }
      if (dim == 0) continue;
      uint64_t num_bounding = 0;
      if (!in.size(num_bounding) || !in.fits_items(num_bounding, 1, 4)) {
        return in.expected("the number of bounding entities");
      }
      for (uint64_t b = 0; b < num_bounding; ++b) {
        int32_t bound = 0;
        if (!in.tag(bound)) return in.expected("a bounding entity tag");
      }
    }
  }
  return Status::success();
}

// $Nodes (4.1): blocks of "dim tag parametric count", the count tags, then the coordinates.
Status read_nodes41(GmshSource& in, GmshContent& out) {
  uint64_t num_blocks = 0, total = 0, min_tag = 0, max_tag = 0;
  if (!in.size(num_blocks) || !in.size(total) || !in.size(min_tag) || !in.size(max_tag)) {
    return in.expected("the $Nodes header (blocks, nodes, min tag, max tag)");
  }
  if (!in.fits_items(num_blocks, 4, 20)) {
    return in.error(Error::Parse, "node block count too large");
  }
  for (uint64_t b = 0; b < num_blocks; ++b) {
    int64_t dim = 0, entity = 0, parametric = 0;
    uint64_t count = 0;
    if (!in.integer(dim) || !in.integer(entity) || !in.integer(parametric) || !in.size(count)) {
      return in.expected("a node block header (dim, tag, parametric, count)");
    }
    if (dim < 0 || dim > 3 || parametric < 0 || parametric > 1) {
      return in.error(Error::Parse, "bad node block header");
    }
    const uint64_t extra = parametric ? static_cast<uint64_t>(dim) : 0;  // u, v, w
    if (!in.fits_items(count, 4 + extra, 8 * (4 + extra))) {
      return in.error(Error::Parse,
                      "node block of " + std::to_string(count) + " nodes does not fit in the file");
    }
    if (out.node_tag.size() + count > kMaxVertices) return in.error(Error::Parse, "too many nodes");
    const size_t first = out.node_tag.size();
    out.node_tag.resize(first + count);
    out.xyz.resize(3 * (first + count));
    for (uint64_t i = 0; i < count; ++i) {
      if (!in.node_tag(out.node_tag[first + i])) return in.expected("a node tag");
    }
    for (uint64_t i = 0; i < count; ++i) {
      for (int k = 0; k < 3; ++k) {
        if (!in.real(out.xyz[3 * (first + i) + k])) return in.expected("a node coordinate");
      }
      double param;
      for (uint64_t k = 0; k < extra; ++k) {
        if (!in.real(param)) return in.expected("a parametric node coordinate");
      }
    }
  }
  return Status::success();
}

// Keeps an element if it is a triangle or a tet.
void keep_element(GmshContent& out, int64_t type, const uint64_t* nodes, int32_t entity,
                  int32_t physical) {
  if (type == kTriangle) {
    out.tri_nodes.insert(out.tri_nodes.end(), nodes, nodes + 3);
    out.tri_entity.push_back(entity);
    out.tri_physical.push_back(physical);
  } else if (type == kTetrahedron) {
    out.tet_nodes.insert(out.tet_nodes.end(), nodes, nodes + 4);
    out.tet_entity.push_back(entity);
    out.tet_physical.push_back(physical);
  }
}

// $Elements (4.1): blocks of "dim tag type count", then "tag node..." per element.
Status read_elements41(GmshSource& in, GmshContent& out, const PhysicalMap physical[4]) {
  uint64_t num_blocks = 0, total = 0, min_tag = 0, max_tag = 0;
  if (!in.size(num_blocks) || !in.size(total) || !in.size(min_tag) || !in.size(max_tag)) {
    return in.expected("the $Elements header (blocks, elements, min tag, max tag)");
  }
  if (!in.fits_items(num_blocks, 4, 20)) {
    return in.error(Error::Parse, "element block count too large");
  }
  uint64_t nodes[125];
  for (uint64_t b = 0; b < num_blocks; ++b) {
    int64_t dim = 0, type = 0;
    int32_t entity = 0;
    uint64_t count = 0;
    if (!in.integer(dim) || !in.tag(entity) || !in.integer(type) || !in.size(count)) {
      return in.expected("an element block header (dim, tag, type, count)");
    }
    const int n = nodes_per_element(type);
    if (n == 0) {
      return in.error(Error::UnsupportedFormat, "unknown element type " + std::to_string(type));
    }
    if (!in.fits_items(count, 1 + n, 8 * (1 + n))) {
      return in.error(Error::Parse, "element block of " + std::to_string(count) +
                                        " elements does not fit in the file");
    }
    int32_t phys = 0;
    if (dim >= 0 && dim <= 3) {
      auto it = physical[dim].find(entity);
      if (it != physical[dim].end()) phys = it->second;
    }
    for (uint64_t e = 0; e < count; ++e) {
      uint64_t element_tag = 0;
      if (!in.node_tag(element_tag)) return in.expected("an element tag");
      for (int k = 0; k < n; ++k) {
        if (!in.node_tag(nodes[k])) {
          return in.expected("a node tag of element " + std::to_string(element_tag));
        }
      }
      keep_element(out, type, nodes, entity, phys);
    }
  }
  return Status::success();
}

// $Nodes (2.x): count, then "tag x y z" per node.
Status read_nodes2(GmshSource& in, GmshContent& out) {
  uint64_t count = 0;
  if (!in.size(count, kMaxVertices)) return in.expected("the number of nodes");
  if (!in.fits_items(count, 4, 32)) {
    return in.error(Error::Parse, std::to_string(count) + " nodes do not fit in the file");
  }
  out.node_tag.resize(count);
  out.xyz.resize(3 * count);
  for (uint64_t i = 0; i < count; ++i) {
    if (!in.node_tag(out.node_tag[i])) return in.expected("a node tag");
    for (int k = 0; k < 3; ++k) {
      if (!in.real(out.xyz[3 * i + k])) return in.expected("a node coordinate");
    }
  }
  return Status::success();
}

// $Elements (2.x): count, then "tag type ntags tag... node..." per element; tags are
// (physical, elementary, ...).
Status read_elements2(GmshSource& in, GmshContent& out) {
  uint64_t count = 0;
  if (!in.size(count)) return in.expected("the number of elements");
  if (!in.fits_items(count, 5, 20)) {
    return in.error(Error::Parse, std::to_string(count) + " elements do not fit in the file");
  }
  uint64_t nodes[125];
  for (uint64_t e = 0; e < count; ++e) {
    int64_t element_tag = 0, type = 0;
    uint64_t num_tags = 0;
    if (!in.integer(element_tag) || !in.integer(type) || !in.size(num_tags, 1000)) {
      return in.expected("an element (tag, type, number of tags)");
    }
    const int n = nodes_per_element(type);
    if (n == 0) {
      return in.error(Error::UnsupportedFormat, "unknown element type " + std::to_string(type));
    }
    int32_t tags[2] = {0, 0};
    for (uint64_t t = 0; t < num_tags; ++t) {
      int32_t value = 0;
      if (!in.tag(value)) return in.expected("a tag of element " + std::to_string(element_tag));
      if (t < 2) tags[t] = value;
    }
    for (int k = 0; k < n; ++k) {
      if (!in.node_tag(nodes[k])) {
        return in.expected("a node tag of element " + std::to_string(element_tag));
      }
    }
    const int32_t elementary = num_tags >= 2 ? tags[1] : tags[0];
    keep_element(out, type, nodes, elementary, tags[0]);
  }
  return Status::success();
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

Status parse_gmsh(std::string_view data, const std::string& name, GmshContent& out) {
  enum class Version { None, V2, V41 } version = Version::None;
  bool binary = false;
  PhysicalMap physical[4];
  bool have_nodes = false;
  LineCounter lines(data);
  size_t pos = 0;
  for (;;) {
    while (pos < data.size() && is_space(data[pos])) ++pos;
    if (pos == data.size()) break;
    size_t stop = pos;
    while (stop < data.size() && !is_space(data[stop])) ++stop;
    std::string_view section = data.substr(pos, stop - pos);
    if (section.empty() || section[0] != '$') {
      return Status(Error::Parse, name + ":" + std::to_string(lines.at(pos)) +
                                      ": expected a section such as $Nodes, found '" +
                                      quote_token(section) + "'");
    }
    // The section's contents start on the next line.
    size_t eol = data.find('\n', stop);
    size_t body = eol == std::string_view::npos ? data.size() : eol + 1;
    if (version == Version::None && section != "$MeshFormat") {
      return Status(Error::Parse,
                    name + ": expected $MeshFormat first, found '" + quote_token(section) + "'");
    }
    GmshSource in(data, body, binary && section != "$MeshFormat" && section != "$PhysicalNames",
                  lines.at(body), name);
    Status status;
    bool skip = false;
    if (section == "$MeshFormat") {
      GmshSource text(data, body, false, lines.at(body), name);
      double number = 0;
      int64_t file_type = 0, data_size = 0;
      if (!text.real(number) || !text.integer(file_type) || !text.integer(data_size)) {
        return text.expected("the format line (version, file type, data size)");
      }
      if (number == 4.1) {
        version = Version::V41;
      } else if (number >= 2.0 && number < 3.0) {
        version = Version::V2;
      } else {
        return text.error(Error::UnsupportedFormat, "Gmsh format " + std::to_string(number) +
                                                        " is not supported (use 4.1 or 2.2)");
      }
      binary = file_type == 1;
      if (binary && (version != Version::V41 || data_size != 8)) {
        return text.error(Error::UnsupportedFormat,
                          "binary Gmsh files are supported in format 4.1 with data size 8 only");
      }
      if (binary) {
        // After the text line comes the integer 1, written in the writer's byte order.
        size_t word = data.find('\n', body);
        ByteReader bytes(data, name, word == std::string_view::npos ? data.size() : word + 1);
        int32_t one = 0;
        if (!bytes.read(one)) {
          return bytes.error(Error::Parse, "expected the binary integer 1 after the format line");
        }
        if (one != 1) {
          return bytes.error(Error::UnsupportedFormat,
                             "big-endian binary Gmsh files are not supported");
        }
      }
      skip = true;
    } else if (section == "$Entities" && version == Version::V41) {
      status = read_entities(in, physical);
    } else if (section == "$Nodes") {
      if (have_nodes) return in.error(Error::Parse, "a second $Nodes section");
      have_nodes = true;
      status = version == Version::V41 ? read_nodes41(in, out) : read_nodes2(in, out);
    } else if (section == "$Elements") {
      status =
          version == Version::V41 ? read_elements41(in, out, physical) : read_elements2(in, out);
    } else {
      skip = true;
    }
    if (!status.ok()) return status;
    std::string end_marker = "$End" + std::string(section.substr(1));
    if (skip) {
      size_t found = data.find(end_marker, body);
      if (found == std::string_view::npos) {
        return Status(Error::Parse, name + ": " + std::string(section) + " has no " + end_marker);
      }
      pos = found + end_marker.size();
    } else {
      pos = in.offset();
      while (pos < data.size() && is_space(data[pos])) ++pos;
      if (data.substr(pos, end_marker.size()) != end_marker) {
        return in.expected("'" + end_marker + "'");
      }
      pos += end_marker.size();
    }
  }
  if (version == Version::None) {
    return Status(Error::Parse, name + ": not a Gmsh file (no $MeshFormat)");
  }
  return Status::success();
}

// Replaces node tags by 0-based indices; Error::BadIndex names the element.
Status resolve_nodes(const std::string& name, const GmshContent& content, const char* what, int n,
                     const std::vector<uint64_t>& tags, std::vector<uint32_t>& indices) {
  const size_t count = content.node_tag.size();
  uint64_t max_tag = 0;
  for (uint64_t t : content.node_tag) max_tag = std::max(max_tag, t);
  indices.resize(tags.size());
  auto missing = [&](size_t i) {
    return Status(Error::BadIndex, name + ": " + what + " " + std::to_string(i / n) +
                                       " refers to node " + std::to_string(tags[i]) +
                                       ", which is not in $Nodes");
  };
  if (max_tag < 2 * uint64_t{count} + 1024) {
    std::vector<uint32_t> index_of(max_tag + 1, UINT32_MAX);
    for (size_t v = 0; v < count; ++v) index_of[content.node_tag[v]] = static_cast<uint32_t>(v);
    for (size_t i = 0; i < tags.size(); ++i) {
      if (tags[i] > max_tag || index_of[tags[i]] == UINT32_MAX) return missing(i);
      indices[i] = index_of[tags[i]];
    }
    return Status::success();
  }
  std::vector<std::pair<uint64_t, uint32_t>> sorted(count);
  for (size_t v = 0; v < count; ++v) sorted[v] = {content.node_tag[v], static_cast<uint32_t>(v)};
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < tags.size(); ++i) {
    auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(tags[i], uint32_t{0}));
    if (it == sorted.end() || it->first != tags[i]) return missing(i);
    indices[i] = it->second;
  }
  return Status::success();
}

std::vector<int32_t> labels(const std::vector<int32_t>& entity,
                            const std::vector<int32_t>& physical) {
  std::vector<int32_t> out(entity.size());
  for (size_t i = 0; i < entity.size(); ++i) out[i] = physical[i] != 0 ? physical[i] : entity[i];
  return out;
}

Result<SurfaceMesh> parse_gmsh_surface(std::string_view data, const std::string& name) {
  GmshContent content;
  Status status = parse_gmsh(data, name, content);
  if (!status.ok()) return status;
  if (content.tri_entity.empty()) {
    return Status(Error::EmptyInput, name + ": the file has no triangles");
  }
  SurfaceMesh mesh;
  status = resolve_nodes(name, content, "triangle", 3, content.tri_nodes, mesh.tri);
  if (!status.ok()) return status;
  mesh.xyz = std::move(content.xyz);
  mesh.patch = labels(content.tri_entity, content.tri_physical);
  return mesh;
}

Result<VolumeMesh> parse_gmsh_volume(std::string_view data, const std::string& name) {
  GmshContent content;
  Status status = parse_gmsh(data, name, content);
  if (!status.ok()) return status;
  if (content.tet_entity.empty()) {
    return Status(Error::EmptyInput, name + ": the file has no tetrahedra");
  }
  VolumeMesh mesh;
  status = resolve_nodes(name, content, "tetrahedron", 4, content.tet_nodes, mesh.tet);
  if (status.ok()) {
    status = resolve_nodes(name, content, "triangle", 3, content.tri_nodes, mesh.bnd_tri);
  }
  if (!status.ok()) return status;
  mesh.region = labels(content.tet_entity, content.tet_physical);
  mesh.bnd_patch = labels(content.tri_entity, content.tri_physical);
  mesh.xyz = std::move(content.xyz);
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_gmsh_surface(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_gmsh_surface(data, name); });
}

Result<VolumeMesh> read_gmsh_volume(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_gmsh_volume(data, name); });
}

Result<PatchNames> gmsh_surface_names(std::string_view data, const std::string& name) {
  PatchNames names;
  const size_t at = data.find("$PhysicalNames");
  if (at == std::string_view::npos) return names;
  const size_t body = data.find('\n', at);
  const size_t end = data.find("$EndPhysicalNames", at);
  if (body == std::string_view::npos || end == std::string_view::npos || end < body)
    return Status(Error::Parse, name + ": $PhysicalNames has no $EndPhysicalNames");
  const size_t line = size_t(std::count(data.begin(), data.begin() + std::ptrdiff_t(body), '\n')) + 2;
  std::vector<std::pair<int32_t, std::string>> list;
  if (Status st = read_physical_names(data.substr(body + 1, end - body - 1), line, name, list); !st.ok()) return st;
  for (auto& [tag, text] : list) names[tag] = std::move(text);
  return names;
}

}  // namespace anitet
