// The 9 adjacency queries: local walks of the vertex cycle, the radial cycle and
// the loops (orders documented in queries.h).
#include "cellforge/topo/queries.h"

#include <algorithm>

#include "cellforge/topo/dedupe.h"

namespace cellforge::inline topo {

namespace {

// The radial cycle of e, from its first use round to it.
template <class Fn>
void for_each_radial(const Model& m, EdgeId e, Fn fn) {
  for (EdgeUseId u : m.radial(e)) fn(u);
}

}  // namespace

void edges_of(const Model& m, VertexId v, std::vector<EdgeId>& out) {
  out.clear();
  m.for_each_end_around(v, [&](const Model::VertexEnd& x) { out.push_back(x.end.edge); });
}

void vertices_of(const Model& m, VertexId v, std::vector<VertexId>& out) {
  out.clear();
  m.for_each_end_around(v, [&](const Model::VertexEnd& x) { out.push_back(x.other); });
  dedupe_stable(out);
}

void faces_of(const Model& m, VertexId v, std::vector<FaceId>& out) {
  out.clear();
  // Every loop through v leaves it once per visit, so the uses starting at v name
  // each face touching v along an edge without collecting it twice per corner.
  m.for_each_end_around(v, [&](const Model::VertexEnd& x) {
    for_each_radial(m, x.end.edge, [&](EdgeUseId u) {
      if (m.is_reversed(u) == (x.end.end == 1)) out.push_back(m.face_of(u));
    });
  });
  if (const LoopId l = m.point_loop(v); l.is_valid()) out.push_back(m.face_of(l));
  dedupe_stable(out);
}

void vertices_of(const Model& m, EdgeId e, std::vector<VertexId>& out) {
  out.clear();
  out.push_back(m.start_of(e));
  out.push_back(m.end_of(e));
}

void edges_of(const Model& m, EdgeId e, std::vector<EdgeId>& out) {
  out.clear();
  for (int end = 0; end < 2; ++end) {
    m.for_each_end_around(m.vertex_of(e, end), [&](const Model::VertexEnd& x) {
      if (x.end.edge != e) out.push_back(x.end.edge);
    });
  }
  dedupe_stable(out);
}

void faces_of(const Model& m, EdgeId e, std::vector<FaceId>& out) {
  out.clear();
  for_each_radial(m, e, [&](EdgeUseId u) { out.push_back(m.face_of(u)); });
  dedupe_stable(out);
}

// A face that is not marked as repeating an element gives each vertex and each
// edge once: its answer needs no dedupe (model.h, kRepeatFace).
void vertices_of(const Model& m, FaceId f, std::vector<VertexId>& out) {
  out.clear();
  const bool repeats = m.may_repeat_elements(f);
  m.for_each_face_vertex(f, [&](VertexId v) { out.push_back(v); });
  if (repeats) dedupe_stable(out);
}

void edges_of(const Model& m, FaceId f, std::vector<EdgeId>& out) {
  out.clear();
  const bool repeats = m.may_repeat_elements(f);
  m.for_each_face_use(f, [&](const Model::FaceUse& x) { out.push_back(x.edge); });
  if (repeats) dedupe_stable(out);
}

void faces_of(const Model& m, FaceId f, std::vector<FaceId>& out) {
  out.clear();
  m.for_each_face_use(f, [&](const Model::FaceUse& x) {
    for (EdgeUseId w = m.radial_next(x.use); w != x.use; w = m.radial_next(w)) {
      if (const FaceId g = m.face_of(w); g != f) out.push_back(g);
    }
  });
  dedupe_stable(out);
}

}  // namespace cellforge::inline topo
