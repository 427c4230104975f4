// The adjacent-dimension cycle structure (seed 000, GEMS 4.0): a face-centred,
// non-manifold boundary representation kept in flat arrays with 32-bit ids.
//
// Model's read API: counts, liveness, iteration, the cycle walks as ranges
// (radial, uses_of, ends_around, loops_of), the face and vertex walks the 9 queries
// (queries.h) are built on, and per-element data. The records, bit masks and slot
// machinery behind it are in detail/model_records.h, which is not API.
//
// The two cycles that name the structure:
//   vertex -> its edges: each edge end links to the next edge end around the same
//             vertex (an "edge end" is 2*edge + end, end 0 = the edge's start);
//   edge -> its uses: each edge use links to the next use around the same edge,
//           in angular order (right-handed about the edge's start->end axis).
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
// Deleted slots go on per-kind free lists threaded through the dead records, so
// ids stay stable across edits and are reused by later creations. A use keeps
// its id while it stays on its edge; moving it to another edge (split_edge,
// merge_edges) gives it a slot of that edge, and so a new id. Accessors check
// in debug builds (assert) that the handle names a live entity.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/ids.h"
#include "cellforge/topo/detail/model_records.h"
#include "cellforge/topo/detail/property_store.h"
#include "cellforge/topo/types.h"

namespace cellforge::inline topo {

class ModelEditor;  // src/topo: the only code that writes records

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

// Iterates the live ids of one kind in one group, in increasing order: the ids of
// the group's runs (detail/model_records.h, the group index) that are live. Costs
// the number of runs of that kind plus the slots of the group's runs, not the
// size of the model.
template <class IdT>
class GroupMembers {
 public:
  using AliveFn = bool (*)(const void*, std::uint32_t);
  class iterator {
   public:
    using value_type = IdT;
    using difference_type = std::ptrdiff_t;
    using iterator_category = std::input_iterator_tag;
    using reference = IdT;
    using pointer = void;
    iterator() = default;
    iterator(const GroupMembers* range, std::size_t run, std::uint32_t i)
        : range_(range), run_(run), i_(i) {
      skip();
    }
    IdT operator*() const { return IdT(i_); }
    iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    iterator operator++(int) {
      iterator old = *this;
      ++*this;
      return old;
    }
    friend bool operator==(const iterator& a, const iterator& b) {
      return a.run_ == b.run_ && a.i_ == b.i_;
    }

   private:
    void skip() {
      const auto& runs = range_->runs_;
      while (run_ < runs.size()) {
        const std::uint32_t end =
            run_ + 1 < runs.size() ? std::min(runs[run_ + 1].first, range_->slots_) : range_->slots_;
        if (runs[run_].group == range_->group_) {
          if (i_ < runs[run_].first) i_ = runs[run_].first;
          while (i_ < end && !range_->alive_(range_->model_, i_)) ++i_;
          if (i_ < end) return;
        }
        ++run_;
        i_ = 0;
      }
      i_ = 0;
    }
    const GroupMembers* range_ = nullptr;
    std::size_t run_ = 0;
    std::uint32_t i_ = 0;
  };

  GroupMembers(const void* model, std::span<const detail::GroupRun> runs, std::uint32_t group,
               std::uint32_t slots, AliveFn alive)
      : model_(model), runs_(runs), group_(group), slots_(slots), alive_(alive) {}
  iterator begin() const { return iterator(this, 0, 0); }
  iterator end() const { return iterator(this, runs_.size(), 0); }

 private:
  const void* model_;
  std::span<const detail::GroupRun> runs_;
  std::uint32_t group_;
  std::uint32_t slots_;
  AliveFn alive_;
};

// The elements of a cycle or a list of links as a range: first, step(first),
// step(step(first)), ... up to the element after which step returns to first (kCycle)
// or returns an invalid element (a list). Empty when first is invalid (T{}).
// Reads the model through its public accessors as it goes: not for a model an
// operator is changing under the walk, nor for a broken cycle that does not close.
template <class T, class Step, bool kCycle>
class LinkRange {
 public:
  class iterator {
   public:
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using iterator_category = std::input_iterator_tag;
    using reference = T;
    using pointer = void;
    iterator() = default;
    iterator(const LinkRange* range, T at) : range_(range), at_(at) {}
    T operator*() const { return at_; }
    iterator& operator++() {
      const T next = range_->step_(at_);
      at_ = (kCycle && next == range_->first_) ? T{} : next;
      return *this;
    }
    iterator operator++(int) {
      iterator old = *this;
      ++*this;
      return old;
    }
    friend bool operator==(const iterator& a, const iterator& b) { return a.at_ == b.at_; }

