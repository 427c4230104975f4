// ModelEditor: allocation from free lists and the low-level linking of the two
// cycles (vertex -> edge ends, edge -> uses) and of loops into faces.
#include "topo/model_editor.h"

#include <algorithm>
#include <cassert>
#include <iterator>

#include "cellforge/topo/dedupe.h"
#include "topo/operators_common.h"

namespace cellforge::inline topo {

namespace {

// Puts id (of a kind with `slots` slots, id among them) into a run of group g:
// the runs, sorted by first, give every id the group of the run holding it.
void assign_run(std::vector<detail::GroupRun>& runs, std::uint32_t id, std::uint32_t slots,
                std::uint32_t g) {
  using Run = detail::GroupRun;
  if (!runs.empty() && id >= runs.back().first && runs.back().group == g) return;  // bulk case
  auto after = std::upper_bound(runs.begin(), runs.end(), id,
                                [](std::uint32_t x, const Run& r) { return x < r.first; });
  if (after != runs.begin() && std::prev(after)->group == g) return;  // in a run of g
  // Split the run holding id (if any) around it: [.., id) old, [id] g, [id+1, ..) old.
  const bool has_run = after != runs.begin();
  const std::uint32_t old = has_run ? std::prev(after)->group : kInvalidIndex;
  const std::uint32_t end = after == runs.end() ? kInvalidIndex : after->first;
  std::size_t at = static_cast<std::size_t>(after - runs.begin());
  if (has_run && std::prev(after)->first == id) {
    std::prev(after)->group = g;
    --at;
  } else {
    runs.insert(runs.begin() + static_cast<std::ptrdiff_t>(at), Run{id, g});
  }
  // The id after this one goes back to the old group, unless this is the last of
  // the ids so far (new slots extend the run of the last one made).
  if (has_run && id + 1 < end && id + 1 < slots) {
    runs.insert(runs.begin() + static_cast<std::ptrdiff_t>(at) + 1, Run{id + 1, old});
  }
  // Merge with neighbours of the same group.
  if (at + 1 < runs.size() && runs[at + 1].group == g) {
    runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(at) + 1);
  }
  if (at > 0 && runs[at - 1].group == g) runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(at));
}

// Drops the runs of group g (every slot of them is free: the group is empty); the
// slots join the run before them.
void drop_runs(std::vector<detail::GroupRun>& runs, std::uint32_t g) {
  std::erase_if(runs, [g](const detail::GroupRun& r) { return r.group == g; });
  for (std::size_t i = 1; i < runs.size();) {
    if (runs[i].group == runs[i - 1].group)
      runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(i));
    else
      ++i;
  }
}

}  // namespace

// A slot from kind's free list (whose links `link(i)` reads), or a new one that
// `grow()` appends.
template <class LinkFn, class GrowFn>
std::uint32_t ModelEditor::take_slot(int kind, LinkFn link, GrowFn grow) {
  ++m_.live_[kind];
  std::uint32_t& head = m_.free_[kind];
  if (head != kInvalidIndex) {
    const std::uint32_t i = head;
    head = link(i);
    return i;
  }
  return grow();
}

template <class Rec>
std::uint32_t ModelEditor::take_slot(std::vector<Rec>& recs, int kind, std::uint32_t Rec::*link) {
  return take_slot(
      kind, [&](std::uint32_t i) { return recs[i].*link; },
      [&] {
        recs.emplace_back();
        return static_cast<std::uint32_t>(recs.size() - 1);
      });
}

GroupId ModelEditor::new_group(std::string name) {
  for (std::uint32_t i = 0; i < m_.groups_.size(); ++i) {
    if (!m_.groups_[i].live) {
      m_.groups_[i] = Model::GroupRec{true, std::move(name), {}};
      m_.group_counts_[i] = {};
      ++m_.live_[Model::kGroup];
      return GroupId(i);
    }
  }
  m_.groups_.push_back(Model::GroupRec{true, std::move(name), {}});
  m_.group_counts_.emplace_back();
  ++m_.live_[Model::kGroup];
  return GroupId(static_cast<std::uint32_t>(m_.groups_.size() - 1));
}

