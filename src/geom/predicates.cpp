// Filtered exact predicates. Each predicate evaluates its polynomial in doubles along
// with a bound on the rounding error, derived for exactly that sequence of operations;
// when |value| exceeds the bound the sign is certain. Otherwise it evaluates the same
// polynomial exactly in stack-allocated expansions (expansion_kernels.h), whose lengths
// are bounded at compile time, so the exact stage never allocates.
//
// Notation: eps = 2^-53, the unit roundoff of doubles; a rounded operation returns
// x (1 + delta) with |delta| <= eps. Should the compiler fuse a multiply and an add
// (-ffp-contract with FMA hardware), that only sets some delta to 0: the bounds hold.
#include "cellforge/geom/predicates.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "cellforge/geom/filtered.h"
#include "geom/expansion_kernels.h"

namespace cellforge::inline geom {

namespace {

using expansion_kernels::exact_diff;

constexpr double kEps = 0x1p-53;
// Shewchuk (1997), section 4.2: ccwerrboundA (o3derrboundA is kOrient3dErrorBound,
// predicates.h), for the computed permanents below (their own rounding included).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
// For x1 y1 + x2 y2 + x3 y3 with x_i, y_i rounded differences: each term carries at
// most 5 roundings (two differences, the product, at most two additions), so the
// error is at most g5 T with g5 = 5 eps / (1 - 5 eps) and T = sum |x_i y_i| in exact
// arithmetic. The computed permanent P >= (1 - g5) T, so the error is at most
// 5 eps / (1 - 10 eps) P < 8 eps P; and 8 eps is a power of two, so 8 eps P is exact.
constexpr double kDot3Bound = 8 * kEps;

// The sign of value when its error is at most bound, else 0 meaning "undecided";
// a decided sign is never 0, so callers fall through to the exact stage on 0.
int filtered_sign(double value, double bound) {
  if (value > bound) return 1;
  if (-value > bound) return -1;
  return 0;
}

// The exact stage's common case, points close together (neighbours on a mesh's
// lines): when the four differences are exact doubles, the determinant is the
// difference of two products p - q, each held exactly by a double and an fma
// residual. Two products that round apart differ in that order (each lies within
// half a spacing of its rounding, and a tie rounds both one way); equal roundings
// leave the residuals, whose rounded difference has the exact one's sign. Products
// that overflow or come near the subnormals (where a residual may be inexact) are
// left to the expansions (kUndecided).
constexpr int kUndecided = 2;

int orient2d_two_products(Vec2 a, Vec2 b, Vec2 c) {
  const TwoDouble ux = two_diff(b.x, a.x), vy = two_diff(c.y, a.y);
  const TwoDouble uy = two_diff(b.y, a.y), vx = two_diff(c.x, a.x);
  if (ux.lo != 0 || vy.lo != 0 || uy.lo != 0 || vx.lo != 0) return kUndecided;
  const TwoDouble p = two_product(ux.hi, vy.hi), q = two_product(uy.hi, vx.hi);
  constexpr double kTiny = 0x1p-900, kHuge = 0x1p+1000;
  const auto safe = [&](double x, double m, double n) {
    return m == 0 || n == 0 || (std::fabs(x) > kTiny && std::fabs(x) < kHuge);
  };
  if (!safe(p.hi, ux.hi, vy.hi) || !safe(q.hi, uy.hi, vx.hi)) return kUndecided;
  if (p.hi != q.hi) return p.hi > q.hi ? 1 : -1;
  return (p.lo > q.lo) - (p.lo < q.lo);
}

int orient2d_exact(Vec2 a, Vec2 b, Vec2 c) {
  const auto det =
      exact_diff(b.x, a.x) * exact_diff(c.y, a.y) - exact_diff(b.y, a.y) * exact_diff(c.x, a.x);
  return det.sign();
}

int orient3d_exact(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const auto ux = exact_diff(b.x, a.x), uy = exact_diff(b.y, a.y), uz = exact_diff(b.z, a.z);
  const auto vx = exact_diff(c.x, a.x), vy = exact_diff(c.y, a.y), vz = exact_diff(c.z, a.z);
  const auto wx = exact_diff(d.x, a.x), wy = exact_diff(d.y, a.y), wz = exact_diff(d.z, a.z);
  const auto det = ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
  return det.sign();
}

int dot_sign_exact(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const auto dot = exact_diff(b.x, a.x) * exact_diff(d.x, c.x) +
                   exact_diff(b.y, a.y) * exact_diff(d.y, c.y) +
                   exact_diff(b.z, a.z) * exact_diff(d.z, c.z);
  return dot.sign();
}

}  // namespace

int orient2d(Vec2 a, Vec2 b, Vec2 c) {
  const double left = (b.x - a.x) * (c.y - a.y);
  const double right = (b.y - a.y) * (c.x - a.x);
  const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
  const int s = filtered_sign(left - right, bound);
  if (s != 0) return s;
  // Three points on one axis-parallel line: 0 without the exact stage.
  if ((a.x == b.x && a.x == c.x) || (a.y == b.y && a.y == c.y)) return 0;
  if (const int t = orient2d_two_products(a, b, c); t != kUndecided) return t;
  return orient2d_exact(a, b, c);
}

int orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double vywz = v.y * w.z, vzwy = v.z * w.y;
  const double vzwx = v.z * w.x, vxwz = v.x * w.z;
  const double vxwy = v.x * w.y, vywx = v.y * w.x;
  const double det = u.x * (vywz - vzwy) + u.y * (vzwx - vxwz) + u.z * (vxwy - vywx);
  const double permanent = (std::fabs(vywz) + std::fabs(vzwy)) * std::fabs(u.x) +
                           (std::fabs(vzwx) + std::fabs(vxwz)) * std::fabs(u.y) +
                           (std::fabs(vxwy) + std::fabs(vywx)) * std::fabs(u.z);
  const int s = filtered_sign(det, kOrient3dErrorBound * permanent);
  if (s != 0) return s;
  // Four points with one coordinate equal (a face parallel to a coordinate plane: a
  // cap of a sphere or cylinder, a box) lie in that plane: 0 without the exact stage,
  // which the filter leaves every such case to (its bound is not zero while the
  // rounded determinant is).
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return 0;
  return orient3d_exact(a, b, c, d);
}

