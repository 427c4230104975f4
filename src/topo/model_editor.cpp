// ModelEditor: allocation from free lists and the low-level linking of the two
// cycles (vertex -> edge ends, edge -> uses) and of loops into faces.
#include "topo/model_editor.h"

#include <cassert>

namespace cellforge {

template <class Rec>
std::uint32_t ModelEditor::take_slot(std::vector<Rec>& recs, int kind, std::uint32_t Rec::*link) {
  ++m_.live_[kind];
  std::uint32_t& head = m_.free_[kind];
  if (head != kInvalidIndex) {
    const std::uint32_t i = head;
    head = recs[i].*link;
    return i;
  }
  recs.emplace_back();
  return static_cast<std::uint32_t>(recs.size() - 1);
}

GroupId ModelEditor::new_group(std::string name) {
  for (std::uint32_t i = 0; i < m_.groups_.size(); ++i) {
    if (!m_.groups_[i].live) {
      m_.groups_[i] = Model::GroupRec{true, std::move(name), {}};
      ++m_.live_[Model::kGroup];
      return GroupId(i);
    }
  }
  m_.groups_.push_back(Model::GroupRec{true, std::move(name), {}});
  ++m_.live_[Model::kGroup];
  return GroupId(static_cast<std::uint32_t>(m_.groups_.size() - 1));
}

VertexId ModelEditor::new_vertex(GroupId g, Vec3 p) {
  const std::uint32_t i = take_slot(m_.vertices_, Model::kVertex, &VertexRec::first_end);
  m_.vertices_[i] = {kInvalidIndex, g.value};
  if (m_.positions_.size() <= i) m_.positions_.resize(i + 1);
  m_.positions_[i] = p;
  return VertexId(i);
}

EdgeId ModelEditor::new_edge(VertexId a, VertexId b) {
  const std::uint32_t i = take_slot(m_.edges_, Model::kEdge, &EdgeRec::first_use);
  m_.edges_[i] = {{a.value, b.value}, {kInvalidIndex, kInvalidIndex}, kInvalidIndex};
  link_end(a, {EdgeId(i), 0});
  link_end(b, {EdgeId(i), 1});
  return EdgeId(i);
}

EdgeUseId ModelEditor::new_use(EdgeId e, bool reversed, FaceId f) {
  const std::uint32_t i = take_slot(m_.uses_, Model::kUse, &UseRec::next);
  m_.uses_[i] = {(e.value << 1) | (reversed ? 1u : 0u), f.value, i, i};
  return EdgeUseId(i);
}

LoopId ModelEditor::new_point_loop(VertexId v) {
  const std::uint32_t i = take_slot(m_.loops_, Model::kLoop, &LoopRec::next);
  m_.loops_[i] = {kInvalidIndex, kInvalidIndex};
  set_point_loop(LoopId(i), v);
  return LoopId(i);
}

void ModelEditor::set_loop_first(LoopId l, EdgeUseId u) {
  if (rec(l).first != kInvalidIndex && m_.is_point_loop(l)) {
    VertexRec& vr = rec(m_.point_loop_vertex(l));
    if (vr.first_end == (l.value | kTagBit)) vr.first_end = kInvalidIndex;
  }
  rec(l).first = u.value;
}

void ModelEditor::set_point_loop(LoopId l, VertexId v) {
  assert(!m_.first_end(v).edge.is_valid());
  rec(l).first = v.value | kTagBit;
  rec(v).first_end = l.value | kTagBit;
}

LoopId ModelEditor::new_loop(EdgeUseId first) {
  const std::uint32_t i = take_slot(m_.loops_, Model::kLoop, &LoopRec::next);
  m_.loops_[i] = {first.value, kInvalidIndex};
  return LoopId(i);
}

FaceId ModelEditor::new_face(std::uint32_t sides) {
  const std::uint32_t i = take_slot(m_.faces_, Model::kFace, &FaceRec::first_loop);
  m_.faces_[i] = {kInvalidIndex, sides};
  if (i < m_.face_surface_.size()) m_.face_surface_[i] = kInvalidIndex;
  return FaceId(i);
}

VolumeId ModelEditor::new_volume(GroupId g) {
  const std::uint32_t i = take_slot(m_.volumes_, Model::kVolume, &Model::VolumeRec::next_free);
  m_.volumes_[i] = {g.value, kInvalidIndex};
  return VolumeId(i);
}

std::uint32_t ModelEditor::intern_sides(VolumeId front, VolumeId back, GroupId g) {
  const SidesRec want{front.value, back.value, g.value};
  for (std::uint32_t i = 0; i < m_.sides_.size(); ++i) {
    if (m_.sides_[i] == want) return i;
  }
  m_.sides_.push_back(want);
  return static_cast<std::uint32_t>(m_.sides_.size() - 1);
}

namespace {

template <class Rec>
void push_free(std::vector<Rec>& recs, std::uint32_t& head, std::uint32_t i,
               std::uint32_t Rec::*link) {
  recs[i].*link = head;
  head = i;
}

}  // namespace

void ModelEditor::free_vertex(VertexId v) {
  m_.vertices_[v.value].group = kDead;
  push_free(m_.vertices_, m_.free_[Model::kVertex], v.value, &VertexRec::first_end);
  --m_.live_[Model::kVertex];
}

void ModelEditor::free_edge(EdgeId e) {
  unlink_end(VertexId(rec(e).vertex[0]), {e, 0});
  unlink_end(VertexId(rec(e).vertex[1]), {e, 1});
  rec(e).vertex[0] = kDead;
  push_free(m_.edges_, m_.free_[Model::kEdge], e.value, &EdgeRec::first_use);
  --m_.live_[Model::kEdge];
}

void ModelEditor::free_use(EdgeUseId u) {
  rec(u).edge_dir = kDead;
  push_free(m_.uses_, m_.free_[Model::kUse], u.value, &UseRec::next);
  --m_.live_[Model::kUse];
}

void ModelEditor::free_loop(LoopId l) {
  if (m_.is_point_loop(l)) {
    VertexRec& vr = rec(m_.point_loop_vertex(l));
    if (vr.first_end == (l.value | kTagBit)) vr.first_end = kInvalidIndex;
  }
  rec(l).first = kDead;
  push_free(m_.loops_, m_.free_[Model::kLoop], l.value, &LoopRec::next);
  --m_.live_[Model::kLoop];
}

void ModelEditor::free_face(FaceId f) {
  rec(f).sides = kDead;
  if (f.value < m_.face_surface_.size()) m_.face_surface_[f.value] = kInvalidIndex;
  push_free(m_.faces_, m_.free_[Model::kFace], f.value, &FaceRec::first_loop);
  --m_.live_[Model::kFace];
}

void ModelEditor::free_volume(VolumeId c) {
  m_.volumes_[c.value].group = kDead;
  push_free(m_.volumes_, m_.free_[Model::kVolume], c.value, &Model::VolumeRec::next_free);
  --m_.live_[Model::kVolume];
}

void ModelEditor::free_group(GroupId g) {
  m_.groups_[g.value] = Model::GroupRec{false, {}, {}};
  --m_.live_[Model::kGroup];
}

void ModelEditor::link_end(VertexId v, EdgeEnd end) {
  VertexRec& vr = rec(v);
  const std::uint32_t code = Model::encode_end(end);
  std::uint32_t& next = rec(end.edge).next_end[end.end];
  assert(!m_.point_loop(v).is_valid());
  if (vr.first_end == kInvalidIndex) {
    vr.first_end = code;
    next = code;
    return;
  }
  // Insert after the first end: O(1), and the first end stays first.
  const EdgeEnd first = Model::decode_end(vr.first_end);
  std::uint32_t& first_next = rec(first.edge).next_end[first.end];
  next = first_next;
  first_next = code;
}

void ModelEditor::unlink_end(VertexId v, EdgeEnd end) {
  VertexRec& vr = rec(v);
  const std::uint32_t code = Model::encode_end(end);
  const std::uint32_t after = rec(end.edge).next_end[end.end];
  if (after == code) {  // the only end at v
    vr.first_end = kInvalidIndex;
    return;
  }
  EdgeEnd p = Model::decode_end(vr.first_end);
  while (rec(p.edge).next_end[p.end] != code) p = Model::decode_end(rec(p.edge).next_end[p.end]);
  rec(p.edge).next_end[p.end] = after;
  if (vr.first_end == code) vr.first_end = after;
}

void ModelEditor::move_end(EdgeEnd end, VertexId to) {
  unlink_end(VertexId(rec(end.edge).vertex[end.end]), end);
  rec(end.edge).vertex[end.end] = to.value;
  link_end(to, end);
}

void ModelEditor::radial_insert(EdgeUseId u) {
  const EdgeId e = m_.edge_of(u);
  EdgeRec& er = rec(e);
  if (er.first_use == kInvalidIndex) {
    er.first_use = u.value;
    rec(u).radial_next = u.value;
    return;
  }
  // Put u anywhere, then restore the angular order of the whole cycle.
  rec(u).radial_next = rec(EdgeUseId(er.first_use)).radial_next;
  rec(EdgeUseId(er.first_use)).radial_next = u.value;
  radial_sort(e);
}

void ModelEditor::radial_remove(EdgeUseId u) {
  const EdgeId e = m_.edge_of(u);
  EdgeRec& er = rec(e);
  if (rec(u).radial_next == u.value) {
    er.first_use = kInvalidIndex;
    return;
  }
  EdgeUseId p = u;
  while (m_.radial_next(p) != u) p = m_.radial_next(p);
  rec(p).radial_next = rec(u).radial_next;
  if (er.first_use == u.value) er.first_use = rec(u).radial_next;
  rec(u).radial_next = u.value;
}

void ModelEditor::radial_sort(EdgeId e) {
  const EdgeUseId first = m_.first_use(e);
  if (!first.is_valid()) return;
  std::vector<EdgeUseId> uses;
  EdgeUseId u = first;
  do {
    uses.push_back(u);
    u = m_.radial_next(u);
  } while (u != first);
  if (uses.size() <= 2) return;
  uses = sort_radially(m_, e, std::move(uses));
  for (std::size_t i = 0; i < uses.size(); ++i) {
    rec(uses[i]).radial_next = uses[(i + 1) % uses.size()].value;
  }
  rec(e).first_use = uses[0].value;
}

void ModelEditor::append_loop(FaceId f, LoopId l) {
  FaceRec& fr = rec(f);
  rec(l).next = f.value | kTagBit;
  if (fr.first_loop == kInvalidIndex) {
    fr.first_loop = l.value;
    return;
  }
  std::uint32_t p = fr.first_loop;
  while (!(m_.loops_[p].next & kTagBit)) p = m_.loops_[p].next;
  m_.loops_[p].next = l.value;
}

void ModelEditor::remove_loop(FaceId f, LoopId l) {
  FaceRec& fr = rec(f);
  if (fr.first_loop == l.value) {
    assert(!(rec(l).next & kTagBit));
    fr.first_loop = rec(l).next;
    return;
  }
  std::uint32_t p = fr.first_loop;
  while (m_.loops_[p].next != l.value) p = m_.loops_[p].next;
  m_.loops_[p].next = rec(l).next;
}

void ModelEditor::assign_face(LoopId l, FaceId f) {
  const EdgeUseId first = m_.loop_first(l);
  if (!first.is_valid()) return;
  EdgeUseId u = first;
  do {
    rec(u).face = f.value;
    u = m_.loop_next(u);
  } while (u != first);
}

void ModelEditor::set_sides(FaceId f, VolumeId front, VolumeId back) {
  rec(f).sides = intern_sides(front, back, m_.group_of(f));
}

}  // namespace cellforge
