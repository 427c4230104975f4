// The certificate that lets the Boolean skip the pairs of one operand's own triangles
// (boolean::embedded_operands, arrangement.h): granted to closed star-shaped surfaces and prisms,
// refused to everything that could meet itself, and the Booleans it speeds up give
// the results of the full pair test.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "boolean/arrangement.h"
#include "boolean/boolean_test_util.h"
#include "cellforge/boolean/boolean.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/region.h"
#include "cellforge/shape/sweep.h"
#include "cellforge/topo/builder.h"

namespace cellforge::boolean {
namespace {

struct Tiles {
  std::vector<Vec3> pos;
  std::vector<Tri> tris;
};

// A model's faces as triangles (each face's index as its input face).
Tiles tiles_of(const Model& m) {
  Tiles t;
  std::vector<std::uint32_t> id(m.vertex_slots(), 0xffffffffu);
  for (VertexId v : m.vertices()) {
    id[v.value] = static_cast<std::uint32_t>(t.pos.size());
    t.pos.push_back(m.position(v));
  }
  std::uint32_t face = 0;
  for (FaceId f : m.faces()) {
    for (const auto& tri : io::triangulate_face(m, f)) {
      Tri x{{id[tri[0].value], id[tri[1].value], id[tri[2].value]}, 0, face};
      if (m.front_volume(f).is_valid()) std::swap(x.v[1], x.v[2]);  // outward
      t.tris.push_back(x);
    }
    ++face;
  }
  return t;
}

bool embedded(const Tiles& t) {
  std::vector<std::array<std::uint32_t, 2>> joins;
  return embedded_operands(t.pos, t.tris, EdgeUseTable(t.tris, t.pos.size()), {1}, 1, joins)[0];
}

Tiles from(std::vector<Vec3> pos, std::vector<std::array<std::uint32_t, 3>> tris) {
  Tiles t{std::move(pos), {}};
  for (std::uint32_t i = 0; i < tris.size(); ++i) t.tris.push_back({tris[i], 0, i});
  return t;
}

TEST(EmbeddedSurface, PrimitivesAreCertified) {
  Model cube, sphere, cylinder, cone;
  ASSERT_TRUE(shape::make_cube(cube, {.size = {1, 2, 3}}).ok());
  ASSERT_TRUE(shape::make_sphere(sphere, {.r = 10, .faceting = {.fn = 64}}).ok());
  ASSERT_TRUE(shape::make_cylinder(cylinder, {.h = 5, .r1 = 2, .r2 = 2, .faceting = {.fn = 30}}).ok());
  ASSERT_TRUE(shape::make_cylinder(cone, {.h = 5, .r1 = 2, .r2 = 0, .faceting = {.fn = 7}}).ok());
  for (const Model* m : {&cube, &sphere, &cylinder, &cone}) EXPECT_TRUE(embedded(tiles_of(*m)));
}

TEST(EmbeddedSurface, CoplanarNeighboursFromDifferentFacesAreJoined) {
  // A unit cube whose top is two faces (two triangles): one join, the top's diagonal.
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  Tiles t = from(p, {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}});
  for (int side = 0; side < 6; ++side) t.tris[2 * side + 1].input_face = t.tris[2 * side].input_face;
  t.tris[3].input_face = 99;  // the top's second triangle: a face of its own
  std::vector<std::array<std::uint32_t, 2>> joins;
  ASSERT_TRUE(embedded_operands(t.pos, t.tris, EdgeUseTable(t.tris, t.pos.size()), {1}, 1, joins)[0]);
  ASSERT_EQ(joins.size(), 1u);
  EXPECT_EQ(std::min(joins[0][0], joins[0][1]), 2u);
  EXPECT_EQ(std::max(joins[0][0], joins[0][1]), 3u);
}

// Several operands in one soup, sharing corners (two cubes sharing a face, so that
// the face's edges have four uses), one of them no candidate and one a torus.
TEST(EmbeddedSurface, EachOperandIsJudgedOnItsOwnTriangles) {
  Model a, b, torus;
  ASSERT_TRUE(shape::make_cube(a).ok());
  ASSERT_TRUE(shape::make_cube(b, {.size = {1, 1, 1}}).ok());
  ASSERT_TRUE(shape::make_torus(torus, {.major_radius = 5, .minor_radius = 1, .faceting = {.fn = 12}}).ok());
  Tiles all;
  std::vector<std::uint32_t> ids;
  auto add = [&](const Model& m, Vec3 shift, std::uint32_t operand) {
    Tiles t = tiles_of(m);
    for (Tri x : t.tris) {
      for (std::uint32_t& v : x.v) {
        const Vec3 p = t.pos[v] + shift;
        auto it = std::find(all.pos.begin(), all.pos.end(), p);
        v = static_cast<std::uint32_t>(it - all.pos.begin());
        if (it == all.pos.end()) all.pos.push_back(p);
      }
      x.operand = operand;
      x.input_face += 1000 * operand;
      all.tris.push_back(x);
    }
  };
  add(a, {0, 0, 0}, 0);
  add(b, {1, 0, 0}, 1);  // shares a's face x = 1
  add(torus, {0, 0, 10}, 2);
  add(b, {0, 5, 0}, 3);
  std::vector<std::array<std::uint32_t, 2>> joins;
  const std::vector<char> ok =
      embedded_operands(all.pos, all.tris, EdgeUseTable(all.tris, all.pos.size()), {1, 1, 1, 0}, 2, joins);
  EXPECT_EQ(ok, (std::vector<char>{1, 1, 0, 0}));
  EXPECT_TRUE(joins.empty());  // a cube's faces' tiles are joined as faces, not here
}

TEST(EmbeddedSurface, EdgeUsesAreGroupedByEdgeThenTriangle) {
  const Model s = testing::sphere_model(3, 20);
  const Tiles t = tiles_of(s);
  const EdgeUseTable table(t.tris, t.pos.size());
  ASSERT_EQ(table.size(), 3 * t.tris.size());
  // Every triangle's every edge, once, in (p, q) order, each edge's uses by triangle.
  std::vector<std::array<std::uint32_t, 4>> seen;  // p, q, triangle, forward
  std::uint64_t last = 0;
  bool first = true;
  table.each_edge([&](std::uint32_t p, std::uint32_t q, std::span<const EdgeUseTable::Use> uses) {
    EXPECT_LT(p, q);
    const std::uint64_t key = (std::uint64_t{p} << 32) | q;
    EXPECT_TRUE(first || last < key);
    first = false;
    last = key;
    ASSERT_FALSE(uses.empty());
    for (std::size_t i = 1; i < uses.size(); ++i) EXPECT_LT(uses[i - 1].tri(), uses[i].tri());
    for (const EdgeUseTable::Use& u : uses) seen.push_back({p, q, u.tri(), u.forward() ? 1u : 0u});
    const auto found = table.uses(q, p);  // either order
    EXPECT_EQ(found.data(), uses.data());
    EXPECT_EQ(found.size(), uses.size());
  });
  std::vector<std::array<std::uint32_t, 4>> want;
  for (std::uint32_t i = 0; i < t.tris.size(); ++i)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = t.tris[i].v[e], q = t.tris[i].v[(e + 1) % 3];
      want.push_back({std::min(p, q), std::max(p, q), i, p < q ? 1u : 0u});
    }
  std::sort(seen.begin(), seen.end());
  std::sort(want.begin(), want.end());
  EXPECT_EQ(seen, want);
  EXPECT_TRUE(table.uses(0, 0).empty());
  EXPECT_TRUE(table.uses(0, static_cast<std::uint32_t>(t.pos.size()) + 5).empty());
  // No triangles: every row empty (run under UBSan by ./test.sh).
  const EdgeUseTable none(std::span<const Tri>{}, 5);
  EXPECT_EQ(none.size(), 0u);
  none.each_edge([](std::uint32_t, std::uint32_t, std::span<const EdgeUseTable::Use>) { ADD_FAILURE(); });
}

