// The exact Boolean of 2D shapes in the plane (planar.cpp), behind ops2d.h, and the
// older route through the 3D arrangement kept as an independent oracle for the tests
// and the benchmark (ops2d.cpp).
//
// Each operand stands for the union of its regions: a point is inside when the sum of
// the winding numbers of its regions' loops about it (outer loops taken
// counterclockwise, holes clockwise) is positive. Loops with no area (a polygon that
// doubles back on itself) wind about nothing and add nothing.
#pragma once

#include <span>

#include "cellforge/boolean/ops2d.h"

namespace cellforge::boolean {

// `expr` over the operands, evaluated on the exact arrangement of all their edges.
// Errors (kInvalidInput) name the operand, region, loop and vertex at fault: fewer
// than 3 vertices, a coordinate that is not finite. A vertex repeated at once makes no
// edge (a projected face with a vertical edge has one).
Result<Evaluated2D> planar_boolean(std::span<const shape::Shape2D> operands, const Expr& expr);

// The same through prisms and the 3D Boolean (the route ops2d took before planar.cpp).
// Operands must be non-empty and their loops of nonzero area.
Result<Evaluated2D> lifted_boolean(std::span<const shape::Shape2D> operands, const Expr& expr);

// projection()'s shadow of a solid (ops2d.cpp): from the boundary of its faces that
// look up, or with `by_faces` as the union of those faces themselves (the route
// projection took before, kept for the tests).
Result<shape::Shape2D> shadow(const topo::Model& solid, bool by_faces);

}  // namespace cellforge::boolean
