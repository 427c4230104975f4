// meeting_clusters (tree_private.h): which of a file's top-level parts need a Boolean
// to be united, beyond what their boxes tell. Tilted parts side by side (the sections
// of example021.scad, slabs turned 30° off the axes) have boxes that overlap while the
// parts are far apart; united by one Boolean, each part's own faces, a rounding apart
// from planar since the turn, would be resolved against each other as well.
//
// Three steps, the cheap ones first. (1) A part lies inside another, or crosses it in
// the common case, when the other's surface winds around one of its vertices (one
// of each of its edge-connected pieces): the loops' fans are surface enough for the winding
// number (their inner edges cancel), so nothing is tiled. (2) For the parts that step
// leaves with a neighbour in another cluster, every pair of triangles whose boxes meet
// (a tree over the boxes, geom/bvh.h) is tested exactly (geom/intersect.h), until the
// two parts are one cluster. (3) Parts whose surfaces do not meet are apart unless one
// lies inside the other, which step 1 decided already: with no surface between them,
// one vertex of each edge-connected piece tells for the piece.
#include <algorithm>
#include <array>
#include <unordered_map>

#include "cellforge/geom/bvh.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/geom/winding.h"
#include "cellforge/io/triangulate.h"
#include "tree_private.h"

namespace cellforge::csg {

namespace {

using Tri = std::array<std::uint32_t, 3>;

// One part: its points (in the shared table from `base`), the fans of its bounding
// faces' loops turned outward, and whether they close (every edge as often each way,
// no sheet, wire or lone point).
struct PartSurface {
  std::uint32_t base = 0, count = 0;
  std::vector<Tri> fans;
  std::vector<std::uint32_t> pieces;  // a vertex of each edge-connected piece
  Box box;
  bool closed = true;
};

std::uint64_t edge_key(std::uint32_t p, std::uint32_t q) { return (std::uint64_t{p} << 32) | q; }

// Adds the triangle's edges to `balance` (a directed edge cancels its reverse).
void balance_edges(const Tri& t, std::unordered_map<std::uint64_t, int>& balance) {
  for (int e = 0; e < 3; ++e) {
    const std::uint32_t a = t[e], b = t[(e + 1) % 3];
    if (auto it = balance.find(edge_key(b, a)); it != balance.end()) {
      if (--it->second == 0) balance.erase(it);
    } else {
      ++balance[edge_key(a, b)];
    }
  }
}

// The faces that bound a cell on one side (a face between two of the part's cells is
// inside it), with whether to reverse each so that it turns outward.
template <class F>
void bounding_faces(const Model& m, bool& sheet, F&& f) {
  for (FaceId face : m.faces()) {
    const bool front = m.front_volume(face).is_valid(), back = m.back_volume(face).is_valid();
    if (front && back) continue;
    sheet |= !front && !back;
    f(face, front);
  }
}

PartSurface surface_of(const Model& m, std::vector<Vec3>& points, std::vector<std::uint32_t>& index) {
  PartSurface s;
  s.base = static_cast<std::uint32_t>(points.size());
  index.assign(m.vertex_slots(), kInvalidIndex);
  for (VertexId v : m.vertices()) {
    index[v.value] = static_cast<std::uint32_t>(points.size());
    points.push_back(m.position(v));
    s.box.add(points.back());
  }
  s.count = static_cast<std::uint32_t>(points.size()) - s.base;
  bool sheet = false;
  std::unordered_map<std::uint64_t, int> balance;
  std::vector<std::uint32_t> loop;
  bounding_faces(m, sheet, [&](FaceId f, bool reverse) {
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      if (m.is_point_loop(l)) continue;
      loop.clear();
      for (EdgeUseId u : m.uses_of(l)) loop.push_back(index[m.use_start(u).value]);
      for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
        Tri t{loop[0], loop[i], loop[i + 1]};
        if (reverse) std::swap(t[1], t[2]);
        balance_edges(t, balance);
        s.fans.push_back(t);
      }
    }
  });
  bool wires = false;
  for (EdgeId e : m.edges()) wires |= m.is_wire(e);
  for (VertexId v : m.vertices()) wires |= !m.first_end(v).edge.is_valid() && !m.point_loop(v).is_valid();
  s.closed = !sheet && !wires && balance.empty() && !s.fans.empty();
  // The pieces: a part may be several solids (a transform of several children, a
  // polyhedron of several shells), each of which may lie inside another part alone.
  UnionFind joined(s.count);
  for (const Tri& t : s.fans) {
    joined.unite_to_smaller(t[0] - s.base, t[1] - s.base);
    joined.unite_to_smaller(t[0] - s.base, t[2] - s.base);
  }
  for (const Tri& t : s.fans)
    for (std::uint32_t v : t) s.pieces.push_back(s.base + joined.find(v - s.base));  // its smallest
  std::sort(s.pieces.begin(), s.pieces.end());
  s.pieces.erase(std::unique(s.pieces.begin(), s.pieces.end()), s.pieces.end());
  return s;
}

