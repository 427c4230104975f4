// The records behind Model (model.h): the storage layout of the adjacent-dimension
// cycle structure, its bit masks and the slot machinery. Not API: Model derives
// from ModelRecords privately, and only src/topo/ (ModelEditor, the one writer)
// reads these names; they are in a header only because the inline read API
// (model.h) compiles to direct loads from these arrays. model.h's top comment
// explains the layout; docs/topology.md the reasons for it.
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
//            built group by group has one run per group); the group index
//            keeps such runs for edges, faces and volumes too, beside the records
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
// Edge and use records live in arrays indexed alike: ends_[2e + end],
// uses_[2e + k] and radial_[2e + k]. The vertex cycle steps with one load and
// no decoding, a use's start vertex is one load from its id, and a loop walk
// reads one 8-byte record per use, addressed by a scaled index
// (docs/structure-comparison.md says what the 12-byte record cost).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/ids.h"
#include "cellforge/topo/types.h"

namespace cellforge::inline topo::detail {

// A run of consecutive ids of one kind made in one group: the run holds the ids
// from `first` up to the next run's first (the group index, below).
struct GroupRun {
  std::uint32_t first;
  std::uint32_t group;
};

// A group's live elements of each kind (the group index, below).
struct GroupCounts {
  std::uint32_t vertices = 0, edges = 0, faces = 0, volumes = 0;
};

class ModelRecords {
 protected:
  // LoopId(f) is face f's outer loop; LoopId(kInnerLoopBit | r) an inner loop.
  static constexpr std::uint32_t kInnerLoopBit = 0x40000000u;

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
  using GroupRun = detail::GroupRun;
  using GroupCounts = detail::GroupCounts;
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
  std::vector<GroupRun> vertex_groups_;  // sorted by first: the group of every vertex
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
  // The group index, a side table beside the records (which hold each element's
  // group already: a vertex by vertex_groups_, an edge by its start vertex, a face
  // by its side row, a volume in its record): for edges, faces and volumes the
  // runs of consecutive slot ids made in one group, sorted by first, as
  // vertex_groups_ is for vertices, so that a group lists its own elements by
  // its runs without reading the other groups' records; and the live counts of
  // each group slot. Slots freed stay in their run (iteration skips dead ones)
  // until a creation in another group takes them. A model built group by group
  // has one run per group and kind.
  std::vector<GroupRun> edge_groups_, face_groups_, volume_groups_;
  std::vector<GroupCounts> group_counts_;  // per group slot
  std::uint32_t free_[kKinds] = {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex,
                                 kInvalidIndex, kInvalidIndex, kInvalidIndex};
  std::size_t live_[kKinds] = {};
};

}  // namespace cellforge::inline topo::detail
