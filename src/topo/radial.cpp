// Angular order of the uses around an edge.
//
// A use's face leaves the edge in the direction d = N x t, where N is the Newell
// normal of the face's outer loop and t the use's direction (the face lies on the
// left of its uses seen from the front). Uses are ordered by the angle of d about
// the edge axis T = end - start, right-handed, starting from the first use. All of
// it is exact (geom/predicates.h): N, t and d are expansions of the input doubles.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>

#include "cellforge/geom/predicates.h"
#include "topo/model_editor.h"

namespace cellforge::inline topo {

namespace {

ExactVec3 interior_direction(const Model& m, EdgeUseId u, FaceNormals* normals) {
  const ExactVec3 t = exact_sub(m.position(m.use_end(u)), m.position(m.use_start(u)));
  if (normals) return exact_cross(normals->of(m, m.face_of(u)), t);
  const std::vector<Vec3> pts = m.loop_points(m.outer_loop(m.face_of(u)));
  return exact_cross(exact_newell_normal(pts), t);
}

bool is_zero(const ExactVec3& d) { return d.x.sign() == 0 && d.y.sign() == 0 && d.z.sign() == 0; }

struct Entry {
  EdgeUseId use;
  ExactVec3 dir;
  bool degenerate;
  std::uint32_t twin;  // the first entry of a face on the same vertex cycle, used the same way
};

// Uses of faces on the same vertex cycle (a stack of equal triangles), running the
// same way along the edge, leave it in the same direction: they are tied without
// the exact comparison, which would cost an expansion evaluation for each pair.
std::vector<std::uint32_t> twins(const Model& m, const std::vector<EdgeUseId>& uses) {
  std::map<std::pair<std::vector<std::uint32_t>, bool>, std::uint32_t> first;
  std::vector<std::uint32_t> out(uses.size());
  for (std::size_t i = 0; i < uses.size(); ++i) {
    std::vector<std::uint32_t> cycle;
    for (VertexId v : m.loop_vertices(m.outer_loop(m.face_of(uses[i])))) cycle.push_back(v.value);
    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
    out[i] = first.try_emplace({std::move(cycle), m.is_reversed(uses[i])},
                               static_cast<std::uint32_t>(i))
                 .first->second;
  }
  return out;
}

// Orders uses by angle from the reference direction d0. Where two faces leave the
// edge at the same angle (coincident faces), the one whose front looks towards
// increasing angle comes first: that is the use running along the axis (its front
// faces T x d exactly when it is not reversed), so the zero-width wedge between
// two glued faces lies between their fronts.
class RadialOrder {
 public:
  RadialOrder(const Model& m, EdgeId e, const std::vector<EdgeUseId>& uses, FaceNormals* normals)
      : axis_(exact_sub(m.position(m.end_of(e)), m.position(m.start_of(e)))), m_(m) {
    entries_.reserve(uses.size());
    const std::vector<std::uint32_t> twin = twins(m, uses);
    for (std::size_t i = 0; i < uses.size(); ++i) {
      ExactVec3 d = twin[i] == i ? interior_direction(m, uses[i], normals) : entries_[twin[i]].dir;
      const bool degenerate = is_zero(d);
      entries_.push_back({uses[i], std::move(d), degenerate, twin[i]});
    }
    const auto ref = std::find_if(entries_.begin(), entries_.end(),
                                  [](const Entry& x) { return !x.degenerate; });
    if (ref != entries_.end()) d0_ = ref->dir;
    has_ref_ = ref != entries_.end();
  }

  bool less(const Entry& a, const Entry& b) const {
    if (a.twin == b.twin) return false;
    if (a.degenerate || b.degenerate) return a.degenerate && !b.degenerate;
    if (angle_less(a.dir, b.dir)) return true;
    if (angle_less(b.dir, a.dir)) return false;
    return !m_.is_reversed(a.use) && m_.is_reversed(b.use);
  }
  bool angle_less(const ExactVec3& a, const ExactVec3& b) const {
    return radial_less(axis_, d0_, a, b);
  }
  bool reversed(const Entry& a) const { return m_.is_reversed(a.use); }

  std::vector<Entry>& entries() { return entries_; }
  bool has_reference() const { return has_ref_; }

