// Files of the kinds other projects publish (issue 19): hollow parts and nested
// shells, back-to-back faces, open meshes, -0 coordinates, stacks of equal triangles.
// The models are in tests/data/{nested,back_to_back,precision}/ (make_corpus.py).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cellforge/geom/intersect.h"
#include "cellforge/io/diagnose.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/topo/validate.h"
#include "io/intersect.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using testing::data_path;
using testing::read_fixture;

// The signed volume of a file's polygons as they stand (fan triangles, origin as the
// reference), computed from the parsed soup alone: independent of import and cells.
double soup_volume(const std::string& name) {
  auto bytes = io::read_bytes(data_path(name));
  EXPECT_TRUE(bytes.ok());
  auto format = io::format_from_path(name);
  auto soup = io::parse_mesh(*bytes, *format);
  EXPECT_TRUE(soup.ok()) << (soup.ok() ? "" : soup.error().message);
  double v6 = 0;
  for (const auto& poly : soup->polygons)
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
      const Vec3 a = soup->positions[poly[0]], b = soup->positions[poly[i]],
                 c = soup->positions[poly[i + 1]];
      v6 += dot(a, cross(b, c));
    }
  return v6 / 6;
}

TEST(HollowSolids, CavitiesBelongToTheSolidAroundThem) {
  struct Case {
    const char* file;
    std::size_t cells;
    double volume;  // closed form
  };
  for (const Case& c : {Case{"nested/cube_octahedron_cavity.stl", 1, 1000 - 4.0 / 3 * 27},
                        Case{"nested/nested_cubes.stl", 2, 1000 - 216 + 8}}) {
    SCOPED_TRACE(c.file);
    const Model m = read_fixture(c.file);
    EXPECT_VALID(m);
    const io::Diagnosis d = io::diagnose(m);
    EXPECT_EQ(d.volumes, c.cells);
    EXPECT_NEAR(d.volume, c.volume, 1e-9 * c.volume);
    EXPECT_TRUE(d.warnings.empty());
  }
  // The polyhedral sphere's cavity: the cell's volume is the file's signed volume.
  const Model m = read_fixture("nested/cube_sphere_cavity.stl");
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_volumes(), 1u);
  const double expected = soup_volume("nested/cube_sphere_cavity.stl");
  EXPECT_LT(expected, 1000 - 100);  // the cavity is about 4/3 pi 27 = 113
  EXPECT_NEAR(shape::mass_properties(m).volume, expected, 1e-9 * expected);
  // Every face, the cavity's included, has the one cell behind it.
  for (FaceId f : m.faces()) {
    EXPECT_TRUE(m.back_volume(f).is_valid()) << f.str();
    EXPECT_FALSE(m.front_volume(f).is_valid()) << f.str();
  }
}

TEST(HollowSolids, OutwardShellsInsideASolidAreNestedCells) {
  const Model m = read_fixture("nested/nested_cubes_outward.stl");
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_volumes(), 3u);  // the shells' regions partition the outer cube
  EXPECT_NEAR(shape::mass_properties(m).volume, 1000, 1e-9);
}

TEST(HollowSolids, RepairOrientationRespectsNesting) {
  const io::ReadOptions repair{.import = {.repair_orientation = true}};
  // Shells at odd depth become cavities: 1000 - 216 + 8.
  io::ReadResult r;
  Model m;
  auto read = io::read_file(m, data_path("nested/nested_cubes_outward.stl"), repair);
  ASSERT_OK(read);
  EXPECT_VALID(m);
  EXPECT_EQ(read->report.flipped_faces, 12u);
  EXPECT_EQ(m.num_volumes(), 2u);
  EXPECT_NEAR(shape::mass_properties(m).volume, 792, 1e-9);
  // Shells already nested right stay as they are.
  for (const char* file : {"nested/nested_cubes.stl", "nested/cube_octahedron_cavity.stl",
                           "nested/cube_sphere_cavity.stl"}) {
    SCOPED_TRACE(file);
    Model k;
    auto again = io::read_file(k, data_path(file), repair);
    ASSERT_OK(again);
    EXPECT_EQ(again->report.flipped_faces, 0u);
    EXPECT_NEAR(shape::mass_properties(k).volume, soup_volume(file), 1e-9 * 1000);
  }
}

