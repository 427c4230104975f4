// The adjacent-dimension cycle structure (seed 000, GEMS 4.0): a face-centred,
// non-manifold boundary representation kept in flat arrays with 32-bit ids.
//
// Entities and what each record holds (all fields are 32-bit indices):
//   Vertex   first edge end of its vertex cycle                    (4 B)
//   Edge     per end: vertex, next end around that vertex (8 B each) (16 B)
//   EdgeUse  face + direction bit, next use in its loop (8 B); next use
//            around its edge (radial cycle) in an array of its own  (4 B)
//            Every edge has two use slots, used or not: 40 B an edge.
//   Face     first use of its loop, interned side record           (8 B)
//   Loop     only for faces with holes or a point loop: first use
//            (or the point's vertex), next loop of the face         (8 B)
//   Sides    front volume, back volume, group (shared by all faces with
//            the same three values; a closed solid's faces share one)
//   Groups of vertices: runs of consecutive vertex ids in one group (a model
//            built group by group has one run per group)
//
// The two cycles that name the structure:
//   vertex -> its edges: each edge end links to the next edge end around the same
//             vertex (an "edge end" is 2*edge + end, end 0 = the edge's start);
//   edge -> its uses: each edge use links to the next use around the same edge,
//           in angular order (right-handed about the edge's start->end axis).
//
// Use ids are slots that belong to edges: edge e owns use slots 2e and 2e+1,
// the same numbers as its two end records. So a use names its edge by its id
// (edge_of(u) is u/2, no load), an edge's first use is slot 2e, and an edge of a
// closed manifold fills both. A third or later use of an edge takes an overflow
// slot: a slot of an edge record kept for overflow (a "spare pair", not an edge),
// whose end record at the same index names the use's edge. Such a use carries
// kOverflowBit beside its face. A use is *in place* when it sits in slot
// 2e + direction (a forward use in 2e, a reversed one in 2e + 1): its start
// vertex is then the end record of its own index, ends_[u]. The two uses of an
// edge of a consistently oriented manifold run opposite ways, so both are in
// place. A face that may hold a use not in place is marked (kUnplacedFace), and
// one that may hold a use in an overflow slot too (kOverflowFace): F->V walks an
// unmarked face reading start vertex ends_[u], F->E and F->F a face without the
// overflow mark reading edge u/2, without a test per use. A third mark
// (kRepeatFace) says that a face's loops may name an edge or a vertex twice (a
// slit, a dangling edge, loops that touch): the F->E and F->V answers of a face
// without it need no deduplication. An edit sets kRepeatFace on every face it
// changes; when the last editor goes out of scope the three marks of those faces
// are made exact (ModelEditor), so outside an edit each mark is set exactly when
// its face needs it. When slot 2e is empty while the edge still has uses, the
// empty slot's radial field names one of them (the edge's first use).
//
// A face with one loop of edges keeps that loop in its own record (the face names
// the loop's first use); only a face with holes, or whose loop is a single vertex,
// lists its loops in Loop records. Loop ids name loops either way: LoopId(f)
// (f < kInnerLoopBit) is face f's outer loop, LoopId(kInnerLoopBit | r) the inner
// loop kept in Loop record r.
//
// Orientation: a face's loops are oriented so that, seen from the front side (the
// side its normal points to), the outer loop runs counterclockwise and inner loops
// clockwise; the face's interior is on the left of every use. The front volume is
// the 3-cell the normal points into; for a closed solid that is "none" (outside)
// and the back volume is the solid's cell.
//
// Geometry lives beside the topology: vertex positions in their own array; faces
// are planar polygons whose plane follows from their vertices.
//
// Edge and use records live in arrays indexed alike: ends_[2e + end],
// uses_[2e + k] and radial_[2e + k]. The vertex cycle steps with one load and
// no decoding, a use's start vertex is one load from its id, and a loop walk
// reads one 8-byte record per use, addressed by a scaled index
// (docs/structure-comparison.md says what the 12-byte record cost).
//
// Deleted slots go on per-kind free lists threaded through the dead records, so
// ids stay stable across edits and are reused by later creations. A use keeps
// its id while it stays on its edge; moving it to another edge (split_edge,
// merge_edges) gives it a slot of that edge, and so a new id. Accessors check
// in debug builds (assert) that the handle names a live entity.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/ids.h"

