// build_mesh: indexed polygons to the cycle structure in O(n log n).
//
// 1. check the input (indices, finite coordinates, loop sizes, volume indices);
// 2. make the vertices, then one edge per unordered vertex pair (sorting the
//    pairs), oriented like the first use that names it;
// 3. make faces, loops and uses; chain each edge's uses into its radial cycle and
//    sort the cycles that have three or more uses by exact angle.
#include "cellforge/topo/builder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

#include "topo/model_editor.h"

namespace cellforge::inline topo {

namespace {

std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

Status check_input(const MeshInput& in) {
  const std::size_t n = in.positions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = in.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return Error{ErrorCode::kInvalidInput,
                   "vertex " + std::to_string(i) + " has a non-finite coordinate"};
    }
  }
  if (n >= Model::kMaxEdges) {
    return Error{ErrorCode::kInvalidInput, "too many vertices: " + std::to_string(n)};
  }
  for (std::size_t fi = 0; fi < in.faces.size(); ++fi) {
    const MeshFace& f = in.faces[fi];
    // The place, spelled out only for an error (a mesh of a million faces has none).
    const auto where = [fi] { return "face " + std::to_string(fi); };
    if (f.loops.empty()) return Error{ErrorCode::kInvalidInput, where() + " has no loop"};
    for (int side : {f.front, f.back}) {
      if (side < -1 || side >= in.volumes) {
        return Error{ErrorCode::kInvalidInput, where() + " names volume " + std::to_string(side) +
                                                   " but there are " + std::to_string(in.volumes)};
      }
    }
    for (std::size_t li = 0; li < f.loops.size(); ++li) {
      const auto& loop = f.loops[li];
      const auto at = [&] { return where() + " loop " + std::to_string(li); };
      if (loop.size() < 3) {
        return Error{ErrorCode::kInvalidInput,
                     at() + " has " + std::to_string(loop.size()) + " vertices (at least 3)"};
      }
      for (std::size_t k = 0; k < loop.size(); ++k) {
        if (loop[k] >= n) {
          return Error{ErrorCode::kInvalidInput, at() + " index " + std::to_string(loop[k]) +
                                                     " is out of range (" + std::to_string(n) +
                                                     " vertices)"};
        }
        if (loop[k] == loop[(k + 1) % loop.size()]) {
          return Error{ErrorCode::kInvalidInput,
                       at() + " repeats vertex " + std::to_string(loop[k]) + " consecutively"};
        }
      }
    }
  }
  for (std::size_t wi = 0; wi < in.wires.size(); ++wi) {
    const auto& w = in.wires[wi];
    if (w[0] >= n || w[1] >= n || w[0] == w[1]) {
      return Error{ErrorCode::kInvalidInput,
                   "wire " + std::to_string(wi) + " (" + std::to_string(w[0]) + ", " +
                       std::to_string(w[1]) + ") is out of range or degenerate"};
    }
  }
  return Status::Ok();
}

}  // namespace

