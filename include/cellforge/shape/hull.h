// Convex hulls (OpenSCAD's hull()): of points in the plane, as a Region, and of points
// in space, as a closed solid.
//
// Every decision is an exact predicate on the input doubles (orient2d, orient3d), so
// the hull's vertices are exactly input points, its vertices are strictly extreme (a
// point on an edge or inside a face of the hull is not a vertex) and coplanar facets
// are merged into one convex polygon face (the hull of a cube's eight corners is the
// cube with six quads). Duplicate points are allowed.
//
// 3D: incremental construction over a starting tetrahedron; a point is added when it
// lies strictly outside some facet; afterwards adjacent coplanar triangles are merged
// and vertices strictly inside a hull edge dropped.
#pragma once

#include <span>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/shape/region.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

// The convex hull of plane points as a counterclockwise region without holes.
// Errors (kInvalidInput): fewer than three distinct points, all points collinear, a
// non-finite coordinate.
Result<Region> convex_hull(std::span<const Vec2> points);

struct HullOptions {
  // When every point lies in one plane: false, an error (kInvalidInput); true, the
  // flat hull as one sheet face (no cell) in the plane, in a new group.
  bool allow_flat = false;
};

// The convex hull of points in space, built into a new group of `m` as one closed
// cell with convex polygon faces pointing outward. Errors (kInvalidInput; the model
// is unchanged): fewer than four distinct points, all points collinear, all points
// coplanar (unless options.allow_flat), a non-finite coordinate.
Result<GroupId> convex_hull(Model& m, std::span<const Vec3> points,
                            const HullOptions& options = {});

// The positions of every live vertex of the model (the input of a 3D hull of solids).
std::vector<Vec3> vertex_positions(const Model& m);

}  // namespace cellforge::shape