namespace cellforge::inline topo {

class ModelEditor;  // src/topo: the only code that writes records

// The analytic surface a face was faceted from (seed 000 keeps a primitive's
// defining parameters on the body; drawings, the database and feature queries
// read them). Faces without one are plain planar polygons.
struct Surface {
  std::string kind;  // "cylinder", "cone", "sphere", "torus", ...
  Vec3 center;
  Vec3 axis{0, 0, 1};
  double radius = 0;   // cylinder/sphere radius, cone base radius, torus major radius
  double radius2 = 0;  // cone top radius, torus minor radius
  double height = 0;
  int segments = 0;
  friend bool operator==(const Surface&, const Surface&) = default;
};

// A primitive's kind and parameters as the user gave them ("sphere", {"r", "10"},
// {"fn", "32"}), kept on its group.
struct Attribute {
  std::string key;
  std::string value;
  friend bool operator==(const Attribute&, const Attribute&) = default;
};

// One end of an edge, as seen from a vertex's edge cycle.
struct EdgeEnd {
  EdgeId edge;
  int end = 0;  // 0: the edge's start vertex, 1: its end vertex
  friend constexpr bool operator==(EdgeEnd, EdgeEnd) = default;
};

// Iterates the live ids of one kind in increasing order.
template <class IdT>
class LiveIds {
 public:
  class iterator {
   public:
    iterator(const LiveIds* range, std::uint32_t i) : range_(range), i_(i) { skip(); }
    IdT operator*() const { return IdT(i_); }
    iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    bool operator==(const iterator& o) const { return i_ == o.i_; }

   private:
    void skip() {
      while (i_ < range_->size_ && !range_->alive_(range_->model_, i_)) ++i_;
    }
    const LiveIds* range_;
    std::uint32_t i_;
  };

  using AliveFn = bool (*)(const void*, std::uint32_t);
  LiveIds(const void* model, std::uint32_t size, AliveFn alive)
      : model_(model), size_(size), alive_(alive) {}
  iterator begin() const { return iterator(this, 0); }
  iterator end() const { return iterator(this, size_); }

 private:
  const void* model_;
  std::uint32_t size_;
  AliveFn alive_;
};

class Model {
 public:
  Model() = default;

  // ---- counts of live entities
  std::size_t num_vertices() const { return live_[kVertex]; }
  std::size_t num_edges() const { return live_[kEdge]; }
  std::size_t num_edge_uses() const { return live_[kUse]; }
  // Every face has one outer loop; Loop records beyond a listed face's first are
  // inner loops.
  std::size_t num_loops() const { return live_[kFace] + live_[kLoop] - listed_faces_; }
  std::size_t num_loop_records() const { return live_[kLoop]; }
  std::size_t num_faces() const { return live_[kFace]; }
  std::size_t num_volumes() const { return live_[kVolume]; }
  std::size_t num_groups() const { return live_[kGroup]; }
  bool empty() const;

  // ---- liveness of a handle (false for invalid or deleted ids)
  bool is_live(VertexId v) const {
    return v.value < vertices_.size() && vertices_[v.value].first_end != kDead;
  }
  // (A free edge slot and a spare pair both carry kTagBit in their first end.)
  bool is_live(EdgeId e) const {
    return e.value < edge_slots() && !(ends_[2 * e.value].vertex & kTagBit);
  }
  bool is_live(EdgeUseId u) const {
    return u.value < uses_.size() && uses_[u.value].face_dir != kNoUse;
  }
  bool is_live(LoopId l) const;
  bool is_live(FaceId f) const { return f.value < faces_.size() && faces_[f.value].sides != kDead; }
  bool is_live(VolumeId c) const {
    return c.value < volumes_.size() && volumes_[c.value].group != kDead;
  }
  bool is_live(GroupId g) const { return g.value < groups_.size() && groups_[g.value].live; }

