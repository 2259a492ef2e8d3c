#include "io/vtk_xml.hpp"

#include <zlib.h>

#include <cstring>

#include "io/reader_util.hpp"
#include "io/text_scanner.hpp"

namespace anitet {

bool next_xml_tag(std::string_view data, size_t pos, XmlTag& tag) {
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
    tag.attributes = name_end == std::string_view::npos ? std::string_view() : inner.substr(name_end);
    return true;
  }
}

std::string_view xml_attribute(std::string_view attributes, std::string_view key) {
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

const VtkArray* VtkGrid::find(VtkSection section, std::string_view name) const {
  for (const VtkArray& a : arrays)
    if (a.section == section && a.name == name) return &a;
  return nullptr;
}

namespace {

// The bytes of one binary array, raw or base64 (read four characters at a time, so that a header
// and its data encoded one after the other, each with its own padding, read as one stream).
class ByteSource {
 public:
  ByteSource(std::string_view text, bool base64) : text_(text), base64_(base64) {}

  // Appends the next n bytes to out; false when there are fewer.
  bool take(uint64_t n, std::string& out) {
    if (n > bound()) return false;
    if (!base64_) {
      out.append(text_.substr(pos_, size_t(n)));
      pos_ += size_t(n);
      return true;
    }
    while (n > 0) {
      if (have_ == used_ && !decode_group()) return false;
      const size_t k = std::min<uint64_t>(n, have_ - used_);
      out.append(group_ + used_, k);
      used_ += k;
      n -= k;
    }
    return true;
  }
  bool take_int(bool is64, uint64_t& v) {
    std::string b;
    if (!take(is64 ? 8 : 4, b)) return false;
    if (is64) {
      std::memcpy(&v, b.data(), 8);
    } else {
      uint32_t v32 = 0;
      std::memcpy(&v32, b.data(), 4);
      v = v32;
    }
    return true;
  }
  // At least as many bytes as are left: no claim of a larger size is believed.
  uint64_t bound() const {
    const uint64_t left = text_.size() - pos_;
    return base64_ ? left / 4 * 3 + 3 + (have_ - used_) : left;
  }

 private:
  static int value_of(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return c == '=' ? 64 : -1;
  }
  bool decode_group() {
    int v[4], got = 0;
    while (got < 4 && pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
      if ((v[got++] = value_of(c)) < 0) return false;
    }
    if (got < 4 || v[0] == 64 || v[1] == 64 || (v[2] == 64 && v[3] != 64)) return false;
    const uint32_t bits = uint32_t(v[0]) << 18 | uint32_t(v[1]) << 12 | uint32_t(v[2] & 63) << 6 | uint32_t(v[3] & 63);
    group_[0] = char(bits >> 16);
    group_[1] = char(bits >> 8 & 255);
    group_[2] = char(bits & 255);
    have_ = v[2] == 64 ? 1 : v[3] == 64 ? 2 : 3;
    used_ = 0;
    return true;
  }

  std::string_view text_;
  bool base64_;
  size_t pos_ = 0;
  char group_[3] = {0, 0, 0};
  size_t have_ = 0, used_ = 0;
};

struct BinaryForm {
  bool header64 = false;  // UInt64 headers (else UInt32)
  bool zlib = false;      // vtkZLibDataCompressor
};

// The bytes of one binary array: a size and the data, or zlib blocks (their count, the size of
// a block and of the last one, each block's compressed size, then the blocks).
bool read_binary(ByteSource& in, const BinaryForm& form, std::string& bytes, std::string& why) {
  bytes.clear();
  uint64_t n = 0;
  if (!form.zlib) {
    if (!in.take_int(form.header64, n) || !in.take(n, bytes)) return why = "truncated binary data", false;
    return true;
  }
  uint64_t blocks = 0, block_size = 0, last_size = 0;
  if (!in.take_int(form.header64, blocks) || !in.take_int(form.header64, block_size) ||
      !in.take_int(form.header64, last_size) || blocks > in.bound() / 4)
    return why = "truncated compressed-data header", false;
  std::vector<uint64_t> packed(blocks);
  uint64_t packed_total = 0;
  for (uint64_t& p : packed) {
    if (!in.take_int(form.header64, p) || p > in.bound()) return why = "truncated compressed-data header", false;
    packed_total += p;
  }
  if (packed_total > in.bound()) return why = "truncated compressed data", false;
  if (blocks == 0) return true;
  const uint64_t last = last_size ? last_size : block_size;
  // zlib expands by at most ~1032 to 1: a larger claim is a corrupt header, not an allocation.
  if (block_size > (uint64_t(1) << 32) || last > block_size || (blocks - 1) * block_size + last > 1100 * packed_total + 4096)
    return why = "implausible compressed-data sizes", false;
  bytes.resize(size_t((blocks - 1) * block_size + last));
  std::string packed_block;
  for (uint64_t b = 0; b < blocks; ++b) {
    packed_block.clear();
    if (!in.take(packed[b], packed_block)) return why = "truncated compressed data", false;
    uLongf size = uLongf(b + 1 == blocks ? last : block_size);
    const uLongf want = size;
    auto* to = reinterpret_cast<Bytef*>(&bytes[size_t(b * block_size)]);
    if (uncompress(to, &size, reinterpret_cast<const Bytef*>(packed_block.data()), uLong(packed_block.size())) != Z_OK ||
        size != want)
      return why = "a zlib block that does not inflate to its size", false;
  }
  return true;
}

template <class T>
void append_as_doubles(const std::string& bytes, std::vector<double>& out) {
  const size_t n = bytes.size() / sizeof(T);
  out.resize(n);
  for (size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    out[i] = static_cast<double>(v);
  }
}

// The values of a binary array of VTK type `type`; false for an unknown type or a byte count
// that is not a whole number of values.
bool binary_values(std::string_view type, const std::string& bytes, std::vector<double>& out) {
  struct Kind {
    const char* name;
    size_t size;
    void (*convert)(const std::string&, std::vector<double>&);
  };
  static constexpr Kind kKinds[] = {
      {"Int8", 1, append_as_doubles<int8_t>},     {"UInt8", 1, append_as_doubles<uint8_t>},
      {"Int16", 2, append_as_doubles<int16_t>},   {"UInt16", 2, append_as_doubles<uint16_t>},
      {"Int32", 4, append_as_doubles<int32_t>},   {"UInt32", 4, append_as_doubles<uint32_t>},
      {"Int64", 8, append_as_doubles<int64_t>},   {"UInt64", 8, append_as_doubles<uint64_t>},
      {"Float32", 4, append_as_doubles<float>},   {"Float64", 8, append_as_doubles<double>}};
  for (const Kind& k : kKinds)
    if (type == k.name) {
      if (bytes.size() % k.size) return false;
      k.convert(bytes, out);
      return true;
    }
  return false;
}

// The numbers of one ascii DataArray.
Status read_ascii(std::string_view data, size_t begin, size_t end, const std::string& name, LineCounter& lines,
                  std::vector<double>& values) {
  TextScanner in(data.substr(begin, end - begin), name, '\0', lines.at(begin));
  values.clear();
  double v = 0;
  while (in.skip_space()) {
    if (!in.read_double(v)) return in.expected("a number");
    values.push_back(v);
  }
  return Status::success();
}

// What the VTKFile tag says of its binary arrays; the unsupported forms fail only when such an
// array is read.
struct FileForm {
  BinaryForm binary;
  std::string unsupported;  // why binary arrays cannot be read, if they cannot
  std::string_view appended;
  bool appended_base64 = false;
  bool have_appended = false;
};

// The binary form and what is unsupported of it, from the VTKFile tag's attributes, into f.
void read_file_form(std::string_view root_attributes, FileForm& f) {
  f.unsupported.clear();
  const std::string_view order = xml_attribute(root_attributes, "byte_order");
  const std::string_view header = xml_attribute(root_attributes, "header_type");
  const std::string_view compressor = xml_attribute(root_attributes, "compressor");
  f.binary.header64 = header == "UInt64";
  f.binary.zlib = compressor == "vtkZLibDataCompressor";
  if (!order.empty() && order != "LittleEndian")
    f.unsupported = "big-endian binary data is not supported";
  else if (!header.empty() && header != "UInt32" && header != "UInt64")
    f.unsupported = "header_type '" + quote_token(header) + "' is not UInt32 or UInt64";
  else if (!compressor.empty() && !f.binary.zlib)
    f.unsupported = "compressor '" + quote_token(compressor) + "' is not supported (zlib is; or write it uncompressed)";
}

// Where the appended data starts ('_' after <AppendedData>), and the XML before it.
Status split_appended(std::string_view data, const std::string& name, std::string_view& xml, FileForm& form) {
  xml = data;
  const size_t at = data.find("<AppendedData");
  if (at == std::string_view::npos) return Status::success();
  XmlTag tag;
  if (!next_xml_tag(data, at, tag)) return Status(Error::Parse, name + ": an unclosed <AppendedData> tag");
  const std::string_view encoding = xml_attribute(tag.attributes, "encoding");
  if (encoding != "raw" && encoding != "base64")
    return Status(Error::Parse, name + ": <AppendedData> encoding is not raw or base64");
  const size_t underscore = data.find('_', tag.end);
  if (underscore == std::string_view::npos) return Status(Error::Parse, name + ": no '_' in <AppendedData>");
  xml = data.substr(0, at);
  form.appended = data.substr(underscore + 1);
  form.appended_base64 = encoding == "base64";
  form.have_appended = true;
  return Status::success();
}

// One wanted DataArray whose tag is `tag` (its text up to `close` when not self-closing).
Status read_array(std::string_view xml, const XmlTag& tag, size_t close, const FileForm& form, const std::string& name,
                  LineCounter& lines, std::vector<double>& values) {
  auto fail = [&](Error code, const std::string& message) {
    return Status(code, name + ":" + std::to_string(lines.at(tag.end)) + ": " + message);
  };
  const std::string_view format = xml_attribute(tag.attributes, "format");
  if (format.empty() || format == "ascii") {
    if (tag.self_closing) return values.clear(), Status::success();
    return read_ascii(xml, tag.end, close, name, lines, values);
  }
  if (format != "binary" && format != "appended")
    return fail(Error::UnsupportedFormat, "DataArray format '" + quote_token(format) + "' is not ascii, binary or appended");
  if (!form.unsupported.empty()) return fail(Error::UnsupportedFormat, form.unsupported);
  ByteSource in(xml.substr(tag.end, close - tag.end), true);
  if (format == "appended") {
    if (!form.have_appended) return fail(Error::Parse, "an appended DataArray but no <AppendedData>");
    uint64_t offset = 0;
    const std::string_view text = xml_attribute(tag.attributes, "offset");
    if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string_view::npos ||
        (offset = std::stoull(std::string(text))) > form.appended.size())
      return fail(Error::Parse, "an appended DataArray without a valid offset");
    in = ByteSource(form.appended.substr(size_t(offset)), form.appended_base64);
  }
  std::string bytes, why;
  if (!read_binary(in, form.binary, bytes, why)) return fail(Error::Parse, why);
  if (!binary_values(xml_attribute(tag.attributes, "type"), bytes, values))
    return fail(Error::Parse, "a binary DataArray of unknown type or a partial value");
  return Status::success();
}

VtkSection section_of(std::string_view tag) {
  if (tag == "Points") return VtkSection::Points;
  if (tag == "Cells") return VtkSection::Cells;
  if (tag == "PointData") return VtkSection::PointData;
  if (tag == "CellData") return VtkSection::CellData;
  return VtkSection::Other;
}

}  // namespace

