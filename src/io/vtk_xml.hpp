// The XML of VTK's UnstructuredGrid files (.vtu, and the pieces a .pvtu names): tags, attributes,
// and the DataArrays in every form VTK and meshio write them: ascii; binary (base64 inside the
// tag); appended (raw or base64, after the XML); each binary array zlib-compressed or not, with
// UInt32 or UInt64 headers, little-endian. Values are read as doubles (exact for integers below
// 2^53), whatever their type.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.hpp"

namespace anitet {

struct XmlTag {
  std::string_view name;
  std::string_view attributes;
  bool closing = false;
  bool self_closing = false;
  size_t end = 0;  // offset after '>'
};

// The next element tag at or after `pos`, skipping <?...?>, <!--...--> and <!...>.
bool next_xml_tag(std::string_view data, size_t pos, XmlTag& tag);
// The value of attribute `key` in a tag's attributes ("" when absent).
std::string_view xml_attribute(std::string_view attributes, std::string_view key);

enum class VtkSection { None, Points, Cells, PointData, CellData, Other };

struct VtkArray {
  VtkSection section = VtkSection::None;
  std::string name;
  std::vector<double> values;
};

struct VtkGrid {
  uint64_t num_points = 0, num_cells = 0;  // of the one Piece
  std::vector<VtkArray> arrays;            // the wanted ones, in file order
  // The first wanted array `name` of `section` (nullptr when there is none).
  const VtkArray* find(VtkSection section, std::string_view name) const;
};

// Which arrays to decode (the others are skipped unread).
using VtkWanted = bool (*)(VtkSection section, std::string_view name);

// The one Piece of a VTKFile of type UnstructuredGrid in `data` (`name` in messages), with its
// wanted arrays. Error::UnsupportedFormat for what VTK allows but this does not read (several
// pieces, big-endian, compressors other than zlib), Error::Parse for malformed data.
Status read_vtk_grid(std::string_view data, const std::string& name, VtkWanted wanted, VtkGrid& grid);

}  // namespace anitet
