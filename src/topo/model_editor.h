// ModelEditor: the one place that writes Model records. Operators and the bulk
// builder use it; it does no checking of its own (callers check first).
#pragma once

#include "cellforge/topo/model.h"

namespace cellforge {

class ModelEditor {
 public:
  explicit ModelEditor(Model& m) : m_(m) {}

  using VertexRec = Model::VertexRec;
  using EdgeRec = Model::EdgeRec;
  using UseRec = Model::UseRec;
  using LoopRec = Model::LoopRec;
  using FaceRec = Model::FaceRec;
  using SidesRec = Model::SidesRec;
  static constexpr std::uint32_t kTagBit = Model::kTagBit;
  static constexpr std::uint32_t kDead = Model::kDead;

  VertexRec& rec(VertexId v) { return m_.vertices_[v.value]; }
  EdgeRec& rec(EdgeId e) { return m_.edges_[e.value]; }
  UseRec& rec(EdgeUseId u) { return m_.uses_[u.value]; }
  LoopRec& rec(LoopId l) { return m_.loops_[l.value]; }
  FaceRec& rec(FaceId f) { return m_.faces_[f.value]; }

  // ---- creation (records come back initialised, not yet linked)
  GroupId new_group(std::string name);
  VertexId new_vertex(GroupId g, Vec3 p);
  EdgeId new_edge(VertexId a, VertexId b);               // links both ends into the vertex cycles
  EdgeUseId new_use(EdgeId e, bool reversed, FaceId f);  // not yet in loop or radial cycle
  LoopId new_point_loop(VertexId v);
  LoopId new_loop(EdgeUseId first);
  FaceId new_face(std::uint32_t sides);
  VolumeId new_volume(GroupId g);
  std::uint32_t intern_sides(VolumeId front, VolumeId back, GroupId g);

  // ---- deletion (the caller has unlinked the entity from everything)
  void free_vertex(VertexId v);
  void free_edge(EdgeId e);  // unlinks both ends from the vertex cycles first
  void free_use(EdgeUseId u);
  void free_loop(LoopId l);
  void free_face(FaceId f);
  void free_volume(VolumeId c);
  void free_group(GroupId g);

  // ---- vertex cycles
  void link_end(VertexId v, EdgeEnd end);    // inserts end into v's cycle
  void unlink_end(VertexId v, EdgeEnd end);  // removes end from v's cycle
  // Moves an edge end from its vertex to another one.
  void move_end(EdgeEnd end, VertexId to);

  // ---- radial cycles
  // Inserts u into its edge's radial cycle at its angular place.
  void radial_insert(EdgeUseId u);
  void radial_remove(EdgeUseId u);
  // Sorts the whole radial cycle of e by angle (after bulk changes).
  void radial_sort(EdgeId e);

  // ---- loops and faces
  // Makes l start at use u (clearing a point loop's mark on its vertex).
  void set_loop_first(LoopId l, EdgeUseId u);
  // Makes l the point loop of v (v must have no edges).
  void set_point_loop(LoopId l, VertexId v);
  void set_next(EdgeUseId u, EdgeUseId next) { rec(u).next = next.value; }
  // Appends l at the end of f's loop list.
  void append_loop(FaceId f, LoopId l);
  // Removes l from its face's loop list (l must not be the only loop).
  void remove_loop(FaceId f, LoopId l);
  // Sets the face of every use of loop l.
  void assign_face(LoopId l, FaceId f);
  void set_sides(FaceId f, VolumeId front, VolumeId back);

  Model& model() { return m_; }

 private:
  template <class Rec>
  std::uint32_t take_slot(std::vector<Rec>& recs, int kind, std::uint32_t Rec::*link);
  Model& m_;
};

// Angular order of the uses around an edge: the interior direction of each use's
// face at the edge, compared exactly (radial.cpp). Returns the uses sorted starting
// from `uses[0]`.
std::vector<EdgeUseId> sort_radially(const Model& m, EdgeId e, std::vector<EdgeUseId> uses);
// True when `cycle` (a radial cycle read from its first use) is in that order.
bool radially_ordered(const Model& m, EdgeId e, const std::vector<EdgeUseId>& cycle);

}  // namespace cellforge
