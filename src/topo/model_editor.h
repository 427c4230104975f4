// ModelEditor: the one place that writes Model records. Operators and the bulk
// builder use it; it does no checking of its own (callers check first).
//
// Two ways to give faces loops:
//  - in bulk (build_mesh, restore): add_loop() / add_point_loop();
//  - in an operator: the loop calls below open the face they touch, which moves
//    its loops into Loop records so that loops can come and go. When the last
//    editor goes out of scope every opened face that is left with one loop of
//    edges keeps that loop in its own record again.
// Radial cycles are kept closed, and an empty slot 2e naming its edge's first use,
// by every call that edits them.
#pragma once

#include <unordered_map>

#include "cellforge/geom/predicates.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

class FaceNormals;  // below

class ModelEditor {
 public:
  explicit ModelEditor(Model& m) : m_(m) { ++m_.edit_depth_; }
  ~ModelEditor();
  ModelEditor(const ModelEditor&) = delete;
  ModelEditor& operator=(const ModelEditor&) = delete;

  using VertexRec = Model::VertexRec;
  using EndRec = Model::EndRec;
  using UseRec = Model::UseRec;
  using LoopRec = Model::LoopRec;
  using FaceRec = Model::FaceRec;
  using SidesRec = Model::SidesRec;
  static constexpr std::uint32_t kTagBit = Model::kTagBit;
  static constexpr std::uint32_t kDead = Model::kDead;
  static constexpr std::uint32_t kRepeatFace = Model::kRepeatFace;
  static constexpr UseRec kEmptyUse() { return {Model::kNoUse, kInvalidIndex}; }

  VertexRec& rec(VertexId v) { return m_.vertices_[v.value]; }
  EndRec& end_rec(EdgeEnd end) { return m_.ends_[Model::encode_end(end)]; }
  UseRec& rec(EdgeUseId u) { return m_.uses_[u.value]; }
  std::uint32_t& radial(std::uint32_t u) { return m_.radial_[u]; }
  FaceRec& rec(FaceId f) { return m_.faces_[f.value]; }

  // ---- creation (records come back initialised, not yet linked)
  // Room for this many more vertices, edges and faces, made at once (a mesh being
  // built) rather than by doubling: no copies, and no freed halves left behind.
  void reserve(std::size_t vertices, std::size_t edges, std::size_t faces);
  GroupId new_group(std::string name);
  VertexId new_vertex(GroupId g, Vec3 p);
  void set_vertex_group(VertexId v, GroupId g);
  EdgeId new_edge(VertexId a, VertexId b);               // links both ends into the vertex cycles
  // A use of e in one of e's slots (2e, 2e + 1, else an overflow slot). Not
  // yet in a loop (its next is itself); in e's radial cycle right after e's
  // first use, until radial_insert gives it its angular place.
  EdgeUseId new_use(EdgeId e, bool reversed, FaceId f);
  // A Loop record not yet in any face, for append_loop (operators only).
  LoopId new_point_loop(VertexId v);
  LoopId new_loop(EdgeUseId first);
  FaceId new_face(std::uint32_t sides);
  VolumeId new_volume(GroupId g);
  std::uint32_t intern_sides(VolumeId front, VolumeId back, GroupId g);

  // ---- deletion (the caller has unlinked the entity from everything)
  void free_vertex(VertexId v);
  void free_edge(EdgeId e);  // unlinks both ends from the vertex cycles first; e has no uses
  void free_use(EdgeUseId u);  // takes u out of its radial cycle (the caller unlinked its loop)
  void free_loop(LoopId l);  // its uses are dead or moved; clears a point loop's mark
  void free_face(FaceId f);
  void free_volume(VolumeId c);
  void free_group(GroupId g);

  // ---- vertex cycles
  void link_end(VertexId v, EdgeEnd end);    // inserts end into v's cycle
  void unlink_end(VertexId v, EdgeEnd end);  // removes end from v's cycle
  // Moves an edge end from its vertex to another one.
  void move_end(EdgeEnd end, VertexId to);

  // ---- radial cycles
  // Gives u (in its edge's cycle since new_use) its angular place there.
  void radial_insert(EdgeUseId u);
  // Sorts the whole radial cycle of e by angle (after bulk changes).
  void radial_sort(EdgeId e, FaceNormals* normals = nullptr);
  // Makes `uses` (in this order; all of e's uses) the radial cycle of e.
  void set_radial_cycle(EdgeId e, const std::vector<EdgeUseId>& uses);
  // Moves u, a use in a closed loop, to edge e (a slot of e, so a new id, which
  // it returns), optionally flipping its direction. Its loop and its face keep
  // it in its place; e's cycle gets it after e's first use (radial_insert or
  // radial_sort then orders it).
  EdgeUseId move_use(EdgeUseId u, EdgeId e, bool flip = false);

