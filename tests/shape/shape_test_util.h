// Helpers shared by the shape tests: Euler counts of a group and independent
// closed-form volumes of faceted solids.
#pragma once

#include <cmath>
#include <numbers>

#include "cellforge/shape/faceting.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape::testing {

struct Counts {
  long v = 0, e = 0, f = 0;
  long euler() const { return v - e + f; }
};

inline Counts counts(const Model& m, GroupId g) {
  Counts c;
  for (VertexId v : m.vertices()) c.v += m.group_of(v) == g;
  for (EdgeId e : m.edges()) c.e += m.group_of(e) == g;
  for (FaceId f : m.faces()) c.f += m.group_of(f) == g;
  return c;
}

// Area of the regular n-gon of circumradius r: (n / 2) r^2 sin(2 pi / n).
inline double ngon_area(int n, double r) {
  return n / 2.0 * r * r * std::sin(2 * std::numbers::pi / n);
}

// Frustum of a regular pyramid between n-gons of circumradius r1 and r2, height h.
inline double frustum_volume(int n, double r1, double r2, double h) {
  const double k = ngon_area(n, 1);
  return h / 3 * k * (r1 * r1 + r1 * r2 + r2 * r2);
}

inline double rel_err(double got, double want) { return std::fabs(got - want) / std::fabs(want); }

}  // namespace cellforge::shape::testing
