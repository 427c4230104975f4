// Euler operators (seed 003) and the non-manifold operators of DESIGN.md.
//
// Every operator X has a check can_X() with the same arguments; X() runs the check
// first and, when it fails, returns its Error and leaves the model unchanged. The
// error message names the violated precondition and the ids involved.
//
// Counts changed, in seed 003's notation (v vertices, e edges, f faces, s shells,
// h through-holes, r inner loops):
//   mvsf  +v +f +s      kvsf  -v -f -s
//   mev   +v +e         kev   -v -e
//   mef   +e +f         kef   -e -f
//   kemr  -e +r         mekr  +e -r
//   kfmrh -f +r +h      mfkrh +f -r -h
//   semv  +v +e         jekv  -v -e
#pragma once

#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

// ---- groups and volumes
GroupId make_group(Model& m, std::string name = {});
Status can_kill_group(const Model& m, GroupId g);
Status kill_group(Model& m, GroupId g);  // only an empty group

// A face side: the face and whether the volume lies on its front or its back.
struct FaceSide {
  FaceId face;
  bool front = false;
};
// make_volume: a new 3-cell in group g bounded by the given face sides (each side
// must be free: no volume yet). kill_volume: clears every side naming c.
Status can_make_volume(const Model& m, GroupId g, const std::vector<FaceSide>& sides);
Result<VolumeId> make_volume(Model& m, GroupId g, const std::vector<FaceSide>& sides);
Status can_kill_volume(const Model& m, VolumeId c);
Status kill_volume(Model& m, VolumeId c);
// All face sides naming c, in face id order.
std::vector<FaceSide> sides_of(const Model& m, VolumeId c);

// ---- the 12 Euler operators
struct VertexFace {
  VertexId vertex;
  FaceId face;
};
struct EdgeVertex {
  EdgeId edge;
  VertexId vertex;
};
struct EdgeFace {
  EdgeId edge;
  FaceId face;
};

// mvsf: makes a vertex and a face whose only loop is that vertex (a new shell).
Status can_mvsf(const Model& m, GroupId g);
Result<VertexFace> mvsf(Model& m, GroupId g, Vec3 position);
// kvsf: kills v and f; f must have a single point loop at v and v no edges.
Status can_kvsf(const Model& m, VertexId v, FaceId f);
Status kvsf(Model& m, VertexId v, FaceId f);

// mev: makes an edge from v (a vertex of loop l) to a new vertex at `position`;
// both uses go into l, after the first use of l that ends at v (a strut).
Status can_mev(const Model& m, LoopId l, VertexId v);
Result<EdgeVertex> mev(Model& m, LoopId l, VertexId v, Vec3 position);
// kev: kills edge e and its end vertex v; v must have no other edge and e's two
// uses must be consecutive in one loop (a strut), or e a wire edge.
Status can_kev(const Model& m, EdgeId e, VertexId v);
Status kev(Model& m, EdgeId e, VertexId v);

// mef: makes an edge v1->v2 across loop l (v1 != v2, both on l), splitting it: the
// part of l from v1 to v2 plus the new use v2->v1 becomes the outer loop of a new
// face with the same sides; l keeps the part from v2 to v1 plus the use v1->v2.
Status can_mef(const Model& m, LoopId l, VertexId v1, VertexId v2);
Result<EdgeFace> mef(Model& m, LoopId l, VertexId v1, VertexId v2);
// kef: kills edge e and face f, one of e's two faces; f's loop merges into the
// other face's loop and f's inner loops move to that face. e must have exactly
// two uses, in different faces with the same sides, and f's use must be in f's
// outer loop.
Status can_kef(const Model& m, EdgeId e, FaceId f);
Status kef(Model& m, EdgeId e, FaceId f);

// kemr: kills the edge of use u, whose mate (the edge's other use) lies in the same
// loop; the uses after u up to the mate become a new inner loop (a point loop at
// u's end if there are none).
Status can_kemr(const Model& m, EdgeUseId u);
Result<LoopId> kemr(Model& m, EdgeUseId u);
// mekr: makes an edge v1->v2 joining vertex v1 of loop l1 and vertex v2 of loop l2
// (two loops of one face); l2 is killed and its cycle spliced into l1.
Status can_mekr(const Model& m, LoopId l1, VertexId v1, LoopId l2, VertexId v2);
Result<EdgeId> mekr(Model& m, LoopId l1, VertexId v1, LoopId l2, VertexId v2);