  // ---- loops in bulk (faces never opened)
  // Gives f the loop that starts at `first` (its uses already linked in a cycle).
  LoopId add_loop(FaceId f, EdgeUseId first);
  LoopId add_point_loop(FaceId f, VertexId v);

  // ---- loops and faces, in operators
  // Opens f for editing (see above); opening twice is harmless.
  void open(FaceId f);
  // Makes l start at use u (clearing a point loop's mark on its vertex).
  void set_loop_first(LoopId l, EdgeUseId u);
  // Makes l the point loop of v (v must have no edges).
  void set_point_loop(LoopId l, VertexId v);
  void set_next(EdgeUseId u, EdgeUseId next) { rec(u).next = next.value; }
  // Appends l at the end of f's loop list.
  void append_loop(FaceId f, LoopId l);
  // Removes l from its face's loop list (l must not be the only loop).
  void remove_loop(FaceId f, LoopId l);
  // Takes f's loops away from it (f is about to die) and returns its outer loop
  // as a Loop record, ready for append_loop to another face.
  LoopId take_outer_loop(FaceId f);
  // Sets the face of every use of loop l.
  void assign_face(LoopId l, FaceId f);
  void set_sides(FaceId f, VolumeId front, VolumeId back);

  Model& model() { return m_; }

 private:
  template <class LinkFn, class GrowFn>
  std::uint32_t take_slot(int kind, LinkFn link, GrowFn grow);
  // An edge slot from the free list or a new one (with its two empty use slots).
  std::uint32_t take_edge_slot();
  // A free overflow use slot (a new spare pair when there is none).
  std::uint32_t take_overflow_slot();
  template <class Rec>
  std::uint32_t take_slot(std::vector<Rec>& recs, int kind, std::uint32_t Rec::*link);
  bool is_open(FaceId f) const;
  // The group of vertex a, looked up in the last vertex run first (the bulk case).
  std::uint32_t group_of_new(VertexId a) const {
    const auto& runs = m_.vertex_groups_;
    return a.value >= runs.back().first ? runs.back().group : m_.group_of(a).value;
  }
  // The face marks (Model::kFaceMarks) that use u calls for.
  std::uint32_t mark_of(EdgeUseId u) const {
    return (m_.in_overflow_slot(u) ? Model::kOverflowFace : 0u) |
           (m_.is_in_place(u) ? 0u : Model::kUnplacedFace);
  }
  // The Loop record behind l (opening its face first).
  std::uint32_t record_of(LoopId l);
  LoopRec& loop_rec(std::uint32_t r) { return m_.loops_[r]; }
  std::uint32_t new_record(std::uint32_t first, std::uint32_t next);
  // Appends Loop record r to f's loop list (listing f's loops first if needed);
  // returns the loop's id.
  LoopId append_record(FaceId f, std::uint32_t r);
  // Writes a face's first field, keeping the count of listed faces.
  void set_face_first(FaceId f, std::uint32_t first);
  // Moves f's single loop into a Loop record.
  void list_loops(FaceId f);
  void close(FaceId f);
  // An edit changed f's loops or their uses: f may now repeat an element, and is
  // listed so that its marks are made exact when the last editor goes out of scope.
  void touch(FaceId f) {
    std::uint32_t& sides = rec(f).sides;
    if (!(sides & Model::kTouchedFace)) m_.touched_faces_.push_back(f.value);
    sides |= Model::kRepeatFace | Model::kTouchedFace;
  }
  // The marks f calls for, exactly: kUnplacedFace and kOverflowFace from its
  // uses' slots, kRepeatFace when its loops name an edge or a vertex twice.
  std::uint32_t exact_marks(FaceId f);
  std::vector<std::uint32_t> seen_edges_, seen_vertices_;  // exact_marks' lists
  Model& m_;
};

// The exact Newell normals of faces' outer loops, each computed once for a run of
// radial sorts or checks over a model whose faces do not change meanwhile (a face
// of many sides met at each of its edges: the sides of a sheet along a curve that
// crosses a solid).
class FaceNormals {
 public:
  const ExactVec3& of(const Model& m, FaceId f);

 private:
  std::unordered_map<std::uint32_t, ExactVec3> normals_;
};

// Angular order of the uses around an edge: the interior direction of each use's
// face at the edge, compared exactly (radial.cpp). Returns the uses sorted starting
// from `uses[0]`. `normals`, when given, keeps the faces' normals for the next calls.
std::vector<EdgeUseId> sort_radially(const Model& m, EdgeId e, std::vector<EdgeUseId> uses,
                                     FaceNormals* normals = nullptr);
// True when `cycle` (a radial cycle read from its first use) is in that order.
bool radially_ordered(const Model& m, EdgeId e, const std::vector<EdgeUseId>& cycle,
                      FaceNormals* normals = nullptr);

}  // namespace cellforge::inline topo
