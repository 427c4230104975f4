#include "cellforge/boolean/minkowski.h"

namespace cellforge::boolean {

Result<Model> minkowski(std::span<const Model* const>) {
  return Error{ErrorCode::kUnsupported, "minkowski: not implemented yet"};
}
bool is_convex_cell(const Model&, VolumeId) { return false; }

}  // namespace cellforge::boolean
