// Implicit points: points known by their construction from explicit double points,
// never rounded, and exact predicates on them (Attene, "Indirect predicates for
// geometric constructions", 2020).
//
// A point is homogeneous, (X, Y, Z, W) with position (X/W, Y/W, Z/W):
//   explicit  p                                            (p.x, p.y, p.z, 1)
//   lpi       segment pq meets the plane through a, b, c: with n = (b - a) x (c - a),
//             dp = n.(p - a), dq = n.(q - a):   X = p (dp - dq) + (q - p) dp,  W = dp - dq
//   tpi       three planes meet, plane i through a_i, b_i, c_i with n_i = (b_i - a_i) x
//             (c_i - a_i) and d_i = n_i.a_i:    X = sum_i d_i (n_j x n_k),  W = n_1.(n_2 x n_3)
//             ((i, j, k) the cyclic orders of 1, 2, 3)
// and in a plane, (U, V, W):
//   lli       the lines through segments ab and cd meet
// W is zero exactly when the construction is degenerate (the segment parallel to the
// plane, or the planes not meeting in one point); the predicates then return 0.
//
// The polynomials are written once, as templates over the number type (filtered.h), so
// that a caller holding its own points (the Boolean's arrangement) evaluates them on
// Fp first, on Dd and on Dyadic only when the filters cannot decide. The functions at
// the end take ImplicitPoint and decide that way themselves.
//
// Conventions follow predicates.h: orient3d(a, b, c, x) = sign ((b - a) x (c - a)).(x - a);
// the projection dropping axis k keeps the coordinates (k + 1, k + 2) mod 3.
#pragma once

#include <array>
#include <cstdint>

#include "cellforge/geom/filtered.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

template <class T>
using V3 = std::array<T, 3>;

template <class T>
struct H3 {
  T c[4];  // X, Y, Z, W
};
template <class T>
struct H2 {
  T u, v, w;
};

