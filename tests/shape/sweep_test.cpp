// Sweeps: twist / scale / partial-angle volumes against closed forms, profiles on the
// axis, the dimension cases (polyline -> sheet, point -> wire), and errors.
#include "cellforge/shape/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shape/shape_test_util.h"
#include "cellforge/shape/mass.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

using testing::counts;
using testing::ngon_area;
using testing::rel_err;

constexpr double kPi = std::numbers::pi;

TEST(LinearExtrude, PlainRegionIsAPrism) {
  auto c = circle(2, {.fn = 12});
  ASSERT_OK(c);
  Model m;
  auto g = linear_extrude(m, *c, {.height = 3, .center = true});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(m.attribute(*g, "slices"), "1");
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, ngon_area(12, 2) * 3), 1e-12);
  EXPECT_EQ(mass_properties(m, *g).bbox_min.z, -1.5);
}

TEST(LinearExtrude, UniformScaleIsAFrustum) {
  auto sq = rectangle({2, 3}, true);
  ASSERT_OK(sq);
  Model m;
  auto g = linear_extrude(m, *sq, {.height = 4, .scale_x = 0.5, .scale_y = 0.5});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *g).f, 6);  // the sides stay quads
  // V = h A (1 + s + s^2) / 3.
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, 4 * 6 * (1 + 0.5 + 0.25) / 3), 1e-12);
}

TEST(LinearExtrude, ScaleZeroClosesInAnApex) {
  auto sq = rectangle({2, 2}, true);
  ASSERT_OK(sq);
  Model m;
  auto g = linear_extrude(m, *sq, {.height = 3, .scale_x = 0, .scale_y = 0});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *g).v, 5);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, 4.0 * 3 / 3), 1e-12);
}

TEST(LinearExtrude, NonUniformScaleOfARectangle) {
  // An axis-aligned rectangle scaled per axis: the cross-section is
  // w h (1 + a t)(1 + b t), so V = w h H (1 + (a + b) / 2 + a b / 3).
  auto sq = rectangle({2, 3}, true);
  ASSERT_OK(sq);
  Model m;
  const double sx = 2, sy = 0.5, a = sx - 1, b = sy - 1;
  auto g = linear_extrude(m, *sq, {.height = 5, .scale_x = sx, .scale_y = sy, .slices = 3});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, 6 * 5 * (1 + (a + b) / 2 + a * b / 3)), 1e-12);
}

// The twisted extrusion of a regular n-gon (circumradius R) turning by d per slice,
// each side quad split along its shorter diagonal, is a stack of prismatoids:
// V = slices * (h / 6) (A + 4 M + A), with M the area of the mid-section, the 2n-gon
// of midpoints of the lateral edges: radii R cos(d / 2) and R cos((2 pi / n - d) / 2)
// alternating at angle steps pi / n, so M = n R cos(d/2) R cos((2pi/n - d)/2) sin(pi/n).
double twisted_ngon_volume(int n, double r, double height, double twist_deg, int slices) {
  const double d = twist_deg / slices * kPi / 180, hs = height / slices;
  const double mid =
      n * r * std::cos(d / 2) * r * std::cos((2 * kPi / n - d) / 2) * std::sin(kPi / n);
  return slices * hs / 6 * (2 * ngon_area(n, r) + 4 * mid);
}

TEST(LinearExtrude, TwistVolumeMatchesPrismatoidFormula) {
  for (int n : {3, 4, 6}) {
    for (double twist : {30.0, 90.0, -45.0}) {
      auto p = regular_polygon(n, 2);
      ASSERT_OK(p);
      Model m;
      auto g = linear_extrude(m, *p, {.height = 10, .twist = twist, .slices = 5});
      ASSERT_OK(g);
      EXPECT_VALID(m);
      EXPECT_EQ(counts(m, *g).f, 2 + 2 * n * 5);  // sides split into triangles
      EXPECT_LE(rel_err(mass_properties(m, *g).volume,
                        twisted_ngon_volume(n, 2, 10, std::fabs(twist), 5)),
                1e-12)
          << n << " " << twist;
    }
  }
}

