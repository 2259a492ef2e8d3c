#include "io/text_scanner.hpp"

#include <charconv>
#include <cstdlib>
#include <cstring>

namespace anitet {

namespace {

inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
inline bool is_space(char c) { return is_blank(c) || c == '\n'; }

}  // namespace

TextScanner::TextScanner(std::string_view text, const std::string& name, char comment,
                         size_t first_line)
    : begin_(text.data()),
      pos_(text.data()),
      end_(text.data() + text.size()),
      line_(first_line),
      name_(name),
      comment_(comment) {}

bool TextScanner::skip_space() {
  while (pos_ != end_) {
    char c = *pos_;
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_blank(c)) {
      ++pos_;
    } else if (c == comment_ && comment_ != '\0') {
      const void* nl = std::memchr(pos_, '\n', static_cast<size_t>(end_ - pos_));
      pos_ = nl ? static_cast<const char*>(nl) : end_;
    } else {
      return true;
    }
  }
  return false;
}

bool TextScanner::skip_space_in_line() {
  while (pos_ != end_ && is_blank(*pos_)) ++pos_;
  if (pos_ != end_ && *pos_ == comment_ && comment_ != '\0') {
    const void* nl = std::memchr(pos_, '\n', static_cast<size_t>(end_ - pos_));
    pos_ = nl ? static_cast<const char*>(nl) : end_;
  }
  return pos_ != end_ && *pos_ != '\n';
}

void TextScanner::skip_line() {
  const void* nl = std::memchr(pos_, '\n', static_cast<size_t>(end_ - pos_));
  if (nl) {
    pos_ = static_cast<const char*>(nl) + 1;
    ++line_;
  } else {
    pos_ = end_;
  }
}

std::string_view TextScanner::next_token() {
  if (!skip_space()) return {};
  const char* start = pos_;
  while (pos_ != end_ && !is_space(*pos_)) ++pos_;
  return std::string_view(start, static_cast<size_t>(pos_ - start));
}

std::string_view TextScanner::token_in_line() {
  if (!skip_space_in_line()) return {};
  const char* start = pos_;
  while (pos_ != end_ && !is_space(*pos_)) ++pos_;
  return std::string_view(start, static_cast<size_t>(pos_ - start));
}

std::string_view TextScanner::peek_token() {
  if (!skip_space()) return {};
  const char* stop = pos_;
  while (stop != end_ && !is_space(*stop)) ++stop;
  return std::string_view(pos_, static_cast<size_t>(stop - pos_));
}

std::string_view TextScanner::rest_of_line() {
  skip_space_in_line();
  const char* start = pos_;
  const char* stop = pos_;
  while (stop != end_ && *stop != '\n' && !(*stop == comment_ && comment_ != '\0')) ++stop;
  const char* trimmed = stop;
  while (trimmed != start && is_blank(trimmed[-1])) --trimmed;
  pos_ = stop;
  skip_line();
  return std::string_view(start, static_cast<size_t>(trimmed - start));
}

bool TextScanner::note(bool ok, std::string_view token) {
  read_failed_ = !ok;
  rejected_ = token;
  return ok;
}

bool TextScanner::read_double(double& out) {
  std::string_view token = next_token();
  return note(parse_double(token, out), token);
}
bool TextScanner::read_double_in_line(double& out) {
  std::string_view token = token_in_line();
  return note(parse_double(token, out), token);
}
bool TextScanner::read_int(int64_t& out) {
  std::string_view token = next_token();
  return note(parse_int(token, out), token);
}
bool TextScanner::read_int_in_line(int64_t& out) {
  std::string_view token = token_in_line();
  return note(parse_int(token, out), token);
}

bool TextScanner::read_count(uint64_t max, uint64_t& out) {
  std::string_view token = next_token();
  int64_t value = 0;
  bool ok = parse_int(token, value) && value >= 0 && static_cast<uint64_t>(value) <= max;
  if (ok) out = static_cast<uint64_t>(value);
  return note(ok, token);
}

bool TextScanner::read_keyword(std::string_view keyword) {
  std::string_view token = next_token();
  return note(iequals(token, keyword), token);
}

Status TextScanner::error(Error code, const std::string& message) const {
  return Status(code, name_ + ":" + std::to_string(line_) + ": " + message);
}

Status TextScanner::expected(const std::string& what) {
  std::string_view token = read_failed_ ? rejected_ : peek_token();
  std::string found = !token.empty() ? "'" + quote_token(token) + "'"
                      : pos_ == end_ ? std::string("end of file")
                                     : std::string("end of line");
  read_failed_ = false;
  return error(Error::Parse, "expected " + what + ", found " + found);
}

namespace {

// The digits of a number token: std::from_chars takes no leading '+', so it is skipped here
// ("+-1" and a lone "+" are refused). False for an empty or malformed token.
bool number_span(std::string_view token, const char*& first, const char*& last) {
  if (token.empty()) return false;
  first = token.data();
  last = first + token.size();
  if (*first == '+') {
    ++first;
    if (first == last || *first == '-') return false;
  }
  return true;
}

}  // namespace

bool parse_double(std::string_view token, double& out) {
  const char *first, *last;
  if (!number_span(token, first, last)) return false;
  auto [ptr, ec] = std::from_chars(first, last, out);
  if (ptr != last) return false;
  if (ec == std::errc()) return true;
  if (ec != std::errc::result_out_of_range) return false;
  // Overflow or underflow: strtod gives +-HUGE_VAL or the nearest denormal/zero.
  std::string copy(first, last);
  out = std::strtod(copy.c_str(), nullptr);
  return true;
}

bool parse_int(std::string_view token, int64_t& out) {
  const char *first, *last;
  if (!number_span(token, first, last)) return false;
  auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

std::string quote_token(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out;
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (token.size() > kMax) out += "...";
  return out;
}

}  // namespace anitet
