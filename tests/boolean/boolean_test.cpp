// Boolean operations on solids: named degenerate cases with hand-checked counts and
// closed-form volumes (boolean/boolean.h). Every run also checks that the result
// validates and that rounding made no crossing (boolean_test_util.h).
#include "cellforge/boolean/boolean.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "boolean/boolean_test_util.h"
#include "boolean/stages.h"
#include "cellforge/io/mesh_io.h"

namespace cellforge::testing {
namespace {

using boolean::Expr;
using boolean::Op;

double polygon_area(int n, double r) { return 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n); }

TEST(Boolean, UnionOfOverlappingBoxes) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  const BoolCase r = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(r.volume, 8 + 8 - 1, 1e-12);
  EXPECT_EQ(r.faces, 12u);
  EXPECT_EQ(r.vertices, 20u);
  EXPECT_EQ(r.volumes, 1u);
}

TEST(Boolean, IntersectionOfOverlappingBoxes) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  const BoolCase r = run(Op::kIntersection, {&a, &b});
  EXPECT_NEAR(r.volume, 1, 1e-12);
  EXPECT_EQ(r.faces, 6u);
  EXPECT_EQ(r.edges, 12u);
  EXPECT_EQ(r.vertices, 8u);
}

TEST(Boolean, DifferenceOfOverlappingBoxes) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  const BoolCase r = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(r.volume, 7, 1e-12);
  EXPECT_EQ(r.faces, 9u);
  EXPECT_EQ(r.vertices, 14u);
}

TEST(Boolean, SameOperandTwice) {
  const Model a = box_model({0, 0, 0}, {1, 2, 3});
  for (Op op : {Op::kUnion, Op::kIntersection}) {
    const BoolCase r = run(op, {&a, &a});
    EXPECT_NEAR(r.volume, 6, 1e-12) << to_string(op);
    EXPECT_EQ(r.faces, 6u);
    EXPECT_EQ(r.edges, 12u);
    EXPECT_EQ(r.vertices, 8u);
  }
  const BoolCase d = run(Op::kDifference, {&a, &a});
  EXPECT_EQ(d.faces, 0u);
  const Model s = sphere_model(3, 16);
  const double vs = shape::mass_properties(s).volume;
  EXPECT_NEAR(run(Op::kUnion, {&s, &s}).volume, vs, 1e-12);
  EXPECT_NEAR(run(Op::kIntersection, {&s, &s}).volume, vs, 1e-12);
  EXPECT_EQ(run(Op::kDifference, {&s, &s}).faces, 0u);
}

TEST(Boolean, BoxesSharingAFaceUniteIntoOneBox) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({0, 0, 1}, {1, 1, 2});
  const BoolCase r = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(r.volume, 2, 1e-12);
  EXPECT_EQ(r.faces, 6u);
  EXPECT_EQ(r.edges, 12u);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(run(Op::kIntersection, {&a, &b}).faces, 0u);
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.faces, 6u);
}

TEST(Boolean, ShiftedCoplanarOverlap) {
  // Equal heights: the tops and bottoms are coplanar and overlap in [1,2]^2.
  const Model a = box_model({0, 0, 0}, {2, 2, 1});
  const Model b = box_model({1, 1, 0}, {3, 3, 1});
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 7, 1e-12);
  EXPECT_EQ(u.faces, 10u);  // top, bottom (octagons), eight sides
  EXPECT_EQ(u.vertices, 16u);
  const BoolCase i = run(Op::kIntersection, {&a, &b});
  EXPECT_NEAR(i.volume, 1, 1e-12);
  EXPECT_EQ(i.faces, 6u);
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 3, 1e-12);
  EXPECT_EQ(d.faces, 8u);
}

TEST(Boolean, BoxesTouchingAtAnEdge) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({1, 1, 0}, {2, 2, 1});
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 2, 1e-12);
  EXPECT_EQ(u.faces, 12u);
  EXPECT_EQ(u.edges, 23u);  // the shared edge once, with four faces
  EXPECT_EQ(u.vertices, 14u);
  EXPECT_EQ(u.volumes, 2u);
  const EdgeId e = edge_at(u.result.model, {1, 1, 0}, {1, 1, 1});
  EXPECT_EQ(u.result.model.use_count(e), 4u);
  EXPECT_EQ(u.result.model.num_groups(), 1u);
  EXPECT_EQ(run(Op::kIntersection, {&a, &b}).faces, 0u);
  EXPECT_NEAR(run(Op::kDifference, {&a, &b}).volume, 1, 1e-12);
}

TEST(Boolean, BoxesTouchingAtAVertex) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({1, 1, 1}, {2, 2, 2});
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 2, 1e-12);
  EXPECT_EQ(u.faces, 12u);
  EXPECT_EQ(u.vertices, 15u);
  EXPECT_EQ(run(Op::kIntersection, {&a, &b}).faces, 0u);
}