template <class T>
V3<T> vec(Vec3 p) {
  return {T(p.x), T(p.y), T(p.z)};
}
template <class T>
V3<T> sub(const V3<T>& a, const V3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
// (b - a) x (c - a): the normal of the plane through a, b, c (not normalized).
template <class T>
V3<T> plane_normal(Vec3 a, Vec3 b, Vec3 c) {
  return cross(sub(vec<T>(b), vec<T>(a)), sub(vec<T>(c), vec<T>(a)));
}

template <class T>
H3<T> explicit_point(Vec3 p) {
  return {{T(p.x), T(p.y), T(p.z), T(1.0)}};
}

// Segment pq meets the plane through a, b, c.
template <class T>
H3<T> lpi(Vec3 p, Vec3 q, Vec3 a, Vec3 b, Vec3 c) {
  const V3<T> n = plane_normal<T>(a, b, c), A = vec<T>(a);
  const V3<T> P = vec<T>(p), Q = vec<T>(q);
  const T dp = dot(n, sub(P, A)), dq = dot(n, sub(Q, A));
  const T w = dp - dq;
  H3<T> out;
  for (int i = 0; i < 3; ++i) out.c[i] = P[i] * w + (Q[i] - P[i]) * dp;
  out.c[3] = w;
  return out;
}

// In a plane: the lines through segments ab and cd meet (at a + tau (b - a), with
// tau = cross(c - a, d - c) / cross(b - a, d - c)).
template <class T>
H2<T> lli(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const T ax(a.x), ay(a.y);
  const T dx = T(b.x) - ax, dy = T(b.y) - ay;
  const T ex = T(d.x) - T(c.x), ey = T(d.y) - T(c.y);
  const T w = dx * ey - dy * ex;
  const T n = (T(c.x) - ax) * ey - (T(c.y) - ay) * ex;
  return {ax * w + dx * n, ay * w + dy * n, w};
}

// A plane through three explicit points.
struct PlanePoints {
  Vec3 a, b, c;
};

// The three planes meet (Cramer's rule on n_i . x = d_i).
template <class T>
H3<T> tpi(const PlanePoints& p1, const PlanePoints& p2, const PlanePoints& p3) {
  const V3<T> n1 = plane_normal<T>(p1.a, p1.b, p1.c), n2 = plane_normal<T>(p2.a, p2.b, p2.c),
              n3 = plane_normal<T>(p3.a, p3.b, p3.c);
  const T d1 = dot(n1, vec<T>(p1.a)), d2 = dot(n2, vec<T>(p2.a)), d3 = dot(n3, vec<T>(p3.a));
  const V3<T> c23 = cross(n2, n3), c31 = cross(n3, n1), c12 = cross(n1, n2);
  H3<T> out;
  for (int i = 0; i < 3; ++i) out.c[i] = d1 * c23[i] + d2 * c31[i] + d3 * c12[i];
  out.c[3] = dot(n1, c23);
  return out;
}

// The polynomials of the predicates, before the signs of W are taken out: each is
// the predicate's value times W (or the product of the W's involved).

// n.(X - a W) for the plane through a, b, c: orient3d(a, b, c, x) * sign(W).
template <class T>
T plane_side_poly(Vec3 a, Vec3 b, Vec3 c, const H3<T>& x) {
  const V3<T> n = plane_normal<T>(a, b, c), A = vec<T>(a);
  return n[0] * (x.c[0] - A[0] * x.c[3]) + n[1] * (x.c[1] - A[1] * x.c[3]) +
         n[2] * (x.c[2] - A[2] * x.c[3]);
}

// x_axis Wy - y_axis Wx: the order of x and y along an axis, times sign(Wx Wy).
template <class T>
T compare_poly(const H3<T>& x, const H3<T>& y, int axis) {
  return x.c[axis] * y.c[3] - y.c[axis] * x.c[3];
}

// The projection of a homogeneous point dropping axis k.
template <class T>
H2<T> projected(const H3<T>& x, int k) {
  return {x.c[(k + 1) % 3], x.c[(k + 2) % 3], x.c[3]};
}

// det [a; b; d] of three homogeneous 2D points: orient2d(a, b, d) times the sign of
// a.w b.w d.w.
template <class T>
T orient2_poly(const H2<T>& a, const H2<T>& b, const H2<T>& d) {
  return a.u * (b.v * d.w - b.w * d.v) - a.v * (b.u * d.w - b.w * d.u) +
         a.w * (b.u * d.v - b.v * d.u);
}

// ---- Decided predicates on points given by construction.

struct ImplicitPoint {
  enum class Kind : std::uint8_t { kExplicit, kLpi, kTpi };
  Kind kind = Kind::kExplicit;
  // kExplicit: p[0]; kLpi: segment p[0] p[1], plane p[2] p[3] p[4];
  // kTpi: planes (p[0], p[1], p[2]), (p[3], p[4], p[5]), (p[6], p[7], p[8]).
  std::array<Vec3, 9> p{};

  static ImplicitPoint at(Vec3 x);
  static ImplicitPoint segment_plane(Vec3 p, Vec3 q, const PlanePoints& plane);
  static ImplicitPoint three_planes(const PlanePoints& a, const PlanePoints& b, const PlanePoints& c);

  template <class T>
  H3<T> eval() const {
    switch (kind) {
      case Kind::kExplicit:
        return explicit_point<T>(p[0]);
      case Kind::kLpi:
        return lpi<T>(p[0], p[1], p[2], p[3], p[4]);
      case Kind::kTpi:
        return tpi<T>({p[0], p[1], p[2]}, {p[3], p[4], p[5]}, {p[6], p[7], p[8]});
    }
    return {};
  }
};

// Whether the construction defines a point (W != 0), exactly.
bool is_defined(const ImplicitPoint& x);
// The position in doubles, each coordinate within a relative 2^-43 of the exact one
// (computed exactly and rounded when the double filter cannot vouch for that).
// Undefined points give NaN.
Vec3 approx(const ImplicitPoint& x);
// orient3d(a, b, c, x): the side of the plane through a, b, c that x lies on.
int orient3d(Vec3 a, Vec3 b, Vec3 c, const ImplicitPoint& x);
// orient2d of three points projected along drop_axis (the in-plane side of c against
// the line ab, for points on a plane whose normal has a nonzero drop_axis component).
int orient2d_projected(const ImplicitPoint& a, const ImplicitPoint& b, const ImplicitPoint& c,
                       int drop_axis);
// The order of x and y along an axis: sign of x_axis - y_axis.
int compare(const ImplicitPoint& x, const ImplicitPoint& y, int axis);
// The order of x and y along the direction q - p: sign of (y - x).(q - p).
int compare_along(const ImplicitPoint& x, const ImplicitPoint& y, Vec3 p, Vec3 q);
// Whether x and y are the same point, exactly.
bool same_point(const ImplicitPoint& x, const ImplicitPoint& y);

}  // namespace cellforge::inline geom
