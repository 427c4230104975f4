// Export triangulation: concave polygons and holes without flipped or overlapping
// triangles, and mesh exports that admesh accepts.
#include "cellforge/io/triangulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/diagnose.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using Loops = std::vector<std::vector<Vec3>>;

// Checks: every triangle turns counterclockwise about +z, the areas add up to the
// polygon's area, and no triangle is degenerate.
void expect_good_triangulation(const Loops& loops, double area) {
  const auto tris = io::triangulate_polygon(loops, {0, 0, 1});
  std::vector<Vec3> all;
  for (const auto& l : loops) all.insert(all.end(), l.begin(), l.end());
  double sum = 0;
  for (const auto& t : tris) {
    const Vec2 a{all[t[0]].x, all[t[0]].y}, b{all[t[1]].x, all[t[1]].y},
        c{all[t[2]].x, all[t[2]].y};
    EXPECT_EQ(orient2d(a, b, c), 1) << t[0] << " " << t[1] << " " << t[2];
    sum += ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
  }
  EXPECT_DOUBLE_EQ(sum, area);
  std::size_t corners = 0;
  for (const auto& l : loops) corners += l.size();
  EXPECT_EQ(tris.size(), corners - 2 + 2 * (loops.size() - 1));
}

// Quadrilaterals take a direct path: seeded random simple ones (convex and concave,
// either orientation) tile into two counterclockwise triangles covering the area.
TEST(Triangulate, RandomQuadrilaterals) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(-4, 4);
  int tested = 0;
  while (tested < 2000) {
    std::vector<Vec3> q;
    for (int k = 0; k < 4; ++k) q.push_back({double(coord(rng)), double(coord(rng)), 0});
    std::vector<Vec2> p;
    for (const Vec3& v : q) p.push_back({v.x, v.y});
    // Simple: no three corners on a line, the two pairs of opposite edges apart.
    bool simple = true;
    for (int k = 0; k < 4; ++k) simple &= orient2d(p[k], p[(k + 1) % 4], p[(k + 2) % 4]) != 0;
    simple &= !segments_meet(p[0], p[1], p[2], p[3]) && !segments_meet(p[1], p[2], p[3], p[0]);
    if (!simple) continue;
    double area = 0;
    for (int k = 0; k < 4; ++k) area += (p[k].x * p[(k + 1) % 4].y - p[(k + 1) % 4].x * p[k].y) / 2;
    if (area < 0) {
      std::reverse(q.begin() + 1, q.end());
      area = -area;
    }
    expect_good_triangulation({q}, area);
    ++tested;
  }
}

// A plate face with 900 holes (octagons, turned a little each, so that no two
// vertices line up): the bridges are found through the grid of edges; the tiling
// still covers the face's area exactly once with counterclockwise triangles.
TEST(Triangulate, NineHundredHoles) {
  Loops loops = {{{0, 0, 0}, {120, 0, 0}, {120, 120, 0}, {0, 120, 0}}};
  double area = 120 * 120;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) {
      std::vector<Vec3> hole;
      const double cx = 2 + 4 * i, cy = 2 + 4 * j, turn = 0.01 * (i * 30 + j);
      std::vector<Vec2> p;
      for (int k = 7; k >= 0; --k) {  // clockwise
        const double a = 2 * std::numbers::pi * k / 8 + turn;
        hole.push_back({cx + std::cos(a), cy + std::sin(a), 0});
        p.push_back({hole.back().x, hole.back().y});
      }
      double twice = 0;
      for (int k = 0; k < 8; ++k) twice += p[k].x * p[(k + 1) % 8].y - p[(k + 1) % 8].x * p[k].y;
      area += twice / 2;  // negative: clockwise
      loops.push_back(std::move(hole));
    }
  const auto tris = io::triangulate_polygon(loops, {0, 0, 1});
  EXPECT_EQ(tris.size(), 4 + 900 * 8 - 2 + 2 * 900u);
  std::vector<Vec3> all;
  for (const auto& l : loops) all.insert(all.end(), l.begin(), l.end());
  double sum = 0;
  for (const auto& t : tris) {
    const Vec2 a{all[t[0]].x, all[t[0]].y}, b{all[t[1]].x, all[t[1]].y}, c{all[t[2]].x, all[t[2]].y};
    EXPECT_EQ(orient2d(a, b, c), 1);
    sum += ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
  }
  EXPECT_NEAR(sum, area, 1e-9 * area);
}

