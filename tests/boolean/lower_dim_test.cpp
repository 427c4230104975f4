// Booleans beyond regularized solids (boolean.h, Options::keep_lower_dim and
// Options::cells): the point set of the expression on the closed operands, with its
// faces, edges and points of no volume, the boundary it does not hold marked, and
// the cells of several operands kept apart. Counts are checked by hand.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <sstream>

#include <filesystem>

#include "boolean/boolean_test_util.h"
#include "cellforge/io/mesh_io.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/property.h"
#include "support/cli.h"

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

// ---- wires and points as operands

Model wire_model(std::vector<std::array<Vec3, 2>> segments, std::vector<Vec3> points = {}) {
  MeshInput in;
  for (const auto& s : segments) {
    in.positions.push_back(s[0]);
    in.positions.push_back(s[1]);
    in.wires.push_back({static_cast<std::uint32_t>(in.positions.size() - 2),
                        static_cast<std::uint32_t>(in.positions.size() - 1)});
  }
  for (Vec3 p : points) in.positions.push_back(p);
  return build(in);
}

TEST(LowerDim, WireThroughACube) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model w = wire_model({{Vec3{-1, 0.5, 0.5}, Vec3{2, 0.5, 0.5}}});
  // Union: the cube and the wire's two pieces outside it.
  const Parts u = sets(Op::kUnion, {&a, &w});
  EXPECT_NEAR(u.volume, 1, 1e-12);
  EXPECT_EQ(u.volumes, 1u);
  EXPECT_EQ(u.faces, 6u);
  EXPECT_EQ(u.wire_edges, 2u);
  EXPECT_EQ(u.vertices, 12u);
  EXPECT_EQ(u.edges_out + u.vertices_out, 0u);
  // Regularized, it is the cube.
  EXPECT_EQ(sets(Op::kUnion, {&a, &w}, false).edges, 12u);
  // Intersection: the piece inside, its ends on the cube's faces.
  const Parts i = sets(Op::kIntersection, {&a, &w});
  EXPECT_EQ(i.faces, 0u);
  EXPECT_EQ(i.wire_edges, 1u);
  EXPECT_EQ(i.vertices, 2u);
  EXPECT_EQ(i.edges_out + i.vertices_out, 0u);
  // The wire minus the cube: two pieces, their inner ends out of the set.
  const Parts d = sets(Expr::op(Op::kDifference, {Expr::of(1), Expr::of(0)}), {&a, &w});
  EXPECT_EQ(d.wire_edges, 2u);
  EXPECT_EQ(d.vertices, 4u);
  EXPECT_EQ(d.vertices_out, 2u);
  // The cube minus the wire: the cube whole, the wire's path through it a cut.
  const Parts c = sets(Op::kDifference, {&a, &w});
  EXPECT_NEAR(c.volume, 1, 1e-12);
  EXPECT_EQ(c.wire_edges, 1u);
  EXPECT_EQ(c.edges_out, 1u);
  EXPECT_EQ(c.vertices_out, 2u);
}

TEST(LowerDim, WireAlongAFaceAndThroughAnEdge) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  // On the top face, from outside across it; it crosses the edges y = 0 and y = 1.
  const Model w = wire_model({{Vec3{0.5, -1, 1}, Vec3{0.5, 2, 1}}});
  const Parts i = sets(Op::kIntersection, {&a, &w});
  EXPECT_EQ(i.wire_edges, 1u);
  EXPECT_EQ(i.vertices, 2u);
  // Union: the wire's outer pieces meet the cube at its top edges, which take their
  // ends as vertices.
  const Parts u = sets(Op::kUnion, {&a, &w});
  EXPECT_NEAR(u.volume, 1, 1e-12);
  EXPECT_EQ(u.vertices, 8u + 2u + 2u);
  EXPECT_GE(u.wire_edges, 2u);
  const VertexId v = vertex_at(u.result.model, {0.5, 0, 1});
  ASSERT_TRUE(v.is_valid());
  std::size_t faces_at_v = 0;
  for (EdgeId e : u.result.model.edges())
    if (!u.result.model.is_wire(e) &&
        (u.result.model.start_of(e) == v || u.result.model.end_of(e) == v))
      ++faces_at_v;
  EXPECT_EQ(faces_at_v, 2u);  // the split top edge
}