TEST(Boolean, EdgesCrossingInCoplanarFaces) {
  // A square and a diamond of one height: their tops are coplanar, edges cross.
  const Model a = box_model({-1, -1, 0}, {1, 1, 1});
  MeshInput in;
  in.volumes = 1;
  const double s = 1.25;
  std::vector<Vec3> p = {{s, 0, 0}, {0, s, 0}, {-s, 0, 0}, {0, -s, 0},
                         {s, 0, 1}, {0, s, 1}, {-s, 0, 1}, {0, -s, 1}};
  in.positions = p;
  in.faces = {{{{3, 2, 1, 0}}, -1, 0}, {{{4, 5, 6, 7}}, -1, 0}, {{{0, 1, 5, 4}}, -1, 0},
              {{{1, 2, 6, 5}}, -1, 0}, {{{2, 3, 7, 6}}, -1, 0}, {{{3, 0, 4, 7}}, -1, 0}};
  const Model b = build(in);
  const double corner = 0.5 * (2 - s) * (2 - s);  // a corner of the square outside
  const BoolCase i = run(Op::kIntersection, {&a, &b});
  EXPECT_NEAR(i.volume, 4 - 4 * corner, 1e-12);
  EXPECT_EQ(i.faces, 10u);  // octagon top and bottom, eight sides
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 2 * s * s + 4 * corner, 1e-12);
  EXPECT_EQ(u.faces, 18u);
}

TEST(Boolean, VertexOnAFace) {
  // A pyramid whose apex touches the middle of the box's top face.
  const Model a = box_model({0, 0, 0}, {2, 2, 1});
  MeshInput in;
  in.volumes = 1;
  in.positions = {{0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 1, 1}};
  in.faces = {{{{0, 1, 2, 3}}, -1, 0}, {{{1, 0, 4}}, -1, 0}, {{{2, 1, 4}}, -1, 0},
              {{{3, 2, 4}}, -1, 0}, {{{0, 3, 4}}, -1, 0}};
  const Model b = build(in);
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 4 + 4.0 / 3, 1e-12);
  EXPECT_EQ(run(Op::kIntersection, {&a, &b}).faces, 0u);
  EXPECT_NEAR(run(Op::kDifference, {&a, &b}).volume, 4, 1e-12);
  // The apex inside a triangle of the top face, off its diagonal: it becomes a vertex
  // of the top face (pieces around it), so the solids share it.
  in.positions[4] = {0.5, 1.25, 1};
  for (Vec3& p : in.positions)
    if (p.z == 2) p = {p.x * 0.5, p.y * 0.5 + 0.5, 2};
  const Model c = build(in);
  const BoolCase w = run(Op::kUnion, {&a, &c});
  EXPECT_NEAR(w.volume, 4 + 1.0 / 3, 1e-12);
  bool shared = false;
  for (VertexId v : w.result.model.vertices()) shared |= w.result.model.position(v) == Vec3{0.5, 1.25, 1};
  EXPECT_TRUE(shared);
}

// Edges of one solid inside a face of the other, the surface passing from outside it
// to inside across them: two square pyramids whose bases, in x = 2 and y = 2, share a
// diagonal (found by the comparison with CGAL Nef, tests/nef). The triangles on either
// side of such an edge are classified apart.
TEST(Boolean, EdgesInsideTheOtherSolidsFace) {
  auto pyramid = [](std::vector<Vec3> base, Vec3 apex) {
    MeshInput in;
    in.volumes = 1;
    in.positions = base;
    in.positions.push_back(apex);
    in.faces = {{{{3, 2, 1, 0}}, -1, 0}, {{{0, 1, 4}}, -1, 0}, {{{1, 2, 4}}, -1, 0},
                {{{2, 3, 4}}, -1, 0}, {{{3, 0, 4}}, -1, 0}};
    Model m = build(in);
    if (shape::mass_properties(m).volume < 0) {
      for (MeshFace& f : in.faces) std::reverse(f.loops[0].begin(), f.loops[0].end());
      m = build(in);
    }
    return m;
  };
  const Model p0 = pyramid({{2, 2, 2.5}, {2, 3.5, 1}, {2, 2, -0.5}, {2, 0.5, 1}}, {0, 2, 1});
  const Model p1 = pyramid({{2, 2, 2.5}, {3.5, 2, 1}, {2, 2, -0.5}, {0.5, 2, 1}}, {2, 3, 1});
  // Bases of area 4.5; heights 2 and 1. The common part is the tetrahedron
  // (2,2,2.5) (2,2,-0.5) (2,3,1) (0.5,2,1) of volume 3 * 1 * 1.5 / 6 = 0.75.
  EXPECT_NEAR(shape::mass_properties(p0).volume, 3, 1e-12);
  EXPECT_NEAR(shape::mass_properties(p1).volume, 1.5, 1e-12);
  const BoolCase i = run(Op::kIntersection, {&p0, &p1});
  EXPECT_NEAR(i.volume, 0.75, 1e-12);
  EXPECT_EQ(i.vertices, 4u);
  EXPECT_EQ(i.faces, 4u);
  EXPECT_NEAR(run(Op::kUnion, {&p0, &p1}).volume, 3.75, 1e-12);
  EXPECT_NEAR(run(Op::kDifference, {&p0, &p1}).volume, 2.25, 1e-12);
  EXPECT_NEAR(run(Op::kDifference, {&p1, &p0}).volume, 0.75, 1e-12);
}

