// Point in solid: the winding number of a closed triangulated surface around a point,
// decided by exact predicates alone.
//
// The ray from p along +x counts the triangles it crosses, +1 for each whose normal
// (b - a) x (c - a) has a positive x component (the ray leaves through it) and -1
// for the others. Ties — p projecting onto an edge or a vertex in the yz plane, or
// lying in a triangle's plane — are broken by simulation of simplicity: p is taken
// as p + (e^3, e, e^2) for an infinitesimal e > 0, so every triangle is crossed or
// not, consistently across the surface, and the sum is the winding number of the
// perturbed point. For a point off the surface that is the winding number of p
// itself: 1 inside a surface oriented outward (counterclockwise seen from outside),
// -1 inside one oriented inward, 0 outside; for a point on the surface it is the one
// of a point beside it, which is why `on_surface` is reported too.
//
// The surface must be closed (every edge used equally often in both directions);
// polygons may be given as their fan triangles (the fans' inner edges cancel).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

struct Winding {
  int number = 0;           // of p + (e^3, e, e^2)
  bool on_surface = false;  // p lies in one of the closed triangles
};

// One triangle's part: +1 or -1 when the ray from the perturbed p crosses it, else 0.
// Triangles whose projection onto the yz plane is a segment or a point give 0.
int ray_crossing(Vec3 a, Vec3 b, Vec3 c, Vec3 p);

// p lies in the closed triangle abc (abc not degenerate).
bool point_on_triangle(Vec3 a, Vec3 b, Vec3 c, Vec3 p);

// The winding number of the surface made of triangles (index triples into points).
Winding winding_number(std::span<const Vec3> points,
                       std::span<const std::array<std::uint32_t, 3>> triangles, Vec3 p);

// Nesting of closed surfaces that do not cross each other (they may touch). Surface
// s contains surface t when the winding number of s around a vertex of t that does
// not lie on s is not 0; when every vertex of t lies on s, t is taken as not inside
// s. Only surfaces marked `container` are tested as containers (all when the span is
// empty). Candidates come from a hierarchy over the surfaces' boxes (bvh.h), and each
// test point walks a hierarchy over the triangles along its ray.
struct Nesting {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> depth;   // how many surfaces contain it
  std::vector<std::uint32_t> parent;  // the innermost of them (deepest), or kNone
};
Nesting nest_surfaces(std::span<const Vec3> points,
                      std::span<const std::array<std::uint32_t, 3>> triangles,
                      std::span<const std::uint32_t> surface_of, std::uint32_t surfaces,
                      const std::vector<bool>& container = {});

}  // namespace cellforge::inline geom
