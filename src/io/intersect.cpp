// Self-intersections (intersect.h): candidate pairs from a bounding-volume hierarchy
// over the triangles' boxes (geom/bvh.h), each decided by the exact triangle test.
// Triangles with the same three vertices are one entry of the hierarchy (their faces
// are listed with it), so a stack of equal triangles costs one triangle, not the
// square of their number.
//
// Planar fans. A faceted circle's cap, written as triangles, is a fan of long thin
// triangles around one rim vertex (the hub): the boxes of any two of them overlap,
// and each box holds much of the side wall too, so the pairs from boxes grow with
// the square of the segments. The triangles of a fan all share the hub, so no pair
// of them is tested. When they lie in one plane and follow one another around the
// hub counterclockwise within a half-turn (checked exactly: each triangle (hub, v_i,
// v_i+1) and each (hub, v_1, v_i+1) of one orientation; the rim need not be convex,
// and after rounding to float a 16000-gon's is not), they fill disjoint sectors of
// the polygon Q = hub, v_1, ..., v_k, and a vertex of Q lies in no fan triangle
// but the ones that have it, an edge of Q in none but the one that has it and, at
// its ends, the ones that have those. So a triangle T that stays on one side of Q's
// plane, or meets it only in a vertex of Q or an edge of Q, meets no fan triangle
// except in a vertex it shares with it: no pair. Such a fan is one entry of the
// hierarchy, with Q's box; a triangle whose box meets it is settled by three
// orient3d signs, and any other case (T crossing the plane, lying in it, touching
// it elsewhere; two fans) falls back to the exact test of T against each fan
// triangle whose box meets T's. The pairs reported are the same.
#include "io/intersect.h"

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "cellforge/geom/bvh.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/plane.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/triangulate.h"

namespace cellforge::io {

namespace {

struct TriangleKeyHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t x : k) h = (h ^ x) * 1099511628211ull;
    return h ^ (h >> 29);
  }
};

struct Tri {
  std::array<VertexId, 3> v;
  std::vector<FaceId> faces;  // every face with a triangle on these three vertices
};

// A planar fan: Q = hub, rim[0], ..., rim.back(), counterclockwise around the hub in
// the projection, fanned into tris[k] = (hub, rim[k], rim[k + 1]).
struct Fan {
  VertexId hub;
  std::vector<VertexId> rim;
  std::vector<std::uint32_t> tris;
  Vec3 plane[3];  // three points of Q spanning its plane
  std::unordered_map<std::uint32_t, long> place;  // vertex -> 0 (hub), k + 1 (rim[k])
};

// Fans of at least kMinFan triangles around the vertices of highest degree.
constexpr std::size_t kMinFan = 32;

// The planar fan of `flat` (triangles at the hub, all in one plane), if
// they form one: each (hub, a, b) in its own order, chained a -> b from the one rim
// vertex no triangle ends at.
std::optional<Fan> make_fan(const Model& m, const std::vector<Tri>& tris, VertexId hub,
                            const std::vector<std::uint32_t>& flat) {
  std::unordered_map<std::uint32_t, std::pair<std::uint32_t, std::uint32_t>> next;  // a -> (b, tri)
  std::unordered_map<std::uint32_t, int> is_b;
  for (std::uint32_t t : flat) {
    const auto& v = tris[t].v;
    const int k = v[0] == hub ? 0 : v[1] == hub ? 1 : 2;
    const std::uint32_t a = v[(k + 1) % 3].value, b = v[(k + 2) % 3].value;
    // Two triangles leaving or entering one rim vertex: not a simple fan.
    if (!next.try_emplace(a, b, t).second || is_b[b]++) return std::nullopt;
  }
  std::uint32_t start = kInvalidIndex;
  for (const auto& [a, bt] : next) {
    if (is_b.count(a)) continue;
    if (start != kInvalidIndex) return std::nullopt;  // two chains
    start = a;
  }
  if (start == kInvalidIndex) return std::nullopt;  // a closed fan (hub inside): not handled
  Fan fan;
  fan.hub = hub;
  fan.rim.push_back(VertexId(start));
  for (std::uint32_t a = start; next.count(a) && fan.tris.size() <= next.size();) {
    const auto [b, t] = next[a];
    fan.tris.push_back(t);
    fan.rim.push_back(VertexId(b));
    a = b;
  }
  if (fan.tris.size() != next.size()) return std::nullopt;
  // Each triangle of one orientation, and no wrapping past the first edge.
  const Vec3 h = m.position(hub);
  const Vec3 p0 = m.position(fan.rim[0]), p1 = m.position(fan.rim[1]);
  if (collinear3d(h, p0, p1)) return std::nullopt;
  const Projection proj = Plane::through(h, p0, p1).projection();
  const Vec2 hh = proj(h);
  std::vector<Vec2> q;
  for (VertexId v : fan.rim) q.push_back(proj(m.position(v)));
  const int turn = orient2d(hh, q[0], q[1]);
  const std::size_t n = q.size();
  bool ok = true;
  for (std::size_t i = 0; ok && i + 1 < n; ++i) {
    ok = orient2d(hh, q[i], q[i + 1]) == turn;                   // each triangle
    if (ok && i > 0) ok = orient2d(hh, q[0], q[i + 1]) == turn;  // within a half-turn
  }
  if (!ok) return std::nullopt;
  fan.plane[0] = h;
  fan.plane[1] = p0;
  fan.plane[2] = p1;
  fan.place[hub.value] = 0;
  for (std::size_t k = 0; k < fan.rim.size(); ++k) fan.place[fan.rim[k].value] = static_cast<long>(k) + 1;
  return fan;
}

