// Planes kept exactly as they were given: through three points, or through a point
// with a normal vector. Nothing is rounded, so side() is an exact predicate on the
// input doubles (orient3d, or the sign of a dot product), and a plane can be compared
// with the points that made it.
#pragma once

#include "cellforge/geom/polygon.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

class Plane {
 public:
  // The plane of a, b, c with normal (b - a) x (c - a): a, b, c run counterclockwise
  // seen from the side it points to. Degenerate when the points are collinear.
  static Plane through(Vec3 a, Vec3 b, Vec3 c) { return Plane(a, b, c, false); }
  // The plane through p with normal n. Degenerate when n is zero.
  static Plane from_point_normal(Vec3 p, Vec3 n) { return Plane(p, n, {}, true); }

  // +1 when q lies on the side the normal points to, -1 behind, 0 on the plane; exact.
  // A degenerate plane gives 0 for every point.
  int side(Vec3 q) const {
    return point_normal_ ? dot_sign({}, b_, a_, q) : orient3d(a_, b_, c_, q);
  }
  bool contains(Vec3 q) const { return side(q) == 0; }
  bool is_degenerate() const {
    return point_normal_ ? b_ == Vec3{} : collinear3d(a_, b_, c_);
  }

  // The normal, rounded to doubles (exact for the point-normal form).
  Vec3 normal() const { return point_normal_ ? b_ : cross(b_ - a_, c_ - a_); }
  // The axis (0, 1, 2) of the normal's largest component in magnitude, decided exactly
  // (ties to the lower axis), and the projection that drops it (polygon.h).
  int dominant_axis() const;
  Projection projection() const;

 private:
  Plane(Vec3 a, Vec3 b, Vec3 c, bool point_normal)
      : a_(a), b_(b), c_(c), point_normal_(point_normal) {}
  Vec3 a_, b_, c_;  // three points, or the point (a_) and the normal (b_)
  bool point_normal_;
};

}  // namespace cellforge::inline geom
