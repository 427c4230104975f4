// Affine transforms of groups. A Transform is the 3x4 matrix [A | t] acting as
// p -> A p + t. Rotations take degrees and use exact sine and cosine at multiples of
// 30 and 45 degrees (faceting.h), as OpenSCAD does.
//
// transformed() builds the image of a group into a new group (the source stays): the
// topology is copied through build_mesh with every position mapped. When det A < 0
// (a mirror) every loop is reversed so that faces still point out of their cells;
// a singular A is an error. Attributes are kept and the matrix is recorded as the
// attribute "transform"; analytic surfaces follow the transform when it is a
// similarity (radii scaled), and are dropped otherwise (the facets are no longer of
// that kind of surface).
#pragma once

#include <array>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

struct Transform {
  std::array<std::array<double, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  static Transform identity() { return {}; }
  static Transform translate(Vec3 t);
  static Transform scale(Vec3 s);
  // Right-handed rotation by `degrees` about `axis` (OpenSCAD's rotate(a, v)).
  static Transform rotate(double degrees, Vec3 axis);
  // OpenSCAD's rotate([x, y, z]): about x first, then y, then z (Rz * Ry * Rx).
  static Transform rotate_xyz(Vec3 degrees);
  // Reflection in the plane through the origin with this normal (OpenSCAD's mirror).
  static Transform mirror(Vec3 normal);
  // A 4x4 matrix in row-major order; the last row must be (0, 0, 0, 1).
  static Result<Transform> from_matrix(const std::array<std::array<double, 4>, 4>& rows);

  Vec3 apply(Vec3 p) const;
  Vec3 apply_linear(Vec3 v) const;  // A v (directions)
  double determinant() const;       // det A
  // (*this * other).apply(p) == apply(other.apply(p)).
  Transform operator*(const Transform& other) const;
};

Result<GroupId> transformed(Model& m, GroupId g, const Transform& t);

}  // namespace cellforge::shape