// The table and the certificate made on threads (ranges of triangles, of rows, of
// edges) are the ones made on one: every edge's uses in the same order, the same
// verdicts and the same plane joins, in order. 32,000 triangles: above the size that
// splits the table's ranges; three threads: uneven ranges.
TEST(EmbeddedSurface, ThreadsMakeTheSameTableAndVerdicts) {
  Model sphere, box;
  ASSERT_TRUE(shape::make_sphere(sphere, {.r = 10, .faceting = {.fn = 180}}).ok());
  ASSERT_TRUE(shape::make_cube(box, {.size = {30, 30, 30}}).ok());
  Tiles all = tiles_of(sphere);
  const Tiles b = tiles_of(box);
  const auto base = static_cast<std::uint32_t>(all.pos.size());
  for (Vec3 p : b.pos) all.pos.push_back(p + Vec3{-15, -15, 20});
  for (Tri x : b.tris) {
    for (std::uint32_t& v : x.v) v += base;
    x.operand = 1;
    all.tris.push_back(x);
  }
  // Every triangle a face of its own: a planar face's two tiles, a cube's and the
  // sphere's planar quads', are then neighbours in one plane from different faces (the
  // plane joins, found by ranges of edges on threads).
  for (std::uint32_t t = 0; t < all.tris.size(); ++t) all.tris[t].input_face = t;
  ASSERT_GT(all.tris.size(), 30000u);
  auto listing = [&](int threads) {
    std::vector<std::array<std::uint32_t, 4>> out;  // p, q, triangle, forward
    EdgeUseTable(all.tris, all.pos.size(), threads)
        .each_edge([&](std::uint32_t p, std::uint32_t q, std::span<const EdgeUseTable::Use> uses) {
          for (const EdgeUseTable::Use& u : uses) out.push_back({p, q, u.tri(), u.forward() ? 1u : 0u});
        });
    return out;
  };
  const auto one = listing(1);
  EXPECT_EQ(one.size(), 3 * all.tris.size());
  EXPECT_EQ(listing(2), one);
  EXPECT_EQ(listing(3), one);
  auto verdicts = [&](int threads) {
    std::vector<std::array<std::uint32_t, 2>> joins;
    const std::vector<char> ok =
        embedded_operands(all.pos, all.tris, EdgeUseTable(all.tris, all.pos.size(), threads), {1, 1}, threads, joins);
    return std::pair{ok, joins};
  };
  const auto [ok, joins] = verdicts(1);
  EXPECT_EQ(ok, (std::vector<char>{1, 1}));
  EXPECT_GE(joins.size(), 6u);  // the cube's faces at least
  EXPECT_EQ(verdicts(3), std::pair(ok, joins));
}

