// 2D shapes as OpenSCAD has them: a set of regions in the xy plane, each a simple
// outer polygon with simple holes (region.h). The regions of a Shape2D produced by an
// operation (the Booleans, offset, projection of boolean/ops2d.h; hull) have disjoint
// interiors; they may touch at isolated points. A Shape2D built by hand may hold
// overlapping regions: it then stands for their union, and the Booleans of
// boolean/ops2d.h read it that way (offset normalizes it first).
//
// Notation: a region's loops[0] is counterclockwise, loops[1..] clockwise, so the
// interior lies to the left of every loop edge.
#pragma once

#include <array>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/shape/region.h"
#include "cellforge/shape/transform.h"

namespace cellforge::shape {

struct Shape2D {
  std::vector<Region> regions;

  bool empty() const { return regions.empty(); }
};

// A one-region shape.
inline Shape2D shape_of(Region region) { return Shape2D{{std::move(region)}}; }

// Sum of the regions' signed areas (outer minus holes).
double area(const Shape2D& shape);

// Every loop vertex of every region, in order (the input of a 2D hull).
std::vector<Vec2> points_of(const Shape2D& shape);

// The bounding box of the vertices; both corners zero for an empty shape.
struct Box2 {
  Vec2 min, max;
};
Box2 bounding_box(const Shape2D& shape);

// The image of the shape under the xy part of t: p -> (A00 x + A01 y + t0,
// A10 x + A11 y + t1); the z row and column are ignored (OpenSCAD applies a 3D
// transform to a 2D child the same way). A mirror (negative 2x2 determinant) reverses
// every loop so that outer loops stay counterclockwise; a singular 2x2 part is an
// error (kInvalidInput).
Result<Shape2D> transformed(const Shape2D& shape, const Transform& t);

}  // namespace cellforge::shape
