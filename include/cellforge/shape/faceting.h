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

#include <string>

namespace cellforge::shape {

// OpenSCAD's GRID_FINE: radii below it get the minimum of 3 fragments.
inline constexpr double kGridFine = 0.00000095367431640625;
// OpenSCAD clamps $fa and $fs to at least this.
inline constexpr double kMinimumFaFs = 0.01;

// OpenSCAD's special variables. Defaults are OpenSCAD's ($fn = 0, $fa = 12, $fs = 2).
struct Faceting {
  double fn = 0;
  double fa = 12;
  double fs = 2;
};

// Number of segments of a full circle of radius r.
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