TEST(Triangulate, ConcaveComb) {
  // A comb: teeth up from a base, 12 vertices, 5 reflex.
  expect_good_triangulation({{{0, 0, 0},
                              {5, 0, 0},
                              {5, 3, 0},
                              {4, 3, 0},
                              {4, 1, 0},
                              {3, 1, 0},
                              {3, 3, 0},
                              {2, 3, 0},
                              {2, 1, 0},
                              {1, 1, 0},
                              {1, 3, 0},
                              {0, 3, 0}}},
                            5 + 3 * 2);
}

TEST(Triangulate, SquareWithTwoHoles) {
  expect_good_triangulation({{{0, 0, 0}, {6, 0, 0}, {6, 3, 0}, {0, 3, 0}},
                             {{1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}},
                             {{4, 1, 0}, {4, 2, 0}, {5, 2, 0}, {5, 1, 0}}},
                            18 - 2);
}

TEST(Triangulate, HoleBehindAConcaveNotch) {
  // The hole's rightmost vertex faces a notch; the nearest outer vertex is not
  // visible, the bridge must go elsewhere.
  expect_good_triangulation({{{0, 0, 0},
                              {10, 0, 0},
                              {10, 10, 0},
                              {4, 10, 0},
                              {4, 4.5, 0},
                              {3.5, 4.5, 0},
                              {3.5, 10, 0},
                              {0, 10, 0}},
                             {{1, 4, 0}, {1, 6, 0}, {3, 6, 0}, {3, 4, 0}}},
                            100 - 0.5 * 5.5 - 4);
}

TEST(Triangulate, CollinearVerticesAreKept) {
  // A square with extra vertices on its sides: every vertex used, no zero-area
  // triangle.
  expect_good_triangulation(
      {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}, {0, 2, 0}, {0, 1, 0}}},
      4);
}

TEST(Triangulate, FaceOrientationFollowsTheModel) {
  const Model m = testing::build(testing::cube_with_through_hole());
  for (FaceId f : m.faces()) {
    const Vec3 n = m.face_normal(f);
    for (const auto& t : io::triangulate_face(m, f)) {
      const Vec3 a = m.position(t[0]), b = m.position(t[1]), c = m.position(t[2]);
      EXPECT_GT(dot(cross(b - a, c - a), n), 0);
    }
  }
}

TEST(Triangulate, BridgeAlongAHoleDiagonal) {
  // Seen along +y (u = z, v = x) the hole's rightmost vertex (2.5, 2.5) has the
  // outer corner (1.5, 3.5) nearest, on the line u + v = 5 through the hole's
  // interior and its vertex (2, 3): the bridge must leave the hole outward and go
  // to another corner, not fall back to the nearest one.
  const Loops loops = {{{0.5, 3.5, 1.5}, {0.5, 3.5, 4}, {3.5, 3.5, 4}, {3.5, 3.5, 1.5}},
                       {{2.5, 3.5, 2}, {3, 3.5, 2}, {3, 3.5, 2.5}, {2.5, 3.5, 2.5}}};
  const auto tris = io::triangulate_polygon(loops, {0, 1, 0});
  ASSERT_EQ(tris.size(), 8u - 2 + 2);
  const auto uv = [&](std::uint32_t i) {
    const Vec3 p = loops[i / 4][i % 4];
    return Vec2{p.z, p.x};
  };
  double area = 0;
  for (const auto& t : tris) {
    const Vec2 a = uv(t[0]), b = uv(t[1]), c = uv(t[2]);
    EXPECT_EQ(orient2d(a, b, c), 1);
    area += ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
    for (std::uint32_t h = 4; h < 8; ++h) {  // no hole corner inside a triangle
      const Vec2 q = uv(h);
      if (q == a || q == b || q == c) continue;
      EXPECT_FALSE(orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 &&
                   orient2d(c, a, q) >= 0)
          << t[0] << " " << t[1] << " " << t[2] << " holds " << h;
    }
  }
  EXPECT_EQ(area, 2.5 * 3 - 0.5 * 0.5);
}