void ModelEditor::reserve(std::size_t vertices, std::size_t edges, std::size_t faces) {
  m_.vertices_.reserve(m_.vertices_.size() + vertices);
  m_.positions_.reserve(m_.positions_.size() + vertices);
  m_.ends_.reserve(m_.ends_.size() + 2 * edges);
  m_.uses_.reserve(m_.uses_.size() + 2 * edges);
  m_.radial_.reserve(m_.radial_.size() + 2 * edges);
  m_.faces_.reserve(m_.faces_.size() + faces);
}

VertexId ModelEditor::new_vertex(GroupId g, Vec3 p) {
  ++m_.live_[Model::kVertex];
  std::uint32_t i;
  if (!m_.free_vertices_.empty()) {
    i = m_.free_vertices_.back();
    m_.free_vertices_.pop_back();
  } else {
    i = static_cast<std::uint32_t>(m_.vertices_.size());
    m_.vertices_.emplace_back();
  }
  m_.vertices_[i] = {kInvalidIndex};
  set_vertex_group(VertexId(i), g);
  ++m_.group_counts_[g.value].vertices;
  m_.properties_.reset(detail::kVertexProperty, i);
  if (m_.positions_.size() <= i) m_.positions_.resize(i + 1);
  m_.positions_[i] = p;
  return VertexId(i);
}

std::uint32_t ModelEditor::take_edge_slot() {
  std::uint32_t& head = m_.free_[Model::kEdge];
  if (head != kInvalidIndex) {
    const std::uint32_t i = head;
    head = m_.ends_[2 * i].next_end;
    return i;
  }
  assert(m_.ends_.size() / 2 + 1 < Model::kMaxEdges);  // spare pairs count too
  m_.ends_.resize(m_.ends_.size() + 2);
  m_.uses_.resize(m_.ends_.size(), kEmptyUse());
  m_.radial_.resize(m_.ends_.size(), kInvalidIndex);
  return static_cast<std::uint32_t>(m_.ends_.size() / 2 - 1);
}

std::uint32_t ModelEditor::take_overflow_slot() {
  std::uint32_t& head = m_.free_[Model::kUse];
  if (head == kInvalidIndex) {  // a new spare pair: two free overflow slots
    const std::uint32_t p = take_edge_slot();
    m_.ends_[2 * p] = {Model::kSpare, 2 * p + 1};
    m_.ends_[2 * p + 1] = {Model::kSpare, kInvalidIndex};
    head = 2 * p;
  }
  const std::uint32_t s = head;
  head = m_.ends_[s].next_end;
  return s;
}

EdgeId ModelEditor::new_edge(VertexId a, VertexId b) {
  ++m_.live_[Model::kEdge];
  const std::uint32_t i = take_edge_slot();
  m_.ends_[2 * i] = {a.value, kInvalidIndex};
  m_.ends_[2 * i + 1] = {b.value, kInvalidIndex};
  m_.uses_[2 * i] = m_.uses_[2 * i + 1] = kEmptyUse();
  radial(2 * i) = radial(2 * i + 1) = kInvalidIndex;
  link_end(a, {EdgeId(i), 0});
  link_end(b, {EdgeId(i), 1});
  const std::uint32_t g = group_of_new(a);
  assign_run(m_.edge_groups_, i, m_.edge_slots(), g);
  ++m_.group_counts_[g].edges;
  m_.properties_.reset(detail::kEdgeProperty, i);
  return EdgeId(i);
}