  // ---- iteration over live entities, in increasing id order
  LiveIds<VertexId> vertices() const;
  LiveIds<EdgeId> edges() const;
  LiveIds<EdgeUseId> edge_uses() const;
  std::vector<LoopId> loops() const;  // outer loops by face, then inner loops
  LiveIds<FaceId> faces() const;
  LiveIds<VolumeId> volumes() const;
  LiveIds<GroupId> groups() const;

  // ---- vertices
  Vec3 position(VertexId v) const {
    assert(is_live(v));
    return positions_[v.value];
  }
  GroupId group_of(VertexId v) const;  // binary search of the group runs
  // First end of v's edge cycle; invalid edge for an isolated vertex.
  EdgeEnd first_end(VertexId v) const { return decode_end(vertices_[v.value].first_end); }
  // The point loop at v (a loop that is the single vertex v), if any. A vertex with
  // a point loop has no edges; its record then names the loop instead of an edge.
  LoopId point_loop(VertexId v) const {
    const std::uint32_t c = vertices_[v.value].first_end;
    return (c != kInvalidIndex && (c & kTagBit)) ? LoopId(c & ~kTagBit) : LoopId();
  }
  // The next edge end around the same vertex (the vertex cycle).
  EdgeEnd next_end_around(EdgeEnd end) const { return decode_end(ends_[encode_end(end)].next_end); }
  std::size_t degree(VertexId v) const;  // number of edge ends at v
  // One step of a vertex walk: the edge end at the vertex and the vertex at the
  // edge's other end.
  struct VertexEnd {
    EdgeEnd end;
    VertexId other;
  };
  // Walks v's vertex cycle from first_end(v), calling on_end(VertexEnd) for every
  // edge end at v (a field the callback ignores is not read). The queries' vertex
  // walks; not for a model an operator is editing.
  template <class EndFn>
  void for_each_end_around(VertexId v, EndFn on_end) const {
    const std::uint32_t first = vertices_[v.value].first_end;
    if (first & kTagBit) return;        // no edges: a bare vertex, or a point loop's
    const EndRec* ends = ends_.data();  // held: the callback's stores could alias it
    std::uint32_t c = first;
    do {
      on_end(VertexEnd{{EdgeId(c >> 1), static_cast<int>(c & 1u)}, VertexId(ends[c ^ 1u].vertex)});
      c = ends[c].next_end;
    } while (c != first);
  }

  // ---- edges
  VertexId vertex_of(EdgeId e, int end) const {
    assert(is_live(e));
    return VertexId(ends_[2 * e.value + static_cast<std::uint32_t>(end)].vertex);
  }
  VertexId start_of(EdgeId e) const { return vertex_of(e, 0); }
  VertexId end_of(EdgeId e) const { return vertex_of(e, 1); }
  // First use of e's radial cycle: slot 2e when used, else the use the empty
  // slot names; invalid for a wire edge.
  EdgeUseId first_use(EdgeId e) const {
    assert(is_live(e));
    const std::uint32_t u = 2 * e.value;
    return EdgeUseId(uses_[u].face_dir != kNoUse ? u : radial_[u]);
  }
  GroupId group_of(EdgeId e) const { return group_of(start_of(e)); }
  bool is_wire(EdgeId e) const { return !first_use(e).is_valid(); }
  std::size_t use_count(EdgeId e) const;  // number of uses in its radial cycle

