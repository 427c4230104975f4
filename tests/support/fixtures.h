// Named fixtures for the topology tests, built with the bulk builder, and small
// lookups by geometry so that tests can state hand-computed answers without ids.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/model.h"

namespace cellforge::testing {

// Faces of the axis-aligned box [lo, hi], outward and counterclockwise, indices into
// box_corners(lo, hi) (corner i has x from bit 0, y from bit 1, z from bit 2).
std::vector<Vec3> box_corners(Vec3 lo, Vec3 hi);
std::vector<std::vector<std::uint32_t>> box_faces();

// Appends a box to `in` (welding to existing identical positions), its faces
// bounding volume `volume` (-1 for a bare surface). Returns the face indices.
std::vector<std::size_t> add_box(MeshInput& in, Vec3 lo, Vec3 hi, int volume);
// Adds a polygon face (welding positions) with the given front/back volumes.
std::size_t add_face(MeshInput& in, const std::vector<std::vector<Vec3>>& loops, int front = -1,
                     int back = -1);
std::uint32_t add_point(MeshInput& in, Vec3 p);

// The fixtures of the foundation issue.
MeshInput unit_cube();
MeshInput cube_with_through_hole();    // [0,3]^3 with a square hole [1,2]^2 along z
MeshInput two_cubes_sharing_edge();    // [0,1]^3 and [1,2]x[1,2]x[0,1]
MeshInput two_cubes_sharing_vertex();  // [0,1]^3 and [1,2]^3
MeshInput cube_with_dangling_face();   // unit cube, a square fin on edge y=0,z=1
MeshInput cube_with_wire_and_point();  // unit cube, wire (1,1,1)-(2,2,2), point (5,5,5)
MeshInput book();                      // three square pages on edge (0,0,0)-(0,0,1)
MeshInput two_cubes_sharing_face();    // [0,1]^3 (cell 0) under [0,1]^2x[1,2] (cell 1)
MeshInput square_sheet_with_hole();    // [0,3]^2 sheet with a [1,2]^2 hole

Model build(const MeshInput& in);

// Lookups by geometry (fail the test when absent).
VertexId vertex_at(const Model& m, Vec3 p);
EdgeId edge_at(const Model& m, Vec3 a, Vec3 b);
// The face whose outer loop has this vertex-position centroid.
FaceId face_at(const Model& m, Vec3 centroid);
Vec3 centroid_of(const Model& m, FaceId f);

std::set<Vec3> positions(const Model& m, const std::vector<VertexId>& vs);
// Edges and faces named by geometry: an edge as its sorted end positions, a face
// by its centroid.
std::set<std::pair<Vec3, Vec3>> edge_keys(const Model& m, const std::vector<EdgeId>& es);
std::set<Vec3> face_keys(const Model& m, const std::vector<FaceId>& fs);

}  // namespace cellforge::testing

namespace cellforge {
bool operator<(const Vec3& a, const Vec3& b);
}