EdgeUseId ModelEditor::new_use(EdgeId e, bool reversed, FaceId f) {
  ++m_.live_[Model::kUse];
  const EdgeUseId first = m_.first_use(e);
  // In place if that slot is free (model.h), else the other slot, else overflow.
  std::uint32_t s = 2 * e.value + (reversed ? 1u : 0u);
  std::uint32_t overflow = 0;
  if (m_.uses_[s].face_dir != Model::kNoUse) s ^= 1u;
  if (m_.uses_[s].face_dir != Model::kNoUse) {
    s = take_overflow_slot();
    m_.ends_[s] = {e.value | kTagBit, kInvalidIndex};
    overflow = Model::kOverflowBit;
  }
  m_.uses_[s] = {f.value | overflow | (reversed ? kTagBit : 0u), s};
  if (f.is_valid()) {
    rec(f).sides |= mark_of(EdgeUseId(s));
    touch(f);
  }
  radial(s) = s;
  if (first.is_valid()) {  // after the first use
    radial(s) = radial(first.value);
    radial(first.value) = s;
  } else if (s != 2 * e.value) {  // the edge's first use, while slot 2e stays empty
    radial(2 * e.value) = s;
  }
  return EdgeUseId(s);
}

std::uint32_t ModelEditor::new_record(std::uint32_t first, std::uint32_t next) {
  const std::uint32_t i = take_slot(m_.loops_, Model::kLoop, &LoopRec::next);
  assert(i < Model::kMaxFaces - 2);  // kTagBit|kInnerLoopBit|i must stay apart from kDead
  m_.loops_[i] = {first, next};
  return i;
}

LoopId ModelEditor::new_point_loop(VertexId v) {
  const LoopId l(new_record(kInvalidIndex, kInvalidIndex) | Model::kInnerLoopBit);
  set_point_loop(l, v);
  return l;
}

LoopId ModelEditor::new_loop(EdgeUseId first) {
  return LoopId(new_record(first.value, kInvalidIndex) | Model::kInnerLoopBit);
}

void ModelEditor::set_face_first(FaceId f, std::uint32_t first) {
  auto listed = [](std::uint32_t x) { return (x & kTagBit) && x != kInvalidIndex; };
  std::uint32_t& slot = rec(f).first;
  if (listed(slot)) --m_.listed_faces_;
  if (listed(first)) ++m_.listed_faces_;
  slot = first;
}

void ModelEditor::list_loops(FaceId f) {
  const std::uint32_t first = rec(f).first;
  if ((first & kTagBit) != 0) return;  // listed already, or empty
  set_face_first(f, new_record(first, f.value | kTagBit) | kTagBit);
}

bool ModelEditor::is_open(FaceId f) const {
  for (std::uint32_t g : m_.open_faces_) {
    if (g == f.value) return true;
  }
  return false;
}

void ModelEditor::open(FaceId f) {
  if (is_open(f)) return;
  m_.open_faces_.push_back(f.value);
  list_loops(f);
  touch(f);  // its marks are made exact when the edit ends
}

std::uint32_t ModelEditor::exact_marks(FaceId f) {
  std::uint32_t marks = 0;
  seen_edges_.clear();
  seen_vertices_.clear();
  m_.for_each_loop_of(
      rec(f),
      [&](std::uint32_t first) {
        std::uint32_t u = first;
        do {
          marks |= mark_of(EdgeUseId(u));
          seen_edges_.push_back(m_.edge_of(EdgeUseId(u)).value);
          seen_vertices_.push_back(m_.use_start(EdgeUseId(u)).value);
          u = m_.uses_[u].next;
        } while (u != first);
      },
      [&](VertexId v) { seen_vertices_.push_back(v.value); });
  if (find_repeat(seen_edges_) || find_repeat(seen_vertices_)) marks |= Model::kRepeatFace;
  return marks;
}

void ModelEditor::close(FaceId f) {
  list_loops(f);
  const std::uint32_t head = rec(f).first & ~kTagBit;
  for (std::uint32_t r = head;; r = loop_rec(r).next) {
    const std::uint32_t first = loop_rec(r).first;
    if (first & kTagBit) {  // a point loop: its vertex names it by its final id
      const std::uint32_t code = r == head ? f.value : (r | Model::kInnerLoopBit);
      rec(VertexId(first & ~kTagBit)).first_end = code | kTagBit;
    }
    if (loop_rec(r).next & kTagBit) break;
  }
  // A face with one loop of edges keeps it in its own record.
  const LoopRec only = loop_rec(head);
  if ((only.next & kTagBit) && !(only.first & kTagBit)) {
    set_face_first(f, only.first);
    free_loop(LoopId(head | Model::kInnerLoopBit));
  }
}

