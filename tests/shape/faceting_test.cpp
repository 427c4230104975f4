// Segment counts against OpenSCAD's get_fragments_from_r, and degree trigonometry.
#include "cellforge/shape/faceting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cellforge::shape {
namespace {

struct Case {
  double fn, fa, fs, r;
  int expected;
};

// Expected values worked out by hand from OpenSCAD's rule:
// r < GRID_FINE -> 3; fn > 0 -> max(trunc(fn), 3); else ceil(max(min(360/fa, 2 pi r/fs), 5)).
TEST(Faceting, TableMatchesOpenScadRule) {
  const Case cases[] = {
      {0, 12, 2, 1, 5},           // 2 pi / 2 = 3.14 -> at least 5
      {0, 12, 2, 10, 30},         // min(30, 31.4) = 30
      {0, 12, 2, 5, 16},          // 2 pi 5 / 2 = 15.7 -> 16
      {0, 12, 2, 0.005, 5},       // r below 0.01, above GRID_FINE: the rule's minimum 5
      {0, 12, 2, 0.0000001, 3},   // below GRID_FINE
      {32, 12, 2, 0.0000001, 3},  // GRID_FINE wins over fn
      {32, 12, 2, 10, 32},       {2, 12, 2, 10, 3},  // fn < 3 -> 3
      {1, 12, 2, 10, 3},                             //
      {0.5, 12, 2, 10, 3},                           // 0 < fn < 3 -> 3
      {7.9, 12, 2, 10, 7},                           // fractional fn truncates
      {-4, 12, 2, 10, 30},                           // negative fn is ignored
      {0, 1, 0.1, 10, 360},                          // min(360, 628.3) = 360
      {0, 0.001, 0.001, 1, 629},  // fa, fs clamp to 0.01: min(36000, 628.3) -> 629
      {0, 30, 2, 100, 12},       {0, 12, 0.5, 1, 13},  // 2 pi / 0.5 = 12.57 -> 13
  };
  for (const Case& c : cases) {
    EXPECT_EQ(fragments(c.r, Faceting{.fn = c.fn, .fa = c.fa, .fs = c.fs}), c.expected)
        << "fn=" << c.fn << " fa=" << c.fa << " fs=" << c.fs << " r=" << c.r;
  }
}

TEST(Faceting, GridFineBoundary) {
  EXPECT_EQ(fragments(kGridFine, {}), 5);
  EXPECT_EQ(fragments(std::nextafter(kGridFine, 0.0), {}), 3);
  EXPECT_EQ(fragments(std::nextafter(kGridFine, 0.0), {.fn = 100}), 3);
}

TEST(Faceting, ArcFragments) {
  EXPECT_EQ(arc_fragments(10, 360, {}), 30);
  EXPECT_EQ(arc_fragments(10, 90, {}), 8);  // ceil(30 / 4 = 7.5)
  EXPECT_EQ(arc_fragments(10, -90, {}), 8);
  EXPECT_EQ(arc_fragments(10, 1, {}), 1);           // at least 1
  EXPECT_EQ(arc_fragments(10, 180, {.fn = 7}), 4);  // ceil(3.5)
}

TEST(Faceting, DegreeTrigIsExactAtSpecialAngles) {
  EXPECT_EQ(sin_degrees(0), 0.0);
  EXPECT_EQ(sin_degrees(30), 0.5);
  EXPECT_EQ(sin_degrees(90), 1.0);
  EXPECT_EQ(sin_degrees(150), 0.5);
  EXPECT_EQ(sin_degrees(180), 0.0);
  EXPECT_EQ(sin_degrees(270), -1.0);
  EXPECT_EQ(sin_degrees(-90), -1.0);
  EXPECT_EQ(sin_degrees(720 + 30), 0.5);
  EXPECT_EQ(cos_degrees(0), 1.0);
  EXPECT_EQ(cos_degrees(60), 0.5);
  EXPECT_EQ(cos_degrees(90), 0.0);
  EXPECT_EQ(cos_degrees(120), -0.5);
  EXPECT_EQ(cos_degrees(180), -1.0);
  EXPECT_EQ(cos_degrees(270), 0.0);
  EXPECT_EQ(cos_degrees(45), std::numbers::sqrt2 / 2);
  EXPECT_EQ(sin_degrees(45), cos_degrees(45));
  for (double a = -720; a <= 720; a += 7.3) {
    EXPECT_NEAR(sin_degrees(a), std::sin(a * std::numbers::pi / 180), 1e-13) << a;
    EXPECT_NEAR(cos_degrees(a), std::cos(a * std::numbers::pi / 180), 1e-13) << a;
  }
}

TEST(Faceting, FormatNumberRoundTrips) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(3), "3");
  EXPECT_EQ(std::stod(format_number(1.0 / 3)), 1.0 / 3);
}

}  // namespace
}  // namespace cellforge::shape