TEST(LinearExtrude, TwistTurnsClockwise) {
  auto sq = rectangle({2, 2});
  ASSERT_OK(sq);
  Model m;
  auto g = linear_extrude(m, *sq, {.height = 1, .twist = 90, .slices = 1});
  ASSERT_OK(g);
  // (2, 0) turned clockwise by 90 degrees is (0, -2): exact with degree trigonometry.
  bool found = false;
  for (VertexId v : m.vertices()) found = found || m.position(v) == Vec3{0, -2, 1};
  EXPECT_TRUE(found);
}

// OpenSCAD 2021+ gives linear_extrude(height=5, twist=90) square(2); the volume
// 22.0438 (4 slices by its $fa/$fs rule). The corner (0, 0) lies on the twist axis, so
// the side quads at it have diagonals of equal length: OpenSCAD's tie rule decides,
// and mirrored (twist = -90) the square gives the same volume.
TEST(LinearExtrude, TwistedSquareOnTheAxisMatchesOpenScad) {
  auto sq = rectangle({2, 2});
  ASSERT_OK(sq);
  for (double twist : {90.0, -90.0}) {
    SCOPED_TRACE(twist);
    Model m;
    auto g = linear_extrude(m, *sq, {.height = 5, .twist = twist});
    ASSERT_OK(g);
    EXPECT_VALID(m);
    EXPECT_EQ(m.num_vertices(), 20u);  // 4 corners x 5 rings
    EXPECT_NEAR(mass_properties(m).volume, 22.0438, 5e-5);
  }
}

// A ring (outer circle, inner hole) twisted both ways: the tie rule flips for holes,
// so the volume is the same for either direction of twist.
TEST(LinearExtrude, TwistedRingIsTheSameEitherWay) {
  auto ring = polygon({{2, 0}, {0, 2}, {-2, 0}, {0, -2}}, {{{1, 0}, {0, -1}, {-1, 0}, {0, 1}}});
  ASSERT_OK(ring);
  double volume[2];
  for (int k = 0; k < 2; ++k) {
    Model m;
    ASSERT_OK(linear_extrude(m, *ring, {.height = 4, .twist = k ? -60.0 : 60.0, .slices = 3}));
    EXPECT_VALID(m);
    volume[k] = mass_properties(m).volume;
  }
  EXPECT_NEAR(volume[0], volume[1], 1e-12);
}

TEST(LinearExtrude, OpenScadSliceCounts) {
  auto c = circle(10, {.fn = 20});
  ASSERT_OK(c);
  // Twist with $fn: ceil(twist / 360 * fn).
  EXPECT_EQ(extrude_slices(*c, {.height = 10, .twist = 180, .faceting = {.fn = 20}}), 10);
  // Twist with $fa / $fs: max(min(ceil(twist / fa), ceil(helix / fs)), ceil(twist / 120)).
  EXPECT_EQ(extrude_slices(*c, {.height = 10, .twist = 360}), 30);
  EXPECT_EQ(extrude_slices(*c, {.height = 10}), 1);
  EXPECT_EQ(extrude_slices(*c, {.height = 10, .slices = 7}), 7);
  // Non-uniform scale without twist: ceil(sqrt(delta^2 + h^2) / fs), delta = 10 * 1.
  EXPECT_EQ(extrude_slices(*c, {.height = 10, .scale_x = 2, .scale_y = 1}),
            static_cast<int>(std::ceil(std::sqrt(200.0) / 2)));
}

TEST(LinearExtrude, RegionWithHole) {
  auto ring = polygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}}, {{{-1, -1}, {-1, 1}, {1, 1}, {1, -1}}});
  ASSERT_OK(ring);
  Model m;
  auto g = linear_extrude(m, *ring, {.height = 2, .twist = 20, .slices = 2});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_GT(mass_properties(m, *g).volume, 0);
  auto plain = linear_extrude(m, *ring, {.height = 2});
  ASSERT_OK(plain);
  EXPECT_LE(rel_err(mass_properties(m, *plain).volume, 32 * 2), 1e-12);
}