TEST(Boolean, NestedBoxMakesACavity) {
  const Model a = box_model({0, 0, 0}, {3, 3, 3});
  const Model b = box_model({1, 1, 1}, {2, 2, 2});
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 26, 1e-12);
  EXPECT_EQ(d.faces, 12u);
  EXPECT_EQ(d.volumes, 1u);  // one cell with an outer and an inner shell
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 27, 1e-12);
  EXPECT_EQ(u.faces, 6u);
  const BoolCase i = run(Op::kIntersection, {&a, &b});
  EXPECT_NEAR(i.volume, 1, 1e-12);
  EXPECT_EQ(i.faces, 6u);
}

// A cavity belongs to the solid around it, decided exactly: an L of two thin slabs
// wrapped round the cube's corner holds the cube's cavity in its bounding box and has
// the smaller volume (the rule "smallest cell whose box holds it" gave it the cavity).
TEST(Boolean, CavityBelongsToTheSolidAroundIt) {
  const Model a = box_model({0, 0, 0}, {10, 10, 10}), b = box_model({1, 1, 1}, {2, 2, 2});
  const Model p = box_model({-1, -1, -1}, {3, 3, -0.5}), q = box_model({-1, -1, -1}, {-0.5, 3, 3});
  const Model* ops[4] = {&a, &b, &p, &q};
  using boolean::Expr;
  const auto r = boolean::evaluate(
      ops, Expr::op(Op::kUnion, {Expr::op(Op::kDifference, {Expr::of(0), Expr::of(1)}), Expr::of(2), Expr::of(3)}));
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Model& m = r->model;
  EXPECT_TRUE(validate(m).empty());
  EXPECT_EQ(m.num_volumes(), 2u);
  EXPECT_NEAR(shape::mass_properties(m).volume, 999 + (8 + 8 - 1), 1e-9);  // the slabs overlap in 1
  // The faces of the cube (operand 0) and of its cavity (operand 1) bound one cell,
  // the slabs' faces (operands 2, 3) the other.
  VolumeId cube, slabs;
  for (FaceId f : m.faces()) {
    const VolumeId v = m.back_volume(f).is_valid() ? m.back_volume(f) : m.front_volume(f);
    VolumeId& want = r->sources[f.value].operand < 2 ? cube : slabs;
    if (!want.is_valid()) want = v;
    EXPECT_EQ(v, want) << "face " << f.value << " of operand " << r->sources[f.value].operand;
  }
  EXPECT_NE(cube, slabs);
}

TEST(Boolean, BoxMinusBoxSharingThreeFaces) {
  const Model a = box_model({0, 0, 0}, {3, 3, 3});
  const Model b = box_model({0, 0, 0}, {1, 1, 1});
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 26, 1e-12);
  EXPECT_EQ(d.faces, 9u);
  EXPECT_EQ(d.vertices, 14u);
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_EQ(u.faces, 6u);
  EXPECT_EQ(u.vertices, 8u);
}

TEST(Boolean, DisjointOperands) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({2, 0, 0}, {3, 1, 1});
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, 2, 1e-12);
  EXPECT_EQ(u.faces, 12u);
  EXPECT_EQ(u.volumes, 2u);
  EXPECT_EQ(run(Op::kIntersection, {&a, &b}).faces, 0u);
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_EQ(d.faces, 6u);
  EXPECT_NEAR(d.volume, 1, 1e-12);
}

TEST(Boolean, CylinderHoleExactlyThroughABox) {
  const int n = 24;
  const Model a = box_model({-2, -2, 0}, {2, 2, 1});
  const Model c = cylinder_model(1, 1, n);
  const BoolCase d = run(Op::kDifference, {&a, &c});
  EXPECT_NEAR(d.volume, 16 - polygon_area(n, 1), 1e-12);
  EXPECT_EQ(d.faces, 6u + n);  // top and bottom with a hole, four sides, n walls
  EXPECT_EQ(d.edges, 12u + 3 * n);
  EXPECT_EQ(d.vertices, 8u + 2 * n);
  const BoolCase i = run(Op::kIntersection, {&a, &c});
  EXPECT_NEAR(i.volume, polygon_area(n, 1), 1e-12);
  EXPECT_EQ(i.faces, 2u + n);
}

