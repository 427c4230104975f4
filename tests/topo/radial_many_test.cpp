// The radial order of an edge with many face uses (sort_by_direction in
// topo/radial.cpp, taken above 16 uses): the same order as the pairwise comparison,
// checked use by use with radially_ordered and validate.
#include <gtest/gtest.h>

#include <cmath>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/validate.h"
#include "topo/model_editor.h"

namespace cellforge {
namespace {

// Triangles on the edge (0,0,0)-(0,0,1), each with a third point from `thirds`
// (index k % thirds.size()), every third one reversed.
MeshInput fan(const std::vector<Vec3>& thirds, int triangles) {
  MeshInput in;
  in.positions = {{0, 0, 0}, {0, 0, 1}};
  for (const Vec3& p : thirds) in.positions.push_back(p);
  for (int k = 0; k < triangles; ++k) {
    const auto c = static_cast<std::uint32_t>(2 + k % thirds.size());
    MeshFace f;
    f.loops = {k % 3 == 0 ? std::vector<std::uint32_t>{1, 0, c}
                          : std::vector<std::uint32_t>{0, 1, c}};
    in.faces.push_back(f);
  }
  return in;
}

EdgeId axis_edge(const Model& m) {
  for (EdgeId e : m.edges()) {
    const Vec3 a = m.position(m.start_of(e)), b = m.position(m.end_of(e));
    if (a.x == 0 && a.y == 0 && b.x == 0 && b.y == 0) return e;
  }
  return EdgeId();
}

TEST(RadialMany, CopiesAndTiesKeepThePairwiseOrder) {
  // Seven directions, two of them at the same angle with different lengths (a tie
  // of different directions), 200 uses: copies, reversed copies and the tie.
  const std::vector<Vec3> thirds = {{1, 0, 0.5}, {0, 1, 0.2}, {-1, 0, 0.7}, {0, -1, 0.1},
                                    {2, 0, 0.5}, {1, 1, 0.3}, {-1, -1, 0.9}};
  for (int triangles : {16, 17, 200}) {
    Model m;
    auto r = build_mesh(m, fan(thirds, triangles));
    ASSERT_TRUE(r.ok()) << r.error().message;
    const EdgeId e = axis_edge(m);
    ASSERT_TRUE(e.is_valid());
    std::vector<EdgeUseId> cycle;
    for (EdgeUseId u : m.radial(e)) cycle.push_back(u);
    ASSERT_EQ(cycle.size(), static_cast<std::size_t>(triangles));
    EXPECT_TRUE(radially_ordered(m, e, cycle)) << triangles << " uses";
    EXPECT_TRUE(validate(m).empty()) << triangles << " uses";
    // Sorting the sorted cycle again gives a cycle as ordered, whichever path sorts.
    EXPECT_TRUE(radially_ordered(m, e, sort_radially(m, e, cycle)));
  }
}

TEST(RadialMany, IdenticalTrianglesSortOnce) {
  // 20,000 copies of one triangle: one direction; the cycle is every use, valid.
  MeshInput in = fan({{1, 0, 0}}, 20000);
  Model m;
  ASSERT_TRUE(build_mesh(m, in).ok());
  const EdgeId e = axis_edge(m);
  std::vector<EdgeUseId> cycle;
  for (EdgeUseId u : m.radial(e)) cycle.push_back(u);
  EXPECT_EQ(cycle.size(), 20000u);
  EXPECT_TRUE(radially_ordered(m, e, cycle));
}

}  // namespace
}  // namespace cellforge
