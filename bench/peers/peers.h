// What bench/bench_boolean.cpp hands to the peer kernels it compares against, and what
// it gets back. Compiled only with -DCELLFORGE_PEERS=ON (cmake/peers.cmake): the CGAL
// peers live in cgal_peers.cpp; manifold-3d runs in node (manifold_peer.mjs) on the same
// meshes, written to a file by the benchmark.
//
// A TriMesh is one operand triangulated from its cellforge model: positions as x, y, z
// triples and triangles as index triples, counterclockwise seen from outside.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/boolean/boolean.h"

namespace cellforge::bench {

struct TriMesh {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tris;
  std::size_t num_vertices() const { return xyz.size() / 3; }
  std::size_t num_triangles() const { return tris.size() / 3; }
};

// One evaluation of an expression by a peer. `seconds` counts building the peer's own
// structures from the TriMeshes in memory, the operations, and (for Nef polyhedra) the
// conversion of the result back to a mesh; the checks after it are not timed.
struct PeerRun {
  enum class Status { kOk, kRefused, kError };
  Status status = Status::kOk;
  double seconds = 0;
  std::size_t out_vertices = 0, out_triangles = 0;
  double volume = 0;              // of the output mesh, when it is closed
  int self_intersecting = -1;     // 1 / 0 as checked on the output, -1 when not checked
  std::size_t degenerate_faces = 0;  // zero-area output triangles
  std::string message;            // why it refused or failed
};

// The CGAL release compiled in ("5.5.1").
const char* cgal_version();

// CGAL Polygon_mesh_processing corefinement on Surface_mesh (Epick kernel): the
// expression evaluated as left folds of binary operations. A step whose output would
// not be manifold is refused by CGAL, and so is the whole case.
PeerRun run_cgal_corefinement(const std::vector<TriMesh>& operands, const boolean::Expr& expr,
                              bool check_output);

// CGAL Nef_polyhedron_3 (Epeck kernel, exact): the expression as left folds of the Nef
// set operations; the result converted to a triangle mesh.
PeerRun run_cgal_nef(const std::vector<TriMesh>& operands, const boolean::Expr& expr);

}  // namespace cellforge::bench
