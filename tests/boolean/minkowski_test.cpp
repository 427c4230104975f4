// Minkowski sums of solids (boolean/minkowski.h): boxes, a box and a faceted sphere
// (against the mixed-volume formula for a box plus a convex body, with the sphere's
// volume, widths and projected areas measured separately), a non-convex prism and a
// cube, cells of a model summed pairwise, and the unsupported case.
#include "cellforge/boolean/minkowski.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cellforge/boolean/boolean.h"
#include "cellforge/boolean/ops2d.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/transform.h"
#include "cellforge/topo/builder.h"
#include "support/checks.h"

namespace cellforge::boolean {
namespace {

// An axis-parallel box from `at` to `at + size` (one cell).
Model cube(Vec3 size, Vec3 at = {}) {
  Model out;
  auto q = shape::make_polyhedron(
      out, {.points = {at, at + Vec3{size.x, 0, 0}, at + Vec3{size.x, size.y, 0}, at + Vec3{0, size.y, 0},
                       at + Vec3{0, 0, size.z}, at + Vec3{size.x, 0, size.z}, at + size,
                       at + Vec3{0, size.y, size.z}},
            .faces = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}}});
  EXPECT_TRUE(q.ok()) << q.error().message;
  return out;
}

double volume(const Model& m) { return shape::mass_properties(m).volume; }

TEST(Minkowski, TwoBoxesMakeABoxOfSummedSizes) {
  const Model a = cube({1, 2, 3}), b = cube({2, 2, 2}, {-1, 0, 1});
  const Model* ops[] = {&a, &b};
  auto r = minkowski(ops);
  ASSERT_OK(r);
  EXPECT_VALID(*r);
  EXPECT_EQ(r->num_faces(), 6u);
  EXPECT_EQ(r->num_vertices(), 8u);
  const shape::MassProperties p = shape::mass_properties(*r);
  EXPECT_DOUBLE_EQ(p.volume, 3 * 4 * 5);
  EXPECT_EQ(p.bbox_min, (Vec3{-1, 0, 1}));
  EXPECT_EQ(p.bbox_max, (Vec3{2, 4, 6}));
}

// V(box(a, b, c) + K) = V(K) + a A_x + b A_y + c A_z + ab w_z + ac w_y + bc w_x + abc,
// where A_i is the area of K's projection along axis i and w_i its width along i (the
// box as the sum of three segments, each adding length x projected area).
TEST(Minkowski, BoxPlusSphereMatchesTheMixedVolumeFormula) {
  Model sphere;
  ASSERT_OK(shape::make_sphere(sphere, {.r = 1, .faceting = {.fn = 12}}));
  const double a = 2, b = 3, c = 1.5;
  const Model box = cube({a, b, c});
  const Model* ops[] = {&box, &sphere};
  auto r = minkowski(ops);
  ASSERT_OK(r);
  EXPECT_VALID(*r);
  const shape::MassProperties k = shape::mass_properties(sphere);
  const Vec3 w = k.bbox_max - k.bbox_min;
  double area_along[3];
  for (int axis = 0; axis < 3; ++axis) {
    const Model& turned = sphere;
    Model only;  // the sphere turned so that `axis` points along z, alone
    const shape::Transform t = axis == 0   ? shape::Transform::rotate(90, {0, 1, 0})
                               : axis == 1 ? shape::Transform::rotate(90, {1, 0, 0})
                                           : shape::Transform::identity();
    MeshInput mesh;
    mesh.volumes = 1;
    for (VertexId v : turned.vertices()) mesh.positions.push_back(t.apply(turned.position(v)));
    for (FaceId f : turned.faces()) {
      MeshFace mf;
      mf.back = 0;
      std::vector<std::uint32_t> loop;
      for (VertexId v : turned.loop_vertices(turned.outer_loop(f))) loop.push_back(v.value);
      mf.loops.push_back(loop);
      mesh.faces.push_back(mf);
    }
    ASSERT_OK(build_mesh(only, mesh));
    auto shadow = projection(only);
    ASSERT_OK(shadow);
    area_along[axis] = shape::area(*shadow);
  }
  const double want = k.volume + a * area_along[0] + b * area_along[1] + c * area_along[2] +
                      a * b * w.z + a * c * w.y + b * c * w.x + a * b * c;
  EXPECT_NEAR(volume(*r), want, 1e-9 * want);
  // And within the bounds of the exact rounded box: faceting only loses volume.
  const double pi = std::numbers::pi;
  EXPECT_LT(volume(*r), a * b * c + 2 * (a * b + b * c + c * a) + pi * (a + b + c) + 4 * pi / 3);
}

