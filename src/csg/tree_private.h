// Helpers of the tree builder shared with the cache (private to csg/).
#pragma once

#include <vector>

#include "cellforge/shape/transform.h"
#include "cellforge/topo/model.h"

namespace cellforge::csg {

// A copy of every group of src with its positions mapped by t (loops reversed when t
// mirrors); analytic surfaces are not kept.
Model copy_transformed(const Model& src, const shape::Transform& t);
// The same into an existing model; returns the new FaceId of each source face (by
// source FaceId value).
std::vector<FaceId> copy_into(Model& out, const Model& src, const shape::Transform& t);
bool is_identity(const shape::Transform& t);

}  // namespace cellforge::csg
