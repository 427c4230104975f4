#include "io/intersect.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "cellforge/io/triangulate.h"
#include "io/exact.h"

namespace cellforge::io {

namespace {

bool on_segment(Point2 p, Point2 q, Point2 r) {  // r on pq, given collinear
  return std::min(p.u, q.u) <= r.u && r.u <= std::max(p.u, q.u) && std::min(p.v, q.v) <= r.v &&
         r.v <= std::max(p.v, q.v);
}

bool segments_meet_2d(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

bool inside_2d(const Point2 t[3], Point2 p) {  // closed triangle, either orientation
  const int a = orient2d(t[0], t[1], p), b = orient2d(t[1], t[2], p), c = orient2d(t[2], t[0], p);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

// Closed triangles in one plane (projected) meet.
bool coplanar_meet(const Point2 a[3], const Point2 b[3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_meet_2d(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return inside_2d(a, b[0]) || inside_2d(b, a[0]);
}

// The normal direction of a triangle that is not degenerate, for projection: the
// exact signs of its components decide the dominant plane only approximately,
// which is enough since any plane the triangle does not project to a line works.
Vec3 normal_of(const Vec3 t[3]) { return cross(t[1] - t[0], t[2] - t[0]); }

// Segment pq meets closed triangle t (not coplanar with it as a whole).
bool segment_meets_triangle(Vec3 p, Vec3 q, const Vec3 t[3]) {
  const int s1 = orient3d_filtered(t[0], t[1], t[2], p);
  const int s2 = orient3d_filtered(t[0], t[1], t[2], q);
  if (s1 == s2 && s1 != 0) return false;
  if (s1 == 0 && s2 == 0) {  // the segment lies in t's plane
    const Projection proj(normal_of(t));
    const Point2 tt[3] = {proj(t[0]), proj(t[1]), proj(t[2])};
    const Point2 pp = proj(p), qq = proj(q);
    for (int j = 0; j < 3; ++j)
      if (segments_meet_2d(pp, qq, tt[j], tt[(j + 1) % 3])) return true;
    return inside_2d(tt, pp);
  }
  const int a = orient3d_filtered(p, q, t[0], t[1]);
  const int b = orient3d_filtered(p, q, t[1], t[2]);
  const int c = orient3d_filtered(p, q, t[2], t[0]);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

}  // namespace

bool triangles_meet(const Vec3 a[3], const Vec3 b[3]) {
  int sb[3], sa[3];
  for (int i = 0; i < 3; ++i) sb[i] = orient3d_filtered(a[0], a[1], a[2], b[i]);
  if ((sb[0] > 0 && sb[1] > 0 && sb[2] > 0) || (sb[0] < 0 && sb[1] < 0 && sb[2] < 0)) return false;
  for (int i = 0; i < 3; ++i) sa[i] = orient3d_filtered(b[0], b[1], b[2], a[i]);
  if ((sa[0] > 0 && sa[1] > 0 && sa[2] > 0) || (sa[0] < 0 && sa[1] < 0 && sa[2] < 0)) return false;
  if (sb[0] == 0 && sb[1] == 0 && sb[2] == 0) {
    const Vec3 n = normal_of(a);
    if (n == Vec3{}) return false;  // degenerate: reported as such elsewhere
    const Projection proj(n);
    const Point2 pa[3] = {proj(a[0]), proj(a[1]), proj(a[2])};
    const Point2 pb[3] = {proj(b[0]), proj(b[1]), proj(b[2])};
    return coplanar_meet(pa, pb);
  }
  for (int i = 0; i < 3; ++i) {
    if (segment_meets_triangle(a[i], a[(i + 1) % 3], b)) return true;
    if (segment_meets_triangle(b[i], b[(i + 1) % 3], a)) return true;
  }
  return false;
}

std::vector<std::pair<FaceId, FaceId>> self_intersections(const Model& m) {
  struct Tri {
    std::array<VertexId, 3> v;
    FaceId face;
    Vec3 lo, hi;
  };
  std::vector<Tri> tris;
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double extent = 0;
  for (FaceId f : m.faces()) {
    for (const auto& t : triangulate_face(m, f)) {
      Tri tri{t, f, m.position(t[0]), m.position(t[0])};
      for (VertexId v : t) {
        const Vec3 p = m.position(v);
        tri.lo = {std::min(tri.lo.x, p.x), std::min(tri.lo.y, p.y), std::min(tri.lo.z, p.z)};
        tri.hi = {std::max(tri.hi.x, p.x), std::max(tri.hi.y, p.y), std::max(tri.hi.z, p.z)};
      }
      lo = {std::min(lo.x, tri.lo.x), std::min(lo.y, tri.lo.y), std::min(lo.z, tri.lo.z)};
      hi = {std::max(hi.x, tri.hi.x), std::max(hi.y, tri.hi.y), std::max(hi.z, tri.hi.z)};
      extent += std::max({tri.hi.x - tri.lo.x, tri.hi.y - tri.lo.y, tri.hi.z - tri.lo.z});
      tris.push_back(tri);
    }
  }
  std::vector<std::pair<FaceId, FaceId>> out;
  if (tris.size() < 2) return out;
  // Cells about twice the mean triangle size, at most ~64 cells per axis per
  // million triangles' worth of span.
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  double cell = std::max(2 * extent / static_cast<double>(tris.size()), span / 1024);
  if (!(cell > 0)) cell = 1;
  const auto cell_of = [&](double x, double base) {
    return static_cast<std::int64_t>(std::floor((x - base) / cell));
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
           static_cast<std::uint64_t>(k) * 83492791u ^ (static_cast<std::uint64_t>(i) << 42) ^
           (static_cast<std::uint64_t>(j) << 21);
  };
  const auto test = [&](std::uint32_t s, std::uint32_t t) {
    const Tri &a = tris[s], &b = tris[t];
    if (a.face == b.face) return;
    if (a.hi.x < b.lo.x || b.hi.x < a.lo.x || a.hi.y < b.lo.y || b.hi.y < a.lo.y ||
        a.hi.z < b.lo.z || b.hi.z < a.lo.z)
      return;
    for (VertexId u : a.v)
      for (VertexId v : b.v)
        if (u == v) return;
    const Vec3 pa[3] = {m.position(a.v[0]), m.position(a.v[1]), m.position(a.v[2])};
    const Vec3 pb[3] = {m.position(b.v[0]), m.position(b.v[1]), m.position(b.v[2])};
    if (triangles_meet(pa, pb))
      out.push_back(a.face < b.face ? std::make_pair(a.face, b.face)
                                    : std::make_pair(b.face, a.face));
  };
  // Triangles spanning many cells are tested against every triangle instead.
  constexpr std::int64_t kMaxCells = 512;
  std::vector<std::uint32_t> large, candidates;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const Tri& a = tris[t];
    const std::int64_t i0 = cell_of(a.lo.x, lo.x), i1 = cell_of(a.hi.x, lo.x);
    const std::int64_t j0 = cell_of(a.lo.y, lo.y), j1 = cell_of(a.hi.y, lo.y);
    const std::int64_t k0 = cell_of(a.lo.z, lo.z), k1 = cell_of(a.hi.z, lo.z);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1) > kMaxCells) {
      large.push_back(t);
      continue;
    }
    candidates.clear();
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) {
          auto& bucket = grid[key(i, j, k)];
          candidates.insert(candidates.end(), bucket.begin(), bucket.end());
          bucket.push_back(t);
        }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (std::uint32_t s : candidates) test(s, t);
  }
  for (std::size_t i = 0; i < large.size(); ++i)
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      if (t != large[i] && (t > large[i] || !std::binary_search(large.begin(), large.end(), t)))
        test(std::min(t, large[i]), std::max(t, large[i]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cellforge::io
