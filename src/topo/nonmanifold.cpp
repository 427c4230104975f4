// Non-manifold operators (DESIGN.md): groups, volumes, isolated vertices, wire
// edges, faces on existing vertices, gluing two faces into one shared face, and
// splitting / merging coincident edges and vertices.
#include <algorithm>
#include <map>
#include <set>

#include "cellforge/topo/operators.h"
#include "topo/model_editor.h"
#include "topo/operators_common.h"

namespace cellforge::inline topo {

using ops::require_live;

// ---------------------------------------------------------------- groups

GroupId make_group(Model& m, std::string name) { return ModelEditor(m).new_group(std::move(name)); }

Status can_kill_group(const Model& m, GroupId g) {
  CF_CHECK(require_live(m, g, "kill_group: group"));
  // The group index names what g holds without a scan of the model.
  const auto holds = [&](auto range) -> Status {
    for (auto id : range) return precondition("kill_group: group " + g.str() + " holds " + id.str());
    return Status::Ok();
  };
  CF_CHECK(holds(m.vertices(g)));
  CF_CHECK(holds(m.faces(g)));
  CF_CHECK(holds(m.edges(g)));
  CF_CHECK(holds(m.volumes(g)));
  return Status::Ok();
}

Status kill_group(Model& m, GroupId g) {
  CF_CHECK(can_kill_group(m, g));
  ModelEditor(m).free_group(g);
  return Status::Ok();
}

// ---------------------------------------------------------------- volumes

Status can_make_volume(const Model& m, GroupId g, const std::vector<FaceSide>& sides) {
  CF_CHECK(require_live(m, g, "make_volume: group"));
  if (sides.empty()) return precondition("make_volume: no face sides given");
  std::set<std::pair<std::uint32_t, bool>> seen;
  // Closed and consistently oriented: seen from the volume, every edge is run as
  // often forwards as backwards by the bounding sides.
  std::map<EdgeId, int> balance;
  for (const FaceSide& s : sides) {
    CF_CHECK(require_live(m, s.face, "make_volume: face"));
    if (m.group_of(s.face) != g) {
      return precondition("make_volume: face " + s.face.str() + " is not in group " + g.str());
    }
    if (!seen.insert({s.face.value, s.front}).second) {
      return precondition("make_volume: face side " + s.face.str() + " given twice");
    }
    const VolumeId taken = s.front ? m.front_volume(s.face) : m.back_volume(s.face);
    if (taken.is_valid()) {
      return precondition("make_volume: the " + std::string(s.front ? "front" : "back") +
                          " of face " + s.face.str() + " already bounds " + taken.str());
    }
    for (LoopId l : m.loops_of(s.face)) {
      for (EdgeUseId u : ops::loop_uses(m, l)) {
        balance[m.edge_of(u)] += (m.is_reversed(u) != s.front) ? -1 : 1;
      }
    }
  }
  for (const auto& [e, b] : balance) {
    if (b != 0) {
      return precondition("make_volume: the sides do not close at edge " + e.str() + " (run " +
                          std::to_string(b) + " more times one way than the other)");
    }
  }
  return Status::Ok();
}

Result<VolumeId> make_volume(Model& m, GroupId g, const std::vector<FaceSide>& sides) {
  CF_CHECK(can_make_volume(m, g, sides));
  ModelEditor ed(m);
  const VolumeId c = ed.new_volume(g);
  for (const FaceSide& s : sides) {
    if (s.front)
      ed.set_sides(s.face, c, m.back_volume(s.face));
    else
      ed.set_sides(s.face, m.front_volume(s.face), c);
  }
  return c;
}

std::vector<FaceSide> sides_of(const Model& m, VolumeId c) {
  std::vector<FaceSide> out;
  for (FaceId f : m.faces()) {
    if (m.front_volume(f) == c) out.push_back({f, true});
    if (m.back_volume(f) == c) out.push_back({f, false});
  }
  return out;
}

Status can_kill_volume(const Model& m, VolumeId c) {
  return require_live(m, c, "kill_volume: volume");
}

Status kill_volume(Model& m, VolumeId c) {
  CF_CHECK(can_kill_volume(m, c));
  ModelEditor ed(m);
  for (const FaceSide& s : sides_of(m, c)) {
    if (s.front)
      ed.set_sides(s.face, VolumeId(), m.back_volume(s.face));
    else
      ed.set_sides(s.face, m.front_volume(s.face), VolumeId());
  }
  ed.free_volume(c);
  return Status::Ok();
}

// ---------------------------------------------------------------- vertices and wires

Status can_make_vertex(const Model& m, GroupId g) {
  return require_live(m, g, "make_vertex: group");
}

Result<VertexId> make_vertex(Model& m, GroupId g, Vec3 position) {
  CF_CHECK(can_make_vertex(m, g));
  return ModelEditor(m).new_vertex(g, position);
}

Status can_kill_vertex(const Model& m, VertexId v) {
  CF_CHECK(require_live(m, v, "kill_vertex: vertex"));
  if (m.degree(v) != 0 || m.point_loop(v).is_valid()) {
    return precondition("kill_vertex: vertex " + v.str() + " is not isolated");
  }
  return Status::Ok();
}

Status kill_vertex(Model& m, VertexId v) {
  CF_CHECK(can_kill_vertex(m, v));
  ModelEditor(m).free_vertex(v);
  return Status::Ok();
}

namespace {

Status check_can_take_edges(const Model& m, VertexId v, const char* op) {
  if (m.point_loop(v).is_valid()) {
    return precondition(std::string(op) + ": vertex " + v.str() + " carries point loop " +
                        m.point_loop(v).str());
  }
  return Status::Ok();
}

}  // namespace

Status can_make_wire_edge(const Model& m, VertexId a, VertexId b) {
  CF_CHECK(require_live(m, a, "make_wire_edge: vertex"));
  CF_CHECK(require_live(m, b, "make_wire_edge: vertex"));
  if (a == b) return precondition("make_wire_edge: both ends are " + a.str());
  if (m.group_of(a) != m.group_of(b)) {
    return precondition("make_wire_edge: vertices " + a.str() + " and " + b.str() +
                        " are in different groups");
  }
  CF_CHECK(check_can_take_edges(m, a, "make_wire_edge"));
  CF_CHECK(check_can_take_edges(m, b, "make_wire_edge"));
  if (!ops::room_for_edges(m, 1)) return precondition("make_wire_edge: too many edges");
  return Status::Ok();
}

Result<EdgeId> make_wire_edge(Model& m, VertexId a, VertexId b) {
  CF_CHECK(can_make_wire_edge(m, a, b));
  return ModelEditor(m).new_edge(a, b);
}

Status can_kill_wire_edge(const Model& m, EdgeId e) {
  CF_CHECK(require_live(m, e, "kill_wire_edge: edge"));
  if (!m.is_wire(e)) {
    return precondition("kill_wire_edge: edge " + e.str() + " has " +
                        std::to_string(m.use_count(e)) + " uses (a wire edge has none)");
  }
  return Status::Ok();
}

Status kill_wire_edge(Model& m, EdgeId e) {
  CF_CHECK(can_kill_wire_edge(m, e));
  ModelEditor(m).free_edge(e);
  return Status::Ok();
}

// ---------------------------------------------------------------- faces

Status can_make_face(const Model& m, const FaceSpec& spec) {
  if (spec.loops.empty()) return precondition("make_face: no loops");
  GroupId g;
  std::size_t uses = 0;
  for (std::size_t li = 0; li < spec.loops.size(); ++li) {
    const auto& loop = spec.loops[li];
    const std::string at = "make_face: loop " + std::to_string(li);
    if (loop.size() < 3) return precondition(at + " has fewer than 3 vertices");
    uses += loop.size();
    for (std::size_t k = 0; k < loop.size(); ++k) {
      CF_CHECK(require_live(m, loop[k], "make_face: vertex"));
      if (!g.is_valid()) g = m.group_of(loop[k]);
      if (m.group_of(loop[k]) != g) {
        return precondition(at + ": vertex " + loop[k].str() + " is not in group " + g.str());
      }
      if (loop[k] == loop[(k + 1) % loop.size()]) {
        return precondition(at + " repeats vertex " + loop[k].str() + " consecutively");
      }
      CF_CHECK(check_can_take_edges(m, loop[k], "make_face"));
    }
  }
  if (!ops::room_for_edges(m, uses, uses)) return precondition("make_face: too many edges");
  if (m.face_slots() + 1 >= Model::kMaxFaces) return precondition("make_face: too many faces");
  return Status::Ok();
}

Result<FaceId> make_face(Model& m, const FaceSpec& spec) {
  CF_CHECK(can_make_face(m, spec));
  ModelEditor ed(m);
  const GroupId g = m.group_of(spec.loops[0][0]);
  const FaceId f = ed.new_face(ed.intern_sides(VolumeId(), VolumeId(), g));
  std::vector<EdgeUseId> made;
  for (const auto& loop : spec.loops) {
    EdgeUseId first, prev;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const VertexId a = loop[k], b = loop[(k + 1) % loop.size()];
      EdgeId e = ops::edge_between(m, a, b);
      if (!e.is_valid()) e = ed.new_edge(a, b);
      const EdgeUseId u = ed.new_use(e, m.start_of(e) != a, f);
      made.push_back(u);
      if (prev.is_valid())
        ed.set_next(prev, u);
      else
        first = u;
      prev = u;
    }
    ed.set_next(prev, first);
    ed.append_loop(f, ed.new_loop(first));
  }
  for (EdgeUseId u : made) ed.radial_insert(u);
  return f;
}