ModelEditor::~ModelEditor() {
  if (--m_.edit_depth_ != 0) return;
  // Close in order of opening; a face freed meanwhile (or freed and made again
  // as another face) is closed once if live.
  std::vector<std::uint32_t> faces;
  faces.swap(m_.open_faces_);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const FaceId f(faces[i]);
    bool seen = false;
    for (std::size_t j = 0; j < i; ++j) seen = seen || faces[j] == faces[i];
    if (!seen && m_.is_live(f) && rec(f).first != kInvalidIndex) close(f);
  }
  // Every face the edit changed or opened gets exact marks (a face freed
  // meanwhile, or freed and made again, is skipped or done twice).
  faces.clear();
  faces.swap(m_.touched_faces_);
  for (std::uint32_t i : faces) {
    const FaceId f(i);
    if (!m_.is_live(f)) continue;
    std::uint32_t& sides = rec(f).sides;
    sides &= ~Model::kFaceMarks;
    if (rec(f).first != kInvalidIndex) sides |= exact_marks(f);
  }
}

LoopId ModelEditor::append_record(FaceId f, std::uint32_t r) {
  loop_rec(r).next = f.value | kTagBit;
  if (rec(f).first == kInvalidIndex) {
    set_face_first(f, r | kTagBit);
    return LoopId(f.value);
  }
  list_loops(f);
  std::uint32_t p = rec(f).first & ~kTagBit;
  while (!(loop_rec(p).next & kTagBit)) p = loop_rec(p).next;
  loop_rec(p).next = r;
  return LoopId(r | Model::kInnerLoopBit);
}

LoopId ModelEditor::add_loop(FaceId f, EdgeUseId first) {
  touch(f);
  if (rec(f).first == kInvalidIndex) {  // the face's only loop, in its own record
    set_face_first(f, first.value);
    return LoopId(f.value);
  }
  return append_record(f, new_record(first.value, kInvalidIndex));
}

LoopId ModelEditor::add_point_loop(FaceId f, VertexId v) {
  touch(f);
  const LoopId l = append_record(f, new_record(v.value | kTagBit, kInvalidIndex));
  assert(!m_.first_end(v).edge.is_valid());
  rec(v).first_end = l.value | kTagBit;
  return l;
}

std::uint32_t ModelEditor::record_of(LoopId l) {
  if (l.value & Model::kInnerLoopBit) {
    const FaceId f = m_.face_of(l);  // invalid while the record is in no face
    if (f.is_valid()) open(f);
    return l.value & ~Model::kInnerLoopBit;
  }
  open(FaceId(l.value));
  return rec(FaceId(l.value)).first & ~kTagBit;
}

void ModelEditor::set_loop_first(LoopId l, EdgeUseId u) {
  const std::uint32_t r = record_of(l);
  const std::uint32_t old = loop_rec(r).first;
  if (old != kInvalidIndex && (old & kTagBit)) {
    VertexRec& vr = rec(VertexId(old & ~kTagBit));
    if (vr.first_end & kTagBit) vr.first_end = kInvalidIndex;
  }
  loop_rec(r).first = u.value;
}

void ModelEditor::set_point_loop(LoopId l, VertexId v) {
  assert(!m_.first_end(v).edge.is_valid());
  const std::uint32_t r = record_of(l);
  loop_rec(r).first = v.value | kTagBit;
  rec(v).first_end = l.value | kTagBit;  // the final id is written when the face closes
}

LoopId ModelEditor::take_outer_loop(FaceId f) {
  open(f);
  const std::uint32_t r = rec(f).first & ~kTagBit;
  set_face_first(f, kInvalidIndex);
  loop_rec(r).next = kInvalidIndex;
  return LoopId(r | Model::kInnerLoopBit);
}

