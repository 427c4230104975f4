// The Minkowski sum of solids (OpenSCAD's minkowski() on 3D children): the set of
// sums a + b of a point of each operand.
//
// An operand is a model taken as the union of its cells (as a Boolean operand). The
// sum of convex cells is exact in the sense of shape/hull.h: the convex hull of the
// pairwise vertex sums, decided by exact orient3d (the sums themselves are rounded
// doubles, one addition each). Otherwise the sum is decomposed and unioned with the
// exact Boolean:
//   - every cell of both operands convex: the union of the hulls of every pair of cells;
//   - B's cells convex, A's not: A + B_j = (A + b0) union the hulls of t + B_j over the
//     pieces t of A's boundary (each face that is an exactly planar convex polygon
//     whole, the others by triangles), for any b0 in B_j (a point x of A + B_j either
//     has x - b0 in A, or the segment from x - b to x - b0 leaves A through its
//     boundary); the operands are swapped when only A's cells are convex;
//   - no operand with all cells convex: unsupported (kUnsupported, naming the operands
//     and a non-convex cell of each), since a convex decomposition of a general
//     non-convex polyhedron is not built here.
#pragma once

#include <span>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::boolean {

// The Minkowski sum of the operands, folded left, as a new model of one group (one
// cell per connected solid). An operand with no cell is an error (kInvalidInput,
// naming it); one operand gives its union.
Result<Model> minkowski(std::span<const Model* const> operands);

// Whether cell c of m counts as convex: no face bounding it has holes, and for every
// corner of every such face (three consecutive points, not collinear) every vertex of
// c not on that face lies on or behind the corner's plane (exact orient3d). The
// face's own vertices are left out so that a face that is planar only up to rounding
// (the quads of a faceted sphere) does not make the cell non-convex; such a cell is
// summed as the hull of its vertices, which differs from it by those roundings.
bool is_convex_cell(const Model& m, VolumeId c);

}  // namespace cellforge::boolean
