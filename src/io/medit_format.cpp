// Medit .mesh (ASCII): keyword sections "Vertices n / x y z ref", "Triangles n / a b c ref",
// "Quadrilaterals n / a b c d ref", "Tetrahedra n / a b c d ref" (1-based), "Dimension 3",
// '#' comments, "End". Other sections are skipped. Also the .sol (SolAtVertices) reader and
// writer.
#include <cstdlib>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "io/file_bytes.hpp"
#include "io/number_text.hpp"
#include "io/parallel_text.hpp"
#include "io/sol_io.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

struct MeditContent {
  std::vector<double> xyz;
  std::vector<uint32_t> tri, quad, tet;  // 0-based after the index check
  std::vector<int32_t> tri_ref, quad_ref, tet_ref;
  std::vector<uint32_t> tri_line, quad_line;  // the file line of each triangle and quadrilateral
};

bool starts_number(std::string_view token) {
  char c = token.empty() ? 'x' : token[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

bool read_ref(TextScanner& in, int32_t& ref) {
  int64_t value = 0;
  if (!in.read_int(value) || value < INT32_MIN || value > INT32_MAX) return false;
  ref = static_cast<int32_t>(value);
  return true;
}

// Reads `count` elements of `n` vertex indices and a ref; indices are checked later.
Status read_elements(TextScanner& in, const char* what, int n, std::vector<uint32_t>& vertices,
                     std::vector<int32_t>& refs, std::vector<uint32_t>* lines = nullptr) {
  uint64_t count = 0;
  if (!in.read_count(UINT32_MAX, count)) return in.expected(std::string("the number of ") + what);
  // Each element takes at least 2 bytes per number.
  if (!fits(count, 2 * (n + 1), in.remaining() + 1)) {
    return in.error(Error::Parse, std::to_string(count) + " " + what + " do not fit in the file");
  }
  vertices.reserve(vertices.size() + n * count);
  refs.reserve(refs.size() + count);
  for (uint64_t e = 0; e < count; ++e) {
    if (lines) {
      in.skip_space();
      lines->push_back(uint32_t(std::min<size_t>(in.line(), UINT32_MAX)));
    }
    for (int k = 0; k < n; ++k) {
      int64_t v = 0;
      if (!in.read_int(v)) {
        return in.expected("a vertex index of " + std::string(what) + " " + std::to_string(e + 1));
      }
      // 0 or too large wraps to a huge value and fails the later range check.
      vertices.push_back(v >= 1 && v <= static_cast<int64_t>(kMaxVertices)
                             ? static_cast<uint32_t>(v - 1)
                             : UINT32_MAX);
    }
    int32_t ref = 0;
    if (!read_ref(in, ref)) {
      return in.expected("the reference of " + std::string(what) + " " + std::to_string(e + 1));
    }
    refs.push_back(ref);
  }
  return Status::success();
}

Status check_indices(const std::string& name, const char* what, int n,
                     const std::vector<uint32_t>& vertices, size_t num_vertices) {
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (vertices[i] >= num_vertices) {
      return Status(Error::BadIndex, name + ": " + what + " " + std::to_string(i / n + 1) +
                                         " refers to a vertex outside 1.." +
                                         std::to_string(num_vertices));
    }
  }
  return Status::success();
}

Status parse_medit(std::string_view data, const std::string& name, MeditContent& out) {
  if (data.size() >= 4 && data.substr(0, 4).find('\0') != std::string_view::npos) {
    return Status(Error::UnsupportedFormat,
                  name + ": binary bytes in an ASCII Medit file (a binary Medit file is a .meshb)");
  }
  TextScanner in(data, name);
  bool have_vertices = false;
  for (;;) {
    std::string_view key = in.next_token();
    if (key.empty() || iequals(key, "End")) break;
    Status status;
    if (iequals(key, "MeshVersionFormatted")) {
      int64_t version = 0;
      if (!in.read_int(version)) return in.expected("the mesh version");
    } else if (iequals(key, "Dimension")) {
      int64_t dim = 0;
      if (!in.read_int(dim)) return in.expected("the dimension");
      if (dim != 3) return in.error(Error::UnsupportedFormat, "only Dimension 3 is supported");
    } else if (iequals(key, "Vertices")) {
      if (have_vertices) return in.error(Error::Parse, "a second Vertices section");
      have_vertices = true;
      uint64_t count = 0;
      if (!in.read_count(kMaxVertices, count)) return in.expected("the number of vertices");
      if (!fits(count, 8, in.remaining() + 1)) {
        return in.error(Error::Parse, std::to_string(count) + " vertices do not fit in the file");
      }
      out.xyz.resize(3 * count);
      for (uint64_t v = 0; v < count; ++v) {
        for (int k = 0; k < 3; ++k) {
          if (!in.read_double(out.xyz[3 * v + k])) {
            return in.expected("a coordinate of vertex " + std::to_string(v + 1));
          }
        }
        int32_t ref;
        if (!read_ref(in, ref)) {
          return in.expected("the reference of vertex " + std::to_string(v + 1));
        }
      }
    } else if (iequals(key, "Triangles")) {
      status = read_elements(in, "triangles", 3, out.tri, out.tri_ref, &out.tri_line);
    } else if (iequals(key, "Quadrilaterals")) {
      status = read_elements(in, "quadrilaterals", 4, out.quad, out.quad_ref, &out.quad_line);
    } else if (iequals(key, "Tetrahedra")) {
      status = read_elements(in, "tetrahedra", 4, out.tet, out.tet_ref);
    } else if (starts_number(key)) {
      return in.error(Error::Parse, "expected a keyword, found '" + quote_token(key) + "'");
    } else {
      // An unknown section: skip its numbers up to the next keyword.
      while (starts_number(in.peek_token())) in.next_token();
    }
    if (!status.ok()) return status;
  }
  size_t nv = out.xyz.size() / 3;
  Status status = check_indices(name, "triangle", 3, out.tri, nv);
  if (status.ok()) status = check_indices(name, "quadrilateral", 4, out.quad, nv);
  if (status.ok()) status = check_indices(name, "tetrahedron", 4, out.tet, nv);
  return status;
}

Result<SurfaceMesh> parse_medit_surface(std::string_view data, const std::string& name) {
  MeditContent content;
  Status status = parse_medit(data, name, content);
  if (!status.ok()) return status;
  SurfaceMesh mesh;
  mesh.xyz = std::move(content.xyz);
  mesh.tri = std::move(content.tri);
  mesh.patch = std::move(content.tri_ref);
  mesh.line = std::move(content.tri_line);
  for (size_t q = 0; q < content.quad_ref.size(); ++q) {
    add_fan(mesh, &content.quad[4 * q], 4, content.quad_ref[q], content.quad_line[q]);
  }
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the file has no triangles");
  return mesh;
}

Result<VolumeMesh> parse_medit_volume(std::string_view data, const std::string& name) {
  MeditContent content;
  Status status = parse_medit(data, name, content);
  if (!status.ok()) return status;
  if (content.tet.empty()) return Status(Error::EmptyInput, name + ": the file has no tetrahedra");
  VolumeMesh mesh;
  mesh.xyz = std::move(content.xyz);
  mesh.tet = std::move(content.tet);
  mesh.region = std::move(content.tet_ref);
  mesh.bnd_tri = std::move(content.tri);
  mesh.bnd_patch = std::move(content.tri_ref);
  return mesh;
}

// The sections, handed to sink(std::string_view) piece by piece (a string or a file).
template <class Sink>
void write_vertices(Sink&& sink, const std::vector<double>& xyz) {
  std::string head = "\nVertices\n";
  append_line(head, xyz.size() / 3);
  sink(std::string_view(head));
  write_items(sink, xyz.size() / 3, [&xyz](std::string& text, size_t v) {
    append_line(text, xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], int32_t{0});
  });
}