Status can_kill_face(const Model& m, FaceId f) {
  CF_CHECK(require_live(m, f, "kill_face: face"));
  if (m.front_volume(f).is_valid() || m.back_volume(f).is_valid()) {
    return precondition("kill_face: face " + f.str() + " bounds a volume");
  }
  return Status::Ok();
}

Status kill_face(Model& m, FaceId f, KillFaceOptions options) {
  CF_CHECK(can_kill_face(m, f));
  ModelEditor ed(m);
  std::vector<EdgeId> edges;
  std::vector<VertexId> verts;
  std::vector<LoopId> loops;
  for (LoopId l : m.loops_of(f)) loops.push_back(l);
  for (LoopId l : loops) {
    if (m.is_point_loop(l)) verts.push_back(m.point_loop_vertex(l));
    for (EdgeUseId u : ops::loop_uses(m, l)) {
      edges.push_back(m.edge_of(u));
      verts.push_back(m.use_start(u));
      ed.free_use(u);
    }
    ed.free_loop(l);
  }
  ed.free_face(f);
  if (options.kill_bare_edges) {
    for (EdgeId e : edges) {
      if (m.is_live(e) && m.is_wire(e)) ed.free_edge(e);
    }
  }
  if (options.kill_bare_vertices) {
    for (VertexId v : verts) {
      if (m.is_live(v) && m.degree(v) == 0 && !m.point_loop(v).is_valid()) ed.free_vertex(v);
    }
  }
  return Status::Ok();
}

