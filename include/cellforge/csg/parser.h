// The OpenSCAD grammar (the language of OpenSCAD 2021.01, parser.y) into ast.h's tree.
// Errors are ErrorCode::kParse with Sources::format's text: file:line:col, the line and
// a caret under the place.
#pragma once

#include <cstdint>

#include "cellforge/csg/ast.h"
#include "cellforge/result.h"

namespace cellforge::csg {

struct ParseOptions {
  // Expressions and statements nested deeper than this are an error (a bound on the
  // parser's and the evaluator's recursion on hostile input).
  int max_depth = 400;
};

// Parses sources.file(index).
Result<File> parse(const Sources& sources, std::uint32_t index, const ParseOptions& options = {});

}  // namespace cellforge::csg
