// A canonical text dump of a model, independent of id assignment and free lists:
// two models that describe the same topology and geometry dump identically.
// Used by tests (apply an operator and its inverse, compare) and by round trips.
#pragma once

#include <string>

#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

std::string canonical_dump(const Model& m);
// A dump that shows ids as they are (for debugging and error messages).
std::string raw_dump(const Model& m);

}  // namespace cellforge::inline topo
