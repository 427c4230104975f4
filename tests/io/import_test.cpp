// Import: exact welding by default, tolerance welding by option, merging of
// coplanar triangles into polygons with holes.
#include <gtest/gtest.h>

#include "cellforge/io/diagnose.h"
#include "cellforge/topo/dump.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

io::PolygonSoup two_triangles(double gap) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1 + gap, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.polygons = {{0, 1, 2}, {3, 4, 5}};
  return soup;
}

TEST(Import, WeldsExactlyByDefault) {
  Model m;
  auto r = io::import_soup(m, two_triangles(1e-12), {});
  ASSERT_OK(r);
  EXPECT_EQ(m.num_vertices(), 5u);  // (0,1,0) welds, (1,0,0) and (1+1e-12,0,0) do not
  EXPECT_EQ(r->report.welded_vertices, 5u);
  Model zero;
  ASSERT_OK(io::import_soup(zero, two_triangles(0), {}));
  EXPECT_EQ(zero.num_vertices(), 4u);
}

TEST(Import, WeldToleranceJoinsNearPositions) {
  Model m;
  auto r = io::import_soup(m, two_triangles(1e-7), {.weld_tolerance = 1e-6});
  ASSERT_OK(r);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.num_edges(), 5u);  // the diagonal is shared
  EXPECT_VALID(m);
  Model far;
  ASSERT_OK(io::import_soup(far, two_triangles(1e-5), {.weld_tolerance = 1e-6}));
  EXPECT_EQ(far.num_vertices(), 5u);
}

TEST(Import, NegativeZeroWeldsWithZero) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, -0.0}, {0, -1, 0}};
  soup.polygons = {{0, 1, 2}, {3, 4, 1}};
  Model m;
  ASSERT_OK(io::import_soup(m, soup, {}));
  EXPECT_EQ(m.num_vertices(), 4u);
}

TEST(Import, MergesSplitCubeFacesBackIntoSquares) {
  const Model m = testing::read_fixture("cube_split.obj", {.import = {.merge_coplanar = true}});
  EXPECT_EQ(m.num_faces(), 6u);
  EXPECT_EQ(m.num_edges(), 12u);
  EXPECT_EQ(m.num_vertices(), 8u);  // the face centres are gone
  EXPECT_EQ(m.num_volumes(), 1u);
  EXPECT_VALID(m);
  const Model unmerged = testing::read_fixture("cube_split.obj");
  EXPECT_EQ(unmerged.num_faces(), 24u);
}

TEST(Import, MergeMakesAFaceWithAHole) {
  // The square sheet with a hole, triangulated and merged back.
  const Model sheet = testing::build(testing::square_sheet_with_hole());
  const Model back =
      testing::round_trip(sheet, io::Format::kStl, {}, {.import = {.merge_coplanar = true}});
  ASSERT_EQ(back.num_faces(), 1u);
  EXPECT_EQ(back.inner_loop_count(*back.faces().begin()), 1u);
  EXPECT_EQ(canonical_dump(back), canonical_dump(sheet));
}

TEST(Import, MergeKeepsFoldsAndNonPlanarNeighboursApart) {
  io::PolygonSoup soup;  // two triangles folded along the x axis: not coplanar
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 1e-300}};
  soup.polygons = {{0, 1, 2}, {1, 0, 3}};
  Model m;
  ASSERT_OK(io::import_soup(m, soup, {.merge_coplanar = true}));
  EXPECT_EQ(m.num_faces(), 2u);
  soup.positions[3] = {0, -1, 0};
  Model flat;
  ASSERT_OK(io::import_soup(flat, soup, {.merge_coplanar = true}));
  EXPECT_EQ(flat.num_faces(), 1u);
}

TEST(Import, VolumesNoneGivesSheets) {
  const Model m =
      testing::read_fixture("cube_binary.stl", {.import = {.volumes = io::VolumeMode::kNone}});
  EXPECT_EQ(m.num_volumes(), 0u);
  EXPECT_TRUE(io::diagnose(m).closed);
}

TEST(Import, GroupNameFromFileOrOption) {
  const Model m = testing::read_fixture("cube_ascii.stl");
  EXPECT_EQ(m.name(*m.groups().begin()), "cube_ascii");
  const Model named = testing::read_fixture("cube_ascii.stl", {.import = {.group_name = "part"}});
  EXPECT_EQ(named.name(*named.groups().begin()), "part");
}

}  // namespace
}  // namespace cellforge
