// Booleans beyond regularized solids (boolean.h, Options::keep_lower_dim and
// Options::cells): the point set of the expression on the closed operands, with its
// faces, edges and points of no volume, the boundary it does not hold marked, and
// the cells of several operands kept apart. Counts are checked by hand.
#include <gtest/gtest.h>

#include "boolean/boolean_test_util.h"

namespace cellforge::testing {
namespace {

using boolean::Expr;
using boolean::Op;

// What a non-regularized result holds, by dimension.
struct Parts {
  boolean::BooleanResult result;
  double volume = 0;
  std::size_t volumes = 0, faces = 0, edges = 0, vertices = 0;
  std::size_t sheet_faces = 0;   // no volume on either side
  std::size_t inner_faces = 0;   // a volume on both sides
  std::size_t wire_edges = 0;    // no face
  std::size_t lone_points = 0;   // no edge
  std::size_t faces_out = 0, edges_out = 0, vertices_out = 0;  // marked not in the set
};

Parts sets(const Expr& e, std::vector<const Model*> ops, bool lower = true, bool cells = false) {
  Parts p;
  boolean::Options o;
  o.keep_lower_dim = lower;
  o.cells = cells;
  auto r = boolean::evaluate(ops, e, o);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
  if (!r.ok()) return p;
  p.result = std::move(r.value());
  const Model& m = p.result.model;
  const auto v = validate(m);
  EXPECT_TRUE(v.empty()) << to_string(v);
  EXPECT_EQ(p.result.report.rounding_self_intersections, 0u);
  p.volumes = m.num_volumes();
  p.faces = m.num_faces();
  p.edges = m.num_edges();
  p.vertices = m.num_vertices();
  for (FaceId f : m.faces()) {
    const bool front = m.front_volume(f).is_valid(), back = m.back_volume(f).is_valid();
    p.sheet_faces += !front && !back;
    p.inner_faces += front && back;
    p.faces_out += !p.result.face_in.empty() && !p.result.face_in[f.value];
  }
  for (EdgeId e : m.edges()) {
    p.wire_edges += m.is_wire(e);
    p.edges_out += !p.result.edge_in.empty() && !p.result.edge_in[e.value];
  }
  for (VertexId x : m.vertices()) {
    p.lone_points += !m.first_end(x).edge.is_valid() && !m.point_loop(x).is_valid();
    p.vertices_out += !p.result.vertex_in.empty() && !p.result.vertex_in[x.value];
  }
  if (p.faces > p.sheet_faces) p.volume = shape::mass_properties(m).volume;
  return p;
}

Parts sets(Op op, std::vector<const Model*> ops, bool lower = true, bool cells = false) {
  const Expr e = Expr::over(op, static_cast<int>(ops.size()));
  return sets(e, std::move(ops), lower, cells);
}

// ---- cubes sharing a face, an edge, a vertex: {union, intersection, difference} x
// {regularized, not}

TEST(LowerDim, CubesSharingAFace) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({0, 0, 1}, {1, 1, 2});
  // Union: one box either way (the common face is inside).
  for (bool lower : {false, true}) {
    const Parts u = sets(Op::kUnion, {&a, &b}, lower);
    EXPECT_NEAR(u.volume, 2, 1e-12);
    EXPECT_EQ(u.volumes, 1u);
    EXPECT_EQ(u.faces, 6u);
    EXPECT_EQ(u.faces_out + u.edges_out + u.vertices_out, 0u);
  }
  // Intersection: nothing, or the common face alone.
  EXPECT_EQ(sets(Op::kIntersection, {&a, &b}, false).faces, 0u);
  const Parts i = sets(Op::kIntersection, {&a, &b});
  EXPECT_EQ(i.faces, 1u);
  EXPECT_EQ(i.sheet_faces, 1u);
  EXPECT_EQ(i.volumes, 0u);
  EXPECT_EQ(i.edges, 4u);
  EXPECT_EQ(i.vertices, 4u);
  EXPECT_EQ(i.faces_out + i.edges_out + i.vertices_out, 0u);
  // Difference: the lower box, whose top face (B's) is not in the set when it is not
  // regularized, nor the top face's edges and corners.
  const Parts d0 = sets(Op::kDifference, {&a, &b}, false);
  EXPECT_NEAR(d0.volume, 1, 1e-12);
  EXPECT_EQ(d0.faces_out, 0u);
  const Parts d = sets(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.faces, 6u);
  EXPECT_EQ(d.faces_out, 1u);
  EXPECT_EQ(d.edges_out, 4u);
  EXPECT_EQ(d.vertices_out, 4u);
}

TEST(LowerDim, CubesSharingAnEdge) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({1, 1, 0}, {2, 2, 1});
  for (bool lower : {false, true}) {
    const Parts u = sets(Op::kUnion, {&a, &b}, lower);
    EXPECT_NEAR(u.volume, 2, 1e-12);
    EXPECT_EQ(u.volumes, 2u);
    EXPECT_EQ(u.faces, 12u);
    EXPECT_EQ(u.edges, 23u);  // the common edge once, with four faces
    EXPECT_EQ(u.vertices, 14u);
  }
  EXPECT_EQ(sets(Op::kIntersection, {&a, &b}, false).edges, 0u);
  const Parts i = sets(Op::kIntersection, {&a, &b});
  EXPECT_EQ(i.faces, 0u);
  EXPECT_EQ(i.edges, 1u);
  EXPECT_EQ(i.wire_edges, 1u);
  EXPECT_EQ(i.vertices, 2u);
  const Parts d = sets(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.faces, 6u);
  EXPECT_EQ(d.faces_out, 0u);
  EXPECT_EQ(d.edges_out, 1u);  // the common edge is B's
  EXPECT_EQ(d.vertices_out, 2u);
}

