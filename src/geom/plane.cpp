// Exact planes (plane.h).
#include "cellforge/geom/plane.h"

namespace cellforge::inline geom {

namespace {

// sign(|a| - |b|) for exact reals.
int compare_magnitude(const Expansion& a, const Expansion& b) {
  const Expansion abs_a = a.sign() < 0 ? -a : a, abs_b = b.sign() < 0 ? -b : b;
  return (abs_a - abs_b).sign();
}

}  // namespace

int Plane::dominant_axis() const {
  const ExactVec3 n = point_normal_ ? exact(b_) : exact_cross(exact_sub(b_, a_), exact_sub(c_, a_));
  if (compare_magnitude(n.x, n.y) >= 0 && compare_magnitude(n.x, n.z) >= 0) return 0;
  return compare_magnitude(n.y, n.z) >= 0 ? 1 : 2;
}

Projection Plane::projection() const {
  const ExactVec3 n = point_normal_ ? exact(b_) : exact_cross(exact_sub(b_, a_), exact_sub(c_, a_));
  Projection p(Vec3{});
  p.drop = dominant_axis();
  const Expansion& along = p.drop == 0 ? n.x : (p.drop == 1 ? n.y : n.z);
  p.flip = along.sign() < 0;
  return p;
}

}  // namespace cellforge::inline geom