// Property test: seeded random polygons with holes on an integer grid (every
// product below is a small integer, so double arithmetic is exact), checked to be
// tiled exactly by their triangles.
class TilingCheck {
 public:
  using Loop = std::vector<Vec2>;
  explicit TilingCheck(std::vector<Loop> loops) : loops_(std::move(loops)) {}

  // Why the triangles fail to tile the polygon, or empty.
  std::string failure() const {
    Loops in;
    std::vector<Vec2> all;
    for (const Loop& l : loops_) {
      in.emplace_back();
      for (Vec2 p : l) in.back().push_back({p.x, p.y, 0});
      all.insert(all.end(), l.begin(), l.end());
    }
    const auto tris = io::triangulate_polygon(in, {0, 0, 1});
    std::vector<bool> used(all.size(), false);
    double twice_area = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const auto& t = tris[i];
      const Vec2 a = all[t[0]], b = all[t[1]], c = all[t[2]];
      if (orient2d(a, b, c) != 1) return "triangle " + name(t) + " not counterclockwise";
      twice_area += twice_signed_area({a, b, c});
      for (std::uint32_t k : t) used[k] = true;
      if (const std::string why = meets_boundary({a, b, c}); !why.empty())
        return "triangle " + name(t) + ": " + why;
      if (!in_region({a.x + b.x + c.x, a.y + b.y + c.y}, 3))
        return "triangle " + name(t) + " outside the polygon";
      for (std::size_t j = 0; j < i; ++j)
        if (interiors_meet({a, b, c}, {all[tris[j][0]], all[tris[j][1]], all[tris[j][2]]}))
          return "triangles " + name(t) + " and " + name(tris[j]) + " overlap";
    }
    for (std::size_t k = 0; k < used.size(); ++k)
      if (!used[k]) return "vertex " + std::to_string(k) + " unused";
    double polygon = std::fabs(twice_signed_area(loops_[0]));
    for (std::size_t l = 1; l < loops_.size(); ++l)
      polygon -= std::fabs(twice_signed_area(loops_[l]));
    if (twice_area != polygon)
      return "area " + std::to_string(twice_area / 2) + " != " + std::to_string(polygon / 2);
    return "";
  }

  // The loops form a polygon with holes: boundaries meet only at shared vertices
  // (no edge touches another except at a common end, no two edges overlap), holes
  // lie inside the outer loop and outside each other.
  bool valid() const {
    for (std::size_t a = 0; a < loops_.size(); ++a) {
      if (twice_signed_area(loops_[a]) == 0) return false;
      for (std::size_t b = a + 1; b < loops_.size(); ++b) {
        if (!boundaries_meet_at_vertices(loops_[a], loops_[b])) return false;
        // Hole b inside the outer loop, outside hole a; loop a outside hole b.
        const int inside_a = a == 0 ? 1 : 0;
        for (Vec2 p : loops_[b])
          if (!has(loops_[a], p) && winding(loops_[a], p, 1) != inside_a) return false;
        for (Vec2 p : loops_[a])
          if (!has(loops_[b], p) && winding(loops_[b], p, 1) != 0) return false;
        if (winding(loops_[a], vertex_sum(loops_[b]), double(loops_[b].size())) != inside_a)
          return false;
        if (a > 0 && winding(loops_[b], vertex_sum(loops_[a]), double(loops_[a].size())) != 0)
          return false;
      }
    }
    return true;
  }

  // Some loops share a vertex.
  bool touching() const {
    for (std::size_t a = 0; a < loops_.size(); ++a)
      for (std::size_t b = a + 1; b < loops_.size(); ++b)
        for (Vec2 p : loops_[a])
          if (has(loops_[b], p)) return true;
    return false;
  }

  std::string describe() const {
    std::ostringstream out;
    for (const Loop& l : loops_) {
      out << "{";
      for (Vec2 p : l) out << "(" << p.x << "," << p.y << ")";
      out << "} ";
    }
    return out.str();
  }

 private:
  static std::string name(const std::array<std::uint32_t, 3>& t) {
    return "(" + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
           ")";
  }
  static double twice_signed_area(const Loop& l) {
    double a = 0;
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2 s = l[i], t = l[(i + 1) % l.size()];
      a += s.x * t.y - t.x * s.y;
    }
    return a;
  }
  static bool has(const Loop& l, Vec2 p) {
    return std::find(l.begin(), l.end(), p) != l.end();
  }
  // n times the vertex centroid of an n-gon (inside it when it is convex).
  static Vec2 vertex_sum(const Loop& l) {
    Vec2 s;
    for (Vec2 p : l) s = {s.x + p.x, s.y + p.y};
    return s;
  }
  // Winding number about the point p / scale, for p off the loop.
  static int winding(const Loop& l, Vec2 p, double scale) {
    int w = 0;
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2 s{l[i].x * scale, l[i].y * scale};
      const Vec2 t{l[(i + 1) % l.size()].x * scale, l[(i + 1) % l.size()].y * scale};
      if (s.y <= p.y && p.y < t.y && orient2d(s, t, p) > 0) ++w;
      if (t.y <= p.y && p.y < s.y && orient2d(s, t, p) < 0) --w;
    }
    return w;
  }
  static bool on_segment(Vec2 a, Vec2 b, Vec2 p) {  // closed, exact
    return orient2d(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
  }
  static bool proper_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    return orient2d(a, b, c) * orient2d(a, b, d) < 0 &&
           orient2d(c, d, a) * orient2d(c, d, b) < 0;
  }
  static bool boundaries_meet_at_vertices(const Loop& x, const Loop& y) {
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Vec2 a = x[i], b = x[(i + 1) % x.size()];
      for (std::size_t j = 0; j < y.size(); ++j) {
        const Vec2 c = y[j], d = y[(j + 1) % y.size()];
        if (proper_cross(a, b, c, d)) return false;
        // An end of one edge on the other, other than at a shared end.
        if ((c != a && c != b && on_segment(a, b, c)) ||
            (d != a && d != b && on_segment(a, b, d)) ||
            (a != c && a != d && on_segment(c, d, a)) || (b != c && b != d && on_segment(c, d, b)))
          return false;
        if ((a == c && b == d) || (a == d && b == c)) return false;
      }
    }
    return true;
  }
  // The open triangle meets no loop: no loop vertex in the closed triangle other
  // than at its corners, no loop edge crossing one of its sides.
  std::string meets_boundary(const Loop& t) const {
    for (const Loop& l : loops_) {
      for (std::size_t i = 0; i < l.size(); ++i) {
        const Vec2 p = l[i], q = l[(i + 1) % l.size()];
        if (!has(t, p) && orient2d(t[0], t[1], p) >= 0 && orient2d(t[1], t[2], p) >= 0 &&
            orient2d(t[2], t[0], p) >= 0)
          return "holds a loop vertex";
        for (int s = 0; s < 3; ++s)
          if (proper_cross(t[s], t[(s + 1) % 3], p, q)) return "crosses a loop edge";
      }
    }
    return "";
  }
  bool in_region(Vec2 p, double scale) const {
    if (winding(loops_[0], p, scale) == 0) return false;
    for (std::size_t l = 1; l < loops_.size(); ++l)
      if (winding(loops_[l], p, scale) != 0) return false;
    return true;
  }
  // Two counterclockwise triangles share interior points unless a side of one has
  // the other on its closed outer side (separating axis).
  static bool interiors_meet(const Loop& x, const Loop& y) {
    for (const auto& [s, t] : {std::pair{&x, &y}, std::pair{&y, &x}})
      for (int e = 0; e < 3; ++e) {
        const Vec2 a = (*s)[e], b = (*s)[(e + 1) % 3];
        if (std::all_of(t->begin(), t->end(),
                        [&](Vec2 p) { return orient2d(a, b, p) <= 0; }))
          return false;
      }
    return true;
  }

  std::vector<Loop> loops_;
};