// "Keyword / count / a b c [d] ref" with 1-based indices; refs may be empty (all 0).
template <class Sink>
void write_elements(Sink&& sink, const char* keyword, int n, const std::vector<uint32_t>& vertices,
                    const std::vector<int32_t>& refs) {
  size_t count = vertices.size() / n;
  if (count == 0) return;
  std::string head = "\n";
  head += keyword;
  head += "\n";
  append_line(head, count);
  sink(std::string_view(head));
  write_items(sink, count, [&](std::string& text, size_t e) {
    for (int k = 0; k < n; ++k) {
      append_int(text, int64_t{vertices[n * e + k]} + 1);
      text += ' ';
    }
    append_int(text, refs.empty() ? 0 : refs[e]);
    text += '\n';
  });
}

void append_vertices(std::string& out, const std::vector<double>& xyz) {
  write_vertices([&out](std::string_view text) { out += text; }, xyz);
}
void append_elements(std::string& out, const char* keyword, int n, const std::vector<uint32_t>& vertices,
                     const std::vector<int32_t>& refs) {
  write_elements([&out](std::string_view text) { out += text; }, keyword, n, vertices, refs);
}

const char* kMeditHeader = "MeshVersionFormatted 2\n\nDimension 3\n";

// The patch names anitet's writer puts in comment lines "# patch LABEL NAME" (Medit has no
// names). Other comments, and lines of another shape, are comments only.
void read_patch_name_comments(std::string_view data, PatchNames& names) {
  constexpr std::string_view kPrefix = "# patch ";
  for (size_t at = data.find(kPrefix); at != std::string_view::npos; at = data.find(kPrefix, at + 1)) {
    if (at > 0 && data[at - 1] != '\n') continue;
    size_t eol = data.find('\n', at);
    std::string line(data.substr(at + kPrefix.size(), (eol == std::string_view::npos ? data.size() : eol) - at - kPrefix.size()));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    const size_t space = line.find(' ');
    if (space == std::string::npos) continue;
    char* end = nullptr;
    const long label = std::strtol(line.c_str(), &end, 10);
    const std::string text = line.substr(space + 1);
    if (end != line.c_str() + space || label < INT32_MIN || label > INT32_MAX || !check_patch_name(text).ok()) continue;
    names[int32_t(label)] = text;
  }
}

}  // namespace

