// Cells from the regions the faces bound (volumes.h).
#include "cellforge/io/volumes.h"

#include <algorithm>
#include <array>

#include "cellforge/geom/union_find.h"
#include "cellforge/geom/volume.h"
#include "cellforge/geom/winding.h"
#include "cellforge/topo/operators.h"

namespace cellforge::io {

namespace {

// Side k of face i: 2i (front) or 2i + 1 (back).
struct Sides {
  std::vector<FaceId> faces;
  std::vector<std::uint32_t> index;  // per face slot
  UnionFind classes;
};

Sides join_sides(const Model& m, GroupId g) {
  Sides s;
  s.index.assign(m.face_slots(), 0);
  for (FaceId f : m.faces()) {
    if (m.group_of(f) != g) continue;
    s.index[f.value] = static_cast<std::uint32_t>(s.faces.size());
    s.faces.push_back(f);
  }
  s.classes.reset(2 * s.faces.size());
  // Going round an edge, the side after use a (towards increasing angle) and the side
  // before the next use b look into one wedge (the rule of topo's wedge check).
  const auto side = [&](EdgeUseId u, bool after) {
    const bool front = after != m.is_reversed(u);
    return 2 * s.index[m.face_of(u).value] + (front ? 0u : 1u);
  };
  std::vector<bool> seen(m.edge_slots(), false);
  for (FaceId f : s.faces) {
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) continue;
      for (EdgeUseId u : m.uses_of(l)) {
        const EdgeId e = m.edge_of(u);
        if (seen[e.value]) continue;
        seen[e.value] = true;
        for (EdgeUseId a : m.radial(e))
          s.classes.unite(side(a, true), side(m.radial_next(a), false));
      }
    }
  }
  return s;
}

}  // namespace

Result<std::size_t> make_region_volumes(Model& m, GroupId g,
                                        const std::function<bool(FaceId, bool front)>& side_in) {
  Sides s = join_sides(m, g);
  const std::size_t n = 2 * s.faces.size();
  std::vector<std::uint32_t> class_of(n), dense(n, Nesting::kNone);
  std::uint32_t classes = 0;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t r = s.classes.find(k);
    if (dense[r] == Nesting::kNone) dense[r] = classes++;
    class_of[k] = dense[r];
  }
  // The surface of each class: the fan triangles of its sides, a front side's reversed.
  std::vector<Vec3> points;
  std::vector<std::uint32_t> point_of(m.vertex_slots(), Nesting::kNone);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> surface_of;
  std::vector<int> fronts(classes, 0);
  std::vector<std::uint32_t> ids;  // a loop's points
  for (std::uint32_t k = 0; k < n; ++k) {
    const FaceId f = s.faces[k / 2];
    const bool front = k % 2 == 0;
    // Both sides in one class (a fin or a membrane inside the region): the face
    // bounds nothing there and leaves that surface.
    if (class_of[k] == class_of[k ^ 1u]) continue;
    if (front) ++fronts[class_of[k]];
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) continue;
      ids.clear();
      for (VertexId v : m.loop_vertices(l)) {
        if (point_of[v.value] == Nesting::kNone) {
          point_of[v.value] = static_cast<std::uint32_t>(points.size());
          points.push_back(m.position(v));
        }
        ids.push_back(point_of[v.value]);
      }
      for (std::size_t i = 1; i + 1 < ids.size(); ++i) {
        triangles.push_back(front ? std::array{ids[0], ids[i + 1], ids[i]}
                                  : std::array{ids[0], ids[i], ids[i + 1]});
        surface_of.push_back(class_of[k]);
      }
    }
  }
  // Exact volume signs per class: a filtered pass, then the exact sum where needed.
  std::vector<VolumeFilter> filter;
  filter.reserve(classes);
  std::vector<Vec3> origin(classes);
  std::vector<bool> has_origin(classes, false);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const std::uint32_t c = surface_of[t];
    if (!has_origin[c]) origin[c] = points[triangles[t][0]], has_origin[c] = true;
  }
  for (std::uint32_t c = 0; c < classes; ++c) filter.emplace_back(origin[c]);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    filter[surface_of[t]].add_triangle(points[triangles[t][0]], points[triangles[t][1]],
                                       points[triangles[t][2]]);
  std::vector<int> sign(classes, 0);
  std::vector<std::uint32_t> undecided;
  for (std::uint32_t c = 0; c < classes; ++c) {
    sign[c] = has_origin[c] ? filter[c].sign() : 0;
    if (sign[c] == 0 && has_origin[c]) undecided.push_back(c);
  }
  if (!undecided.empty()) {
    std::vector<ExactVolume> exact;
    std::vector<std::uint32_t> slot(classes, Nesting::kNone);
    for (std::uint32_t c : undecided) {
      slot[c] = static_cast<std::uint32_t>(exact.size());
      exact.emplace_back(origin[c]);
    }
    for (std::size_t t = 0; t < triangles.size(); ++t)
      if (const std::uint32_t k = slot[surface_of[t]]; k != Nesting::kNone)
        exact[k].add_triangle(points[triangles[t][0]], points[triangles[t][1]],
                              points[triangles[t][2]]);
    for (std::uint32_t c : undecided) sign[c] = exact[slot[c]].sign();
  }
  // Outer boundaries are cells or void; inner ones take the region around them.
  std::vector<bool> outer(classes);
  for (std::uint32_t c = 0; c < classes; ++c) outer[c] = sign[c] > 0;
  std::vector<std::uint32_t> cell_of(classes, Nesting::kNone);
  std::uint32_t cells = 0;
  std::vector<char> given(classes, 0);  // by side_in: 1 not a cell, 2 a cell
  if (side_in)
    for (std::uint32_t k = 0; k < n; ++k)
      if (given[class_of[k]] == 0) given[class_of[k]] = side_in(s.faces[k / 2], k % 2 == 0) ? 2 : 1;
  for (std::uint32_t c = 0; c < classes; ++c)
    if (outer[c] && (side_in ? given[c] == 2 : fronts[c] == 0)) cell_of[c] = cells++;
  // When something is enclosed (a cell), the region around everything has at least
  // one class of negative volume (the outside of a surface that encloses it). So a
  // lone negative class is that region's, inside no surface: no cavity to nest.
  std::uint32_t inner = 0;
  for (std::uint32_t c = 0; c < classes; ++c) inner += sign[c] < 0;
  if (cells > 0 && inner > 1) {
    const Nesting nest = nest_surfaces(points, triangles, surface_of, classes, outer);
    for (std::uint32_t c = 0; c < classes; ++c)
      if (sign[c] < 0 && nest.parent[c] != Nesting::kNone && (!side_in || given[c] == 2))
        cell_of[c] = cell_of[nest.parent[c]];
  }
  std::vector<std::vector<FaceSide>> sides(cells);
  for (std::uint32_t k = 0; k < n; ++k)
    if (const std::uint32_t c = cell_of[class_of[k]]; c != Nesting::kNone)
      sides[c].push_back({s.faces[k / 2], k % 2 == 0});
  for (auto& list : sides) {
    auto made = make_volume(m, g, list);
    if (!made) return made.error();
  }
  return static_cast<std::size_t>(cells);
}

}  // namespace cellforge::io