class RandomPolygons {
 public:
  using Loop = TilingCheck::Loop;
  explicit RandomPolygons(std::uint32_t seed) : rng_(seed) {}

  // A rectangle with a vertex at every grid point of its sides, or at its corners
  // only, and up to `holes` holes: rectangles, diamonds and triangles on the grid,
  // free to touch the outer loop and each other at vertices.
  std::vector<Loop> holed_rectangle(int holes) {
    const int w = uniform(3, 9), h = uniform(3, 9);
    Loop outer;
    const bool dense = uniform(0, 1) == 1;
    const auto side = [&](Vec2 from, double du, double dv, int steps) {
      for (int i = 0; i < steps; ++i)
        if (dense || i == 0) outer.push_back({from.x + du * i, from.y + dv * i});
    };
    side({0, 0}, 1, 0, w);
    side({double(w), 0}, 0, 1, h);
    side({double(w), double(h)}, -1, 0, w);
    side({0, double(h)}, 0, -1, h);
    return with_holes(std::move(outer), holes, w, h);
  }

  // A polygon star-shaped about the origin (convex or not) with up to `holes` holes.
  std::vector<Loop> star(int holes) {
    for (;;) {
      Loop outer;
      const int n = uniform(3, 12);
      for (int i = 0; i < n; ++i) outer.push_back({double(uniform(-6, 6)), double(uniform(-6, 6))});
      const auto upper = [](Vec2 p) { return p.y > 0 || (p.y == 0 && p.x > 0); };
      std::sort(outer.begin(), outer.end(), [&](Vec2 a, Vec2 b) {
        if (upper(a) != upper(b)) return upper(a);
        return orient2d({0, 0}, a, b) > 0;
      });
      bool ok = true;
      for (std::size_t i = 0; i < outer.size(); ++i)
        ok = ok && orient2d(outer[i], outer[(i + 1) % outer.size()], {0, 0}) > 0;
      if (ok) return with_holes(std::move(outer), holes, -6, -6, 6, 6);
    }
  }

