// Appending numbers to text output. Doubles use the shortest form that reads back to the same
// bits (std::to_chars), so every written coordinate round-trips exactly.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>

namespace anitet {

inline void append_double(std::string& out, double v) {
  char buf[32];
  auto result = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, result.ptr);
}

inline void append_int(std::string& out, int64_t v) {
  char buf[24];
  auto result = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, result.ptr);
}

// Appends the values separated by single spaces, then a line break.
template <class... T>
void append_line(std::string& out, T... values);

inline void append_value(std::string& out, double v) { append_double(out, v); }
inline void append_value(std::string& out, int64_t v) { append_int(out, v); }
inline void append_value(std::string& out, int32_t v) { append_int(out, v); }
inline void append_value(std::string& out, uint32_t v) { append_int(out, v); }
inline void append_value(std::string& out, uint64_t v) { append_int(out, static_cast<int64_t>(v)); }

template <class... T>
void append_line(std::string& out, T... values) {
  bool first = true;
  ((out += first ? "" : " ", first = false, append_value(out, values)), ...);
  out += '\n';
}

}  // namespace anitet
