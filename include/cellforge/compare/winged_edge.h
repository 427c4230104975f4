// Baumgart's winged edge structure (B. G. Baumgart, "A polyhedron representation
// for computer vision", AFIPS 1975), pointer-based, built from a cellforge Model
// for the storage and query comparison only.
//
// Topology records (64-bit pointers; coordinates and face planes omitted, since
// the cellforge figures count no geometry either):
//   Vertex  next/prev vertex of the body ring, one incident edge
//   Edge    next/prev edge of the body ring; start and end vertex; left face (its
//           loop runs start -> end) and right face (end -> start); the four wings:
//           previous and next edge in the left face's loop, previous and next in
//           the right face's loop
//   Face    next/prev face of the body ring, one edge of its outer loop, its ring
//           list (below)
//   Ring    one edge of an inner loop, next ring of the same face
// Faces with holes: Baumgart's faces have one boundary cycle; as in the later
// loop ("ring") extensions of the winged edge, each inner loop is a Ring record
// naming one of its edges, and a face lists its rings. A face without holes pays
// one null pointer. The edges' left/right fields stay faces.
//
// What it refuses (from_model returns ErrorCode::kUnsupported, the message naming
// the first offender, checked in this order):
//   1. an edge used by three or more faces (non-manifold edge, seed 000 figure 4);
//   2. a wire edge (no face) or a dangling/boundary edge (one face);
//   3. an edge whose two uses are by the same face, or run the same way
//      (left and right would be undefined);
//   4. an isolated vertex (no edge) or a point loop (a loop that is one vertex);
//   5. a non-manifold vertex: its edges form more than one cycle of faces (two
//      solids touching at a corner), since the wings walk a single cycle.
// A vertex of any degree is fine (seed 000 figure 3 is representable); a face of
// any number of sides and holes is fine.
#pragma once

#include <vector>

#include "cellforge/compare/storage.h"
#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::compare {

class WingedEdge {
 public:
  struct Edge;
  struct Face;
  struct Ring;
  struct Vertex {
    Vertex* next = nullptr;
    Vertex* prev = nullptr;
    Edge* edge = nullptr;
  };
  struct Edge {
    Edge* next = nullptr;
    Edge* prev = nullptr;
    Vertex* start = nullptr;
    Vertex* end = nullptr;
    Face* left = nullptr;
    Face* right = nullptr;
    Edge* left_prev = nullptr;
    Edge* left_next = nullptr;
    Edge* right_prev = nullptr;
    Edge* right_next = nullptr;
  };
  struct Face {
    Face* next = nullptr;
    Face* prev = nullptr;
    Edge* edge = nullptr;
    Ring* rings = nullptr;
  };
  struct Ring {
    Edge* edge = nullptr;
    Ring* next = nullptr;
  };

  // Converts `m`, or refuses (see the header comment) with a message naming the
  // offending edge or vertex.
  static Result<WingedEdge> from_model(const Model& m);

  WingedEdge(WingedEdge&&) = default;
  WingedEdge& operator=(WingedEdge&&) = default;
  WingedEdge(const WingedEdge&) = delete;  // records point into their own arrays
  WingedEdge& operator=(const WingedEdge&) = delete;

  StorageStats storage() const;

  // The 9 adjacency queries by wing traversal; each element listed once.
  void vertices_of(VertexId v, std::vector<VertexId>& out) const;
  void edges_of(VertexId v, std::vector<EdgeId>& out) const;
  void faces_of(VertexId v, std::vector<FaceId>& out) const;
  void vertices_of(EdgeId e, std::vector<VertexId>& out) const;
  void edges_of(EdgeId e, std::vector<EdgeId>& out) const;
  void faces_of(EdgeId e, std::vector<FaceId>& out) const;
  void vertices_of(FaceId f, std::vector<VertexId>& out) const;
  void edges_of(FaceId f, std::vector<EdgeId>& out) const;
  void faces_of(FaceId f, std::vector<FaceId>& out) const;

 private:
  WingedEdge() = default;
  VertexId id_of(const Vertex* v) const {
    return VertexId(static_cast<std::uint32_t>(v - vertices_.data()));
  }
  EdgeId id_of(const Edge* e) const {
    return EdgeId(static_cast<std::uint32_t>(e - edges_.data()));
  }
  FaceId id_of(const Face* f) const {
    return FaceId(static_cast<std::uint32_t>(f - faces_.data()));
  }

  // Arrays indexed by cellforge slot; a record's id is its position.
  std::vector<Vertex> vertices_;
  std::vector<Edge> edges_;
  std::size_t spare_edges_ = 0;  // slots of edges_ for cellforge spare pairs (not counted)
  std::vector<Face> faces_;
  std::vector<Ring> rings_;
};

}  // namespace cellforge::compare
