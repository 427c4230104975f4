// Polygons in space and in a plane: the Newell normal, area, the projection onto the
// coordinate plane that keeps a polygon's shape, and the exact tests on projected
// polygons (orientation, winding number, point in polygon).
//
// Notation: a loop is a closed polygon given by its vertices in order, the edge from
// the last vertex back to the first implied. Floating-point results (newell_normal,
// polygon_area, signed_area) measure; the int-valued functions decide, and are exact
// (predicates.h states the coordinate range).
#pragma once

#include <span>

#include "cellforge/geom/predicates.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

// The Newell normal sum_i p_i x p_(i+1) of a loop, added to `sum` (so the loops of one
// face can be summed in one pass): twice the vector area, pointing to the side from
// which the loop runs counterclockwise. Zero for fewer than three points. Computed
// about the loop's first point (the sum does not depend on the origin), so a small
// face far from the origin keeps its direction: about the origin, the products of
// large coordinates round away a normal of 1e-18 at 0.1 from the origin.
Vec3 newell_normal(std::span<const Vec3> loop, Vec3 sum = {});

// The area of a loop in space (half the length of its Newell normal).
double polygon_area(std::span<const Vec3> loop);

// Twice the signed area of a plane loop (the shoelace sum), positive when it runs
// counterclockwise; in doubles.
double signed_area2(std::span<const Vec2> loop);

// The exact sign of the loop's signed area: +1 counterclockwise, -1 clockwise, 0 when
// the area is exactly zero. Filtered: the shoelace sum in doubles with a bound on its
// rounding error, the exact sum in expansions only when the bound cannot decide.
int area_sign(std::span<const Vec2> loop);

// Winding number of the loop about p, exactly; p must not lie on the loop.
int winding_number(std::span<const Vec2> loop, Vec2 p);

// p lies strictly inside the loop (nonzero winding number), exactly; p not on the loop.
inline bool point_in_polygon(std::span<const Vec2> loop, Vec2 p) {
  return winding_number(loop, p) != 0;
}

// The coordinate plane a polygon with normal n projects onto without folding, its
// orientation kept: seen from the side n points to, counterclockwise stays
// counterclockwise. The axis dropped is that of n's largest component (ties to the
// lower axis); dropping x keeps (y, z), dropping y keeps (z, x), dropping z keeps
// (x, y), each a right-handed pair about the dropped axis, and a negative component
// swaps the pair.
struct Projection {
  int drop = 2;
  bool flip = false;
  explicit Projection(Vec3 n);
  Vec2 operator()(Vec3 p) const {
    const double a = p[(drop + 1) % 3], b = p[(drop + 2) % 3];
    return flip ? Vec2{b, a} : Vec2{a, b};
  }
};

}  // namespace cellforge::inline geom
