#include "io/text.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>

namespace cellforge::io {

TextPos position_of(std::string_view text, std::size_t offset) {
  TextPos p;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.col = 1;
    } else {
      ++p.col;
    }
  }
  return p;
}

Error parse_error(std::string_view format, TextPos at, const std::string& message) {
  return Error{ErrorCode::kParse, std::string(format) + ": line " + std::to_string(at.line) + ":" +
                                      std::to_string(at.col) + ": " + message};
}

Error byte_error(std::string_view format, std::size_t offset, const std::string& message) {
  return Error{ErrorCode::kParse,
               std::string(format) + ": byte " + std::to_string(offset) + ": " + message};
}

namespace {

// Length of the valid UTF-8 sequence at s[i], or 0 if it is invalid.
std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  const unsigned char c = b(0);
  if (c < 0x80) return 1;
  std::size_t n;
  std::uint32_t cp;
  if ((c & 0xE0) == 0xC0) {
    n = 2;
    cp = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3;
    cp = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4;
    cp = c & 0x07;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (b(k) & 0x3F);
  }
  static constexpr std::uint32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

Status check_utf8(std::string_view format, std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
      continue;
    }
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[i]));
      return parse_error(format, position_of(text, i),
                         "invalid UTF-8 (byte " + std::to_string(i) + " is " + hex + ")");
    }
    i += n;
  }
  return Status::Ok();
}

std::string valid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = static_cast<unsigned char>(text[i]) < 0x80 ? 1 : utf8_length(text, i);
    if (n == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

bool is_blank(std::string_view text) {
  for (char c : text) {
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v') return false;
  }
  return true;
}

Status check_not_blank(std::string_view format, std::string_view text) {
  if (text.empty()) return byte_error(format, 0, "empty file");
  if (is_blank(text))
    return byte_error(format, 0,
                      "empty file (" + std::to_string(text.size()) + " bytes of whitespace only)");
  return Status::Ok();
}

void Tokenizer::skip_space() {
  while (i_ < text_.size()) {
    const char c = text_[i_];
    if (c == '\n') {
      ++line_;
      line_begin_ = ++i_;
      line_start_ = true;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i_;
    } else if (c == '#' && comments_) {
      while (i_ < text_.size() && text_[i_] != '\n') ++i_;
    } else if (c == '\\' && comments_ && i_ + 1 < text_.size() &&
               (text_[i_ + 1] == '\n' ||
                (text_[i_ + 1] == '\r' && i_ + 2 < text_.size() && text_[i_ + 2] == '\n'))) {
      // OBJ line continuation: the next line belongs to this one.
      i_ += text_[i_ + 1] == '\n' ? 2 : 3;
      ++line_;
      line_begin_ = i_;
    } else {
      return;
    }
  }
}

bool Tokenizer::at_end() {
  const bool was = line_start_;
  skip_space();
  const bool end = i_ >= text_.size();
  if (!end) line_start_ = was || line_start_;
  return end;
}

std::string_view Tokenizer::next() {
  line_start_ = false;
  skip_space();
  col_ = i_ - line_begin_ + 1;
  const std::size_t start = i_;
  while (i_ < text_.size()) {
    const char c = text_[i_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
    if (c == '#' && comments_) break;
    ++i_;
  }
  return text_.substr(start, i_ - start);
}

bool parse_double(std::string_view token, double& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  if (end != token.data() + token.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    // Overflow reads as infinite and underflow as (signed) zero, as strtod has it.
    const std::string copy(token);
    out = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

bool parse_int64(std::string_view token, std::int64_t& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

std::string quote(std::string_view token) {
  std::string s = "'";
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7F) {
      s += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      s += hex;
    }
  }
  if (token.size() > 40) s += "...";
  return s + "'";
}

}  // namespace cellforge::io
