// Check "wedge": going round an edge in radial order, the wedge between two
// consecutive faces is one region, so the face sides that look into it must name
// the same volume (or none). A use's front looks towards increasing angle exactly
// when the use runs along the edge (radial.cpp), so for use a followed by use b:
//   side after a  = a reversed ? back(a) : front(a)
//   side before b = b reversed ? front(b) : back(b)
// On a manifold edge of a solid this is the usual orientation rule (its two uses
// run opposite ways); a face with a free edge cannot bound a volume.
#include "topo/operators_common.h"
#include "topo/validate_checks.h"

namespace cellforge::inline topo::checks {

void wedges(const Model& m, Violations& out) {
  std::vector<EdgeUseId> uses;
  for (EdgeId e : m.edges()) {
    ops::radial_uses(m, e, uses);
    for (std::size_t i = 0; i < uses.size(); ++i) {
      const EdgeUseId a = uses[i], b = uses[(i + 1) % uses.size()];
      using ops::side_after, ops::side_before;
      if (side_after(m, a) != side_before(m, b)) {
        out.push_back({"wedge", "around " + e.str() + ", the wedge between faces " +
                                    m.face_of(a).str() + " and " + m.face_of(b).str() +
                                    " is bounded by " + side_after(m, a).str() +
                                    " on one side and " + side_before(m, b).str() +
                                    " on the other"});
      }
    }
  }
}

}  // namespace cellforge::inline topo::checks