Result<SurfaceMesh> read_medit_surface(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_medit_surface(data, name); });
}

PatchNames medit_patch_names(std::string_view data) {
  PatchNames names;
  read_patch_name_comments(data, names);
  return names;
}

Result<VolumeMesh> read_medit_volume(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_medit_volume(data, name); });
}

Result<std::string> to_medit(const SurfaceMesh& mesh) {
  Status valid = check_surface_arrays(mesh);
  if (!valid.ok()) return valid;
  std::string out = kMeditHeader;
  append_vertices(out, mesh.xyz);
  append_elements(out, "Triangles", 3, mesh.tri, mesh.patch);
  out += "\nEnd\n";
  return out;
}

namespace {

// The volume mesh's text, handed to sink piece by piece; `named` from medit_patch_names.
template <class Sink>
void write_medit_volume_text(const VolumeMesh& mesh, const std::vector<NamedPatch>& named, Sink&& sink) {
  std::string head = kMeditHeader;
  // Medit has no names: the patch names go in comments (readers skip lines starting with '#').
  if (!named.empty()) head += "\n";
  for (const NamedPatch& p : named) {
    head += "# patch ";
    append_int(head, p.label);
    head += ' ' + p.name + '\n';
  }
  sink(std::string_view(head));
  write_vertices(sink, mesh.xyz);
  write_elements(sink, "Triangles", 3, mesh.bnd_tri, mesh.bnd_patch);
  write_elements(sink, "Tetrahedra", 4, mesh.tet, mesh.region);
  sink(std::string_view("\nEnd\n"));
}

// The mesh's arrays checked and its patches named, before anything is written.
Result<std::vector<NamedPatch>> medit_patch_names(const VolumeMesh& mesh, const PatchNames& patch_names) {
  if (Status valid = check_volume_arrays(mesh); !valid.ok()) return valid;
  return named_patches(mesh.bnd_patch, patch_names);
}

}  // namespace

Result<std::string> to_medit(const VolumeMesh& mesh, const PatchNames& patch_names) {
  Result<std::vector<NamedPatch>> named = medit_patch_names(mesh, patch_names);
  if (!named.ok()) return named.status();
  std::string out;
  write_medit_volume_text(mesh, named.value(), [&out](std::string_view text) { out += text; });
  return out;
}

Status write_medit_volume(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names) {
  Result<std::vector<NamedPatch>> named = medit_patch_names(mesh, patch_names);
  if (!named.ok()) return named.status();
  // Streamed to the file, not built in a string first: a large mesh's text runs to hundreds of MB,
  // and a string grown by doubling copies it and touches fresh pages each time.
  return write_file_with(path, [&](const std::function<bool(std::string_view)>& write) {
    bool ok = true;
    write_medit_volume_text(mesh, named.value(), [&](std::string_view bytes) {
      if (ok) ok = write(bytes);
    });
    return ok;
  });
}

