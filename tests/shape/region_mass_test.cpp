// 2D regions (exact checks of polygon()) and mass properties of sheets and cells.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "shape/shape_test_util.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/region.h"
#include "cellforge/topo/builder.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

TEST(Region, PolygonOrientsLoops) {
  // Outer given clockwise, hole counterclockwise: both are turned.
  auto r = polygon({{0, 0}, {0, 4}, {4, 4}, {4, 0}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  ASSERT_OK(r);
  EXPECT_DOUBLE_EQ(area(*r), 15);
  EXPECT_EQ(r->loops[0][0], (Vec2{4, 0}));
  EXPECT_EQ(r->loops[0][1], (Vec2{4, 4}));  // counterclockwise now
  EXPECT_EQ(r->loops[1][1], (Vec2{2, 2}));  // the hole clockwise
}

TEST(Region, PolygonErrorsNameTheProblem) {
  auto expect_error = [](Result<Region> r, const std::string& words) {
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(words), std::string::npos) << r.error().message;
  };
  expect_error(polygon({{0, 0}, {1, 0}}), "at least 3");
  expect_error(polygon({{0, 0}, {2, 0}, {0, 2}, {2, 2}}), "meets");  // bow tie
  expect_error(polygon({{0, 0}, {1, 0}, {2, 0}}), "meets");          // folds back onto itself
  expect_error(polygon({{0, 0}, {1, 0}, {1, 1}, {1, 0}}), "repeats the point (1, 0)");
  expect_error(polygon({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{5, 5}, {6, 5}, {6, 6}}}),
               "hole 0 lies outside");
  expect_error(polygon({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{0, 1}, {1, 1}, {1, 2}}}),
               "meets");  // a hole touching the outer loop
  expect_error(polygon({{0, 0}, {9, 0}, {9, 9}, {0, 9}},
                       {{{1, 1}, {8, 1}, {8, 8}, {1, 8}}, {{2, 2}, {3, 2}, {3, 3}}}),
               "hole 1 lies inside hole 0");
  expect_error(circle(0), "positive");
  expect_error(regular_polygon(2, 1), "at least 3");
}

// polygon()'s check of crossings (a sweep over the edges' boxes) against every pair of
// edges, on 2,000 seeded random polygons on a small grid (most cross or touch): the
// same verdict, and the same first pair named.
TEST(Region, CrossingsAgreeWithEveryPairOfEdges) {
  std::mt19937 rng(7);
  int refused = 0;
  for (int c = 0; c < 2000; ++c) {
    const int n = std::uniform_int_distribution<int>(3, 9)(rng);
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i)
      pts.push_back({static_cast<double>(rng() % 6), static_cast<double>(rng() % 6)});
    // The first meeting pair in loop order, by the definition.
    int first = -1, second = -1;
    for (int i = 0; i < n && first < 0; ++i)
      for (int j = i + 1; j < n && first < 0; ++j) {
        const Vec2 a = pts[i], b = pts[(i + 1) % n], p = pts[j], q = pts[(j + 1) % n];
        bool bad;
        if (j == i + 1) {
          bad = edges_fold_back(a, b, q);
        } else if ((j + 1) % n == i) {
          bad = edges_fold_back(p, q, b);
        } else {
          bad = segments_meet(a, b, p, q);
        }
        if (bad) first = i, second = j;
      }
    const auto r = polygon(pts);
    const std::string message = r.ok() ? "" : r.error().message;
    if (message.find("repeats") != std::string::npos || message.find("at least") != std::string::npos)
      continue;  // checked before the crossings
    if (first < 0) {
      EXPECT_EQ(message.find("meets"), std::string::npos) << c << ": " << message;
      continue;
    }
    ++refused;
    ASSERT_FALSE(r.ok()) << c;
    EXPECT_EQ(message.rfind("outer loop edge " + std::to_string(first) + " ", 0), 0u) << c << ": " << message;
    EXPECT_NE(message.find("meets outer loop edge " + std::to_string(second) + " "), std::string::npos)
        << c << ": " << message;
  }
  EXPECT_GT(refused, 500);
}