TEST(EmbeddedSurface, WhatCouldMeetItselfIsRefused) {
  // A torus: closed and embedded, but no point sees every face from inside.
  Model torus;
  ASSERT_TRUE(shape::make_torus(torus, {.major_radius = 5, .minor_radius = 1, .faceting = {.fn = 12}}).ok());
  EXPECT_FALSE(embedded(tiles_of(torus)));

  // A bipyramid over a band that winds twice around the axis: closed, oriented, every
  // tile facing away from the centre, yet it covers every direction twice.
  std::vector<Vec3> pos{{0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<std::uint32_t, 3>> tris;
  const int m = 5;
  for (int k = 0; k < 2 * m; ++k) {
    const double a = 2 * std::numbers::pi * 2 * k / (2 * m), r = k < m ? 1.0 : 1.5;
    pos.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  for (std::uint32_t k = 0; k < 2 * m; ++k) {
    const std::uint32_t a = 2 + k, b = 2 + (k + 1) % (2 * m);
    tris.push_back({0, a, b});
    tris.push_back({1, b, a});
  }
  EXPECT_FALSE(embedded(from(pos, tris)));

  // An octahedron, certified; with one corner pushed through the opposite face, not.
  std::vector<Vec3> oct{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const std::vector<std::array<std::uint32_t, 3>> faces{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                        {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  EXPECT_TRUE(embedded(from(oct, faces)));
  oct[4] = {0, 0, -1.5};
  EXPECT_FALSE(embedded(from(oct, faces)));

  // Open (one triangle gone), a triangle turned round, a repeated triangle.
  oct[4] = {0, 0, 1};
  auto open = faces;
  open.pop_back();
  EXPECT_FALSE(embedded(from(oct, open)));
  auto turned = faces;
  std::swap(turned[3][0], turned[3][1]);
  EXPECT_FALSE(embedded(from(oct, turned)));
  auto doubled = faces;
  doubled.push_back(faces[0]);
  EXPECT_FALSE(embedded(from(oct, doubled)));
}

// Extrusions of outlines (the second argument, a prism along an axis): a C, a square
// ring, two pieces, an island in a hole, turned a quarter turn; none star-shaped.
// Refused: an island on the solid part of a ring (the caps cover it twice), a square
// in a square, pieces standing on different floors, a prism sheared so that its walls
// lean.
Model extruded(const std::vector<shape::Region>& pieces, double h = 3, double z = 0) {
  Model m;
  for (const shape::Region& r : pieces) {
    EXPECT_TRUE(shape::linear_extrude(m, r, {.height = h}).ok());
  }
  return z == 0 ? std::move(m) : testing::moved(m, shape::Transform::translate({0, 0, z}));
}

shape::Region outline(std::vector<Vec2> outer, std::vector<std::vector<Vec2>> holes = {}) {
  auto r = shape::polygon(std::move(outer), std::move(holes));
  EXPECT_TRUE(r.ok());
  return r.ok() ? *r : shape::Region{};
}

shape::Region square_at(double x, double y, double side) {
  return outline({{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}});
}

TEST(EmbeddedSurface, ExtrusionsOfOutlinesAreCertified) {
  const shape::Region c = outline({{0, 0}, {6, 0}, {6, 1}, {1, 1}, {1, 5}, {6, 5}, {6, 6}, {0, 6}});
  const shape::Region ring = outline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{2, 2}, {2, 8}, {8, 8}, {8, 2}}});
  const Model c_prism = extruded({c});
  const Model ring_prism = extruded({ring});
  const Model two = extruded({c, square_at(20, 0, 2)});
  const Model island = extruded({ring, square_at(4, 4, 2)});
  const Model turned = testing::moved(extruded({c}, 3, -1.5), shape::Transform::rotate_xyz({90, 0, 90}));
  for (const Model* m : {&c_prism, &ring_prism, &two, &island, &turned}) EXPECT_TRUE(embedded(tiles_of(*m)));

  // The star test certifies none of them: with one top corner moved across by 1e-7
  // (its walls no longer vertical, and as star-shaped as before but for that sliver),
  // each is refused.
  for (const Model* m : {&c_prism, &ring_prism, &two, &island}) {
    Tiles t = tiles_of(*m);
    for (Vec3& p : t.pos)
      if (p.z == 3 && p.x == 0 && p.y == 0) p.x = 1e-7;
    EXPECT_FALSE(embedded(t));
  }
  // Pieces of different heights, and the C with one top corner lifted: the top is a
  // heightfield over the floor, not a plane, and that is certified too.
  Model other_heights = extruded({c});
  ASSERT_TRUE(shape::linear_extrude(other_heights, square_at(20, 0, 2), {.height = 4}).ok());
  EXPECT_TRUE(embedded(tiles_of(other_heights)));
  Tiles lifted = tiles_of(c_prism);
  for (Vec3& p : lifted.pos)
    if (p.z == 3 && p.x == 0 && p.y == 0) p.z = 3.5;
  EXPECT_TRUE(embedded(lifted));
}

TEST(EmbeddedSurface, PrismsThatCouldMeetThemselvesAreRefused) {
  const shape::Region ring = outline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{2, 2}, {2, 8}, {8, 8}, {8, 2}}});
  // An island on the ring's solid part: every cap passes its own faces' test, the two
  // caps' outlines are apart, and yet the island's caps lie on the ring's.
  EXPECT_FALSE(embedded(tiles_of(extruded({ring, square_at(0.5, 0.5, 1)}))));
  // A square inside a square, no hole.
  EXPECT_FALSE(embedded(tiles_of(extruded({square_at(0, 0, 10), square_at(4, 4, 2)}))));
  // A piece whose floor is not the others' (a heightfield needs one flat floor).
  Model other_floors = extruded({ring});
  ASSERT_TRUE(shape::linear_extrude(other_floors, square_at(20, 0, 2), {.height = 4}).ok());
  Tiles raised = tiles_of(other_floors);
  for (Vec3& p : raised.pos)
    if (p.x >= 20) p.z += 1;
  EXPECT_FALSE(embedded(raised));
  // The C sheared: its top moved along x, its walls leaning.
  const shape::Region c = outline({{0, 0}, {6, 0}, {6, 1}, {1, 1}, {1, 5}, {6, 5}, {6, 6}, {0, 6}});
  Tiles sheared = tiles_of(extruded({c}));
  for (Vec3& p : sheared.pos)
    if (p.z == 3) p.x += 0.5;
  EXPECT_FALSE(embedded(sheared));
}

