// Small helpers shared by the readers (not part of the public API).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"

namespace anitet {

// Vertex counts must leave room for an "invalid" index value.
constexpr uint64_t kMaxVertices = 0xfffffff0u;

// Adds the polygon v[0..k) as the fan (v0, vi, vi+1).
inline void add_fan(SurfaceMesh& mesh, const uint32_t* v, size_t k, int32_t label) {
  for (size_t i = 1; i + 1 < k; ++i) mesh.add_triangle(v[0], v[i], v[i + 1], label);
}
// The same, read from line `line` of a text file (SurfaceMesh::line).
inline void add_fan(SurfaceMesh& mesh, const uint32_t* v, size_t k, int32_t label, size_t line) {
  add_fan(mesh, v, k, label);
  mesh.line.resize(mesh.num_triangles(), uint32_t(std::min<size_t>(line, UINT32_MAX)));
}

// True when `count` items of at least `min_bytes` bytes each can fit in `remaining` bytes: a
// bogus count is rejected before anything is reserved for it.
inline bool fits(uint64_t count, uint64_t min_bytes, uint64_t remaining) {
  return min_bytes == 0 || count <= remaining / min_bytes + 1;
}

// Runs a reader or writer, turning an allocation failure into Error::OutOfMemory.
template <class F>
auto catch_bad_alloc(const std::string& name, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    return Status(Error::OutOfMemory, name + ": out of memory");
  } catch (const std::length_error&) {
    return Status(Error::OutOfMemory, name + ": out of memory");
  }
}

// Line numbers of increasing offsets, counted incrementally.
class LineCounter {
 public:
  explicit LineCounter(std::string_view data) : data_(data) {}
  size_t at(size_t offset) {
    if (offset < pos_) pos_ = 0, line_ = 1;
    line_ +=
        static_cast<size_t>(std::count(data_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                       data_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    pos_ = offset;
    return line_;
  }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  size_t line_ = 1;
};

inline Status bad_index(const std::string& where, const char* element, uint64_t id, uint64_t index,
                        uint64_t count, uint64_t base) {
  return Status(Error::BadIndex, where + ": " + element + " " + std::to_string(id) +
                                     " refers to vertex " + std::to_string(index) +
                                     ", but there are " + std::to_string(count) +
                                     " vertices (numbered from " + std::to_string(base) + ")");
}

}  // namespace anitet
