// snapshot / restore: lossless on every fixture and Euler example (the snapshot is
// a fixed point, so edge directions, loop starts and radial order all survive), and refused
// with the offending row named when the tables are inconsistent.
#include "cellforge/topo/snapshot.h"

#include <gtest/gtest.h>

#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

void expect_round_trip(const Model& m) {
  auto back = restore(snapshot(m));
  ASSERT_OK(back);
  EXPECT_TRUE(snapshot(*back) == snapshot(m));
  EXPECT_EQ(canonical_dump(*back), canonical_dump(m));
}

TEST(Snapshot, RoundTripsEveryFixture) {
  for (auto make : {unit_cube, cube_with_through_hole, two_cubes_sharing_edge,
                    two_cubes_sharing_vertex, cube_with_dangling_face, cube_with_wire_and_point,
                    book, two_cubes_sharing_face, square_sheet_with_hole}) {
    expect_round_trip(build(make()));
  }
  Model m;
  ASSERT_OK(euler_nonmanifold_example(m));
  expect_round_trip(m);
  Model point;  // a point loop survives
  ASSERT_OK(mvsf(point, make_group(point, "p"), {1, 2, 3}));
  expect_round_trip(point);
}

TEST(Snapshot, InconsistentTablesAreRefused) {
  Snapshot s = snapshot(build(unit_cube()));
  s.uses[5].edge = 99;
  auto r = restore(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("edge use 5"), std::string::npos) << r.error().message;

  s = snapshot(build(unit_cube()));
  std::swap(s.uses[0].edge, s.uses[4].edge);  // keys fine, topology broken
  r = restore(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("invalid"), std::string::npos) << r.error().message;
}

TEST(Snapshot, ACellWithoutFacesIsRefused) {
  // Found by the JSON fuzzer: a group with one 3-cell and nothing else.
  Snapshot s;
  s.groups.push_back({"a"});
  s.cells.push_back(0);
  auto r = restore(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("c0 is bounded by no face"), std::string::npos)
      << r.error().message;
}

}  // namespace
}  // namespace cellforge
