// A fast tokenizer over text held in memory (no iostreams): whitespace-separated tokens,
// line counting for messages, optional comment character, std::from_chars numbers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/status.hpp"

namespace anitet {

class TextScanner {
 public:
  // `name` is used in messages ("name:line: ..."); `comment` starts a comment running to the end
  // of the line when it begins a token ('\0' for none).
  // `first_line` numbers the first line of `text` (when it starts inside a file).
  TextScanner(std::string_view text, const std::string& name, char comment = '#',
              size_t first_line = 1);

  // Skips whitespace, line breaks and comments; false when nothing is left.
  bool skip_space();
  // Skips blanks and a trailing comment but not the line break; false at the end of the line.
  bool skip_space_in_line();
  // Moves past the next line break (or to the end).
  void skip_line();

  // The next token, possibly on a later line ("" at the end of the text).
  std::string_view next_token();
  // The next token on the current line ("" at the end of the line).
  std::string_view token_in_line();
  // The next token without consuming it (may advance over whitespace and comments).
  std::string_view peek_token();
  // The rest of the current line without the comment and outer blanks; moves to the next line.
  std::string_view rest_of_line();

  // Numbers: the whole next token must be a number. The *_in_line forms stay on this line.
  bool read_double(double& out);
  bool read_double_in_line(double& out);
  bool read_int(int64_t& out);
  bool read_int_in_line(int64_t& out);
  // A count in [0, max]; fails on negative or larger values.
  bool read_count(uint64_t max, uint64_t& out);
  // The next token must be `keyword` (ASCII case-insensitive).
  bool read_keyword(std::string_view keyword);

  bool at_end() const { return pos_ == end_; }
  size_t line() const { return line_; }
  size_t remaining() const { return static_cast<size_t>(end_ - pos_); }
  size_t offset() const { return static_cast<size_t>(pos_ - begin_); }
  const std::string& name() const { return name_; }

  // "name:line: message".
  Status error(Error code, const std::string& message) const;
  // Error::Parse "name:line: expected <what>, found '<token>'": the token a failed read_* call
  // rejected, else the next one ("end of file" / "end of line" when there is none).
  Status expected(const std::string& what);

 private:
  const char* begin_;
  const char* pos_;
  const char* end_;
  size_t line_ = 1;
  std::string name_;
  char comment_;
  bool read_failed_ = false;  // the last read_* call failed on rejected_
  std::string_view rejected_;

  bool note(bool ok, std::string_view token);
};

// Number parsing of a whole token (leading '+' allowed; inf/nan accepted; out-of-range doubles
// become +-inf or 0 as strtod would give).
bool parse_double(std::string_view token, double& out);
bool parse_int(std::string_view token, int64_t& out);

// Case-insensitive ASCII comparison.
bool iequals(std::string_view a, std::string_view b);

// A token shortened and made printable for messages.
std::string quote_token(std::string_view token);

}  // namespace anitet
