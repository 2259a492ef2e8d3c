// Wavefront OBJ: `v x y z [w|r g b]`, `f a b c ...` with a, a/t, a//n, a/t/n (1-based, negative
// = relative to the last vertex), `g`/`o` groups as patch labels; everything else is skipped.
#include <string>
#include <unordered_map>
#include <vector>

#include "io/number_text.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"

namespace anitet {

namespace {

// The vertex part of "a/t/n" as a 0-based index; false when it is not a valid reference.
bool parse_face_vertex(std::string_view token, uint64_t num_vertices, int64_t& index) {
  size_t slash = token.find('/');
  if (!parse_int(token.substr(0, slash), index)) return false;
  // 1 is the first vertex, -1 the last one read so far.
  index += index < 0 ? static_cast<int64_t>(num_vertices) : -1;
  return true;
}

Result<SurfaceMesh> parse_obj(std::string_view data, const std::string& name) {
  TextScanner in(data, name);
  SurfaceMesh mesh;
  // Rough sizes from the file length keep reallocation low on big files.
  mesh.xyz.reserve(data.size() / 40 * 3);
  mesh.tri.reserve(data.size() / 40 * 3);
  std::unordered_map<std::string, int32_t> group_label;
  int32_t label = 0;
  std::vector<uint32_t> polygon;
  while (in.skip_space()) {
    std::string_view key = in.token_in_line();
    if (key == "v") {
      double p[3];
      for (double& c : p) {
        if (!in.read_double_in_line(c)) return in.expected("a vertex coordinate");
      }
      if (mesh.num_vertices() >= kMaxVertices) return in.error(Error::Parse, "too many vertices");
      mesh.add_vertex(p[0], p[1], p[2]);
    } else if (key == "f") {
      polygon.clear();
      for (std::string_view token = in.token_in_line(); !token.empty();
           token = in.token_in_line()) {
        int64_t index = 0;
        if (!parse_face_vertex(token, mesh.num_vertices(), index)) {
          return in.error(Error::Parse, "expected a face vertex (a, a/t, a//n or a/t/n), found '" +
                                            quote_token(token) + "'");
        }
        // Negative or zero references are wrong now; too large ones are checked at the end
        // (a file may define vertices after the faces that use them).
        if (index < 0 || static_cast<uint64_t>(index) >= kMaxVertices) {
          return in.error(Error::BadIndex, "triangle " + std::to_string(mesh.num_triangles()) +
                                               " refers to vertex '" + quote_token(token) +
                                               "', which does not exist");
        }
        polygon.push_back(static_cast<uint32_t>(index));
      }
      if (polygon.size() < 3) return in.error(Error::Parse, "a face needs at least 3 vertices");
      add_fan(mesh, polygon.data(), polygon.size(), label, in.line());
    } else if (key == "g" || key == "o") {
      std::string group(in.rest_of_line());
      if (group.empty()) {
        label = 0;
      } else {
        auto inserted = group_label.emplace(group, static_cast<int32_t>(group_label.size() + 1));
        label = inserted.first->second;
      }
      continue;  // rest_of_line already moved to the next line
    }
    in.skip_line();
  }
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.tri[3 * t + k] >= mesh.num_vertices()) {
        return bad_index(name, "triangle", t, uint64_t{mesh.tri[3 * t + k]} + 1,
                         mesh.num_vertices(), 1);
      }
    }
  }
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the file has no faces");
  mesh.xyz.shrink_to_fit();
  mesh.tri.shrink_to_fit();
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_obj(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_obj(data, name); });
}

Result<std::string> to_obj(const SurfaceMesh& mesh) {
  Status valid = check_surface_arrays(mesh);
  if (!valid.ok()) return valid;
  std::string out;
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    out += "v ";
    append_line(out, mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2]);
  }
  bool labelled = false;
  for (int32_t p : mesh.patch) labelled = labelled || p != 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    if (labelled && (t == 0 || mesh.patch[t] != mesh.patch[t - 1])) {
      out += "g patch";
      append_int(out, mesh.patch[t]);
      out += '\n';
    }
    out += "f ";
    append_line(out, mesh.tri[3 * t] + 1, mesh.tri[3 * t + 1] + 1, mesh.tri[3 * t + 2] + 1);
  }
  return out;
}

}  // namespace anitet
