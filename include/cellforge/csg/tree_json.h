// The JSON form of a CSG tree (docs/csg.md), for programs that make trees without
// the OpenSCAD language; `cellforge build` reads it, `--tree` writes it.
//
//   {"cellforge_csg": 1, "root": {"type": "difference", "children": [
//       {"type": "cube", "size": [10, 10, 10], "center": true},
//       {"type": "cylinder", "h": 12, "r1": 3, "r2": 3, "center": true, "fn": 32}]}}
//
// Every node is an object with "type" (tree.h's node names) and its parameters under
// OpenSCAD's names; absent parameters take OpenSCAD's defaults. Numbers are written
// as the shortest text that reads back as the same double.
#pragma once

#include <string>
#include <string_view>

#include "cellforge/csg/tree.h"
#include "cellforge/result.h"

namespace cellforge::csg {

std::string tree_to_json(const Node& root);
// One node as JSON, without source positions (what content_key digests).
std::string node_json(const Node& node);
// Errors (kParse) give the byte offset and what was expected.
Result<NodePtr> tree_from_json(std::string_view text);

}  // namespace cellforge::csg
