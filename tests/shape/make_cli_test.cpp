// `cellforge make` end to end: the files it writes read back with the same counts and
// volume; unknown kinds and keys list the valid ones.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>

#include "shape/shape_test_util.h"
#include "cellforge/shape/mass.h"
#include "cellforge/io/mesh_io.h"
#include "support/cli.h"

namespace cellforge::shape {
namespace {

using cellforge::testing::CliRun;
CliRun run(const std::string& args) { return cellforge::testing::run_cli(args); }

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cellforge_make_" + name)).string();
}

TEST(MakeCli, SphereStlReadsBack) {
  const std::string path = temp_path("sphere.stl");
  const CliRun r = run("make sphere r=10 fn=32 -o " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("512 vertices"), std::string::npos) << r.out;
  Model m;
  auto read = io::read_file(m, path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(m.num_vertices(), 512u);
  const double v = mass_properties(m, read->group).volume;
  // The figure the command printed; STL keeps single-precision coordinates.
  EXPECT_LE(testing::rel_err(v, 4121.989759446126), 1e-6);
  std::filesystem::remove(path);
}

TEST(MakeCli, OpenScadParameterNames) {
  const std::string path = temp_path("cyl.stl");
  CliRun r = run("make cylinder h=5 r1=3 r2=1 fn=17 --ascii -o " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("34 vertices, 51 edges, 19 faces, 17 segments"), std::string::npos) << r.out;
  r = run("make cube size=2,3,4 center=true -o " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("volume 24"), std::string::npos) << r.out;
  r = run("make torus R=5 r=1 fn=24 -o " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("576 vertices"), std::string::npos) << r.out;
  r = run("make sphere d=4 '$fn=6' -o " + path);  // d = 2 r; $fn read as fn
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("18 vertices"), std::string::npos) << r.out;
  r = run("make linear_extrude shape=square size=2 height=3 scale=0.5 -o " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("volume 7"), std::string::npos) << r.out;  // 3 * 4 * (1 + .5 + .25) / 3
  std::filesystem::remove(path);
}

TEST(MakeCli, ErrorsListValidChoices) {
  CliRun r = run("make blob -o x.stl");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("unknown kind 'blob' (valid: cube, cylinder, sphere"), std::string::npos)
      << r.out;
  r = run("make sphere q=1 -o x.stl");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("unknown key 'q' (valid: r, d, fn, fa, fs, max_vertices)"),
            std::string::npos)
      << r.out;
  r = run("make sphere r=-1 -o x.stl");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("r must be positive"), std::string::npos) << r.out;
  r = run("make cube size=a -o x.stl");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("size=a"), std::string::npos) << r.out;
  r = run("make cube");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("-o is required"), std::string::npos) << r.out;
}

TEST(MakeCli, ParametersAreFiniteAndWithinTheLimits) {
  const std::string out = temp_path("limits.stl");
  const struct {
    const char* args;
    int status;
    const char* message;
  } cases[] = {
      {"cube size=1e200", 1, "beyond the coordinate limit"},
      {"sphere r=1e300", 1, "beyond the coordinate limit"},
      {"sphere fn=nan", 1, "fn must be finite and >= 0, got nan"},
      {"cylinder fa=inf", 1, "fa must be finite and >= 0"},
      {"cylinder fs=-1", 1, "fs must be finite and >= 0"},
      {"sphere fn=100000", 1, "would make 5000000000 vertices, more than the limit of 10000000"},
      {"prism n=1e9", 1, "would make 2000000000 vertices"},
      {"prism n=1e20", 1, "n=1e20: expected a whole number of at most 2147483647"},
      {"sphere fn=100 max_vertices=4999", 1, "more than the limit of 4999"},
      {"sphere fn=100 max_vertices=x", 1, "max_vertices=x: expected a count"},
  };
  for (const auto& c : cases) {
    const CliRun r = run(std::string("make ") + c.args + " -o " + out);
    EXPECT_EQ(r.status, c.status) << c.args << ": " << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << ": " << r.out;
  }
  EXPECT_EQ(run("make sphere fn=100 max_vertices=5000 -o " + out).status, 0);
}

}  // namespace
}  // namespace cellforge::shape