TEST(LowerDim, CubesSharingAVertex) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({1, 1, 1}, {2, 2, 2});
  const Parts u = sets(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 2, 1e-12);
  EXPECT_EQ(u.vertices, 15u);
  EXPECT_EQ(sets(Op::kIntersection, {&a, &b}, false).vertices, 0u);
  const Parts i = sets(Op::kIntersection, {&a, &b});
  EXPECT_EQ(i.faces, 0u);
  EXPECT_EQ(i.edges, 0u);
  EXPECT_EQ(i.vertices, 1u);
  EXPECT_EQ(i.lone_points, 1u);
  const Parts d = sets(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.edges_out, 0u);
  EXPECT_EQ(d.vertices_out, 1u);
}

// ---- sheets as operands

// A square sheet through the middle of a unit cube, wider than it.
Model sheet_through_cube() {
  MeshInput in;
  add_face(in, {{{-1, -1, 0.5}, {2, -1, 0.5}, {2, 2, 0.5}, {-1, 2, 0.5}}});
  return build(in);
}

TEST(LowerDim, SheetAcrossACube) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model s = sheet_through_cube();
  // Regularized, the sheet is nothing.
  const Parts u0 = sets(Op::kUnion, {&a, &s}, false);
  EXPECT_NEAR(u0.volume, 1, 1e-12);
  EXPECT_EQ(u0.faces, 6u);
  // Union: the cube and the sheet's part outside it, a frame around the cube's waist
  // (where the frame meets the sides, they are cut: each edge of the waist has three
  // faces).
  const Parts u = sets(Op::kUnion, {&a, &s});
  EXPECT_NEAR(u.volume, 1, 1e-12);
  EXPECT_EQ(u.volumes, 1u);
  EXPECT_EQ(u.sheet_faces, 1u);
  EXPECT_EQ(u.faces, 11u);
  // Intersection: the square where the sheet is inside the cube (and on its sides).
  const Parts i = sets(Op::kIntersection, {&a, &s});
  EXPECT_EQ(i.faces, 1u);
  EXPECT_EQ(i.sheet_faces, 1u);
  EXPECT_EQ(i.volumes, 0u);
  EXPECT_EQ(i.edges, 4u);
  // Difference: the cube stays whole and the cut is recorded, a face not in the set
  // between the two halves.
  const Parts d = sets(Op::kDifference, {&a, &s});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.volumes, 2u);
  EXPECT_EQ(d.inner_faces, 1u);
  EXPECT_EQ(d.faces_out, 1u);
  // The sheet minus the cube: the frame, open along the cube's waist.
  const Parts f = sets(Expr::op(Op::kDifference, {Expr::of(1), Expr::of(0)}), {&a, &s});
  EXPECT_EQ(f.volumes, 0u);
  EXPECT_EQ(f.sheet_faces, 1u);
  EXPECT_EQ(f.edges_out, 4u);
}

// ---- cells

TEST(LowerDim, CubeCutBySheetIntoTwoCells) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model s = sheet_through_cube();
  // The union with cells: the cube in two cells, the sheet's frame outside.
  const Parts u = sets(Op::kUnion, {&a, &s}, true, true);
  EXPECT_NEAR(u.volume, 1, 1e-12);
  EXPECT_EQ(u.volumes, 2u);
  EXPECT_EQ(u.inner_faces, 1u);
  EXPECT_EQ(u.sheet_faces, 1u);
}

TEST(LowerDim, OverlappingCubesAsCells) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  // A - B, A n B and B - A: three cells of one group, volume 15.
  const Parts u = sets(Op::kUnion, {&a, &b}, false, true);
  EXPECT_NEAR(u.volume, 15, 1e-12);
  EXPECT_EQ(u.volumes, 3u);
  EXPECT_EQ(u.inner_faces, 6u);  // the common cube's six sides, split where they cross
}

}  // namespace
}  // namespace cellforge::testing
