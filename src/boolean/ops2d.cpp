#include "cellforge/boolean/ops2d.h"

namespace cellforge::boolean {

using shape::Shape2D;

Result<Shape2D> evaluate_2d(std::span<const Shape2D>, const Expr&) {
  return Error{ErrorCode::kUnsupported, "2D Booleans: not implemented yet"};
}
Result<Shape2D> apply_2d(Op, std::span<const Shape2D>) {
  return Error{ErrorCode::kUnsupported, "2D Booleans: not implemented yet"};
}
Result<Shape2D> offset(const Shape2D&, const OffsetOptions&) {
  return Error{ErrorCode::kUnsupported, "offset: not implemented yet"};
}
Result<Shape2D> minkowski_2d(std::span<const Shape2D>) {
  return Error{ErrorCode::kUnsupported, "minkowski (2D): not implemented yet"};
}
Result<Shape2D> projection(const Model&, const ProjectionOptions&) {
  return Error{ErrorCode::kUnsupported, "projection: not implemented yet"};
}

}  // namespace cellforge::boolean