TEST(HollowSolids, AClosedShellWithoutACellIsAWarning) {
  const io::Diagnosis d = io::diagnose(read_fixture("nested/cavity_alone.stl"));
  EXPECT_TRUE(d.valid);
  EXPECT_TRUE(d.closed);
  EXPECT_EQ(d.volumes, 0u);
  EXPECT_DOUBLE_EQ(d.volume, -1);  // the signed volume of the inside-out surface
  ASSERT_FALSE(d.warnings.empty());
  bool named = false;
  for (const auto& w : d.warnings) named = named || w.find("bounds no cell") != std::string::npos;
  EXPECT_TRUE(named) << d.warnings[0];
  EXPECT_NE(io::to_text(d).find("warning: "), std::string::npos);
}

TEST(BackToBack, PairsAndFinsImportIntoValidModels) {
  struct Case {
    const char* file;
    std::size_t cells;
    double volume;
  };
  for (const Case& c :
       {Case{"back_to_back/two_cubes_face.obj", 2, 2}, Case{"back_to_back/pair_in_cube.obj", 1, 1},
        Case{"back_to_back/fin_in_cube.obj", 1, 1}, Case{"back_to_back/diagonal_wall.obj", 2, 1}}) {
    for (bool merge : {false, true}) {
      SCOPED_TRACE(std::string(c.file) + (merge ? " merged" : ""));
      const Model m = read_fixture(c.file, {.import = {.merge_coplanar = merge}});
      EXPECT_VALID(m);
      EXPECT_EQ(m.num_volumes(), c.cells);
      EXPECT_NEAR(shape::mass_properties(m).volume, c.volume, 1e-12);
      // Written and read back losslessly.
      const Model back = testing::round_trip(m, io::Format::kJson);
      EXPECT_VALID(back);
      EXPECT_EQ(back.num_volumes(), c.cells);
    }
  }
}

// A model the JSON reader would refuse (a cube whose last face misses its cell:
// the wedges around its edges disagree) is not written.
TEST(BackToBack, AnInvalidModelIsNotWritten) {
  MeshInput in = testing::unit_cube();
  in.faces.back().back = -1;
  const Model m = testing::build(in);
  ASSERT_FALSE(validate(m).empty());
  auto json = io::write_model(m, io::Format::kJson);
  ASSERT_FALSE(json.ok());
  EXPECT_NE(json.error().message.find("wedge"), std::string::npos) << json.error().message;
  const std::string path = ::testing::TempDir() + "/cellforge_invalid.json";
  std::remove(path.c_str());
  EXPECT_FALSE(io::write_file(m, path).ok());
  EXPECT_FALSE(io::read_bytes(path).ok()) << "the file was created";
}

TEST(OpenMeshes, VolumeIsTheSurfacesSignedVolumeWithAWarning) {
  const io::Diagnosis d = io::diagnose(read_fixture("open_box.stl"));
  EXPECT_FALSE(d.closed);
  EXPECT_EQ(d.volumes, 0u);
  EXPECT_EQ(d.mass.volume, 0);
  // The missing bottom lies in z = 0, where its cones from the origin are flat.
  EXPECT_NEAR(d.volume, soup_volume("open_box.stl"), 1e-15);
  EXPECT_NEAR(d.volume, 1, 1e-15);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("open"), std::string::npos) << d.warnings[0];
  // An open box is a disk (1); the closed cube's surface is a sphere (2), its solid a ball (1).
  EXPECT_EQ(d.euler_characteristic_surface, 1);
  const io::Diagnosis cube = io::diagnose(read_fixture("cube.obj"));
  EXPECT_EQ(cube.euler_characteristic_surface, 2);
  EXPECT_EQ(cube.euler_characteristic_solid, 1);
  EXPECT_TRUE(cube.warnings.empty());
}