// kfmrh: kills face `dying` (one loop, no inner loops, same sides as `keep`); its
// loop becomes an inner loop of `keep` (a ring and a through-hole). Returns that
// loop's new id (an outer loop is named after its face, an inner one is not).
Status can_kfmrh(const Model& m, FaceId keep, FaceId dying);
Result<LoopId> kfmrh(Model& m, FaceId keep, FaceId dying);
// mfkrh: the inner loop l of its face becomes the outer loop of a new face g,
// and so is named outer_loop(g) from then on.
Status can_mfkrh(const Model& m, LoopId l);
Result<FaceId> mfkrh(Model& m, LoopId l);

// semv: splits edge e at a new vertex: e keeps its start and ends at the new vertex,
// the new edge runs from the new vertex to e's old end; every use of e is split.
Status can_semv(const Model& m, EdgeId e);
Result<EdgeVertex> semv(Model& m, EdgeId e, Vec3 position);
// jekv: joins edge `dying` into its neighbour at vertex v (v must have exactly two
// edges, `dying` and one other, with matching uses); v and `dying` are killed.
Status can_jekv(const Model& m, EdgeId dying, VertexId v);
Status jekv(Model& m, EdgeId dying, VertexId v);

// ---- non-manifold operators (DESIGN.md)
// An isolated vertex (no edges).
Status can_make_vertex(const Model& m, GroupId g);
Result<VertexId> make_vertex(Model& m, GroupId g, Vec3 position);
Status can_kill_vertex(const Model& m, VertexId v);
Status kill_vertex(Model& m, VertexId v);  // only an isolated vertex

// A wire edge (no uses) between two distinct vertices of one group.
Status can_make_wire_edge(const Model& m, VertexId a, VertexId b);
Result<EdgeId> make_wire_edge(Model& m, VertexId a, VertexId b);
Status can_kill_wire_edge(const Model& m, EdgeId e);
Status kill_wire_edge(Model& m, EdgeId e);

// A face on existing vertices: `loops[0]` the outer loop, the rest inner loops,
// each a vertex cycle. Consecutive vertices reuse an existing edge between them
// if there is one (this is how non-manifold edges arise), else get a new edge.
// The face has no volumes; its uses enter each radial cycle in angular order.
struct FaceSpec {
  std::vector<std::vector<VertexId>> loops;
};
Status can_make_face(const Model& m, const FaceSpec& spec);
Result<FaceId> make_face(Model& m, const FaceSpec& spec);
// kill_face: kills f with its loops and uses (f must bound no volume). With
// kill_bare_edges, edges left without uses are killed too, and then vertices left
// without edges.
struct KillFaceOptions {
  bool kill_bare_edges = false;
  bool kill_bare_vertices = false;
};
Status can_kill_face(const Model& m, FaceId f);
Status kill_face(Model& m, FaceId f, KillFaceOptions options = {});

// glue_faces: a and b bound the same polygon with opposite orientation (b's vertex
// cycle is a's reversed, over the same edges) and each has a volume on its back
// only; b is killed and a becomes one shared face: its front volume is b's back.
Status can_glue_faces(const Model& m, FaceId a, FaceId b);
Status glue_faces(Model& m, FaceId a, FaceId b);
// unglue_face: the inverse: a shared face (volumes on both sides) splits into itself
// (keeping its back volume) and a new reversed face on the same edges that takes
// its front volume.
Status can_unglue_face(const Model& m, FaceId f);
Result<FaceId> unglue_face(Model& m, FaceId f);

// split_edge: the uses listed move to a new edge with the same two vertices
// (a non-manifold edge is separated into two coincident edges). A use's id is a
// slot of its edge, so the moved uses get new ids (the new edge's first use and
// its radial cycle name them); the uses that stay keep theirs.
Status can_split_edge(const Model& m, EdgeId e, const std::vector<EdgeUseId>& moving);
Result<EdgeId> split_edge(Model& m, EdgeId e, const std::vector<EdgeUseId>& moving);
// merge_edges: the inverse: `dying` (same two vertices as `keep`) is killed and its
// uses join keep's radial cycle in angular order, with new ids (slots of keep).
Status can_merge_edges(const Model& m, EdgeId keep, EdgeId dying);
Status merge_edges(Model& m, EdgeId keep, EdgeId dying);

// split_vertex: the listed edge ends move to a new vertex at the same position. No
// loop may pass through v from a moving edge to a staying one.
Status can_split_vertex(const Model& m, VertexId v, const std::vector<EdgeEnd>& moving);
Result<VertexId> split_vertex(Model& m, VertexId v, const std::vector<EdgeEnd>& moving);
// merge_vertices: the inverse: `dying` (same position, same group) is killed and its
// edge ends and point loops move to `keep`.
Status can_merge_vertices(const Model& m, VertexId keep, VertexId dying);
Status merge_vertices(Model& m, VertexId keep, VertexId dying);

}  // namespace cellforge::inline topo
