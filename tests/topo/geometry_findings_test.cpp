// check_geometry: crossing loops and non-planar faces are found exactly and named by
// id, each in its own list; the fixtures, whose faces are planar and simple, give
// none; a loop that passes a vertex twice (a pinched face) is not a crossing.
#include <gtest/gtest.h>

#include <cmath>

#include "cellforge/topo/validate.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

TEST(CheckGeometry, FixturesHaveNoFindings) {
  for (MeshInput (*make)() : {unit_cube, cube_with_through_hole, two_cubes_sharing_edge, book,
                              cube_with_dangling_face, square_sheet_with_hole}) {
    const Model m = build(make());
    const GeometryFindings g = check_geometry(m);
    EXPECT_TRUE(g.crossings.empty()) << to_string(g.crossings);
    EXPECT_TRUE(g.non_planar.empty()) << to_string(g.non_planar);
  }
}

TEST(CheckGeometry, BowTieLoopCrossesItself) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}});
  const Model m = build(in);
  const GeometryFindings g = check_geometry(m);
  ASSERT_EQ(g.crossings.size(), 1u);
  EXPECT_EQ(g.crossings[0].check, "crossing");
  EXPECT_NE(g.crossings[0].message.find("f0"), std::string::npos) << g.crossings[0].message;
  EXPECT_TRUE(g.non_planar.empty());
}

TEST(CheckGeometry, TouchingByOneUlpIsDecidedExactly) {
  // A loop whose vertex (1, 0.5) lies exactly on an edge from (2, 0) to (0, 1)
  // touches itself; moved one ulp away from the edge, it does not.
  for (const double x : {1.0, std::nextafter(1.0, 0.0)}) {
    MeshInput in;
    add_face(in, {{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0.75, 0}, {x, 0.5, 0}, {0, 0.25, 0}}});
    const GeometryFindings g = check_geometry(build(in));
    EXPECT_EQ(g.crossings.size(), x == 1.0 ? 1u : 0u) << x;
  }
}

TEST(CheckGeometry, NonPlanarFaceIsAFindingOfItsOwn) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 0, 0}, {1, 1, std::ldexp(1.0, -60)}, {0, 1, 0}}});
  const Model m = build(in);
  EXPECT_TRUE(validate(m).empty()) << to_string(validate(m));  // topology is fine
  const GeometryFindings g = check_geometry(m);
  ASSERT_EQ(g.non_planar.size(), 1u);
  EXPECT_EQ(g.non_planar[0].check, "planarity");
  EXPECT_NE(g.non_planar[0].message.find("f0 is not planar"), std::string::npos);
  EXPECT_TRUE(g.crossings.empty());
}

TEST(CycleRanges, AgreeWithTheStepByStepWalks) {
  const Model m = build(book());
  for (EdgeId e : m.edges()) {
    std::size_t n = 0;
    EdgeUseId expect = m.first_use(e);
    for (EdgeUseId u : m.radial(e)) {
      EXPECT_EQ(u, expect);
      expect = m.radial_next(u);
      ++n;
    }
    EXPECT_EQ(n, m.use_count(e));
    if (n > 0) {
      EXPECT_EQ(expect, m.first_use(e));  // the walk went once round
    }
  }
  for (VertexId v : m.vertices()) {
    std::size_t n = 0;
    for (EdgeEnd end : m.ends_around(v)) {
      EXPECT_EQ(m.vertex_of(end.edge, end.end), v);
      ++n;
    }
    EXPECT_EQ(n, m.degree(v));
  }
  for (FaceId f : m.faces()) {
    std::size_t loops = 0;
    for (LoopId l : m.loops_of(f)) {
      ++loops;
      std::size_t n = 0;
      for (EdgeUseId u : m.uses_of(l)) {
        EXPECT_EQ(m.face_of(u), f);
        ++n;
      }
      EXPECT_EQ(n, m.loop_length(l));
    }
    EXPECT_EQ(loops, 1 + m.inner_loop_count(f));
  }
}

}  // namespace
}  // namespace cellforge
