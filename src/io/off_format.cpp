// OFF: "OFF" (optionally with ST/C/N prefixes), counts "nv nf [ne]", nv vertex lines "x y z ...",
// nf face lines "k i1 .. ik ...", 0-based indices, '#' comments.
#include <vector>

#include "io/number_text.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"

namespace anitet {

namespace {

// The keyword without its ST/C/N prefixes must be "OFF"; "4OFF", "nOFF" are not 3D files.
Status check_off_keyword(std::string_view word, TextScanner& in) {
  std::string_view rest = word;
  if (rest.substr(0, 2) == "ST") rest.remove_prefix(2);
  if (!rest.empty() && rest[0] == 'C') rest.remove_prefix(1);
  if (!rest.empty() && rest[0] == 'N') rest.remove_prefix(1);
  if (rest == "OFF") return Status::success();
  if (rest == "4OFF" || rest == "nOFF" || rest == "4nOFF") {
    return in.error(Error::UnsupportedFormat,
                    "only 3D OFF files are supported, not '" + quote_token(word) + "'");
  }
  return in.error(Error::Parse, "expected the 'OFF' header, found '" + quote_token(word) + "'");
}

Result<SurfaceMesh> parse_off(std::string_view data, const std::string& name) {
  TextScanner in(data, name);
  int64_t count = 0;
  // Some writers omit the keyword and start with the counts.
  if (!parse_int(in.peek_token(), count)) {
    Status header = check_off_keyword(in.next_token(), in);
    if (!header.ok()) return header;
    if (iequals(in.peek_token(), "BINARY")) {
      return in.error(Error::UnsupportedFormat, "binary OFF is not supported");
    }
  }
  uint64_t nv = 0, nf = 0;
  if (!in.read_count(kMaxVertices, nv)) return in.expected("the vertex count");
  if (!in.read_count(UINT32_MAX, nf)) return in.expected("the face count");
  in.skip_line();  // the edge count, ignored
  // A vertex takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
  if (nv * 6 + nf * 8 > in.remaining() + 1) {
    return in.error(Error::Parse, "the counts (" + std::to_string(nv) + " vertices, " +
                                      std::to_string(nf) + " faces) do not fit in the file");
  }
  SurfaceMesh mesh;
  mesh.xyz.reserve(3 * nv);
  mesh.tri.reserve(3 * nf);
  mesh.patch.reserve(nf);
  for (uint64_t v = 0; v < nv; ++v) {
    double p[3];
    for (double& c : p) {
      if (!in.read_double(c)) return in.expected("a coordinate of vertex " + std::to_string(v));
    }
    mesh.add_vertex(p[0], p[1], p[2]);
    in.skip_line();  // colours, normals, texture coordinates
  }
  std::vector<uint32_t> polygon;
  for (uint64_t f = 0; f < nf; ++f) {
    in.skip_space();
    const size_t line = in.line();
    uint64_t k = 0;
    if (!in.read_count(in.remaining(), k) || k < 3) {
      return in.expected("the vertex count (at least 3) of face " + std::to_string(f));
    }
    polygon.clear();
    for (uint64_t i = 0; i < k; ++i) {
      int64_t index = 0;
      if (!in.read_int(index)) return in.expected("a vertex index of face " + std::to_string(f));
      if (index < 0 || static_cast<uint64_t>(index) >= nv) {
        return bad_index(name + ":" + std::to_string(in.line()), "triangle", mesh.num_triangles(),
                         static_cast<uint64_t>(index), nv, 0);
      }
      polygon.push_back(static_cast<uint32_t>(index));
    }
    add_fan(mesh, polygon.data(), polygon.size(), 0, line);
    in.skip_line();  // face colour
  }
  // Data after the announced faces: the counts are wrong; refuse rather than drop faces.
  if (in.skip_space()) {
    return in.error(Error::Parse, "data after the " + std::to_string(nf) +
                                      " faces the header announces: '" +
                                      quote_token(in.peek_token()) + "'");
  }
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the file has no faces");
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_off(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_off(data, name); });
}

Result<std::string> to_off(const SurfaceMesh& mesh) {
  Status valid = check_surface_arrays(mesh);
  if (!valid.ok()) return valid;
  std::string out = "OFF\n";
  append_line(out, mesh.num_vertices(), mesh.num_triangles(), uint64_t{0});
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    append_line(out, mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2]);
  }
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    append_line(out, uint32_t{3}, mesh.tri[3 * t], mesh.tri[3 * t + 1], mesh.tri[3 * t + 2]);
  }
  return out;
}

}  // namespace anitet