// The certificate against the definition, on 1,000 seeded random operands: one to three
// pieces on a coarse grid (rectangles, some with a rectangular hole, small squares
// that often fall on or in them, and polygons around a centre), extruded to one height, their points welded as the soup welds
// them. Whenever the certificate is granted, no two triangles may meet but in the
// corners and edges they share (checked pair by pair, exactly); and it must be
// granted to most of the operands that are so.
Tiles welded(const Tiles& t) {
  Tiles out;
  std::vector<std::uint32_t> id(t.pos.size());
  for (std::size_t i = 0; i < t.pos.size(); ++i) {
    const auto it = std::find(out.pos.begin(), out.pos.end(), t.pos[i]);
    id[i] = static_cast<std::uint32_t>(it - out.pos.begin());
    if (it == out.pos.end()) out.pos.push_back(t.pos[i]);
  }
  for (Tri x : t.tris) {
    for (std::uint32_t& v : x.v) v = id[v];
    out.tris.push_back(x);
  }
  return out;
}

bool meet_only_where_shared(const Tiles& t) {
  const auto& p = t.pos;
  for (std::size_t i = 0; i < t.tris.size(); ++i)
    for (std::size_t j = i + 1; j < t.tris.size(); ++j) {
      const auto &a = t.tris[i].v, &b = t.tris[j].v;
      const Vec3 pa[3] = {p[a[0]], p[a[1]], p[a[2]]}, pb[3] = {p[b[0]], p[b[1]], p[b[2]]};
      std::vector<int> ia, ib;  // places of the shared corners in a and in b
      for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
          if (a[x] == b[y]) ia.push_back(x), ib.push_back(y);
      if (ia.empty()) {
        if (triangles_meet(pa, pb)) return false;
      } else if (ia.size() == 1) {
        // Each one's edge away from the shared corner misses the other.
        if (segment_meets_triangle(pa[(ia[0] + 1) % 3], pa[(ia[0] + 2) % 3], pb) ||
            segment_meets_triangle(pb[(ib[0] + 1) % 3], pb[(ib[0] + 2) % 3], pa))
          return false;
      } else if (ia.size() == 2) {
        // In one plane, the third corners on the two sides of the shared edge.
        const Vec3 c = pb[3 - ib[0] - ib[1]];
        if (orient3d(pa[0], pa[1], pa[2], c) == 0) {
          const Vec3 e0 = pa[ia[0]], e1 = pa[ia[1]], d = pa[3 - ia[0] - ia[1]];
          int k = 0;
          while (k < 3 && orient2d_projected(pa[0], pa[1], pa[2], k) == 0) ++k;
          if (orient2d_projected(e0, e1, c, k) == orient2d_projected(e0, e1, d, k)) return false;
        }
      } else {
        return false;
      }
    }
  return true;
}

