#include "cellforge/csg/source.h"

namespace cellforge::csg {

std::uint32_t Sources::add(std::string path, std::string text) {
  files_.push_back(std::make_unique<SourceFile>(SourceFile{std::move(path), std::move(text)}));
  return static_cast<std::uint32_t>(files_.size() - 1);
}

std::string Sources::where(SourcePos p) const {
  if (p.file >= files_.size()) return "<unknown>";
  std::string s = files_[p.file]->path;
  if (p.line == 0) return s;
  return s + ":" + std::to_string(p.line) + ":" + std::to_string(p.column);
}

std::string Sources::line_text(SourcePos p) const {
  if (p.file >= files_.size() || p.line == 0) return {};
  const std::string& t = files_[p.file]->text;
  std::size_t start = 0;
  for (std::uint32_t l = 1; l < p.line; ++l) {
    start = t.find('\n', start);
    if (start == std::string::npos) return {};
    ++start;
  }
  std::size_t end = t.find('\n', start);
  if (end == std::string::npos) end = t.size();
  std::string line = t.substr(start, end - start);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

std::string Sources::format(SourcePos p, const std::string& message) const {
  if (p.file >= files_.size()) return message;
  if (p.line == 0) return files_[p.file]->path + ": " + message;
  std::string out = where(p) + ": " + message;
  const std::string line = line_text(p);
  if (line.empty() && p.column <= 1) return out;
  out += "\n  " + line + "\n  ";
  // The caret keeps the tabs of the line before it so that it lines up.
  for (std::uint32_t c = 1; c < p.column && c - 1 < line.size(); ++c)
    out += line[c - 1] == '\t' ? '\t' : ' ';
  out += '^';
  return out;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

}  // namespace cellforge::csg