std::vector<Fan> find_fans(const Model& m, const std::vector<Tri>& tris, std::vector<int>& fan_of) {
  std::vector<Fan> fans;
  fan_of.assign(tris.size(), -1);
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> around;  // vertex -> triangles
  {
    std::unordered_map<std::uint32_t, std::uint32_t> degree;
    for (const Tri& t : tris)
      for (VertexId v : t.v) ++degree[v.value];
    for (std::uint32_t i = 0; i < tris.size(); ++i)
      for (VertexId v : tris[i].v)
        if (degree[v.value] >= kMinFan) around[v.value].push_back(i);
  }
  std::vector<std::pair<std::size_t, std::uint32_t>> hubs;
  for (const auto& [v, list] : around) hubs.push_back({list.size(), v});
  std::sort(hubs.begin(), hubs.end(), std::greater<>());
  for (const auto& [deg, hub_index] : hubs) {
    const VertexId hub(hub_index);
    // The triangles at the hub in one plane with a reference triangle (the cap's,
    // not the walls' around it): tried with each of the first eight triangles at the hub.
    const std::vector<std::uint32_t>& at_hub = around[hub_index];
    for (std::size_t ref = 0; ref < at_hub.size() && ref < 8; ++ref) {
      if (fan_of[at_hub[ref]] >= 0) continue;
      const auto& rv = tris[at_hub[ref]].v;
      const Vec3 r0 = m.position(rv[0]), r1 = m.position(rv[1]), r2 = m.position(rv[2]);
      if (collinear3d(r0, r1, r2)) continue;
      std::vector<std::uint32_t> flat;
      for (std::uint32_t t : at_hub) {
        if (fan_of[t] >= 0) continue;
        bool in_plane = true;
        for (VertexId v : tris[t].v) in_plane = in_plane && orient3d(r0, r1, r2, m.position(v)) == 0;
        if (in_plane) flat.push_back(t);
      }
      if (flat.size() < kMinFan) continue;
      if (auto fan = make_fan(m, tris, hub, flat)) {
        for (std::uint32_t t : fan->tris) fan_of[t] = static_cast<int>(fans.size());
        fans.push_back(std::move(*fan));
        break;
      }
    }
  }
  return fans;
}

}  // namespace

