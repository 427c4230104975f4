// Solid primitives, each built through build_mesh (topo/builder.h) into a new group of
// one closed cell. Faces keep their polygons: a cylinder has two n-gon caps and n
// quads; a sphere has OpenSCAD's layout (rings = (n + 1) / 2, ring i at polar angle
// 180 (i + 0.5) / rings, flat n-gon caps, no pole vertices).
//
// Every primitive records on its group the attribute "kind" and its parameters under
// OpenSCAD's names ("r", "h", "r1", "r2", "center", "fn", "fa", "fs", "segments", ...),
// and gives the faces that came from a curved surface one Surface (Model::add_surface),
// so the edges between those facets are smooth (Model::is_smooth).
//
// Errors (ErrorCode::kInvalidInput) name the parameter at fault; on error the model is
// unchanged. Parameters must be finite (fn, fa, fs also >= 0); a primitive that would
// make more than max_vertices vertices (faceting.h, checked before allocating) or a
// coordinate beyond kMaxCoordinate is refused.
#pragma once

#include <cstdint>
#include <vector>

#include "cellforge/shape/faceting.h"
#include "cellforge/shape/region.h"
#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

// OpenSCAD's cube(size, center): corner at the origin, or centred on it.
struct CubeOptions {
  Vec3 size{1, 1, 1};
  bool center = false;
};
Result<GroupId> make_cube(Model& m, const CubeOptions& options = {});

// OpenSCAD's cylinder(h, r1, r2, center): fragments(max(r1, r2)) segments; a zero
// radius makes that end an apex (a cone), not an n-gon.
struct CylinderOptions {
  double h = 1;
  double r1 = 1;
  double r2 = 1;
  bool center = false;
  Faceting faceting = {};
};
Result<GroupId> make_cylinder(Model& m, const CylinderOptions& options = {});

// OpenSCAD's sphere(r).
struct SphereOptions {
  double r = 1;
  Faceting faceting = {};
};
Result<GroupId> make_sphere(Model& m, const SphereOptions& options = {});

// The torus about the z axis that OpenSCAD makes with
// rotate_extrude() translate([major_radius, 0]) circle(minor_radius): the profile has
// fragments(minor_radius) vertices, the revolution fragments(major + minor) segments
// starting on the -x axis (OpenSCAD's full-turn convention).
struct TorusOptions {
  double major_radius = 2;
  double minor_radius = 1;
  Faceting faceting = {};
};
Result<GroupId> make_torus(Model& m, const TorusOptions& options = {});

// A right prism over the regular n-gon of circumradius r (first vertex at (r, 0)).
struct RegularPrismOptions {
  int sides = 6;
  double r = 1;
  double h = 1;
  bool center = false;
  std::uint64_t max_vertices = kDefaultMaxVertices;
};
Result<GroupId> make_regular_prism(Model& m, const RegularPrismOptions& options = {});

// A right prism over any region (a simple polygon, with holes), height h along z.
Result<GroupId> make_prism(Model& m, const Region& base, double h, bool center = false);

// A pyramid: the regular n-gon of circumradius r at z = 0, the apex at (0, 0, h).
struct PyramidOptions {
  int sides = 4;
  double r = 1;
  double h = 1;
  bool center = false;
  std::uint64_t max_vertices = kDefaultMaxVertices;
};
Result<GroupId> make_pyramid(Model& m, const PyramidOptions& options = {});

// A frustum of a regular pyramid: n-gons of circumradius r1 at the bottom, r2 at the top.
struct FrustumOptions {
  int sides = 4;
  double r1 = 1;
  double r2 = 0.5;
  double h = 1;
  bool center = false;
  std::uint64_t max_vertices = kDefaultMaxVertices;
};
Result<GroupId> make_frustum(Model& m, const FrustumOptions& options = {});

// OpenSCAD's polyhedron(points, faces). With `clockwise` (OpenSCAD's convention) each
// face lists its points clockwise seen from outside; otherwise counterclockwise.
// Checked, each error naming the face: an index out of range, fewer than 3 or repeated
// indices, a face whose points are collinear or not coplanar (exact test; see
// planarity_tolerance), an edge that is not used equally often in both directions
// (an open surface or inconsistent orientation), and a negative total volume (faces
// pointing inward).
struct PolyhedronOptions {
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;
  bool clockwise = true;
  // A face's points may lie off the plane of its first three non-collinear points by
  // this much (absolute distance). 0: exactly coplanar (exact predicate).
  double planarity_tolerance = 0;
};
Result<GroupId> make_polyhedron(Model& m, const PolyhedronOptions& options);

}  // namespace cellforge::shape