TEST(Minkowski, NonConvexPrismPlusCubeIsTheGrownPrism) {
  // An L-shaped prism (one non-convex cell) plus a cube of side s: the L grown by s
  // in x and y, extruded over h + s.
  Model l;
  auto region = shape::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  ASSERT_OK(region);
  ASSERT_OK(shape::make_prism(l, *region, 1));
  const double s = 0.5, h = 1;
  const Model c = cube({s, s, s});
  EXPECT_FALSE(is_convex_cell(l, *l.volumes().begin()));
  EXPECT_TRUE(is_convex_cell(c, *c.volumes().begin()));
  for (bool swapped : {false, true}) {
    const Model* ops[] = {swapped ? &c : &l, swapped ? &l : &c};
    auto r = minkowski(ops);
    ASSERT_OK(r);
    EXPECT_VALID(*r);
    EXPECT_EQ(r->num_volumes(), 1u);
    EXPECT_NEAR(volume(*r), (2 * (2 + s) * (1 + s) - (1 + s) * (1 + s)) * (h + s), 1e-12);
  }
}

TEST(Minkowski, FacetedSphereIsConvexAndRoundsANonConvexPrism) {
  Model sphere;
  ASSERT_OK(shape::make_sphere(sphere, {.r = 0.25, .faceting = {.fn = 8}}));
  EXPECT_TRUE(is_convex_cell(sphere, *sphere.volumes().begin()));
  Model l;
  ASSERT_OK(shape::make_prism(l, *shape::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}), 1));
  const Model* ops[] = {&l, &sphere};
  auto r = minkowski(ops);
  ASSERT_OK(r);
  EXPECT_VALID(*r);
  EXPECT_EQ(r->num_volumes(), 1u);
  // Independently: L is the union of two boxes, each box + sphere is convex (the
  // hull of vertex sums), and the sum distributes over the union.
  const Model b1 = cube({2, 1, 1}), b2 = cube({1, 2, 1});
  const Model* s1[] = {&b1, &sphere};
  const Model* s2[] = {&b2, &sphere};
  auto m1 = minkowski(s1);
  auto m2 = minkowski(s2);
  ASSERT_OK(m1);
  ASSERT_OK(m2);
  const Model* both[] = {&*m1, &*m2};
  auto u = apply(Op::kUnion, both);
  ASSERT_OK(u);
  EXPECT_NEAR(volume(*r), volume(u->model), 1e-12 * volume(u->model));
  const shape::MassProperties p = shape::mass_properties(*r), k = shape::mass_properties(sphere);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(p.bbox_min[i], k.bbox_min[i], 1e-15);
    EXPECT_NEAR(p.bbox_max[i], (Vec3{2, 2, 1} + k.bbox_max)[i], 1e-15);
  }
}

TEST(Minkowski, CellsOfAModelAreSummedPairwise) {
  Model two;  // two unit cubes 2 apart along x, as two cells
  ASSERT_OK(shape::make_polyhedron(
      two, {.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
                       {3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}, {3, 0, 1}, {4, 0, 1}, {4, 1, 1}, {3, 1, 1}},
            .faces = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0},
                      {8, 9, 10, 11}, {12, 15, 14, 13}, {8, 12, 13, 9}, {9, 13, 14, 10},
                      {10, 14, 15, 11}, {11, 15, 12, 8}}}));
  const Model grow = cube({1.5, 1, 1});
  const Model* ops[] = {&two, &grow};
  auto r = minkowski(ops);
  ASSERT_OK(r);
  EXPECT_VALID(*r);
  // [0, 2.5] and [3, 5.5] along x: still apart.
  EXPECT_NEAR(volume(*r), 2 * 2.5 * 2 * 2, 1e-12);
  const Model wider = cube({2.5, 1, 1});
  const Model* ops2[] = {&two, &wider};
  auto joined = minkowski(ops2);
  ASSERT_OK(joined);
  EXPECT_VALID(*joined);
  EXPECT_EQ(joined->num_volumes(), 1u);  // [0, 3.5] and [3, 6.5] overlap
  EXPECT_NEAR(volume(*joined), 6.5 * 2 * 2, 1e-12);
}

TEST(Minkowski, TwoNonConvexSolidsAreUnsupportedAndEmptyIsAnError) {
  Model l;
  ASSERT_OK(shape::make_prism(l, *shape::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}), 1));
  const Model* ops[] = {&l, &l};
  auto r = minkowski(ops);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(r.error().message.find("operand 0"), std::string::npos);
  const Model empty;
  const Model* bad[] = {&l, &empty};
  auto e = minkowski(bad);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("operand 1"), std::string::npos);
}

}  // namespace
}  // namespace cellforge::boolean
