// Conversion from the cellforge structure to Baumgart's winged edge structure
// (with what it refuses), its storage figures, and the 9 adjacency queries by
// wing traversal.
#include "cellforge/compare/winged_edge.h"

#include "cellforge/topo/dedupe.h"

namespace cellforge::compare {

namespace {

using WE = WingedEdge;

Error refuse(const std::string& what) {
  return Error{ErrorCode::kUnsupported, "winged edge cannot represent " + what};
}

std::string edge_name(const Model& m, EdgeId e) {
  return "edge " + e.str() + " (" + m.start_of(e).str() + "-" + m.end_of(e).str() + ")";
}

// The first edge or vertex the winged edge structure cannot hold, by the order of
// the header comment (the last check, non-manifold vertices, needs the wings).
std::optional<Error> first_refusal(const Model& m) {
  for (EdgeId e : m.edges()) {
    if (const std::size_t n = m.use_count(e); n > 2) {
      return refuse(edge_name(m, e) + ": it is used by " + std::to_string(n) +
                    " faces (non-manifold edge; a winged edge has exactly two faces)");
    }
  }
  for (EdgeId e : m.edges()) {
    if (m.is_wire(e)) return refuse("wire " + edge_name(m, e) + ": it bounds no face");
    if (m.use_count(e) == 1) {
      return refuse("dangling " + edge_name(m, e) + ": it is used by 1 face (" +
                    m.face_of(m.first_use(e)).str() + "), a winged edge needs two");
    }
  }
  for (EdgeId e : m.edges()) {
    const EdgeUseId a = m.first_use(e), b = m.radial_next(a);
    if (m.face_of(a) == m.face_of(b)) {
      return refuse(edge_name(m, e) + ": both of its sides are face " + m.face_of(a).str());
    }
    if (m.is_reversed(a) == m.is_reversed(b)) {
      return refuse(edge_name(m, e) + ": faces " + m.face_of(a).str() + " and " +
                    m.face_of(b).str() + " run it the same way (inconsistent orientation)");
    }
  }
  for (VertexId v : m.vertices()) {
    if (const LoopId l = m.point_loop(v); l.is_valid()) {
      return refuse("isolated vertex " + v.str() + ": a point loop of face " + m.face_of(l).str());
    }
    if (!m.first_end(v).edge.is_valid()) {
      return refuse("isolated vertex " + v.str() + ": it has no edge");
    }
  }
  return std::nullopt;
}

// Links the records of `slots` whose index passes `live` into a circular ring.
template <class T, class Live>
void link_ring(std::vector<T>& slots, Live live) {
  T* first = nullptr;
  T* last = nullptr;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!live(static_cast<std::uint32_t>(i))) continue;
    T* x = &slots[i];
    if (!first) first = x;
    if (last) last->next = x;
    x->prev = last;
    last = x;
  }
  if (first) {
    first->prev = last;
    last->next = first;
  }
}

// The next edge around v after e (crossing the face on the side where e arrives
// at v), and that face.
const WE::Edge* next_around(const WE::Edge* e, const WE::Vertex* v) {
  return e->start == v ? e->right_next : e->left_next;
}
const WE::Face* face_after(const WE::Edge* e, const WE::Vertex* v) {
  return e->start == v ? e->right : e->left;
}

template <class Fn>
void for_each_edge_around(const WE::Vertex* v, Fn fn) {
  const WE::Edge* e = v->edge;
  do {
    fn(e);
    e = next_around(e, v);
  } while (e != v->edge);
}

// Walks the loop through `first` on face f: fn(edge, forward) where forward
// means f is the edge's left face (the loop runs it start -> end).
template <class Fn>
void walk_loop(const WE::Edge* first, const WE::Face* f, Fn fn) {
  const WE::Edge* e = first;
  bool forward = first->left == f;
  do {
    fn(e, forward);
    const WE::Vertex* at = forward ? e->end : e->start;
    e = forward ? e->left_next : e->right_next;
    forward = e->start == at;
  } while (e != first);
}

template <class Fn>
void for_each_loop_edge(const WE::Face* f, Fn fn) {
  walk_loop(f->edge, f, fn);
  for (const WE::Ring* r = f->rings; r; r = r->next) walk_loop(r->edge, f, fn);
}

}  // namespace