TEST(EmbeddedSurface, RandomPrismsAreCertifiedOnlyWhenEmbedded) {
  std::mt19937 rng(20261207);
  auto coord = [&](int n) { return static_cast<double>(std::uniform_int_distribution<int>(0, n)(rng)); };
  int granted = 0, embedded_cases = 0;
  const int cases = 1000;
  for (int c = 0; c < cases; ++c) {
    Model m;
    const int pieces = std::uniform_int_distribution<int>(1, 3)(rng);
    for (int k = 0; k < pieces; ++k) {
      shape::Region r;
      const int kind = static_cast<int>(rng() % 3);
      if (kind == 0) {
        // A small square, often on or in a bigger piece.
        const double x = 1 + coord(7), y = 1 + coord(7), w = 1 + coord(1);
        r = *shape::polygon({{x, y}, {x + w, y}, {x + w, y + w}, {x, y + w}});
      } else if (kind == 1) {
        const double x = coord(6), y = coord(6), w = 1 + coord(8), h = 1 + coord(8);
        std::vector<std::vector<Vec2>> holes;
        if (w >= 3 && h >= 3 && rng() % 2 == 0) holes.push_back({{x + 1, y + 1}, {x + w - 1, y + 1}, {x + w - 1, y + h - 1}, {x + 1, y + h - 1}});
        auto made = shape::polygon({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, holes);
        if (!made.ok()) continue;
        r = *made;
      } else {
        // Corners at increasing angles about a centre, at radii 1 to 4: simple.
        const double cx = coord(10), cy = coord(10);
        const int n = std::uniform_int_distribution<int>(3, 9)(rng);
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i) {
          const double a = 2 * std::numbers::pi * (i + 0.25 * (rng() % 4)) / n, rad = 1 + coord(3);
          pts.push_back({std::round(4 * (cx + rad * std::cos(a))) / 4, std::round(4 * (cy + rad * std::sin(a))) / 4});
        }
        auto made = shape::polygon(pts);
        if (!made.ok()) continue;
        r = *made;
      }
      ASSERT_TRUE(shape::linear_extrude(m, r, {.height = 2}).ok());
    }
    if (m.num_faces() == 0) continue;
    const Tiles t = welded(tiles_of(m));
    const bool truth = meet_only_where_shared(t);
    const bool verdict = embedded(t);
    EXPECT_TRUE(truth || !verdict) << "case " << c << ": certified, but two triangles meet";
    embedded_cases += truth;
    granted += verdict;
  }
  RecordProperty("embedded", embedded_cases);
  RecordProperty("granted", granted);
  EXPECT_GT(embedded_cases, cases / 4);
  EXPECT_GT(granted * 10, embedded_cases * 9) << granted << " of " << embedded_cases;
}

