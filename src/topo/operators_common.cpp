#include "topo/operators_common.h"

namespace cellforge::inline topo::ops {

EdgeUseId first_use_from(const Model& m, LoopId l, VertexId v) {
  for (EdgeUseId u : loop_uses(m, l)) {
    if (m.use_start(u) == v) return u;
  }
  return {};
}

EdgeUseId first_use_to(const Model& m, LoopId l, VertexId v) {
  for (EdgeUseId u : loop_uses(m, l)) {
    if (m.use_end(u) == v) return u;
  }
  return {};
}

bool on_loop(const Model& m, LoopId l, VertexId v) {
  if (m.is_point_loop(l)) return m.point_loop_vertex(l) == v;
  return first_use_from(m, l, v).is_valid();
}

void radial_uses(const Model& m, EdgeId e, std::vector<EdgeUseId>& out) {
  const auto radial = m.radial(e);
  out.assign(radial.begin(), radial.end());
}

std::vector<EdgeUseId> radial_uses(const Model& m, EdgeId e) {
  std::vector<EdgeUseId> out;
  radial_uses(m, e, out);
  return out;
}

std::vector<EdgeUseId> loop_uses(const Model& m, LoopId l) {
  const auto uses = m.uses_of(l);
  return {uses.begin(), uses.end()};
}

std::vector<EdgeEnd> ends_at(const Model& m, VertexId v) {
  const auto ends = m.ends_around(v);
  return {ends.begin(), ends.end()};
}

EdgeId edge_between(const Model& m, VertexId a, VertexId b) {
  for (EdgeEnd end : ends_at(m, a)) {
    if (m.vertex_of(end.edge, 1 - end.end) == b) return end.edge;
  }
  return {};
}

VolumeId side_after(const Model& m, EdgeUseId u) {
  const FaceId f = m.face_of(u);
  return m.is_reversed(u) ? m.back_volume(f) : m.front_volume(f);
}

VolumeId side_before(const Model& m, EdgeUseId u) {
  const FaceId f = m.face_of(u);
  return m.is_reversed(u) ? m.front_volume(f) : m.back_volume(f);
}

EdgeUseId inconsistent_wedge(const Model& m, const std::vector<EdgeUseId>& cycle) {
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    const EdgeUseId a = cycle[i], b = cycle[(i + 1) % cycle.size()];
    if (side_after(m, a) != side_before(m, b)) return a;
  }
  return {};
}

}  // namespace cellforge::inline topo::ops
