// The 12 Euler operators of seed 003, each with its check. Loop splicing notation:
// for a use u, "prev u" and "next u" are its neighbours in its loop; a strut is an
// edge whose two uses follow each other in one loop (out to a vertex and back).
#include <algorithm>

#include "cellforge/topo/operators.h"
#include "topo/model_editor.h"
#include "topo/operators_common.h"

namespace cellforge::inline topo {

using ops::require_live;

// ---------------------------------------------------------------- mvsf / kvsf

Status can_mvsf(const Model& m, GroupId g) {
  CF_CHECK(require_live(m, g, "mvsf: group"));
  if (m.face_slots() + 1 >= Model::kMaxFaces) return precondition("mvsf: too many faces");
  return Status::Ok();
}

Result<VertexFace> mvsf(Model& m, GroupId g, Vec3 position) {
  CF_CHECK(can_mvsf(m, g));
  ModelEditor ed(m);
  const VertexId v = ed.new_vertex(g, position);
  const FaceId f = ed.new_face(ed.intern_sides(VolumeId(), VolumeId(), g));
  ed.append_loop(f, ed.new_point_loop(v));
  return VertexFace{v, f};
}

Status can_kvsf(const Model& m, VertexId v, FaceId f) {
  CF_CHECK(require_live(m, v, "kvsf: vertex"));
  CF_CHECK(require_live(m, f, "kvsf: face"));
  const LoopId l = m.outer_loop(f);
  if (m.next_loop(l).is_valid() || !m.is_point_loop(l) || m.point_loop_vertex(l) != v) {
    return precondition("kvsf: face " + f.str() + " must have a single point loop at " + v.str());
  }
  if (m.front_volume(f).is_valid() || m.back_volume(f).is_valid()) {
    return precondition("kvsf: face " + f.str() + " bounds a volume");
  }
  return Status::Ok();
}

Status kvsf(Model& m, VertexId v, FaceId f) {
  CF_CHECK(can_kvsf(m, v, f));
  ModelEditor ed(m);
  ed.free_loop(m.outer_loop(f));
  ed.free_face(f);
  ed.free_vertex(v);
  return Status::Ok();
}

// ---------------------------------------------------------------- mev / kev

Status can_mev(const Model& m, LoopId l, VertexId v) {
  CF_CHECK(require_live(m, l, "mev: loop"));
  CF_CHECK(require_live(m, v, "mev: vertex"));
  if (!ops::on_loop(m, l, v)) {
    return precondition("mev: vertex " + v.str() + " is not on loop " + l.str());
  }
  if (!ops::room_for_edges(m, 1)) return precondition("mev: too many edges");
  return Status::Ok();
}

Result<EdgeVertex> mev(Model& m, LoopId l, VertexId v, Vec3 position) {
  CF_CHECK(can_mev(m, l, v));
  ModelEditor ed(m);
  const FaceId f = m.face_of(l);
  const bool point = m.is_point_loop(l);
  const EdgeUseId before = point ? EdgeUseId() : ops::first_use_to(m, l, v);
  if (point) ed.set_loop_first(l, EdgeUseId());  // clears v's point-loop mark
  const VertexId w = ed.new_vertex(m.group_of(v), position);
  const EdgeId e = ed.new_edge(v, w);
  const EdgeUseId out = ed.new_use(e, false, f);
  const EdgeUseId back = ed.new_use(e, true, f);
  ed.set_next(out, back);
  if (point) {
    ed.set_next(back, out);
    ed.set_loop_first(l, out);
  } else {
    ed.set_next(back, m.loop_next(before));
    ed.set_next(before, out);
  }
  ed.radial_insert(out);
  ed.radial_insert(back);
  return EdgeVertex{e, w};
}

Status can_kev(const Model& m, EdgeId e, VertexId v) {
  CF_CHECK(require_live(m, e, "kev: edge"));
  CF_CHECK(require_live(m, v, "kev: vertex"));
  if (m.start_of(e) != v && m.end_of(e) != v) {
    return precondition("kev: vertex " + v.str() + " is not an end of edge " + e.str());
  }
  if (m.degree(v) != 1) {
    return precondition("kev: vertex " + v.str() + " has " + std::to_string(m.degree(v)) +
                        " edges (must have only " + e.str() + ")");
  }
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  if (uses.empty()) return Status::Ok();
  if (uses.size() != 2 || (m.loop_next(uses[0]) != uses[1] && m.loop_next(uses[1]) != uses[0])) {
    return precondition("kev: edge " + e.str() +
                        " is not a strut (its two uses must follow each other in one loop)");
  }
  const VertexId w = m.start_of(e) == v ? m.end_of(e) : m.start_of(e);
  if (m.loop_length(m.loop_of(uses[0])) == 2 && m.degree(w) != 1) {
    return precondition("kev: loop " + m.loop_of(uses[0]).str() + " would become a point loop at " +
                        w.str() + ", which has other edges");
  }
  return Status::Ok();
}

Status kev(Model& m, EdgeId e, VertexId v) {
  CF_CHECK(can_kev(m, e, v));
  ModelEditor ed(m);
  const VertexId w = m.start_of(e) == v ? m.end_of(e) : m.start_of(e);
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  LoopId to_point;
  if (!uses.empty()) {
    const EdgeUseId in = m.use_end(uses[0]) == v ? uses[0] : uses[1];  // w -> v
    const EdgeUseId out = m.loop_next(in);                             // v -> w
    const LoopId l = m.loop_of(in);
    if (m.loop_length(l) == 2) {
      to_point = l;
    } else {
      const EdgeUseId after = m.loop_next(out);
      ed.set_next(m.loop_prev(in), after);
      if (m.loop_first(l) == in || m.loop_first(l) == out) ed.set_loop_first(l, after);
    }
    for (EdgeUseId u : uses) {
      ed.free_use(u);
    }
  }
  ed.free_edge(e);
  ed.free_vertex(v);
  if (to_point.is_valid()) ed.set_point_loop(to_point, w);
  return Status::Ok();
}

// ---------------------------------------------------------------- mef / kef

Status can_mef(const Model& m, LoopId l, VertexId v1, VertexId v2) {
  CF_CHECK(require_live(m, l, "mef: loop"));
  CF_CHECK(require_live(m, v1, "mef: vertex"));
  CF_CHECK(require_live(m, v2, "mef: vertex"));
  if (v1 == v2) return precondition("mef: the two vertices are both " + v1.str());
  if (m.is_point_loop(l)) return precondition("mef: loop " + l.str() + " is a point loop");
  for (VertexId v : {v1, v2}) {
    if (!ops::on_loop(m, l, v)) {
      return precondition("mef: vertex " + v.str() + " is not on loop " + l.str());
    }
  }
  if (!ops::room_for_edges(m, 1)) return precondition("mef: too many edges");
  if (m.face_slots() + 1 >= Model::kMaxFaces) return precondition("mef: too many faces");
  return Status::Ok();
}

Result<EdgeFace> mef(Model& m, LoopId l, VertexId v1, VertexId v2) {
  CF_CHECK(can_mef(m, l, v1, v2));
  ModelEditor ed(m);
  const FaceId f = m.face_of(l);
  const EdgeUseId s1 = ops::first_use_from(m, l, v1);
  const EdgeUseId s2 = ops::first_use_from(m, l, v2);
  const EdgeUseId p1 = m.loop_prev(s1), p2 = m.loop_prev(s2);
  const EdgeId e = ed.new_edge(v1, v2);
  const FaceId g = ed.new_face(ed.rec(f).sides);
  const EdgeUseId n1 = ed.new_use(e, false, f);  // v1 -> v2, stays in l
  const EdgeUseId n2 = ed.new_use(e, true, g);   // v2 -> v1, closes the new loop
  ed.set_next(p1, n1);
  ed.set_next(n1, s2);
  ed.set_next(p2, n2);
  ed.set_next(n2, s1);
  ed.set_loop_first(l, n1);
  const LoopId nl = ed.new_loop(n2);
  ed.append_loop(g, nl);
  ed.assign_face(nl, g);
  ed.radial_insert(n1);
  ed.radial_insert(n2);
  return EdgeFace{e, g};
}

Status can_kef(const Model& m, EdgeId e, FaceId f) {
  CF_CHECK(require_live(m, e, "kef: edge"));
  CF_CHECK(require_live(m, f, "kef: face"));
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  if (uses.size() != 2) {
    return precondition("kef: edge " + e.str() + " has " + std::to_string(uses.size()) +
                        " uses (must have 2)");
  }
  const FaceId a = m.face_of(uses[0]), b = m.face_of(uses[1]);
  if (a == b) return precondition("kef: both uses of edge " + e.str() + " are in face " + a.str());
  if (a != f && b != f) {
    return precondition("kef: face " + f.str() + " is not a face of edge " + e.str());
  }
  const FaceId keep = a == f ? b : a;
  if (m.front_volume(f) != m.front_volume(keep) || m.back_volume(f) != m.back_volume(keep)) {
    return precondition("kef: faces " + f.str() + " and " + keep.str() +
                        " bound different volumes");
  }
  if (m.is_reversed(uses[0]) == m.is_reversed(uses[1])) {
    return precondition("kef: faces " + a.str() + " and " + b.str() + " use edge " + e.str() +
                        " in the same direction");
  }
  const EdgeUseId dying = a == f ? uses[0] : uses[1];
  if (m.loop_of(dying) != m.outer_loop(f)) {
    return precondition("kef: edge " + e.str() + " is not on the outer loop of face " + f.str());
  }
  return Status::Ok();
}

Status kef(Model& m, EdgeId e, FaceId f) {
  CF_CHECK(can_kef(m, e, f));
  ModelEditor ed(m);
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  const EdgeUseId d = m.face_of(uses[0]) == f ? uses[0] : uses[1];
  const EdgeUseId k = d == uses[0] ? uses[1] : uses[0];
  const FaceId keep = m.face_of(k);
  const LoopId lk = m.loop_of(k), ld = m.outer_loop(f);
  const EdgeUseId pk = m.loop_prev(k), pd = m.loop_prev(d);
  const EdgeUseId nk = m.loop_next(k), nd = m.loop_next(d);
  ed.set_next(pk, nd);
  ed.set_next(pd, nk);
  ed.set_loop_first(lk, pk);
  ed.assign_face(lk, keep);
  // f's inner loops move to the surviving face.
  while (m.next_loop(ld).is_valid()) {
    const LoopId inner = m.next_loop(ld);
    ed.remove_loop(f, inner);
    ed.append_loop(keep, inner);
    ed.assign_face(inner, keep);
  }
  for (EdgeUseId u : uses) {
    ed.free_use(u);
  }
  ed.free_edge(e);
  ed.free_loop(ld);
  ed.free_face(f);
  return Status::Ok();
}

// ---------------------------------------------------------------- kemr / mekr

Status can_kemr(const Model& m, EdgeUseId u) {
  CF_CHECK(require_live(m, u, "kemr: edge use"));
  const EdgeId e = m.edge_of(u);
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  if (uses.size() != 2) {
    return precondition("kemr: edge " + e.str() + " has " + std::to_string(uses.size()) +
                        " uses (must have 2)");
  }
  const EdgeUseId w = uses[0] == u ? uses[1] : uses[0];
  if (m.loop_of(w) != m.loop_of(u)) {
    return precondition("kemr: the two uses of edge " + e.str() + " are in different loops");
  }
  // A side of the split with no uses left becomes a point loop at a vertex, which
  // must then have no other edge.
  if (m.loop_next(u) == w && m.degree(m.use_end(u)) != 1) {
    return precondition("kemr: vertex " + m.use_end(u).str() +
                        " would carry a point loop but has other edges");
  }
  if (m.loop_next(w) == u && m.degree(m.use_start(u)) != 1) {
    return precondition("kemr: vertex " + m.use_start(u).str() +
                        " would carry a point loop but has other edges");
  }
  return Status::Ok();
}

Result<LoopId> kemr(Model& m, EdgeUseId u) {
  CF_CHECK(can_kemr(m, u));
  ModelEditor ed(m);
  const EdgeId e = m.edge_of(u);
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  const EdgeUseId w = uses[0] == u ? uses[1] : uses[0];
  const LoopId l = m.loop_of(u);
  const FaceId f = m.face_of(u);
  const EdgeUseId nu = m.loop_next(u), nw = m.loop_next(w);
  const EdgeUseId pu = m.loop_prev(u), pw = m.loop_prev(w);
  const VertexId ring_point = m.use_end(u), rest_point = m.use_start(u);
  LoopId ring;
  if (nu != w) {
    ed.set_next(pw, nu);
    ring = ed.new_loop(nu);
  }
  if (nw != u) {
    ed.set_next(pu, nw);
    ed.set_loop_first(l, nw);
  }
  ed.free_use(u);
  ed.free_use(w);
  ed.free_edge(e);
  if (!ring.is_valid()) ring = ed.new_point_loop(ring_point);
  if (nw == u) ed.set_point_loop(l, rest_point);
  ed.append_loop(f, ring);
  return ring;
}

Status can_mekr(const Model& m, LoopId l1, VertexId v1, LoopId l2, VertexId v2) {
  CF_CHECK(require_live(m, l1, "mekr: loop"));
  CF_CHECK(require_live(m, l2, "mekr: loop"));
  CF_CHECK(require_live(m, v1, "mekr: vertex"));
  CF_CHECK(require_live(m, v2, "mekr: vertex"));
  if (l1 == l2) return precondition("mekr: both loops are " + l1.str());
  if (m.face_of(l1) != m.face_of(l2)) {
    return precondition("mekr: loops " + l1.str() + " and " + l2.str() +
                        " belong to different faces");
  }
  if (m.outer_loop(m.face_of(l2)) == l2) {
    return precondition("mekr: loop " + l2.str() + " is an outer loop (must be inner)");
  }
  if (v1 == v2) return precondition("mekr: the two vertices are both " + v1.str());
  if (!ops::on_loop(m, l1, v1)) {
    return precondition("mekr: vertex " + v1.str() + " is not on loop " + l1.str());
  }
  if (!ops::on_loop(m, l2, v2)) {
    return precondition("mekr: vertex " + v2.str() + " is not on loop " + l2.str());
  }
  if (!ops::room_for_edges(m, 1)) return precondition("mekr: too many edges");
  return Status::Ok();
}

Result<EdgeId> mekr(Model& m, LoopId l1, VertexId v1, LoopId l2, VertexId v2) {
  CF_CHECK(can_mekr(m, l1, v1, l2, v2));
  ModelEditor ed(m);
  const FaceId f = m.face_of(l1);
  const bool point1 = m.is_point_loop(l1), point2 = m.is_point_loop(l2);
  const EdgeUseId a = point1 ? EdgeUseId() : ops::first_use_to(m, l1, v1);
  const EdgeUseId b = point2 ? EdgeUseId() : ops::first_use_from(m, l2, v2);
  const EdgeUseId pb = point2 ? EdgeUseId() : m.loop_prev(b);
  ed.remove_loop(f, l2);
  ed.free_loop(l2);  // clears v2's point-loop mark
  if (point1) ed.set_loop_first(l1, EdgeUseId());
  const EdgeId e = ed.new_edge(v1, v2);
  const EdgeUseId n1 = ed.new_use(e, false, f);  // v1 -> v2
  const EdgeUseId n2 = ed.new_use(e, true, f);   // v2 -> v1
  const EdgeUseId after = point1 ? n1 : m.loop_next(a);
  if (point2) {
    ed.set_next(n1, n2);
  } else {
    ed.set_next(n1, b);
    ed.set_next(pb, n2);
  }
  ed.set_next(n2, after);
  if (point1)
    ed.set_loop_first(l1, n1);
  else
    ed.set_next(a, n1);
  ed.radial_insert(n1);
  ed.radial_insert(n2);
  return e;
}

// ---------------------------------------------------------------- kfmrh / mfkrh

Status can_kfmrh(const Model& m, FaceId keep, FaceId dying) {
  CF_CHECK(require_live(m, keep, "kfmrh: face"));
  CF_CHECK(require_live(m, dying, "kfmrh: face"));
  if (keep == dying) return precondition("kfmrh: both faces are " + keep.str());
  if (m.inner_loop_count(dying) != 0) {
    return precondition("kfmrh: face " + dying.str() + " has inner loops");
  }
  if (m.group_of(keep) != m.group_of(dying) || m.front_volume(keep) != m.front_volume(dying) ||
      m.back_volume(keep) != m.back_volume(dying)) {
    return precondition("kfmrh: faces " + keep.str() + " and " + dying.str() +
                        " differ in group or volumes");
  }
  return Status::Ok();
}

Result<LoopId> kfmrh(Model& m, FaceId keep, FaceId dying) {
  CF_CHECK(can_kfmrh(m, keep, dying));
  ModelEditor ed(m);
  const LoopId l = ed.take_outer_loop(dying);
  ed.append_loop(keep, l);
  ed.assign_face(l, keep);
  ed.free_face(dying);
  return l;
}

Status can_mfkrh(const Model& m, LoopId l) {
  CF_CHECK(require_live(m, l, "mfkrh: loop"));
  if (m.face_slots() + 1 >= Model::kMaxFaces) return precondition("mfkrh: too many faces");
  if (m.outer_loop(m.face_of(l)) == l) {
    return precondition("mfkrh: loop " + l.str() + " is the outer loop of face " +
                        m.face_of(l).str());
  }
  return Status::Ok();
}

Result<FaceId> mfkrh(Model& m, LoopId l) {
  CF_CHECK(can_mfkrh(m, l));
  ModelEditor ed(m);
  const FaceId f = m.face_of(l);
  const FaceId g = ed.new_face(ed.rec(f).sides);
  ed.remove_loop(f, l);
  ed.append_loop(g, l);
  ed.assign_face(l, g);
  return g;
}

// ---------------------------------------------------------------- semv / jekv

Status can_semv(const Model& m, EdgeId e) {
  CF_CHECK(require_live(m, e, "semv: edge"));
  if (!ops::room_for_edges(m, 1, m.use_count(e))) return precondition("semv: too many edges");
  return Status::Ok();
}

Result<EdgeVertex> semv(Model& m, EdgeId e, Vec3 position) {
  CF_CHECK(can_semv(m, e));
  ModelEditor ed(m);
  const VertexId b = m.end_of(e);
  const VertexId w = ed.new_vertex(m.group_of(e), position);
  const std::vector<EdgeUseId> uses = ops::radial_uses(m, e);
  ed.move_end({e, 1}, w);
  const EdgeId e2 = ed.new_edge(w, b);
  std::vector<EdgeUseId> cycle;  // e2's uses, in the radial order of e's
  for (EdgeUseId u : uses) {
    const bool reversed = m.is_reversed(u);
    const EdgeUseId u2 = ed.new_use(e2, reversed, m.face_of(u));
    if (!reversed) {  // u: a -> w, then u2: w -> b
      ed.set_next(u2, m.loop_next(u));
      ed.set_next(u, u2);
    } else {  // u2: b -> w, then u: w -> a
      ed.set_next(m.loop_prev(u), u2);
      ed.set_next(u2, u);
    }
    cycle.push_back(u2);
  }
  ed.set_radial_cycle(e2, cycle);
  return EdgeVertex{e2, w};
}

Status can_jekv(const Model& m, EdgeId dying, VertexId v) {
  CF_CHECK(require_live(m, dying, "jekv: edge"));
  CF_CHECK(require_live(m, v, "jekv: vertex"));
  if (m.start_of(dying) != v && m.end_of(dying) != v) {
    return precondition("jekv: vertex " + v.str() + " is not an end of edge " + dying.str());
  }
  const std::vector<EdgeEnd> ends = ops::ends_at(m, v);
  if (ends.size() != 2) {
    return precondition("jekv: vertex " + v.str() + " has " + std::to_string(ends.size()) +
                        " edges (must have 2)");
  }
  const EdgeId keep = ends[0].edge == dying ? ends[1].edge : ends[0].edge;
  const VertexId x = m.start_of(dying) == v ? m.end_of(dying) : m.start_of(dying);
  const VertexId y = m.start_of(keep) == v ? m.end_of(keep) : m.start_of(keep);
  if (x == y) {
    return precondition("jekv: edges " + dying.str() + " and " + keep.str() +
                        " join the same vertices; the joined edge would be a loop at " + x.str());
  }
  if (m.use_count(dying) != m.use_count(keep)) {
    return precondition("jekv: edges " + dying.str() + " and " + keep.str() +
                        " have different numbers of uses");
  }
  for (EdgeUseId d : ops::radial_uses(m, dying)) {
    const EdgeUseId n = m.use_end(d) == v ? m.loop_next(d) : m.loop_prev(d);
    if (m.edge_of(n) != keep) {
      return precondition("jekv: use " + d.str() + " of edge " + dying.str() +
                          " does not continue along edge " + keep.str() + " at " + v.str());
    }
  }
  return Status::Ok();
}

Status jekv(Model& m, EdgeId dying, VertexId v) {
  CF_CHECK(can_jekv(m, dying, v));
  ModelEditor ed(m);
  const std::vector<EdgeEnd> ends = ops::ends_at(m, v);
  const EdgeEnd keep_end = ends[0].edge == dying ? ends[1] : ends[0];
  const VertexId x = m.start_of(dying) == v ? m.end_of(dying) : m.start_of(dying);
  for (EdgeUseId d : ops::radial_uses(m, dying)) {
    const LoopId l = m.loop_of(d);
    const EdgeUseId p = m.loop_prev(d);
    const EdgeUseId n = m.loop_next(d);
    ed.set_next(p, n);
    if (m.loop_first(l) == d) ed.set_loop_first(l, n);
    ed.free_use(d);
  }
  ed.free_edge(dying);
  ed.move_end(keep_end, x);
  ed.free_vertex(v);
  ed.radial_sort(keep_end.edge);
  return Status::Ok();
}

}  // namespace cellforge::inline topo
