// Polygons, planes, intersection tests, signed volume and disjoint sets (geom/):
// exact signs against the Dyadic oracle on inputs where doubles get them wrong, the
// closed-set conventions of the intersection tests on touching configurations, and
// the signed volume's independence of the reference point on closed surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/plane.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/geom/volume.h"
#include "geom/dyadic.h"

namespace cellforge {
namespace {

using testing::Dyadic;

int oracle_area_sign(const std::vector<Vec2>& loop) {
  Dyadic s;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % loop.size()];
    s = s + Dyadic(p.x) * q.y - Dyadic(q.x) * p.y;
  }
  return s.sign();
}

// ---- polygons

TEST(Polygon, NewellNormalIsTwiceTheVectorArea) {
  const std::vector<Vec3> square{{0, 0, 5}, {2, 0, 5}, {2, 2, 5}, {0, 2, 5}};
  EXPECT_EQ(newell_normal(square), (Vec3{0, 0, 8}));
  EXPECT_DOUBLE_EQ(polygon_area(square), 4);
  // Summing loops: a square with a clockwise square hole.
  const std::vector<Vec3> hole{{0.5, 0.5, 5}, {0.5, 1.5, 5}, {1.5, 1.5, 5}, {1.5, 0.5, 5}};
  EXPECT_EQ(newell_normal(hole, newell_normal(square)), (Vec3{0, 0, 6}));
  EXPECT_EQ(newell_normal(std::vector<Vec3>{{1, 2, 3}, {4, 5, 6}}), Vec3{});
}

TEST(Polygon, AreaSignIsExactWhereTheShoelaceSumRoundsWrong) {
  // A sliver far from the origin: its signed area is a few ulps of the coordinates'
  // products, and the double shoelace sum loses it to cancellation.
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<int> ulps(-3, 3);
  int disagreements = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double base = 1e8 + trial;
    std::vector<Vec2> loop{{base, base}, {base + 1, base + 1}, {base + 2, base + 2}};
    loop[1].x = std::nextafter(loop[1].x, ulps(rng) > 0 ? 1e300 : -1e300);
    loop[2].y += ulps(rng) * std::ldexp(1.0, -26);
    const int want = oracle_area_sign(loop);
    EXPECT_EQ(area_sign(loop), want) << "trial " << trial;
    const double naive = signed_area2(loop);
    disagreements += (naive > 0) - (naive < 0) != want;
  }
  EXPECT_GT(disagreements, 0) << "the cases should be hard for doubles";
}

TEST(Polygon, AreaSignOfOrientedLoops) {
  const std::vector<Vec2> ccw{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> cw(ccw.rbegin(), ccw.rend());
  EXPECT_EQ(area_sign(ccw), 1);
  EXPECT_EQ(area_sign(cw), -1);
  EXPECT_EQ(area_sign(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}}), 0);
  // A figure eight: equal lobes of opposite turn.
  EXPECT_EQ(area_sign(std::vector<Vec2>{{0, 0}, {1, 1}, {1, 0}, {0, 1}}), 0);
}

TEST(Polygon, WindingNumberAndPointInPolygon) {
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_TRUE(point_in_polygon(l_shape, {0.5, 1.5}));
  EXPECT_FALSE(point_in_polygon(l_shape, {1.5, 1.5}));
  const std::vector<Vec2> cw(l_shape.rbegin(), l_shape.rend());
  EXPECT_EQ(winding_number(l_shape, {0.5, 0.5}), 1);
  EXPECT_EQ(winding_number(cw, {0.5, 0.5}), -1);
  // Just off an edge by one ulp, on either side.
  EXPECT_TRUE(point_in_polygon(l_shape, {std::nextafter(1.0, 0.0), 1.5}));
  EXPECT_FALSE(point_in_polygon(l_shape, {std::nextafter(1.0, 2.0), 1.5}));
}

TEST(Polygon, ProjectionKeepsOrientation) {
  const std::vector<Vec3> tri{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // normal +x
  for (const Vec3& n : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}}) {
    const Projection proj(n);
    EXPECT_EQ(proj.drop, 0);
    const std::vector<Vec2> p{proj(tri[0]), proj(tri[1]), proj(tri[2])};
    EXPECT_EQ(area_sign(p), n.x > 0 ? 1 : -1);
  }
}

// ---- planes

