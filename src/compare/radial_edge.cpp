// Conversion from the cellforge structure to Weiler's radial edge structure, its
// storage figures, and the 9 adjacency queries by radial-edge traversal.
#include "cellforge/compare/radial_edge.h"

#include <cassert>

#include "cellforge/topo/dedupe.h"

namespace cellforge::compare {

namespace {

// Prepends `node` to the doubly linked, null-terminated list at `head`.
template <class T>
void push_front(T*& head, T* node) {
  node->next = head;
  node->prev = nullptr;
  if (head) head->prev = node;
  head = node;
}

// Appends `node` after `tail` (the list's last node, or null when it is empty).
template <class T>
void push_back(T*& head, T*& tail, T* node) {
  node->prev = tail;
  node->next = nullptr;
  (tail ? tail->next : head) = node;
  tail = node;
}

std::uint32_t group_slots(const Model& m) {
  std::uint32_t n = 0;
  for (GroupId g : m.groups()) n = g.value + 1;
  return n;
}

template <class T>
std::size_t heap_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

RadialEdge RadialEdge::from_model(const Model& m) {
  RadialEdge r;
  std::size_t wires = 0, point_loops = 0, isolated = 0;
  for (EdgeId e : m.edges()) wires += m.is_wire(e) ? 1 : 0;
  for (LoopId l : m.loops()) point_loops += m.is_point_loop(l) ? 1 : 0;
  for (VertexId v : m.vertices()) {
    isolated += (!m.first_end(v).edge.is_valid() && !m.point_loop(v).is_valid()) ? 1 : 0;
  }
  const std::uint32_t groups = group_slots(m);
  // Two edgeuses per cellforge use, numbered densely (cellforge's use slots
  // include empty ones).
  std::vector<std::uint32_t> dense(m.use_slots(), kInvalidIndex);
  std::uint32_t live_uses = 0;
  for (EdgeUseId u : m.edge_uses()) dense[u.value] = live_uses++;
  auto eu_of = [&](EdgeUseId u) { return &r.edgeuses_[2 * std::size_t{dense[u.value]}]; };
  const std::size_t use_eus = 2 * std::size_t{live_uses};
  r.spare_edges_ = m.spare_pairs();

  // Every array gets its final size first: records are linked by address.
  r.model_storage_.resize(1);
  r.model_ = &r.model_storage_[0];
  r.regions_.resize(groups);
  r.shells_.reserve(groups + isolated);
  r.shells_.resize(groups);
  r.faces_.resize(m.face_slots());
  r.faceuses_.resize(2 * std::size_t{m.face_slots()});
  r.loops_.resize(m.num_loops());
  r.loopuses_.resize(2 * m.num_loops());
  r.edges_.resize(m.edge_slots());
  r.edgeuses_.resize(use_eus + 2 * wires);
  r.vertexuses_.reserve(r.edgeuses_.size() + 2 * point_loops + isolated);
  r.vertexuses_.resize(r.edgeuses_.size());  // vertexuses_[i] is edgeuses_[i]'s
  r.vertices_.resize(m.vertex_slots());

  for (GroupId g : m.groups()) {
    Region& region = r.regions_[g.value];
    region.model = r.model_;
    push_front(r.model_->regions, &region);
    Shell& shell = r.shells_[g.value];
    shell.region = &region;
    push_front(region.shells, &shell);
  }

  auto edgeuse_at = [&](VertexId start, EdgeUse* eu) {
    VertexUse* vu = &r.vertexuses_[static_cast<std::size_t>(eu - r.edgeuses_.data())];
    vu->up.edgeuse = eu;
    vu->parent = UseParent::kEdgeUse;
    vu->vertex = &r.vertices_[start.value];
    eu->vertexuse = vu;
  };
  auto add_vertexuse = [&](VertexId v, UseParent parent) {
    VertexUse& vu = r.vertexuses_.emplace_back();
    vu.parent = parent;
    vu.vertex = &r.vertices_[v.value];
    return &vu;
  };

  std::vector<EdgeUseId> uses;
  std::size_t next_loop = 0;  // loops numbered in face order
  for (FaceId f : m.faces()) {
    Shell& shell = r.shells_[m.group_of(f).value];
    Face& face = r.faces_[f.value];
    FaceUse* side[2] = {&r.faceuses_[2 * f.value], &r.faceuses_[2 * f.value + 1]};
    face.faceuse = side[0];
    for (int s = 0; s < 2; ++s) {
      side[s]->shell = &shell;
      side[s]->mate = side[1 - s];
      side[s]->face = &face;
      side[s]->same_sense = s == 0;
      push_front(shell.faceuses, side[s]);
    }
    LoopUse* tail[2] = {nullptr, nullptr};
    for (LoopId l : m.loops_of(f)) {
      const std::size_t li = next_loop++;
      Loop& loop = r.loops_[li];
      LoopUse* lu[2] = {&r.loopuses_[2 * li], &r.loopuses_[2 * li + 1]};
      loop.loopuse = lu[0];
      for (int s = 0; s < 2; ++s) {
        lu[s]->faceuse = side[s];
        lu[s]->mate = lu[1 - s];
        lu[s]->loop = &loop;
        push_back(side[s]->loopuses, tail[s], lu[s]);
      }
      if (m.is_point_loop(l)) {
        for (int s = 0; s < 2; ++s) {
          lu[s]->vertexuse = add_vertexuse(m.point_loop_vertex(l), UseParent::kLoopUse);
          lu[s]->vertexuse->up.loopuse = lu[s];
        }
        continue;
      }
      uses.clear();
      const EdgeUseId first = m.loop_first(l);
      for (EdgeUseId u = first; uses.empty() || u != first; u = m.loop_next(u)) uses.push_back(u);
      const std::size_t n = uses.size();
      for (std::size_t i = 0; i < n; ++i) {
        const EdgeUseId u = uses[i], after = uses[(i + 1) % n], before = uses[(i + n - 1) % n];
        EdgeUse* front = eu_of(u);
        EdgeUse* back = front + 1;  // the mate runs the other way, in the back loopuse
        front->up.loopuse = lu[0];
        back->up.loopuse = lu[1];
        front->next = eu_of(after);
        front->prev = eu_of(before);
        back->next = eu_of(before) + 1;
        back->prev = eu_of(after) + 1;
        front->mate = back;
        back->mate = front;
        front->edge = back->edge = &r.edges_[m.edge_of(u).value];
        front->same_sense = !m.is_reversed(u);
        back->same_sense = m.is_reversed(u);
        edgeuse_at(m.use_start(u), front);
        edgeuse_at(m.use_end(u), back);
      }
      lu[0]->edgeuses = eu_of(uses[0]);
      lu[1]->edgeuses = eu_of(uses[0]) + 1;
    }
  }

  // Radial pointers. A use not reversed has the face's front side towards the next
  // face in the right-handed order about the edge (its normal points along the
  // rotation); a reversed use its back side. The facing pair across each wedge
  // are radial partners.
  std::size_t next_wire = use_eus;
  std::vector<EdgeUse*> plus, minus;
  for (EdgeId e : m.edges()) {
    Edge& edge = r.edges_[e.value];
    if (m.is_wire(e)) {
      Shell& shell = r.shells_[m.group_of(e).value];
      EdgeUse* a = &r.edgeuses_[next_wire];
      EdgeUse* b = a + 1;
      next_wire += 2;
      for (EdgeUse* eu : {a, b}) {
        eu->up.shell = &shell;
        eu->in_loop = false;
        eu->edge = &edge;
        eu->mate = eu->radial = (eu == a ? b : a);
        push_front(shell.wire_edgeuses, eu);
      }
      b->same_sense = false;
      edgeuse_at(m.start_of(e), a);
      edgeuse_at(m.end_of(e), b);
      edge.edgeuse = a;
      continue;
    }
    plus.clear();
    minus.clear();
    const EdgeUseId first = m.first_use(e);
    for (EdgeUseId u = first; plus.empty() || u != first; u = m.radial_next(u)) {
      EdgeUse* front = eu_of(u);
      plus.push_back(m.is_reversed(u) ? front + 1 : front);
      minus.push_back(m.is_reversed(u) ? front : front + 1);
    }
    const std::size_t k = plus.size();
    for (std::size_t i = 0; i < k; ++i) {
      plus[i]->radial = minus[(i + 1) % k];
      minus[(i + 1) % k]->radial = plus[i];
    }
    edge.edgeuse = plus[0];
  }

  for (VertexId v : m.vertices()) {
    if (m.first_end(v).edge.is_valid() || m.point_loop(v).is_valid()) continue;
    Shell& shell = r.shells_.emplace_back();
    Region& region = r.regions_[m.group_of(v).value];
    shell.region = &region;
    push_front(region.shells, &shell);
    shell.vertexuse = add_vertexuse(v, UseParent::kShell);
    shell.vertexuse->up.shell = &shell;
  }
  for (VertexUse& vu : r.vertexuses_) push_front(vu.vertex->vertexuses, &vu);
  assert(r.vertexuses_.size() == r.vertexuses_.capacity() &&
         r.shells_.size() == r.shells_.capacity());
  return r;
}

StorageStats RadialEdge::storage() const {
  StorageStats s;
  auto add = [&s](const auto& records, std::size_t pointers) {
    s.records += records.size();
    s.references += records.size() * pointers;
    s.bytes += heap_bytes(records);
  };
  add(model_storage_, 1);
  add(regions_, 4);
  add(shells_, 6);
  add(faceuses_, 6);
  add(loopuses_, 7);
  add(edgeuses_, 7);
  add(vertexuses_, 4);
  add(faces_, 1);
  add(loops_, 1);
  add(edges_, 1);
  add(vertices_, 1);
  // cellforge's spare pairs (overflow use slots) are edge slots but no edges.
  s.records -= spare_edges_;
  s.references -= spare_edges_;
  s.bytes -= spare_edges_ * sizeof(Edge);
  return s;
}

namespace {

using RE = RadialEdge;

const RE::Face* face_of(const RE::VertexUse& vu) {
  if (vu.parent == RE::UseParent::kLoopUse) return vu.up.loopuse->faceuse->face;
  if (vu.parent == RE::UseParent::kEdgeUse && vu.up.edgeuse->in_loop) {
    return vu.up.edgeuse->up.loopuse->faceuse->face;
  }
  return nullptr;
}

// Calls fn(edgeuse) for each edgeuse of faceuse fu's loops, and on_point(vertexuse)
// for each point loop.
template <class Fn, class PointFn>
void for_each_loop_use(const RE::FaceUse* fu, Fn fn, PointFn on_point) {
  for (const RE::LoopUse* lu = fu->loopuses; lu; lu = lu->next) {
    if (!lu->edgeuses) {
      on_point(lu->vertexuse);
      continue;
    }
    const RE::EdgeUse* eu = lu->edgeuses;
    do {
      fn(eu);
      eu = eu->next;
    } while (eu != lu->edgeuses);
  }
}

// Calls fn(face) for each face around eu's edge, in radial order from eu.
template <class Fn>
void for_each_radial_face(const RE::EdgeUse* first, Fn fn) {
  const RE::EdgeUse* eu = first;
  do {
    if (eu->in_loop) fn(eu->up.loopuse->faceuse->face);
    eu = eu->radial->mate;
  } while (eu != first);
}

}  // namespace

void RadialEdge::edges_of(VertexId v, std::vector<EdgeId>& out) const {
  out.clear();
  for (const VertexUse* vu = vertices_[v.value].vertexuses; vu; vu = vu->next) {
    if (vu->parent == UseParent::kEdgeUse) out.push_back(id_of(vu->up.edgeuse->edge));
  }
  dedupe_stable(out);
}

void RadialEdge::vertices_of(VertexId v, std::vector<VertexId>& out) const {
  out.clear();
  for (const VertexUse* vu = vertices_[v.value].vertexuses; vu; vu = vu->next) {
    if (vu->parent == UseParent::kEdgeUse) {
      out.push_back(id_of(vu->up.edgeuse->mate->vertexuse->vertex));
    }
  }
  dedupe_stable(out);
}

void RadialEdge::faces_of(VertexId v, std::vector<FaceId>& out) const {
  out.clear();
  for (const VertexUse* vu = vertices_[v.value].vertexuses; vu; vu = vu->next) {
    if (const Face* f = face_of(*vu)) out.push_back(id_of(f));
  }
  dedupe_stable(out);
}

void RadialEdge::vertices_of(EdgeId e, std::vector<VertexId>& out) const {
  out.clear();
  const EdgeUse* eu = edges_[e.value].edgeuse;
  const bool forward = eu->same_sense;  // list start then end, as cellforge does
  const Vertex* a = eu->vertexuse->vertex;
  const Vertex* b = eu->mate->vertexuse->vertex;
  out.push_back(id_of(forward ? a : b));
  out.push_back(id_of(forward ? b : a));
}

void RadialEdge::edges_of(EdgeId e, std::vector<EdgeId>& out) const {
  out.clear();
  const EdgeUse* eu = edges_[e.value].edgeuse;
  for (const Vertex* v : {eu->vertexuse->vertex, eu->mate->vertexuse->vertex}) {
    for (const VertexUse* vu = v->vertexuses; vu; vu = vu->next) {
      if (vu->parent != UseParent::kEdgeUse) continue;
      const EdgeId x = id_of(vu->up.edgeuse->edge);
      if (x != e) out.push_back(x);
    }
  }
  dedupe_stable(out);
}

void RadialEdge::faces_of(EdgeId e, std::vector<FaceId>& out) const {
  out.clear();
  for_each_radial_face(edges_[e.value].edgeuse, [&](const Face* f) { out.push_back(id_of(f)); });
  dedupe_stable(out);
}

void RadialEdge::vertices_of(FaceId f, std::vector<VertexId>& out) const {
  out.clear();
  for_each_loop_use(
      faces_[f.value].faceuse,
      [&](const EdgeUse* eu) { out.push_back(id_of(eu->vertexuse->vertex)); },
      [&](const VertexUse* vu) { out.push_back(id_of(vu->vertex)); });
  dedupe_stable(out);
}

void RadialEdge::edges_of(FaceId f, std::vector<EdgeId>& out) const {
  out.clear();
  for_each_loop_use(
      faces_[f.value].faceuse, [&](const EdgeUse* eu) { out.push_back(id_of(eu->edge)); },
      [](const VertexUse*) {});
  dedupe_stable(out);
}

void RadialEdge::faces_of(FaceId f, std::vector<FaceId>& out) const {
  out.clear();
  const Face* self = &faces_[f.value];
  for_each_loop_use(
      self->faceuse,
      [&](const EdgeUse* eu) {
        for_each_radial_face(eu, [&](const Face* g) {
          if (g != self) out.push_back(id_of(g));
        });
      },
      [](const VertexUse*) {});
  dedupe_stable(out);
}

}  // namespace cellforge::compare