Result<BuildResult> build_mesh(Model& m, const MeshInput& in) {
  if (Status s = check_input(in); !s) return s.error();
  if (m.face_slots() + in.faces.size() >= Model::kMaxFaces) {
    return Error{ErrorCode::kInvalidInput,
                 "too many faces: " + std::to_string(m.face_slots() + in.faces.size())};
  }
  ModelEditor ed(m);
  BuildResult out;
  out.group = ed.new_group(in.group_name);

  ed.reserve(in.positions.size(), 0, in.faces.size());
  out.vertices.reserve(in.positions.size());
  for (const Vec3& p : in.positions) out.vertices.push_back(ed.new_vertex(out.group, p));
  for (int i = 0; i < in.volumes; ++i) out.volumes.push_back(ed.new_volume(out.group));

  // Every directed side of every loop, then wires, as (key, start vertex, slot).
  struct Side {
    std::uint64_t key;
    std::uint32_t from;
    std::uint32_t slot;  // index of the use in creation order, or kInvalidIndex for wires
  };
  std::vector<Side> sides;
  std::size_t use_total = 0;
  for (const MeshFace& f : in.faces) {
    for (const auto& loop : f.loops) use_total += loop.size();
  }
  sides.reserve(use_total + in.wires.size());
  std::uint32_t slot = 0;
  for (const MeshFace& f : in.faces) {
    for (const auto& loop : f.loops) {
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
        sides.push_back({pair_key(a, b), a, slot++});
      }
    }
  }
  for (const auto& w : in.wires) sides.push_back({pair_key(w[0], w[1]), w[0], kInvalidIndex});
  // By key, stably: counted into rows by the smaller vertex (a pass each way, no
  // comparisons), then each row's few sides ordered in place.
  {
    const std::size_t n = in.positions.size();
    std::vector<std::uint32_t> start(n + 1, 0);
    for (const Side& x : sides) ++start[(x.key >> 32) + 1];
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<Side> sorted(sides.size());
    for (const Side& x : sides) sorted[start[x.key >> 32]++] = x;  // start[v]: row v's end now
    const auto by_key = [](const Side& x, const Side& y) { return x.key < y.key; };
    for (std::size_t v = 0, b = 0; v < n; b = start[v++]) {
      if (start[v] - b < 2) continue;
      Side* first = sorted.data() + b;
      Side* last = sorted.data() + start[v];
      if (last - first > 32) {
        std::stable_sort(first, last, by_key);
        continue;
      }
      for (Side* x = first + 1; x < last; ++x)
        for (Side* y = x; y > first && by_key(*y, *(y - 1)); --y) std::swap(*y, *(y - 1));
    }
    sides.swap(sorted);
  }

  // One edge per key, oriented like its first side; each use learns its edge.
  std::vector<EdgeId> edge_of_slot(use_total);
  std::vector<std::pair<std::size_t, std::size_t>> groups;  // ranges in `sides`
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    groups.emplace_back(i, j);
    i = j;
  }
  // Edge slots: the edges, and spare pairs for the third and later uses of an edge
  // (counted as one pair each, an upper bound).
  std::size_t overflow = 0;
  for (const auto& [first, last] : groups) overflow += last - first > 2 ? last - first - 2 : 0;
  if (m.edge_slots() + groups.size() + overflow >= Model::kMaxEdges) {
    return Error{ErrorCode::kInvalidInput, "too many edges: " + std::to_string(groups.size())};
  }
  ed.reserve(0, groups.size() + overflow, 0);
  std::vector<EdgeId> edge_of_group(groups.size());
  std::vector<std::uint32_t> edge_start(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Side& first = sides[groups[g].first];
    const std::uint32_t a = first.from;
    const std::uint32_t lo = static_cast<std::uint32_t>(first.key >> 32);
    const std::uint32_t hi = static_cast<std::uint32_t>(first.key);
    const std::uint32_t b = a == lo ? hi : lo;
    edge_of_group[g] = ed.new_edge(out.vertices[a], out.vertices[b]);
    edge_start[g] = a;
    for (std::size_t i = groups[g].first; i < groups[g].second; ++i) {
      if (sides[i].slot != kInvalidIndex) edge_of_slot[sides[i].slot] = edge_of_group[g];
    }
  }

  // Faces, loops and uses, in input order.
  std::map<std::pair<int, int>, std::uint32_t> sides_index;
  out.faces.reserve(in.faces.size());
  std::vector<EdgeUseId> use_of_slot(use_total);
  slot = 0;
  for (const MeshFace& f : in.faces) {
    auto [it, fresh] = sides_index.try_emplace({f.front, f.back}, 0);
    if (fresh) {
      it->second = ed.intern_sides(f.front < 0 ? VolumeId() : out.volumes[f.front],
                                   f.back < 0 ? VolumeId() : out.volumes[f.back], out.group);
    }
    const FaceId face = ed.new_face(it->second);
    out.faces.push_back(face);
    for (const auto& loop : f.loops) {
      EdgeUseId first, prev;
      for (std::size_t k = 0; k < loop.size(); ++k, ++slot) {
        const EdgeId e = edge_of_slot[slot];
        const bool reversed = out.vertices[loop[k]] != m.start_of(e);
        const EdgeUseId u = ed.new_use(e, reversed, face);
        use_of_slot[slot] = u;
        if (prev.is_valid())
          ed.set_next(prev, u);
        else
          first = u;
        prev = u;
      }
      ed.set_next(prev, first);
      ed.add_loop(face, first);
    }
  }

  // Radial cycles: uses in input order, then angular order where three or more meet.
  std::vector<EdgeUseId> cycle;
  FaceNormals normals;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const EdgeId e = edge_of_group[g];
    cycle.clear();
    for (std::size_t i = groups[g].first; i < groups[g].second; ++i) {
      if (sides[i].slot != kInvalidIndex) cycle.push_back(use_of_slot[sides[i].slot]);
    }
    ed.set_radial_cycle(e, cycle);
    if (cycle.size() >= 3) ed.radial_sort(e, &normals);
  }
  return out;
}

MeshInput solid_input(std::vector<Vec3> positions, std::vector<std::vector<std::uint32_t>> faces) {
  MeshInput in;
  in.positions = std::move(positions);
  in.volumes = 1;
  in.faces.reserve(faces.size());
  for (auto& f : faces) in.faces.push_back(MeshFace{{std::move(f)}, -1, 0});
  return in;
}

}  // namespace cellforge::inline topo
