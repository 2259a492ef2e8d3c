// Bounds-checked reads of binary data held in memory; messages name the byte offset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include "core/status.hpp"

namespace anitet {

class ByteReader {
 public:
  ByteReader(std::string_view data, std::string name, size_t start = 0)
      : data_(data), pos_(start < data.size() ? start : data.size()), name_(std::move(name)) {}

  size_t offset() const { return pos_; }
  size_t remaining() const { return data_.size() - pos_; }
  const std::string& name() const { return name_; }

  bool skip(size_t n) {
    if (n > remaining()) return false;
    pos_ += n;
    return true;
  }

  // A little-endian value (byte-swapped when `big_endian`); false when the data ends first.
  template <class T>
  bool read(T& out, bool big_endian = false) {
    if (sizeof(T) > remaining()) return false;
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (big_endian) {
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    std::memcpy(&out, bytes, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }

  // "name: byte offset N: message".
  Status error(Error code, const std::string& message) const {
    return Status(code, name_ + ": byte offset " + std::to_string(pos_) + ": " + message);
  }

 private:
  std::string_view data_;
  size_t pos_;
  std::string name_;
};

}  // namespace anitet
