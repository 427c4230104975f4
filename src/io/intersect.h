// Self-intersections of a model's faces: pairs of faces whose triangulations
// meet (touching counts), found through a bounding-volume hierarchy over triangle
// boxes (geom/bvh.h) and decided by the exact triangle test of geom/intersect.h. Triangles that share a vertex
// are not tested against each other (their meeting there is the mesh's own
// connectivity), so an overlap between triangles with a common vertex is missed.
#pragma once

#include <utility>
#include <vector>

#include "cellforge/topo/model.h"

namespace cellforge::io {

std::vector<std::pair<FaceId, FaceId>> self_intersections(const Model& m);

}  // namespace cellforge::io
