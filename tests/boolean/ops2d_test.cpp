// 2D operations (boolean/ops2d.h): Booleans of rectangles and faceted circles with
// closed-form areas; seeded random cases checked by the area identities
// area(A u B) + area(A n B) = area(A) + area(B) and area(A - B) = area(A) - area(A n B)
// and, independently, by exact point membership (the result's winding number at
// random points against the expression on the operands) and by agreement with the
// route through the 3D arrangement (planar.h's lifted_boolean); the degenerate cases
// (shared and overlapping edges, vertices on edges, touching at a point, identical
// operands, loops of no area) with hand-checked areas and loop counts; offset, 2D
// Minkowski sums and projections with closed-form areas.
#include "cellforge/boolean/ops2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/region.h"
#include "cellforge/shape/transform.h"
#include "boolean/planar.h"
#include "support/checks.h"

namespace cellforge::boolean {
namespace {

using shape::Region;
using shape::Shape2D;

constexpr double kPi = std::numbers::pi;

double ngon_area(int n, double r) { return n / 2.0 * r * r * std::sin(2 * kPi / n); }

Shape2D rect(double x0, double y0, double x1, double y1) {
  return shape::shape_of(Region{{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
}

Shape2D circle(double r, int n, Vec2 c = {}) {
  Region g = *shape::circle(r, {.fn = static_cast<double>(n)});
  for (Vec2& p : g.loops[0]) p = {p.x + c.x, p.y + c.y};
  return shape::shape_of(std::move(g));
}

Shape2D op(Op o, std::vector<Shape2D> shapes) {
  auto r = apply_2d(o, shapes);
  EXPECT_TRUE(r.ok()) << r.error().message;
  return r.ok() ? *r : Shape2D{};
}

// Inside the shape (exactly): an odd number of its loops wind about p. The loops of
// a valid result nest, so the sum of winding numbers is 0 or 1.
int membership(const Shape2D& s, Vec2 p) {
  int w = 0;
  for (const Region& r : s.regions)
    for (const auto& loop : r.loops) w += winding_number(loop, p);
  return w;
}

// Every result region is a valid polygon with holes (polygon() accepts it) and its
// loops run outer counterclockwise, holes clockwise.
void expect_valid_regions(const Shape2D& s) {
  for (const Region& r : s.regions) {
    ASSERT_FALSE(r.loops.empty());
    EXPECT_GT(area_sign(r.loops[0]), 0);
    for (std::size_t i = 1; i < r.loops.size(); ++i) EXPECT_LT(area_sign(r.loops[i]), 0);
    std::vector<std::vector<Vec2>> holes(r.loops.begin() + 1, r.loops.end());
    auto checked = shape::polygon(r.loops[0], holes);
    EXPECT_TRUE(checked.ok()) << checked.error().message;
  }
}

// Outer loops counterclockwise, holes clockwise, and no two edges of the shape cross or
// overlap (they may meet at a vertex).
void expect_oriented_and_not_crossing(const Shape2D& s) {
  std::vector<std::pair<Vec2, Vec2>> es;
  for (const Region& r : s.regions) {
    ASSERT_FALSE(r.loops.empty());
    EXPECT_GT(area_sign(r.loops[0]), 0);
    for (std::size_t i = 1; i < r.loops.size(); ++i) EXPECT_LT(area_sign(r.loops[i]), 0);
    for (const auto& l : r.loops)
      for (std::size_t i = 0; i < l.size(); ++i) es.push_back({l[i], l[(i + 1) % l.size()]});
  }
  for (std::size_t i = 0; i < es.size(); ++i) {
    for (std::size_t j = i + 1; j < es.size(); ++j) {
      const auto [a, b] = es[i];
      const auto [c, d] = es[j];
      const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
      const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
      EXPECT_FALSE(o1 * o2 < 0 && o3 * o4 < 0) << "edges cross";
      if (o1 == 0 && o2 == 0) {  // collinear: at most an end in common
        const bool inside = (point_on_segment(a, b, c) && !(c == a) && !(c == b)) ||
                            (point_on_segment(a, b, d) && !(d == a) && !(d == b)) ||
                            (point_on_segment(c, d, a) && !(a == c) && !(a == d)) ||
                            (a == c && b == d) || (a == d && b == c);
        EXPECT_FALSE(inside) << "edges overlap";
      } else if ((o1 == 0 && point_on_segment(a, b, c) && !(c == a) && !(c == b)) ||
                 (o2 == 0 && point_on_segment(a, b, d) && !(d == a) && !(d == b)) ||
                 (o3 == 0 && point_on_segment(c, d, a) && !(a == c) && !(a == d)) ||
                 (o4 == 0 && point_on_segment(c, d, b) && !(b == c) && !(b == d))) {
        ADD_FAILURE() << "a vertex lies inside another edge";
      }
    }
  }
}

TEST(Boolean2D, OverlappingRectangles) {
  const Shape2D a = rect(0, 0, 4, 2), b = rect(2, 1, 6, 5);
  EXPECT_DOUBLE_EQ(area(op(Op::kUnion, {a, b})), 8 + 16 - 2);
  EXPECT_DOUBLE_EQ(area(op(Op::kIntersection, {a, b})), 2);
  const Shape2D d = op(Op::kDifference, {a, b});
  EXPECT_DOUBLE_EQ(area(d), 6);
  ASSERT_EQ(d.regions.size(), 1u);
  EXPECT_EQ(d.regions[0].loops[0].size(), 6u);  // an L: the collinear points are gone
  expect_valid_regions(d);
}

TEST(Boolean2D, DifferenceMakesAHoleAndUnionOfDisjointKeepsTwoRegions) {
  const Shape2D d = op(Op::kDifference, {rect(0, 0, 10, 10), rect(2, 3, 5, 7)});
  ASSERT_EQ(d.regions.size(), 1u);
  ASSERT_EQ(d.regions[0].loops.size(), 2u);
  EXPECT_DOUBLE_EQ(area(d), 100 - 12);
  expect_valid_regions(d);
  // An island inside the hole is a region of its own.
  const Shape2D island = op(Op::kUnion, {d, rect(3, 4, 4, 5)});
  ASSERT_EQ(island.regions.size(), 2u);
  EXPECT_DOUBLE_EQ(area(island), 89);
  expect_valid_regions(island);
  const Shape2D two = op(Op::kUnion, {rect(0, 0, 1, 1), rect(3, 0, 4, 1)});
  EXPECT_EQ(two.regions.size(), 2u);
  EXPECT_DOUBLE_EQ(area(two), 2);
}

TEST(Boolean2D, TouchingAtAPointStaysTwoSimpleRegions) {
  const Shape2D s = op(Op::kUnion, {rect(0, 0, 1, 1), rect(1, 1, 2, 2)});
  EXPECT_EQ(s.regions.size(), 2u);
  EXPECT_DOUBLE_EQ(area(s), 2);
  // A square minus a diamond touching its sides at their midpoints: four corners.
  const Shape2D diamond = shape::shape_of(Region{{{{1, 0}, {2, 1}, {1, 2}, {0, 1}}}});
  const Shape2D corners = op(Op::kDifference, {rect(0, 0, 2, 2), diamond});
  EXPECT_DOUBLE_EQ(area(corners), 2);
  if (corners.regions.size() == 4) {
    for (const Region& r : corners.regions) EXPECT_DOUBLE_EQ(shape::area(r), 0.5);
  } else {  // or the square with the diamond as a hole touching it
    ASSERT_EQ(corners.regions.size(), 1u);
    EXPECT_EQ(corners.regions[0].loops.size(), 2u);
  }
}

TEST(Boolean2D, SquareAndCircleQuarterClosedForm) {
  // A 24-gon at the origin has vertices on both axes, so the square [0, 3]^2 holds
  // exactly a quarter of it.
  const Shape2D c = circle(2, 24), s = rect(0, 0, 3, 3);
  const double q = ngon_area(24, 2) / 4;
  EXPECT_NEAR(area(op(Op::kIntersection, {c, s})), q, 1e-12);
  EXPECT_NEAR(area(op(Op::kUnion, {c, s})), 9 + 3 * q, 1e-12);
  EXPECT_NEAR(area(op(Op::kDifference, {s, c})), 9 - q, 1e-12);
  const Shape2D ring = op(Op::kDifference, {circle(2, 24), circle(1, 24)});
  ASSERT_EQ(ring.regions.size(), 1u);
  EXPECT_EQ(ring.regions[0].loops.size(), 2u);
  EXPECT_NEAR(area(ring), ngon_area(24, 2) - ngon_area(24, 1), 1e-12);
}

TEST(Boolean2D, NaryExpressionsAndEmptyOperands) {
  const std::vector<Shape2D> ops = {rect(0, 0, 3, 3), rect(1, 1, 4, 4), rect(2, 2, 5, 5), {}};
  EXPECT_DOUBLE_EQ(area(*apply_2d(Op::kUnion, ops)), 27 - 4 - 4 + 0);
  EXPECT_DOUBLE_EQ(area(*apply_2d(Op::kIntersection, ops)), 0);
  EXPECT_TRUE(apply_2d(Op::kIntersection, ops)->empty());
  EXPECT_DOUBLE_EQ(area(*apply_2d(Op::kDifference, ops)), 9 - 4);
  const Expr e =
      Expr::op(Op::kIntersection, {Expr::op(Op::kUnion, {Expr::of(0), Expr::of(2)}), Expr::of(1)});
  EXPECT_DOUBLE_EQ(area(*evaluate_2d(ops, e)), 4 + 4 - 1);
  EXPECT_FALSE(evaluate_2d(ops, Expr::of(7)).ok());
  EXPECT_TRUE(apply_2d(Op::kUnion, std::vector<Shape2D>{})->empty());
}

TEST(Boolean2D, BadRegionIsAnError) {
  const Shape2D bad = shape::shape_of(Region{{{{0, 0}, {1, 0}}}});
  auto r = apply_2d(Op::kUnion, std::vector<Shape2D>{rect(0, 0, 1, 1), bad});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("operand 1 region 0"), std::string::npos) << r.error().message;
  const Shape2D nan = shape::shape_of(Region{{{{0, 0}, {1, NAN}, {0, 1}}}});
  auto n = apply_2d(Op::kUnion, std::vector<Shape2D>{rect(0, 0, 1, 1), rect(3, 3, 4, 4), nan});
  ASSERT_FALSE(n.ok());
  EXPECT_NE(n.error().message.find("operand 2 region 0 outer loop vertex 1 is not finite"),
            std::string::npos)
      << n.error().message;
}

// ---------------------------------------------------------------- degenerate cases

std::size_t loop_count(const Shape2D& s) {
  std::size_t n = 0;
  for (const Region& r : s.regions) n += r.loops.size();
  return n;
}

Shape2D poly(std::vector<Vec2> loop) { return shape::shape_of(Region{{std::move(loop)}}); }

TEST(Boolean2DDegenerate, SharedEdgeUnionIsOneRectangle) {
  const Shape2D u = op(Op::kUnion, {rect(0, 0, 1, 1), rect(1, 0, 2, 1)});
  ASSERT_EQ(u.regions.size(), 1u);
  ASSERT_EQ(loop_count(u), 1u);
  EXPECT_EQ(u.regions[0].loops[0].size(), 4u);  // the shared edge and its ends are gone
  EXPECT_EQ(area(u), 2);
  EXPECT_TRUE(op(Op::kIntersection, {rect(0, 0, 1, 1), rect(1, 0, 2, 1)}).empty());
  const Shape2D d = op(Op::kDifference, {rect(0, 0, 2, 1), rect(1, 0, 2, 1)});
  ASSERT_EQ(d.regions.size(), 1u);
  EXPECT_EQ(d.regions[0].loops[0].size(), 4u);
  EXPECT_EQ(area(d), 1);
}

TEST(Boolean2DDegenerate, CollinearOverlappingEdges) {
  // Overlapping along the bottom and top edges.
  const Shape2D u = op(Op::kUnion, {rect(0, 0, 2, 1), rect(1, 0, 3, 1)});
  ASSERT_EQ(u.regions.size(), 1u);
  EXPECT_EQ(u.regions[0].loops[0].size(), 4u);
  EXPECT_EQ(area(u), 3);
  EXPECT_EQ(area(op(Op::kIntersection, {rect(0, 0, 2, 1), rect(1, 0, 3, 1)})), 1);
  // Sharing a piece of an edge from the outside: one region with 8 corners.
  const Shape2D side = op(Op::kUnion, {rect(0, 0, 2, 1), rect(1, -1, 3, 0)});
  ASSERT_EQ(side.regions.size(), 1u);
  ASSERT_EQ(loop_count(side), 1u);
  EXPECT_EQ(side.regions[0].loops[0].size(), 8u);
  EXPECT_EQ(area(side), 4);
  EXPECT_TRUE(op(Op::kIntersection, {rect(0, 0, 2, 1), rect(1, -1, 3, 0)}).empty());
  // A rectangle inside another, sharing three sides: the difference is a strip.
  const Shape2D strip = op(Op::kDifference, {rect(0, 0, 4, 2), rect(0, 0, 3, 2)});
  ASSERT_EQ(strip.regions.size(), 1u);
  EXPECT_EQ(strip.regions[0].loops[0].size(), 4u);
  EXPECT_EQ(area(strip), 2);
}

TEST(Boolean2DDegenerate, VertexOnAnEdge) {
  // A triangle whose apex lies on the square's top edge, from above and from below.
  const Shape2D sq = rect(0, 0, 2, 2);
  const Shape2D above = poly({{0, 3}, {1, 2}, {2, 3}});
  const Shape2D u = op(Op::kUnion, {sq, above});
  EXPECT_EQ(area(u), 4 + 1);
  ASSERT_EQ(u.regions.size(), 2u);  // they touch at the apex only
  EXPECT_TRUE(op(Op::kIntersection, {sq, above}).empty());
  // A triangle from the bottom edge to a point of the top edge cuts the square into
  // two pieces that touch at that point.
  const Shape2D below = poly({{0.5, 0}, {1.5, 0}, {1, 2}});
  const Shape2D d = op(Op::kDifference, {sq, below});
  ASSERT_EQ(d.regions.size(), 2u);
  for (const Region& r : d.regions) EXPECT_EQ(shape::area(r), 1.5);
  expect_valid_regions(d);
  expect_valid_regions(op(Op::kDifference, {sq, poly({{0.5, -1}, {1.5, -1}, {1, 1}})}));
}

TEST(Boolean2DDegenerate, HoleTouchingTheOuterLoopAtAPoint) {
  const Shape2D d = op(Op::kDifference, {rect(0, 0, 4, 4), poly({{2, 0}, {3, 1}, {1, 1}})});
  ASSERT_EQ(d.regions.size(), 1u);
  ASSERT_EQ(d.regions[0].loops.size(), 2u);
  EXPECT_GT(area_sign(d.regions[0].loops[0]), 0);
  EXPECT_LT(area_sign(d.regions[0].loops[1]), 0);
  EXPECT_EQ(area(d), 16 - 1);
}

TEST(Boolean2DDegenerate, IdenticalOperands) {
  const Shape2D c = circle(3, 17, {0.25, -0.5});
  const Shape2D u = op(Op::kUnion, {c, c, c});
  ASSERT_EQ(u.regions.size(), 1u);
  EXPECT_EQ(u.regions[0].loops[0], c.regions[0].loops[0]);  // vertex for vertex
  const Shape2D n = op(Op::kIntersection, {c, c});
  EXPECT_EQ(n.regions[0].loops[0], c.regions[0].loops[0]);
  EXPECT_TRUE(op(Op::kDifference, {c, c}).empty());
  // A shape given twice as overlapping regions of one operand is their union.
  const Shape2D twice{{c.regions[0], c.regions[0]}};
  EXPECT_EQ(area(op(Op::kUnion, {twice, rect(100, 100, 101, 101)})), area(c) + 1);
}

TEST(Boolean2DDegenerate, LoopsOfNoAreaAddNothing) {
  const Shape2D flat = poly({{0, 0}, {1, 0}, {2, 0}});
  const Shape2D back = poly({{0, 1}, {2, 1}, {1, 1}});  // doubles back on itself
  const Shape2D u = op(Op::kUnion, {rect(0, 0, 2, 2), flat, back});
  ASSERT_EQ(u.regions.size(), 1u);
  EXPECT_EQ(u.regions[0].loops[0].size(), 4u);
  EXPECT_EQ(area(u), 4);
  EXPECT_TRUE(op(Op::kIntersection, {rect(0, 0, 2, 2), back}).empty());
  EXPECT_TRUE(op(Op::kUnion, {flat, back}).empty());
  // A vertex repeated at once (a projected face's vertical edge) makes no edge.
  const Shape2D repeated = poly({{0, 0}, {2, 0}, {2, 0}, {2, 2}, {0, 2}});
  EXPECT_EQ(area(op(Op::kUnion, {repeated, rect(1, 1, 3, 3)})), 7);
}

TEST(Boolean2DDegenerate, ThreeSegmentsThroughOnePoint) {
  // A diamond, the square with its corners on the diamond's edges, and a triangle
  // whose edge runs along the square's diagonal: at (1, -1) and (-1, 1) an input
  // vertex, two crossings and four segments are one point.
  const Shape2D a = poly({{0, -2}, {2, 0}, {0, 2}, {-2, 0}});
  const Shape2D b = rect(-1, -1, 1, 1);
  const Shape2D c = poly({{-3, 3}, {3, -3}, {3, 3}});
  const Shape2D n = op(Op::kIntersection, {a, b});
  EXPECT_EQ(area(n), 4);
  EXPECT_EQ(n.regions[0].loops[0].size(), 4u);
  const Shape2D half = op(Op::kIntersection, {a, c});
  EXPECT_EQ(area(half), 4);
  EXPECT_EQ(half.regions[0].loops[0].size(), 4u);
  const Shape2D tri = op(Op::kIntersection, {a, b, c});
  ASSERT_EQ(tri.regions.size(), 1u);
  EXPECT_EQ(tri.regions[0].loops[0].size(), 3u);
  EXPECT_EQ(area(tri), 2);
  const Shape2D u = op(Op::kUnion, {a, b, c});
  EXPECT_EQ(loop_count(u), 1u);
  expect_valid_regions(u);
  EXPECT_EQ(area(u), 8 + 18 - 4);
}

enum class Kind { kFree, kGridRectangles, kGridPolygons };

// A random operand: one to three pieces as overlapping regions of one shape (it stands
// for their union). kFree: regular n-gons, rotated and scaled, anywhere; kGridRectangles:
// rectangles on a coarse integer grid (every point of the arrangement is a double);
// kGridPolygons: simple star-shaped polygons with vertices snapped to a grid of 1/2
// (shared edges and vertices, vertices on edges, crossings off the grid).
Shape2D random_shape(std::mt19937& rng, Kind kind) {
  std::uniform_real_distribution<double> u(0, 1);
  const int parts = 1 + static_cast<int>(rng() % 3);
  Shape2D s;
  for (int k = 0; k < parts; ++k) {
    if (kind == Kind::kGridRectangles) {
      const double x = std::floor(u(rng) * 6), y = std::floor(u(rng) * 6);
      const double w = 1 + std::floor(u(rng) * 4), h = 1 + std::floor(u(rng) * 4);
      s.regions.push_back(rect(x, y, x + w, y + h).regions[0]);
    } else if (kind == Kind::kGridPolygons) {
      const int n = 3 + static_cast<int>(rng() % 7);
      const Vec2 c{std::floor(u(rng) * 12) / 2, std::floor(u(rng) * 12) / 2};
      std::vector<double> angles;
      for (int i = 0; i < n; ++i) angles.push_back(2 * kPi * u(rng));
      std::sort(angles.begin(), angles.end());
      std::vector<Vec2> loop;
      for (double a : angles) {
        const double r = 0.5 + 3 * u(rng);
        const Vec2 p{std::round(2 * (c.x + r * std::cos(a))) / 2,
                     std::round(2 * (c.y + r * std::sin(a))) / 2};
        if (loop.empty() || !(loop.back() == p)) loop.push_back(p);
      }
      while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
      auto g = loop.size() >= 3 ? shape::polygon(loop) : Result<Region>(Error{});
      s.regions.push_back(g.ok() ? *g : rect(c.x, c.y, c.x + 1, c.y + 0.5).regions[0]);
    } else {
      const int n = 3 + static_cast<int>(rng() % 6);
      const double r = 0.5 + 2 * u(rng), a = 360 * u(rng);
      Region g = *shape::regular_polygon(n, r);
      const Vec2 c{6 * u(rng), 6 * u(rng)};
      for (Vec2& p : g.loops[0])
        p = {c.x + p.x * shape::cos_degrees(a) - p.y * shape::sin_degrees(a),
             c.y + p.x * shape::sin_degrees(a) + p.y * shape::cos_degrees(a)};
      s.regions.push_back(std::move(g));
    }
  }
  return s;
}

// Inside an operand given as overlapping simple regions (outer counterclockwise, holes
// clockwise), exactly and without the code under test: inside some region. p must lie
// on no loop.
bool inside_operand(const Shape2D& s, Vec2 p) {
  for (const Region& r : s.regions) {
    int w = 0;
    for (const auto& loop : r.loops) w += winding_number(loop, p);
    if (w > 0) return true;
  }
  return false;
}

bool on_some_loop(const std::vector<const Shape2D*>& shapes, Vec2 p) {
  for (const Shape2D* s : shapes)
    for (const Region& r : s->regions)
      for (const auto& loop : r.loops)
        for (std::size_t i = 0; i < loop.size(); ++i)
          if (point_on_segment(loop[i], loop[(i + 1) % loop.size()], p)) return true;
  return false;
}

// The operation with the rounding check's count added to `crossings`.
Shape2D counted(Op o, const Shape2D& a, const Shape2D& b, std::size_t& crossings) {
  const std::vector<Shape2D> ab = {a, b};
  auto r = evaluate_2d_counted(ab, Expr::over(o, 2));
  EXPECT_TRUE(r.ok()) << r.error().message;
  if (!r.ok()) return {};
  crossings += r->rounding_crossings;
  return r->shape;
}

// The union of an operand's regions, through the planar arrangement.
Shape2D united(const Shape2D& s) {
  const Shape2D one[] = {s};
  auto r = planar_boolean(one, Expr::of(0));
  EXPECT_TRUE(r.ok()) << r.error().message;
  return r.ok() ? r->shape : Shape2D{};
}

void check_identities(Kind kind, unsigned first_seed, int cases) {
  if (const char* only = std::getenv("CELLFORGE_OPS2D_SEED"))
    first_seed = static_cast<unsigned>(std::atol(only));
  int rounded = 0, lifted = 0;
  for (int i = 0; i < cases; ++i) {
    const unsigned seed = first_seed + static_cast<unsigned>(i);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    const Shape2D a = random_shape(rng, kind), b = random_shape(rng, kind);
    std::size_t crossings = 0;
    const Shape2D u = counted(Op::kUnion, a, b, crossings),
                  n = counted(Op::kIntersection, a, b, crossings),
                  d = counted(Op::kDifference, a, b, crossings);
    rounded += crossings != 0;
    const double area_a = area(united(a)), area_b = area(united(b));
    if (kind == Kind::kGridRectangles) {  // every point is a small integer: exact
      EXPECT_EQ(crossings, 0u);
      EXPECT_EQ(area(u) + area(n), area_a + area_b);
      EXPECT_EQ(area(d), area_a - area(n));
    } else {
      const double tol = 1e-12 * (area_a + area_b);
      EXPECT_NEAR(area(u) + area(n), area_a + area_b, tol);
      EXPECT_NEAR(area(d), area_a - area(n), tol);
    }
    if (crossings == 0) {  // rounding crossed nothing
      for (const Shape2D* r : {&u, &n, &d}) {
        // Regions of grid shapes touch (polygon() refuses a hole touching its outer loop).
        if (kind == Kind::kFree) expect_valid_regions(*r);
        expect_oriented_and_not_crossing(*r);
      }
    }
    // Every fiftieth case against the route through the 3D arrangement (slow).
    std::vector<Shape2D> oracle;
    if (i % 50 == 0) {
      ++lifted;
      for (Op o : {Op::kUnion, Op::kIntersection, Op::kDifference}) {
        const std::vector<Shape2D> ab = {a, b};
        auto r = lifted_boolean(ab, Expr::over(o, 2));
        ASSERT_TRUE(r.ok()) << r.error().message;
        oracle.push_back(r->shape);
      }
      EXPECT_NEAR(area(oracle[0]), area(u), 1e-12 * (area_a + area_b));
      EXPECT_NEAR(area(oracle[1]), area(n), 1e-12 * (area_a + area_b));
      EXPECT_NEAR(area(oracle[2]), area(d), 1e-12 * (area_a + area_b));
    }
    std::uniform_real_distribution<double> pu(-4, 10);
    const std::vector<const Shape2D*> all = {&a, &b, &u, &n, &d};
    for (int k = 0; k < 40; ++k) {
      const Vec2 p{pu(rng), pu(rng)};
      if (on_some_loop(all, p)) continue;
      const bool in_a = inside_operand(a, p), in_b = inside_operand(b, p);
      EXPECT_EQ(membership(u, p), in_a || in_b) << p.x << " " << p.y;
      EXPECT_EQ(membership(n, p), in_a && in_b) << p.x << " " << p.y;
      EXPECT_EQ(membership(d, p), in_a && !in_b) << p.x << " " << p.y;
      if (!oracle.empty()) {
        EXPECT_EQ(membership(oracle[0], p), membership(u, p)) << p.x << " " << p.y;
        EXPECT_EQ(membership(oracle[1], p), membership(n, p)) << p.x << " " << p.y;
        EXPECT_EQ(membership(oracle[2], p), membership(d, p)) << p.x << " " << p.y;
      }
    }
  }
  std::printf("%d cases (%d also through the 3D route), %d with crossings made by rounding\n",
              cases, lifted, rounded);
}

// CELLFORGE_OPS2D_CASES sets the number of cases of each kind (a long run);
// CELLFORGE_OPS2D_SEED runs the one case of that seed.
int cases() {
  if (std::getenv("CELLFORGE_OPS2D_SEED")) return 1;
#ifdef CELLFORGE_ASAN
  constexpr int kDefault = 200;  // the sanitized build is about 20 times slower
#else
  constexpr int kDefault = 1000;
#endif
  const char* v = std::getenv("CELLFORGE_OPS2D_CASES");
  return v ? std::atoi(v) : kDefault;
}

TEST(Boolean2D, AreaIdentitiesAndMembershipOnRandomPolygons) {
  check_identities(Kind::kFree, 1, cases());
}
TEST(Boolean2D, AreaIdentitiesAndMembershipOnGridRectangles) {
  check_identities(Kind::kGridRectangles, 1000001, cases());
}
TEST(Boolean2D, AreaIdentitiesAndMembershipOnGridPolygons) {
  check_identities(Kind::kGridPolygons, 2000001, cases());
}

// A random expression over operands 0..n-1: nested unions, intersections and
// differences of one to three children, operands repeated at times.
Expr random_expr(std::mt19937& rng, int n, int depth) {
  if (depth == 0 || rng() % 4 == 0) return Expr::of(static_cast<int>(rng() % n));
  const Op ops[] = {Op::kUnion, Op::kIntersection, Op::kDifference};
  std::vector<Expr> kids;
  const int k = 1 + static_cast<int>(rng() % 3);
  for (int i = 0; i < k; ++i) kids.push_back(random_expr(rng, n, depth - 1));
  return Expr::op(ops[rng() % 3], std::move(kids));
}

// Whether the expression is one operand under nodes of one child (evaluate_2d returns
// that operand as given).
bool single_operand(const Expr& e) {
  if (e.kind == Expr::Kind::kOperand) return true;
  return e.children.size() == 1 && single_operand(e.children[0]);
}

TEST(Boolean2D, NestedExpressionsAgreeWithMembershipOnTheOperands) {
  const int count = cases() / 5;
  for (int i = 0; i < count; ++i) {
    const unsigned seed = 3000001 + static_cast<unsigned>(i);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::vector<Shape2D> ops;
    for (int k = 0; k < 4; ++k)
      ops.push_back(random_shape(rng, k % 2 ? Kind::kGridPolygons : Kind::kFree));
    const Expr e = random_expr(rng, 4, 3);
    auto r = evaluate_2d(ops, e);
    ASSERT_TRUE(r.ok()) << r.error().message;
    if (!single_operand(e)) expect_oriented_and_not_crossing(*r);  // else returned as given
    std::uniform_real_distribution<double> pu(-4, 10);
    std::vector<const Shape2D*> all = {&*r};
    for (const Shape2D& s : ops) all.push_back(&s);
    for (int k = 0; k < 40; ++k) {
      const Vec2 p{pu(rng), pu(rng)};
      if (on_some_loop(all, p)) continue;
      std::vector<bool> in;
      for (const Shape2D& s : ops) in.push_back(inside_operand(s, p));
      EXPECT_EQ(membership(*r, p) != 0, e.contains(in)) << p.x << " " << p.y;
    }
  }
}

// ---------------------------------------------------------------- offset

TEST(Offset, RoundGrowsASquareByStripsAndAFacetedCircle) {
  for (int n : {4, 8, 12, 36}) {
    auto r = offset(rect(0, 0, 3, 3), {.amount = 0.5, .faceting = {.fn = static_cast<double>(n)}});
    ASSERT_OK(r);
    ASSERT_EQ(r->regions.size(), 1u);
    EXPECT_NEAR(area(*r), 9 + 4 * 3 * 0.5 + ngon_area(n, 0.5), 1e-12) << n;
    // Each corner: n / 4 steps, so n / 4 + 1 points.
    EXPECT_EQ(r->regions[0].loops[0].size(), static_cast<std::size_t>(n + 4)) << n;
  }
}

TEST(Offset, NegativeRoundShrinksOuterSharpAndGrowsHolesRound) {
  const Shape2D framed = op(Op::kDifference, {rect(0, 0, 10, 10), rect(4, 4, 6, 6)});
  auto r = offset(framed, {.amount = -1, .faceting = {.fn = 16}});
  ASSERT_OK(r);
  EXPECT_NEAR(area(*r), 64 - (4 + 4 * 2 * 1 + ngon_area(16, 1)), 1e-12);
  auto gone = offset(rect(0, 0, 2, 2), {.amount = -1.5});
  ASSERT_OK(gone);
  EXPECT_TRUE(gone->empty());
}

TEST(Offset, LShapeRoundHasOneOverlapAtTheReflexCorner) {
  const Shape2D l = op(Op::kUnion, {rect(0, 0, 4, 2), rect(0, 0, 2, 4)});
  const double r = 0.5;
  auto g = offset(l, {.amount = r, .faceting = {.fn = 20}});
  ASSERT_OK(g);
  // area + perimeter * r + five quarter 20-gons - the r x r square both strips cover
  EXPECT_NEAR(area(*g), 12 + 16 * r + 5 * ngon_area(20, r) / 4 - r * r, 1e-12);
}

TEST(Offset, DeltaMiterAndChamfer) {
  auto m = offset(rect(0, 0, 3, 3), {.amount = 1, .join = OffsetJoin::kMiter});
  ASSERT_OK(m);
  EXPECT_NEAR(area(*m), 25, 1e-12);
  EXPECT_EQ(m->regions[0].loops[0].size(), 4u);
  auto c = offset(rect(0, 0, 3, 3), {.amount = 1, .join = OffsetJoin::kChamfer});
  ASSERT_OK(c);
  const double leg = 1 - std::tan(kPi / 8);  // from a chamfer end to the miter corner
  EXPECT_NEAR(area(*c), 25 - 4 * leg * leg / 2, 1e-12);
  EXPECT_EQ(c->regions[0].loops[0].size(), 8u);
  auto in = offset(rect(0, 0, 3, 3), {.amount = -1, .join = OffsetJoin::kMiter});
  ASSERT_OK(in);
  EXPECT_NEAR(area(*in), 1, 1e-12);
}

TEST(Offset, TwoSquaresGrowTogether) {
  const std::vector<Shape2D> parts = {rect(0, 0, 1, 1), rect(1.5, 0, 2.5, 1)};
  const Shape2D two = op(Op::kUnion, parts);
  ASSERT_EQ(two.regions.size(), 2u);
  auto g = offset(two, {.amount = 0.5, .join = OffsetJoin::kMiter});
  ASSERT_OK(g);
  EXPECT_EQ(g->regions.size(), 1u);
  EXPECT_NEAR(area(*g), 3.5 * 2, 1e-12);
  EXPECT_FALSE(offset(two, {.amount = NAN}).ok());
}

// ---------------------------------------------------------------- minkowski

TEST(Minkowski2D, ConvexOperands) {
  const std::vector<Shape2D> squares = {rect(0, 0, 2, 1), rect(0, 0, 1, 3)};
  auto s = minkowski_2d(squares);
  ASSERT_OK(s);
  EXPECT_DOUBLE_EQ(area(*s), 3 * 4);
  const std::vector<Shape2D> rounded = {rect(0, 0, 3, 2), circle(1, 16)};
  auto r = minkowski_2d(rounded);
  ASSERT_OK(r);
  // A + B + the mixed term: widths of a 16-gon with vertices on the axes are 2 r.
  EXPECT_NEAR(area(*r), 6 + ngon_area(16, 1) + 3 * 2 + 2 * 2, 1e-12);
}

TEST(Minkowski2D, NonConvexWithConvexAndBothNonConvex) {
  const Shape2D l = op(Op::kUnion, {rect(0, 0, 2, 1), rect(0, 0, 1, 2)});
  const double c = 0.5;
  const std::vector<Shape2D> lc = {l, rect(0, 0, c, c)};
  auto a = minkowski_2d(lc);
  ASSERT_OK(a);
  EXPECT_NEAR(area(*a), 2 * (2 + c) * (1 + c) - (1 + c) * (1 + c), 1e-12);
  const std::vector<Shape2D> ll = {l, l};
  auto b = minkowski_2d(ll);
  ASSERT_OK(b);
  EXPECT_NEAR(area(*b), 13, 1e-12);  // squares of side 2 at the six pairwise sums
  expect_valid_regions(*b);
  // A frame grows inward too: a 6 x 6 frame of width 1 plus a 1 x 1 square.
  const Shape2D frame = op(Op::kDifference, {rect(0, 0, 6, 6), rect(1, 1, 5, 5)});
  const std::vector<Shape2D> fs = {frame, rect(0, 0, 1, 1)};
  auto f = minkowski_2d(fs);
  ASSERT_OK(f);
  EXPECT_NEAR(area(*f), 49 - 9, 1e-12);
}

// ---------------------------------------------------------------- projection

TEST(Projection, CutAndShadowOfACube) {
  Model m;
  auto g = shape::make_cube(m, {.size = {2, 3, 4}, .center = true});
  ASSERT_OK(g);
  auto cut = projection(m, {.cut = true});
  ASSERT_OK(cut);
  EXPECT_DOUBLE_EQ(area(*cut), 6);
  auto shadow = projection(m);
  ASSERT_OK(shadow);
  EXPECT_DOUBLE_EQ(area(*shadow), 6);
  ASSERT_EQ(shadow->regions.size(), 1u);
  EXPECT_EQ(shadow->regions[0].loops[0].size(), 4u);
}

TEST(Projection, CutOnTheBoundaryFollowsTheSolidAbove) {
  Model above;
  ASSERT_OK(shape::make_cube(above, {.size = {1, 1, 1}}));
  EXPECT_DOUBLE_EQ(area(*projection(above, {.cut = true})), 1);
  Model moved;  // a unit cube below z = 0: its top face lies on the plane
  ASSERT_OK(shape::make_polyhedron(
      moved,
      {.points = {{0, 0, -1},
                  {1, 0, -1},
                  {1, 1, -1},
                  {0, 1, -1},
                  {0, 0, 0},
                  {1, 0, 0},
                  {1, 1, 0},
                  {0, 1, 0}},
       .faces = {
           {0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}}}));
  auto none = projection(moved, {.cut = true});
  ASSERT_OK(none);
  EXPECT_TRUE(none->empty());
}

// A box of the given sizes with its lowest corner at the origin, turned and moved by t.
Model turned_box(Vec3 size, const shape::Transform& t) {
  std::vector<Vec3> p;
  for (const Vec3 c : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 1},
                       Vec3{1, 1, 1}, Vec3{0, 1, 1}})
    p.push_back(t.apply({c.x * size.x, c.y * size.y, c.z * size.z}));
  Model m;
  // Triangles: a turn rounds the corners off the quads' planes.
  auto built = shape::make_polyhedron(m, {.points = p,
                                          .faces = {{0, 1, 2}, {0, 2, 3}, {4, 7, 6}, {4, 6, 5}, {0, 4, 5}, {0, 5, 1},
                                                    {1, 5, 6}, {1, 6, 2}, {2, 6, 7}, {2, 7, 3}, {3, 7, 4}, {3, 4, 0}}});
  EXPECT_TRUE(built.ok()) << built.error().message;
  return m;
}

// projection() takes the shadow from the boundary of the faces that look up (their
// shared edges cancel; the rest winds about each point as often as the faces cover
// it). The union of those faces themselves, the route it took before, must give the
// same point set: on boxes turned every way, united or cut from one another (faces
// that overlap in the plane, overhangs, holes), and on a C whose slot floor lies
// under its top.
TEST(Projection, ShadowFromTheBoundaryIsTheUnionOfTheFacesThatLookUp) {
  const auto same = [](const Shape2D& a, const Shape2D& b) {
    return op(Op::kDifference, {a, b}).empty() && op(Op::kDifference, {b, a}).empty();
  };
  std::mt19937_64 rng(1207);
  std::uniform_real_distribution<double> angle(0, 360), place(-1.5, 1.5), size(0.5, 3);
  int holes = 0;
  for (int round = 0; round < 40; ++round) {
    std::vector<Model> boxes;
    for (int k = 0; k < 3; ++k)
      boxes.push_back(turned_box({size(rng), size(rng), size(rng)},
                                 shape::Transform::translate({place(rng), place(rng), place(rng)}) *
                                     shape::Transform::rotate_xyz({angle(rng), angle(rng), angle(rng)})));
    const Model* ops[] = {&boxes[0], &boxes[1], &boxes[2]};
    const Expr e = round % 2 == 0 ? Expr::over(Op::kUnion, 3)
                                  : Expr::op(Op::kDifference, {Expr::of(0), Expr::of(1), Expr::of(2)});
    auto r = evaluate(ops, e);
    ASSERT_OK(r);
    auto from_boundary = shadow(r->model, false);
    auto by_faces = shadow(r->model, true);
    ASSERT_OK(from_boundary);
    ASSERT_OK(by_faces);
    EXPECT_TRUE(same(*from_boundary, *by_faces)) << "round " << round;
    EXPECT_EQ(from_boundary->empty(), r->model.num_faces() == 0) << "round " << round;
    for (const Region& g : from_boundary->regions) holes += static_cast<int>(g.loops.size()) - 1;
  }
  // A box with a box cut from it, at the origin and at `at`: its shadow, which must be
  // the faces' union too.
  const auto cut_shadow = [&](Vec3 size, Vec3 cut, Vec3 at) {
    Model block = turned_box(size, shape::Transform::identity());
    Model taken = turned_box(cut, shape::Transform::translate(at));
    const Model* ops[] = {&block, &taken};
    auto r = apply(Op::kDifference, ops);
    EXPECT_TRUE(r.ok());
    if (!r.ok()) return Shape2D{};
    auto from_boundary = shadow(r->model, false);
    EXPECT_TRUE(from_boundary.ok());
    if (!from_boundary.ok()) return Shape2D{};
    EXPECT_TRUE(same(*from_boundary, *shadow(r->model, true)));
    return *from_boundary;
  };
  // A C: 3 x 1 x 3 with a slot 2 deep and 1 high cut from its side at mid height.
  const Shape2D c = cut_shadow({3, 1, 3}, {2, 2, 1}, {1, -0.5, 1});
  EXPECT_DOUBLE_EQ(area(c), 3);
  ASSERT_EQ(c.regions.size(), 1u);
  EXPECT_EQ(c.regions[0].loops[0].size(), 4u);
  // A frame: a 3 x 3 x 1 block with a 1 x 1 hole through it; its shadow has the hole.
  const Shape2D ring = cut_shadow({3, 3, 1}, {1, 1, 3}, {1, 1, -1});
  EXPECT_DOUBLE_EQ(area(ring), 8);
  ASSERT_EQ(ring.regions.size(), 1u);
  EXPECT_EQ(ring.regions[0].loops.size(), 2u);
  RecordProperty("holes", holes);
}

TEST(Projection, SphereCutAndShadowAreTheEquatorialPolygon) {
  // fn = 16: 8 rings at polar angles 180 (i + 0.5) / 8; rings 3 and 4 (78.75 and
  // 101.25 degrees) have one radius, so the band between them is vertical.
  Model m;
  ASSERT_OK(shape::make_sphere(m, {.r = 2, .faceting = {.fn = 16}}));
  const double want = ngon_area(16, 2 * std::sin(78.75 * kPi / 180));
  auto cut = projection(m, {.cut = true});
  ASSERT_OK(cut);
  EXPECT_NEAR(area(*cut), want, 1e-12);
  auto shadow = projection(m);
  ASSERT_OK(shadow);
  EXPECT_NEAR(area(*shadow), want, 1e-12);
}

TEST(Projection, ShadowOfTwoCubesAtDifferentHeightsIsTheirUnion) {
  Model two;
  auto g1 = shape::make_cube(two, {.size = {2, 2, 1}});
  ASSERT_OK(g1);
  auto g2 = shape::make_cube(two, {.size = {2, 2, 1}});
  ASSERT_OK(g2);
  ASSERT_OK(shape::transformed(two, *g2, shape::Transform::translate({1, 1, 3})));
  // `two` holds the cube at the origin, the copy that stayed, and the moved one.
  auto s = projection(two);
  ASSERT_OK(s);
  EXPECT_DOUBLE_EQ(area(*s), 4 + 4 - 1);
  EXPECT_TRUE(projection(Model{})->empty());
}

}  // namespace
}  // namespace cellforge::boolean