Result<WingedEdge> WingedEdge::from_model(const Model& m) {
  if (auto error = first_refusal(m)) return *error;
  WingedEdge w;
  w.vertices_.resize(m.vertex_slots());
  w.edges_.resize(m.edge_slots());
  w.spare_edges_ = m.spare_pairs();
  w.faces_.resize(m.face_slots());
  std::size_t inner = 0;
  for (FaceId f : m.faces()) inner += m.inner_loop_count(f);
  w.rings_.reserve(inner);
  link_ring(w.vertices_, [&](std::uint32_t i) { return m.is_live(VertexId(i)); });
  link_ring(w.edges_, [&](std::uint32_t i) { return m.is_live(EdgeId(i)); });
  link_ring(w.faces_, [&](std::uint32_t i) { return m.is_live(FaceId(i)); });

  for (EdgeId e : m.edges()) {
    w.edges_[e.value].start = &w.vertices_[m.start_of(e).value];
    w.edges_[e.value].end = &w.vertices_[m.end_of(e).value];
  }
  for (VertexId v : m.vertices()) w.vertices_[v.value].edge = &w.edges_[m.first_end(v).edge.value];

  std::vector<EdgeUseId> uses;
  for (FaceId f : m.faces()) {
    Face& face = w.faces_[f.value];
    Ring* last_ring = nullptr;
    for (LoopId l : m.loops_of(f)) {
      uses.clear();
      const EdgeUseId first = m.loop_first(l);
      for (EdgeUseId u = first; uses.empty() || u != first; u = m.loop_next(u)) uses.push_back(u);
      const std::size_t n = uses.size();
      for (std::size_t i = 0; i < n; ++i) {
        Edge& e = w.edges_[m.edge_of(uses[i]).value];
        Edge* prev = &w.edges_[m.edge_of(uses[(i + n - 1) % n]).value];
        Edge* next = &w.edges_[m.edge_of(uses[(i + 1) % n]).value];
        if (m.is_reversed(uses[i])) {
          e.right = &face;
          e.right_prev = prev;
          e.right_next = next;
        } else {
          e.left = &face;
          e.left_prev = prev;
          e.left_next = next;
        }
      }
      Edge* loop_edge = &w.edges_[m.edge_of(first).value];
      if (l == m.outer_loop(f)) {
        face.edge = loop_edge;
        continue;
      }
      Ring& ring = w.rings_.emplace_back();
      ring.edge = loop_edge;
      (last_ring ? last_ring->next : face.rings) = &ring;
      last_ring = &ring;
    }
  }

  // A vertex where solids touch only at a corner: its wing cycle misses edges.
  for (VertexId v : m.vertices()) {
    const std::size_t degree = m.degree(v);
    std::size_t reached = 0;
    const Vertex* x = &w.vertices_[v.value];
    const Edge* e = x->edge;
    do {
      ++reached;
      e = next_around(e, x);
    } while (e != x->edge && reached <= degree);
    if (reached != degree) {
      return refuse("non-manifold vertex " + v.str() + ": its " + std::to_string(degree) +
                    " edges form more than one cycle of faces (the wings around it reach " +
                    std::to_string(reached) + ")");
    }
  }
  return w;
}

StorageStats WingedEdge::storage() const {
  StorageStats s;
  auto add = [&s](const auto& records, std::size_t pointers) {
    s.records += records.size();
    s.references += records.size() * pointers;
    s.bytes += records.capacity() * sizeof(records[0]);
  };
  add(vertices_, 3);
  add(edges_, 10);
  add(faces_, 4);
  add(rings_, 2);
  // cellforge's spare pairs (overflow use slots) are edge slots but no edges.
  s.records -= spare_edges_;
  s.references -= spare_edges_ * 10;
  s.bytes -= spare_edges_ * sizeof(Edge);
  return s;
}

void WingedEdge::edges_of(VertexId v, std::vector<EdgeId>& out) const {
  out.clear();
  for_each_edge_around(&vertices_[v.value], [&](const Edge* e) { out.push_back(id_of(e)); });
  dedupe_stable(out);
}

void WingedEdge::vertices_of(VertexId v, std::vector<VertexId>& out) const {
  out.clear();
  const Vertex* x = &vertices_[v.value];
  for_each_edge_around(
      x, [&](const Edge* e) { out.push_back(id_of(e->start == x ? e->end : e->start)); });
  dedupe_stable(out);
}

void WingedEdge::faces_of(VertexId v, std::vector<FaceId>& out) const {
  out.clear();
  const Vertex* x = &vertices_[v.value];
  for_each_edge_around(x, [&](const Edge* e) { out.push_back(id_of(face_after(e, x))); });
  dedupe_stable(out);
}

void WingedEdge::vertices_of(EdgeId e, std::vector<VertexId>& out) const {
  out.clear();
  out.push_back(id_of(edges_[e.value].start));
  out.push_back(id_of(edges_[e.value].end));
}

void WingedEdge::edges_of(EdgeId e, std::vector<EdgeId>& out) const {
  out.clear();
  const Edge* self = &edges_[e.value];
  for (const Vertex* x : {self->start, self->end}) {
    for_each_edge_around(x, [&](const Edge* g) {
      if (g != self) out.push_back(id_of(g));
    });
  }
  dedupe_stable(out);
}

void WingedEdge::faces_of(EdgeId e, std::vector<FaceId>& out) const {
  out.clear();
  out.push_back(id_of(edges_[e.value].left));
  out.push_back(id_of(edges_[e.value].right));
}

void WingedEdge::vertices_of(FaceId f, std::vector<VertexId>& out) const {
  out.clear();
  for_each_loop_edge(&faces_[f.value], [&](const Edge* e, bool forward) {
    out.push_back(id_of(forward ? e->start : e->end));
  });
  dedupe_stable(out);
}

void WingedEdge::edges_of(FaceId f, std::vector<EdgeId>& out) const {
  out.clear();
  for_each_loop_edge(&faces_[f.value], [&](const Edge* e, bool) { out.push_back(id_of(e)); });
  dedupe_stable(out);
}

void WingedEdge::faces_of(FaceId f, std::vector<FaceId>& out) const {
  out.clear();
  for_each_loop_edge(&faces_[f.value], [&](const Edge* e, bool forward) {
    out.push_back(id_of(forward ? e->right : e->left));
  });
  dedupe_stable(out);
}

}  // namespace cellforge::compare
