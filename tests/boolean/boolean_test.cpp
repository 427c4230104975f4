// Boolean operations on solids: named degenerate cases with hand-checked counts and
// closed-form volumes (boolean/boolean.h).
#include "cellforge/boolean/boolean.h"

#include <gtest/gtest.h>

#include "boolean/boolean_test_util.h"

namespace cellforge::testing {
namespace {

using boolean::Op;

TEST(Boolean, UnionOfOverlappingBoxes) {
  const Model a = box_model({0, 0, 0}, {2, 2, 2});
  const Model b = box_model({1, 1, 1}, {3, 3, 3});
  const BoolCase r = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(r.volume, 8 + 8 - 1, 1e-12);
  EXPECT_EQ(r.faces, 12u);
  EXPECT_EQ(r.vertices, 20u);
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
}

TEST(Boolean, BoxesSharingAFaceUniteIntoOneBox) {
  const Model a = box_model({0, 0, 0}, {1, 1, 1});
  const Model b = box_model({0, 0, 1}, {1, 1, 2});
  const BoolCase r = run(Op::kUnion, {&a, &b});
  EXPECT_NEAR(r.volume, 2, 1e-12);
  EXPECT_EQ(r.faces, 6u);
  EXPECT_EQ(r.edges, 12u);
  EXPECT_EQ(r.vertices, 8u);
}

}  // namespace
}  // namespace cellforge::testing