// ---------------------------------------------------------------- glue / unglue

Status can_glue_faces(const Model& m, FaceId a, FaceId b) {
  CF_CHECK(require_live(m, a, "glue_faces: face"));
  CF_CHECK(require_live(m, b, "glue_faces: face"));
  if (a == b) return precondition("glue_faces: both faces are " + a.str());
  for (FaceId f : {a, b}) {
    if (m.front_volume(f).is_valid() || !m.back_volume(f).is_valid()) {
      return precondition("glue_faces: face " + f.str() +
                          " must have a volume on its back and none in front");
    }
    if (m.inner_loop_count(f) != 0)
      return precondition("glue_faces: face " + f.str() + " has inner loops");
  }
  if (m.group_of(a) != m.group_of(b)) {
    return precondition("glue_faces: faces " + a.str() + " and " + b.str() +
                        " are in different groups");
  }
  // b must run over a's edges, each once and the other way.
  const std::vector<EdgeUseId> ua = ops::loop_uses(m, m.outer_loop(a));
  const std::vector<EdgeUseId> ub = ops::loop_uses(m, m.outer_loop(b));
  std::map<EdgeId, int> runs;
  for (EdgeUseId u : ua) runs[m.edge_of(u)] += m.is_reversed(u) ? -1 : 1;
  for (EdgeUseId u : ub) runs[m.edge_of(u)] += m.is_reversed(u) ? -1 : 1;
  if (ua.size() != ub.size() || ua.empty()) {
    return precondition("glue_faces: faces " + a.str() + " and " + b.str() + " differ in size");
  }
  for (const auto& [e, n] : runs) {
    if (n != 0) {
      return precondition("glue_faces: faces " + a.str() + " and " + b.str() +
                          " do not run over edge " + e.str() + " in opposite directions");
    }
  }
  return Status::Ok();
}