// Cylinders standing on a slab, their bottom caps on its top face: the caps join the
// slab's cluster and the walls' bottom edges lie in its plane (cut along the lines
// through their vertices; the walls' corners there are vertices already). The union
// is the slab with the cylinders on it: its top face has a hole under each.
TEST(Boolean, CylindersStandingOnASlab) {
  const int n = 20, k = 4;
  const Model slab = box_model({0, 0, 0}, {10, 10, 1});
  std::vector<Model> cyl;
  for (int i = 0; i < k; ++i) cyl.push_back(cylinder_model(1, 2, n, {2.5 + 5.0 * (i % 2), 2.5 + 5.0 * (i / 2), 1}));
  std::vector<const Model*> ops{&slab};
  for (const Model& c : cyl) ops.push_back(&c);
  const BoolCase u = run(Op::kUnion, ops);
  EXPECT_NEAR(u.volume, 100 + k * 2 * polygon_area(n, 1), 1e-12);
  EXPECT_EQ(u.faces, 6u + k * (n + 1));  // the slab's six, each cylinder's walls and top
  EXPECT_EQ(u.edges, 12u + k * 3 * n);
  EXPECT_EQ(u.vertices, 8u + k * 2 * n);
  // Standing on the slab's bottom plane instead, through it: the caps are coplanar with
  // the slab's bottom face and the walls rest on that plane.
  std::vector<Model> half;
  for (int i = 0; i < k; ++i) half.push_back(cylinder_model(1, 2, n, {2.5 + 5.0 * (i % 2), 2.5 + 5.0 * (i / 2), 0}));
  std::vector<const Model*> ops2{&slab};
  for (const Model& c : half) ops2.push_back(&c);
  const BoolCase u2 = run(Op::kUnion, ops2);
  EXPECT_NEAR(u2.volume, 100 + k * polygon_area(n, 1), 1e-12);
  const BoolCase d2 = run(Op::kDifference, ops2);
  EXPECT_NEAR(d2.volume, 100 - k * polygon_area(n, 1), 1e-12);
  EXPECT_EQ(d2.faces, 6u + k * n);  // through holes: top and bottom with k holes, the walls
  EXPECT_EQ(d2.vertices, 8u + k * 2 * n);
}

TEST(Boolean, SphereMinusOffsetSphere) {
  const Model a = sphere_model(10, 24);
  const Model b = sphere_model(10, 24, {5, 3, 2});
  const double va = shape::mass_properties(a).volume;
  const BoolCase u = run(Op::kUnion, {&a, &b}, false);
  const BoolCase i = run(Op::kIntersection, {&a, &b}, false);
  const BoolCase d = run(Op::kDifference, {&a, &b}, false);
  EXPECT_NEAR(u.volume + i.volume, 2 * va, 1e-9 * va);
  EXPECT_NEAR(d.volume, va - i.volume, 1e-9 * va);
  EXPECT_GT(i.volume, 0.3 * va);
}

TEST(Boolean, UntouchedSphereKeepsItsFaces) {
  // OpenSCAD's sphere: its quads are planar only up to rounding, so neighbouring
  // tiles cross each other's planes by a rounding's width, and tiles a ring apart
  // straddle each other's planes without meeting. None of that cuts anything: a
  // union with a box far away keeps every face, and no input triangle is split.
  for (int fn : {16, 64, 128}) {
    const Model a = sphere_model(10, fn);
    const Model b = box_model({30, 0, 0}, {31, 1, 1});
    const BoolCase u = run(Op::kUnion, {&a, &b}, false);
    EXPECT_EQ(u.faces, a.num_faces() + 6) << "fn " << fn;
    EXPECT_EQ(u.result.report.intersecting_pairs, 0u) << "fn " << fn;
    EXPECT_EQ(u.result.report.touched_triangles, 0u) << "fn " << fn;
    EXPECT_EQ(u.result.report.implicit_points, 0u) << "fn " << fn;
    EXPECT_NEAR(u.volume, shape::mass_properties(a).volume + 1, 1e-9);
  }
}

TEST(Boolean, SphereMinusItselfTurnedOntoItsVertices) {
  // A quarter turn maps the sphere's vertices onto vertices (sin and cos are exact).
  const Model a = sphere_model(5, 16);
  const Model b = moved(a, shape::Transform::rotate(90, {0, 0, 1}));
  EXPECT_EQ(run(Op::kDifference, {&a, &b}).faces, 0u);
  const BoolCase u = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(u.volume, shape::mass_properties(a).volume, 1e-12);
}

TEST(Boolean, OperandWithANonManifoldEdge) {
  // Two cubes sharing an edge in one model, cut by a slab through both.
  const Model a = build(two_cubes_sharing_edge());
  const Model b = box_model({-1, -1, 0.25}, {3, 3, 0.75});
  const BoolCase i = run(Op::kIntersection, {&a, &b});
  EXPECT_NEAR(i.volume, 1, 1e-12);
  EXPECT_EQ(i.volumes, 2u);
  EXPECT_EQ(i.result.model.use_count(edge_at(i.result.model, {1, 1, 0.25}, {1, 1, 0.75})), 4u);
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.volumes, 4u);
}

