// Closed paths filled even-odd (OpenSCAD's polygon() with several paths, DXF and SVG
// outlines), for the common case where no two paths meet (private to csg/).
#pragma once

#include <optional>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/shape/region.h"

namespace cellforge::csg {

// When every path is a simple polygon and no two paths share a point (decided with
// the exact predicates), the even-odd fill is read off the nesting: a path inside an
// even number of others is an outer boundary, and the paths directly inside it are
// its holes. The regions returned are then disjoint and do not touch. nullopt when
// some path is not simple or two paths meet (the caller falls back to Booleans).
// Paths of fewer than 3 points are ignored.
std::optional<std::vector<shape::Region>> fill_nested(const std::vector<std::vector<Vec2>>& paths);

}  // namespace cellforge::csg
