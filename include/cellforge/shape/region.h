// 2D profiles for sweeps: regions (a simple outer polygon with simple holes), open
// polylines and points, in the xy plane. linear_extrude lifts them along z;
// rotate_extrude reads (x, y) as (radius, height) and turns them about the z axis.
//
// A Region's loops[0] is the outer boundary, counterclockwise; loops[1..] are holes,
// clockwise. The constructors below guarantee that; polygon() checks arbitrary input
// with exact predicates (no tolerance) and orients the loops.
#pragma once

#include <vector>

#include "cellforge/shape/faceting.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

struct Region {
  std::vector<std::vector<Vec2>> loops;
};

// An open chain of at least two points (an open profile sweeps to a sheet).
struct Polyline {
  std::vector<Vec2> points;
};

// OpenSCAD's square(size, center): corners (0,0) .. size, or centred on the origin.
Result<Region> rectangle(Vec2 size, bool center = false);
// OpenSCAD's circle(r): fragments(r) vertices at 360 i / n degrees from (r, 0).
Result<Region> circle(double r, const Faceting& faceting = {});
// n vertices on the circle of radius r (circumradius), the first at (r, 0).
Result<Region> regular_polygon(int sides, double r);
// A simple polygon with simple holes strictly inside it and apart from each other.
// Either orientation is accepted; the result is outer counterclockwise, holes
// clockwise. Errors name the loop and the edges or vertices at fault: fewer than 3
// vertices, repeated vertices, zero area, crossing or touching edges, a hole outside
// the outer loop or inside another hole.
Result<Region> polygon(std::vector<Vec2> outer, std::vector<std::vector<Vec2>> holes = {});

// Signed area (outer minus holes), by the shoelace formula.
double area(const Region& region);

// The region as one sheet face in the plane z = 0 (normal +z), in a new group.
Result<GroupId> make_region_face(Model& m, const Region& region);

}  // namespace cellforge::shape
