// Round trips through every format, and STL's binary/ASCII detection.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cellforge/io/diagnose.h"
#include "cellforge/topo/dump.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/snapshot.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using io::Format;
using testing::round_trip;

struct Counts {
  std::size_t v, e, f, c;
  friend bool operator==(const Counts&, const Counts&) = default;
};
Counts counts(const Model& m) {
  return {m.num_vertices(), m.num_edges(), m.num_faces(), m.num_volumes()};
}
std::ostream& operator<<(std::ostream& os, const Counts& c) {
  return os << c.v << "v " << c.e << "e " << c.f << "f " << c.c << "c";
}

TEST(Json, RoundTripIsLosslessOnEveryFixture) {
  for (const MeshInput& in :
       {testing::unit_cube(), testing::cube_with_through_hole(), testing::two_cubes_sharing_edge(),
        testing::two_cubes_sharing_vertex(), testing::cube_with_dangling_face(),
        testing::cube_with_wire_and_point(), testing::book(), testing::two_cubes_sharing_face(),
        testing::square_sheet_with_hole()}) {
    const Model m = testing::build(in);
    const Model back = round_trip(m, Format::kJson);
    EXPECT_VALID(back);
    EXPECT_EQ(canonical_dump(back), canonical_dump(m));
    EXPECT_EQ(snapshot(back), snapshot(m));
  }
}

TEST(Json, KeepsEulerExamplesGroupNamesAttributesAndSurfaces) {
  Model m;
  ASSERT_OK(euler_box_with_hole(m, {0, 0, 0}, {3, 3, 3}, 1, 2, "holed \"box\"\n"));
  auto g = euler_nonmanifold_example(m, "caf\xC3\xA9");
  ASSERT_OK(g);
  m.set_attribute(*g, "kind", "sphere");
  m.set_attribute(*g, "r", "10");
  Surface s{"cylinder", {1, 2, 3}, {0, 0, 1}, 0.5, 0, 2, 32};
  const std::uint32_t sid = m.add_surface(s);
  m.set_surface(*m.faces().begin(), sid);
  const Model back = round_trip(m, Format::kJson);
  EXPECT_EQ(snapshot(back), snapshot(m));
  EXPECT_EQ(canonical_dump(back), canonical_dump(m));
}

TEST(Json, CoordinatesAreBitExact) {
  const double odd[] = {
      0.1 + 0.2, -0.0, 4.9406564584124654e-324, 1.7976931348623157e308, -2.2250738585072014e-308,
      1.0 / 3.0};
  MeshInput in;
  in.positions = {{odd[0], odd[1], odd[2]}, {odd[3], odd[4], odd[5]}, {1, 2, 3}};
  in.faces.push_back({{{0, 1, 2}}});
  const Model m = testing::build(in);
  const Model back = round_trip(m, Format::kJson);
  ASSERT_EQ(back.num_vertices(), 3u);
  for (VertexId v : m.vertices()) {
    const Vec3 a = m.position(v), b = back.position(v);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::signbit(a[k]), std::signbit(b[k]));
      EXPECT_EQ(a[k], b[k]);
    }
  }
}

TEST(Json, AppendsToANonEmptyModel) {
  Model m = testing::build(testing::unit_cube());
  const auto bytes = io::write_model(testing::build(testing::book()), Format::kJson);
  ASSERT_OK(bytes);
  auto r = io::read_model(m, testing::bytes_of(*bytes), Format::kJson);
  ASSERT_OK(r);
  EXPECT_EQ(m.num_groups(), 2u);
  EXPECT_VALID(m);
}

// Mesh formats: a closed solid comes back with the same counts (its polygons
// triangulated where the format needs it) and the same volume.
TEST(MeshFormats, RoundTripCounts) {
  const Model cube = testing::build(testing::unit_cube());
  EXPECT_EQ(counts(round_trip(cube, Format::kObj)), (Counts{8, 12, 6, 1}));
  EXPECT_EQ(counts(round_trip(cube, Format::kOff)), (Counts{8, 12, 6, 1}));
  EXPECT_EQ(counts(round_trip(cube, Format::kStl)), (Counts{8, 18, 12, 1}));
  EXPECT_EQ(counts(round_trip(cube, Format::kStl, {.stl_binary = false})), (Counts{8, 18, 12, 1}));
  // Merging coplanar triangles gives the polygons back.
  const io::ReadOptions merge{.import = {.merge_coplanar = true}};
  EXPECT_EQ(counts(round_trip(cube, Format::kStl, {}, merge)), (Counts{8, 12, 6, 1}));
  if (io::has_3mf()) {
    EXPECT_EQ(counts(round_trip(cube, Format::k3mf)), (Counts{8, 18, 12, 1}));
    EXPECT_EQ(counts(round_trip(cube, Format::k3mf, {}, merge)), (Counts{8, 12, 6, 1}));
  }
}