TEST(Plane, SidesAreExactInBothForms) {
  const Vec3 a{0.1, 0.2, 0.3}, b{1.7, 0.2, 0.3}, c{0.1, 2.9, 0.3};
  const Plane three = Plane::through(a, b, c);
  const Plane normal = Plane::from_point_normal(a, {0, 0, 1});
  const Vec3 above{0.5, 0.5, std::nextafter(0.3, 1.0)}, below{0.5, 0.5, std::nextafter(0.3, 0.0)};
  for (const Plane& p : {three, normal}) {
    EXPECT_EQ(p.side(above), 1);
    EXPECT_EQ(p.side(below), -1);
    EXPECT_TRUE(p.contains({123.0, -7.0, 0.3}));
    EXPECT_FALSE(p.is_degenerate());
    EXPECT_EQ(p.dominant_axis(), 2);
  }
  EXPECT_TRUE(Plane::through(a, b, a + (b - a) * 2).is_degenerate());
  EXPECT_TRUE(Plane::from_point_normal(a, {}).is_degenerate());
}

TEST(Plane, DominantAxisIsExactOnTies) {
  // Normal (1, -1, 0) exactly: a tie between x and y goes to x; (0, -1, 1) to y.
  EXPECT_EQ(Plane::from_point_normal({}, {1, -1, 0}).dominant_axis(), 0);
  EXPECT_EQ(Plane::from_point_normal({}, {0, -1, 1}).dominant_axis(), 1);
  const Projection p = Plane::from_point_normal({}, {0, -2, 1}).projection();
  EXPECT_EQ(p.drop, 1);
  EXPECT_TRUE(p.flip);
}

// ---- intersections

TEST(Intersect, SegmentsTouchingCountAsMeeting) {
  EXPECT_TRUE(segments_meet({0, 0}, {2, 2}, {0, 2}, {2, 0}));  // crossing
  EXPECT_TRUE(segments_meet({0, 0}, {2, 0}, {1, 0}, {1, 5}));  // T
  EXPECT_TRUE(segments_meet({0, 0}, {2, 0}, {2, 0}, {3, 1}));  // shared end
  EXPECT_TRUE(segments_meet({0, 0}, {2, 0}, {1, 0}, {3, 0}));  // overlap
  EXPECT_FALSE(segments_meet({0, 0}, {2, 0}, {3, 0}, {4, 0}));  // collinear, apart
  EXPECT_FALSE(segments_meet({0, 0}, {2, 0}, {1, std::nextafter(0.0, 1.0)}, {1, 5}));
  EXPECT_TRUE(point_on_segment({0, 0}, {4, 4}, {1, 1}));
  EXPECT_FALSE(point_on_segment({0, 0}, {4, 4}, {5, 5}));
  EXPECT_FALSE(point_on_segment({0, 0}, {4, 4}, {1, std::nextafter(1.0, 2.0)}));
}