// The part's bounding faces tiled; where a tiling misses a sliver along a loop (a face
// that rounding left a hair off planar), the fans, which cover at least the face.
std::vector<Tri> tiles_of(const Model& m, const PartSurface& s, std::vector<std::uint32_t>& index) {
  index.assign(m.vertex_slots(), kInvalidIndex);
  std::uint32_t next = s.base;
  for (VertexId v : m.vertices()) index[v.value] = next++;
  std::vector<Tri> out;
  std::unordered_map<std::uint64_t, int> balance;
  std::vector<std::array<VertexId, 3>> tiles;
  bool sheet = false;
  bounding_faces(m, sheet, [&](FaceId f, bool reverse) {
    tiles.clear();
    io::triangulate_face(m, f, tiles);
    for (const auto& t : tiles) {
      Tri tri{index[t[0].value], index[t[1].value], index[t[2].value]};
      if (reverse) std::swap(tri[1], tri[2]);
      balance_edges(tri, balance);
      out.push_back(tri);
    }
  });
  return balance.empty() || !s.closed ? out : s.fans;
}

bool in_box(Vec3 p, const Box& b) {
  return p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z && p.x <= b.hi.x && p.y <= b.hi.y &&
         p.z <= b.hi.z;
}

}  // namespace

std::vector<std::uint32_t> meeting_clusters(const std::vector<const Model*>& parts,
                                            const std::vector<std::uint32_t>& together) {
  const std::size_t n = parts.size();
  UnionFind clusters(n);
  const auto same = [&](std::size_t p, std::size_t q) {
    return clusters.find(static_cast<std::uint32_t>(p)) == clusters.find(static_cast<std::uint32_t>(q));
  };
  const auto unite = [&](std::size_t p, std::size_t q) {
    clusters.unite_to_smaller(static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(q));
  };
  if (!together.empty()) {
    std::unordered_map<std::uint32_t, std::size_t> first_of;  // id -> its first part
    for (std::size_t k = 0; k < n; ++k) {
      const auto [it, fresh] = first_of.emplace(together[k], k);
      if (!fresh) unite(it->second, k);
    }
  }
  // A part whose box meets no other part's is a cluster of its own and needs no
  // surface (a `for` loop's parts side by side: functions.scad's 41 cubes).
  std::vector<Box> part_box(n);
  for (std::size_t k = 0; k < n; ++k)
    for (VertexId v : parts[k]->vertices()) part_box[k].add(parts[k]->position(v));
  std::vector<bool> alone(n, true);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p + 1; q < n; ++q)
      if (part_box[p].overlaps(part_box[q])) alone[p] = alone[q] = false;
  std::vector<Vec3> points;
  std::vector<std::uint32_t> index;
  std::vector<PartSurface> surfaces(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (alone[k]) {
      surfaces[k].box = part_box[k];
      continue;
    }
    surfaces[k] = surface_of(*parts[k], points, index);
  }

  // 1: a vertex of a piece of one inside the other (a piece inside lies in the
  // other's box whole, so the piece's root vertex tells).
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t s = 0; s < n; ++s) {
      const PartSurface &a = surfaces[t], &b = surfaces[s];
      if (s == t || !b.closed || !a.box.overlaps(b.box)) continue;
      for (std::uint32_t v : a.pieces) {
        if (same(s, t)) break;
        if (in_box(points[v], b.box) && winding_number(points, b.fans, points[v]).number != 0) unite(s, t);
      }
    }
  // 2: the surfaces of parts with a neighbour in another cluster, triangle by triangle.
  std::vector<bool> open(n, false);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p + 1; q < n; ++q)
      if (!same(p, q) && surfaces[p].box.overlaps(surfaces[q].box)) open[p] = open[q] = true;
  std::vector<Tri> tris;
  std::vector<std::uint32_t> part_of;
  for (std::size_t k = 0; k < n; ++k) {
    if (!open[k]) continue;
    for (const Tri& t : tiles_of(*parts[k], surfaces[k], index)) {
      tris.push_back(t);
      part_of.push_back(static_cast<std::uint32_t>(k));
    }
  }
  std::vector<Box> boxes(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::uint32_t v : tris[i]) boxes[i].add(points[v]);
  if (!tris.empty()) Bvh(boxes, part_of).pairs([&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t p = part_of[i], q = part_of[j];
    if (same(p, q)) return;
    const Vec3 a[3] = {points[tris[i][0]], points[tris[i][1]], points[tris[i][2]]};
    const Vec3 b[3] = {points[tris[j][0]], points[tris[j][1]], points[tris[j][2]]};
    if (!surfaces[p].closed || !surfaces[q].closed || triangles_meet(a, b)) unite(p, q);
  });
  std::vector<std::uint32_t> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = clusters.find(static_cast<std::uint32_t>(k));
  return out;
}

}  // namespace cellforge::csg
