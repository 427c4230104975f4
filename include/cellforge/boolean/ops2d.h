// Exact operations on 2D shapes (shape/shape2d.h): Booleans, offset, 2D Minkowski sum,
// and the projection of a solid onto the plane z = 0 (OpenSCAD's union, difference,
// intersection, offset, minkowski and projection on 2D children).
//
// Route: the Booleans (and the unions inside offset, minkowski_2d and the shadow
// projection) run on one exact arrangement of all operands' loop edges in the plane
// (src/boolean/planar.cpp): crossings are implicit points decided by exact predicates,
// every face gets each operand's winding number, the expression picks the faces, and
// their boundary comes out as outer loops with holes. Each operand is the union of its
// regions (winding number > 0). Crossings are rounded to doubles once, when the result is
// built, and the rounded loops are checked exactly (Evaluated2D::rounding_crossings). The
// section projection (cut) intersects the solid with a slab by the 3D Boolean and reads
// its faces on z = 0 back.
//
// Offset builds, for every loop edge, the strip swept by the edge along its outward
// normal (inward for a negative amount) and, at every vertex where the boundary turns
// away from the strips, the join piece (a faceted circular sector, a miter or a
// chamfer as OpenSCAD's Clipper joins make them); the result is the union of the shape
// with those pieces (amount > 0) or the shape minus them (amount < 0), again with the
// exact Boolean. The arc of a round join at a corner turning by angle a (between the
// two edge normals) has max(1, round(n a / 2 pi)) steps of 2 pi / n from the first
// normal, then a last point on the second normal, n = fragments(|r|) (OpenSCAD's
// offset through Clipper with arc tolerance |r| (1 - cos(180 / n))).
//
// Errors are values: kInvalidInput names the operand or the parameter at fault; a
// Boolean failure is passed on with its message.
#pragma once

#include <span>

#include "cellforge/boolean/boolean.h"
#include "cellforge/result.h"
#include "cellforge/shape/faceting.h"
#include "cellforge/shape/shape2d.h"
#include "cellforge/topo/model.h"

namespace cellforge::boolean {

// `expr` (boolean.h) over the 2D operands. An empty operand is the empty set; an
// expression that reduces to one operand returns it as given.
Result<shape::Shape2D> evaluate_2d(std::span<const shape::Shape2D> operands, const Expr& expr);

// The same with the rounding check: the number of defects that rounding crossings to
// doubles made — pairs of result edges that cross or overlap, loops that collapsed or
// turned over, points a loop passes twice. When it is 0 the regions' loops are simple
// and meet only at shared vertices; otherwise a loop may touch or cross itself or
// another near the rounded points (docs/shape-ops.md).
struct Evaluated2D {
  shape::Shape2D shape;
  std::size_t rounding_crossings = 0;
};
Result<Evaluated2D> evaluate_2d_counted(std::span<const shape::Shape2D> operands, const Expr& expr);

// The operation over all operands in order: union of all, intersection of all, or the
// first minus the others. No operands: the empty shape.
Result<shape::Shape2D> apply_2d(Op op, std::span<const shape::Shape2D> operands);

enum class OffsetJoin {
  kRound,    // OpenSCAD offset(r = amount)
  kMiter,    // offset(delta = amount) (chamfer = false)
  kChamfer,  // offset(delta = amount, chamfer = true)
};

struct OffsetOptions {
  double amount = 0;  // r or delta; negative shrinks; 0 returns the shape as given
  OffsetJoin join = OffsetJoin::kRound;
  shape::Faceting faceting = {};  // for kRound: n = fragments(|amount|, faceting)
};

// The shape grown (amount > 0) or shrunk (amount < 0) by |amount|.
Result<shape::Shape2D> offset(const shape::Shape2D& shape, const OffsetOptions& options);

// The Minkowski sum of 2D operands, folded left (an empty operand makes the result
// empty). Exact for convex operands (the hull of pairwise vertex sums); otherwise
// decomposed: with B convex, A + B = (A + b0) union the hulls of (edge of A) + B for
// every boundary edge of A, any b0 in B; with neither operand convex, B is split into
// its regions' triangles (each convex) and the sums of A with each are unioned.
Result<shape::Shape2D> minkowski_2d(std::span<const shape::Shape2D> operands);

struct ProjectionOptions {
  // false: the shadow onto z = 0 (the union of the projections of the faces facing
  // +z); true: the section by the plane z = 0, as the closure of the solid's
  // interior just above the plane (a solid resting on z = 0 from above gives its
  // bottom face; one touching it from below gives nothing).
  bool cut = false;
};

// The projection of the solid in `solid` (every cell of every group, as a Boolean
// operand) onto the plane z = 0. An empty model gives the empty shape.
Result<shape::Shape2D> projection(const Model& solid, const ProjectionOptions& options = {});

}  // namespace cellforge::boolean
