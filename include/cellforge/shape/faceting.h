// How curved primitives are faceted: OpenSCAD's $fn / $fa / $fs rule, and sine and
// cosine in degrees that are exact at multiples of 30 and 45 degrees (as OpenSCAD's
// sin_degrees / cos_degrees), so that a model built here and the same model built by
// OpenSCAD agree vertex for vertex.
//
// fragments(r) (OpenSCAD's get_fragments_from_r, src/utils/calc.cc):
//   r < kGridFine            -> 3
//   fn > 0                   -> max(trunc(fn), 3)
//   otherwise                -> ceil(max(min(360 / fa, 2 pi r / fs), 5))
// with fa and fs clamped below at 0.01 and a negative fn read as 0, as OpenSCAD does.
#pragma once

#include <cstdint>
#include <string>

#include "cellforge/result.h"

namespace cellforge::shape {

// OpenSCAD's GRID_FINE: radii below it get the minimum of 3 fragments.
inline constexpr double kGridFine = 0.00000095367431640625;
// OpenSCAD clamps $fa and $fs to at least this.
inline constexpr double kMinimumFaFs = 0.01;

// The most vertices a primitive or sweep may make (docs/shape.md, "Limits"): the
// count follows from the parameters and is checked before anything is allocated,
// so that fn=100000 on a sphere (5e9 vertices) or a prism of 1e9 sides is an error,
// not an attempt to allocate it. Options carry it as max_vertices, to raise it.
inline constexpr std::uint64_t kDefaultMaxVertices = 10'000'000;
// The largest coordinate magnitude a primitive or sweep may produce: 2^120
// (~1.3e36), the range in which geom's predicates (up to the radial order's degree 8)
// stay exact (geom/predicates.h). Beyond it volumes and areas overflow too.
inline constexpr double kMaxCoordinate = 0x1p120;

// OpenSCAD's special variables. Defaults are OpenSCAD's ($fn = 0, $fa = 12, $fs = 2).
struct Faceting {
  double fn = 0;
  double fa = 12;
  double fs = 2;
  std::uint64_t max_vertices = kDefaultMaxVertices;
};

// fn, fa and fs finite and not negative (OpenSCAD reads a negative fn as 0 and
// NaN as 3 fragments; here they are errors naming the value).
Status check_faceting(const Faceting& f);
// An error when `vertices` (what `what` would make) exceeds `max_vertices`.
Status check_vertex_count(std::uint64_t vertices, std::uint64_t max_vertices,
                          const std::string& what);
// x rounded toward zero to an int, saturating at INT_MAX (and at 0 below), so
// that counts computed from huge parameters stay defined and are refused by
// check_vertex_count.
int saturated_count(double x);

// Number of segments of a full circle of radius r (at most INT_MAX).
int fragments(double r, const Faceting& f);

// Segments of an arc of `angle_degrees` (rotate_extrude): max(1, ceil(fragments(r) *
// |angle| / 360)).
int arc_fragments(double r, double angle_degrees, const Faceting& f);

// sin and cos of an angle in degrees, exact at 0, 30, 45, 60, 90, ... (OpenSCAD's
// src/utils/degree_trig.cc).
double sin_degrees(double degrees);
double cos_degrees(double degrees);

// The shortest decimal text that reads back as the same double ("0.1", "3", "1e-07").
std::string format_number(double x);

}  // namespace cellforge::shape