TEST(Precision, NegativeZeroSurvivesImportBitForBit) {
  const Model m = read_fixture("precision/negative_zero.obj");
  int negative = 0;
  for (VertexId v : m.vertices()) {
    const Vec3 p = m.position(v);
    negative += std::signbit(p.x) + std::signbit(p.y) + std::signbit(p.z);
  }
  EXPECT_EQ(negative, 6);  // as the file has them (-0 of vertex 1 welds nothing here)
  const Model back = testing::round_trip(m, io::Format::kJson);
  for (VertexId v : m.vertices()) {
    const Vec3 a = m.position(v), b = back.position(v);
    EXPECT_EQ(std::signbit(a.x), std::signbit(b.x));
    EXPECT_EQ(std::signbit(a.y), std::signbit(b.y));
    EXPECT_EQ(std::signbit(a.z), std::signbit(b.z));
  }
}

// Every pair of triangles that share no vertex and belong to different faces, by
// brute force: the hierarchy must find the same pairs.
std::vector<std::pair<FaceId, FaceId>> brute_force(const Model& m) {
  struct Tri {
    std::array<VertexId, 3> v;
    FaceId f;
  };
  std::vector<Tri> tris;
  for (FaceId f : m.faces())
    for (const auto& t : io::triangulate_face(m, f)) tris.push_back({t, f});
  std::vector<std::pair<FaceId, FaceId>> out;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j) {
      const Tri &a = tris[i], &b = tris[j];
      if (a.f == b.f) continue;
      bool shared = false;
      for (VertexId u : a.v)
        for (VertexId w : b.v) shared = shared || u == w;
      if (shared) continue;
      const Vec3 pa[3] = {m.position(a.v[0]), m.position(a.v[1]), m.position(a.v[2])};
      const Vec3 pb[3] = {m.position(b.v[0]), m.position(b.v[1]), m.position(b.v[2])};
      if (triangles_meet(pa, pb)) out.push_back(std::minmax(a.f, b.f));
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TEST(SelfIntersections, SameAsBruteForceOnRandomTriangles) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coord(0, 12);  // a coarse grid: touching and coplanar cases
    io::PolygonSoup soup;
    for (int t = 0; t < 150; ++t) {
      std::vector<std::uint32_t> poly;
      for (int k = 0; k < 3; ++k) {
        poly.push_back(static_cast<std::uint32_t>(soup.positions.size()));
        soup.positions.push_back({coord(rng) * 0.25, coord(rng) * 0.25, coord(rng) * 0.25});
      }
      soup.polygons.push_back(poly);
      if (t % 10 == 0) soup.polygons.push_back(poly);  // equal triangles too
    }
    Model m;
    ASSERT_OK(io::import_soup(m, soup, {.volumes = io::VolumeMode::kNone}));
    const auto fast = io::self_intersections(m);
    EXPECT_EQ(fast, brute_force(m));
    EXPECT_FALSE(fast.empty());
  }
}

TEST(SelfIntersections, AStackOfEqualTrianglesAndOneCrossingIt) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -1}, {1, 1, 1}, {2, 2, 1}};
  for (int i = 0; i < 20000; ++i) soup.polygons.push_back({0, 1, 2});
  soup.polygons.push_back({3, 4, 5});  // pierces the stack
  Model m;
  ASSERT_OK(io::import_soup(m, soup, {.volumes = io::VolumeMode::kNone}));
  const auto pairs = io::self_intersections(m);
  EXPECT_EQ(pairs.size(), 20000u);  // the crossing triangle with each face of the stack
}

}  // namespace
}  // namespace cellforge
