// Convex hulls: the hull of a cube's corners (with points on its faces, edges and
// inside) is the cube with six quads; random point sets, many of them degenerate
// (integer grids), give a valid closed convex solid that contains every point, whose
// vertices are input points and whose faces are maximal; the errors of degenerate
// input.
#include "cellforge/shape/hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <tuple>

#include "cellforge/geom/predicates.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "shape/shape_test_util.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

using testing::counts;
using testing::ngon_area;

TEST(Hull2D, SquareWithInteriorEdgeAndDuplicatePointsHasFourVertices) {
  const std::vector<Vec2> pts = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1},
                                 {1, 1}, {0.5, 1.5}, {0, 0}, {2, 2}, {0, 1}};
  auto r = convex_hull(std::span<const Vec2>(pts));
  ASSERT_OK(r);
  ASSERT_EQ(r->loops.size(), 1u);
  EXPECT_EQ(r->loops[0].size(), 4u);
  EXPECT_DOUBLE_EQ(area(*r), 4);
  EXPECT_EQ(r->loops[0][0], (Vec2{0, 0}));  // counterclockwise from the lowest point
  EXPECT_EQ(r->loops[0][1], (Vec2{2, 0}));
}

TEST(Hull2D, RegularPolygonWithRandomInteriorPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  auto poly = regular_polygon(13, 1);
  ASSERT_OK(poly);
  std::vector<Vec2> pts = poly->loops[0];
  for (int i = 0; i < 200; ++i) pts.push_back({u(rng), u(rng)});
  std::shuffle(pts.begin(), pts.end(), rng);
  auto r = convex_hull(std::span<const Vec2>(pts));
  ASSERT_OK(r);
  EXPECT_EQ(r->loops[0].size(), 13u);
  EXPECT_NEAR(area(*r), ngon_area(13, 1), 1e-12);
}

TEST(Hull2D, DegenerateInputIsAnError) {
  const std::vector<Vec2> line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  auto r = convex_hull(std::span<const Vec2>(line));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("collinear"), std::string::npos);
  const std::vector<Vec2> two = {{0, 0}, {1, 1}, {0, 0}};
  EXPECT_FALSE(convex_hull(std::span<const Vec2>(two)).ok());
  const std::vector<Vec2> nan = {{0, 0}, {1, 0}, {0, NAN}};
  EXPECT_FALSE(convex_hull(std::span<const Vec2>(nan)).ok());
}

std::vector<Vec3> cube_points_with_extras() {
  std::vector<Vec3> pts;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 2; ++j)
      for (int k = 0; k <= 2; ++k) pts.push_back({i * 1.5, j * 1.5, k * 1.5});  // corners, mids
  pts.push_back({0.3, 0.2, 0.1});
  pts.push_back({3, 3, 3});  // a duplicate corner
  return pts;
}

TEST(Hull3D, CubeCornersWithFaceEdgeAndInteriorPointsIsTheCube) {
  Model m;
  const std::vector<Vec3> pts = cube_points_with_extras();
  auto g = convex_hull(m, std::span<const Vec3>(pts));
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 8);
  EXPECT_EQ(c.e, 12);
  EXPECT_EQ(c.f, 6);
  const MassProperties p = mass_properties(m, *g);
  EXPECT_TRUE(p.solid);
  EXPECT_DOUBLE_EQ(p.volume, 27);
  EXPECT_DOUBLE_EQ(p.area, 54);
}

TEST(Hull3D, HullOfACylindersVerticesIsTheCylinder) {
  Model src;
  ASSERT_OK(make_cylinder(src, {.h = 2, .r1 = 1, .r2 = 1, .faceting = {.fn = 24}}));
  const std::vector<Vec3> pts = vertex_positions(src);
  Model m;
  auto g = convex_hull(m, std::span<const Vec3>(pts));
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *g).f, 26);  // two 24-gon caps and 24 quads
  EXPECT_NEAR(mass_properties(m, *g).volume, 2 * ngon_area(24, 1), 1e-12);
}

