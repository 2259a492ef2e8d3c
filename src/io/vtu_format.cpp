// VTK XML UnstructuredGrid (.vtu) with ASCII data arrays: writer, and a reader for such files
// (one Piece; tets and triangles kept, other cell types skipped).
#include <algorithm>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "io/reader_util.hpp"
#include "io/text_scanner.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;
constexpr int kVtkWedge = 13;
// VolumeMesh::prism's vertex k is VTK wedge vertex kVtkWedgeOrder[k] (VTK's 0 1 2 face points away
// from 3 4 5).
constexpr int kVtkWedgeOrder[6] = {0, 2, 1, 3, 5, 4};

// --- writer ---

template <class T>
void append_values(std::string& out, const T* values, size_t count, size_t per_line) {
  for (size_t i = 0; i < count; ++i) {
    append_value(out, values[i]);
    out += (i + 1) % per_line == 0 || i + 1 == count ? '\n' : ' ';
  }
}

void open_array(std::string& out, const char* type, const std::string& name, int components) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"";
  out += name;
  if (components > 1) {  // 1 is the default; meshio then gives 1-D arrays
    out += "\" NumberOfComponents=\"";
    append_int(out, components);
  }
  out += "\" format=\"ascii\">\n";
}

const char* kCloseArray = "        </DataArray>\n";

bool valid_xml_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    if (c == '"' || c == '<' || c == '>' || c == '&' || static_cast<unsigned char>(c) < 32) {
      return false;
    }
  }
  return true;
}

// --- reader ---

struct XmlTag {
  std::string_view name;
  std::string_view attributes;
  bool closing = false;
  bool self_closing = false;
  size_t end = 0;  // offset after '>'
};

// The next element tag at or after `pos`, skipping <?...?>, <!--...--> and <!...>.
bool next_tag(std::string_view data, size_t pos, XmlTag& tag) {
  for (;;) {
    size_t open = data.find('<', pos);
    if (open == std::string_view::npos) return false;
    if (data.substr(open, 4) == "<!--") {
      size_t close = data.find("-->", open + 4);
      if (close == std::string_view::npos) return false;
      pos = close + 3;
      continue;
    }
    size_t close = data.find('>', open);
    if (close == std::string_view::npos) return false;
    if (open + 1 < data.size() && (data[open + 1] == '?' || data[open + 1] == '!')) {
      pos = close + 1;
      continue;
    }
    std::string_view inner = data.substr(open + 1, close - open - 1);
    tag = XmlTag();
    tag.end = close + 1;
    if (!inner.empty() && inner[0] == '/') {
      tag.closing = true;
      inner.remove_prefix(1);
    }
    if (!inner.empty() && inner.back() == '/') {
      tag.self_closing = true;
      inner.remove_suffix(1);
    }
    size_t name_end = inner.find_first_of(" \t\r\n");
    tag.name = inner.substr(0, name_end);
    tag.attributes =
        name_end == std::string_view::npos ? std::string_view() : inner.substr(name_end);
    return true;
  }
}

// The value of attribute `key` ("" when absent).
std::string_view attribute(std::string_view attributes, std::string_view key) {
  size_t pos = 0;
  while ((pos = attributes.find(key, pos)) != std::string_view::npos) {
    size_t after = pos + key.size();
    bool starts = pos == 0 || attributes[pos - 1] == ' ' || attributes[pos - 1] == '\t' ||
                  attributes[pos - 1] == '\n' || attributes[pos - 1] == '\r';
    while (after < attributes.size() && attributes[after] == ' ') ++after;
    if (starts && after < attributes.size() && attributes[after] == '=') {
      ++after;
      while (after < attributes.size() && attributes[after] == ' ') ++after;
      if (after >= attributes.size()) return {};
      char quote = attributes[after];
      if (quote != '"' && quote != '\'') return {};
      size_t close = attributes.find(quote, after + 1);
      if (close == std::string_view::npos) return {};
      return attributes.substr(after + 1, close - after - 1);
    }
    pos = after;
  }
  return {};
}

