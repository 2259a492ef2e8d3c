// SU2 native mesh (.su2) as a surface: the boundary markers' triangles (quadrilaterals split),
// so that a mesh made for SU2 can be meshed again from its boundary. The volume elements are
// skipped. Marker i (in file order) becomes patch label i + 1, named by its MARKER_TAG.
#include <string>

#include "io/patch_names.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"

namespace anitet {

namespace {

// "KEY= value" or "KEY=value" at the start of a line: the value, trimmed; false for other lines.
bool keyword_value(std::string_view line, std::string_view key, std::string_view& value) {
  if (line.size() <= key.size() || !iequals(line.substr(0, key.size()), key)) return false;
  size_t i = key.size();
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i >= line.size() || line[i] != '=') return false;
  value = line.substr(i + 1);
  while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
  while (!value.empty() && (value.back() == ' ' || value.back() == '\t' || value.back() == '\r'))
    value.remove_suffix(1);
  return true;
}

Result<SurfaceMesh> parse_su2_surface(std::string_view data, const std::string& name, PatchNames* names) {
  TextScanner in(data, name, '%');
  SurfaceMesh mesh;
  uint64_t npoin = 0;
  bool have_points = false;
  int32_t marker = 0;
  auto count_of = [&](std::string_view value, const char* what, uint64_t& n) -> Status {
    // NPOIN may be followed by the count of domain points; the first number is the total.
    TextScanner v(value, name, '\0', in.line() - 1);
    if (!v.read_count(uint64_t(1) << 31, n)) return in.error(Error::Parse, std::string("bad ") + what + " count");
    return Status::success();
  };
  while (in.skip_space()) {
    const std::string_view line = in.rest_of_line();
    std::string_view value;
    if (keyword_value(line, "NDIME", value)) {
      if (value != "3") return in.error(Error::UnsupportedFormat, "NDIME= " + std::string(value) + ": only 3D meshes are read");
    } else if (keyword_value(line, "NELEM", value)) {
      uint64_t n = 0;
      if (Status s = count_of(value, "NELEM", n); !s.ok()) return s;
      for (uint64_t i = 0; i < n; ++i) {  // volume elements: not needed for the boundary
        if (!in.skip_space()) return in.error(Error::Parse, "end of file inside NELEM");
        in.skip_line();
      }
    } else if (keyword_value(line, "NPOIN", value)) {
      if (have_points) return in.error(Error::UnsupportedFormat, "a second NPOIN: multi-zone SU2 files are not read");
      if (Status s = count_of(value, "NPOIN", npoin); !s.ok()) return s;
      // A point takes a line of at least "x y z": a bogus count is refused before anything is
      // reserved for it (found by fuzzing: a 50-byte file asked for 36 GB).
      if (!fits(npoin, 6, in.remaining() + 1))
        return in.error(Error::Parse, "NPOIN= " + std::to_string(npoin) + ": the points do not fit in the file");
      mesh.xyz.reserve(3 * npoin);
      for (uint64_t i = 0; i < npoin; ++i) {
        double p[3];
        for (double& x : p)
          if (!in.read_double(x)) return in.expected("a point coordinate");
        mesh.add_vertex(p[0], p[1], p[2]);
        in.skip_line();  // an optional point index
      }
      have_points = true;
    } else if (keyword_value(line, "NMARK", value)) {
      continue;  // the markers follow, each announced by MARKER_TAG
    } else if (keyword_value(line, "MARKER_TAG", value)) {
      ++marker;
      if (names) {
        if (Status s = check_patch_name(std::string(value)); !s.ok())
          return in.error(Error::Parse, "MARKER_TAG '" + std::string(value) + "': " + s.message());
        (*names)[marker] = std::string(value);
      }
    } else if (keyword_value(line, "MARKER_ELEMS", value)) {
      if (marker == 0) return in.error(Error::Parse, "MARKER_ELEMS before any MARKER_TAG");
      uint64_t n = 0;
      if (Status s = count_of(value, "MARKER_ELEMS", n); !s.ok()) return s;
      for (uint64_t i = 0; i < n; ++i) {
        int64_t type = 0;
        if (!in.read_int(type)) return in.expected("a boundary element type (5 triangle, 9 quadrilateral)");
        const int corners = type == 5 ? 3 : type == 9 ? 4 : 0;
        if (corners == 0)
          return in.error(Error::UnsupportedFormat,
                          "boundary element type " + std::to_string(type) + " (only 5 triangle and 9 quadrilateral)");
        uint32_t v[4];
        for (int k = 0; k < corners; ++k) {
          int64_t id = 0;
          if (!in.read_int_in_line(id)) return in.expected("a boundary element vertex");
          if (id < 0 || uint64_t(id) >= npoin || !have_points)
            return in.error(Error::BadIndex, "boundary element vertex " + std::to_string(id) + " is not a point (NPOIN= " +
                                                 std::to_string(npoin) + (have_points ? ")" : ", before the points)"));
          v[k] = uint32_t(id);
        }
        mesh.add_triangle(v[0], v[1], v[2], marker);
        if (corners == 4) mesh.add_triangle(v[0], v[2], v[3], marker);
        in.skip_line();
      }
    }
    // Other keywords (and SU2's NZONE/IZONE of multi-zone files) carry nothing the surface needs.
  }
  if (mesh.num_triangles() == 0) return Status(Error::EmptyInput, name + ": no boundary marker triangles");
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_su2_surface(std::string_view data, const std::string& name, PatchNames* names) {
  return catch_bad_alloc(name, [&] { return parse_su2_surface(data, name, names); });
}

}  // namespace anitet
