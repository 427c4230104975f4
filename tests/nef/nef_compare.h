// The Boolean operations against an independent implementation: CGAL's
// Nef_polyhedron_3 on an exact kernel (Debian's libcgal-dev, linked by test_nef only).
// Both sides evaluate one expression on the same operands; the results are compared
// by exact point membership at sampled points, and (non-regularized) by the counts
// of their lower-dimensional parts.
//
// Operands become Nef polyhedra through their boundary: the faces with a cell on one
// side only, triangulated (io/triangulate.h) with the cell behind, split into
// connected shells. A shell of positive signed volume is a solid, one of negative
// volume a cavity; the operand is the union of its solids minus the interiors of its
// cavities (a closed set, as every operand is), which is the winding number > 0 rule
// of boolean.h for operands whose shells nest at most two deep (a solid with
// cavities), as every operand here does.
//
// A sampled point is located on each side as the element holding it in its relative
// interior: a vertex, an edge, a face or, off every element, a volume or the outside.
// Nef answers with Nef_polyhedron_3::locate and the element's mark. cellforge's answer
// comes from the result model: the point equals a vertex, lies inside an edge, lies in
// a face's triangles (geom/winding.h point_on_triangle), each an exact test; else it
// is in a volume when the winding number of the faces bounding the result's cells is
// positive (geom/winding.h). The element's mark is BooleanResult::face_in / edge_in /
// vertex_in (true when the vector is empty).
//
// Rounding: result vertices that BooleanResult::rounded marks may sit off their exact
// position by an ulp, and so may the faces and edges at them. A point inside the box
// of such an element, widened by a margin far above an ulp, is not compared (counted
// as skipped); every other point has the same answer on the rounded result as on the
// exact one, since moving the element within its box cannot sweep across the point.
// The margin only chooses which points are compared; no membership is decided by it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/topo/model.h"

namespace cellforge::testing::nef {

// Where a point lies: in the relative interior of an element of this dimension
// (3: a volume or the outside), and whether the set holds it.
struct Where {
  int dim = 3;
  bool in = false;
};

// Lower-dimensional parts of a result: faces with no kept volume on either side,
// edges with no kept face or volume around them, vertices with nothing kept around.
struct LowerDim {
  std::size_t sheets = 0, wires = 0, points = 0;
  friend bool operator==(const LowerDim&, const LowerDim&) = default;
};
std::ostream& operator<<(std::ostream& os, const LowerDim& d);

std::string describe(const boolean::Expr& e);

// One comparison: the operands, the expression, and whether it is regularized.
struct Case {
  std::string name = {};
  std::vector<const Model*> operands = {};
  boolean::Expr expr = {};
  bool regularized = true;
  // Options::cells: inner faces between the operands' cells stay. They lie inside the
  // set, so only membership is compared, not which points lie on the boundary.
  bool cells = false;
  // Step of the grid of sampled points inside the operands' box (0: the box's
  // extent / 8), and how many grid points at most.
  double grid_step = 0;
  std::size_t grid_points = 200;
  std::uint64_t seed = 1;
  // The expression Nef evaluates when it is not `expr`: only for the test that the
  // comparison notices a wrong answer.
  std::optional<boolean::Expr> nef_expr = {};
};

struct Outcome {
  std::size_t compared = 0;  // points compared
  std::size_t skipped = 0;   // points near a rounded element
  std::size_t disagreements = 0;
  // Non-regularized: points where Nef's result is not what its own operands'
  // memberships there make of the expression (the set operations are pointwise) and
  // cellforge's is. Nef's error, not counted as disagreements.
  std::size_t nef_errors = 0;
  std::string first_nef_error;
  std::size_t rounded_vertices = 0;
  std::array<std::size_t, 4> nef_dims{};  // compared points Nef located on a vertex,
                                          // an edge, a facet, in a volume
  LowerDim cellforge, nef;                // lower-dimensional parts of either result
  std::string first_disagreement;         // operands, expression, point, both answers
};

// Evaluates the case with cellforge and with Nef and compares them; records a
// gtest failure (with the first disagreements) when they differ or cellforge fails.
// Regularized results must have no lower-dimensional part on either side; for the
// others both must have the same number of isolated points, and sheets and wires on
// both sides or on neither (their numbers may differ where one side splits a sheet or
// a wire that the other keeps whole; named tests compare the numbers).
Outcome compare(const Case& c);

// Where p lies in cellforge's result of c, and whether the set holds it; the same in
// Nef's result of c, and whether Nef's operands there make the expression hold it (for
// a non-regularized case, what the result must answer: the set operations are
// pointwise).
Where cellforge_where(const Case& c, Vec3 p);
Where nef_result_where(const Case& c, Vec3 p);
bool nef_operands_hold(const Case& c, Vec3 p);
// The same at the point num / den, exactly (a point that is no double).
Where nef_result_where(const Case& c, std::array<double, 3> num, double den);
bool nef_operands_hold(const Case& c, std::array<double, 3> num, double den);

}  // namespace cellforge::testing::nef
