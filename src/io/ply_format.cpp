// PLY: a text header (ply / format / element / property / end_header), then the elements in
// order, ascii or binary. The `vertex` element gives x y z, the `face` element's index list
// (vertex_indices or vertex_index, else its first list) the polygons; all else is skipped.
#include <string>
#include <vector>

#include "io/byte_reader.hpp"
#include "io/reader_util.hpp"
#include "io/surface_io.hpp"
#include "io/text_scanner.hpp"

namespace anitet {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_ply_type(std::string_view word, PlyType& type) {
  struct Entry {
    const char* name;
    PlyType type;
  };
  static const Entry kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const Entry& e : kTypes) {
    if (word == e.name) {
      type = e.type;
      return true;
    }
  }
  return false;
}

size_t type_size(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool whole_number(double d, int64_t& out) {
  if (!(d >= -9.0e18 && d <= 9.0e18)) return false;  // also rejects NaN
  out = static_cast<int64_t>(d);
  return static_cast<double>(out) == d;
}

bool is_integer(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the item type for a list
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyEncoding { Ascii, BinaryLittle, BinaryBig };

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // first byte after end_header's line
  size_t data_line = 0;    // its line number
};

Status parse_header(std::string_view data, const std::string& name, PlyHeader& header) {
  TextScanner in(data, name, '\0');
  if (in.next_token() != "ply") return in.error(Error::Parse, "expected 'ply' as the first line");
  in.skip_line();
  bool have_format = false;
  for (;;) {
    if (!in.skip_space()) return in.expected("'end_header'");
    std::string_view key = in.token_in_line();
    if (key == "format") {
      std::string_view encoding = in.token_in_line();
      if (encoding == "ascii") {
        header.encoding = PlyEncoding::Ascii;
      } else if (encoding == "binary_little_endian") {
        header.encoding = PlyEncoding::BinaryLittle;
      } else if (encoding == "binary_big_endian") {
        header.encoding = PlyEncoding::BinaryBig;
      } else
        return in.error(Error::UnsupportedFormat,
                        "unknown PLY format '" + quote_token(encoding) + "'");
      have_format = true;
      in.skip_line();
    } else if (key == "comment" || key == "obj_info") {
      in.skip_line();
    } else if (key == "element") {
      PlyElement element;
      element.name = std::string(in.token_in_line());
      int64_t count = 0;
      if (element.name.empty() || !in.read_int_in_line(count) || count < 0) {
        return in.expected("an element name and count");
      }
      element.count = static_cast<uint64_t>(count);
      header.elements.push_back(std::move(element));
      in.skip_line();
    } else if (key == "property") {
      if (header.elements.empty()) return in.error(Error::Parse, "a property before any element");
      PlyProperty property;
      std::string_view type = in.token_in_line();
      if (type == "list") {
        property.is_list = true;
        std::string_view count_type = in.token_in_line();
        if (!parse_ply_type(count_type, property.count_type) || !is_integer(property.count_type)) {
          return in.error(Error::Parse, "expected an integer list count type, found '" +
                                            quote_token(count_type) + "'");
        }
        type = in.token_in_line();
      }
      if (!parse_ply_type(type, property.type)) {
        return in.error(Error::Parse, "unknown property type '" + quote_token(type) + "'");
      }
      property.name = std::string(in.token_in_line());
      if (property.name.empty()) return in.error(Error::Parse, "a property without a name");
      header.elements.back().properties.push_back(std::move(property));
      in.skip_line();
    } else if (key == "end_header") {
      in.skip_line();
      break;
    } else {
      return in.error(Error::Parse, "unknown header line '" + quote_token(key) + "'");
    }
  }
  if (!have_format) return in.error(Error::Parse, "the header has no 'format' line");
  header.data_offset = in.offset();
  header.data_line = in.line();
  return Status::success();
}

// Reads one value of a property (or list item) as double or integer, from text or bytes.
class PlyValueReader {
 public:
  PlyValueReader(std::string_view data, const std::string& name, const PlyHeader& header)
      : encoding_(header.encoding),
        text_(data.substr(header.data_offset), name, '\0', header.data_line),
        bytes_(data, name, header.data_offset) {}

  bool binary() const { return encoding_ != PlyEncoding::Ascii; }
  size_t remaining() const { return binary() ? bytes_.remaining() : text_.remaining(); }
  // ASCII: something other than whitespace is left (binary files may carry padding).
  bool text_left() { return !binary() && text_.skip_space(); }

  bool read_double(PlyType type, double& out) {
    if (!binary()) return text_.read_double(out);
    if (!is_integer(type)) {
      if (type == PlyType::Float32) {
        float f;
        if (!bytes_.read(f, big())) return false;
        out = f;
        return true;
      }
      return bytes_.read(out, big());
    }
    int64_t i;
    if (!read_int(type, i)) return false;
    out = static_cast<double>(i);
    return true;
  }

  bool read_int(PlyType type, int64_t& out) {
    if (!binary()) {
      if (is_integer(type)) return text_.read_int(out);
      double d;  // a float-typed index list: accept whole numbers only
      return text_.read_double(d) && whole_number(d, out);
    }
    switch (type) {
      case PlyType::Int8:
        return read_as<int8_t>(out);
      case PlyType::UInt8:
        return read_as<uint8_t>(out);
      case PlyType::Int16:
        return read_as<int16_t>(out);
      case PlyType::UInt16:
        return read_as<uint16_t>(out);
      case PlyType::Int32:
        return read_as<int32_t>(out);
      case PlyType::UInt32:
        return read_as<uint32_t>(out);
      case PlyType::Float32:
      case PlyType::Float64: {
        double d;
        return read_double(type, d) && whole_number(d, out);
      }
    }
    return false;
  }

  // Skips one value: cheaper than reading it in binary.
  bool skip(PlyType type) {
    if (!binary()) return !text_.next_token().empty();
    return bytes_.skip(type_size(type));
  }

  Status expected(const std::string& what) {
    if (!binary()) return text_.expected(what);
    return bytes_.error(Error::Parse, "expected " + what + ", found " +
                                          (bytes_.remaining() ? "too few bytes" : "end of file"));
  }
  Status error(Error code, const std::string& message) {
    return binary() ? bytes_.error(code, message) : text_.error(code, message);
  }

 private:
  bool big() const { return encoding_ == PlyEncoding::BinaryBig; }
  template <class T>
  bool read_as(int64_t& out) {
    T v;
    if (!bytes_.read(v, big())) return false;
    out = static_cast<int64_t>(v);
    return true;
  }

  PlyEncoding encoding_;
  TextScanner text_;
  ByteReader bytes_;
};

// The least number of bytes one instance of the element takes (lists may be empty).
uint64_t min_element_bytes(const PlyElement& element, bool binary) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    bytes += binary ? type_size(p.is_list ? p.count_type : p.type) : 2;
  }
  return bytes;
}