TEST(Intersect, TrianglesInSpace) {
  const Vec3 t[3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  const Vec3 piercing[3] = {{1, 1, -1}, {1, 1, 1}, {5, 5, 5}};
  const Vec3 touching[3] = {{1, 1, 0}, {1, 1, 1}, {2, 1, 1}};  // a vertex on t
  const Vec3 above[3] = {{1, 1, 1e-300}, {1, 2, 1}, {2, 1, 1}};
  const Vec3 coplanar_apart[3] = {{3, 3, 0}, {5, 3, 0}, {3, 5, 0}};
  const Vec3 coplanar_inside[3] = {{0.5, 0.5, 0}, {1, 0.5, 0}, {0.5, 1, 0}};
  EXPECT_TRUE(triangles_meet(t, piercing));
  EXPECT_TRUE(triangles_meet(t, touching));
  EXPECT_FALSE(triangles_meet(t, above));
  EXPECT_FALSE(triangles_meet(t, coplanar_apart));
  EXPECT_TRUE(triangles_meet(t, coplanar_inside));
  // Degenerate triangles (three corners on a line) are the segments they cover: every
  // point is on their "plane", which must not make them meet what they miss.
  const Vec3 needle_through[3] = {{1, 1, -1}, {1, 1, 1}, {1, 1, 0.5}};
  const Vec3 needle_beside[3] = {{5, 5, -1}, {5, 5, 1}, {5, 5, 0.5}};
  const Vec3 needle_above[3] = {{1, 1, 1}, {1, 1, 2}, {1, 1, 3}};
  const Vec3 needle_on_edge[3] = {{2, -1, 0}, {2, 0, 0}, {2, -2, 0}};  // in t's plane, touching
  EXPECT_TRUE(triangles_meet(t, needle_through));
  EXPECT_TRUE(triangles_meet(needle_through, t));
  EXPECT_FALSE(triangles_meet(t, needle_beside));
  EXPECT_FALSE(triangles_meet(needle_beside, t));
  EXPECT_FALSE(triangles_meet(t, needle_above));
  EXPECT_FALSE(triangles_meet(needle_above, t));
  EXPECT_TRUE(triangles_meet(t, needle_on_edge));
  EXPECT_TRUE(segment_meets_triangle({1, 1, 5}, {1, 1, 0}, t));
  EXPECT_FALSE(segment_meets_triangle({3, 3, 5}, {3, 3, -5}, t));  // passes beside it
}

// A triangle in an axis plane (the quick test in the plane) against any other, on a
// small grid where corners land on the plane and on the other's edges: the same
// answer as the six edge-against-triangle tests, in both argument orders.
TEST(Intersect, TrianglesOnAnAxisPlaneAgreeWithTheEdgeTests) {
  std::mt19937_64 rng(20261204);
  std::uniform_int_distribution<int> grid(0, 4), axis(0, 2);
  int tested = 0, meeting = 0;
  for (int n = 0; n < 200000; ++n) {
    Vec3 a[3], b[3];
    const int k = axis(rng);
    for (int i = 0; i < 3; ++i) {
      double c[3] = {double(grid(rng)), double(grid(rng)), double(grid(rng))};
      c[k] = 2;
      a[i] = {c[0], c[1], c[2]};
      b[i] = {double(grid(rng)), double(grid(rng)), double(grid(rng))};
    }
    if (collinear3d(a[0], a[1], a[2]) || collinear3d(b[0], b[1], b[2])) continue;
    if (b[0][k] == 2 && b[1][k] == 2 && b[2][k] == 2) continue;  // coplanar: tested above
    ++tested;
    bool edges_meet = false;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      edges_meet = edges_meet || segment_meets_triangle(a[i], a[j], b) || segment_meets_triangle(b[i], b[j], a);
    }
    meeting += edges_meet;
    ASSERT_EQ(triangles_meet(a, b), edges_meet) << "pair " << n;
    ASSERT_EQ(triangles_meet(b, a), edges_meet) << "pair " << n;
  }
  EXPECT_GT(tested, 100000);
  EXPECT_GT(meeting, tested / 10);
  EXPECT_LT(meeting, tested - tested / 10);
}

// Triangles that straddle each other's planes: the two-orientation test against the
// six edge-against-triangle tests, over seeded random pairs on a small grid (where
// traces touch exactly: an edge through an edge, a trace ending on the other's) and
// off it (where they pass within a rounding of each other).
TEST(Intersect, StraddlingTrianglesApartAgreesWithTheEdgeTests) {
  std::mt19937_64 rng(20261202);
  std::uniform_int_distribution<int> grid(0, 4);
  std::uniform_real_distribution<double> unit(0, 1);
  int straddling = 0, meeting = 0, apart = 0, touching = 0;
  for (int n = 0; n < 400000; ++n) {
    Vec3 a[3], b[3];
    const bool on_grid = n % 2 == 0;
    for (Vec3* t : {a, b})
      for (int k = 0; k < 3; ++k)
        t[k] = on_grid ? Vec3{double(grid(rng)), double(grid(rng)), double(grid(rng))}
                       : Vec3{unit(rng), unit(rng), unit(rng)};
    if (!on_grid && n % 4 == 1) b[0] = a[0] + (b[0] - a[0]) * 1e-9;  // nearly a shared corner
    int sa[3], sb[3];
    for (int k = 0; k < 3; ++k) {
      sa[k] = orient3d(b[0], b[1], b[2], a[k]);
      sb[k] = orient3d(a[0], a[1], a[2], b[k]);
    }
    auto straddles = [](const int s[3]) {
      return s[0] * s[1] * s[2] != 0 && !(s[0] == s[1] && s[1] == s[2]);
    };
    if (!straddles(sa) || !straddles(sb)) continue;
    ++straddling;
    bool edges_meet = false;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      edges_meet = edges_meet || segment_meets_triangle(a[i], a[j], b) || segment_meets_triangle(b[i], b[j], a);
    }
    const bool far = straddling_triangles_apart(a, b, sa, sb);
    ASSERT_EQ(far, !edges_meet) << "pair " << n;
    ASSERT_EQ(far, straddling_triangles_apart(b, a, sb, sa)) << "pair " << n;
    ASSERT_EQ(triangles_meet(a, b), edges_meet) << "pair " << n;
    (far ? apart : meeting) += 1;
    if (on_grid && edges_meet) {
      // An edge of each in one plane: where the traces' ends can coincide exactly.
      bool coplanar_edges = false;
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          coplanar_edges = coplanar_edges || orient3d(a[i], a[(i + 1) % 3], b[k], b[(k + 1) % 3]) == 0;
      touching += coplanar_edges;
    }
  }
  EXPECT_GT(straddling, 50000);
  EXPECT_GT(meeting, 10000);
  EXPECT_GT(apart, 10000);
  EXPECT_GT(touching, 100);
}