 private:
  ExactVec3 axis_;
  ExactVec3 d0_;
  bool has_ref_ = false;
  const Model& m_;
  std::vector<Entry> entries_;
};

bool same_components(const Expansion& a, const Expansion& b) {
  const auto x = a.components(), y = b.components();
  return std::equal(x.begin(), x.end(), y.begin(), y.end());
}

bool same_direction(const ExactVec3& a, const ExactVec3& b) {
  return same_components(a.x, b.x) && same_components(a.y, b.y) && same_components(a.z, b.z);
}

std::size_t direction_hash(const ExactVec3& d) {
  std::size_t h = 0;
  for (const Expansion* c : {&d.x, &d.y, &d.z}) {
    for (double v : c->components()) h = h * 1000003u ^ std::hash<double>{}(v);
    h = h * 31u + 7u;
  }
  return h;
}

// The order of `less`, reached through the distinct directions: uses whose faces
// leave the edge in the same exact direction (copies of one face; 200,000 of them
// in one file) are ranked once instead of compared pairwise in exact arithmetic.
// Equal directions are found by equal components (the same computation on the same
// doubles); equal angles of different directions still tie through the ranks.
void sort_by_direction(const RadialOrder& order, std::vector<Entry>& entries) {
  std::vector<std::size_t> group(entries.size(), 0), reps;  // reps: an entry per direction
  std::unordered_map<std::size_t, std::vector<std::size_t>> by_hash;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].degenerate) continue;
    auto& bucket = by_hash[direction_hash(entries[i].dir)];
    std::size_t g = reps.size();
    for (std::size_t r : bucket) {
      if (same_direction(entries[reps[r]].dir, entries[i].dir)) {
        g = r;
        break;
      }
    }
    if (g == reps.size()) {
      bucket.push_back(g);
      reps.push_back(i);
    }
    group[i] = g;
  }
  std::vector<std::size_t> sorted(reps.size());
  for (std::size_t g = 0; g < sorted.size(); ++g) sorted[g] = g;
  std::stable_sort(sorted.begin(), sorted.end(), [&](std::size_t a, std::size_t b) {
    return order.angle_less(entries[reps[a]].dir, entries[reps[b]].dir);
  });
  std::vector<std::int64_t> rank(reps.size());
  std::int64_t r = 0;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    if (k > 0 && order.angle_less(entries[reps[sorted[k - 1]]].dir, entries[reps[sorted[k]]].dir))
      ++r;
    rank[sorted[k]] = r;
  }
  // Degenerate uses first (as `less` has them), then by angle, then the use running
  // along the axis first; stable otherwise.
  std::vector<std::pair<std::int64_t, std::size_t>> keyed(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    keyed[i] = {
        entries[i].degenerate ? -1 : 2 * rank[group[i]] + (order.reversed(entries[i]) ? 1 : 0), i};
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Entry> out;
  out.reserve(entries.size());
  for (const auto& [key, i] : keyed) out.push_back(std::move(entries[i]));
  entries = std::move(out);
}

}  // namespace

const ExactVec3& FaceNormals::of(const Model& m, FaceId f) {
  auto [it, fresh] = normals_.try_emplace(f.value);
  if (fresh) it->second = exact_newell_normal(m.loop_points(m.outer_loop(f)));
  return it->second;
}

std::vector<EdgeUseId> sort_radially(const Model& m, EdgeId e, std::vector<EdgeUseId> uses,
                                     FaceNormals* normals) {
  RadialOrder order(m, e, uses, normals);
  if (!order.has_reference()) return uses;
  auto& entries = order.entries();
  if (entries.size() > 16) {
    sort_by_direction(order, entries);
  } else {
    std::stable_sort(entries.begin(), entries.end(),
                     [&](const Entry& a, const Entry& b) { return order.less(a, b); });
  }
  for (std::size_t i = 0; i < entries.size(); ++i) uses[i] = entries[i].use;
  return uses;
}

bool radially_ordered(const Model& m, EdgeId e, const std::vector<EdgeUseId>& cycle,
                      FaceNormals* normals) {
  if (cycle.size() <= 2) return true;
  // A rotation of a sorted sequence: at most one place where, going round the
  // cycle, the angle decreases.
  RadialOrder order(m, e, cycle, normals);
  if (!order.has_reference()) return true;
  const auto& entries = order.entries();
  int descents = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (order.less(entries[(i + 1) % entries.size()], entries[i])) ++descents;
  }
  return descents <= 1;
}

}  // namespace cellforge::inline topo