FaceId ModelEditor::new_face(std::uint32_t sides) {
  const std::uint32_t i = take_slot(m_.faces_, Model::kFace, &FaceRec::first);
  m_.faces_[i] = {kInvalidIndex, sides & ~Model::kFaceMarks};
  if (i < m_.face_surface_.size()) m_.face_surface_[i] = kInvalidIndex;
  const std::uint32_t g = m_.sides_[sides & ~Model::kFaceMarks].group;
  assign_run(m_.face_groups_, i, m_.face_slots(), g);
  ++m_.group_counts_[g].faces;
  m_.properties_.reset(detail::kFaceProperty, i);
  return FaceId(i);
}

VolumeId ModelEditor::new_volume(GroupId g) {
  const std::uint32_t i = take_slot(m_.volumes_, Model::kVolume, &Model::VolumeRec::next_free);
  m_.volumes_[i] = {g.value, kInvalidIndex};
  assign_run(m_.volume_groups_, i, static_cast<std::uint32_t>(m_.volumes_.size()), g.value);
  ++m_.group_counts_[g.value].volumes;
  m_.properties_.reset(detail::kVolumeProperty, i);
  return VolumeId(i);
}

std::uint32_t ModelEditor::intern_sides(VolumeId front, VolumeId back, GroupId g) {
  const SidesRec want{front.value, back.value, g.value};
  for (std::uint32_t i = 0; i < m_.sides_.size(); ++i) {
    if (m_.sides_[i] == want) return i;
  }
  assert(m_.sides_.size() < Model::kMaxSideRows);  // beside the face marks
  m_.sides_.push_back(want);
  return static_cast<std::uint32_t>(m_.sides_.size() - 1);
}


void ModelEditor::set_vertex_group(VertexId v, GroupId g) {
  assign_run(m_.vertex_groups_, v.value, m_.vertex_slots(), g.value);
}

namespace {

// Puts slot i at the head of a free list whose link for i is `link`.
void push_free(std::uint32_t& head, std::uint32_t i, std::uint32_t& link) {
  link = head;
  head = i;
}

}  // namespace

void ModelEditor::free_vertex(VertexId v) {
  --m_.group_counts_[m_.group_of(v).value].vertices;
  m_.vertices_[v.value].first_end = kDead;
  m_.properties_.reset(detail::kVertexProperty, v.value);
  m_.free_vertices_.push_back(v.value);
  --m_.live_[Model::kVertex];
}

void ModelEditor::free_edge(EdgeId e) {
  assert(!m_.first_use(e).is_valid());
  --m_.group_counts_[m_.group_of(e).value].edges;
  m_.properties_.reset(detail::kEdgeProperty, e.value);
  unlink_end(m_.vertex_of(e, 0), {e, 0});
  unlink_end(m_.vertex_of(e, 1), {e, 1});
  end_rec({e, 0}).vertex = kDead;
  end_rec({e, 1}).vertex = kDead;
  m_.uses_[2 * e.value] = kEmptyUse();
  radial(2 * e.value) = kInvalidIndex;
  push_free(m_.free_[Model::kEdge], e.value, end_rec({e, 0}).next_end);
  --m_.live_[Model::kEdge];
}

void ModelEditor::free_use(EdgeUseId u) {
  const std::uint32_t e = m_.edge_of(u).value;
  // Out of the radial cycle: its predecessor skips it.
  const std::uint32_t after = radial(u.value);
  std::uint32_t p = u.value;
  while (radial(p) != u.value) p = radial(p);
  radial(p) = after;
  const std::uint32_t rest = after == u.value ? kInvalidIndex : after;  // a use left, if any
  if (const FaceId f = m_.face_of(u); m_.is_live(f)) touch(f);
  if (rec(u).face_dir & Model::kOverflowBit) {
    m_.ends_[u.value].vertex = Model::kSpare;
    push_free(m_.free_[Model::kUse], u.value, m_.ends_[u.value].next_end);
  }
  rec(u) = kEmptyUse();
  radial(u.value) = kInvalidIndex;
  // An empty slot 2e names a use of the cycle, if one is left.
  if (m_.uses_[2 * e].face_dir == Model::kNoUse && (u.value == 2 * e || radial(2 * e) == u.value)) {
    radial(2 * e) = rest;
  }
  --m_.live_[Model::kUse];
}