TEST(LowerDim, PointsAndCrossingWires) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  // A point inside, one on a face, one outside; two wires crossing at (3, 3, 3).
  const Model p = wire_model({{Vec3{2, 3, 3}, Vec3{4, 3, 3}}, {Vec3{3, 2, 3}, Vec3{3, 4, 3}}},
                             {Vec3{0.5, 0.5, 0.5}, Vec3{0.5, 0.5, 1}, Vec3{5, 5, 5}});
  const Parts i = sets(Op::kIntersection, {&a, &p});
  EXPECT_EQ(i.vertices, 2u);  // the point inside and the point on the face
  EXPECT_EQ(i.lone_points, 2u);
  const Parts u = sets(Op::kUnion, {&a, &p});
  EXPECT_EQ(u.lone_points, 1u);  // the outside point (the one on the face is the face's)
  EXPECT_EQ(u.wire_edges, 4u);   // the crossing cuts both wires
  const VertexId x = vertex_at(u.result.model, {3, 3, 3});
  ASSERT_TRUE(x.is_valid());
}

// ---- the point set, at sampled points, against closed boxes

// Whether p is in the point set of a result: at a vertex, inside an edge or a face (by
// their marks), else inside a cell (winding number > 0). Exact on grid points.
bool member(const boolean::BooleanResult& r, Vec3 p) {
  const Model& m = r.model;
  for (VertexId v : m.vertices())
    if (m.position(v) == p) return r.vertex_in.empty() || r.vertex_in[v.value];
  for (EdgeId e : m.edges()) {
    const Vec3 a = m.position(m.start_of(e)), b = m.position(m.end_of(e));
    if (!collinear3d(a, b, p)) continue;
    bool inside = false;
    for (int d = 0; d < 3; ++d)
      if (a[d] != b[d]) {
        inside = (a[d] < p[d]) == (p[d] < b[d]);
        break;
      }
    if (inside) return r.edge_in.empty() || r.edge_in[e.value];
  }
  for (FaceId f : m.faces()) {
    const auto tris = io::triangulate_face(m, f);
    for (const auto& t : tris) {
      const Vec3 a = m.position(t[0]), b = m.position(t[1]), c = m.position(t[2]);
      if (orient3d(a, b, c, p) != 0) continue;
      int k = 0;
      while (k < 3 && orient2d_projected(a, b, c, k) == 0) ++k;
      if (k == 3) continue;
      const int o = orient2d_projected(a, b, c, k);
      // Not on the face's boundary (edges were tried): inside a triangle or on a
      // diagonal between two, so inside the face.
      if (orient2d_projected(a, b, p, k) * o >= 0 && orient2d_projected(b, c, p, k) * o >= 0 &&
          orient2d_projected(c, a, p, k) * o >= 0)
        return r.face_in.empty() || r.face_in[f.value];
    }
  }
  return winding_at(m, p) > 0;
}

