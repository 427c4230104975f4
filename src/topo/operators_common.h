// Shared helpers of the operator files: id checks with uniform error text and the
// small loop walks the operators need.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

// Returns the error of a failed check from the enclosing function.
#define CF_CHECK(expr)             \
  do {                             \
    if (Status s_ = (expr); !s_) { \
      return s_.error();           \
    }                              \
  } while (0)

namespace cellforge::inline topo::ops {

template <class IdT>
Status require_live(const Model& m, IdT id, const char* role) {
  if (!m.is_live(id)) {
    return Error{ErrorCode::kInvalidId,
                 std::string(role) + " " + id.str() + " is not a live entity"};
  }
  return Status::Ok();
}

// True when `edges` new edges and `uses` new uses of existing edges fit: edge
// slots, spare pairs for overflow uses included, stay below Model::kMaxEdges even
// if every such use takes a spare pair of its own (a free slot counts as taken).
inline bool room_for_edges(const Model& m, std::size_t edges, std::size_t uses = 0) {
  return m.edge_slots() + edges + uses < Model::kMaxEdges;
}

// First use of loop l (in loop order) that starts / ends at v; invalid if none.
EdgeUseId first_use_from(const Model& m, LoopId l, VertexId v);
EdgeUseId first_use_to(const Model& m, LoopId l, VertexId v);
// True when v is on l (a use starts there, or l is v's point loop).
bool on_loop(const Model& m, LoopId l, VertexId v);
// The uses of e's radial cycle, from first_use(e).
std::vector<EdgeUseId> radial_uses(const Model& m, EdgeId e);
void radial_uses(const Model& m, EdgeId e, std::vector<EdgeUseId>& out);  // reuses out
// The uses of loop l, in loop order.
std::vector<EdgeUseId> loop_uses(const Model& m, LoopId l);
// The edge ends at v, in cycle order.
std::vector<EdgeEnd> ends_at(const Model& m, VertexId v);
// An edge joining a and b, or invalid.
EdgeId edge_between(const Model& m, VertexId a, VertexId b);

// Going round an edge, the volumes on the two sides of the wedge that follows /
// precedes use u: a use's front looks towards increasing angle exactly when the
// use runs along the edge (radial.cpp).
VolumeId side_after(const Model& m, EdgeUseId u);
VolumeId side_before(const Model& m, EdgeUseId u);
// The first use of `cycle` (in radial order) whose following wedge is bounded by
// different volumes on its two sides; invalid when every wedge agrees.
EdgeUseId inconsistent_wedge(const Model& m, const std::vector<EdgeUseId>& cycle);

}  // namespace cellforge::inline topo::ops