// The numbers of one ascii DataArray (all read as doubles: exact for integers below 2^53).
Status read_numbers(std::string_view data, size_t begin, size_t end, const std::string& name,
                    LineCounter& lines, std::vector<double>& values) {
  TextScanner in(data.substr(begin, end - begin), name, '\0', lines.at(begin));
  values.clear();
  double v = 0;
  while (in.skip_space()) {
    if (!in.read_double(v)) return in.expected("a number");
    values.push_back(v);
  }
  return Status::success();
}

bool is_index(double v, uint64_t limit) {
  return v >= 0 && v < static_cast<double>(limit) &&
         v == static_cast<double>(static_cast<uint64_t>(v));
}

bool is_label(double v) {
  return v >= INT32_MIN && v <= INT32_MAX && v == static_cast<double>(static_cast<int64_t>(v));
}

struct VtuArrays {
  std::vector<double> points, connectivity, offsets, types, region, patch;
  bool have_region = false, have_patch = false;
  uint64_t num_points = 0, num_cells = 0;
};

Status parse_vtu_arrays(std::string_view data, const std::string& name, VtuArrays& a) {
  enum class Section { None, Points, Cells, CellData, Other } section = Section::None;
  bool have_piece = false, have_grid = false;
  XmlTag tag;
  std::vector<double> values;
  std::string region_name, patch_name;  // the names found, best first
  LineCounter lines(data);
  size_t pos = 0;
  while (next_tag(data, pos, tag)) {
    pos = tag.end;
    auto fail = [&](Error code, const std::string& message) {
      return Status(code, name + ":" + std::to_string(lines.at(tag.end)) + ": " + message);
    };
    if (tag.name == "VTKFile" && !tag.closing) {
      if (attribute(tag.attributes, "type") != "UnstructuredGrid") {
        return fail(Error::UnsupportedFormat, "only UnstructuredGrid VTK files are supported");
      }
      have_grid = true;
    } else if (tag.name == "Piece" && !tag.closing) {
      if (have_piece) {
        return fail(Error::UnsupportedFormat, "files with several Pieces are not supported");
      }
      have_piece = true;
      double np = 0, nc = 0;
      if (!parse_double(attribute(tag.attributes, "NumberOfPoints"), np) ||
          !is_index(np, kMaxVertices) ||
          !parse_double(attribute(tag.attributes, "NumberOfCells"), nc) ||
          !is_index(nc, UINT32_MAX)) {
        return fail(Error::Parse, "expected NumberOfPoints and NumberOfCells in <Piece>");
      }
      a.num_points = static_cast<uint64_t>(np);
      a.num_cells = static_cast<uint64_t>(nc);
    } else if (tag.name == "Points" || tag.name == "Cells" || tag.name == "CellData" ||
               tag.name == "PointData" || tag.name == "FieldData") {
      if (tag.closing || tag.self_closing) {
        section = Section::None;
      } else if (tag.name == "Points") {
        section = Section::Points;
      } else if (tag.name == "Cells") {
        section = Section::Cells;
      } else if (tag.name == "CellData") {
        section = Section::CellData;
      } else
        section = Section::Other;
    } else if (tag.name == "AppendedData") {
      return fail(Error::UnsupportedFormat, "appended (binary) VTU data is not supported");
    } else if (tag.name == "DataArray" && !tag.closing && !tag.self_closing) {
      size_t close = data.find("</DataArray>", tag.end);
      if (close == std::string_view::npos) {
        return fail(Error::Parse, "a DataArray has no </DataArray>");
      }
      pos = close + 12;
      std::string_view array_name = attribute(tag.attributes, "Name");
      bool wanted =
          section == Section::Points ||
          (section == Section::Cells &&
           (array_name == "connectivity" || array_name == "offsets" || array_name == "types")) ||
          (section == Section::CellData &&
           (array_name == "region" || array_name == "patch" || array_name == "medit:ref" ||
            array_name == "gmsh:physical"));
      if (!wanted) continue;
      std::string_view format = attribute(tag.attributes, "format");
      if (!format.empty() && format != "ascii") {
        return fail(
            Error::UnsupportedFormat,
            "only format=\"ascii\" data arrays are supported, not '" + quote_token(format) + "'");
      }
      Status status = read_numbers(data, tag.end, close, name, lines, values);
      if (!status.ok()) return status;
      if (section == Section::Points) {
        a.points.swap(values);
      } else if (section == Section::Cells) {
        (array_name == "connectivity" ? a.connectivity
         : array_name == "offsets"    ? a.offsets
                                      : a.types)
            .swap(values);
      } else {
        // "region"/"patch" win over meshio's names, which serve both cell kinds.
        bool generic = array_name != "region" && array_name != "patch";
        if ((array_name == "region" || generic) && (!a.have_region || region_name != "region")) {
          a.region = values;
          a.have_region = true;
          region_name = std::string(array_name);
        }
        if ((array_name == "patch" || generic) && (!a.have_patch || patch_name != "patch")) {
          a.patch = values;
          a.have_patch = true;
          patch_name = std::string(array_name);
        }
      }
    }
  }
  if (!have_grid || !have_piece) {
    return Status(Error::Parse,
                  name + ": expected a VTKFile of type UnstructuredGrid with a Piece");
  }
  return Status::success();
}