  // ---- edge uses
  // From the use's id: u/2, or for an overflow slot the edge its end record names.
  EdgeId edge_of(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeId(use_edge(uses_[u.value], ends_.data(), u.value));
  }
  // True when u sits in an overflow slot (its edge has two other uses in its
  // own slots, or had when u was made).
  bool in_overflow_slot(EdgeUseId u) const { return (uses_[u.value].face_dir & kOverflowBit) != 0; }
  // True when u sits in slot 2 * edge + direction (model.h, top).
  bool is_in_place(EdgeUseId u) const {
    const std::uint32_t fd = uses_[u.value].face_dir;
    return !(fd & kOverflowBit) && (u.value & 1u) == (fd >> 31);
  }
  // True when u runs from the edge's end vertex to its start vertex.
  bool is_reversed(EdgeUseId u) const { return (uses_[u.value].face_dir & kTagBit) != 0; }
  VertexId use_start(EdgeUseId u) const { return vertex_of(edge_of(u), is_reversed(u) ? 1 : 0); }
  VertexId use_end(EdgeUseId u) const { return vertex_of(edge_of(u), is_reversed(u) ? 0 : 1); }
  FaceId face_of(EdgeUseId u) const {
    assert(is_live(u));
    return FaceId(uses_[u.value].face_dir & kFaceMask);
  }
  EdgeUseId loop_next(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeUseId(uses_[u.value].next);
  }
  EdgeUseId loop_prev(EdgeUseId u) const;  // walks the loop: O(loop length)
  EdgeUseId radial_next(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeUseId(radial_[u.value]);
  }
  LoopId loop_of(EdgeUseId u) const;  // walks the face's loops: O(face size)

  // ---- loops
  // LoopId(f) is face f's outer loop; LoopId(kInnerLoopBit | r) an inner loop.
  static constexpr std::uint32_t kInnerLoopBit = 0x40000000u;
  // First use of l; invalid when l is a point loop (a loop that is one vertex).
  EdgeUseId loop_first(LoopId l) const {
    const std::uint32_t f = loop_start(l);
    return (f & kTagBit) ? EdgeUseId() : EdgeUseId(f);
  }
  bool is_point_loop(LoopId l) const {
    const std::uint32_t f = loop_start(l);
    return f != kInvalidIndex && (f & kTagBit) != 0;
  }
  VertexId point_loop_vertex(LoopId l) const { return VertexId(loop_start(l) & ~kTagBit); }
  // Next loop of the same face; invalid after the last one.
  LoopId next_loop(LoopId l) const {
    std::uint32_t r;
    if (l.value & kInnerLoopBit) {
      r = l.value & ~kInnerLoopBit;
    } else {
      r = faces_[l.value].first;
      if (!(r & kTagBit) || r == kInvalidIndex) return LoopId();  // the face's only loop
      r &= ~kTagBit;
    }
    const std::uint32_t n = loops_[r].next;
    return (n & kTagBit) ? LoopId() : LoopId(n | kInnerLoopBit);
  }
  // O(1) for an outer loop; walks the face's loop list for an inner one.
  FaceId face_of(LoopId l) const {
    if (!(l.value & kInnerLoopBit)) return FaceId(l.value);
    std::uint32_t n = loops_[l.value & ~kInnerLoopBit].next;
    while (!(n & kTagBit)) n = loops_[n].next;
    return n == kInvalidIndex ? FaceId() : FaceId(n & ~kTagBit);
  }
  std::size_t loop_length(LoopId l) const;  // number of uses (0 for a point loop)

