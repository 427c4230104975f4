// libFuzzer target for the OpenSCAD language (csg/): any input must end in a CSG tree
// or an error, within the evaluator's limits (steps, list sizes, nesting, stack),
// without touching the file system. A tree that comes out is written in its JSON form
// and read back, and must give the same JSON.
#include <cstddef>
#include <cstdint>
#include <string>

#include "cellforge/csg/evaluator.h"
#include "cellforge/csg/tree_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cellforge::csg;
  EvalOptions options;
  options.allow_files = false;
  options.use_default_library_path = false;
  options.max_steps = 200'000;
  options.max_list_size = 100'000;
  options.max_nesting = 1'000;
  options.max_stack_bytes = 64u << 20;
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto r = evaluate_text(text, "fuzz.scad", options);
  if (!r.ok()) return 0;
  const std::string json = tree_to_json(*r->root);
  if (json.size() > (1u << 20)) return 0;
  auto back = tree_from_json(json);
  if (!back.ok() || node_json(**back) != node_json(*r->root)) __builtin_trap();
  return 0;
}