TEST(Region, CircleIsOpenScads) {
  auto c = circle(10);  // fragments(10) = 30
  ASSERT_OK(c);
  ASSERT_EQ(c->loops[0].size(), 30u);
  EXPECT_EQ(c->loops[0][0], (Vec2{10, 0}));
  EXPECT_EQ(c->loops[0][5], (Vec2{10 * cos_degrees(60), 10 * sin_degrees(60)}));
  EXPECT_EQ(c->loops[0][5].x, 5);  // cos 60 is exactly 0.5
}

TEST(Mass, SheetReportsAreaOnly) {
  auto r = polygon({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  ASSERT_OK(r);
  Model m;
  auto g = make_region_face(m, *r);
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const MassProperties p = mass_properties(m, *g);
  EXPECT_FALSE(p.solid);
  EXPECT_EQ(p.volume, 0);
  EXPECT_DOUBLE_EQ(p.area, 15);
  // Area centroid: (16 * (2, 2) - 1 * (1.5, 1.5)) / 15.
  EXPECT_NEAR(p.centroid.x, (32 - 1.5) / 15, 1e-14);
  EXPECT_EQ(p.bbox_max, (Vec3{4, 4, 0}));
}

TEST(Mass, PerCellOfTwoCellsSharingAFace) {
  // Two unit cubes sharing the face x = 1: cells 0 and 1, the shared face between.
  MeshInput in;
  in.volumes = 2;
  for (int x = 0; x <= 2; ++x) {
    for (int y = 0; y <= 1; ++y) {
      for (int z = 0; z <= 1; ++z) {
        in.positions.push_back(
            {static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)});
      }
    }
  }
  auto id = [](int x, int y, int z) { return static_cast<std::uint32_t>(x * 4 + y * 2 + z); };
  auto face = [&](std::vector<std::uint32_t> loop, int front, int back) {
    in.faces.push_back({{std::move(loop)}, front, back});
  };
  for (int c = 0; c < 2; ++c) {
    const int x0 = c, x1 = c + 1;
    face({id(x0, 0, 0), id(x0, 1, 0), id(x1, 1, 0), id(x1, 0, 0)}, -1, c);  // bottom
    face({id(x0, 0, 1), id(x1, 0, 1), id(x1, 1, 1), id(x0, 1, 1)}, -1, c);  // top
    face({id(x0, 0, 0), id(x1, 0, 0), id(x1, 0, 1), id(x0, 0, 1)}, -1, c);  // y = 0
    face({id(x0, 1, 0), id(x0, 1, 1), id(x1, 1, 1), id(x1, 1, 0)}, -1, c);  // y = 1
  }
  face({id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0)}, -1, 0);  // x = 0
  face({id(2, 0, 0), id(2, 1, 0), id(2, 1, 1), id(2, 0, 1)}, -1, 1);  // x = 2
  face({id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1)}, 1, 0);   // shared, +x normal
  Model m;
  auto built = build_mesh(m, in);
  ASSERT_OK(built);
  EXPECT_VALID(m);
  const MassProperties whole = mass_properties(m, built->group);
  EXPECT_DOUBLE_EQ(whole.volume, 2);
  EXPECT_DOUBLE_EQ(whole.centroid.x, 1);
  const MassProperties right = mass_properties(m, built->volumes[1]);
  EXPECT_DOUBLE_EQ(right.volume, 1);
  EXPECT_DOUBLE_EQ(right.centroid.x, 1.5);
  EXPECT_DOUBLE_EQ(right.area, 6);
}

TEST(Mass, FarFromOriginKeepsPrecision) {
  auto base = polygon({{1e6, 1e6}, {1e6 + 1, 1e6}, {1e6 + 1, 1e6 + 1}, {1e6, 1e6 + 1}});
  ASSERT_OK(base);
  Model m;
  auto g = make_prism(m, *base, 1);
  ASSERT_OK(g);
  EXPECT_DOUBLE_EQ(mass_properties(m, *g).volume, 1);
}

}  // namespace
}  // namespace cellforge::shape
