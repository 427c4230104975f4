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

namespace cellforge::csg {

// Which of the parts meet, as a cluster id for each (the smallest part index of its
// cluster): two parts meet when a triangle of one meets a triangle of the other
// (exactly, geom/intersect.h) or when one lies inside the other (the winding number
// of the other's surface around a vertex of each of its pieces, geom/winding.h); a
// part whose surface is not closed (a sheet) meets every part its triangles' boxes
// reach. Parts in different clusters are apart, and their union is the parts side by
// side. Parts are solids with faces (the tree's leaves are); a wire or a lone point
// in a part is not looked at.
// Parts with the same `together` id (when given, one per part) start in one cluster.
std::vector<std::uint32_t> meeting_clusters(const std::vector<const Model*>& parts,
                                            const std::vector<std::uint32_t>& together = {});

}  // namespace cellforge::csg