TEST(LowerDim, RandomBoxesAgreeWithClosedSetsAtSampledPoints) {
#ifdef CELLFORGE_ASAN
  constexpr int kDefaultCases = 40;  // the sanitized build runs the same code 20 times slower
#else
  constexpr int kDefaultCases = 300;
#endif
  const int cases = std::getenv("CELLFORGE_LOWER_CASES") ? std::atoi(std::getenv("CELLFORGE_LOWER_CASES")) : kDefaultCases;
  const int only = std::getenv("CELLFORGE_LOWER_SEED") ? std::atoi(std::getenv("CELLFORGE_LOWER_SEED")) : 0;
  int failures = 0;
  for (int seed = only ? only : 1; seed <= (only ? only : cases) && failures < 5; ++seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed));
    auto coord = [&] { return 0.5 * static_cast<int>(rng() % 7); };  // 0 .. 3, touching often
    const int n = 2 + static_cast<int>(rng() % 2);
    std::vector<Model> boxes;
    std::vector<std::array<Vec3, 2>> extent;
    std::vector<double> ticks;
    for (int i = 0; i < n; ++i) {
      double l[3], h[3];
      for (int d = 0; d < 3; ++d) {
        double x = coord(), y = coord();
        while (x == y) y = coord();
        l[d] = std::min(x, y);
        h[d] = std::max(x, y);
        ticks.push_back(l[d]);
        ticks.push_back(h[d]);
      }
      const Vec3 lo{l[0], l[1], l[2]}, hi{h[0], h[1], h[2]};
      boxes.push_back(box_model(lo, hi));
      extent.push_back({lo, hi});
    }
    std::vector<const Model*> ops;
    for (const Model& b : boxes) ops.push_back(&b);
    const Op op = static_cast<Op>(rng() % 3);
    const Expr e = Expr::over(op, n);
    boolean::Options o;
    o.keep_lower_dim = true;
    auto r = boolean::evaluate(ops, e, o);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.error().message;
    const auto v = validate(r->model);
    EXPECT_TRUE(v.empty()) << "seed " << seed << ": " << to_string(v);
    // Points on the boxes' planes, their edges and corners, and between.
    for (int k = 0; k < 60; ++k) {
      double c[3];
      for (double& x : c) x = rng() % 3 ? ticks[rng() % ticks.size()] : 0.25 * static_cast<int>(rng() % 13);
      const Vec3 p{c[0], c[1], c[2]};
      std::vector<bool> inside(n);
      for (int i = 0; i < n; ++i)
        inside[i] = extent[i][0].x <= p.x && p.x <= extent[i][1].x && extent[i][0].y <= p.y &&
                    p.y <= extent[i][1].y && extent[i][0].z <= p.z && p.z <= extent[i][1].z;
      const bool want = e.contains(inside), got = member(*r, p);
      if (want != got) {
        ++failures;
        std::string boxes_text;
        for (const auto& x : extent) { std::ostringstream os; os << " [" << x[0] << " .. " << x[1] << "]"; boxes_text += os.str(); }
        ADD_FAILURE() << "seed " << seed << ": " << to_string(op) << " of" << boxes_text << ", at " << p
                      << ": expected " << want << ", the result says " << got;
        break;
      }
    }
  }
}

// Faceted primitives under random motions: the non-regularized result validates and
// has the regularized result's volume (they differ in parts of no volume only).
TEST(LowerDim, RandomPrimitivesKeepTheRegularizedVolume) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> angle(0, 360), offset(-1.5, 1.5);
#ifdef CELLFORGE_ASAN
  constexpr int kCases = 6;
#else
  constexpr int kCases = 24;
#endif
  for (int k = 0; k < kCases; ++k) {
    const Model a = k % 2 ? sphere_model(2, 12) : cylinder_model(1.5, 3, 10);
    const Model b0 = k % 3 ? box_model({-1, -1, -1}, {1, 1, 1}) : sphere_model(1.5, 10);
    const Model b = moved(b0, shape::Transform::translate({offset(rng), offset(rng), offset(rng)}) *
                                  shape::Transform::rotate(angle(rng), {angle(rng) - 180, angle(rng) - 180, angle(rng)}));
    for (Op op : {Op::kUnion, Op::kIntersection, Op::kDifference}) {
      const boolean::Expr e = Expr::over(op, 2);
      boolean::Options o;
      auto reg = boolean::evaluate(std::vector<const Model*>{&a, &b}, e, o);
      o.keep_lower_dim = true;
      auto low = boolean::evaluate(std::vector<const Model*>{&a, &b}, e, o);
      ASSERT_TRUE(reg.ok() && low.ok()) << k;
      EXPECT_TRUE(validate(low->model).empty()) << "case " << k << " " << to_string(op) << ": "
                                                << to_string(validate(low->model));
      const double vr = reg->model.num_faces() ? shape::mass_properties(reg->model).volume : 0;
      const double vl = low->model.num_faces() ? shape::mass_properties(low->model).volume : 0;
      EXPECT_NEAR(vl, vr, 1e-9 * (1 + vr)) << "case " << k << " " << to_string(op);
      EXPECT_EQ(low->model.num_volumes(), reg->model.num_volumes()) << "case " << k << " " << to_string(op);
    }
  }
}

