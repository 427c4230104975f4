// meeting_clusters (tree_private.h): which of a file's top-level parts need a Boolean
// to be united, beyond what their boxes tell. Tilted parts side by side (the sections
// of example021.scad, slabs turned 30° off the axes) have boxes that overlap while the
// parts are far apart; united by one Boolean, each part's own faces, a rounding apart
// from planar since the turn, would be resolved against each other as well.
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

std::vector<std::uint32_t> meeting_clusters(const std::vector<const Model*>& parts,
                                            const std::vector<std::uint32_t>& together) {
  const std::size_t n = parts.size();
  // Every part's bounding faces as outward triangles over one table of points.
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> part_of;     // by triangle
  std::vector<std::uint32_t> first(n + 1);  // part k's triangles: [first[k], first[k + 1])
  std::vector<bool> closed(n, true);
  std::vector<std::array<VertexId, 3>> tiles;
  for (std::size_t k = 0; k < n; ++k) {
    const Model& m = *parts[k];
    first[k] = static_cast<std::uint32_t>(tris.size());
    std::vector<std::uint32_t> index(m.vertex_slots(), kInvalidIndex);
    for (VertexId v : m.vertices()) {
      index[v.value] = static_cast<std::uint32_t>(points.size());
      points.push_back(m.position(v));
    }
    // The faces' tilings; where they miss a sliver along a loop (a face that rounding
    // left a hair off planar), the loops' fans instead, whose signed sum still winds
    // once around the inside.
    bool sheet = false;
    auto triangles = [&](bool fans) {
      tris.resize(first[k]);
      part_of.resize(first[k]);
      std::unordered_map<std::uint64_t, int> balance;  // directed edge -> uses not undone
      const auto key = [](std::uint32_t p, std::uint32_t q) { return (std::uint64_t{p} << 32) | q; };
      auto add = [&](std::array<std::uint32_t, 3> tri) {
        for (int e = 0; e < 3; ++e) {
          const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
          if (auto it = balance.find(key(b, a)); it != balance.end()) {
            if (--it->second == 0) balance.erase(it);
          } else {
            ++balance[key(a, b)];
          }
        }
        tris.push_back(tri);
        part_of.push_back(static_cast<std::uint32_t>(k));
      };
      for (FaceId f : m.faces()) {
        const bool front = m.front_volume(f).is_valid(), back = m.back_volume(f).is_valid();
        if (front && back) continue;  // between two of the part's cells
        sheet |= !front && !back;
        tiles.clear();
        if (!fans) {
          io::triangulate_face(m, f, tiles);
        } else {
          for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
            if (m.is_point_loop(l)) continue;
            std::vector<VertexId> loop;
            for (EdgeUseId u : m.uses_of(l)) loop.push_back(m.use_start(u));
            for (std::size_t i = 1; i + 1 < loop.size(); ++i) tiles.push_back({loop[0], loop[i], loop[i + 1]});
          }
        }
        for (const auto& t : tiles) {
          std::array<std::uint32_t, 3> tri{index[t[0].value], index[t[1].value], index[t[2].value]};
          if (front) std::swap(tri[1], tri[2]);
          add(tri);
        }
      }
      return balance.empty();
    };
    closed[k] = (triangles(false) || triangles(true)) && !sheet && tris.size() > first[k];
    // Wires and points are not in the triangles: such a part meets all it reaches.
    for (EdgeId e : m.edges()) closed[k] = closed[k] && !m.is_wire(e);
  }
  first[n] = static_cast<std::uint32_t>(tris.size());

  UnionFind clusters(n);
  if (!together.empty()) {
    std::unordered_map<std::uint32_t, std::uint32_t> first_of;  // id -> its first part
    for (std::size_t k = 0; k < n; ++k) {
      const auto [it, fresh] = first_of.emplace(together[k], static_cast<std::uint32_t>(k));
      if (!fresh) clusters.unite_to_smaller(it->second, static_cast<std::uint32_t>(k));
    }
  }
  std::vector<Box> boxes(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::uint32_t v : tris[i]) boxes[i].add(points[v]);
  const Bvh tree(boxes, part_of);
  tree.pairs([&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t p = part_of[i], q = part_of[j];
    if (clusters.find(p) == clusters.find(q)) return;
    const Vec3 a[3] = {points[tris[i][0]], points[tris[i][1]], points[tris[i][2]]};
    const Vec3 b[3] = {points[tris[j][0]], points[tris[j][1]], points[tris[j][2]]};
    if (!closed[p] || !closed[q] || triangles_meet(a, b)) clusters.unite_to_smaller(p, q);
  });
  // The surfaces of parts in different clusters do not meet: one lies inside another
  // exactly when the other winds around one of its points.
  std::vector<Box> part_box(n);
  for (std::size_t k = 0; k < n; ++k)
    for (std::uint32_t i = first[k]; i < first[k + 1]; ++i) part_box[k].add(boxes[i]);
  for (std::size_t t = 0; t < n; ++t) {
    if (first[t] == first[t + 1]) continue;
    const Vec3 v = points[tris[first[t]][0]];
    for (std::size_t s = 0; s < n; ++s) {
      if (s == t || !closed[s] || clusters.find(static_cast<std::uint32_t>(s)) ==
                                      clusters.find(static_cast<std::uint32_t>(t)))
        continue;
      const Box& b = part_box[s];
      if (v.x < b.lo.x || v.y < b.lo.y || v.z < b.lo.z || v.x > b.hi.x || v.y > b.hi.y || v.z > b.hi.z)
        continue;
      const std::span<const std::array<std::uint32_t, 3>> own(tris.data() + first[s], first[s + 1] - first[s]);
      if (winding_number(points, own, v).number != 0)
        clusters.unite_to_smaller(static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(t));
    }
  }
  std::vector<std::uint32_t> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = clusters.find(static_cast<std::uint32_t>(k));
  return out;
}

}  // namespace cellforge::csg
