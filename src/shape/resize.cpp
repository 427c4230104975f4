#include "cellforge/shape/resize.h"

namespace cellforge::shape {

Result<Vec3> resize_factors(Vec3, const ResizeOptions&) {
  return Error{ErrorCode::kUnsupported, "resize: not implemented yet"};
}
Result<GroupId> resized(Model&, GroupId, const ResizeOptions&) {
  return Error{ErrorCode::kUnsupported, "resize: not implemented yet"};
}
Result<Shape2D> resized(const Shape2D&, const ResizeOptions&) {
  return Error{ErrorCode::kUnsupported, "resize: not implemented yet"};
}

}  // namespace cellforge::shape