namespace {

// "k t1 .. tk": the fields of a SolAtVertices block.
Status read_field_kinds(TextScanner& in, std::vector<FieldKind>& kinds) {
  uint64_t count = 0;
  if (!in.read_count(in.remaining(), count) || count == 0) return in.expected("the number of fields (at least 1)");
  for (uint64_t i = 0; i < count; ++i) {
    int64_t type = 0;
    if (!in.read_int(type)) return in.expected("the type of field " + std::to_string(i + 1));
    if (type == 4) {
      return in.error(Error::UnsupportedFormat, "field " + std::to_string(i + 1) + " is a full matrix (type 4): "
                                                "anitet reads scalars (1), vectors (2) and symmetric tensors (3)");
    }
    if (type < 1 || type > 4) {
      return in.error(Error::Parse, "field " + std::to_string(i + 1) + " has type " + std::to_string(type) +
                                        " (expected 1 scalar, 2 vector, 3 symmetric tensor)");
    }
    kinds.push_back(FieldKind(type));
  }
  return Status::success();
}

Status read_sol_at_vertices(TextScanner& in, VertexFields& out) {
  uint64_t count = 0;
  if (!in.read_count(kMaxVertices, count)) return in.expected("the number of vertices");
  if (Status s = read_field_kinds(in, out.kinds); !s.ok()) return s;
  const size_t record = out.record_size();
  // Each value takes at least 2 bytes.
  if (!fits(count, 2 * record, in.remaining() + 1)) {
    return in.error(Error::Parse, std::to_string(count) + " vertices of " + std::to_string(record) +
                                      " values do not fit in the file");
  }
  out.values.resize(count * record);
  for (size_t i = 0; i < out.values.size(); ++i) {
    if (!in.read_double(out.values[i])) {
      return in.expected("value " + std::to_string(i % record + 1) + " of vertex " + std::to_string(i / record + 1));
    }
  }
  return Status::success();
}

Result<VertexFields> parse_medit_sol(std::string_view data, const std::string& name) {
  if (data.size() >= 4 && data.substr(0, 4).find('\0') != std::string_view::npos) {
    return Status(Error::UnsupportedFormat, name + ": binary bytes in an ASCII .sol (a binary file is a .solb)");
  }
  TextScanner in(data, name);
  VertexFields out;
  bool have_field = false;
  for (;;) {
    std::string_view key = in.next_token();
    if (key.empty() || iequals(key, "End")) break;
    if (iequals(key, "MeshVersionFormatted")) {
      int64_t version = 0;
      if (!in.read_int(version)) return in.expected("the mesh version");
    } else if (iequals(key, "Dimension")) {
      int64_t dim = 0;
      if (!in.read_int(dim)) return in.expected("the dimension");
      if (dim != 3 && dim != 2) return in.error(Error::UnsupportedFormat, "only Dimension 3 or 2 is supported");
      if (have_field) return in.error(Error::Parse, "Dimension after SolAtVertices");
      out.dimension = int(dim);
    } else if (iequals(key, "SolAtVertices")) {
      if (have_field) return in.error(Error::Parse, "a second SolAtVertices section");
      have_field = true;
      if (Status s = read_sol_at_vertices(in, out); !s.ok()) return s;
    } else if (starts_number(key)) {
      return in.error(Error::Parse, "expected a keyword, found '" + quote_token(key) + "'");
    } else {
      while (starts_number(in.peek_token())) in.next_token();  // a section anitet does not read
    }
  }
  if (!have_field) return Status(Error::EmptyInput, name + ": no SolAtVertices");
  return out;
}

}  // namespace

Result<VertexFields> read_medit_sol(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_medit_sol(data, name); });
}

Result<std::string> to_sol(const VertexFields& fields) {
  const size_t record = fields.record_size();
  if (record == 0 || fields.values.size() % record != 0) {
    return Status(Error::InvalidArgument, "vertex fields: " + std::to_string(fields.values.size()) +
                                              " values are not a whole number of records of " + std::to_string(record));
  }
  const size_t nv = fields.values.size() / record;
  std::string out = fields.dimension == 2 ? "MeshVersionFormatted 2\n\nDimension 2\n" : kMeditHeader;
  out += "\nSolAtVertices\n";
  append_line(out, nv);
  append_int(out, int64_t(fields.kinds.size()));
  for (const FieldKind k : fields.kinds) {
    out += ' ';
    append_int(out, int64_t(k));
  }
  out += '\n';
  for (size_t v = 0; v < nv; ++v) {
    for (size_t k = 0; k < record; ++k) {
      if (k) out += ' ';
      append_double(out, fields.values[record * v + k]);
    }
    out += '\n';
  }
  out += "\nEnd\n";
  return out;
}

}  // namespace anitet
