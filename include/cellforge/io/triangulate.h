// Triangulation of planar faces for mesh export: ear clipping in the face's plane,
// inner loops joined to the outer loop by bridges first. Every decision (convexity,
// a vertex inside an ear, a bridge crossing an edge) is an exact orientation test
// on the face's vertices projected onto the coordinate plane that drops the largest
// component of the face normal, so concave faces and faces with holes come out
// without flipped or overlapping triangles. Every vertex of every loop is used, so
// the triangles of neighbouring faces meet edge to edge (no T-junctions).
#pragma once

#include <array>
#include <vector>

#include "cellforge/topo/model.h"

namespace cellforge::io {

// The triangles of face f, counterclockwise seen from its front side. A face with
// a point loop ignores it. A face whose polygon is degenerate (all vertices on a
// line) yields zero-area triangles rather than none, so that edges still match.
std::vector<std::array<VertexId, 3>> triangulate_face(const Model& m, FaceId f);
// The same, appended to out (no allocation for a triangle or a quad).
void triangulate_face(const Model& m, FaceId f, std::vector<std::array<VertexId, 3>>& out);

// The same for a polygon given as loops of points (loops[0] outer, counterclockwise
// about `normal`, the rest inner loops): triangles as indices into the
// concatenation of the loops.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(
    const std::vector<std::vector<Vec3>>& loops, Vec3 normal);

}  // namespace cellforge::io
