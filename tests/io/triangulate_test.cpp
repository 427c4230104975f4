// Export triangulation: concave polygons and holes without flipped or overlapping
// triangles, and mesh exports that admesh accepts.
#include "cellforge/io/triangulate.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

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
