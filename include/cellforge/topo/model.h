// The adjacent-dimension cycle structure (seed 000, GEMS 4.0): a face-centred,
// non-manifold boundary representation kept in flat arrays with 32-bit ids.
//
// Entities and what each record holds (all fields are 32-bit indices):
//   Vertex   first edge end of its vertex cycle, group            (8 B)
//   Edge     per end: vertex, next end around that vertex;
//            first use of its radial cycle                         (20 B)
//   EdgeUse  edge + direction bit, face, next use in its loop,
//            next use around its edge (radial cycle)               (16 B)
//   Loop     first use (or, for a point loop, its vertex),
//            next loop of the same face (the last one names the face) (8 B)
//   Face     first loop (the outer one), interned side record      (8 B)
//   Sides    front volume, back volume, group (shared by all faces with
//            the same three values; a closed solid's faces share one)
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
// ids stay stable across edits and are reused by later creations. Accessors check
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

namespace cellforge {

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
  std::size_t num_loops() const { return live_[kLoop]; }
  std::size_t num_faces() const { return live_[kFace]; }
  std::size_t num_volumes() const { return live_[kVolume]; }
  std::size_t num_groups() const { return live_[kGroup]; }
  bool empty() const;

  // ---- liveness of a handle (false for invalid or deleted ids)
  bool is_live(VertexId v) const {
    return v.value < vertices_.size() && vertices_[v.value].group != kDead;
  }
  bool is_live(EdgeId e) const {
    return e.value < edges_.size() && edges_[e.value].vertex[0] != kDead;
  }
  bool is_live(EdgeUseId u) const {
    return u.value < uses_.size() && uses_[u.value].edge_dir != kDead;
  }
  bool is_live(LoopId l) const { return l.value < loops_.size() && loops_[l.value].first != kDead; }
  bool is_live(FaceId f) const { return f.value < faces_.size() && faces_[f.value].sides != kDead; }
  bool is_live(VolumeId c) const {
    return c.value < volumes_.size() && volumes_[c.value].group != kDead;
  }
  bool is_live(GroupId g) const { return g.value < groups_.size() && groups_[g.value].live; }

  // ---- iteration over live entities, in increasing id order
  LiveIds<VertexId> vertices() const;
  LiveIds<EdgeId> edges() const;
  LiveIds<EdgeUseId> edge_uses() const;
  LiveIds<LoopId> loops() const;
  LiveIds<FaceId> faces() const;
  LiveIds<VolumeId> volumes() const;
  LiveIds<GroupId> groups() const;

  // ---- vertices
  Vec3 position(VertexId v) const {
    assert(is_live(v));
    return positions_[v.value];
  }
  GroupId group_of(VertexId v) const { return GroupId(vertices_[v.value].group); }
  // First end of v's edge cycle; invalid edge for an isolated vertex.
  EdgeEnd first_end(VertexId v) const { return decode_end(vertices_[v.value].first_end); }
  // The point loop at v (a loop that is the single vertex v), if any. A vertex with
  // a point loop has no edges; its record then names the loop instead of an edge.
  LoopId point_loop(VertexId v) const {
    const std::uint32_t c = vertices_[v.value].first_end;
    return (c != kInvalidIndex && (c & kTagBit)) ? LoopId(c & ~kTagBit) : LoopId();
  }
  // The next edge end around the same vertex (the vertex cycle).
  EdgeEnd next_end_around(EdgeEnd end) const {
    return decode_end(edges_[end.edge.value].next_end[end.end]);
  }
  std::size_t degree(VertexId v) const;  // number of edge ends at v

  // ---- edges
  VertexId vertex_of(EdgeId e, int end) const {
    assert(is_live(e));
    return VertexId(edges_[e.value].vertex[end]);
  }
  VertexId start_of(EdgeId e) const { return vertex_of(e, 0); }
  VertexId end_of(EdgeId e) const { return vertex_of(e, 1); }
  // First use of e's radial cycle; invalid for a wire edge.
  EdgeUseId first_use(EdgeId e) const {
    assert(is_live(e));
    return EdgeUseId(edges_[e.value].first_use);
  }
  GroupId group_of(EdgeId e) const { return group_of(start_of(e)); }
  bool is_wire(EdgeId e) const { return !first_use(e).is_valid(); }
  std::size_t use_count(EdgeId e) const;  // number of uses in its radial cycle

  // ---- edge uses
  EdgeId edge_of(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeId(uses_[u.value].edge_dir >> 1);
  }
  // True when u runs from the edge's end vertex to its start vertex.
  bool is_reversed(EdgeUseId u) const { return (uses_[u.value].edge_dir & 1u) != 0; }
  VertexId use_start(EdgeUseId u) const { return vertex_of(edge_of(u), is_reversed(u) ? 1 : 0); }
  VertexId use_end(EdgeUseId u) const { return vertex_of(edge_of(u), is_reversed(u) ? 0 : 1); }
  FaceId face_of(EdgeUseId u) const {
    assert(is_live(u));
    return FaceId(uses_[u.value].face);
  }
  EdgeUseId loop_next(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeUseId(uses_[u.value].next);
  }
  EdgeUseId loop_prev(EdgeUseId u) const;  // walks the loop: O(loop length)
  EdgeUseId radial_next(EdgeUseId u) const {
    assert(is_live(u));
    return EdgeUseId(uses_[u.value].radial_next);
  }
  LoopId loop_of(EdgeUseId u) const;  // walks the face's loops: O(face size)