Status glue_faces(Model& m, FaceId a, FaceId b) {
  CF_CHECK(can_glue_faces(m, a, b));
  ModelEditor ed(m);
  const VolumeId front = m.back_volume(b);
  const LoopId lb = m.outer_loop(b);
  for (EdgeUseId u : ops::loop_uses(m, lb)) {
    ed.free_use(u);
  }
  ed.free_loop(lb);
  ed.free_face(b);
  ed.set_sides(a, front, m.back_volume(a));
  return Status::Ok();
}

Status can_unglue_face(const Model& m, FaceId f) {
  CF_CHECK(require_live(m, f, "unglue_face: face"));
  if (m.face_slots() + 1 >= Model::kMaxFaces) return precondition("unglue_face: too many faces");
  if (!m.front_volume(f).is_valid() || !m.back_volume(f).is_valid()) {
    return precondition("unglue_face: face " + f.str() + " does not have volumes on both sides");
  }
  std::size_t uses = 0;  // each gets a twin on its edge
  for (LoopId l : m.loops_of(f)) uses += m.loop_length(l);
  if (!ops::room_for_edges(m, 0, uses)) return precondition("unglue_face: too many edges");
  return Status::Ok();
}

Result<FaceId> unglue_face(Model& m, FaceId f) {
  CF_CHECK(can_unglue_face(m, f));
  ModelEditor ed(m);
  const FaceId g = ed.new_face(ed.intern_sides(VolumeId(), m.front_volume(f), m.group_of(f)));
  ed.set_sides(f, VolumeId(), m.back_volume(f));
  std::vector<EdgeUseId> made;
  for (LoopId l : m.loops_of(f)) {
    const std::vector<EdgeUseId> uses = ops::loop_uses(m, l);
    std::vector<EdgeUseId> rev;
    for (auto it = uses.rbegin(); it != uses.rend(); ++it) {
      rev.push_back(ed.new_use(m.edge_of(*it), !m.is_reversed(*it), g));
    }
    for (std::size_t i = 0; i < rev.size(); ++i) ed.set_next(rev[i], rev[(i + 1) % rev.size()]);
    ed.append_loop(g, ed.new_loop(rev[0]));
    made.insert(made.end(), rev.begin(), rev.end());
  }
  for (EdgeUseId u : made) ed.radial_insert(u);
  return g;
}

// ---------------------------------------------------------------- split / merge edges