int orient2d_projected(Vec3 a, Vec3 b, Vec3 c, int drop_axis) {
  assert(drop_axis >= 0 && drop_axis <= 2);
  const int i = (drop_axis + 1) % 3, j = (drop_axis + 2) % 3;
  return orient2d({a[i], a[j]}, {b[i], b[j]}, {c[i], c[j]});
}

bool collinear3d(Vec3 a, Vec3 b, Vec3 c) {
  // (b - a) x (c - a) == 0, one component (one projection) at a time, the largest
  // rounded component first (picked, not sorted: a million calls a heightfield): a triangle in a plane parallel to an axis projects
  // along it to a segment, whose exact test would come first for nothing.
  const Vec3 u = b - a, v = c - a;
  const double n[3] = {std::fabs(u.y * v.z - u.z * v.y), std::fabs(u.z * v.x - u.x * v.z),
                       std::fabs(u.x * v.y - u.y * v.x)};
  const int first = n[0] >= n[1] ? (n[0] >= n[2] ? 0 : 2) : (n[1] >= n[2] ? 1 : 2);
  if (orient2d_projected(a, b, c, first) != 0) return false;
  for (int axis = 0; axis < 3; ++axis)
    if (axis != first && orient2d_projected(a, b, c, axis) != 0) return false;
  return true;
}

int dot_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 x = b - a, y = d - c;
  const double px = x.x * y.x, py = x.y * y.y, pz = x.z * y.z;
  const double bound = kDot3Bound * (std::fabs(px) + std::fabs(py) + std::fabs(pz));
  const int s = filtered_sign(px + py + pz, bound);
  return s != 0 ? s : dot_sign_exact(a, b, c, d);
}

int compare_along(Vec3 a, Vec3 b, Vec3 p, Vec3 q) { return dot_sign(a, b, p, q); }

