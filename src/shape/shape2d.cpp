#include "cellforge/shape/shape2d.h"

#include <algorithm>

namespace cellforge::shape {

double area(const Shape2D& shape) {
  double a = 0;
  for (const Region& r : shape.regions) a += area(r);
  return a;
}

std::vector<Vec2> points_of(const Shape2D& shape) {
  std::vector<Vec2> out;
  for (const Region& r : shape.regions)
    for (const auto& loop : r.loops) out.insert(out.end(), loop.begin(), loop.end());
  return out;
}

Box2 bounding_box(const Shape2D& shape) {
  const std::vector<Vec2> pts = points_of(shape);
  if (pts.empty()) return {};
  Box2 b{pts[0], pts[0]};
  for (Vec2 p : pts) {
    b.min = {std::min(b.min.x, p.x), std::min(b.min.y, p.y)};
    b.max = {std::max(b.max.x, p.x), std::max(b.max.y, p.y)};
  }
  return b;
}

Result<Shape2D> transformed(const Shape2D& shape, const Transform& t) {
  const auto& a = t.m;
  const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  if (det == 0 || !std::isfinite(det))
    return Error{ErrorCode::kInvalidInput,
                 "transform of a 2D shape: the xy part of the matrix is singular"};
  Shape2D out;
  out.regions.reserve(shape.regions.size());
  for (const Region& r : shape.regions) {
    Region image;
    for (const auto& loop : r.loops) {
      std::vector<Vec2> l;
      l.reserve(loop.size());
      for (Vec2 p : loop)
        l.push_back({a[0][0] * p.x + a[0][1] * p.y + a[0][3], a[1][0] * p.x + a[1][1] * p.y + a[1][3]});
      if (det < 0) std::reverse(l.begin(), l.end());
      image.loops.push_back(std::move(l));
    }
    out.regions.push_back(std::move(image));
  }
  return out;
}

}  // namespace cellforge::shape