  // ---- faces
  LoopId outer_loop(FaceId f) const {
    assert(is_live(f));
    return faces_[f.value].first == kInvalidIndex ? LoopId() : LoopId(f.value);
  }
  std::size_t inner_loop_count(FaceId f) const;
  // One use of a face walk: the use and its edge.
  struct FaceUse {
    EdgeUseId use;
    EdgeId edge;
  };
  // Walks f's loops of edges in order (outer first), reading each record once:
  // calls on_use(FaceUse) for every use, in loop order (point loops have none).
  // The F->E and F->F walks; not for a model an operator is editing.
  template <class UseFn>
  void for_each_face_use(FaceId f, UseFn on_use) const {
    const FaceRec face = faces_[f.value];
    if (face.sides & kOverflowFace) {
      for_each_loop_of(
          face, [&](std::uint32_t first) { walk_loop<true>(first, on_use); }, [](VertexId) {});
    } else {
      for_each_loop_of(
          face, [&](std::uint32_t first) { walk_loop<false>(first, on_use); }, [](VertexId) {});
    }
  }
  // Walks f's loops in order (outer first), calling on_vertex(VertexId) for every
  // use's start vertex, in loop order, and for a point loop's vertex: the F->V walk.
  // It finds the edge of every other use only: a use's end vertex is the next
  // use's start, and the edge's two end records sit side by side. Not for a model
  // an operator is editing (it relies on closed, continuous loops).
  template <class VertexFn>
  void for_each_face_vertex(FaceId f, VertexFn on_vertex) const {
    const FaceRec face = faces_[f.value];
    if (face.sides & kUnplacedFace) {
      for_each_loop_of(
          face, [&](std::uint32_t first) { walk_loop_vertices<true>(first, on_vertex); }, on_vertex);
    } else {
      for_each_loop_of(
          face, [&](std::uint32_t first) { walk_loop_vertices<false>(first, on_vertex); }, on_vertex);
    }
  }
  VolumeId front_volume(FaceId f) const { return VolumeId(side_row(f).front); }
  VolumeId back_volume(FaceId f) const { return VolumeId(side_row(f).back); }
  GroupId group_of(FaceId f) const { return GroupId(side_row(f).group); }
  // False when every use of f is in place (model.h, top); true when one may not
  // be (the mark is set with such a use and made exact when an operator closes
  // the face).
  bool may_hold_unplaced_uses(FaceId f) const { return (faces_[f.value].sides & kUnplacedFace) != 0; }
  // False when no use of f sits in an overflow slot (marked likewise).
  bool may_hold_overflow_uses(FaceId f) const { return (faces_[f.value].sides & kOverflowFace) != 0; }
  // False when f's loops name no edge twice and no vertex twice (counting point
  // loops), so that its F->E and F->V walks give each answer once.
  bool may_repeat_elements(FaceId f) const { return (faces_[f.value].sides & kRepeatFace) != 0; }
  // True while a ModelEditor is alive: face marks may then be set where not needed.
  bool being_edited() const { return edit_depth_ != 0; }
  // The vertex cycle of loop l, in loop order (one vertex for a point loop).
  std::vector<VertexId> loop_vertices(LoopId l) const;
  std::vector<Vec3> loop_points(LoopId l) const;
  // Newell normal of the outer loop (not normalized; twice the vector area).
  Vec3 face_normal(FaceId f) const;

  // ---- volumes and groups
  GroupId group_of(VolumeId c) const { return GroupId(volumes_[c.value].group); }
  const std::string& name(GroupId g) const { return groups_[g.value].name; }
  void set_name(GroupId g, std::string name) { groups_[g.value].name = std::move(name); }
  const std::vector<Attribute>& attributes(GroupId g) const { return groups_[g.value].attributes; }
  void set_attribute(GroupId g, std::string key, std::string value);
  // The attribute's value, or "" when it is absent.
  std::string attribute(GroupId g, const std::string& key) const;

  // ---- analytic surfaces behind faceted faces
  std::uint32_t add_surface(Surface s);
  std::size_t num_surfaces() const { return surfaces_.size(); }
  const Surface& surface(std::uint32_t id) const { return surfaces_[id]; }
  // kInvalidIndex for a plain planar face.
  std::uint32_t surface_of(FaceId f) const {
    return f.value < face_surface_.size() ? face_surface_[f.value] : kInvalidIndex;
  }
  void set_surface(FaceId f, std::uint32_t surface);
  // An edge between two facets of one curved surface is smooth (drawn only as
  // part of a silhouette).
  bool is_smooth(EdgeId e) const;

  // ---- memory
  // Bytes held by the topology arrays (records of every slot, live or free, and
  // the interned side table); positions and names are geometry and not counted.
  std::size_t topology_bytes() const;
  std::size_t geometry_bytes() const { return positions_.size() * sizeof(Vec3); }

