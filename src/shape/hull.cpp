#include "cellforge/shape/hull.h"

namespace cellforge::shape {

Result<Region> convex_hull(std::span<const Vec2>) {
  return Error{ErrorCode::kUnsupported, "convex_hull: not implemented yet"};
}

Result<GroupId> convex_hull(Model&, std::span<const Vec3>, const HullOptions&) {
  return Error{ErrorCode::kUnsupported, "convex_hull: not implemented yet"};
}

std::vector<Vec3> vertex_positions(const Model& m) {
  std::vector<Vec3> out;
  out.reserve(m.num_vertices());
  for (VertexId v : m.vertices()) out.push_back(m.position(v));
  return out;
}

}  // namespace cellforge::shape