  // ---- loops
  // First use of l; invalid when l is a point loop (a loop that is one vertex).
  EdgeUseId loop_first(LoopId l) const {
    const std::uint32_t f = loops_[l.value].first;
    return (f & kTagBit) ? EdgeUseId() : EdgeUseId(f);
  }
  bool is_point_loop(LoopId l) const { return (loops_[l.value].first & kTagBit) != 0; }
  VertexId point_loop_vertex(LoopId l) const { return VertexId(loops_[l.value].first & ~kTagBit); }
  // Next loop of the same face; invalid after the last one.
  LoopId next_loop(LoopId l) const {
    const std::uint32_t n = loops_[l.value].next;
    return (n & kTagBit) ? LoopId() : LoopId(n);
  }
  FaceId face_of(LoopId l) const;           // walks the face's loop list: O(loops of the face)
  std::size_t loop_length(LoopId l) const;  // number of uses (0 for a point loop)

  // ---- faces
  LoopId outer_loop(FaceId f) const {
    assert(is_live(f));
    return LoopId(faces_[f.value].first_loop);
  }
  std::size_t inner_loop_count(FaceId f) const;
  VolumeId front_volume(FaceId f) const { return VolumeId(sides_[faces_[f.value].sides].front); }
  VolumeId back_volume(FaceId f) const { return VolumeId(sides_[faces_[f.value].sides].back); }
  GroupId group_of(FaceId f) const { return GroupId(sides_[faces_[f.value].sides].group); }
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

  // Edge ids stay below 2^30 so that an encoded edge end never sets the tag bit.
  static constexpr std::uint32_t kMaxEdges = 1u << 30;

  // ---- raw record sizes, for the storage comparison
  static constexpr std::size_t kVertexRecordBytes = 8;
  static constexpr std::size_t kEdgeRecordBytes = 20;
  static constexpr std::size_t kUseRecordBytes = 16;
  static constexpr std::size_t kLoopRecordBytes = 8;
  static constexpr std::size_t kFaceRecordBytes = 8;

  // Slot counts (live + free), for iteration by index.
  std::uint32_t vertex_slots() const { return static_cast<std::uint32_t>(vertices_.size()); }
  std::uint32_t edge_slots() const { return static_cast<std::uint32_t>(edges_.size()); }
  std::uint32_t use_slots() const { return static_cast<std::uint32_t>(uses_.size()); }
  std::uint32_t loop_slots() const { return static_cast<std::uint32_t>(loops_.size()); }
  std::uint32_t face_slots() const { return static_cast<std::uint32_t>(faces_.size()); }

 private:
  friend class ModelEditor;

  static constexpr std::uint32_t kDead = 0xFFFFFFFEu;  // marks a free slot
  static constexpr std::uint32_t kTagBit = 0x80000000u;

  static EdgeEnd decode_end(std::uint32_t code) {
    if (code & kTagBit) return {};  // invalid, or a vertex's point-loop tag
    return {EdgeId(code >> 1), static_cast<int>(code & 1u)};
  }
  static std::uint32_t encode_end(EdgeEnd end) {
    return end.edge.is_valid() ? (end.edge.value << 1) | static_cast<std::uint32_t>(end.end)
                               : kInvalidIndex;
  }

  struct VertexRec {
    std::uint32_t first_end;  // encoded edge end, kTagBit|loop for a point loop, or invalid
    std::uint32_t group;      // kDead when the slot is free; first_end then links the free list
  };
  struct EdgeRec {
    std::uint32_t vertex[2];  // vertex[0] == kDead when free; first_use links the free list
    std::uint32_t next_end[2];
    std::uint32_t first_use;
  };
  struct UseRec {
    std::uint32_t edge_dir;  // 2*edge + reversed; kDead when free (next links the free list)
    std::uint32_t face;
    std::uint32_t next;
    std::uint32_t radial_next;
  };
  struct LoopRec {
    std::uint32_t first;  // use id, or kTagBit|vertex for a point loop; kDead when free
    std::uint32_t next;   // next loop id, or kTagBit|face after the last loop
  };
  struct FaceRec {
    std::uint32_t first_loop;
    std::uint32_t sides;  // index into sides_; kDead when free (first_loop links the list)
  };
  struct SidesRec {
    std::uint32_t front, back, group;
    friend bool operator==(const SidesRec&, const SidesRec&) = default;
  };
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
  std::vector<Vec3> positions_;
  std::vector<EdgeRec> edges_;
  std::vector<UseRec> uses_;
  std::vector<LoopRec> loops_;
  std::vector<FaceRec> faces_;
  std::vector<SidesRec> sides_;
  std::vector<VolumeRec> volumes_;
  std::vector<GroupRec> groups_;
  std::vector<Surface> surfaces_;
  std::vector<std::uint32_t> face_surface_;  // per face slot, kInvalidIndex = plane
  std::uint32_t free_[kKinds] = {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex,
                                 kInvalidIndex, kInvalidIndex, kInvalidIndex};
  std::size_t live_[kKinds] = {};
};

}  // namespace cellforge