TEST(LinearExtrude, PolylineGivesASheetAndPointAWire) {
  Model m;
  auto sheet = linear_extrude(m, Polyline{{{0, 0}, {1, 0}, {1, 1}}}, {.height = 2});
  ASSERT_OK(sheet);
  EXPECT_VALID(m);
  const MassProperties p = mass_properties(m, *sheet);
  EXPECT_FALSE(p.solid);
  EXPECT_DOUBLE_EQ(p.area, 4);
  EXPECT_EQ(counts(m, *sheet).f, 2);
  auto wire = linear_extrude(m, Vec2{1, 0}, {.height = 2, .twist = 90, .slices = 4});
  ASSERT_OK(wire);
  EXPECT_VALID(m);
  const auto c = counts(m, *wire);
  EXPECT_EQ(c.v, 5);
  EXPECT_EQ(c.e, 4);
  EXPECT_EQ(c.f, 0);
}

TEST(LinearExtrude, Errors) {
  auto sq = rectangle({1, 1});
  ASSERT_OK(sq);
  Model m;
  EXPECT_FALSE(linear_extrude(m, *sq, {.height = 0}).ok());
  EXPECT_FALSE(linear_extrude(m, *sq, {.scale_x = 0, .scale_y = 1}).ok());
  EXPECT_FALSE(linear_extrude(m, *sq, {.scale_x = -1}).ok());
  EXPECT_FALSE(linear_extrude(m, Region{{{{0, 0}, {1, 1}, {1, 0}, {0, 1}}}}).ok());  // bow tie
  EXPECT_TRUE(m.empty());
}

// V = m sin(d) * integral of x dA over the profile (d = angle / m).
TEST(RotateExtrude, PartialAngleVolume) {
  auto sq = rectangle({1, 1});
  ASSERT_OK(sq);
  for (auto& p : sq->loops[0]) p.x += 1;  // [1, 2] x [0, 1]: integral of x dA = 1.5
  Model m;
  auto g = rotate_extrude(m, *sq, {.angle = 90, .faceting = {.fn = 40}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(m.attribute(*g, "segments"), "10");
  const double d = kPi / 2 / 10;
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, 10 * std::sin(d) * 1.5), 1e-12);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 4 * 11);
  EXPECT_EQ(c.f, 4 * 10 + 2);  // sides and two end caps
  EXPECT_EQ(c.euler(), 2);
}

TEST(RotateExtrude, NegativeAngleAndNegativeProfile) {
  auto sq = rectangle({1, 1});
  ASSERT_OK(sq);
  for (auto& p : sq->loops[0]) p.x += 1;
  Region mirrored = *sq;
  for (auto& p : mirrored.loops[0]) p.x = -p.x;
  std::reverse(mirrored.loops[0].begin(), mirrored.loops[0].end());
  const double want = 10 * std::sin(kPi / 2 / 10) * 1.5;
  for (const Region* r : {&*sq, &mirrored}) {
    for (double angle : {90.0, -90.0}) {
      Model m;
      auto g = rotate_extrude(m, *r, {.angle = angle, .faceting = {.fn = 40}});
      ASSERT_OK(g);
      EXPECT_VALID(m);
      EXPECT_LE(rel_err(mass_properties(m, *g).volume, want), 1e-12) << angle;
    }
  }
}