// Heightfields (surface()'s solids: a flat floor, vertical walls, a top over the floor)
// against the definition, on 1,000 seeded random grids of 2 to 5 cells a side: heights
// 1 to 3 (now and then 0, on the floor), inner top corners moved across by up to 1.2
// (some of the tops then fold over themselves), sometimes turned upside down.
TEST(EmbeddedSurface, RandomHeightfieldsAreCertifiedOnlyWhenEmbedded) {
  std::mt19937 rng(42);
  int granted = 0, embedded_cases = 0, folded = 0;
  for (int c = 0; c < 1000; ++c) {
    const int n = 2 + static_cast<int>(rng() % 4), m = 2 + static_cast<int>(rng() % 4);
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (m + 1) + j); };
    const auto top = static_cast<std::uint32_t>((n + 1) * (m + 1));
    std::vector<Vec3> pos(2 * top);
    const double moves[] = {0, 0, 0.3, -0.3, 0.6, -0.6, 1.2, -1.2};
    const bool flip = rng() % 4 == 0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= m; ++j) {
        const bool inner = i > 0 && i < n && j > 0 && j < m;
        const double h = rng() % 20 == 0 ? 0.0 : 1.0 + static_cast<double>(rng() % 3);
        const double dx = inner ? moves[rng() % 8] : 0, dy = inner ? moves[rng() % 8] : 0;
        pos[at(i, j)] = {double(i), double(j), 0};
        pos[top + at(i, j)] = {i + dx, j + dy, flip ? -h : h};
      }
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const std::uint32_t a = at(i, j), b = at(i + 1, j), d = at(i + 1, j + 1), e = at(i, j + 1);
        tris.push_back({top + a, top + b, top + d});
        tris.push_back({top + a, top + d, top + e});
        tris.push_back({a, d, b});
        tris.push_back({a, e, d});
      }
    // The boundary counterclockwise seen from +z, each edge's wall facing out.
    std::vector<std::uint32_t> ring;
    for (int i = 0; i < n; ++i) ring.push_back(at(i, 0));
    for (int j = 0; j < m; ++j) ring.push_back(at(n, j));
    for (int i = n; i > 0; --i) ring.push_back(at(i, m));
    for (int j = m; j > 0; --j) ring.push_back(at(0, j));
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const std::uint32_t p = ring[k], q = ring[(k + 1) % ring.size()];
      tris.push_back({p, q, top + q});
      tris.push_back({p, top + q, top + p});
    }
    if (flip)  // mirrored in z = 0: every triangle turned round to face out again
      for (auto& t : tris) std::swap(t[1], t[2]);
    const Tiles t = from(pos, tris);
    const bool truth = meet_only_where_shared(t);
    const bool verdict = embedded(t);
    EXPECT_TRUE(truth || !verdict) << "case " << c << ": certified, but two triangles meet";
    embedded_cases += truth;
    folded += !truth;
    granted += verdict;
  }
  RecordProperty("embedded", embedded_cases);
  RecordProperty("granted", granted);
  EXPECT_GT(folded, 50);
  EXPECT_GT(granted * 2, embedded_cases) << granted << " of " << embedded_cases;
}

