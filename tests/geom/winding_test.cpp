// Point in solid (winding.h): winding numbers of closed triangle surfaces, exact in
// every degenerate position of the ray, and the nesting of shells.
#include "cellforge/geom/winding.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

namespace cellforge {
namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// The box [lo, hi] as 12 triangles, counterclockwise seen from outside (or inward),
// its corners appended to points.
void add_box(std::vector<Vec3>& points, Triangles& tris, Vec3 lo, Vec3 hi, bool inward = false) {
  const auto base = static_cast<std::uint32_t>(points.size());
  for (int i = 0; i < 8; ++i)
    points.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    std::array<std::uint32_t, 3> a{base + q[0], base + q[1], base + q[2]};
    std::array<std::uint32_t, 3> b{base + q[0], base + q[2], base + q[3]};
    if (inward) std::swap(a[1], a[2]), std::swap(b[1], b[2]);
    tris.push_back(a);
    tris.push_back(b);
  }
}

TEST(Winding, InsideOutsideAndOrientation) {
  std::vector<Vec3> pts;
  Triangles tris;
  add_box(pts, tris, {0, 0, 0}, {2, 2, 2});
  EXPECT_EQ(winding_number(pts, tris, {1, 1, 1}).number, 1);
  EXPECT_EQ(winding_number(pts, tris, {3, 1, 1}).number, 0);
  EXPECT_EQ(winding_number(pts, tris, {-1, 1, 1}).number, 0);
  EXPECT_FALSE(winding_number(pts, tris, {1, 1, 1}).on_surface);
  std::vector<Vec3> in_pts;
  Triangles in_tris;
  add_box(in_pts, in_tris, {0, 0, 0}, {2, 2, 2}, true);
  EXPECT_EQ(winding_number(in_pts, in_tris, {1, 1, 1}).number, -1);
}

// The ray from these points runs exactly along edges, through vertices and in the
// planes of faces: the perturbation must still count each crossing once.
TEST(Winding, DegenerateRaysCountOnce) {
  std::vector<Vec3> pts;
  Triangles tris;
  add_box(pts, tris, {0, 0, 0}, {2, 2, 2});
  // y = 1, z = 1 crosses the diagonal edges of the x = 2 face's triangles.
  EXPECT_EQ(winding_number(pts, tris, {1, 1, 1}).number, 1);
  // Along the plane y = 0 (a face's plane) and through the edge z = 0, y = 0.
  const Winding on_edge = winding_number(pts, tris, {1, 0, 0});
  EXPECT_TRUE(on_edge.on_surface);
  // Through the cube's vertices from outside, at their height: 0 either way.
  EXPECT_EQ(winding_number(pts, tris, {-5, 2, 2}).number, 0);
  EXPECT_EQ(winding_number(pts, tris, {-5, 0, 0}).number, 0);
  EXPECT_EQ(winding_number(pts, tris, {-5, 1, 2}).number, 0);
  // On a face: reported as on the surface, winding of a point beside it (0 or 1).
  const Winding face = winding_number(pts, tris, {2, 1, 1});
  EXPECT_TRUE(face.on_surface);
  EXPECT_TRUE(face.number == 0 || face.number == 1);
}

// Against a direct test on a box, at random points of a grid that puts many of them
// on the box's planes and on the rays through its edges.
TEST(Winding, AgreesWithBoxTestOnGridPoints) {
  std::vector<Vec3> pts;
  Triangles tris;
  add_box(pts, tris, {-1, -1, -1}, {1, 1, 1});
  std::mt19937 rng(19);
  std::uniform_int_distribution<int> coord(-3, 3);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{coord(rng) * 0.5, coord(rng) * 0.5, coord(rng) * 0.5};
    const bool inside = std::abs(p.x) < 1 && std::abs(p.y) < 1 && std::abs(p.z) < 1;
    const bool boundary = !inside && std::abs(p.x) <= 1 && std::abs(p.y) <= 1 && std::abs(p.z) <= 1;
    const Winding w = winding_number(pts, tris, p);
    EXPECT_EQ(w.on_surface, boundary) << p.x << " " << p.y << " " << p.z;
    if (!boundary) {
      EXPECT_EQ(w.number, inside ? 1 : 0) << p.x << " " << p.y << " " << p.z;
    }
  }
}

TEST(Winding, NestingOfShells) {
  std::vector<Vec3> pts;
  Triangles tris;
  std::vector<std::uint32_t> surface;
  const auto add = [&](Vec3 lo, Vec3 hi, bool inward, std::uint32_t s) {
    add_box(pts, tris, lo, hi, inward);
    surface.resize(tris.size(), s);
  };
  add({0, 0, 0}, {10, 10, 10}, false, 0);
  add({2, 2, 2}, {8, 8, 8}, true, 1);
  add({4, 4, 4}, {6, 6, 6}, false, 2);
  add({20, 0, 0}, {21, 1, 1}, false, 3);  // beside the others
  add({0, 0, 0}, {1, 1, 1}, false, 4);    // inside 0, touching it at a corner and 3 faces
  const Nesting n = nest_surfaces(pts, tris, surface, 5);
  EXPECT_EQ(n.depth, (std::vector<std::uint32_t>{0, 1, 2, 0, 1}));
  EXPECT_EQ(n.parent[0], Nesting::kNone);
  EXPECT_EQ(n.parent[1], 0u);
  EXPECT_EQ(n.parent[2], 1u);
  EXPECT_EQ(n.parent[3], Nesting::kNone);
  EXPECT_EQ(n.parent[4], 0u);
  // Only marked containers contain.
  const Nesting only_outer =
      nest_surfaces(pts, tris, surface, 5, {true, false, false, false, false});
  EXPECT_EQ(only_outer.parent[2], 0u);
  EXPECT_EQ(only_outer.depth[2], 1u);
}

}  // namespace
}  // namespace cellforge