void ModelEditor::free_loop(LoopId l) {
  std::uint32_t r;
  if (l.value & Model::kInnerLoopBit) {
    r = l.value & ~Model::kInnerLoopBit;
  } else {
    r = rec(FaceId(l.value)).first;
    if (!(r & kTagBit) || r == kInvalidIndex) return;  // kept in the face's own record
    r &= ~kTagBit;
  }
  const std::uint32_t first = loop_rec(r).first;
  if (first != kInvalidIndex && (first & kTagBit)) {
    VertexRec& vr = rec(VertexId(first & ~kTagBit));
    if (vr.first_end & kTagBit) vr.first_end = kInvalidIndex;
  }
  loop_rec(r).first = kDead;
  push_free(m_.free_[Model::kLoop], r, loop_rec(r).next);
  --m_.live_[Model::kLoop];
}

void ModelEditor::free_face(FaceId f) {
  --m_.group_counts_[m_.group_of(f).value].faces;
  m_.properties_.reset(detail::kFaceProperty, f.value);
  set_face_first(f, kInvalidIndex);
  rec(f).sides = kDead;
  if (f.value < m_.face_surface_.size()) m_.face_surface_[f.value] = kInvalidIndex;
  push_free(m_.free_[Model::kFace], f.value, rec(f).first);
  --m_.live_[Model::kFace];
}

void ModelEditor::free_volume(VolumeId c) {
  --m_.group_counts_[m_.volumes_[c.value].group].volumes;
  m_.properties_.reset(detail::kVolumeProperty, c.value);
  m_.volumes_[c.value].group = kDead;
  push_free(m_.free_[Model::kVolume], c.value, m_.volumes_[c.value].next_free);
  --m_.live_[Model::kVolume];
}

void ModelEditor::free_group(GroupId g) {
  assert(m_.group_empty(g));
  for (auto* runs : {&m_.vertex_groups_, &m_.edge_groups_, &m_.face_groups_, &m_.volume_groups_})
    drop_runs(*runs, g.value);
  m_.groups_[g.value] = Model::GroupRec{false, {}, {}};
  --m_.live_[Model::kGroup];
}

void ModelEditor::link_end(VertexId v, EdgeEnd end) {
  VertexRec& vr = rec(v);
  const std::uint32_t code = Model::encode_end(end);
  std::uint32_t& next = end_rec(end).next_end;
  assert(!m_.point_loop(v).is_valid());
  if (vr.first_end == kInvalidIndex) {
    vr.first_end = code;
    next = code;
    return;
  }
  // Insert after the first end: O(1), and the first end stays first.
  const EdgeEnd first = Model::decode_end(vr.first_end);
  std::uint32_t& first_next = end_rec(first).next_end;
  next = first_next;
  first_next = code;
}

void ModelEditor::unlink_end(VertexId v, EdgeEnd end) {
  VertexRec& vr = rec(v);
  const std::uint32_t code = Model::encode_end(end);
  const std::uint32_t after = end_rec(end).next_end;
  if (after == code) {  // the only end at v
    vr.first_end = kInvalidIndex;
    return;
  }
  EdgeEnd p = Model::decode_end(vr.first_end);
  while (end_rec(p).next_end != code) p = Model::decode_end(end_rec(p).next_end);
  end_rec(p).next_end = after;
  if (vr.first_end == code) vr.first_end = after;
}