TEST(Boolean, CellsSharingAFaceInOneOperand) {
  const Model a = build(two_cubes_sharing_face());  // [0,1]^2 x [0,2] as two cells
  const Model b = box_model({0.5, -1, -1}, {2, 2, 3});
  const BoolCase d = run(Op::kDifference, {&a, &b});
  EXPECT_NEAR(d.volume, 1, 1e-12);
  EXPECT_EQ(d.faces, 6u);  // the inner face is inside the operand and goes
}

TEST(Boolean, SelfIntersectingOperandIsResolved) {
  MeshInput in;
  in.volumes = 2;
  add_box(in, {0, 0, 0}, {2, 2, 2}, 0);
  add_box(in, {1, 1, 1}, {3, 3, 3}, 1);
  const Model a = build(in);
  const BoolCase r = run_expr(Expr::of(0), {&a});
  EXPECT_NEAR(r.volume, 15, 1e-12);
  EXPECT_EQ(r.faces, 12u);
  const Model c = box_model({1.5, -1, -1}, {4, 4, 4});
  EXPECT_NEAR(run(Op::kDifference, {&a, &c}).volume, 1.5 * 4 + 0.5 * 4 - 0.5, 1e-12);
}

TEST(Boolean, OperandOrderDoesNotMatter) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 0, 0}, {3, 2, 2});
  const Model c = sphere_model(1.2, 12, {1.5, 1, 2});
  std::vector<const Model*> ops = {&a, &b, &c};
  std::vector<int> perm = {0, 1, 2};
  double vu = -1, vi = -1;
  std::size_t fu = 0;
  do {
    std::vector<const Model*> p = {ops[perm[0]], ops[perm[1]], ops[perm[2]]};
    const BoolCase u = run(Op::kUnion, p);
    const BoolCase i = run(Op::kIntersection, p);
    if (vu < 0) {
      vu = u.volume;
      vi = i.volume;
      fu = u.faces;
    }
    EXPECT_NEAR(u.volume, vu, 1e-12);
    EXPECT_NEAR(i.volume, vi, 1e-12);
    EXPECT_EQ(u.faces, fu);
  } while (std::next_permutation(perm.begin(), perm.end()));
}

TEST(Boolean, NestedExpression) {
  // (A u B) - (C n D), evaluated in one pass.
  const Model a = box_model({0, 0, 0}, {2, 1, 1});
  const Model b = box_model({1, 0, 0}, {3, 1, 1});
  const Model c = box_model({0.5, -1, -1}, {2.5, 2, 2});
  const Model d = box_model({-1, -1, 0.5}, {4, 2, 2});
  const Expr e = Expr::op(Op::kDifference, {Expr::op(Op::kUnion, {Expr::of(0), Expr::of(1)}),
                                            Expr::op(Op::kIntersection, {Expr::of(2), Expr::of(3)})});
  const BoolCase r = run_expr(e, {&a, &b, &c, &d});
  EXPECT_NEAR(r.volume, 3 - 2 * 0.5, 1e-12);
}

