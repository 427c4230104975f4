// Exact geometric predicates on double coordinates, and exact 3-vectors.
//
// Every predicate returns the sign of a polynomial in the input coordinates exactly,
// as if evaluated in real arithmetic. The double evaluation runs first with Shewchuk's
// a-priori error bound (errbound * permanent, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", 1997, section 4); only when it
// cannot decide the sign is the polynomial evaluated again in expansion arithmetic
// (expansion.h).
//
// Conventions (note the sign of orient3d):
//   orient2d(a, b, c)     = sign det[b - a, c - a]; +1 when a, b, c turn counterclockwise.
//   orient3d(a, b, c, d)  = sign det[b - a, c - a, d - a] = sign ((b - a) x (c - a)) . (d - a);
//                           +1 when d lies on the side that (b - a) x (c - a) points to,
//                           the side from which a, b, c appear counterclockwise. This is
//                           the opposite of Shewchuk's orient3d (his is det[a-d, b-d, c-d]).
//   Axis k of a Vec3 is x, y, z for k = 0, 1, 2.
//
// Exactness holds while no intermediate result overflows or underflows (nor, in the
// filters, goes subnormal): for the predicates on points (degree <= 3) that means
// nonzero coordinates of magnitude within [2^-280, 2^280]; for the radial order of
// directions built as in topo/radial.cpp (degree 8 in the coordinates) within
// [2^-80, 2^120]. Coordinates must be finite.
#pragma once

#include <cmath>
#include <span>

#include "cellforge/geom/expansion.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

// sign det[b - a, c - a]: +1 counterclockwise, -1 clockwise, 0 collinear.
int orient2d(Vec2 a, Vec2 b, Vec2 c);

// sign det[b - a, c - a, d - a]: +1 when d is on the side (b - a) x (c - a) points to,
// 0 when the four points are coplanar.
int orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d);

// Shewchuk's a-priori bound for orient3d's double evaluation, (7 + 56 eps) eps times
// the computed permanent (its own rounding included); predicates.cpp and PlaneSide.
inline constexpr double kOrient3dErrorBound = (7.0 + 56.0 * 0x1p-53) * 0x1p-53;

// The plane through a, b, c set up once for the sides of many points:
// side(d) == orient3d(a, b, c, d) for every d. The cross product (b - a) x (c - a) and
// its permanent are computed once; each point costs one dot product and the bound, and
// a point the filter leaves undecided goes to orient3d. The evaluation has the
// structure of orient3d's (each coordinate of d - a times a 2x2 minor, summed in the
// same order), so the same bound holds.
class PlaneSide {
 public:
  PlaneSide(Vec3 a, Vec3 b, Vec3 c) : a_(a), b_(b), c_(c) {
    const Vec3 u = b - a, v = c - a;
    const double uyvz = u.y * v.z, uzvy = u.z * v.y, uzvx = u.z * v.x;
    const double uxvz = u.x * v.z, uxvy = u.x * v.y, uyvx = u.y * v.x;
    n_ = {uyvz - uzvy, uzvx - uxvz, uxvy - uyvx};
    m_ = {std::fabs(uyvz) + std::fabs(uzvy), std::fabs(uzvx) + std::fabs(uxvz), std::fabs(uxvy) + std::fabs(uyvx)};
  }
  int operator()(Vec3 d) const {
    const Vec3 w = d - a_;
    const double det = w.x * n_.x + w.y * n_.y + w.z * n_.z;
    const double bound = kOrient3dErrorBound * (std::fabs(w.x) * m_.x + std::fabs(w.y) * m_.y + std::fabs(w.z) * m_.z);
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return orient3d(a_, b_, c_, d);
  }

 private:
  Vec3 a_, b_, c_, n_, m_;
};

// orient2d of the points with axis drop_axis (0, 1 or 2) removed, the two remaining
// axes taken in cyclic order (drop x: (y, z); drop y: (z, x); drop z: (x, y)). So the
// result is the sign of component drop_axis of (b - a) x (c - a), and a polygon keeps
// its orientation when projected along the dominant axis of a normal pointing +axis.
int orient2d_projected(Vec3 a, Vec3 b, Vec3 c, int drop_axis);

// True when a, b, c lie on one line (also when two or three of them coincide).
bool collinear3d(Vec3 a, Vec3 b, Vec3 c);

// sign (b - a) . (d - c).
int dot_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d);

// Order along the line direction a -> b: sign (b - a) . (q - p), so +1 when q comes after
// p going from a towards b (for p, q on the line; otherwise compares their projections).
int compare_along(Vec3 a, Vec3 b, Vec3 p, Vec3 q);

// A 3-vector of exact reals.
struct ExactVec3 {
  Expansion x, y, z;
};

ExactVec3 exact(Vec3 a);
ExactVec3 exact_sub(Vec3 a, Vec3 b);  // a - b
ExactVec3 exact_cross(const ExactVec3& a, const ExactVec3& b);
Expansion exact_dot(const ExactVec3& a, const ExactVec3& b);
Expansion exact_det3(const ExactVec3& a, const ExactVec3& b, const ExactVec3& c);  // a.(b x c)

// The Newell normal sum_i p_i x p_(i+1) (indices mod n): twice the vector area of the
// closed polygon, pointing to the side from which it runs counterclockwise. Zero for
// fewer than three points.
ExactVec3 exact_newell_normal(std::span<const Vec3> polygon);

// Radial order of directions about an axis t (e.g. the faces around an edge a -> b,
// t = b - a, each face given by a direction d leaving the edge into the face). A
// direction d is measured by the angle theta in [0, 2pi) from the reference direction
// d0 to d, both projected onto the plane perpendicular to t, turning right-handed about
// t. Only the projections matter: d and d + s t, and d and k d (k > 0), are at the
// same angle. Precondition: neither d0 nor any d is parallel to t (nor zero).
//
// radial_half tells where d lies: 0 at theta == 0, 1 for theta in (0, pi), 2 at
// theta == pi, 3 for theta in (pi, 2pi). Exactly: 1 or 3 by the sign of det[t, d0, d];
// when that is 0, 0 or 2 by the sign of (t x d0) . (t x d).
int radial_half(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& d);

// theta(di) < theta(dj): a strict weak order; directions at equal angles are
// equivalent (neither is less).
bool radial_less(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& di, const ExactVec3& dj);

}  // namespace cellforge::inline geom