// ---- signed volume

// The unit cube's six faces, counterclockwise seen from outside, as index loops.
const std::vector<std::vector<std::uint32_t>> kCubeFaces{
    {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

std::vector<Vec3> cube_at(Vec3 o, double s) {
  std::vector<Vec3> p;
  for (int k = 0; k < 8; ++k) {
    const double x = (k == 1 || k == 2 || k == 5 || k == 6) ? s : 0;
    const double y = (k == 2 || k == 3 || k == 6 || k == 7) ? s : 0;
    p.push_back(o + Vec3{x, y, k >= 4 ? s : 0});
  }
  return p;
}

TEST(Volume, SignOfClosedSurfaces) {
  const auto cube = cube_at({0, 0, 0}, 1);
  EXPECT_EQ(volume_sign(cube, kCubeFaces), 1);
  auto inside_out = kCubeFaces;
  for (auto& f : inside_out) std::reverse(f.begin(), f.end());
  EXPECT_EQ(volume_sign(cube, inside_out), -1);
  // Six times the volume, from any reference point.
  for (const Vec3 o : {Vec3{}, Vec3{10, -3, 7}}) {
    VolumeFilter v(o);
    for (const auto& f : kCubeFaces)
      for_each_fan_triangle<std::uint32_t>(cube, f,
                                           [&](Vec3 a, Vec3 b, Vec3 c) { v.add_triangle(a, b, c); });
    EXPECT_DOUBLE_EQ(v.volume6(), 6);
  }
}

TEST(Volume, TinyCubeFarAwayIsDecidedExactly) {
  // A cube of side 2^-30 at 2^20: the filter, seeded far from the cube, cannot decide;
  // the exact sum still finds the sign, whatever the reference point.
  const auto cube = cube_at({1048576, 1048576, 1048576}, std::ldexp(1.0, -30));
  VolumeFilter far(Vec3{});
  ExactVolume exact(Vec3{});
  for (const auto& f : kCubeFaces) {
    for_each_fan_triangle<std::uint32_t>(cube, f, [&](Vec3 a, Vec3 b, Vec3 c) {
      far.add_triangle(a, b, c);
      exact.add_triangle(a, b, c);
    });
  }
  EXPECT_EQ(far.sign(), 0);
  EXPECT_EQ(exact.sign(), 1);
  EXPECT_EQ(volume_sign(cube, kCubeFaces), 1);
}

TEST(Volume, FlatClosedSurfaceHasSignZero) {
  // Two triangles back to back enclose nothing.
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::vector<std::uint32_t>> faces{{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(volume_sign(p, faces), 0);
}

// ---- disjoint sets

TEST(UnionFind, CountsComponents) {
  UnionFind u(6);
  EXPECT_TRUE(u.unite(0, 1));
  EXPECT_TRUE(u.unite(2, 3));
  EXPECT_TRUE(u.unite(1, 3));
  EXPECT_FALSE(u.unite(0, 2));
  EXPECT_EQ(u.find(3), u.find(0));
  EXPECT_NE(u.find(4), u.find(5));
  u.reset(2);
  EXPECT_EQ(u.size(), 2u);
  EXPECT_NE(u.find(0), u.find(1));
}

}  // namespace
}  // namespace cellforge