Result<VolumeMesh> parse_vtu(std::string_view data, const std::string& name) {
  VtuArrays a;
  Status status = parse_vtu_arrays(data, name, a);
  if (!status.ok()) return status;
  const uint64_t nv = a.num_points, nc = a.num_cells;
  auto fail = [&](const std::string& message) {
    return Status(Error::Parse, name + ": " + message);
  };
  if (a.points.size() != 3 * nv) {
    return fail("expected " + std::to_string(3 * nv) + " point coordinates, found " +
                std::to_string(a.points.size()));
  }
  if (a.offsets.size() != nc || a.types.size() != nc) {
    return fail("expected " + std::to_string(nc) + " cell offsets and types");
  }
  if ((a.have_region && a.region.size() != nc) || (a.have_patch && a.patch.size() != nc)) {
    return fail("a cell data array does not have one value per cell");
  }
  VolumeMesh mesh;
  mesh.xyz = std::move(a.points);
  uint64_t begin = 0;
  for (uint64_t c = 0; c < nc; ++c) {
    const double end = a.offsets[c];
    if (!(end >= static_cast<double>(begin) && end <= static_cast<double>(a.connectivity.size()))) {
      return fail("cell " + std::to_string(c) + " has a bad offset");
    }
    const uint64_t stop = static_cast<uint64_t>(end);
    const double type = a.types[c];
    const uint64_t size = stop - begin;
    const bool is_tet = type == kVtkTetra, is_tri = type == kVtkTriangle;
    if ((is_tet && size != 4) || (is_tri && size != 3)) {
      return fail("cell " + std::to_string(c) + " has " + std::to_string(size) +
                  " points for its type");
    }
    if (is_tet || is_tri) {
      for (uint64_t k = begin; k < stop; ++k) {
        if (!is_index(a.connectivity[k], nv)) {
          return Status(Error::BadIndex, name + ": cell " + std::to_string(c) +
                                             " refers to a point outside 0.." + std::to_string(nv) +
                                             " (exclusive)");
        }
        (is_tet ? mesh.tet : mesh.bnd_tri).push_back(static_cast<uint32_t>(a.connectivity[k]));
      }
      const std::vector<double>& labels = is_tet ? a.region : a.patch;
      double label = labels.empty() ? 0 : labels[c];
      if (!is_label(label)) {
        return fail("cell " + std::to_string(c) + " has a label that is not an int32");
      }
      (is_tet ? mesh.region : mesh.bnd_patch).push_back(static_cast<int32_t>(label));
    }
    begin = stop;
  }
  if (mesh.tet.empty()) return Status(Error::EmptyInput, name + ": the file has no tetrahedra");
  return mesh;
}

}  // namespace

Result<VolumeMesh> read_vtu(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_vtu(data, name); });
}