void ModelEditor::move_end(EdgeEnd end, VertexId to) {
  // The faces along the edge may now meet `to` twice.
  for (EdgeUseId u : m_.radial(end.edge))
    if (const FaceId f = m_.face_of(u); m_.is_live(f)) touch(f);
  unlink_end(VertexId(end_rec(end).vertex), end);
  end_rec(end).vertex = to.value;
  link_end(to, end);
}

void ModelEditor::set_radial_cycle(EdgeId e, const std::vector<EdgeUseId>& uses) {
  for (std::size_t i = 0; i < uses.size(); ++i) {
    radial(uses[i].value) = uses[(i + 1) % uses.size()].value;
  }
  if (m_.uses_[2 * e.value].face_dir == Model::kNoUse) {
    radial(2 * e.value) = uses.empty() ? kInvalidIndex : uses.front().value;
  }
}

void ModelEditor::radial_insert(EdgeUseId u) { radial_sort(m_.edge_of(u)); }

void ModelEditor::radial_sort(EdgeId e, FaceNormals* normals) {
  std::vector<EdgeUseId> cycle = ops::radial_uses(m_, e);
  if (cycle.size() <= 2) return;
  set_radial_cycle(e, sort_radially(m_, e, std::move(cycle), normals));
}

EdgeUseId ModelEditor::move_use(EdgeUseId u, EdgeId e, bool flip) {
  const FaceId f = m_.face_of(u);
  const bool reversed = m_.is_reversed(u) != flip;
  const std::uint32_t next = rec(u).next;
  std::uint32_t prev = u.value;
  while (m_.uses_[prev].next != u.value) prev = m_.uses_[prev].next;
  free_use(u);
  const EdgeUseId w = new_use(e, reversed, f);
  if (prev != u.value) {
    m_.uses_[prev].next = w.value;
    rec(w).next = next;
  }
  // The loop that starts at u starts at w: in the face's record or a Loop record.
  FaceRec& fr = rec(f);
  if (fr.first == u.value) {
    fr.first = w.value;
  } else if ((fr.first & kTagBit) && fr.first != kInvalidIndex) {
    for (std::uint32_t r = fr.first & ~kTagBit;; r = loop_rec(r).next) {
      if (loop_rec(r).first == u.value) loop_rec(r).first = w.value;
      if (loop_rec(r).next & kTagBit) break;
    }
  }
  return w;
}

void ModelEditor::append_loop(FaceId f, LoopId l) {
  assert(l.value & Model::kInnerLoopBit);  // a record from new_loop or remove_loop
  open(f);
  append_record(f, l.value & ~Model::kInnerLoopBit);
}

void ModelEditor::remove_loop(FaceId f, LoopId l) {
  open(f);
  const std::uint32_t r = l.value & Model::kInnerLoopBit ? l.value & ~Model::kInnerLoopBit
                                                          : rec(f).first & ~kTagBit;
  const std::uint32_t head = rec(f).first & ~kTagBit;
  if (head == r) {
    assert(!(loop_rec(r).next & kTagBit));
    set_face_first(f, loop_rec(r).next | kTagBit);
  } else {
    std::uint32_t p = head;
    while (loop_rec(p).next != r) p = loop_rec(p).next;
    loop_rec(p).next = loop_rec(r).next;
  }
  loop_rec(r).next = kInvalidIndex;
}

void ModelEditor::assign_face(LoopId l, FaceId f) {
  const std::uint32_t first = loop_rec(record_of(l)).first;
  if (first & kTagBit) return;
  std::uint32_t u = first;
  touch(f);
  do {
    UseRec& r = m_.uses_[u];
    r.face_dir = f.value | (r.face_dir & ~Model::kFaceMask);
    rec(f).sides |= mark_of(EdgeUseId(u));
    u = r.next;
  } while (u != first);
}

void ModelEditor::set_sides(FaceId f, VolumeId front, VolumeId back) {
  rec(f).sides = intern_sides(front, back, m_.group_of(f)) | (rec(f).sides & Model::kFaceMarks);
}

}  // namespace cellforge::inline topo
