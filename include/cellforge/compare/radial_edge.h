// Weiler's radial edge structure (K. Weiler, "Topological structures for geometric
// modeling", RPI 1986), pointer-based as Weiler and seed 000 (figures 5-7) describe
// it, built from a cellforge Model for the storage and query comparison only.
//
// Topology records (64-bit pointers; geometry and attribute pointers omitted, since
// the cellforge figures count no geometry either):
//   Model     its region list
//   Region    model, next/prev region, its shell list
//   Shell     region, next/prev shell, its faceuse list, its wire edgeuse list,
//             its vertexuse (a shell that is a single vertex)
//   FaceUse   shell, next/prev faceuse in the shell, mate (the face's other side),
//             its loopuse list, face, orientation
//   LoopUse   faceuse, next/prev loopuse in the faceuse, mate, loop, its edgeuse
//             cycle or (a loop that is one vertex) its vertexuse
//   EdgeUse   parent loopuse (or shell, for a wire edge), next/prev in the loop
//             (Weiler's cw/ccw), mate (the use on the faceuse's mate), radial (the
//             facing use of the next face around the edge), edge, vertexuse at
//             its start, orientation
//   VertexUse parent (edgeuse, loopuse or shell), next/prev use of the same
//             vertex, vertex
//   Face, Loop, Edge, Vertex   one pointer each, to one of their uses
// Every face has two faceuses (front: same sense as the face, back: opposite),
// every loop two loopuses, every edge two edgeuses per face that uses it, and every
// edgeuse its own vertexuse — seed 000's "five pointers per vertex use and per edge
// use".
//
// Conversion: one region and one shell per cellforge group (the non-manifold
// extension BRL-CAD's NMG also uses: both faceuses of a face in the same shell).
// Around an edge, the cellforge radial cycle's angular order is kept: walking
// eu -> radial -> mate visits the faces in that order, and each radial pair faces
// the same wedge of space.
//
// Records live in arrays sized exactly before they are linked, so no pointer moves;
// the Face, Edge and Vertex arrays are indexed by cellforge slot, so a record's id
// is its position (no id field is stored). Wire edges, isolated vertices and point
// loops are converted too.
#pragma once

#include <cstdint>
#include <vector>

#include "cellforge/compare/storage.h"
#include "cellforge/topo/model.h"

namespace cellforge::compare {

class RadialEdge {
 public:
  struct Region;
  struct Shell;
  struct FaceUse;
  struct LoopUse;
  struct EdgeUse;
  struct VertexUse;
  struct Face;
  struct Loop;
  struct Edge;
  struct Vertex;

  struct TopModel {
    Region* regions = nullptr;
  };
  struct Region {
    TopModel* model = nullptr;
    Region* next = nullptr;
    Region* prev = nullptr;
    Shell* shells = nullptr;
  };
  struct Shell {
    Region* region = nullptr;
    Shell* next = nullptr;
    Shell* prev = nullptr;
    FaceUse* faceuses = nullptr;
    EdgeUse* wire_edgeuses = nullptr;
    VertexUse* vertexuse = nullptr;
  };
  struct FaceUse {
    Shell* shell = nullptr;
    FaceUse* next = nullptr;
    FaceUse* prev = nullptr;
    FaceUse* mate = nullptr;
    LoopUse* loopuses = nullptr;
    Face* face = nullptr;
    bool same_sense = true;
  };
  struct LoopUse {
    FaceUse* faceuse = nullptr;
    LoopUse* next = nullptr;
    LoopUse* prev = nullptr;
    LoopUse* mate = nullptr;
    Loop* loop = nullptr;
    EdgeUse* edgeuses = nullptr;     // first use of its cycle, or null for a point loop
    VertexUse* vertexuse = nullptr;  // a point loop's vertex use
  };
  struct EdgeUse {
    union Parent {
      LoopUse* loopuse;
      Shell* shell;
    } up{nullptr};
    EdgeUse* next = nullptr;  // in the loop, or in the shell's wire list
    EdgeUse* prev = nullptr;
    EdgeUse* mate = nullptr;
    EdgeUse* radial = nullptr;
    Edge* edge = nullptr;
    VertexUse* vertexuse = nullptr;
    bool in_loop = true;  // false: `up` is a shell (wire edge)
    bool same_sense = true;
  };
  enum class UseParent : std::uint8_t { kEdgeUse, kLoopUse, kShell };
  struct VertexUse {
    union Parent {
      EdgeUse* edgeuse;
      LoopUse* loopuse;
      Shell* shell;
    } up{nullptr};
    VertexUse* next = nullptr;
    VertexUse* prev = nullptr;
    Vertex* vertex = nullptr;
    UseParent parent = UseParent::kEdgeUse;
  };
  struct Face {
    FaceUse* faceuse = nullptr;
  };
  struct Loop {
    LoopUse* loopuse = nullptr;
  };
  struct Edge {
    EdgeUse* edgeuse = nullptr;
  };
  struct Vertex {
    VertexUse* vertexuses = nullptr;
  };

  // Converts every live entity of `m`. Always succeeds: the radial edge structure
  // holds everything cellforge holds.
  static RadialEdge from_model(const Model& m);

  RadialEdge(RadialEdge&&) = default;
  RadialEdge& operator=(RadialEdge&&) = default;
  RadialEdge(const RadialEdge&) = delete;  // records point into their own arrays
  RadialEdge& operator=(const RadialEdge&) = delete;

  StorageStats storage() const;

  // The 9 adjacency queries, answered by walking this structure only; each answer
  // lists every element once (the same sets as cellforge's queries.h).
  void vertices_of(VertexId v, std::vector<VertexId>& out) const;
  void edges_of(VertexId v, std::vector<EdgeId>& out) const;
  void faces_of(VertexId v, std::vector<FaceId>& out) const;
  void vertices_of(EdgeId e, std::vector<VertexId>& out) const;
  void edges_of(EdgeId e, std::vector<EdgeId>& out) const;
  void faces_of(EdgeId e, std::vector<FaceId>& out) const;
  void vertices_of(FaceId f, std::vector<VertexId>& out) const;
  void edges_of(FaceId f, std::vector<EdgeId>& out) const;
  void faces_of(FaceId f, std::vector<FaceId>& out) const;

  const TopModel& top() const { return *model_; }

 private:
  RadialEdge() = default;
  VertexId id_of(const Vertex* v) const {
    return VertexId(static_cast<std::uint32_t>(v - vertices_.data()));
  }
  EdgeId id_of(const Edge* e) const {
    return EdgeId(static_cast<std::uint32_t>(e - edges_.data()));
  }
  FaceId id_of(const Face* f) const {
    return FaceId(static_cast<std::uint32_t>(f - faces_.data()));
  }

  // Heap-held so that the records' back pointers survive a move of this object.
  std::vector<TopModel> model_storage_;
  TopModel* model_ = nullptr;
  std::vector<Region> regions_;
  std::vector<Shell> shells_;
  std::vector<FaceUse> faceuses_;
  std::vector<LoopUse> loopuses_;
  std::vector<EdgeUse> edgeuses_;
  std::vector<VertexUse> vertexuses_;
  std::vector<Face> faces_;
  std::vector<Loop> loops_;
  std::vector<Edge> edges_;
  std::size_t spare_edges_ = 0;  // slots of edges_ for cellforge spare pairs (not counted)
  std::vector<Vertex> vertices_;
};

}  // namespace cellforge::compare