std::vector<std::pair<FaceId, FaceId>> self_intersections(const Model& m) {
  std::vector<Tri> tris;
  std::unordered_map<std::array<std::uint32_t, 3>, std::uint32_t, TriangleKeyHash> index;
  for (FaceId f : m.faces()) {
    for (const auto& t : triangulate_face(m, f)) {
      std::array<std::uint32_t, 3> key{t[0].value, t[1].value, t[2].value};
      std::sort(key.begin(), key.end());
      const auto [it, fresh] = index.try_emplace(key, static_cast<std::uint32_t>(tris.size()));
      if (fresh) tris.push_back({t, {}});
      auto& faces = tris[it->second].faces;
      if (faces.empty() || faces.back() != f) faces.push_back(f);
    }
  }
  std::vector<std::pair<FaceId, FaceId>> out;
  const auto emit = [&](FaceId a, FaceId b) {
    if (a != b) out.push_back(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
  };
  std::vector<Box> tri_box(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (VertexId v : tris[i].v) tri_box[i].add(m.position(v));
  // The exact test of one pair of triangles.
  const auto test = [&](std::uint32_t s, std::uint32_t t) {
    const Tri &a = tris[s], &b = tris[t];
    if (a.faces.size() == 1 && b.faces.size() == 1 && a.faces[0] == b.faces[0]) return;
    for (VertexId u : a.v)
      for (VertexId v : b.v)
        if (u == v) return;
    const Vec3 pa[3] = {m.position(a.v[0]), m.position(a.v[1]), m.position(a.v[2])};
    const Vec3 pb[3] = {m.position(b.v[0]), m.position(b.v[1]), m.position(b.v[2])};
    if (!triangles_meet(pa, pb)) return;
    for (FaceId f : a.faces)
      for (FaceId g : b.faces) emit(f, g);
  };

  std::vector<int> fan_of;
  const std::vector<Fan> fans = find_fans(m, tris, fan_of);
  // Entries of the hierarchy: the triangles outside fans, then one per fan.
  std::vector<std::uint32_t> entry_tri;
  std::vector<Box> boxes;
  for (std::uint32_t i = 0; i < tris.size(); ++i) {
    if (fan_of[i] >= 0) continue;
    entry_tri.push_back(i);
    boxes.push_back(tri_box[i]);
  }
  const auto first_fan = static_cast<std::uint32_t>(entry_tri.size());
  for (const Fan& fan : fans) {
    Box b;
    b.add(m.position(fan.hub));
    for (VertexId v : fan.rim) b.add(m.position(v));
    boxes.push_back(b);
  }
  // Triangle t against every triangle of fan k whose box meets t's.
  const auto against_fan = [&](std::uint32_t t, const Fan& fan) {
    for (std::uint32_t s : fan.tris)
      if (tri_box[s].overlaps(tri_box[t])) test(s, t);
  };
  const auto settled_by_fan = [&](std::uint32_t t, const Fan& fan) {
    const Tri& tri = tris[t];
    int sign[3];
    bool above = false, below = false;
    std::vector<VertexId> on;
    for (int k = 0; k < 3; ++k) {
      sign[k] = orient3d(fan.plane[0], fan.plane[1], fan.plane[2], m.position(tri.v[k]));
      above |= sign[k] > 0;
      below |= sign[k] < 0;
      if (sign[k] == 0) on.push_back(tri.v[k]);
    }
    if (above != below) {
      if (on.empty()) return true;  // strictly on one side
    } else {
      return false;  // crossing the plane, or lying in it
    }
    // T meets the plane in `on` (one vertex, or the edge between two).
    const auto position_on_q = [&](VertexId v) -> long {  // -1: not a vertex of Q
      const auto it = fan.place.find(v.value);
      return it == fan.place.end() ? -1 : it->second;
    };
    const long a = position_on_q(on[0]);
    if (a < 0) return false;
    if (on.size() == 1) return true;
    const long b = position_on_q(on[1]);
    if (b < 0) return false;
    const long q = static_cast<long>(fan.rim.size()) + 1;  // Q's vertex count
    return (a - b + q) % q == 1 || (b - a + q) % q == 1;  // an edge of Q
  };
  Bvh(std::move(boxes)).pairs([&](std::uint32_t s, std::uint32_t t) {
    if (s >= first_fan && t >= first_fan) {  // two fans: every pair of their triangles
      const Fan &a = fans[s - first_fan], &b = fans[t - first_fan];
      for (std::uint32_t x : a.tris) against_fan(x, b);
      return;
    }
    if (t >= first_fan) std::swap(s, t);
    if (s >= first_fan) {
      const Fan& fan = fans[s - first_fan];
      const std::uint32_t tri = entry_tri[t];
      if (!settled_by_fan(tri, fan)) against_fan(tri, fan);
      return;
    }
    test(entry_tri[s], entry_tri[t]);
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cellforge::io
