// Segment and triangle intersection tests (intersect.h). In space, a segment meets a
// triangle when its ends are not strictly on one side of the triangle's plane and the
// segment's line passes through the closed triangle (the three orient3d signs of the
// line against the triangle's edges agree); a segment in the triangle's plane, and
// triangles in one plane, are decided in the projection along the dominant axis of
// the normal (polygon.h), which keeps incidences because it is a linear bijection of
// the plane.
#include "cellforge/geom/intersect.h"

#include <algorithm>
#include <utility>

#include "cellforge/geom/polygon.h"

namespace cellforge::inline geom {

namespace {

// p within the bounding box of ab: on the segment, given that a, b, p are collinear.
bool in_box(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

bool same_strict_side(const int s[3]) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

// The normal of a triangle, for the choice of projection only: any plane the triangle
// does not project to a line will do, so the rounded direction is enough.
Vec3 projection_normal(const Vec3 t[3]) { return cross(t[1] - t[0], t[2] - t[0]); }

}  // namespace

bool point_on_segment(Vec2 a, Vec2 b, Vec2 p) { return orient2d(a, b, p) == 0 && in_box(a, b, p); }

bool segments_meet(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && in_box(a, b, c)) || (o2 == 0 && in_box(a, b, d)) ||
         (o3 == 0 && in_box(c, d, a)) || (o4 == 0 && in_box(c, d, b));
}

bool edges_fold_back(Vec2 a, Vec2 b, Vec2 c) {
  if (orient2d(a, b, c) != 0) return false;
  const auto lift = [](Vec2 p) { return Vec3{p.x, p.y, 0}; };
  return dot_sign(lift(a), lift(b), lift(b), lift(c)) < 0 || point_on_segment(a, b, c) ||
         point_on_segment(b, c, a);
}

bool point_in_triangle(const Vec2 t[3], Vec2 p) {
  const int a = orient2d(t[0], t[1], p), b = orient2d(t[1], t[2], p), c = orient2d(t[2], t[0], p);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

bool triangles_meet(const Vec2 a[3], const Vec2 b[3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_meet(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return point_in_triangle(a, b[0]) || point_in_triangle(b, a[0]);
}

namespace {

// segment_meets_triangle with the sides of p and q of t's plane already known.
bool segment_meets_triangle(Vec3 p, Vec3 q, const Vec3 t[3], int s1, int s2) {
  if (s1 == s2 && s1 != 0) return false;
  if (s1 == 0 && s2 == 0) {  // the segment lies in t's plane
    const Projection proj(projection_normal(t));
    const Vec2 tt[3] = {proj(t[0]), proj(t[1]), proj(t[2])};
    const Vec2 pp = proj(p), qq = proj(q);
    for (int j = 0; j < 3; ++j)
      if (segments_meet(pp, qq, tt[j], tt[(j + 1) % 3])) return true;
    return point_in_triangle(tt, pp);
  }
  const int s[3] = {orient3d(p, q, t[0], t[1]), orient3d(p, q, t[1], t[2]),
                    orient3d(p, q, t[2], t[0])};
  return (s[0] >= 0 && s[1] >= 0 && s[2] >= 0) || (s[0] <= 0 && s[1] <= 0 && s[2] <= 0);
}

}  // namespace

bool segment_meets_triangle(Vec3 p, Vec3 q, const Vec3 t[3]) {
  return segment_meets_triangle(p, q, t, orient3d(t[0], t[1], t[2], p), orient3d(t[0], t[1], t[2], q));
}

bool straddling_triangles_apart(const Vec3 a[3], const Vec3 b[3], const int sa[3], const int sb[3]) {
  // p1: a's corner alone on its side of b's plane, q1: b's alone on its side of a's.
  // Each triangle's other two corners are ordered so that p1 and q1 lie on the
  // positive sides (swapping two corners turns a plane over); then the traces are
  // apart exactly when q1's edges pass p1's on the line (a positive orientation).
  auto alone = [](const int s[3]) { return s[0] == s[1] ? 2 : (s[0] == s[2] ? 1 : 0); };
  const int i = alone(sa), j = alone(sb);
  Vec3 p1 = a[i], p2 = a[(i + 1) % 3], p3 = a[(i + 2) % 3];
  Vec3 q1 = b[j], q2 = b[(j + 1) % 3], q3 = b[(j + 2) % 3];
  if (sa[i] < 0) std::swap(q2, q3);
  if (sb[j] < 0) std::swap(p2, p3);
  return orient3d(p1, p2, q1, q2) > 0 || orient3d(p1, p3, q3, q1) > 0;
}

namespace {

// Triangle a lies in the plane x_k = c exactly and b has no corner on the far side of
// it (every corner with x_k >= c, or every one <= c): then they meet only where b's
// corners on the plane (none, one, an edge) meet a, decided in the plane with axis k
// dropped, which keeps incidences. Returns -1 when that does not apply.
int meet_on_axis_plane(const Vec3 a[3], const Vec3 b[3]) {
  for (int k = 0; k < 3; ++k) {
    const double c = a[0][k];
    if (a[1][k] != c || a[2][k] != c) continue;
    int above = 0, below = 0, on = 0;
    Vec3 at[3];
    for (int i = 0; i < 3; ++i) {
      if (b[i][k] > c) ++above;
      else if (b[i][k] < c) ++below;
      else at[on++] = b[i];
    }
    if (above > 0 && below > 0) return -1;  // b crosses the plane
    if (on == 3) return -1;                 // coplanar: the general test
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const auto flat = [&](Vec3 p) { return Vec2{p[i], p[j]}; };
    const Vec2 t[3] = {flat(a[0]), flat(a[1]), flat(a[2])};
    if (orient2d(t[0], t[1], t[2]) == 0) return -1;  // a degenerate
    if (on == 0) return 0;
    if (on == 1) return point_in_triangle(t, flat(at[0])) ? 1 : 0;
    const Vec2 p = flat(at[0]), q = flat(at[1]);
    for (int e = 0; e < 3; ++e)
      if (segments_meet(p, q, t[e], t[(e + 1) % 3])) return 1;
    return point_in_triangle(t, p) ? 1 : 0;
  }
  return -1;
}

}  // namespace

bool triangles_meet(const Vec3 a[3], const Vec3 b[3]) {
  // Faces in an axis plane (a box, a plate, a cap) against what rests on them: no
  // orientation in space needed.
  if (const int m = meet_on_axis_plane(a, b); m >= 0) return m == 1;
  if (const int m = meet_on_axis_plane(b, a); m >= 0) return m == 1;
  int sb[3], sa[3];
  const PlaneSide plane_a(a[0], a[1], a[2]);
  for (int i = 0; i < 3; ++i) sb[i] = plane_a(b[i]);
  if (same_strict_side(sb)) return false;
  const PlaneSide plane_b(b[0], b[1], b[2]);
  for (int i = 0; i < 3; ++i) sa[i] = plane_b(a[i]);
  if (same_strict_side(sa)) return false;
  const bool b_on_a = sb[0] == 0 && sb[1] == 0 && sb[2] == 0;
  const bool a_on_b = sa[0] == 0 && sa[1] == 0 && sa[2] == 0;
  if (b_on_a && a_on_b) {
    const Vec3 n = projection_normal(a);
    if (n == Vec3{}) return false;
    const Projection proj(n);
    const Vec2 pa[3] = {proj(a[0]), proj(a[1]), proj(a[2])};
    const Vec2 pb[3] = {proj(b[0]), proj(b[1]), proj(b[2])};
    return triangles_meet(pa, pb);
  }
  // Every corner of one on the other's "plane" while the other's are not all on the
  // first's: the first is a triangle, the other is degenerate (three corners on a
  // line, so every point is on its plane): a segment or a point, meeting the
  // triangle where one of its edges does.
  if (b_on_a || a_on_b) {
    const Vec3* seg = a_on_b ? b : a;
    const Vec3* tri = a_on_b ? a : b;
    const int* s = a_on_b ? sb : sa;
    for (int i = 0; i < 3; ++i)
      if (segment_meets_triangle(seg[i], seg[(i + 1) % 3], tri, s[i], s[(i + 1) % 3])) return true;
    return false;
  }
  const bool strict = sa[0] * sa[1] * sa[2] != 0 && sb[0] * sb[1] * sb[2] != 0;
  if (strict) return !straddling_triangles_apart(a, b, sa, sb);
  // Each edge against the other triangle, with its ends' sides known from above.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (segment_meets_triangle(a[i], a[j], b, sa[i], sa[j])) return true;
    if (segment_meets_triangle(b[i], b[j], a, sb[i], sb[j])) return true;
  }
  return false;
}

}  // namespace cellforge::inline geom
