// Regularized Boolean operations on solids: one exact arrangement of every operand,
// then a selection by a Boolean expression (DESIGN.md, "Boolean operations").
//
//   Expr e = Expr::difference({Expr::operand(0), Expr::operand(1)});
//   Result<BooleanResult> r = evaluate({&a, &b}, e);
//
// An operand is a whole model: the union of the 3-cells of all its groups, bounded by
// the faces that have a cell on one side only (faces between two of its cells are
// inside it). Operands may be non-manifold (cubes sharing an edge, cells sharing a
// face) and may intersect themselves: membership is the winding number > 0 of the
// operand's outward faces, so a self-intersecting but consistently oriented operand
// is resolved, not refused.
//
// Every decision is an exact predicate on the input doubles: intersection points are
// implicit (a segment meeting a plane, two lines of a plane meeting) and are rounded
// to doubles once, when the result is built. Faces keep the input plane they lie on
// (FaceSource::plane), and which operand and input face they came from.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::boolean {

enum class Op { kUnion, kIntersection, kDifference };

// A Boolean expression over operands 0..n-1. Union and intersection take any number
// of children; difference is the first child minus all the others.
struct Expr {
  enum class Kind { kOperand, kUnion, kIntersection, kDifference };
  Kind kind = Kind::kOperand;
  int operand = 0;  // for kOperand
  std::vector<Expr> children;

  static Expr of(int i) { return Expr{Kind::kOperand, i, {}}; }
  static Expr op(Op o, std::vector<Expr> children);
  // The expression `o` applied to operands 0..n-1 in order.
  static Expr over(Op o, int n);
  // Whether a point inside exactly the operands marked in `inside` is in the result.
  bool contains(const std::vector<bool>& inside) const;
  // The same set with nested runs of one operation made one: a union's unions and an
  // intersection's intersections spliced in, and a difference's first difference and
  // the unions it takes away (A - (B u C) - D = A - B - C - D); a child with no children
  // stays (an empty intersection is empty). The classification decides a flat
  // expression from the operands a ray met alone.
  Expr flattened() const;
  // The largest operand index named, or -1.
  int max_operand() const;
};

struct Options {
  // Threads for the stages that run on threads: the triangulation of the operands'
  // faces, the pair tests, the classification rays and the rounding check (0: every
  // hardware thread). The result is the same at any count, bit for bit.
  int threads = 1;
  // Non-regularized (seed 003): the result is the point set the expression gives on the
  // closed operands, lower-dimensional parts included. Faces, edges and points with no
  // volume around them are kept (cubes sharing a face intersect in that face), and the
  // boundary the set does not hold is kept and marked (BooleanResult::face_in).
  bool keep_lower_dim = false;
  // Faces between two kept 3-cells that lie in different operands stay, as inner faces
  // separating two volumes of the result's group (a part of several materials).
  bool cells = false;
  // Cut the clusters as earlier versions did: every segment along its whole line
  // through the convex pieces it crosses. The same point sets, with more vertices
  // and slower; for comparisons (tests, benchmarks).
  bool convex_split = false;
  // The result's rounded vertices checked exactly for crossings they made, and moved
  // to a neighbouring double where that removes them (stages.h). false: rounded to
  // nearest and not checked (Report::rounding_self_intersections is then SIZE_MAX),
  // for a caller that reads the result again exactly rather than using it as a solid
  // (projection(cut = true) takes the section's faces to the planar Boolean).
  bool check_rounding = true;
};

// Where a result face came from.
struct FaceSource {
  int operand = -1;             // the operand whose face it lies on
  std::uint32_t face = 0;       // that face's id in the operand's model
  bool reversed = false;        // true when the result face points against it
  std::array<Vec3, 3> plane{};  // three input points spanning the plane it lies on
};

struct StageTimes {
  // seconds; check: the exact test of the rounded result for crossings
  double soup = 0, intersect = 0, split = 0, classify = 0, output = 0, check = 0;
};

struct Report {
  std::size_t input_triangles = 0;
  std::size_t candidate_pairs = 0;      // bounding-box overlaps tested exactly
  std::size_t intersecting_pairs = 0;   // pairs that cut each other or overlap
  std::size_t touched_triangles = 0;    // input triangles split by something
  std::size_t pieces = 0;               // faces of the arrangement
  std::size_t rays = 0;                 // classification rays cast
  std::size_t implicit_points = 0;      // points made by intersection
  // Clusters (coplanar triangles cut as one) cut into convex pieces rather than along
  // their segments alone, where a face would pass a point twice (Options::convex_split).
  std::size_t convex_split_clusters = 0;
  std::size_t exact_fallbacks = 0;      // predicates the double filter could not decide
  std::size_t rounding_self_intersections = 0;  // pairs of result triangles that cross
                                                // after rounding (checked exactly)
  // Non-regularized and cell results: faces of no volume, faces between two cells,
  // edges of no face, points of no edge, and elements marked not in the set.
  std::size_t sheet_faces = 0, inner_faces = 0, wire_edges = 0, isolated_points = 0;
  std::size_t excluded = 0;
  StageTimes seconds;
};

struct ExactForm;  // exact.h

// The property that marks a non-regularized result's faces, edges and vertices in
// the set (1) or not (0), on models that have an element not in it
// (BooleanResult::face_in).
inline constexpr const char* kInSetProperty = "in_set";

struct BooleanResult {
  Model model;                      // one group, one cell per connected solid
  std::vector<FaceSource> sources;  // by result FaceId value
  // By result VertexId value: true where the exact position may not be a double, so
  // that rounding may have moved the vertex (false: it is exactly where it was).
  std::vector<bool> rounded;
  // Whether the points of each result face, edge and vertex (by id value) belong to
  // the result's point set. Regularized results hold all their boundary; a
  // non-regularized one may not (a difference removing a face, a cut by a sheet).
  // When some element is not in the set, the model carries the same marks as uint8
  // properties named kInSetProperty on its faces, edges and vertices (1: in, 0: not;
  // topo/property.h), so that the native JSON and the model database keep them.
  std::vector<bool> face_in, edge_in, vertex_in;
  Report report;
  // How it was made, exactly, when it came from boolean::chain (exact.h): a Boolean on
  // it re-evaluates from the same inputs instead of from its rounded model.
  std::shared_ptr<const ExactForm> exact;
};

// Evaluates `expr` on the operands. An error names an operand that holds no solid,
// an expression naming an operand that does not exist, or a result the builder
// refused (with its message).
Result<BooleanResult> evaluate(std::span<const Model* const> operands, const Expr& expr,
                               const Options& options = {});

// The operation over all operands in order: union of all, intersection of all, or
// the first minus the others.
Result<BooleanResult> apply(Op op, std::span<const Model* const> operands,
                            const Options& options = {});

std::string to_string(Op op);

}  // namespace cellforge::boolean