Status read_vtk_grid(std::string_view data, const std::string& name, VtkWanted wanted, VtkGrid& grid) {
  grid = VtkGrid();
  FileForm form;
  std::string_view xml;
  if (Status st = split_appended(data, name, xml, form); !st.ok()) return st;
  VtkSection section = VtkSection::None;
  bool have_piece = false, have_grid = false;
  XmlTag tag;
  LineCounter lines(xml);
  size_t pos = 0;
  while (next_xml_tag(xml, pos, tag)) {
    pos = tag.end;
    auto fail = [&](Error code, const std::string& message) {
      return Status(code, name + ":" + std::to_string(lines.at(tag.end)) + ": " + message);
    };
    if (tag.name == "VTKFile" && !tag.closing) {
      if (xml_attribute(tag.attributes, "type") != "UnstructuredGrid")
        return fail(Error::UnsupportedFormat, "only UnstructuredGrid VTK files are supported");
      read_file_form(tag.attributes, form);
      have_grid = true;
    } else if (tag.name == "Piece" && !tag.closing) {
      if (have_piece) return fail(Error::UnsupportedFormat, "files with several Pieces are not supported");
      have_piece = true;
      const std::string_view np = xml_attribute(tag.attributes, "NumberOfPoints");
      const std::string_view nc = xml_attribute(tag.attributes, "NumberOfCells");
      if (np.empty() || nc.empty() || np.size() > 12 || nc.size() > 12 ||
          np.find_first_not_of("0123456789") != std::string_view::npos ||
          nc.find_first_not_of("0123456789") != std::string_view::npos)
        return fail(Error::Parse, "expected NumberOfPoints and NumberOfCells in <Piece>");
      grid.num_points = std::stoull(std::string(np));
      grid.num_cells = std::stoull(std::string(nc));
    } else if (tag.name == "Points" || tag.name == "Cells" || tag.name == "CellData" || tag.name == "PointData" ||
               tag.name == "FieldData") {
      section = tag.closing || tag.self_closing ? VtkSection::None : section_of(tag.name);
    } else if (tag.name == "DataArray" && !tag.closing) {
      size_t close = tag.end;
      if (!tag.self_closing) {
        close = xml.find("</DataArray>", tag.end);
        if (close == std::string_view::npos) return fail(Error::Parse, "a DataArray has no </DataArray>");
        pos = close + 12;
      }
      const std::string_view array_name = xml_attribute(tag.attributes, "Name");
      if (section == VtkSection::None || section == VtkSection::Other || !wanted(section, array_name)) continue;
      VtkArray a{section, std::string(array_name), {}};
      if (Status st = read_array(xml, tag, close, form, name, lines, a.values); !st.ok()) return st;
      grid.arrays.push_back(std::move(a));
    }
  }
  if (!have_grid || !have_piece)
    return Status(Error::Parse, name + ": expected a VTKFile of type UnstructuredGrid with a Piece");
  return Status::success();
}

}  // namespace anitet