 private:
  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  std::vector<Loop> with_holes(Loop outer, int holes, int w, int h) {
    return with_holes(std::move(outer), holes, 0, 0, w, h);
  }
  std::vector<Loop> with_holes(Loop outer, int holes, int u0, int v0, int u1, int v1) {
    std::vector<Loop> loops = {std::move(outer)};
    for (int tries = 0; tries < 60 && int(loops.size()) <= holes; ++tries) {
      loops.push_back(hole(u0, v0, u1, v1));
      if (!TilingCheck(loops).valid()) loops.pop_back();
    }
    return loops;
  }
  Loop hole(int u0, int v0, int u1, int v1) {
    const auto at = [&](int du, int dv) {
      return Vec2{double(uniform(u0, u1 - du)), double(uniform(v0, v1 - dv))};
    };
    Loop l;
    switch (uniform(0, 2)) {
      case 0: {
        const int du = uniform(1, 3), dv = uniform(1, 3);
        const Vec2 p = at(du, dv);
        l = {p, {p.x + du, p.y}, {p.x + du, p.y + dv}, {p.x, p.y + dv}};
        break;
      }
      case 1: {
        const int r = uniform(1, std::min({2, (u1 - u0) / 2, (v1 - v0) / 2}));
        const Vec2 p = at(2 * r, 2 * r);
        l = {{p.x + r, p.y}, {p.x + 2 * r, p.y + r}, {p.x + r, p.y + 2 * r}, {p.x, p.y + r}};
        break;
      }
      default:
        l = {at(0, 0), at(0, 0), at(0, 0)};
    }
    if (uniform(0, 1)) std::reverse(l.begin(), l.end());
    return l;
  }

  std::mt19937 rng_;
};