TEST(MeshFormats, HoledSolidSurvivesEveryFormat) {
  const Model m = testing::build(testing::cube_with_through_hole());
  const io::ReadOptions merge{.import = {.merge_coplanar = true}};
  std::vector<Format> formats = {Format::kStl, Format::kObj, Format::kOff};
  if (io::has_3mf()) formats.push_back(Format::k3mf);
  for (Format f : formats) {
    SCOPED_TRACE(std::string(io::format_name(f)));
    const Model back = round_trip(m, f);
    EXPECT_VALID(back);
    const io::Diagnosis d = io::diagnose(back);
    EXPECT_TRUE(d.closed);
    EXPECT_TRUE(d.manifold);
    EXPECT_TRUE(d.inconsistent_edges.empty());
    EXPECT_TRUE(d.self_intersections.empty());
    EXPECT_EQ(back.num_volumes(), 1u);
    EXPECT_DOUBLE_EQ(d.mass.volume, 27 - 3);
    // Merged back: the 10 faces of the fixture, top and bottom with their holes.
    const Model merged = round_trip(m, f, {}, merge);
    EXPECT_EQ(counts(merged), counts(m));
    EXPECT_EQ(euler_figures(merged).lhs(), euler_figures(m).lhs());
    EXPECT_VALID(merged);
  }
}

TEST(MeshFormats, ObjKeepsWiresAndPoints) {
  const Model m = testing::build(testing::cube_with_wire_and_point());
  const Model back = round_trip(m, Format::kObj);
  EXPECT_EQ(counts(back), counts(m));
  EXPECT_EQ(canonical_dump(back), canonical_dump(m));
}

TEST(MeshFormats, ObjAndOffKeepDoublesExactly) {
  MeshInput in;
  in.positions = {{0.1, 0.2, 0.3}, {1.0 / 3, 0, 0}, {0, 2.0 / 3, 1e-300}};
  in.faces.push_back({{{0, 1, 2}}});
  const Model m = testing::build(in);
  for (Format f : {Format::kObj, Format::kOff}) {
    const Model back = round_trip(m, f);
    EXPECT_EQ(canonical_dump(back), canonical_dump(m)) << io::format_name(f);
  }
}

TEST(StlDetection, FromContentNotExtension) {
  const io::ReadOptions named{.import = {.group_name = "cube"}};
  const Model ascii = testing::read_fixture("cube_ascii.stl", named);
  const Model binary = testing::read_fixture("cube_binary.stl", named);
  const Model solid_header = testing::read_fixture("cube_binary_solid_header.stl", named);
  EXPECT_EQ(counts(ascii), (Counts{8, 18, 12, 1}));
  EXPECT_EQ(canonical_dump(binary), canonical_dump(ascii));
  EXPECT_EQ(canonical_dump(solid_header), canonical_dump(ascii));
  // Binary output is 84 + 50 n bytes; ASCII output starts with "solid".
  const auto b = io::write_model(ascii, Format::kStl);
  const auto a = io::write_model(ascii, Format::kStl, {.stl_binary = false});
  ASSERT_OK(b);
  ASSERT_OK(a);
  EXPECT_EQ(b->size(), 84u + 50u * 12u);
  EXPECT_EQ(a->rfind("solid", 0), 0u);
}

TEST(ObjReading, IndexFormsAndNegativeIndices) {
  const Model m = testing::read_fixture("cube.obj");
  EXPECT_EQ(counts(m), (Counts{8, 12, 6, 1}));
  EXPECT_VALID(m);
  EXPECT_EQ(m.name(*m.groups().begin()), "cube");
}

TEST(OffReading, Cube) {
  const Model m = testing::read_fixture("cube.off");
  EXPECT_EQ(counts(m), (Counts{8, 12, 6, 1}));
  EXPECT_VALID(m);
}

}  // namespace
}  // namespace cellforge