  // Edge ids (spare pairs included) stay below 2^30 so that an encoded edge end
  // never sets the tag bit; face ids and Loop records below 2^30 - 1 so that a
  // loop id fits beside the tag and a face id beside a use's direction and
  // overflow bits, apart from the empty-slot mark.
  static constexpr std::uint32_t kMaxEdges = 1u << 30;
  static constexpr std::uint32_t kMaxFaces = (1u << 30) - 1;

  // ---- raw record sizes, for the storage comparison
  static constexpr std::size_t kVertexRecordBytes = 4;
  static constexpr std::size_t kEdgeRecordBytes = 16;  // plus its two use slots
  static constexpr std::size_t kUseRecordBytes = 12;  // 8 in uses_, 4 in radial_
  static constexpr std::size_t kLoopRecordBytes = 8;
  static constexpr std::size_t kFaceRecordBytes = 8;

  // Slot counts (live + free), for iteration by index.
  std::uint32_t vertex_slots() const { return static_cast<std::uint32_t>(vertices_.size()); }
  std::size_t vertex_group_runs() const { return vertex_groups_.size(); }  // 8 B each
  std::size_t free_vertex_slots() const { return free_vertices_.size(); }  // 4 B each
  // Edge slots include spare pairs (overflow use slots); use slots are two per edge slot.
  std::uint32_t edge_slots() const { return static_cast<std::uint32_t>(ends_.size() / 2); }
  std::uint32_t use_slots() const { return static_cast<std::uint32_t>(uses_.size()); }
  // True when edge slot i is a spare pair (holds overflow use slots, not an edge).
  bool is_spare_pair(std::uint32_t i) const {
    const std::uint32_t v = ends_[2 * i].vertex;
    return (v & kTagBit) && v != kDead;
  }
  std::size_t spare_pairs() const;  // how many edge slots are spare pairs (a scan)
  std::uint32_t loop_slots() const { return static_cast<std::uint32_t>(loops_.size()); }  // records
  std::uint32_t face_slots() const { return static_cast<std::uint32_t>(faces_.size()); }

 private:
  friend class ModelEditor;

  static constexpr std::uint32_t kDead = 0xFFFFFFFEu;  // marks a free slot
  static constexpr std::uint32_t kTagBit = 0x80000000u;
  // A use's face_dir: the face in the low 30 bits, kOverflowBit for a use in an
  // overflow slot, kTagBit when reversed; kNoUse for an empty slot.
  static constexpr std::uint32_t kOverflowBit = 0x40000000u;
  static constexpr std::uint32_t kFaceMask = 0x3FFFFFFFu;
  static constexpr std::uint32_t kNoUse = kFaceMask;
  // The first end record of a spare pair's free slot (a used one holds
  // kTagBit | edge).
  static constexpr std::uint32_t kSpare = 0xFFFFFFFDu;

  static EdgeEnd decode_end(std::uint32_t code) {
    if (code & kTagBit) return {};  // invalid, or a vertex's point-loop tag
    return {EdgeId(code >> 1), static_cast<int>(code & 1u)};
  }
  static std::uint32_t encode_end(EdgeEnd end) {
    return end.edge.is_valid() ? (end.edge.value << 1) | static_cast<std::uint32_t>(end.end)
                               : kInvalidIndex;
  }