TEST(RotateExtrude, ProfileTouchingTheAxisCollapses) {
  auto sq = rectangle({1, 1});  // [0, 1] x [0, 1]: one edge on the axis
  ASSERT_OK(sq);
  Model m;
  auto full = rotate_extrude(m, *sq, {.faceting = {.fn = 16}});
  ASSERT_OK(full);
  EXPECT_VALID(m);
  auto c = counts(m, *full);
  EXPECT_EQ(c.v, 2 + 2 * 16);  // two axis vertices, two rings
  EXPECT_EQ(c.f, 3 * 16);      // top and bottom fans of triangles, 16 side quads
  EXPECT_EQ(c.euler(), 2);
  // Integral of x dA = 0.5: V = 16 sin(2 pi / 16) / 2, the 16-gon prism.
  EXPECT_LE(rel_err(mass_properties(m, *full).volume, ngon_area(16, 1)), 1e-12);

  auto part = rotate_extrude(m, *sq, {.angle = 90, .faceting = {.fn = 16}});
  ASSERT_OK(part);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *part).euler(), 2);
  EXPECT_LE(rel_err(mass_properties(m, *part).volume, 4 * std::sin(kPi / 8) * 0.5), 1e-12);

  // A triangle with one vertex on the axis: a disk and a cone touching at that point,
  // which becomes two coincident vertices so that the shell stays manifold.
  auto tri = polygon({{0, 0}, {2, 0}, {1, 1}});
  ASSERT_OK(tri);
  auto pinched = rotate_extrude(m, *tri, {.faceting = {.fn = 12}});
  ASSERT_OK(pinched);
  EXPECT_VALID(m);
  c = counts(m, *pinched);
  EXPECT_EQ(c.v, 2 + 2 * 12);
  EXPECT_EQ(c.euler(), 2);
  // Integral of x dA over the triangle: area 1, centroid x = 1.
  EXPECT_LE(rel_err(mass_properties(m, *pinched).volume, 12 * std::sin(kPi / 6)), 1e-12);
  auto wedge = rotate_extrude(m, *tri, {.angle = 60, .faceting = {.fn = 12}});
  ASSERT_OK(wedge);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *wedge).v, 1 + 2 * 3);  // partial: one vertex on the axis
}

TEST(RotateExtrude, CrossingTheAxisIsAnError) {
  auto sq = rectangle({2, 1}, true);
  ASSERT_OK(sq);
  Model m;
  auto g = rotate_extrude(m, *sq);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.error().message.find("crosses the axis"), std::string::npos) << g.error().message;
  EXPECT_TRUE(m.empty());
}

TEST(RotateExtrude, HoleMakesACavity) {
  auto annulus = polygon({{2, -2}, {6, -2}, {6, 2}, {2, 2}}, {{{3, -1}, {3, 1}, {5, 1}, {5, -1}}});
  ASSERT_OK(annulus);
  Model m;
  auto g = rotate_extrude(m, *annulus, {.faceting = {.fn = 20}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  // Integral of x dA: 16 * 4 - 4 * 4 = 48.
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, 20 * std::sin(2 * kPi / 20) * 48), 1e-12);
  auto half = rotate_extrude(m, *annulus, {.angle = 180, .faceting = {.fn = 20}});
  ASSERT_OK(half);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *half).volume, 10 * std::sin(kPi / 10) * 48), 1e-12);
}

TEST(RotateExtrude, PolylineGivesASheetAndPointAWireCircle) {
  Model m;
  auto sheet = rotate_extrude(m, Polyline{{{0, 1}, {1, 1}, {1, 0}}}, {.faceting = {.fn = 8}});
  ASSERT_OK(sheet);
  EXPECT_VALID(m);
  EXPECT_FALSE(mass_properties(m, *sheet).solid);
  EXPECT_EQ(counts(m, *sheet).f, 16);  // a fan of 8 triangles and 8 quads
  auto circle_wire = rotate_extrude(m, Vec2{2, 1}, {.faceting = {.fn = 8}});
  ASSERT_OK(circle_wire);
  EXPECT_VALID(m);
  auto c = counts(m, *circle_wire);
  EXPECT_EQ(c.v, 8);
  EXPECT_EQ(c.e, 8);
  auto arc = rotate_extrude(m, Vec2{2, 1}, {.angle = 90, .faceting = {.fn = 8}});
  ASSERT_OK(arc);
  c = counts(m, *arc);
  EXPECT_EQ(c.v, 3);
  EXPECT_EQ(c.e, 2);
  auto point = rotate_extrude(m, Vec2{0, 1});
  ASSERT_OK(point);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *point).v, 1);
}

TEST(RotateExtrude, AngleErrors) {
  auto sq = rectangle({1, 1});
  ASSERT_OK(sq);
  Model m;
  EXPECT_FALSE(rotate_extrude(m, *sq, {.angle = 0}).ok());
  EXPECT_FALSE(rotate_extrude(m, *sq, {.angle = 400}).ok());
  EXPECT_TRUE(m.empty());
}

}  // namespace
}  // namespace cellforge::shape