   private:
    const LinkRange* range_ = nullptr;
    T at_{};
  };

  LinkRange(T first, Step step) : first_(first), step_(step) {}
  iterator begin() const { return iterator(this, first_); }
  iterator end() const { return iterator(this, T{}); }
  bool empty() const { return first_ == T{}; }

 private:
  T first_;
  Step step_;
};

class Model : private detail::ModelRecords {
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
  using VertexEnd = topo::VertexEnd;
  // v's vertex cycle from first_end(v): every edge end at v, once.
  //   for (EdgeEnd end : m.ends_around(v)) ...
  auto ends_around(VertexId v) const {
    const auto step = [this](EdgeEnd e) { return next_end_around(e); };
    return LinkRange<EdgeEnd, decltype(step), true>(first_end(v), step);
  }
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
  // e's radial cycle from first_use(e), in angular order (empty for a wire edge).
  //   for (EdgeUseId u : m.radial(e)) ...
  auto radial(EdgeId e) const {
    const auto step = [this](EdgeUseId u) { return radial_next(u); };
    return LinkRange<EdgeUseId, decltype(step), true>(first_use(e), step);
  }

  // ---- loops
  // LoopId(f) is face f's outer loop; LoopId(kInnerLoopBit | r) an inner loop.
  static constexpr std::uint32_t kInnerLoopBit = detail::ModelRecords::kInnerLoopBit;
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
  // The uses of loop l in loop order from loop_first(l) (none for a point loop).
  auto uses_of(LoopId l) const {
    const auto step = [this](EdgeUseId u) { return loop_next(u); };
    return LinkRange<EdgeUseId, decltype(step), true>(loop_first(l), step);
  }

  // ---- faces
  LoopId outer_loop(FaceId f) const {
    assert(is_live(f));
    return faces_[f.value].first == kInvalidIndex ? LoopId() : LoopId(f.value);
  }
  std::size_t inner_loop_count(FaceId f) const;
  // f's loops, the outer one first, then its inner loops in order.
  auto loops_of(FaceId f) const {
    const auto step = [this](LoopId l) { return next_loop(l); };
    return LinkRange<LoopId, decltype(step), false>(outer_loop(f), step);
  }
  using FaceUse = topo::FaceUse;
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
  // A group's own elements, through the group index (detail/model_records.h): its
  // live vertices, edges, faces and volumes in increasing id order, and how many
  // of each it holds, without reading the rest of the model.
  //   for (FaceId f : m.faces(g)) ...
  GroupMembers<VertexId> vertices(GroupId g) const;
  GroupMembers<EdgeId> edges(GroupId g) const;
  GroupMembers<FaceId> faces(GroupId g) const;
  GroupMembers<VolumeId> volumes(GroupId g) const;
  std::size_t num_vertices(GroupId g) const { return group_counts_[g.value].vertices; }
  std::size_t num_edges(GroupId g) const { return group_counts_[g.value].edges; }
  std::size_t num_faces(GroupId g) const { return group_counts_[g.value].faces; }
  std::size_t num_volumes(GroupId g) const { return group_counts_[g.value].volumes; }
  // True when g holds no vertex, edge, face or volume.
  bool group_empty(GroupId g) const {
    const detail::GroupCounts& c = group_counts_[g.value];
    return c.vertices == 0 && c.edges == 0 && c.faces == 0 && c.volumes == 0;
  }
  // Runs of the group index, for the validator and the storage figures.
  std::size_t group_runs() const {
    return vertex_groups_.size() + edge_groups_.size() + face_groups_.size() + volume_groups_.size();
  }
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
  // Bytes held by the topology arrays (records of every slot, live or free, the
  // interned side table and the group index); positions and names are geometry and
  // not counted.
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

  // The per-element property tables (property.h, which is their API).
  detail::PropertyStore& property_store() { return properties_; }
  const detail::PropertyStore& property_store() const { return properties_; }

 private:
  friend class ModelEditor;
  detail::PropertyStore properties_;  // beside the records, not in them
};

}  // namespace cellforge::inline topo
