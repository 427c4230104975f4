// Runs an OpenSCAD script with OpenSCAD's semantics and gives its CSG tree (tree.h).
//
// Values, operators and scoping are OpenSCAD's: in each scope the module and function
// definitions and then the assignments are taken first (the last assignment of a name
// wins, at the place of the first), then the module instantiations in order; $
// variables are looked up along the calls (dynamic scope). Function calls in tail
// position (the branches of ?:, the body of let, assert and echo) reuse the frame, so
// tail recursion runs in constant stack. echo() lines are in OpenSCAD's format
// ("ECHO: 1, \"a\", x = [1, 2]"); warnings (an unknown variable is undef, as OpenSCAD
// does) and errors are "file:line:col: message" with the source line and a caret.
//
// Limits, each an error rather than a crash: evaluation steps (max_steps), the stack
// a deep non-tail recursion may take (max_stack_bytes; the evaluation runs on a thread
// with a stack of that size), list and range sizes (max_list_size), and vector
// nesting (max_nesting).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/csg/source.h"
#include "cellforge/csg/tree.h"
#include "cellforge/result.h"

namespace cellforge::csg {

struct EvalOptions {
  // -D name=value: value is an expression, as for `openscad -D`; it overrides the
  // script's top-level assignment of that name.
  std::vector<std::pair<std::string, std::string>> defines;
  // Folders searched for include<> and use<> after the including file's folder. Empty:
  // OPENSCADPATH (':'-separated), then /usr/share/openscad/libraries.
  std::vector<std::string> library_path;
  bool use_default_library_path = true;
  // Called with each echo line ("ECHO: ...") and each warning; null: collected only.
  std::function<void(const std::string&)> on_echo;
  std::function<void(const std::string&)> on_warning;
  std::uint64_t max_steps = 2'000'000'000;
  std::size_t max_stack_bytes = 512u << 20;
  std::size_t max_list_size = 50'000'000;
  std::uint32_t max_nesting = 10'000;
  // Allow reading files (include<>, use<>, import()); off for fuzzing.
  bool allow_files = true;
  double t = 0;          // $t
  bool preview = false;  // $preview
};

struct EvalOutput {
  NodePtr root;  // a kGroup of the top-level objects (or the '!' subtree)
  std::vector<std::string> echoes;
  std::vector<std::string> warnings;
  std::shared_ptr<Sources> sources;  // the files read, for messages about the tree
};

// Evaluates the script at `path`. Errors: kIo when the file cannot be read, kParse for
// syntax, kInvalidInput for evaluation (a failed assert, a wrong argument, a limit).
Result<EvalOutput> evaluate_file(const std::string& path, const EvalOptions& options = {});
// The same for script text; `name` is what messages call it (include<> resolves
// against its folder).
Result<EvalOutput> evaluate_text(const std::string& text, const std::string& name,
                                 const EvalOptions& options = {});

}  // namespace cellforge::csg
