// Angular order of the uses around an edge.
//
// A use's face leaves the edge in the direction d = N x t, where N is the Newell
// normal of the face's outer loop and t the use's direction (the face lies on the
// left of its uses seen from the front). Uses are ordered by the angle of d about
// the edge axis T = end - start, right-handed, starting from the first use. All of
// it is exact (geom/predicates.h): N, t and d are expansions of the input doubles.
#include <algorithm>
#include <map>

#include "cellforge/geom/predicates.h"
#include "topo/model_editor.h"

namespace cellforge::inline topo {

namespace {

ExactVec3 interior_direction(const Model& m, EdgeUseId u) {
  const std::vector<Vec3> pts = m.loop_points(m.outer_loop(m.face_of(u)));
  const ExactVec3 n = exact_newell_normal(pts);
  const ExactVec3 t = exact_sub(m.position(m.use_end(u)), m.position(m.use_start(u)));
  return exact_cross(n, t);
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
  RadialOrder(const Model& m, EdgeId e, const std::vector<EdgeUseId>& uses)
      : axis_(exact_sub(m.position(m.end_of(e)), m.position(m.start_of(e)))), m_(m) {
    entries_.reserve(uses.size());
    const std::vector<std::uint32_t> twin = twins(m, uses);
    for (std::size_t i = 0; i < uses.size(); ++i) {
      ExactVec3 d = twin[i] == i ? interior_direction(m, uses[i]) : entries_[twin[i]].dir;
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
    if (radial_less(axis_, d0_, a.dir, b.dir)) return true;
    if (radial_less(axis_, d0_, b.dir, a.dir)) return false;
    return !m_.is_reversed(a.use) && m_.is_reversed(b.use);
  }

  std::vector<Entry>& entries() { return entries_; }
  bool has_reference() const { return has_ref_; }

 private:
  ExactVec3 axis_;
  ExactVec3 d0_;
  bool has_ref_ = false;
  const Model& m_;
  std::vector<Entry> entries_;
};

}  // namespace

std::vector<EdgeUseId> sort_radially(const Model& m, EdgeId e, std::vector<EdgeUseId> uses) {
  RadialOrder order(m, e, uses);
  if (!order.has_reference()) return uses;
  const auto& entries = order.entries();
  std::vector<std::uint32_t> at(entries.size());  // sorted by index: entries are heavy
  for (std::size_t i = 0; i < at.size(); ++i) at[i] = static_cast<std::uint32_t>(i);
  std::stable_sort(at.begin(), at.end(), [&](std::uint32_t a, std::uint32_t b) {
    return order.less(entries[a], entries[b]);
  });
  for (std::size_t i = 0; i < at.size(); ++i) uses[i] = entries[at[i]].use;
  return uses;
}

bool radially_ordered(const Model& m, EdgeId e, const std::vector<EdgeUseId>& cycle) {
  if (cycle.size() <= 2) return true;
  // A rotation of a sorted sequence: at most one place where, going round the
  // cycle, the angle decreases.
  RadialOrder order(m, e, cycle);
  if (!order.has_reference()) return true;
  const auto& entries = order.entries();
  int descents = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (order.less(entries[(i + 1) % entries.size()], entries[i])) ++descents;
  }
  return descents <= 1;
}

}  // namespace cellforge::inline topo