Result<std::string> to_vtu(const VolumeMesh& mesh, const std::vector<TetScalar>& tet_scalars) {
  Status valid = check_volume_arrays(mesh);
  if (!valid.ok()) return valid;
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets(), nb = mesh.num_boundary_triangles();
  // Cells: the tets, the prisms (nc - nb cells in all), then the boundary triangles.
  const size_t np = mesh.num_prisms(), nc = nt + np + nb;
  for (const TetScalar& s : tet_scalars) {
    if (s.values.size() != nt || !valid_xml_name(s.name) || s.name == "region" ||
        s.name == "patch") {
      return Status(Error::InvalidArgument,
                    "tet scalar '" + s.name + "' needs a plain, new name and one value per tet");
    }
  }
  const size_t per_vertex = nv == 0 ? 0 : mesh.vertex_metric.size() / nv;
  const bool write_metric = nv > 0 && (per_vertex == 1 || per_vertex == 6) &&
                            per_vertex * nv == mesh.vertex_metric.size();
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"";
  append_int(out, static_cast<int64_t>(nv));
  out += "\" NumberOfCells=\"";
  append_int(out, static_cast<int64_t>(nc));
  out += "\">\n      <Points>\n";
  open_array(out, "Float64", "Points", 3);
  append_values(out, mesh.xyz.data(), mesh.xyz.size(), 3);
  out += kCloseArray;
  out += "      </Points>\n      <Cells>\n";
  open_array(out, "Int64", "connectivity", 1);
  append_values(out, mesh.tet.data(), mesh.tet.size(), 4);
  if (np > 0) {
    std::vector<uint32_t> wedges(mesh.prism.size());
    for (size_t p = 0; p < np; ++p)
      for (int k = 0; k < 6; ++k) wedges[6 * p + size_t(k)] = mesh.prism[6 * p + size_t(kVtkWedgeOrder[k])];
    append_values(out, wedges.data(), wedges.size(), 6);
  }
  append_values(out, mesh.bnd_tri.data(), mesh.bnd_tri.size(), 3);
  out += kCloseArray;
  open_array(out, "Int64", "offsets", 1);
  std::vector<uint64_t> offsets(nc);
  for (size_t c = 0; c < nc; ++c) {
    offsets[c] = c < nt ? 4 * (c + 1) : c < nt + np ? 4 * nt + 6 * (c - nt + 1) : 4 * nt + 6 * np + 3 * (c - nt - np + 1);
  }
  append_values(out, offsets.data(), offsets.size(), 10);
  out += kCloseArray;
  open_array(out, "UInt8", "types", 1);
  std::vector<int32_t> types(nc, kVtkTriangle);
  std::fill(types.begin(), types.begin() + static_cast<std::ptrdiff_t>(nt), kVtkTetra);
  std::fill(types.begin() + static_cast<std::ptrdiff_t>(nt), types.begin() + static_cast<std::ptrdiff_t>(nt + np), kVtkWedge);
  append_values(out, types.data(), types.size(), 20);
  out += kCloseArray;
  out += "      </Cells>\n      <CellData>\n";
  // Labels on the cells they belong to, -1 on the other kind (VTK needs a value per cell).
  std::vector<int32_t> labels(nc, -1);
  for (size_t t = 0; t < nt; ++t) labels[t] = mesh.region.empty() ? 0 : mesh.region[t];
  for (size_t p = 0; p < np; ++p) labels[nt + p] = mesh.prism_region.empty() ? 0 : mesh.prism_region[p];
  open_array(out, "Int32", "region", 1);
  append_values(out, labels.data(), labels.size(), 20);
  out += kCloseArray;
  std::fill(labels.begin(), labels.end(), -1);
  for (size_t b = 0; b < nb; ++b) labels[nt + np + b] = mesh.bnd_patch[b];
  open_array(out, "Int32", "patch", 1);
  append_values(out, labels.data(), labels.size(), 20);
  out += kCloseArray;
  for (const TetScalar& s : tet_scalars) {
    std::vector<double> values(nc, -1.0);
    std::copy(s.values.begin(), s.values.end(), values.begin());
    open_array(out, "Float64", s.name, 1);
    append_values(out, values.data(), values.size(), 10);
    out += kCloseArray;
  }
  out += "      </CellData>\n";
  if (write_metric) {
    out += "      <PointData>\n";
    open_array(out, "Float64", per_vertex == 1 ? "size" : "metric", static_cast<int>(per_vertex));
    append_values(out, mesh.vertex_metric.data(), mesh.vertex_metric.size(), per_vertex);
    out += kCloseArray;
    out += "      </PointData>\n";
  }
  out += "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

}  // namespace anitet