  struct VertexRec {
    // Encoded edge end, kTagBit|loop id for a point loop, invalid for a bare
    // vertex; kDead when the slot is free (free slots are kept in free_vertices_).
    std::uint32_t first_end;
  };
  struct GroupRun {
    std::uint32_t first_vertex;  // the run holds vertex ids from here to the next run
    std::uint32_t group;
  };
  // One end of an edge, at index 2*edge + end of ends_ (the encoded end). In a
  // spare pair each record serves the overflow use slot of the same index.
  struct EndRec {
    // The end's vertex; kDead at end 0 of a free edge slot; in a spare pair
    // kTagBit | the use's edge, or kSpare when the slot is free.
    std::uint32_t vertex;
    // Encoded: the next edge end around the same vertex; links the free list of
    // edge slots (at end 0) and of overflow slots.
    std::uint32_t next_end;
  };
  // A use's loop fields; its radial link is in radial_ (same index).
  struct UseRec {
    std::uint32_t face_dir;  // see kOverflowBit; kNoUse for an empty slot
    std::uint32_t next;      // next use of its loop
  };
  struct LoopRec {
    std::uint32_t first;  // use id, or kTagBit|vertex for a point loop; kDead when free
    std::uint32_t next;   // next Loop record of the face, or kTagBit|face after the last
  };
  struct FaceRec {
    // The outer loop's first use when the face has that one loop of edges;
    // kTagBit|Loop record of its first loop otherwise; kInvalidIndex while empty.
    std::uint32_t first;
    // Index into sides_ (below kMaxSideRows), | kUnplacedFace when a use of the
    // face may not be in place, | kOverflowFace too when one may sit in an
    // overflow slot, | kRepeatFace when its loops may name an edge or a vertex
    // twice, | kTouchedFace while an edit lists it; kDead when free (first links
    // the list).
    std::uint32_t sides;
  };
  static constexpr std::uint32_t kOverflowFace = 0x40000000u;
  static constexpr std::uint32_t kUnplacedFace = 0x20000000u;
  static constexpr std::uint32_t kRepeatFace = 0x10000000u;
  // Set while the face is listed in touched_faces_ (during an edit only).
  static constexpr std::uint32_t kTouchedFace = 0x08000000u;
  static constexpr std::uint32_t kFaceMarks = kOverflowFace | kUnplacedFace | kRepeatFace | kTouchedFace;
  static constexpr std::uint32_t kMaxSideRows = kTouchedFace;
  struct SidesRec {
    std::uint32_t front, back, group;
    friend bool operator==(const SidesRec&, const SidesRec&) = default;
  };
  const SidesRec& side_row(FaceId f) const { return sides_[faces_[f.value].sides & ~kFaceMarks]; }
  struct VolumeRec {
    std::uint32_t group;  // kDead when free
    std::uint32_t next_free;
  };
  struct GroupRec {
    bool live = true;
    std::string name;
    std::vector<Attribute> attributes;
  };

  enum Kind { kVertex, kEdge, kUse, kLoop, kFace, kVolume, kGroup, kKinds };

  std::vector<VertexRec> vertices_;
  std::vector<GroupRun> vertex_groups_;  // sorted by first_vertex
  std::vector<std::uint32_t> free_vertices_;
  std::vector<Vec3> positions_;
  std::vector<EndRec> ends_;  // two per edge slot
  std::vector<UseRec> uses_;  // two per edge slot
  // Per use slot: the next use around its edge (the cycle closes); in an empty
  // slot 2e of an edge with uses, its first use; kInvalidIndex otherwise.
  std::vector<std::uint32_t> radial_;
  std::vector<LoopRec> loops_;
  std::vector<FaceRec> faces_;
  std::vector<SidesRec> sides_;
  std::vector<VolumeRec> volumes_;
  std::vector<GroupRec> groups_;
  std::vector<Surface> surfaces_;
  std::size_t listed_faces_ = 0;       // live faces whose loops are in Loop records
  std::vector<std::uint32_t> open_faces_;  // faces an operator is editing (ModelEditor)
  // Faces an edit has changed (kTouchedFace), whose marks are made exact when the
  // last editor goes out of scope.
  std::vector<std::uint32_t> touched_faces_;
  int edit_depth_ = 0;