Status can_split_edge(const Model& m, EdgeId e, const std::vector<EdgeUseId>& moving) {
  CF_CHECK(require_live(m, e, "split_edge: edge"));
  if (moving.empty()) return precondition("split_edge: no uses to move");
  std::set<EdgeUseId> seen;
  for (EdgeUseId u : moving) {
    CF_CHECK(require_live(m, u, "split_edge: use"));
    if (m.edge_of(u) != e)
      return precondition("split_edge: use " + u.str() + " is not a use of " + e.str());
    if (!seen.insert(u).second) return precondition("split_edge: use " + u.str() + " given twice");
  }
  if (seen.size() == m.use_count(e)) {
    return precondition("split_edge: all uses of " + e.str() + " would move");
  }
  // Each part keeps its radial order; every wedge of each must still be one region.
  std::vector<EdgeUseId> parts[2];
  for (EdgeUseId u : ops::radial_uses(m, e)) parts[seen.count(u) ? 1 : 0].push_back(u);
  for (const auto& part : parts) {
    if (const EdgeUseId bad = ops::inconsistent_wedge(m, part); bad.is_valid()) {
      return precondition("split_edge: after the split, face " + m.face_of(bad).str() +
                          " would face different volumes across one wedge at " + e.str());
    }
  }
  if (!ops::room_for_edges(m, 1, moving.size())) return precondition("split_edge: too many edges");
  return Status::Ok();
}

Result<EdgeId> split_edge(Model& m, EdgeId e, const std::vector<EdgeUseId>& moving) {
  CF_CHECK(can_split_edge(m, e, moving));
  ModelEditor ed(m);
  const EdgeId e2 = ed.new_edge(m.start_of(e), m.end_of(e));
  for (EdgeUseId u : moving) ed.move_use(u, e2);  // each takes a slot of e2
  ed.radial_sort(e2);
  return e2;
}

Status can_merge_edges(const Model& m, EdgeId keep, EdgeId dying) {
  CF_CHECK(require_live(m, keep, "merge_edges: edge"));
  CF_CHECK(require_live(m, dying, "merge_edges: edge"));
  if (keep == dying) return precondition("merge_edges: both edges are " + keep.str());
  const bool same = m.start_of(keep) == m.start_of(dying) && m.end_of(keep) == m.end_of(dying);
  const bool flipped = m.start_of(keep) == m.end_of(dying) && m.end_of(keep) == m.start_of(dying);
  if (!same && !flipped) {
    return precondition("merge_edges: edges " + keep.str() + " and " + dying.str() +
                        " do not join the same vertices");
  }
  // The merged radial cycle, in angular order, must keep every wedge one region.
  // (The check reads directions relative to keep; a flipped use is judged by a
  // stand-in with its direction bit as it will be after the merge.)
  std::vector<EdgeUseId> all = ops::radial_uses(m, keep);
  const std::vector<EdgeUseId> more = ops::radial_uses(m, dying);
  if (!ops::room_for_edges(m, 0, more.size())) return precondition("merge_edges: too many edges");
  if (flipped && !more.empty()) {
    Model trial = m;  // O(model): flipped merges are rare; check on a copy
    ModelEditor ed(trial);
    for (EdgeUseId u : more) ed.move_use(u, keep, /*flip=*/true);
    ed.radial_sort(keep);
    if (const EdgeUseId bad = ops::inconsistent_wedge(trial, ops::radial_uses(trial, keep));
        bad.is_valid()) {
      return precondition("merge_edges: merging " + dying.str() + " into " + keep.str() +
                          " would leave face " + trial.face_of(bad).str() +
                          " facing different volumes across one wedge");
    }
    return Status::Ok();
  }
  all.insert(all.end(), more.begin(), more.end());
  if (!all.empty()) {
    all = sort_radially(m, keep, std::move(all));
    if (const EdgeUseId bad = ops::inconsistent_wedge(m, all); bad.is_valid()) {
      return precondition("merge_edges: merging " + dying.str() + " into " + keep.str() +
                          " would leave face " + m.face_of(bad).str() +
                          " facing different volumes across one wedge");
    }
  }
  return Status::Ok();
}

Status merge_edges(Model& m, EdgeId keep, EdgeId dying) {
  CF_CHECK(can_merge_edges(m, keep, dying));
  ModelEditor ed(m);
  const bool flipped = m.start_of(keep) != m.start_of(dying);
  for (EdgeUseId u : ops::radial_uses(m, dying)) ed.move_use(u, keep, flipped);
  ed.radial_sort(keep);
  ed.free_edge(dying);
  return Status::Ok();
}