// Expr::flattened names the same set: on 2,000 random trees over up to six operands
// (empty operations among them), the same answer for every one of the 64 memberships;
// nested runs of one operation are made one (the Menger sponge's difference of unions
// of unions becomes one difference of its boxes).
TEST(Boolean, FlattenedExpressionIsTheSameSet) {
  std::mt19937 rng(20261207);
  const std::function<Expr(int)> tree = [&](int depth) {
    if (depth == 0 || rng() % 4 == 0) return Expr::of(static_cast<int>(rng() % 6));
    const Op ops[3] = {Op::kUnion, Op::kIntersection, Op::kDifference};
    std::vector<Expr> children(rng() % 4);
    for (Expr& c : children) c = tree(depth - 1);
    return Expr::op(ops[rng() % 3], std::move(children));
  };
  int spliced = 0;
  for (int n = 0; n < 2000; ++n) {
    const Expr e = tree(4), f = e.flattened();
    const std::function<int(const Expr&)> size = [&](const Expr& x) {
      int s = 1;
      for (const Expr& c : x.children) s += size(c);
      return s;
    };
    spliced += size(f) < size(e);
    for (unsigned bits = 0; bits < 64; ++bits) {
      std::vector<bool> inside(6);
      for (int k = 0; k < 6; ++k) inside[k] = (bits >> k) & 1;
      ASSERT_EQ(f.contains(inside), e.contains(inside)) << "tree " << n << ", membership " << bits;
    }
  }
  EXPECT_GT(spliced, 500);
  const Expr menger = Expr::op(
      Op::kDifference,
      {Expr::of(0), Expr::op(Op::kUnion, {Expr::op(Op::kUnion, {Expr::of(1), Expr::of(2)}), Expr::of(3)}),
       Expr::op(Op::kUnion, {Expr::of(4)})});
  const Expr flat = menger.flattened();
  ASSERT_EQ(flat.kind, Expr::Kind::kDifference);
  ASSERT_EQ(flat.children.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(flat.children[k].operand, k);
}

// A prism of height h over a planar region: its caps are single faces (the outer loop
// and the holes as given), its walls quads.
Model prism(const std::vector<std::vector<Vec2>>& loops, double h) {
  MeshInput in;
  in.volumes = 1;
  MeshFace bottom, top;
  for (const auto& loop : loops) {
    const auto base = static_cast<std::uint32_t>(in.positions.size());
    const auto n = static_cast<std::uint32_t>(loop.size());
    for (const Vec2 p : loop) in.positions.push_back({p.x, p.y, 0});
    for (const Vec2 p : loop) in.positions.push_back({p.x, p.y, h});
    std::vector<std::uint32_t> lo, hi;
    for (std::uint32_t i = 0; i < n; ++i) {
      lo.push_back(base + n - 1 - i);
      hi.push_back(base + n + i);
      const std::uint32_t j = (i + 1) % n;
      in.faces.push_back({{{base + i, base + j, base + n + j, base + n + i}}, -1, 0});
    }
    bottom.loops.push_back(lo);
    top.loops.push_back(hi);
  }
  bottom.back = top.back = 0;  // the cell behind the outward faces
  in.faces.push_back(bottom);
  in.faces.push_back(top);
  return build(in);
}

// Non-convex caps whose tiles are certified to meet only in shared edges and corners
// (boolean.cpp, simple_face) and are not tested against each other, beside caps that
// fail the certificate: a self-crossing pentagram, whose centre the loop winds twice
// round, must come out as the star's outline, its tiles' overlap found by the tests.
TEST(Boolean, NonConvexCapsSimpleOrNot) {
  // A comb: a spine [0,9] x [0,1] and teeth [2i, 2i+1] x [1,3], with a hole in the spine.
  std::vector<Vec2> comb = {{0, 0}, {9, 0}, {9, 3}, {8, 3}, {8, 1}, {7, 1}, {7, 3}, {6, 3}, {6, 1},
                            {5, 1}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1},
                            {1, 3}, {0, 3}};
  const Model c = prism({comb}, 1);
  const Model holed = prism({comb, {{0.5, 0.25}, {0.5, 0.75}, {8.5, 0.75}, {8.5, 0.25}}}, 1);
  const Model bar = box_model({-1, 2, 0.5}, {10, 2.5, 2});
  for (const auto& [m, area] : {std::pair{&c, 9.0 + 5 * 2}, std::pair{&holed, 9.0 + 5 * 2 - 4}}) {
    EXPECT_NEAR(shape::mass_properties(*m).volume, area, 1e-12);
    const BoolCase i = run(Op::kIntersection, {m, &bar});
    EXPECT_NEAR(i.volume, 5 * 1 * 0.5 * 0.5, 1e-12);  // five teeth, 1 x 0.5 x 0.5 each
    const BoolCase u = run(Op::kUnion, {m, &bar});
    EXPECT_NEAR(u.volume + i.volume, area + 11 * 0.5 * 1.5, 1e-12);
    const BoolCase d = run(Op::kDifference, {m, &bar});
    EXPECT_NEAR(d.volume, area - i.volume, 1e-12);
  }
  // The pentagram {5/2} and its outline (ten corners; inner radius R cos 72 / cos 36).
  const double R = 2, r = R * std::cos(0.4 * std::numbers::pi) / std::cos(0.2 * std::numbers::pi);
  std::vector<Vec2> star, outline;
  for (int k = 0; k < 5; ++k) {
    const double a = std::numbers::pi / 2 + k * 4 * std::numbers::pi / 5;
    star.push_back({R * std::cos(a), R * std::sin(a)});
  }
  for (int k = 0; k < 10; ++k) {
    const double a = std::numbers::pi / 2 + k * std::numbers::pi / 5, rk = k % 2 ? r : R;
    outline.push_back({rk * std::cos(a), rk * std::sin(a)});
  }
  const Model s = prism({star}, 1), o = prism({outline}, 1);
  const double outline_area = 5 * R * r * std::sin(0.2 * std::numbers::pi);
  EXPECT_NEAR(shape::mass_properties(o).volume, outline_area, 1e-12);
  const Model far = box_model({10, 10, 0}, {11, 11, 1});
  const BoolCase u = run(Op::kUnion, {&s, &far}, false);
  EXPECT_NEAR(u.volume, outline_area + 1, 1e-9);
  const Model cut = box_model({-3, -0.1, -1}, {3, 0.1, 2});
  EXPECT_NEAR(run(Op::kDifference, {&s, &cut}, false).volume,
              run(Op::kDifference, {&o, &cut}, false).volume, 1e-9);
}

