// resize(): OpenSCAD's scale factors (resize.h) and the scaling through transformed().
#include "cellforge/shape/resize.h"

#include <cmath>
#include <string>

#include "cellforge/shape/mass.h"

namespace cellforge::shape {

namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

Result<Vec3> factors(Vec3 current, const ResizeOptions& o, int axes) {
  double s[3] = {1, 1, 1};
  for (int i = 0; i < axes; ++i) {
    const double want = o.size[i];
    if (!std::isfinite(want) || want < 0)
      return Error{ErrorCode::kInvalidInput, std::string("resize: new size along ") + kAxis[i] +
                                                 " is " + format_number(want) +
                                                 " (must be finite and not negative)"};
    if (want == 0) continue;
    if (current[i] == 0)
      return Error{ErrorCode::kInvalidInput,
                   std::string("resize: the object is flat along ") + kAxis[i] +
                       " (resize in the direction normal to a flat object is not implemented)"};
    s[i] = want / current[i];
  }
  int largest = 0;  // the axis with the largest new size, the first on ties
  for (int i = 1; i < axes; ++i)
    if (o.size[i] > o.size[largest]) largest = i;
  const double autoscale = s[largest];  // 1 when no new size is given
  for (int i = 0; i < axes; ++i)
    if (o.autosize[static_cast<std::size_t>(i)] && o.size[i] == 0) s[i] = autoscale;
  return Vec3{s[0], s[1], s[2]};
}

}  // namespace

Result<Vec3> resize_factors(Vec3 current, const ResizeOptions& options) {
  return factors(current, options, 3);
}

Result<GroupId> resized(Model& m, GroupId g, const ResizeOptions& options) {
  const MassProperties p = mass_properties(m, g);
  Result<Vec3> s = factors(p.bbox_max - p.bbox_min, options, 3);
  if (!s) return s.error();
  return transformed(m, g, Transform::scale(*s));
}

Result<Shape2D> resized(const Shape2D& shape, const ResizeOptions& options) {
  const Box2 b = bounding_box(shape);
  Result<Vec3> s = factors({b.max.x - b.min.x, b.max.y - b.min.y, 0}, options, 2);
  if (!s) return s.error();
  return transformed(shape, Transform::scale({s->x, s->y, 1}));
}

}  // namespace cellforge::shape
