// VTK XML UnstructuredGrid (.vtu): the writer (ASCII data arrays), and a reader for one-Piece
// files in any of VTK's encodings (io/vtk_xml.hpp; tets and triangles kept, other cells skipped).
#include <algorithm>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "io/reader_util.hpp"
#include "io/volume_io.hpp"
#include "io/vtk_xml.hpp"

namespace anitet {

namespace {

constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;
constexpr int kVtkWedge = 13;
constexpr int kVtkPyramid = 14;  // VolumeMesh::pyramid's order is VTK's
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

bool wanted_array(VtkSection section, std::string_view name) {
  return section == VtkSection::Points ||
         (section == VtkSection::Cells && (name == "connectivity" || name == "offsets" || name == "types")) ||
         (section == VtkSection::CellData &&
          (name == "region" || name == "patch" || name == "medit:ref" || name == "gmsh:physical"));
}

Status parse_vtu_arrays(std::string_view data, const std::string& name, VtuArrays& a) {
  VtkGrid grid;
  if (Status st = read_vtk_grid(data, name, wanted_array, grid); !st.ok()) return st;
  if (grid.num_points >= kMaxVertices || grid.num_cells >= UINT32_MAX)
    return Status(Error::Parse, name + ": NumberOfPoints or NumberOfCells too large");
  a.num_points = grid.num_points;
  a.num_cells = grid.num_cells;
  std::string region_name, patch_name;  // the names found, best first
  for (VtkArray& array : grid.arrays) {
    if (array.section == VtkSection::Points) {
      a.points.swap(array.values);
    } else if (array.section == VtkSection::Cells) {
      (array.name == "connectivity" ? a.connectivity : array.name == "offsets" ? a.offsets : a.types)
          .swap(array.values);
    } else {
      // "region"/"patch" win over meshio's names, which serve both cell kinds.
      const bool generic = array.name != "region" && array.name != "patch";
      if ((array.name == "region" || generic) && (!a.have_region || region_name != "region")) {
        a.region = array.values;
        a.have_region = true;
        region_name = array.name;
      }
      if ((array.name == "patch" || generic) && (!a.have_patch || patch_name != "patch")) {
        a.patch = array.values;
        a.have_patch = true;
        patch_name = array.name;
      }
    }
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
  // Cells: the tets, the prisms, the pyramids (nc - nb cells in all), then the boundary triangles.
  const size_t np = mesh.num_prisms(), ny = mesh.num_pyramids(), nvol = nt + np + ny, nc = nvol + nb;
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
  append_values(out, mesh.pyramid.data(), mesh.pyramid.size(), 5);
  append_values(out, mesh.bnd_tri.data(), mesh.bnd_tri.size(), 3);
  out += kCloseArray;
  open_array(out, "Int64", "offsets", 1);
  std::vector<uint64_t> offsets(nc);
  for (size_t c = 0, end = 0; c < nc; ++c) {
    end += c < nt ? 4 : c < nt + np ? 6 : c < nvol ? 5 : 3;
    offsets[c] = end;
  }
  append_values(out, offsets.data(), offsets.size(), 10);
  out += kCloseArray;
  open_array(out, "UInt8", "types", 1);
  std::vector<int32_t> types(nc, kVtkTriangle);
  std::fill(types.begin(), types.begin() + static_cast<std::ptrdiff_t>(nt), kVtkTetra);
  std::fill(types.begin() + static_cast<std::ptrdiff_t>(nt), types.begin() + static_cast<std::ptrdiff_t>(nt + np), kVtkWedge);
  std::fill(types.begin() + static_cast<std::ptrdiff_t>(nt + np), types.begin() + static_cast<std::ptrdiff_t>(nvol),
            kVtkPyramid);
  append_values(out, types.data(), types.size(), 20);
  out += kCloseArray;
  out += "      </Cells>\n      <CellData>\n";
  // Labels on the cells they belong to, -1 on the other kind (VTK needs a value per cell).
  std::vector<int32_t> labels(nc, -1);
  for (size_t t = 0; t < nt; ++t) labels[t] = mesh.region.empty() ? 0 : mesh.region[t];
  for (size_t p = 0; p < np; ++p) labels[nt + p] = mesh.prism_region.empty() ? 0 : mesh.prism_region[p];
  for (size_t y = 0; y < ny; ++y) labels[nt + np + y] = mesh.pyramid_region.empty() ? 0 : mesh.pyramid_region[y];
  open_array(out, "Int32", "region", 1);
  append_values(out, labels.data(), labels.size(), 20);
  out += kCloseArray;
  std::fill(labels.begin(), labels.end(), -1);
  for (size_t b = 0; b < nb; ++b) labels[nvol + b] = mesh.bnd_patch[b];
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