// The certificate itself (stages.h, simple_face) on hand-made tilings in z = 0.
TEST(Boolean, SimpleFaceCertificate) {
  struct Face {
    std::vector<Vec3> pos;
    std::vector<boolean::Tri> tris;
    boolean::LoopTable loops;
    boolean::TileRange tiles;
    std::uint32_t loop_count = 0;
    bool simple() const {
      return boolean::simple_face(pos, boolean::FaceLoops{&loops, 0, loop_count}, tris, tiles);
    }
  };
  const auto make = [](std::vector<Vec2> pts, std::vector<std::vector<std::uint32_t>> loops,
                       std::vector<std::array<std::uint32_t, 3>> tiles) {
    Face f;
    for (const Vec2 p : pts) f.pos.push_back({p.x, p.y, 0});
    for (const auto& l : loops) f.loops.add(l);
    f.loop_count = static_cast<std::uint32_t>(loops.size());
    for (const auto& t : tiles) {
      f.tiles.push_back(static_cast<std::uint32_t>(f.tris.size()));
      f.tris.push_back({t, 0, 0});
    }
    return f;
  };
  // An L (six corners, four tiles): simple.
  EXPECT_TRUE(make({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {{0, 1, 2, 3, 4, 5}},
                   {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}})
                  .simple());
  // The same tiles, one of them turned over: not.
  EXPECT_FALSE(make({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {{0, 1, 2, 3, 4, 5}},
                    {{0, 1, 2}, {0, 3, 2}, {0, 3, 4}, {0, 4, 5}})
                   .simple());
  // A dart (its corner b reflex) cut along b d: simple; along a c, the tile a b c turns
  // the other way inside a c d, though its edges pair up: not.
  const std::vector<Vec2> dart = {{0, 0}, {2, 1}, {4, 0}, {2, 3}};
  EXPECT_TRUE(make(dart, {{0, 1, 2, 3}}, {{0, 1, 3}, {1, 2, 3}}).simple());
  EXPECT_FALSE(make(dart, {{0, 1, 2, 3}}, {{0, 2, 3}, {0, 1, 2}}).simple());
  // A square with a square hole, eight tiles round it: simple. The square and a square
  // island inside it, each tiled on its own (the island covered twice): not.
  const std::vector<Vec2> frame = {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {1, 1}, {1, 2}, {2, 2}, {2, 1}};
  const std::vector<std::array<std::uint32_t, 3>> ring = {{0, 1, 7}, {0, 7, 4}, {1, 2, 6}, {1, 6, 7},
                                                          {2, 3, 5}, {2, 5, 6}, {3, 0, 4}, {3, 4, 5}};
  EXPECT_TRUE(make(frame, {{0, 1, 2, 3}, {4, 5, 6, 7}}, ring).simple());
  EXPECT_FALSE(make(frame, {{0, 1, 2, 3}, {4, 7, 6, 5}}, {{0, 1, 2}, {0, 2, 3}, {4, 7, 6}, {4, 6, 5}}).simple());
  // Five corners on a circle, each `step` fifths of a turn after the last, and the
  // centre, fanned from the centre. Step 2, the pentagram {5/2}: every tile turns one
  // way, the edges pair up and the one loop turns the tiles' way, but it crosses itself
  // (the centre is covered twice). Step 1, a pentagon: simple.
  const auto fanned = [&](int step) {
    std::vector<Vec2> corners;
    for (int k = 0; k < 5; ++k) {
      const double a = std::numbers::pi / 2 + k * step * 2 * std::numbers::pi / 5;
      corners.push_back({2 * std::cos(a), 2 * std::sin(a)});
    }
    corners.push_back({0, 0});
    return make(corners, {{0, 1, 2, 3, 4}}, {{5, 0, 1}, {5, 1, 2}, {5, 2, 3}, {5, 3, 4}, {5, 4, 0}});
  };
  EXPECT_FALSE(fanned(2).simple());
  EXPECT_TRUE(fanned(1).simple());
  // A corner of the hole on the outer loop's edge (touching): not.
  const std::vector<Vec2> touching = {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {1, 0}, {1, 2}, {2, 2}, {2, 1}};
  EXPECT_FALSE(make(touching, {{0, 1, 2, 3}, {4, 5, 6, 7}}, ring).simple());
}

TEST(Boolean, FacesKnowWhereTheyCameFrom) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  const BoolCase d = run(Op::kDifference, {&a, &b});
  int from_b = 0;
  for (FaceId f : d.result.model.faces()) {
    const boolean::FaceSource& s = d.result.sources.at(f.value);
    ASSERT_TRUE(s.operand == 0 || s.operand == 1);
    if (s.operand == 1) {
      ++from_b;
      EXPECT_TRUE(s.reversed);  // B's faces bound the result from the other side
    } else {
      EXPECT_FALSE(s.reversed);
    }
    EXPECT_EQ(orient3d(s.plane[0], s.plane[1], s.plane[2], centroid_of(d.result.model, f)), 0);
  }
  EXPECT_EQ(from_b, 3);
}