TEST(TriangulateProperty, RandomPolygonsWithHolesAreTiledExactly) {
#ifdef CELLFORGE_ASAN
  constexpr std::uint32_t kSeeds = 1000;  // the sanitized build is 30-50 times slower
#else
  constexpr std::uint32_t kSeeds = 3000;
#endif
  int holes = 0, cases = 0, touching = 0;
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    RandomPolygons gen(seed);
    for (const auto& loops :
         {gen.holed_rectangle(1 + int(seed % 4)), gen.star(0), gen.star(int(seed % 3))}) {
      const TilingCheck check(loops);
      ASSERT_TRUE(check.valid()) << "seed " << seed << ": " << check.describe();
      const std::string why = check.failure();
      ASSERT_TRUE(why.empty()) << "seed " << seed << ": " << why << "\n" << check.describe();
      holes += int(loops.size()) - 1;
      touching += check.touching() ? 1 : 0;
      ++cases;
    }
  }
  std::printf("%d polygons, %d holes, %d with loops touching at a vertex\n", cases, holes,
              touching);
}

// admesh (Debian package admesh) checks an STL: no disconnected facets, no
// backwards edges, no degenerate facets, one part, positive volume.
TEST(Admesh, AcceptsExportsOfClosedModels) {
  if (std::system("command -v admesh > /dev/null 2>&1") != 0) {
    // test.sh installs admesh (deps/apt-io.txt): in CI its absence is a failure.
    if (std::getenv("CI")) FAIL() << "admesh is not installed but CI is set";
    GTEST_SKIP() << "admesh not installed";
  }
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_io_admesh";
  std::filesystem::create_directories(dir);
  const std::pair<const char*, MeshInput> models[] = {{"cube", testing::unit_cube()},
                                                      {"holed", testing::cube_with_through_hole()}};
  for (const auto& [name, in] : models) {
    const Model m = testing::build(in);
    for (bool binary : {true, false}) {
      const auto path = dir / (std::string(name) + (binary ? "_bin.stl" : "_ascii.stl"));
      ASSERT_OK(io::write_file(m, path.string(), {.stl_binary = binary}));
      const auto log = dir / "admesh.log";
      ASSERT_EQ(std::system(("admesh " + path.string() + " > " + log.string() + " 2>&1").c_str()),
                0);
      std::ifstream in_log(log);
      const std::string text((std::istreambuf_iterator<char>(in_log)), {});
      for (const char* line :
           {"Facets with 1 disconnected edge  :     0", "Facets with 2 disconnected edges :     0",
            "Facets with 3 disconnected edges :     0", "Total disconnected facets        :     0",
            "Number of parts       :     1", "Degenerate facets     :     0",
            "Facets reversed       :     0", "Backwards edges       :     0",
            "Edges fixed           :     0", "Facets removed        :     0"})
        EXPECT_NE(text.find(line), std::string::npos) << path << " lacks '" << line << "'\n"
                                                      << text;
      EXPECT_EQ(text.find("Volume   :  -"), std::string::npos) << text;
    }
  }
}

}  // namespace
}  // namespace cellforge

namespace cellforge {
namespace {

// A triangle with points on one side (other faces' vertices on its edge): every start
// of the loop gives triangles of positive area, none of zero area along that side.
TEST(Triangulate, CollinearRunLeavesNoZeroAreaTriangle) {
  const std::vector<Vec3> corners = {{0, 0, 0}, {8, 0, 0}, {6, 2, 0}, {4, 4, 0}, {2, 6, 0}, {0, 6, 0}};
  for (std::size_t start = 0; start < corners.size(); ++start) {
    std::vector<Vec3> loop(corners.begin() + start, corners.end());
    loop.insert(loop.end(), corners.begin(), corners.begin() + start);
    const auto tris = io::triangulate_polygon({loop}, {0, 0, 1});
    ASSERT_EQ(tris.size(), 4u) << "start " << start;
    for (const auto& t : tris)
      EXPECT_EQ(orient2d(Vec2{loop[t[0]].x, loop[t[0]].y}, Vec2{loop[t[1]].x, loop[t[1]].y},
                         Vec2{loop[t[2]].x, loop[t[2]].y}),
                1)
          << "start " << start << ": (" << t[0] << t[1] << t[2] << ")";
  }
}

}  // namespace
}  // namespace cellforge
