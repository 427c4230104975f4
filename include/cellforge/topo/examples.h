// Small models built step by step with the Euler operators: the main job's
// examples and the tests' cross-checks against the bulk builder.
#pragma once

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

// The box [lo, hi] from mvsf, mev and mef (faces outward, counterclockwise). With
// `solid`, make_volume fills it. The group is created with `name`.
Result<GroupId> euler_box(Model& m, Vec3 lo, Vec3 hi, bool solid, std::string name = {});
// The same box into an existing group.
Status euler_box_into(Model& m, GroupId g, Vec3 lo, Vec3 hi, bool solid);

// The box [lo, hi] with a square hole [hole_lo, hole_hi] (in x and y) through it
// along z: the box, then on its top and bottom an inner square made with mev,
// kemr, mev and mef, kfmrh joining the two squares into a handle, mekr and three
// mef for the hole's walls.
Result<GroupId> euler_box_with_hole(Model& m, Vec3 lo, Vec3 hi, double hole_lo, double hole_hi,
                                    std::string name = {});

// A non-manifold group: two unit cubes (each its own volume) sharing the edge
// x = y = 1 (merge_vertices and merge_edges join them), a wire edge from the
// corner (1, 1, 1) to (2, 2, 2), and an isolated vertex at (3, 0, 0).
Result<GroupId> euler_nonmanifold_example(Model& m, std::string name = {});

}  // namespace cellforge::inline topo