TEST(Boolean, SameInputSameOutput) {
  const Model a = sphere_model(10, 20);
  const Model b = sphere_model(10, 20, {5, 3, 2});
  const BoolCase x = run(Op::kDifference, {&a, &b}, false);
  const BoolCase y = run(Op::kDifference, {&a, &b}, false);
  ASSERT_EQ(x.vertices, y.vertices);
  ASSERT_EQ(x.faces, y.faces);
  for (VertexId v : x.result.model.vertices()) EXPECT_EQ(x.result.model.position(v), y.result.model.position(v));
  for (FaceId f : x.result.model.faces())
    EXPECT_EQ(x.result.model.loop_vertices(x.result.model.outer_loop(f)),
              y.result.model.loop_vertices(y.result.model.outer_loop(f)));
}

// The stages on threads give the result one thread gives, bit for bit, and the same
// report counts.
TEST(Boolean, SameOutputAtAnyThreadCount) {
  std::vector<Model> spheres, plate;
  spheres.push_back(sphere_model(10, 48));
  spheres.push_back(sphere_model(10, 48, {5, 3, 2}));
  plate.push_back(box_model({0, 0, 0}, {20, 20, 5}));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) plate.push_back(cylinder_model(1.5, 7, 24, {5.0 * i + 2.5, 5.0 * j + 2.5, -1}));
  for (const std::vector<Model>* ops : {&spheres, &plate}) {
    std::vector<const Model*> p;
    for (const Model& m : *ops) p.push_back(&m);
    const auto one = boolean::apply(Op::kDifference, p, {.threads = 1});
    ASSERT_TRUE(one.ok());
    for (int threads : {2, 3, 0}) {
      const auto many = boolean::apply(Op::kDifference, p, {.threads = threads});
      ASSERT_TRUE(many.ok());
      const Model &x = one->model, &y = many->model;
      ASSERT_EQ(x.num_vertices(), y.num_vertices()) << threads << " threads";
      ASSERT_EQ(x.num_faces(), y.num_faces());
      for (VertexId v : x.vertices()) {
        const Vec3 a = x.position(v), b = y.position(v);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "vertex " << v.value;
      }
      for (FaceId f : x.faces()) {
        std::vector<std::vector<VertexId>> lx, ly;
        for (LoopId l : x.loops_of(f)) lx.push_back(x.loop_vertices(l));
        for (LoopId l : y.loops_of(f)) ly.push_back(y.loop_vertices(l));
        EXPECT_EQ(lx, ly) << "face " << f.value;
        EXPECT_EQ(one->sources[f.value].face, many->sources[f.value].face);
      }
      const boolean::Report &rx = one->report, &ry = many->report;
      EXPECT_EQ(rx.candidate_pairs, ry.candidate_pairs);
      EXPECT_EQ(rx.pieces, ry.pieces);
      EXPECT_EQ(rx.rays, ry.rays);
      EXPECT_EQ(rx.implicit_points, ry.implicit_points);
      EXPECT_EQ(rx.exact_fallbacks, ry.exact_fallbacks);
      EXPECT_EQ(rx.rounding_self_intersections, ry.rounding_self_intersections);
    }
  }
}

// A rounded result read back: a sphere minus a cylinder, turned by 30 degrees, whose
// 15-gon has two vertices one unit in the last place apart that its projection makes
// one point; the face's tiling used to miss the sliver between them, leaving a hole
// in any result (found by children.scad). Kept beside this test rather than in
// tests/data: its twin vertices do not survive a text STL's 9 digits, which the
// holdout check of every model there requires.
TEST(Boolean, RoundedOperandWithTwinVertices) {
  Model a;
  ASSERT_TRUE(io::read_file(a, std::string(CELLFORGE_TEST_DATA) + "/../boolean/rounded_sphere_minus_cylinder.json").ok());
  const Model far = box_model({100, 0, 0}, {101, 1, 1});
  const double va = shape::mass_properties(a).volume;
  const BoolCase u = run(Op::kUnion, {&a, &far}, false);
  EXPECT_NEAR(u.volume, va + 1, 1e-9 * va);
  const BoolCase self = run(Op::kUnion, {&a, &a}, false);
  EXPECT_NEAR(self.volume, va, 1e-9 * va);
}

TEST(Boolean, RefusesAnOperandWithoutAFace) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  // A sheet is an operand (of no volume: a regularized union is the box alone).
  const Model sheet = build(square_sheet_with_hole());
  const Model* ops[2] = {&a, &sheet};
  const BoolCase u = run(Op::kUnion, {&a, &sheet});
  EXPECT_NEAR(u.volume, 1, 1e-12);
  EXPECT_EQ(u.faces, 6u);
  const Model empty;
  const Model* with_empty[2] = {&a, &empty};
  auto r = boolean::apply(Op::kUnion, with_empty);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("operand 1"), std::string::npos);
  auto bad = boolean::evaluate(std::span<const Model* const>(ops, 1), Expr::of(3));
  ASSERT_FALSE(bad.ok());
}

}  // namespace
}  // namespace cellforge::testing

