// Helpers shared by the text parsers (ASCII STL, OBJ, OFF, JSON): UTF-8 checking,
// a whitespace tokenizer that knows line and column, number parsing, and errors
// that name the position ("obj: line 4:9: ...").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "cellforge/result.h"

namespace cellforge::io {

struct TextPos {
  std::size_t line = 1, col = 1;  // 1-based; col counts bytes
};

// The line:col of byte `offset` of `text`.
TextPos position_of(std::string_view text, std::size_t offset);

Error parse_error(std::string_view format, TextPos at, const std::string& message);
Error byte_error(std::string_view format, std::size_t offset, const std::string& message);

// An error naming the first byte that is not part of valid UTF-8 (overlong forms,
// surrogates and code points above U+10FFFF are invalid), or Ok.
Status check_utf8(std::string_view format, std::string_view text);

// The text with each byte that is not part of valid UTF-8 replaced by U+FFFD.
std::string valid_utf8(std::string_view text);
// Whether the text is only whitespace (or nothing).
bool is_blank(std::string_view text);
// The one rule for empty input in every format: a file of no bytes, or of
// whitespace only, is an error "byte 0: empty file". A file with content but no
// geometry (comments only, zero counts) is a model without entities.
Status check_not_blank(std::string_view format, std::string_view text);

// Whitespace-separated tokens with their positions. `#` comments are skipped when
// `hash_comments` is set.
class Tokenizer {
 public:
  Tokenizer(std::string_view text, bool hash_comments) : text_(text), comments_(hash_comments) {}

  // The next token, or an empty view at the end of the text. `line_start` tells
  // whether a newline came between the previous token and this one.
  std::string_view next();
  bool line_start() const { return line_start_; }
  TextPos pos() const { return {line_, col_}; }  // of the token last returned
  bool at_end();

 private:
  void skip_space();
  std::string_view text_;
  bool comments_;
  std::size_t i_ = 0;
  std::size_t line_ = 1, line_begin_ = 0, col_ = 1;
  bool line_start_ = true;
};

// Parses the whole token as a number; false if it is not one (or has trailing
// characters). A number that parses but is NaN or infinite is returned as such;
// callers reject it with their own message.
bool parse_double(std::string_view token, double& out);
bool parse_int64(std::string_view token, std::int64_t& out);

// "'tok'" clipped to 40 bytes, with non-printable bytes as \xNN.
std::string quote(std::string_view token);

}  // namespace cellforge::io
