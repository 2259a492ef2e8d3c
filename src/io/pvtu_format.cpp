#include "io/pvtu_format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string_view>

#include "io/file_bytes.hpp"
#include "io/volume_io.hpp"
#include "io/vtk_xml.hpp"

namespace anitet {

namespace {

constexpr uint8_t kVtkTetra = 10, kVtkTriangle = 5;

// One appended array: its declaration, its byte count, and how its values are written (in
// order, through a Sink). The values are made as they are written, not copied into a buffer
// first: the whole file built in memory held several times the piece's bytes and set the peak of
// an anitet-mpi rank.
class Sink;
struct Array {
  const char* type;
  const char* name;
  int components;
  uint64_t bytes;
  std::function<void(Sink&)> values;
};

// Buffers the appended bytes (1 MiB at a time) for write_file_with's writer.
class Sink {
 public:
  explicit Sink(const std::function<bool(std::string_view)>& write) : write_(write) { buffer_.reserve(kSize); }
  template <class T>
  void put(T v) {
    if (buffer_.size() + sizeof(T) > kSize) flush();
    buffer_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void put_all(const std::vector<T>& v) {
    for (const T& x : v) put(x);
  }
  void put_text(std::string_view text) {
    flush();
    ok_ = ok_ && write_(text);
  }
  bool flush() {
    if (!buffer_.empty()) ok_ = ok_ && write_(buffer_);
    buffer_.clear();
    return ok_;
  }

 private:
  static constexpr size_t kSize = size_t(1) << 20;
  const std::function<bool(std::string_view)>& write_;
  std::string buffer_;
  bool ok_ = true;
};

template <class T>
Array array_of(const char* type, const char* name, int components, const std::vector<T>& v) {
  return {type, name, components, v.size() * sizeof(T), [&v](Sink& s) { s.put_all(v); }};
}

void declare(std::string& out, const Array& a, uint64_t offset) {
  out += "        <DataArray type=\"" + std::string(a.type) + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" +
         std::to_string(a.components) + "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
}

// The arrays of a piece's sections (point data, cell data, points, cells): the cells are its tets,
// then its triangles.
std::array<std::vector<Array>, 4> piece_arrays(const VtuPiece& p) {
  const size_t nt = p.region.size(), nb = p.patch.size();
  auto cells_then = [nt, nb](const char* type, const char* name, uint64_t size, auto tet_value, auto tri_value) {
    return Array{type, name, 1, uint64_t(nt + nb) * size, [=](Sink& s) {
                   for (size_t t = 0; t < nt; ++t) tet_value(s, t);
                   for (size_t b = 0; b < nb; ++b) tri_value(s, b);
                 }};
  };
  std::array<std::vector<Array>, 4> sections;
  sections[0].push_back(array_of("Int64", "GlobalNodeIds", 1, p.node_id));
  sections[1].push_back(cells_then("Int32", "region", 4, [&p](Sink& s, size_t t) { s.put(p.region[t]); },
                                   [](Sink& s, size_t) { s.put(int32_t(-1)); }));
  sections[1].push_back(cells_then("Int32", "patch", 4, [](Sink& s, size_t) { s.put(int32_t(-1)); },
                                   [&p](Sink& s, size_t b) { s.put(p.patch[b]); }));
  sections[1].push_back(cells_then("Int64", "GlobalCellIds", 8, [&p](Sink& s, size_t t) { s.put(p.tet_id[t]); },
                                   [](Sink& s, size_t) { s.put(int64_t(-1)); }));
  const int32_t owner = p.owner;
  auto put_owner = [owner](Sink& s, size_t) { s.put(owner); };
  sections[1].push_back(cells_then("Int32", "owner", 4, put_owner, put_owner));
  sections[2].push_back(array_of("Float64", "Points", 3, p.xyz));
  sections[3].push_back(Array{"Int64", "connectivity", 1, 8 * uint64_t(4 * nt + 3 * nb), [&p](Sink& s) {
                                for (uint32_t v : p.tet) s.put(int64_t(v));
                                for (uint32_t v : p.tri) s.put(int64_t(v));
                              }});
  sections[3].push_back(cells_then("Int64", "offsets", 8, [](Sink& s, size_t t) { s.put(int64_t(4 * (t + 1))); },
                                   [nt](Sink& s, size_t b) { s.put(int64_t(4 * nt + 3 * (b + 1))); }));
  sections[3].push_back(cells_then("UInt8", "types", 1, [](Sink& s, size_t) { s.put(kVtkTetra); },
                                   [](Sink& s, size_t) { s.put(kVtkTriangle); }));
  return sections;
}

Status parse_error(const std::string& path, const std::string& what) {
  return Status(Error::Parse, path + ": " + what + " (not a piece of `anitet-mpi`'s .pvtu output)");
}

std::string directory_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

}  // namespace

Status write_vtu_piece(const std::string& path, const VtuPiece& p) {
  // As every writer does (check_boundary_elements): no boundary triangle that is not a face of the
  // piece's tets; cover off, since the faces between pieces carry none.
  const size_t nv = p.xyz.size() / 3;
  for (const std::vector<uint32_t>* ids : {&p.tet, &p.tri})
    for (uint32_t v : *ids)
      if (v >= nv)
        return Status(Error::BadIndex, path + ": vertex index " + std::to_string(v) + " in a piece of " +
                                           std::to_string(nv) + " vertices");
  if (Status st = check_boundary_elements(p.tet, nv, p.tri, /*cover=*/false); !st.ok())
    return Status(st.code(), path + ": " + st.message());
  const std::array<std::vector<Array>, 4> sections = piece_arrays(p);
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" +
      std::to_string(p.node_id.size()) + "\" NumberOfCells=\"" + std::to_string(p.region.size() + p.patch.size()) +
      "\">\n";
  const char* open[4] = {"      <PointData GlobalIds=\"GlobalNodeIds\">\n", "      <CellData>\n", "      <Points>\n",
                         "      <Cells>\n"};
  const char* close[4] = {"      </PointData>\n", "      </CellData>\n", "      </Points>\n", "      </Cells>\n"};
  uint64_t offset = 0;
  for (size_t k = 0; k < sections.size(); ++k) {
    out += open[k];
    for (const Array& a : sections[k]) {
      declare(out, a, offset);
      offset += sizeof(uint64_t) + a.bytes;
    }
    out += close[k];
  }
  out += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  return write_file_with(path, [&](const std::function<bool(std::string_view)>& write) {
    Sink sink(write);
    sink.put_text(out);
    for (const std::vector<Array>& section : sections)
      for (const Array& a : section) {
        sink.put(a.bytes);
        a.values(sink);
      }
    sink.put_text("\n  </AppendedData>\n</VTKFile>\n");
    return sink.flush();
  });
}

Status write_pvtu_index(const std::string& path, const std::vector<std::string>& pieces) {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n"
      "    <PPointData GlobalIds=\"GlobalNodeIds\">\n"
      "      <PDataArray type=\"Int64\" Name=\"GlobalNodeIds\" NumberOfComponents=\"1\"/>\n    </PPointData>\n"
      "    <PCellData>\n"
      "      <PDataArray type=\"Int32\" Name=\"region\" NumberOfComponents=\"1\"/>\n"
      "      <PDataArray type=\"Int32\" Name=\"patch\" NumberOfComponents=\"1\"/>\n"
      "      <PDataArray type=\"Int64\" Name=\"GlobalCellIds\" NumberOfComponents=\"1\"/>\n"
      "      <PDataArray type=\"Int32\" Name=\"owner\" NumberOfComponents=\"1\"/>\n    </PCellData>\n"
      "    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& piece : pieces) out += "    <Piece Source=\"" + piece + "\"/>\n";
  out += "  </PUnstructuredGrid>\n</VTKFile>\n";
  return write_file_bytes(path, out);
}

Result<std::vector<std::string>> read_pvtu_index(const std::string& path) {
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  const std::string_view text = bytes.value();
  bool index = false, grid = false, points = false;
  std::vector<std::string> pieces;
  XmlTag tag;
  for (size_t pos = 0; next_xml_tag(text, pos, tag); pos = tag.end) {
    if (tag.closing) continue;
    if (tag.name == "VTKFile") index = xml_attribute(tag.attributes, "type") == "PUnstructuredGrid";
    grid = grid || tag.name == "PUnstructuredGrid";
    points = points || tag.name == "PPoints";
    if (tag.name != "Piece") continue;
    const std::string source(xml_attribute(tag.attributes, "Source"));
    if (source.empty()) return Status(Error::Parse, path + ": a <Piece> without Source");
    pieces.push_back(source[0] == '/' ? source : directory_of(path) + source);
  }
  if (!index) return Status(Error::Parse, path + ": not a .pvtu index (no <VTKFile type=\"PUnstructuredGrid\">)");
  if (!grid || !points) return Status(Error::Parse, path + ": no <PUnstructuredGrid> with <PPoints>");
  if (pieces.empty()) return Status(Error::Parse, path + ": no <Piece>");
  return pieces;
}

namespace {

bool wanted_in_piece(VtkSection section, std::string_view name) {
  switch (section) {
    case VtkSection::Points: return true;
    case VtkSection::PointData: return name == "GlobalNodeIds";
    case VtkSection::Cells: return name == "connectivity" || name == "offsets" || name == "types";
    case VtkSection::CellData: return name == "region" || name == "patch" || name == "GlobalCellIds" || name == "owner";
    default: return false;
  }
}

// Array `name` of `section` as T values; false when it is absent or a value is not a T.
template <class T>
bool integers(const VtkGrid& grid, VtkSection section, const char* name, std::vector<T>& out) {
  const VtkArray* a = grid.find(section, name);
  if (!a) return false;
  out.resize(a->values.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const double v = a->values[i];
    if (!(v >= double(std::numeric_limits<T>::min()) && v < std::ldexp(1.0, std::numeric_limits<T>::digits)) ||
        v != std::floor(v))
      return false;
    out[i] = T(v);
  }
  return true;
}

}  // namespace

Result<VtuPiece> read_vtu_piece(const std::string& path) {
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  VtkGrid grid;
  if (Status st = read_vtk_grid(bytes.value(), path, wanted_in_piece, grid); !st.ok()) return st;
  VtuPiece p;
  std::vector<int64_t> connectivity, offsets, cell_id;
  std::vector<uint8_t> types;
  std::vector<int32_t> region, patch, owner;
  if (const VtkArray* points = grid.find(VtkSection::Points, "Points")) p.xyz = points->values;
  if (!integers(grid, VtkSection::PointData, "GlobalNodeIds", p.node_id) ||
      !integers(grid, VtkSection::Cells, "connectivity", connectivity) ||
      !integers(grid, VtkSection::Cells, "offsets", offsets) || !integers(grid, VtkSection::Cells, "types", types) ||
      !integers(grid, VtkSection::CellData, "region", region) || !integers(grid, VtkSection::CellData, "patch", patch) ||
      !integers(grid, VtkSection::CellData, "GlobalCellIds", cell_id) ||
      !integers(grid, VtkSection::CellData, "owner", owner))
    return parse_error(path, "an array missing or of values out of its type's range");
  const size_t nv = p.node_id.size(), nc = types.size();
  if (p.xyz.size() != 3 * nv || offsets.size() != nc || region.size() != nc || patch.size() != nc ||
      cell_id.size() != nc || owner.size() != nc)
    return parse_error(path, "arrays of different lengths");
  int64_t at = 0;
  for (size_t c = 0; c < nc; ++c) {
    const int64_t size = types[c] == kVtkTetra ? 4 : types[c] == kVtkTriangle ? 3 : -1;
    if (size < 0 || offsets[c] != at + size || offsets[c] > int64_t(connectivity.size()))
      return parse_error(path, "a cell that is neither a tet nor a triangle, or bad offsets");
    std::vector<uint32_t>& to = size == 4 ? p.tet : p.tri;
    for (int64_t k = at; k < offsets[c]; ++k) {
      if (connectivity[size_t(k)] < 0 || uint64_t(connectivity[size_t(k)]) >= nv)
        return parse_error(path, "a cell vertex out of range");
      to.push_back(uint32_t(connectivity[size_t(k)]));
    }
    if (size == 4) {
      p.region.push_back(region[c]);
      p.tet_id.push_back(cell_id[c]);
    } else {
      p.patch.push_back(patch[c]);
    }
    at = offsets[c];
  }
  p.owner = owner.empty() ? 0 : owner[0];
  return p;
}

Result<VolumeMesh> join_pieces(const std::vector<VtuPiece>& pieces) {
  uint64_t nv = 0, nt = 0;
  for (const VtuPiece& p : pieces) {
    for (int64_t id : p.node_id) nv = std::max<uint64_t>(nv, uint64_t(id) + 1);
    nt += p.region.size();
  }
  VolumeMesh m;
  m.xyz.assign(3 * nv, 0.0);
  std::vector<uint8_t> seen(nv, 0);
  m.tet.assign(4 * nt, 0);
  m.region.assign(nt, 0);
  std::vector<uint8_t> tet_seen(nt, 0);
  for (size_t k = 0; k < pieces.size(); ++k) {
    const VtuPiece& p = pieces[k];
    const std::string which = "piece " + std::to_string(k);
    for (size_t v = 0; v < p.node_id.size(); ++v) {
      const auto id = size_t(p.node_id[v]);
      if (p.node_id[v] < 0) return Status(Error::InvalidMesh, which + ": a negative GlobalNodeIds");
      if (seen[id] && !std::equal(&p.xyz[3 * v], &p.xyz[3 * v] + 3, &m.xyz[3 * id]))
        return Status(Error::InvalidMesh, which + ": vertex " + std::to_string(id) + " has two positions");
      std::copy_n(&p.xyz[3 * v], 3, &m.xyz[3 * id]);
      seen[id] = 1;
    }
    for (size_t t = 0; t < p.region.size(); ++t) {
      const int64_t id = p.tet_id[t];
      if (id < 0 || uint64_t(id) >= nt || tet_seen[size_t(id)])
        return Status(Error::InvalidMesh, which + ": GlobalCellIds " + std::to_string(id) + " out of range or twice");
      tet_seen[size_t(id)] = 1;
      for (int i = 0; i < 4; ++i) m.tet[4 * size_t(id) + size_t(i)] = uint32_t(p.node_id[p.tet[4 * t + size_t(i)]]);
      m.region[size_t(id)] = p.region[t];
    }
    for (size_t b = 0; b < p.patch.size(); ++b) {
      for (int i = 0; i < 3; ++i) m.bnd_tri.push_back(uint32_t(p.node_id[p.tri[3 * b + size_t(i)]]));
      m.bnd_patch.push_back(p.patch[b]);
    }
  }
  for (uint64_t v = 0; v < nv; ++v)
    if (!seen[v]) return Status(Error::InvalidMesh, "GlobalNodeIds " + std::to_string(v) + " is in no piece");
  return m;
}

}  // namespace anitet

namespace anitet {

Status check_joined(const VolumeMesh& m) {
  std::vector<std::array<uint32_t, 4>> facets;  // sorted vertices, then 0 (a tet's) or 1 (a triangle)
  facets.reserve(4 * m.num_tets() + m.num_boundary_triangles());
  static constexpr int kFacet[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (const auto& f : kFacet) {
      std::array<uint32_t, 4> k = {m.tet[4 * t + size_t(f[0])], m.tet[4 * t + size_t(f[1])], m.tet[4 * t + size_t(f[2])], 0};
      std::sort(k.begin(), k.begin() + 3);
      facets.push_back(k);
    }
  for (size_t b = 0; b < m.num_boundary_triangles(); ++b) {
    std::array<uint32_t, 4> k = {m.bnd_tri[3 * b], m.bnd_tri[3 * b + 1], m.bnd_tri[3 * b + 2], 1};
    std::sort(k.begin(), k.begin() + 3);
    facets.push_back(k);
  }
  std::sort(facets.begin(), facets.end());
  for (size_t a = 0; a < facets.size();) {
    size_t b = a, tets = 0, triangles = 0;
    for (; b < facets.size() && std::equal(facets[b].begin(), facets[b].begin() + 3, facets[a].begin()); ++b)
      (facets[b][3] ? triangles : tets) += 1;
    if (tets > 2 || triangles > 1 || (tets == 2 && triangles) || (tets == 1 && !triangles && m.num_boundary_triangles()))
      return Status(Error::InvalidMesh, "facet " + std::to_string(facets[a][0]) + " " + std::to_string(facets[a][1]) + " " +
                                            std::to_string(facets[a][2]) + " has " + std::to_string(tets) + " tets and " +
                                            std::to_string(triangles) + " boundary triangles: the pieces do not fit");
    a = b;
  }
  return Status::success();
}

}  // namespace anitet