// ---------------------------------------------------------------- split / merge vertices

Status can_split_vertex(const Model& m, VertexId v, const std::vector<EdgeEnd>& moving) {
  CF_CHECK(require_live(m, v, "split_vertex: vertex"));
  if (moving.empty()) return precondition("split_vertex: no edge ends to move");
  std::set<std::pair<std::uint32_t, int>> move;
  for (EdgeEnd end : moving) {
    CF_CHECK(require_live(m, end.edge, "split_vertex: edge"));
    if (end.end < 0 || end.end > 1 || m.vertex_of(end.edge, end.end) != v) {
      return precondition("split_vertex: edge " + end.edge.str() + " end " +
                          std::to_string(end.end) + " is not at " + v.str());
    }
    if (!move.insert({end.edge.value, end.end}).second) {
      return precondition("split_vertex: edge end " + end.edge.str() + " given twice");
    }
  }
  if (move.size() == m.degree(v))
    return precondition("split_vertex: all edges of " + v.str() + " would move");
  // No loop may pass through v from a moving edge to a staying one.
  for (EdgeEnd end : ops::ends_at(m, v)) {
    for (EdgeUseId u : ops::radial_uses(m, end.edge)) {
      if (m.use_end(u) != v) continue;
      const EdgeUseId n = m.loop_next(u);
      const int n_end = m.is_reversed(n) ? 1 : 0;
      const bool a = move.count({end.edge.value, end.end}) != 0;
      const bool b = move.count({m.edge_of(n).value, n_end}) != 0;
      if (a != b) {
        return precondition("split_vertex: the loop of face " + m.face_of(u).str() +
                            " passes through " + v.str() + " from edge " + end.edge.str() +
                            " to edge " + m.edge_of(n).str() + ", across the split");
      }
    }
  }
  return Status::Ok();
}

Result<VertexId> split_vertex(Model& m, VertexId v, const std::vector<EdgeEnd>& moving) {
  CF_CHECK(can_split_vertex(m, v, moving));
  ModelEditor ed(m);
  const VertexId w = ed.new_vertex(m.group_of(v), m.position(v));
  for (EdgeEnd end : moving) ed.move_end(end, w);
  return w;
}

Status can_merge_vertices(const Model& m, VertexId keep, VertexId dying) {
  CF_CHECK(require_live(m, keep, "merge_vertices: vertex"));
  CF_CHECK(require_live(m, dying, "merge_vertices: vertex"));
  if (keep == dying) return precondition("merge_vertices: both vertices are " + keep.str());
  if (!(m.position(keep) == m.position(dying))) {
    return precondition("merge_vertices: vertices " + keep.str() + " and " + dying.str() +
                        " are at different positions");
  }
  if (m.group_of(keep) != m.group_of(dying)) {
    return precondition("merge_vertices: vertices " + keep.str() + " and " + dying.str() +
                        " are in different groups");
  }
  if (ops::edge_between(m, keep, dying).is_valid()) {
    return precondition("merge_vertices: edge " + ops::edge_between(m, keep, dying).str() +
                        " joins " + keep.str() + " and " + dying.str());
  }
  for (VertexId v : {keep, dying}) {
    if (m.point_loop(v).is_valid()) {
      return precondition("merge_vertices: vertex " + v.str() + " carries point loop " +
                          m.point_loop(v).str());
    }
  }
  return Status::Ok();
}

Status merge_vertices(Model& m, VertexId keep, VertexId dying) {
  CF_CHECK(can_merge_vertices(m, keep, dying));
  ModelEditor ed(m);
  for (EdgeEnd end : ops::ends_at(m, dying)) ed.move_end(end, keep);
  ed.free_vertex(dying);
  return Status::Ok();
}

}  // namespace cellforge::inline topo