// The Boolean of certified operands tests no pair of one operand's triangles, and
// gives the result it gives when the same operands are not certified (each one a
// model with a far-away tetrahedron of its own beside it: two shells).
Model with_far_tetrahedron(const Model& m, double at) {
  MeshInput in;
  std::vector<std::uint32_t> id(m.vertex_slots());
  for (VertexId v : m.vertices()) {
    id[v.value] = static_cast<std::uint32_t>(in.positions.size());
    in.positions.push_back(m.position(v));
  }
  for (FaceId f : m.faces()) {
    MeshFace mf{.loops = {}, .front = m.front_volume(f).is_valid() ? 0 : -1,
                .back = m.back_volume(f).is_valid() ? 0 : -1};
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      auto& loop = mf.loops.emplace_back();
      for (VertexId v : m.loop_vertices(l)) loop.push_back(id[v.value]);
    }
    in.faces.push_back(std::move(mf));
  }
  const auto n = static_cast<std::uint32_t>(in.positions.size());
  for (Vec3 p : {Vec3{at, at, at}, Vec3{at + 1, at, at}, Vec3{at, at + 1, at}, Vec3{at, at, at + 1}})
    in.positions.push_back(p);
  for (std::array<std::uint32_t, 3> t : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})
    in.faces.push_back({.loops = {{n + t[0], n + t[1], n + t[2]}}, .back = 1});
  in.volumes = 2;
  return testing::build(in);
}

// A thick arc from 30 to 330 degrees (a C of 2 x 48 corners), extruded 4 along z.
Model arc_prism() {
  std::vector<Vec2> pts;
  const int n = 48;
  for (int i = 0; i <= n; ++i) {
    const double a = (30 + 300.0 * i / n) * std::numbers::pi / 180;
    pts.push_back({10 * std::cos(a), 10 * std::sin(a)});
  }
  for (int i = n; i >= 0; --i) {
    const double a = (30 + 300.0 * i / n) * std::numbers::pi / 180;
    pts.push_back({7 * std::cos(a), 7 * std::sin(a)});
  }
  return extruded({outline(pts)}, 4);
}

TEST(EmbeddedSurface, BooleansWithAndWithoutTheCertificateAgree) {
  const Model sphere = testing::sphere_model(10, 24);
  const Model arc = arc_prism();
  const Model cylinder = testing::cylinder_model(4, 30, 17, {0.5, 0.25, -15});
  const Model across = testing::cylinder_model(2, 10, 17, {-8.5, 0.25, -3});  // through the C's back
  ASSERT_TRUE(embedded(tiles_of(arc)));
  const double tetra = 1.0 / 6.0;
  for (auto [a, b] : {std::pair{&sphere, &cylinder}, std::pair{&arc, &across}}) {
    const Model a2 = with_far_tetrahedron(*a, 100), b2 = with_far_tetrahedron(*b, 200);
    for (Op op : {Op::kUnion, Op::kIntersection, Op::kDifference}) {
      const testing::BoolCase fast = testing::run(op, {a, b}, false);
      const testing::BoolCase slow = testing::run(op, {&a2, &b2}, false);
      EXPECT_LT(fast.result.report.candidate_pairs * 3, slow.result.report.candidate_pairs) << to_string(op);
      // The tetrahedra add themselves to the union (both) and the difference (a's).
      const int extra = op == Op::kUnion ? 2 : (op == Op::kDifference ? 1 : 0);
      EXPECT_NEAR(slow.volume - fast.volume, extra * tetra, 1e-9) << to_string(op);
      EXPECT_EQ(fast.faces + 4u * extra, slow.faces) << to_string(op);
      EXPECT_EQ(fast.vertices + 4u * extra, slow.vertices) << to_string(op);
      EXPECT_EQ(fast.edges + 6u * extra, slow.edges) << to_string(op);
      EXPECT_EQ(fast.result.report.rounding_self_intersections, slow.result.report.rounding_self_intersections);
    }
  }
}

}  // namespace
}  // namespace cellforge::boolean