// The marks of elements not in the set, on the model as kInSetProperty, so that a
// file or the database keeps them.
std::array<std::size_t, 3> marked_out(const Model& m) {
  std::array<std::size_t, 3> out{};
  const auto f = find_property<FaceProperty<std::uint8_t>>(m, boolean::kInSetProperty);
  const auto e = find_property<EdgeProperty<std::uint8_t>>(m, boolean::kInSetProperty);
  const auto v = find_property<VertexProperty<std::uint8_t>>(m, boolean::kInSetProperty);
  EXPECT_TRUE(f.is_valid() && e.is_valid() && v.is_valid());
  if (!f.is_valid() || !e.is_valid() || !v.is_valid()) return out;
  for (FaceId x : m.faces()) out[0] += f[x] == 0;
  for (EdgeId x : m.edges()) out[1] += e[x] == 0;
  for (VertexId x : m.vertices()) out[2] += v[x] == 0;
  return out;
}

TEST(LowerDim, MarksAreKeptInFilesAndTheDatabase) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({0, 0, 1}, {1, 1, 2});
  const Parts d = sets(Op::kDifference, {&a, &b});
  const Model& m = d.result.model;
  const auto f = find_property<FaceProperty<std::uint8_t>>(m, boolean::kInSetProperty);
  ASSERT_TRUE(f.is_valid());
  for (FaceId x : m.faces()) EXPECT_EQ(f[x] != 0, d.result.face_in[x.value]);
  const std::array<std::size_t, 3> expected{1, 4, 4};  // B's face, its edges and corners
  EXPECT_EQ(marked_out(m), expected);
  // A result with every element in the set carries no marks.
  const Parts u = sets(Op::kUnion, {&a, &b});
  EXPECT_FALSE(find_property<FaceProperty<std::uint8_t>>(u.result.model, boolean::kInSetProperty).is_valid());

  const auto dir = std::filesystem::temp_directory_path() / "cellforge_lower_dim_marks";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // The native JSON, written by the command line.
  const std::string pa = (dir / "a.json").string(), pb = (dir / "b.json").string();
  const std::string out = (dir / "d.json").string();
  ASSERT_TRUE(io::write_file(a, pa).ok());
  ASSERT_TRUE(io::write_file(b, pb).ok());
  const CliRun r = run_cli("bool difference " + pa + " " + pb + " -o " + out + " --keep-lower-dim");
  ASSERT_EQ(r.status, 0) << r.out;
  Model back;
  ASSERT_TRUE(io::read_file(back, out).ok());
  EXPECT_EQ(marked_out(back), expected);
  // The model database.
  auto store = open_store((dir / "marks.db").string());
  ASSERT_TRUE(store.ok()) << store.error().message;
  ASSERT_TRUE((*store)->put("d", m).ok());
  auto loaded = (*store)->get("d");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(marked_out(*loaded), expected);
  std::filesystem::remove_all(dir);
}

TEST(LowerDim, CommandLine) {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_lower_dim_cli";
  std::filesystem::create_directories(dir);
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
  const std::string out = (dir / "c.json").string();
  ASSERT_TRUE(io::write_file(box_model({0, 0, 0}, {1, 1, 1}), a).ok());
  ASSERT_TRUE(io::write_file(box_model({0, 0, 1}, {1, 1, 2}), b).ok());
  const CliRun r = run_cli("bool intersection " + a + " " + b + " -o " + out + " --keep-lower-dim --report json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 1,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"sheet_faces\": 1,"), std::string::npos) << r.out;
  Model back;
  ASSERT_TRUE(io::read_file(back, out).ok());
  EXPECT_EQ(back.num_faces(), 1u);
  EXPECT_EQ(back.num_volumes(), 0u);
  const CliRun cells = run_cli("bool union " + a + " " + b + " -o " + out + " --cells");
  ASSERT_EQ(cells.status, 0) << cells.out;
  EXPECT_NE(cells.out.find("2 volumes"), std::string::npos) << cells.out;
  EXPECT_NE(cells.out.find("1 inner faces"), std::string::npos) << cells.out;
  const CliRun regular = run_cli("bool intersection " + a + " " + b + " -o " + out);
  EXPECT_NE(regular.out.find("0 faces"), std::string::npos) << regular.out;
}

}  // namespace
}  // namespace cellforge::testing