  // The raw start of loop l: a use id, kTagBit|vertex (point loop), or kInvalidIndex.
  std::uint32_t loop_start(LoopId l) const {
    if (l.value & kInnerLoopBit) return loops_[l.value & ~kInnerLoopBit].first;
    const std::uint32_t f = faces_[l.value].first;
    if (!(f & kTagBit) || f == kInvalidIndex) return f;
    return loops_[f & ~kTagBit].first;
  }
  // The uses of the loop of edges that starts at `first`, for for_each_face_use.
  // kAny: the face may hold uses in overflow slots (kOverflowFace); for a face
  // that holds none every use's edge is u / 2, without a test.
  template <bool kAny, class UseFn>
  void walk_loop(std::uint32_t first, UseFn& on_use) const {
    // The array's address is held here: the callback's stores could alias the
    // vector, which would otherwise be re-read for every use.
    const UseRec* uses = uses_.data();
    const EndRec* ends = ends_.data();
    std::uint32_t u = first;
    do {
      const UseRec& rec = uses[u];
      const std::uint32_t next = rec.next;  // read before the callback's stores
      on_use(FaceUse{EdgeUseId(u), EdgeId(kAny ? use_edge(rec, ends, u) : u >> 1)});
      u = next;
    } while (u != first);
  }
  // The start vertices of the loop of edges that starts at `first`, for
  // for_each_face_vertex: two per edge found, u's start and its end (the next
  // use's start), so a loop of n uses looks up ceil(n / 2) edges.
  // kAny: the face may hold uses that are not in place (kUnplacedFace); for a
  // face that holds none u's start is ends[u] and its end ends[u ^ 1], so the
  // walk reads no use's face field.
  template <bool kAny, class VertexFn>
  void walk_loop_vertices(std::uint32_t first, VertexFn& on_vertex) const {
    const UseRec* uses = uses_.data();
    const EndRec* ends = ends_.data();
    std::uint32_t u = first;
    for (;;) {
      const UseRec& rec = uses[u];
      const std::uint32_t c = kAny ? 2 * use_edge(rec, ends, u) + (rec.face_dir >> 31) : u;
      on_vertex(VertexId(ends[c].vertex));
      const std::uint32_t n = rec.next;
      if (n == first) return;
      on_vertex(VertexId(ends[c ^ 1u].vertex));  // n's start is u's end
      u = uses[n].next;
      if (u == first) return;
    }
  }
  // f's loops in order: on_loop(first use) for a loop of edges, on_point(vertex)
  // for a point loop. A face without holes has its loop's first use in its record;
  // a face with holes or a point loop lists its loops in Loop records.
  template <class LoopFn, class PointFn>
  void for_each_loop_of(const FaceRec& face, LoopFn&& on_loop, PointFn&& on_point) const {
    const std::uint32_t first = face.first;
    if (!(first & kTagBit)) {
      on_loop(first);
      return;
    }
    if (first == kInvalidIndex) return;
    for (std::uint32_t r = first & ~kTagBit;;) {
      const LoopRec loop = loops_[r];
      if (loop.first & kTagBit)
        on_point(VertexId(loop.first & ~kTagBit));
      else
        on_loop(loop.first);
      if (loop.next & kTagBit) return;
      r = loop.next;
    }
  }
  // The edge of the use in slot u, whose record is rec: u/2, or for an overflow
  // slot the edge its end record names. It computes both and selects one (a
  // conditional move; the end record at index u is always there to read): in the
  // walks of marked faces a branch on the overflow bit was mispredicted. It takes
  // the array so that a walk can keep its address in a register.
  static std::uint32_t use_edge(const UseRec& rec, const EndRec* ends, std::uint32_t u) {
    const std::uint32_t spare = ends[u].vertex & ~kTagBit;
    const std::uint32_t own = u >> 1;
    return (rec.face_dir & kOverflowBit) ? spare : own;
  }
  std::vector<std::uint32_t> face_surface_;  // per face slot, kInvalidIndex = plane
  std::uint32_t free_[kKinds] = {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex,
                                 kInvalidIndex, kInvalidIndex, kInvalidIndex};
  std::size_t live_[kKinds] = {};
};

}  // namespace cellforge::inline topo
