// Sweeps (seed 003): linear extrusion and rotational sweep of 2D profiles, as
// OpenSCAD's linear_extrude and rotate_extrude make them.
//
// The dimension of the result follows the profile (seed 003's dimension cases):
//   Region   -> a solid (one closed cell)
//   Polyline -> a sheet (faces without cells)
//   point    -> wire edges (a chain along the path), or an isolated vertex when a
//               rotated point lies on the axis
//
// linear_extrude: slice k of `slices` (t = k / slices) is the profile rotated by
// -twist * t degrees, then scaled by (1 + (scale_x - 1) t, 1 + (scale_y - 1) t), at
// z = height * t (minus height / 2 when centred). Side quads stay quads when they are
// planar by construction (no twist, scale_x == scale_y); otherwise each is split along
// its shorter diagonal with OpenSCAD's tie rule, so the faces match OpenSCAD's. scale 0
// on both axes closes the top in an apex (regions without holes only). slices = 0
// picks OpenSCAD's count (1 without twist or non-uniform scale; else its helix /
// diagonal rules with the faceting).
//
// rotate_extrude: point (x, y) of the profile goes to (x cos a, x sin a, y) for
// a = start + j * angle / segments, segments = arc_fragments(max |x|, angle). A full
// turn starts at 180 degrees (on the -x axis, OpenSCAD's convention); a partial one at
// `start` (default 0) and gets two end caps. The profile must not cross the axis
// (x = 0); points on it collapse to one vertex, and profile edges on it to one edge.
#pragma once

#include <optional>

#include "cellforge/shape/faceting.h"
#include "cellforge/shape/region.h"
#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

struct LinearExtrudeOptions {
  double height = 1;
  bool center = false;
  double twist = 0;  // degrees, clockwise seen from +z (OpenSCAD)
  double scale_x = 1;
  double scale_y = 1;
  int slices = 0;  // 0: OpenSCAD's rule
  Faceting faceting = {};
};

Result<GroupId> linear_extrude(Model& m, const Region& profile,
                               const LinearExtrudeOptions& options = {});
Result<GroupId> linear_extrude(Model& m, const Polyline& profile,
                               const LinearExtrudeOptions& options = {});
Result<GroupId> linear_extrude(Model& m, Vec2 point, const LinearExtrudeOptions& options = {});

struct RotateExtrudeOptions {
  double angle = 360;                // degrees in [-360, 360], not 0
  std::optional<double> start = {};  // default: 180 for a full turn, else 0
  Faceting faceting = {};
};

Result<GroupId> rotate_extrude(Model& m, const Region& profile,
                               const RotateExtrudeOptions& options = {});
Result<GroupId> rotate_extrude(Model& m, const Polyline& profile,
                               const RotateExtrudeOptions& options = {});
Result<GroupId> rotate_extrude(Model& m, Vec2 point, const RotateExtrudeOptions& options = {});

// The number of slices linear_extrude uses for these options (OpenSCAD's rule).
int extrude_slices(const Region& profile, const LinearExtrudeOptions& options);

}  // namespace cellforge::shape
