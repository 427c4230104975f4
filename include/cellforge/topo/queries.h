// The 9 adjacency queries of seed 000 (V->V, V->E, V->F, E->V, E->E, E->F, F->V,
// F->E, F->F). Each walks only the local cycles of its argument (on a model no
// operator is editing) and lists every element once. Orders (deterministic,
// first occurrence wins):
//   edges_of(v)      the vertex cycle from first_end(v)
//   vertices_of(v)   the other ends of edges_of(v), in that order
//   faces_of(v)      for each edge of v in cycle order, the faces of its uses that
//                    leave v, in radial order; then the face whose point loop is v
//   vertices_of(e)   start, end
//   edges_of(e)      edges_of(start) then edges_of(end), e itself excluded
//   faces_of(e)      the radial cycle from first_use(e) (angular order)
//   edges_of(f)      loop order, outer loop first
//   vertices_of(f)   loop order, outer loop first (point loops included)
//   faces_of(f)      for each edge of f in loop order, the other faces of its
//                    radial cycle in radial order; faces meeting f only at a
//                    vertex are not neighbours
// The out-parameter forms clear `out` and fill it, so a caller can reuse storage.
#pragma once

#include <vector>

#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

void vertices_of(const Model& m, VertexId v, std::vector<VertexId>& out);
void edges_of(const Model& m, VertexId v, std::vector<EdgeId>& out);
void faces_of(const Model& m, VertexId v, std::vector<FaceId>& out);
void vertices_of(const Model& m, EdgeId e, std::vector<VertexId>& out);
void edges_of(const Model& m, EdgeId e, std::vector<EdgeId>& out);
void faces_of(const Model& m, EdgeId e, std::vector<FaceId>& out);
void vertices_of(const Model& m, FaceId f, std::vector<VertexId>& out);
void edges_of(const Model& m, FaceId f, std::vector<EdgeId>& out);
void faces_of(const Model& m, FaceId f, std::vector<FaceId>& out);

template <class Out, class In>
std::vector<Out> query(const Model& m, In x) {
  std::vector<Out> out;
  if constexpr (std::is_same_v<Out, VertexId>)
    vertices_of(m, x, out);
  else if constexpr (std::is_same_v<Out, EdgeId>)
    edges_of(m, x, out);
  else
    faces_of(m, x, out);
  return out;
}

}  // namespace cellforge::inline topo
