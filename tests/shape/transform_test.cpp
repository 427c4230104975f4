// Transforms: exact OpenSCAD rotations, mirror keeps faces outward and volume
// positive, non-uniform scale, surfaces follow similarities, singular matrices fail.
#include "cellforge/shape/transform.h"

#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "shape/shape_test_util.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

using testing::rel_err;

std::set<std::tuple<double, double, double>> positions(const Model& m, GroupId g) {
  std::set<std::tuple<double, double, double>> out;
  for (VertexId v : m.vertices()) {
    if (m.group_of(v) == g) out.insert({m.position(v).x, m.position(v).y, m.position(v).z});
  }
  return out;
}

TEST(Transform, TranslateMovesCentroidKeepsVolume) {
  Model m;
  auto cube = make_cube(m, {.size = {1, 2, 3}});
  ASSERT_OK(cube);
  auto moved = transformed(m, *cube, Transform::translate({10, -5, 1}));
  ASSERT_OK(moved);
  EXPECT_VALID(m);
  const MassProperties p = mass_properties(m, *moved);
  EXPECT_DOUBLE_EQ(p.volume, 6);
  EXPECT_DOUBLE_EQ(p.centroid.x, 10.5);
  EXPECT_DOUBLE_EQ(p.centroid.y, -4);
  EXPECT_DOUBLE_EQ(p.centroid.z, 2.5);
  EXPECT_EQ(m.attribute(*moved, "kind"), "cube");
  EXPECT_FALSE(m.attribute(*moved, "transform").empty());
}

TEST(Transform, RotateXyzIsExactAtRightAngles) {
  Model m;
  auto cube = make_cube(m, {.size = {1, 2, 3}});
  ASSERT_OK(cube);
  // OpenSCAD's rotate([90, 0, 0]) takes (x, y, z) to (x, -z, y).
  auto r = transformed(m, *cube, Transform::rotate_xyz({90, 0, 0}));
  ASSERT_OK(r);
  EXPECT_VALID(m);
  const auto pos = positions(m, *r);
  EXPECT_TRUE(pos.count({1, -3, 2}));
  EXPECT_TRUE(pos.count({0, 0, 0}));
  // Rz * Ry * Rx: rotate([90, 90, 0]) sends x to -z... checked on a single point.
  const Vec3 p = Transform::rotate_xyz({90, 90, 0}).apply({1, 0, 0});
  EXPECT_EQ(p, (Vec3{0, 0, -1}));
  const Vec3 q = Transform::rotate_xyz({0, 0, 90}).apply({1, 0, 0});
  EXPECT_EQ(q, (Vec3{0, 1, 0}));
  // rotate(a, v) about z equals rotate([0, 0, a]).
  const Vec3 s = Transform::rotate(30, {0, 0, 1}).apply({1, 2, 3});
  const Vec3 t = Transform::rotate_xyz({0, 0, 30}).apply({1, 2, 3});
  EXPECT_NEAR(s.x, t.x, 1e-15);
  EXPECT_NEAR(s.y, t.y, 1e-15);
  EXPECT_EQ(s.z, 3);
}

TEST(Transform, MirrorKeepsFacesOutward) {
  Model m;
  auto cyl = make_cylinder(m, {.h = 2, .r1 = 1, .r2 = 0.5, .faceting = {.fn = 9}});
  ASSERT_OK(cyl);
  const double v = mass_properties(m, *cyl).volume;
  for (Vec3 n : {Vec3{1, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 1, 1}}) {
    auto mirrored = transformed(m, *cyl, Transform::mirror(n));
    ASSERT_OK(mirrored);
    EXPECT_VALID(m);
    EXPECT_LT(Transform::mirror(n).determinant(), 0);
    const MassProperties p = mass_properties(m, *mirrored);
    EXPECT_GT(p.volume, 0);
    EXPECT_LE(rel_err(p.volume, v), 1e-12);
  }
  auto flipped = transformed(m, *cyl, Transform::scale({1, 1, -1}));
  ASSERT_OK(flipped);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *flipped).volume, v), 1e-12);
  EXPECT_EQ(mass_properties(m, *flipped).bbox_min.z, -2);
}

TEST(Transform, ScaleMultipliesVolumeByDeterminant) {
  Model m;
  auto s = make_sphere(m, {.r = 1, .faceting = {.fn = 12}});
  ASSERT_OK(s);
  const double v = mass_properties(m, *s).volume;
  auto e = transformed(m, *s, Transform::scale({2, 3, 0.5}));
  ASSERT_OK(e);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *e).volume, 3 * v), 1e-12);
}

TEST(Transform, SurfacesFollowSimilaritiesOnly) {
  Model m;
  auto cyl = make_cylinder(m, {.h = 2, .r1 = 1, .r2 = 1, .faceting = {.fn = 6}});
  ASSERT_OK(cyl);
  auto big = transformed(m, *cyl, Transform::translate({0, 0, 5}) * Transform::scale({2, 2, 2}));
  ASSERT_OK(big);
  auto squashed = transformed(m, *cyl, Transform::scale({2, 1, 1}));
  ASSERT_OK(squashed);
  std::size_t big_faces = 0, squashed_faces = 0;
  for (FaceId f : m.faces()) {
    if (m.surface_of(f) == kInvalidIndex) continue;
    if (m.group_of(f) == *big) {
      ++big_faces;
      const Surface& s = m.surface(m.surface_of(f));
      EXPECT_EQ(s.kind, "cylinder");
      EXPECT_EQ(s.radius, 2);
      EXPECT_EQ(s.height, 4);
      EXPECT_EQ(s.center, (Vec3{0, 0, 5}));
    }
    squashed_faces += m.group_of(f) == *squashed;
  }
  EXPECT_EQ(big_faces, 6u);
  EXPECT_EQ(squashed_faces, 0u);
}

TEST(Transform, AffineMatrixAndComposition) {
  auto t = Transform::from_matrix({{{0, -1, 0, 1}, {1, 0, 0, 2}, {0, 0, 1, 3}, {0, 0, 0, 1}}});
  ASSERT_OK(t);
  EXPECT_EQ(t->apply({1, 0, 0}), (Vec3{1, 3, 3}));
  const Transform both = Transform::translate({1, 0, 0}) * Transform::rotate_xyz({0, 0, 90});
  EXPECT_EQ(both.apply({1, 0, 0}), (Vec3{1, 1, 0}));  // rotate first, then translate
  EXPECT_FALSE(
      Transform::from_matrix({{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 1, 1}}}).ok());
}

TEST(Transform, SingularMatrixIsAnError) {
  Model m;
  auto cube = make_cube(m);
  ASSERT_OK(cube);
  const std::size_t groups = m.num_groups();
  auto r = transformed(m, *cube, Transform::scale({1, 0, 1}));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("singular"), std::string::npos) << r.error().message;
  EXPECT_EQ(m.num_groups(), groups);
}

}  // namespace
}  // namespace cellforge::shape
