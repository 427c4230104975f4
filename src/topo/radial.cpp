// Angular order of the uses around an edge.
//
// A use's face leaves the edge in the direction d = N x t, where N is the Newell
// normal of the face's outer loop and t the use's direction (the face lies on the
// left of its uses seen from the front). Uses are ordered by the angle of d about
// the edge axis T = end - start, right-handed, starting from the first use. All of
// it is exact (geom/predicates.h): N, t and d are expansions of the input doubles.
#include <algorithm>

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
};

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
    for (EdgeUseId u : uses) {
      ExactVec3 d = interior_direction(m, u);
      const bool degenerate = is_zero(d);
      entries_.push_back({u, std::move(d), degenerate});
    }
    const auto ref = std::find_if(entries_.begin(), entries_.end(),
                                  [](const Entry& x) { return !x.degenerate; });
    if (ref != entries_.end()) d0_ = ref->dir;
    has_ref_ = ref != entries_.end();
  }

  bool less(const Entry& a, const Entry& b) const {
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
  auto& entries = order.entries();
  std::stable_sort(entries.begin(), entries.end(),
                   [&](const Entry& a, const Entry& b) { return order.less(a, b); });
  for (std::size_t i = 0; i < entries.size(); ++i) uses[i] = entries[i].use;
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
