// Exact geometric predicates. Interim implementation on GMP rationals (exact for
// any double input); the filtered expansion-arithmetic version replaces it with the
// same interface.
//
// Conventions:
//   orient3d(a, b, c, d) = sign det[b - a, c - a, d - a]: +1 when d lies on the side
//   that (b - a) x (c - a) points to.
//   radial_less orders directions d by their angle in [0, 2pi) from d0, rotating
//   right-handed about the axis t.
#pragma once

#include <gmpxx.h>

#include <span>

#include "cellforge/geom/vec.h"

namespace cellforge {

class Expansion {
 public:
  Expansion(double d = 0) : q_(d) {}  // NOLINT: implicit from double by design
  explicit Expansion(mpq_class q) : q_(std::move(q)) {}
  int sign() const { return sgn(q_); }
  double estimate() const { return q_.get_d(); }
  friend Expansion operator+(const Expansion& a, const Expansion& b) {
    return Expansion(mpq_class(a.q_ + b.q_));
  }
  friend Expansion operator-(const Expansion& a, const Expansion& b) {
    return Expansion(mpq_class(a.q_ - b.q_));
  }
  friend Expansion operator*(const Expansion& a, const Expansion& b) {
    return Expansion(mpq_class(a.q_ * b.q_));
  }
  friend Expansion operator-(const Expansion& a) { return Expansion(mpq_class(-a.q_)); }

 private:
  mpq_class q_;
};

struct ExactVec3 {
  Expansion x, y, z;
};

inline ExactVec3 exact(Vec3 a) { return {a.x, a.y, a.z}; }
inline ExactVec3 exact_sub(Vec3 a, Vec3 b) {
  return {Expansion(a.x) - b.x, Expansion(a.y) - b.y, Expansion(a.z) - b.z};
}
inline ExactVec3 exact_cross(const ExactVec3& a, const ExactVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Expansion exact_dot(const ExactVec3& a, const ExactVec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Expansion exact_det3(const ExactVec3& a, const ExactVec3& b, const ExactVec3& c) {
  return exact_dot(a, exact_cross(b, c));
}
// Newell normal: sum of p_i x p_(i+1), twice the vector area of the polygon.
inline ExactVec3 exact_newell_normal(std::span<const Vec3> p) {
  ExactVec3 n{0, 0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ExactVec3 c = exact_cross(exact(p[i]), exact(p[(i + 1) % p.size()]));
    n = {n.x + c.x, n.y + c.y, n.z + c.z};
  }
  return n;
}

inline int orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  return exact_det3(exact_sub(b, a), exact_sub(c, a), exact_sub(d, a)).sign();
}

// Which quarter of the turn from d0 a direction d lies in: 0 at angle 0, 1 in
// (0, pi), 2 at pi, 3 in (pi, 2pi).
inline int radial_half(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& d) {
  const int s = exact_det3(t, d0, d).sign();
  if (s != 0) return s > 0 ? 1 : 3;
  return exact_dot(exact_cross(t, d0), exact_cross(t, d)).sign() > 0 ? 0 : 2;
}

inline bool radial_less(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& di,
                        const ExactVec3& dj) {
  const int hi = radial_half(t, d0, di), hj = radial_half(t, d0, dj);
  if (hi != hj) return hi < hj;
  if (hi == 0 || hi == 2) return false;
  return exact_det3(t, di, dj).sign() > 0;
}

}  // namespace cellforge
