// The bulk builder: from vertex positions and indexed polygon faces to the full
// cycle structure in O(n log n). Primitives, imported meshes and Boolean results
// are built here; Euler operators are for local edits.
//
// Faces sharing a vertex pair share one edge (so an edge used by three or more
// faces is non-manifold, and its radial cycle is sorted by exact angle). Vertices
// used by no face stay isolated; `wires` adds wire edges.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

struct MeshFace {
  // loops[0] is the outer loop (counterclockwise seen from the front), the rest
  // inner loops; each a cycle of indices into MeshInput::positions.
  std::vector<std::vector<std::uint32_t>> loops;
  // Indices into MeshInput::volumes for the cell in front of / behind the face;
  // -1 for none.
  int front = -1;
  int back = -1;
};

struct MeshInput {
  std::vector<Vec3> positions;
  std::vector<MeshFace> faces;
  std::vector<std::array<std::uint32_t, 2>> wires;
  int volumes = 0;  // number of 3-cells referenced by faces
  std::string group_name;
};

struct BuildResult {
  GroupId group;
  std::vector<VertexId> vertices;  // per input position
  std::vector<FaceId> faces;       // per input face
  std::vector<VolumeId> volumes;   // per input volume
};

// Builds into a new group of `m`. On error (an index out of range, a loop with
// fewer than 3 distinct vertices or repeating a vertex consecutively, a volume
// index out of range, a non-finite coordinate) nothing is added and the message
// names the face and loop.
Result<BuildResult> build_mesh(Model& m, const MeshInput& input);

// A closed solid from a triangle/polygon soup: every face gets back volume 0.
MeshInput solid_input(std::vector<Vec3> positions, std::vector<std::vector<std::uint32_t>> faces);

}  // namespace cellforge::inline topo