ExactVec3 exact(Vec3 a) { return {a.x, a.y, a.z}; }

ExactVec3 exact_sub(Vec3 a, Vec3 b) {
  return {Expansion(a.x) - b.x, Expansion(a.y) - b.y, Expansion(a.z) - b.z};
}

ExactVec3 exact_cross(const ExactVec3& a, const ExactVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

Expansion exact_dot(const ExactVec3& a, const ExactVec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

Expansion exact_det3(const ExactVec3& a, const ExactVec3& b, const ExactVec3& c) {
  return exact_dot(a, exact_cross(b, c));
}

ExactVec3 exact_newell_normal(std::span<const Vec3> polygon) {
  ExactVec3 n;
  if (polygon.size() < 3) return n;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3 p = polygon[i], q = polygon[(i + 1) % polygon.size()];
    n.x += Expansion(p.y) * q.z - Expansion(p.z) * q.y;
    n.y += Expansion(p.z) * q.x - Expansion(p.x) * q.z;
    n.z += Expansion(p.x) * q.y - Expansion(p.y) * q.x;
  }
  return n;
}

namespace {

// An expansion as a filtered number (filtered.h): its components summed in doubles,
// with the bound n u sum|c| on that sum's error (recursive summation of n terms errs
// by at most gamma_(n-1) sum|c|; the bound is doubled to cover the rounding of
// sum|c| itself).
Fp filtered(const Expansion& x) {
  const auto c = x.components();
  double s = 0, a = 0;
  for (double v : c) {
    s += v;
    a += std::abs(v);
  }
  return c.size() <= 1 ? Fp(s) : Fp(s, 2 * static_cast<double>(c.size()) * kUnit * a * kGrow);
}

// The sign of a . (b x c): the filter first, the expansions when it cannot tell.
int det3_sign(const ExactVec3& a, const ExactVec3& b, const ExactVec3& c) {
  const Fp ax = filtered(a.x), ay = filtered(a.y), az = filtered(a.z);
  const Fp bx = filtered(b.x), by = filtered(b.y), bz = filtered(b.z);
  const Fp cx = filtered(c.x), cy = filtered(c.y), cz = filtered(c.z);
  const Fp d = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
  if (const int s = sign_of(d); s != kUncertain) return s;
  return exact_det3(a, b, c).sign();
}

}  // namespace

int radial_half(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& d) {
  const int s = det3_sign(t, d0, d);
  if (s != 0) return s > 0 ? 1 : 3;
  // d is in the plane of t and d0: on d0's side of t (theta 0) or the opposite (pi),
  // the sign of (t x d0) . (t x d), the filter first.
  const Fp tx = filtered(t.x), ty = filtered(t.y), tz = filtered(t.z);
  const Fp ax = filtered(d0.x), ay = filtered(d0.y), az = filtered(d0.z);
  const Fp bx = filtered(d.x), by = filtered(d.y), bz = filtered(d.z);
  const Fp u[3] = {ty * az - tz * ay, tz * ax - tx * az, tx * ay - ty * ax};
  const Fp v[3] = {ty * bz - tz * by, tz * bx - tx * bz, tx * by - ty * bx};
  if (const int side = sign_of(u[0] * v[0] + u[1] * v[1] + u[2] * v[2]); side != kUncertain)
    return side > 0 ? 0 : 2;
  return exact_dot(exact_cross(t, d0), exact_cross(t, d)).sign() > 0 ? 0 : 2;
}

bool radial_less(const ExactVec3& t, const ExactVec3& d0, const ExactVec3& di,
                 const ExactVec3& dj) {
  const int hi = radial_half(t, d0, di), hj = radial_half(t, d0, dj);
  if (hi != hj) return hi < hj;
  if (hi == 0 || hi == 2) return false;
  // Both strictly inside the same half turn: the angle from di to dj lies in
  // (-pi, pi), and it is positive iff det[t, di, dj] > 0.
  return det3_sign(t, di, dj) > 0;
}

}  // namespace cellforge::inline geom
