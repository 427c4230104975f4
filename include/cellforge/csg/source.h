// Source text and places in it: the files a build read (the script, its include<>
// and use<> files), positions as (file, line, column), and the diagnostics format
// every error and warning of the csg layer uses:
//
//   part.scad:12:7: message
//     translate([1, 2]) cube(siz = 3);
//         ^
//
// Lines and columns count from 1; a column counts bytes (a tab is one column).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cellforge::csg {

struct SourcePos {
  std::uint32_t file = 0;  // index into Sources
  std::uint32_t line = 0;  // 0: no position (built-in or generated)
  std::uint32_t column = 0;
};

struct SourceFile {
  std::string path;  // as given (what diagnostics print)
  std::string text;
};

// Every file read during one evaluation; positions refer to them by index.
class Sources {
 public:
  std::uint32_t add(std::string path, std::string text);
  const SourceFile& file(std::uint32_t index) const { return *files_[index]; }
  std::size_t size() const { return files_.size(); }

  // "path:line:col" (or "path" without a line).
  std::string where(SourcePos p) const;
  // The line of the file that p is on (without its newline).
  std::string line_text(SourcePos p) const;
  // "path:line:col: message\n  <line>\n  <caret>" (the message alone without a position).
  std::string format(SourcePos p, const std::string& message) const;

 private:
  std::vector<std::unique_ptr<SourceFile>> files_;
};

// Appends the UTF-8 encoding of code point cp (string escapes, chr()).
void append_utf8(std::string& out, std::uint32_t cp);

}  // namespace cellforge::csg