Result<SurfaceMesh> parse_ply(std::string_view data, const std::string& name) {
  PlyHeader header;
  Status status = parse_header(data, name, header);
  if (!status.ok()) return status;
  PlyValueReader in(data, name, header);
  SurfaceMesh mesh;
  bool have_vertices = false;
  std::vector<uint32_t> polygon;
  for (const PlyElement& element : header.elements) {
    if (element.properties.empty()) continue;  // takes no bytes, whatever its count
    if (!fits(element.count, min_element_bytes(element, in.binary()), in.remaining())) {
      return in.error(Error::Parse, "element '" + element.name + "' claims " +
                                        std::to_string(element.count) +
                                        " entries, more than the file can hold");
    }
    const bool is_vertex = element.name == "vertex" && !have_vertices;
    const bool is_face = element.name == "face";
    int coord_of[3] = {-1, -1, -1};  // property index of x, y, z
    int index_list = -1;             // property index of the face's vertex list
    for (size_t i = 0; i < element.properties.size(); ++i) {
      const PlyProperty& p = element.properties[i];
      for (int k = 0; k < 3; ++k) {
        const char axis[2] = {static_cast<char>('x' + k), '\0'};
        if (!p.is_list && p.name == axis) coord_of[k] = static_cast<int>(i);
      }
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        index_list = static_cast<int>(i);
      }
    }
    if (is_face && index_list < 0) {
      for (size_t i = 0; i < element.properties.size() && index_list < 0; ++i) {
        if (element.properties[i].is_list) index_list = static_cast<int>(i);
      }
    }
    if (is_vertex) {
      if (coord_of[0] < 0 || coord_of[1] < 0 || coord_of[2] < 0) {
        return Status(Error::Parse, name + ": the vertex element lacks an x, y or z property");
      }
      if (element.count > kMaxVertices) return in.error(Error::Parse, "too many vertices");
      mesh.xyz.resize(3 * element.count);
      have_vertices = true;
    }
    if (is_face && index_list < 0) {
      return Status(Error::Parse, name + ": the face element has no vertex index list");
    }
    if (is_face) mesh.tri.reserve(mesh.tri.size() + 3 * element.count);
    for (uint64_t e = 0; e < element.count; ++e) {
      for (size_t i = 0; i < element.properties.size(); ++i) {
        const PlyProperty& p = element.properties[i];
        const int pi = static_cast<int>(i);
        if (p.is_list) {
          int64_t n = 0;
          if (!in.read_int(p.count_type, n) || n < 0 ||
              !fits(static_cast<uint64_t>(n), in.binary() ? type_size(p.type) : 2,
                    in.remaining())) {
            return in.expected("a list length of " + element.name + " " + std::to_string(e));
          }
          if (is_face && pi == index_list) {
            if (n < 3) {
              return in.error(Error::Parse,
                              "face " + std::to_string(e) + " has fewer than 3 vertices");
            }
            polygon.clear();
            for (int64_t k = 0; k < n; ++k) {
              int64_t v = 0;
              if (!in.read_int(p.type, v)) {
                return in.expected("a vertex index of face " + std::to_string(e));
              }
              if (v < 0 || static_cast<uint64_t>(v) >= mesh.num_vertices()) {
                return bad_index(name, "triangle", mesh.num_triangles(), static_cast<uint64_t>(v),
                                 mesh.num_vertices(), 0);
              }
              polygon.push_back(static_cast<uint32_t>(v));
            }
            add_fan(mesh, polygon.data(), polygon.size(), 0);
          } else {
            for (int64_t k = 0; k < n; ++k) {
              if (!in.skip(p.type)) return in.expected("a list item of " + element.name);
            }
          }
        } else if (is_vertex && (pi == coord_of[0] || pi == coord_of[1] || pi == coord_of[2])) {
          int k = pi == coord_of[0] ? 0 : pi == coord_of[1] ? 1 : 2;
          if (!in.read_double(p.type, mesh.xyz[3 * e + k])) {
            return in.expected("coordinate '" + p.name + "' of vertex " + std::to_string(e));
          }
        } else if (!in.skip(p.type)) {
          return in.expected("property '" + p.name + "' of " + element.name + " " +
                             std::to_string(e));
        }
      }
    }
  }
  if (in.text_left()) {
    return in.error(Error::Parse, "data after the elements the header announces (wrong counts?)");
  }
  if (mesh.tri.empty()) return Status(Error::EmptyInput, name + ": the PLY file has no faces");
  return mesh;
}

}  // namespace

Result<SurfaceMesh> read_ply(std::string_view data, const std::string& name) {
  return catch_bad_alloc(name, [&] { return parse_ply(data, name); });
}

}  // namespace anitet
