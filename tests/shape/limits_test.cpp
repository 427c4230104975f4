// Issue 18's `make` parameters in the shape layer: every result finite (and within
// the predicates' range), fn/fa/fs that are NaN, infinite or negative refused, and
// resolutions above the vertex limit refused before anything is allocated.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cellforge/shape/primitives.h"
#include "cellforge/shape/sweep.h"
#include "shape_test_util.h"

namespace cellforge::shape {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class R>
std::string error_of(const R& r) {
  EXPECT_FALSE(r.ok());
  return r.ok() ? std::string() : r.error().message;
}

TEST(ShapeLimits, OverflowingSizesAreRefusedAndLeaveTheModelEmpty) {
  Model m;
  const std::string cube = error_of(make_cube(m, {.size = {1e200, 1e200, 1e200}}));
  EXPECT_NE(cube.find("beyond the coordinate limit of 2^120"), std::string::npos) << cube;
  const std::string sphere = error_of(make_sphere(m, {.r = 1e300}));
  EXPECT_NE(sphere.find("beyond the coordinate limit"), std::string::npos) << sphere;
  EXPECT_FALSE(make_cylinder(m, {.h = 1e300, .r1 = 1, .r2 = 1}).ok());
  EXPECT_FALSE(make_polyhedron(m, {.points = {{0, 0, 0}, {1e37, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                   .faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}})
                   .ok());
  EXPECT_TRUE(m.empty());
  // At the limit itself a cube is made, and its volume is finite.
  auto g = make_cube(m, {.size = {0x1p120, 0x1p120, 0x1p120}});
  ASSERT_TRUE(g.ok()) << g.error().message;
}

TEST(ShapeLimits, FacetingThatIsNotFiniteOrIsNegativeIsRefused) {
  for (double bad : {kNaN, kInf, -kInf, -1.0}) {
    for (int which = 0; which < 3; ++which) {
      Faceting f;
      (which == 0 ? f.fn : which == 1 ? f.fa : f.fs) = bad;
      Model m;
      const std::string e = error_of(make_sphere(m, {.r = 1, .faceting = f}));
      const std::string name = which == 0 ? "fn" : which == 1 ? "fa" : "fs";
      EXPECT_NE(e.find(name + " must be finite and >= 0"), std::string::npos) << e;
      EXPECT_FALSE(make_cylinder(m, {.faceting = f}).ok());
      EXPECT_FALSE(make_torus(m, {.faceting = f}).ok());
      EXPECT_FALSE(circle(1, f).ok());
      EXPECT_FALSE(linear_extrude(m, *rectangle({1, 1}, false), {.twist = 90, .faceting = f}).ok());
      EXPECT_FALSE(rotate_extrude(m, *rectangle({1, 1}, false), {.faceting = f}).ok());
      EXPECT_TRUE(m.empty());
    }
  }
  // fn = 0 with fa and fs is OpenSCAD's default rule and stays allowed.
  Model m;
  EXPECT_TRUE(make_sphere(m, {.r = 1, .faceting = {.fn = 0}}).ok());
}

TEST(ShapeLimits, ResolutionsAboveTheLimitAreRefusedBeforeAllocating) {
  Model m;
  // A sphere of fn=100000 would be 100000 x 50000 vertices.
  const std::string sphere = error_of(make_sphere(m, {.r = 1, .faceting = {.fn = 100000}}));
  EXPECT_NE(sphere.find("a sphere of 100000 segments would make 5000000000 vertices, more than "
                        "the limit of 10000000"),
            std::string::npos)
      << sphere;
  const std::string prism = error_of(make_regular_prism(m, {.sides = 1000000000}));
  EXPECT_NE(prism.find("prism sides=1000000000 would make 2000000000 vertices"), std::string::npos)
      << prism;
  // fn = 1e300 saturates instead of overflowing an int, and is refused.
  EXPECT_FALSE(make_cylinder(m, {.faceting = {.fn = 1e300}}).ok());
  EXPECT_FALSE(circle(1, {.fn = 1e12}).ok());
  EXPECT_FALSE(linear_extrude(m, *rectangle({1, 1}, false), {.slices = 100000000}).ok());
  EXPECT_FALSE(
      linear_extrude(m, *rectangle({1, 1}, false), {.twist = 1e300, .faceting = {.fn = 10}}).ok());
  EXPECT_FALSE(rotate_extrude(m, *rectangle({1, 1}, false), {.faceting = {.fn = 1e9}}).ok());
  EXPECT_TRUE(m.empty());
  // The limit is an option: a lower one refuses what the default allows, a higher
  // one allows what the default refuses.
  EXPECT_FALSE(make_sphere(m, {.r = 1, .faceting = {.fn = 100, .max_vertices = 4999}}).ok());
  auto g = make_sphere(m, {.r = 1, .faceting = {.fn = 100, .max_vertices = 5000}});
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(testing::counts(m, *g).v, 5000);
  EXPECT_FALSE(make_regular_prism(m, {.sides = 600, .max_vertices = 1000}).ok());
  EXPECT_TRUE(make_regular_prism(m, {.sides = 600, .max_vertices = 1200}).ok());
}

TEST(ShapeLimits, SaturatedCount) {
  EXPECT_EQ(saturated_count(1e300), std::numeric_limits<int>::max());
  EXPECT_EQ(saturated_count(kNaN), 0);
  EXPECT_EQ(saturated_count(-5), 0);
  EXPECT_EQ(saturated_count(7.9), 7);
  EXPECT_EQ(fragments(1, {.fn = 1e300}), std::numeric_limits<int>::max());
}

}  // namespace
}  // namespace cellforge::shape