// The hull property, checked independently of how the hull was built: a closed valid
// solid whose every face has all input points on or behind its plane (so it contains
// them and is convex), whose vertices are input points, with no two neighbouring
// faces coplanar and no vertex inside a straight run of a face's boundary.
void expect_hull_of(const Model& m, GroupId g, const std::vector<Vec3>& pts) {
  EXPECT_VALID(m);
  std::set<std::tuple<double, double, double>> input;
  for (Vec3 p : pts) input.insert({p.x, p.y, p.z});
  for (VertexId v : m.vertices()) {
    const Vec3 p = m.position(v);
    EXPECT_TRUE(input.count({p.x, p.y, p.z})) << p;
  }
  for (FaceId f : m.faces()) {
    const std::vector<Vec3> loop = m.loop_points(m.outer_loop(f));
    ASSERT_GE(loop.size(), 3u);
    for (std::size_t i = 0; i < loop.size(); ++i)
      EXPECT_FALSE(collinear3d(loop[i], loop[(i + 1) % loop.size()], loop[(i + 2) % loop.size()]));
    for (Vec3 q : pts) ASSERT_LE(orient3d(loop[0], loop[1], loop[2], q), 0) << q;
    for (EdgeId e : m.edges()) {
      for (EdgeUseId u : m.radial(e)) {
        if (m.face_of(u) != f) continue;
        for (EdgeUseId w : m.radial(e)) {
          if (m.face_of(w) == f) continue;
          for (Vec3 q : m.loop_points(m.outer_loop(m.face_of(w))))
            if (orient3d(loop[0], loop[1], loop[2], q) != 0) goto not_coplanar;
          ADD_FAILURE() << "neighbouring faces are coplanar";
        not_coplanar:;
        }
      }
    }
  }
  EXPECT_TRUE(mass_properties(m, g).volume > 0);
  EXPECT_EQ(counts(m, g).euler(), 2);
}

TEST(Hull3D, RandomGridPointSetsAreHulls) {
  for (unsigned seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> u(0, 3);
    std::vector<Vec3> pts;
    const int n = 4 + static_cast<int>(seed % 20);
    for (int i = 0; i < n; ++i) pts.push_back({1.0 * u(rng), 1.0 * u(rng), 0.5 * u(rng)});
    Model m;
    auto g = convex_hull(m, std::span<const Vec3>(pts));
    if (!g.ok()) {  // only a flat or collinear set may fail
      bool flat = true;
      for (std::size_t a = 0; a < pts.size() && flat; ++a)
        for (std::size_t b = 0; b < pts.size() && flat; ++b)
          for (std::size_t c = 0; c < pts.size() && flat; ++c)
            for (std::size_t d = 0; d < pts.size() && flat; ++d)
              flat = orient3d(pts[a], pts[b], pts[c], pts[d]) == 0;
      EXPECT_TRUE(flat) << g.error().message;
      continue;
    }
    expect_hull_of(m, *g, pts);
  }
}

TEST(Hull3D, RandomPointsOnAndInASphere) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd;
    std::vector<Vec3> pts;
    for (int i = 0; i < 300; ++i) {
      const Vec3 d = normalized(Vec3{nd(rng), nd(rng), nd(rng)});
      pts.push_back(i % 3 == 0 ? d * 0.5 : d);
    }
    Model m;
    auto g = convex_hull(m, std::span<const Vec3>(pts));
    ASSERT_OK(g);
    expect_hull_of(m, *g, pts);
    const double v = mass_properties(m, *g).volume;
    EXPECT_LT(v, 4 * std::numbers::pi / 3);
    EXPECT_GT(v, 0.9 * 4 * std::numbers::pi / 3);
  }
}

TEST(Hull3D, DegenerateInput) {
  Model m;
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}};
  auto r = convex_hull(m, std::span<const Vec3>(line));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("collinear"), std::string::npos);
  const std::vector<Vec3> flat = {{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}, {1, 1, 1}, {1, 0, 1}};
  r = convex_hull(m, std::span<const Vec3>(flat));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("plane"), std::string::npos);
  EXPECT_TRUE(m.empty());
  r = convex_hull(m, std::span<const Vec3>(flat), {.allow_flat = true});
  ASSERT_OK(r);
  EXPECT_VALID(m);
  const auto c = counts(m, *r);
  EXPECT_EQ(c.v, 4);
  EXPECT_EQ(c.f, 1);
  const MassProperties p = mass_properties(m, *r);
  EXPECT_FALSE(p.solid);
  EXPECT_DOUBLE_EQ(p.area, 4);
}

}  // namespace
}  // namespace cellforge::shape
