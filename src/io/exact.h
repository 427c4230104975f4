// Filtered exact orientation tests for io/: a floating-point evaluation with
// Shewchuk's static error bounds ("Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", 1997, ccwerrboundA and o3derrboundA), falling
// back to the exact predicates of geom/predicates.h when the sign is not certain.
#pragma once

#include <cmath>

#include "cellforge/geom/predicates.h"

namespace cellforge::io {

struct Point2 {
  double u = 0, v = 0;
  friend bool operator==(const Point2&, const Point2&) = default;
};

// +1 when a, b, c turn counterclockwise, -1 clockwise, 0 on one line.
inline int orient2d(Point2 a, Point2 b, Point2 c) {
  const double l = (b.u - a.u) * (c.v - a.v), r = (b.v - a.v) * (c.u - a.u);
  const double det = l - r;
  const double bound = 3.3306690738754716e-16 * (std::fabs(l) + std::fabs(r));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  const Expansion e = (Expansion(b.u) - a.u) * (Expansion(c.v) - a.v) -
                      (Expansion(b.v) - a.v) * (Expansion(c.u) - a.u);
  return e.sign();
}

// orient3d of predicates.h (the sign of det[b - a, c - a, d - a]), filtered.
inline int orient3d_filtered(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double vw_x = v.y * w.z, wv_x = v.z * w.y;
  const double vw_y = v.z * w.x, wv_y = v.x * w.z;
  const double vw_z = v.x * w.y, wv_z = v.y * w.x;
  const double det = u.x * (vw_x - wv_x) + u.y * (vw_y - wv_y) + u.z * (vw_z - wv_z);
  const double permanent = std::fabs(u.x) * (std::fabs(vw_x) + std::fabs(wv_x)) +
                           std::fabs(u.y) * (std::fabs(vw_y) + std::fabs(wv_y)) +
                           std::fabs(u.z) * (std::fabs(vw_z) + std::fabs(wv_z));
  const double bound = 7.7715611723761027e-16 * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient3d(a, b, c, d);
}

// The coordinate plane a polygon with normal n projects onto without folding, with
// the orientation kept: seen from the side n points to, counterclockwise stays
// counterclockwise.
struct Projection {
  int drop = 2;
  bool flip = false;
  explicit Projection(Vec3 n) {
    const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    drop = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
    flip = n[drop] < 0;
  }
  Point2 operator()(Vec3 p) const {
    // Dropping x keeps (y, z), dropping y keeps (z, x), dropping z keeps (x, y):
    // each a right-handed pair about the dropped axis.
    const double a = p[(drop + 1) % 3], b = p[(drop + 2) % 3];
    return flip ? Point2{b, a} : Point2{a, b};
  }
};

}  // namespace cellforge::io
