// Shape2D helpers (area, points, bounding box, transforms of 2D shapes) and resize():
// OpenSCAD's scale factors, auto axes, and the errors of a flat object.
#include "cellforge/shape/shape2d.h"

#include <gtest/gtest.h>

#include "cellforge/geom/polygon.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/resize.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

Shape2D framed() {  // a 4 x 2 rectangle with a 1 x 1 hole, and a unit square beside it
  Shape2D s;
  s.regions.push_back(*polygon({{0, 0}, {4, 0}, {4, 2}, {0, 2}}, {{{1, 0.5}, {2, 0.5}, {2, 1.5}, {1, 1.5}}}));
  s.regions.push_back(*rectangle({1, 1}));
  s.regions[1].loops[0] = {{5, 0}, {6, 0}, {6, 1}, {5, 1}};
  return s;
}

TEST(Shape2D, AreaPointsAndBox) {
  const Shape2D s = framed();
  EXPECT_DOUBLE_EQ(area(s), 8 - 1 + 1);
  EXPECT_EQ(points_of(s).size(), 12u);
  const Box2 b = bounding_box(s);
  EXPECT_EQ(b.min, (Vec2{0, 0}));
  EXPECT_EQ(b.max, (Vec2{6, 2}));
  EXPECT_EQ(bounding_box(Shape2D{}).max, (Vec2{0, 0}));
}

TEST(Shape2D, TransformsKeepOrientationThroughMirrors) {
  const Shape2D s = framed();
  auto m = transformed(s, Transform::mirror({1, 0, 0}));
  ASSERT_OK(m);
  EXPECT_DOUBLE_EQ(area(*m), 8);
  EXPECT_GT(area_sign(m->regions[0].loops[0]), 0);
  EXPECT_LT(area_sign(m->regions[0].loops[1]), 0);
  auto r = transformed(s, Transform::rotate(90, {0, 0, 1}) * Transform::scale({2, 3, 1}));
  ASSERT_OK(r);
  EXPECT_NEAR(area(*r), 8 * 6, 1e-12);
  EXPECT_FALSE(transformed(s, Transform::scale({1, 0, 1})).ok());
}

TEST(Resize, FactorsAsOpenScadComputesThem) {
  auto f = resize_factors({2, 4, 8}, {.size = {4, 0, 0}});
  ASSERT_OK(f);
  EXPECT_EQ(*f, (Vec3{2, 1, 1}));
  // auto on y: the factor of the axis with the largest new size; x's 4 and z's 4
  // tie and the first (x, factor 2) wins, although z's factor is 0.5.
  f = resize_factors({2, 4, 8}, {.size = {4, 0, 4}, .autosize = {false, true, false}});
  ASSERT_OK(f);
  EXPECT_EQ(*f, (Vec3{2, 2, 0.5}));
  f = resize_factors({2, 4, 8}, {.size = {1, 0, 4}, .autosize = {false, true, false}});
  ASSERT_OK(f);
  EXPECT_EQ(*f, (Vec3{0.5, 0.5, 0.5}));
  f = resize_factors({2, 4, 8}, {.size = {0, 0, 0}, .autosize = {true, true, true}});
  ASSERT_OK(f);
  EXPECT_EQ(*f, (Vec3{1, 1, 1}));
  auto flat = resize_factors({2, 0, 8}, {.size = {1, 1, 1}});
  ASSERT_FALSE(flat.ok());
  EXPECT_NE(flat.error().message.find("flat along y"), std::string::npos);
  EXPECT_FALSE(resize_factors({1, 1, 1}, {.size = {-1, 0, 0}}).ok());
}

TEST(Resize, GroupsAndShapes) {
  Model m;
  auto g = make_cube(m, {.size = {2, 4, 8}, .center = true});
  ASSERT_OK(g);
  auto r = resized(m, *g, {.size = {1, 0, 0}, .autosize = {false, true, true}});
  ASSERT_OK(r);
  const MassProperties p = mass_properties(m, *r);
  EXPECT_EQ(p.bbox_min, (Vec3{-0.5, -1, -2}));
  EXPECT_EQ(p.bbox_max, (Vec3{0.5, 1, 2}));
  EXPECT_DOUBLE_EQ(p.volume, 8);
  auto s = resized(framed(), {.size = {12, 0, 0}, .autosize = {false, true, false}});
  ASSERT_OK(s);
  EXPECT_DOUBLE_EQ(area(*s), 8 * 4);
  EXPECT_EQ(bounding_box(*s).max, (Vec2{12, 4}));
}

}  // namespace
}  // namespace cellforge::shape
