// OpenSCAD's resize(newsize, auto): per-axis scale factors from the bounding box, and
// the scaling itself. As OpenSCAD does it (GeometryEvaluator, after RapCAD's resize):
// axis i with newsize[i] != 0 scales by newsize[i] / size[i]; an axis with
// newsize[i] == 0 keeps scale 1, unless autosize[i], when it takes the factor of the
// axis with the largest new size (the first on ties; 1 when no new size is given).
// The scaling is about the origin, not the box corner.
#pragma once

#include <array>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/shape/shape2d.h"
#include "cellforge/shape/transform.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

struct ResizeOptions {
  Vec3 size{0, 0, 0};  // OpenSCAD's newsize; 0 on an axis: keep (or auto)
  std::array<bool, 3> autosize{false, false, false};
};

// The scale factors for a bounding box of extent `current` (max - min). Errors
// (kInvalidInput): a negative or non-finite new size; a nonzero new size on an axis
// along which the box is flat (OpenSCAD: "Resize in direction normal to flat object
// is not implemented").
Result<Vec3> resize_factors(Vec3 current, const ResizeOptions& options);

// The group scaled by resize_factors of its bounding box, as a new group
// (transformed()).
Result<GroupId> resized(Model& m, GroupId g, const ResizeOptions& options);

// The same for a 2D shape: only size.x, size.y and autosize[0..1] are read.
Result<Shape2D> resized(const Shape2D& shape, const ResizeOptions& options);

}  // namespace cellforge::shape
