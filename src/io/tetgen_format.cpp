// TetGen .node / .ele / .face (ASCII, '#' comments). The first index of the .node file (0 or 1)
// numbers the vertices in all three files.
#include <cmath>
#include <string>

#include "io/reader_util.hpp"
#include "io/text_scanner.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

// A TetGen attribute or marker as an int32 label (attributes are written as reals).
bool to_label(double value, int32_t& label) {
  if (!(value >= INT32_MIN && value <= INT32_MAX)) return false;
  label = static_cast<int32_t>(std::lround(value));
  return true;
}

Status read_node_file(std::string_view text, const std::string& name, VolumeMesh& mesh,
                      int64_t& base) {
  TextScanner in(text, name);
  uint64_t count = 0, dim = 0, attributes = 0, markers = 0;
  if (!in.read_count(kMaxVertices, count)) return in.expected("the number of points");
  if (!in.read_count(UINT32_MAX, dim) || !in.read_count(UINT32_MAX, attributes) ||
      !in.read_count(1, markers)) {
    return in.expected("the .node header (points, dimension, attributes, markers)");
  }
  if (dim != 3) return in.error(Error::UnsupportedFormat, "only 3D .node files are supported");
  in.skip_line();
  if (!fits(count, 8, in.remaining() + 1)) {
    return in.error(Error::Parse, std::to_string(count) + " points do not fit in the file");
  }
  mesh.xyz.resize(3 * count);
  base = 0;
  for (uint64_t v = 0; v < count; ++v) {
    int64_t index = 0;
    if (!in.read_int(index)) return in.expected("the index of point " + std::to_string(v));
    if (v == 0) {
      if (index != 0 && index != 1) {
        return in.error(Error::Parse, "the first point index must be 0 or 1");
      }
      base = index;
    }
    for (int k = 0; k < 3; ++k) {
      if (!in.read_double(mesh.xyz[3 * v + k])) {
        return in.expected("a coordinate of point " + std::to_string(index));
      }
    }
    in.skip_line();  // attributes and marker
  }
  return Status::success();
}

Status read_ele_file(std::string_view text, const std::string& name, int64_t base,
                     VolumeMesh& mesh) {
  TextScanner in(text, name);
  uint64_t count = 0, corners = 0, attributes = 0;
  if (!in.read_count(UINT32_MAX, count) || !in.read_count(UINT32_MAX, corners) ||
      !in.read_count(UINT32_MAX, attributes)) {
    return in.expected("the .ele header (tetrahedra, nodes per tetrahedron, attributes)");
  }
  if (corners != 4 && corners != 10) {
    return in.error(Error::Parse, "expected 4 or 10 nodes per tetrahedron");
  }
  in.skip_line();
  if (!fits(count, 10, in.remaining() + 1)) {
    return in.error(Error::Parse, std::to_string(count) + " tetrahedra do not fit in the file");
  }
  const uint64_t nv = mesh.num_vertices();
  mesh.tet.resize(4 * count);
  mesh.region.assign(count, 0);
  for (uint64_t t = 0; t < count; ++t) {
    int64_t index = 0;
    if (!in.read_int(index)) return in.expected("the index of tetrahedron " + std::to_string(t));
    for (uint64_t k = 0; k < corners; ++k) {
      int64_t v = 0;
      if (!in.read_int(v)) return in.expected("a node of tetrahedron " + std::to_string(index));
      if (k >= 4) continue;  // quadratic tets: keep the corners
      if (v < base || static_cast<uint64_t>(v - base) >= nv) {
        return bad_index(name + ":" + std::to_string(in.line()), "tetrahedron", t,
                         static_cast<uint64_t>(v), nv, static_cast<uint64_t>(base));
      }
      mesh.tet[4 * t + k] = static_cast<uint32_t>(v - base);
    }
    if (attributes > 0) {
      double region = 0;
      if (!in.read_double(region) || !to_label(region, mesh.region[t])) {
        return in.expected("the region attribute of tetrahedron " + std::to_string(index));
      }
    }
    in.skip_line();
  }
  return Status::success();
}

Status read_face_file(std::string_view text, const std::string& name, int64_t base,
                      VolumeMesh& mesh) {
  TextScanner in(text, name);
  uint64_t count = 0, markers = 0;
  if (!in.read_count(UINT32_MAX, count) || !in.read_count(1, markers)) {
    return in.expected("the .face header (faces, markers)");
  }
  in.skip_line();
  if (!fits(count, 8, in.remaining() + 1)) {
    return in.error(Error::Parse, std::to_string(count) + " faces do not fit in the file");
  }
  const uint64_t nv = mesh.num_vertices();
  mesh.bnd_tri.resize(3 * count);
  mesh.bnd_patch.assign(count, 0);
  for (uint64_t f = 0; f < count; ++f) {
    int64_t index = 0;
    if (!in.read_int(index)) return in.expected("the index of face " + std::to_string(f));
    for (int k = 0; k < 3; ++k) {
      int64_t v = 0;
      if (!in.read_int(v)) return in.expected("a node of face " + std::to_string(index));
      if (v < base || static_cast<uint64_t>(v - base) >= nv) {
        return bad_index(name + ":" + std::to_string(in.line()), "triangle", f,
                         static_cast<uint64_t>(v), nv, static_cast<uint64_t>(base));
      }
      mesh.bnd_tri[3 * f + k] = static_cast<uint32_t>(v - base);
    }
    if (markers) {
      double marker = 0;
      if (!in.read_double(marker) || !to_label(marker, mesh.bnd_patch[f])) {
        return in.expected("the marker of face " + std::to_string(index));
      }
    }
    in.skip_line();  // adjacent tets (-nn)
  }
  return Status::success();
}

Result<VolumeMesh> parse_tetgen(std::string_view node, std::string_view ele, std::string_view face,
                                const std::string& name) {
  VolumeMesh mesh;
  int64_t base = 0;
  Status status = read_node_file(node, name + ".node", mesh, base);
  if (status.ok()) status = read_ele_file(ele, name + ".ele", base, mesh);
  if (status.ok() && !face.empty()) status = read_face_file(face, name + ".face", base, mesh);
  if (!status.ok()) return status;
  if (mesh.tet.empty()) return Status(Error::EmptyInput, name + ".ele: the file has no tetrahedra");
  return mesh;
}

}  // namespace

Result<VolumeMesh> read_tetgen(std::string_view node, std::string_view ele, std::string_view face,
                               const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_tetgen(node, ele, face, name); });
}

}  // namespace anitet
