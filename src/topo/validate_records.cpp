// Check "records": every stored reference names a live entity of the right kind
// and the back-references that a record implies agree.
#include <cstdint>

#include "cellforge/topo/dedupe.h"
#include "topo/validate_checks.h"

namespace cellforge::inline topo::checks {

void records(const Model& m, Violations& out) {
  auto fail = [&](std::string msg) { out.push_back({"records", std::move(msg)}); };
  for (VertexId v : m.vertices()) {
    if (!m.is_live(m.group_of(v))) fail(v.str() + " names dead group " + m.group_of(v).str());
    const EdgeEnd end = m.first_end(v);
    if (end.edge.is_valid() && (!m.is_live(end.edge) || m.vertex_of(end.edge, end.end) != v)) {
      fail(v.str() + " starts its edge cycle at " + end.edge.str() + " which does not end at it");
    }
    const LoopId pl = m.point_loop(v);
    if (pl.is_valid() && (!m.is_live(pl) || !m.is_point_loop(pl) || m.point_loop_vertex(pl) != v)) {
      fail(v.str() + " names " + pl.str() + " as its point loop, which is not");
    }
  }
  for (EdgeId e : m.edges()) {
    for (int end = 0; end < 2; ++end) {
      if (!m.is_live(m.vertex_of(e, end))) fail(e.str() + " ends at a dead vertex");
    }
    if (m.start_of(e) == m.end_of(e)) fail(e.str() + " starts and ends at " + m.start_of(e).str());
    for (int end = 0; end < 2; ++end) {
      const EdgeEnd n = m.next_end_around({e, end});
      if (!m.is_live(n.edge)) fail(e.str() + " links its vertex cycle to a dead edge");
    }
    const EdgeUseId u = m.first_use(e);
    if (u.is_valid() && (!m.is_live(u) || m.edge_of(u) != e)) {
      fail(e.str() + " starts its radial cycle at " + u.str() + ", not one of its uses");
    }
  }
  // A use names its edge by its slot: slot 2e or 2e + 1 of a live edge, or an
  // overflow slot (of a spare pair, not an edge) whose end record names one.
  for (EdgeUseId u : m.edge_uses()) {
    const bool spare = !m.is_live(EdgeId(u.value / 2));
    if (m.in_overflow_slot(u) != spare) {
      fail(u.str() + (spare ? " sits in a slot of no edge" : " is marked as an overflow use"));
      return;
    }
    const FaceId f = m.face_of(u);
    if (m.is_live(f) && ((!m.is_in_place(u) && !m.may_hold_unplaced_uses(f)) ||
                         (m.in_overflow_slot(u) && !m.may_hold_overflow_uses(f)))) {
      fail(u.str() + " is not in slot 2 * edge + direction, but " + f.str() +
           " is not marked as holding such a use");
      return;
    }
    if (!m.is_live(m.edge_of(u))) {
      fail(u.str() + " names dead edge " + m.edge_of(u).str());
      return;
    }
    if (!m.is_live(m.radial_next(u))) {
      fail(u.str() + " links its radial cycle to a dead use");
      return;
    }
  }
  for (EdgeUseId u : m.edge_uses()) {
    if (!m.is_live(m.face_of(u))) fail(u.str() + " names dead face " + m.face_of(u).str());
    if (!m.is_live(m.loop_next(u))) fail(u.str() + " links its loop to a dead use");
  }
  for (LoopId l : m.loops()) {
    if (m.is_point_loop(l)) {
      const VertexId v = m.point_loop_vertex(l);
      if (!m.is_live(v) || m.point_loop(v) != l) {
        fail(l.str() + " is a point loop at " + v.str() + ", which does not name it back");
      }
    } else if (!m.is_live(m.loop_first(l))) {
      fail(l.str() + " starts at a dead use");
    }
  }
  for (FaceId f : m.faces()) {
    if (!m.is_live(m.outer_loop(f))) fail(f.str() + " has no live outer loop");
    if (!m.is_live(m.group_of(f))) fail(f.str() + " names a dead group");
    for (VolumeId c : {m.front_volume(f), m.back_volume(f)}) {
      if (c.is_valid() && !m.is_live(c)) fail(f.str() + " names dead volume " + c.str());
      if (c.is_valid() && m.is_live(c) && m.group_of(c) != m.group_of(f)) {
        fail(f.str() + " in " + m.group_of(f).str() + " bounds " + c.str() + " of another group");
      }
    }
  }
  // A 3-cell is bounded by faces; one that no face names bounds nothing.
  std::uint32_t slots = 0;
  for (VolumeId c : m.volumes()) slots = c.value + 1;
  std::vector<char> bounded(slots, 0);
  for (FaceId f : m.faces()) {
    for (VolumeId c : {m.front_volume(f), m.back_volume(f)}) {
      if (c.is_valid() && c.value < slots) bounded[c.value] = 1;
    }
  }
  for (VolumeId c : m.volumes()) {
    if (!m.is_live(m.group_of(c))) fail(c.str() + " names a dead group");
    if (!bounded[c.value]) fail(c.str() + " is bounded by no face");
  }
}

void face_marks(const Model& m, Violations& out) {
  auto fail = [&](std::string msg) { out.push_back({"marks", std::move(msg)}); };
  std::vector<std::uint32_t> edges, vertices;
  for (FaceId f : m.faces()) {
    edges.clear();
    vertices.clear();
    bool unplaced = false, overflow = false;
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) {
        vertices.push_back(m.point_loop_vertex(l).value);
        continue;
      }
      const EdgeUseId first = m.loop_first(l);
      EdgeUseId u = first;
      do {
        edges.push_back(m.edge_of(u).value);
        vertices.push_back(m.use_start(u).value);
        unplaced = unplaced || !m.is_in_place(u);
        overflow = overflow || m.in_overflow_slot(u);
        u = m.loop_next(u);
      } while (u != first);
    }
    const std::uint32_t* edge = find_repeat(edges);
    const std::uint32_t* vertex = find_repeat(vertices);
    if ((edge || vertex) && !m.may_repeat_elements(f)) {
      fail(f.str() + " names " + (edge ? EdgeId(*edge).str() : VertexId(*vertex).str()) +
           " twice but is not marked as repeating an element");
    }
    if (m.being_edited()) continue;  // marks may be set where not needed
    if (!edge && !vertex && m.may_repeat_elements(f)) {
      fail(f.str() + " is marked as repeating an element but names each edge and vertex once");
    }
    if (unplaced != m.may_hold_unplaced_uses(f) || overflow != m.may_hold_overflow_uses(f)) {
      auto yes = [](bool x) { return std::string(x ? "yes" : "no"); };
      fail(f.str() + "'s marks are not exact: marked as holding uses out of place " +
           yes(m.may_hold_unplaced_uses(f)) + ", in overflow slots " +
           yes(m.may_hold_overflow_uses(f)) + "; holds them " + yes(unplaced) + ", " +
           yes(overflow));
    }
  }
}

}  // namespace cellforge::inline topo::checks
