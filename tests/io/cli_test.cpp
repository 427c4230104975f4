// `cellforge info` and `cellforge convert` end to end.
#include "support/cli.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>

#include "io_test_util.h"

namespace cellforge {
namespace {

using cellforge::testing::CliRun;
CliRun run(const std::string& args) { return cellforge::testing::run_cli(args); }

TEST(Cli, InfoJsonOfTheNonManifoldStl) {
  const CliRun r = run("info " + testing::data_path("two_cubes_edge.stl") + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* field :
       {"\"vertices\": 14", "\"edges\": 35", "\"faces\": 24", "\"loops\": 24", "\"volumes\": 2",
        "\"groups\": 1", "\"euler_characteristic_surface\": 3",
        "\"euler_characteristic_solid\": 1", "\"valid\": true", "\"closed\": true",
        "\"manifold\": false", "\"volume\": 2", "\"area\": 12", "\"centroid\": [1, 1, 0.5]",
        "\"bbox\": {\"min\": [0, 0, 0], \"max\": [2, 2, 1]}", "\"non_manifold_edges_count\": 1"})
    EXPECT_NE(r.out.find(field), std::string::npos) << field << "\n" << r.out;
}

TEST(Cli, InfoTextAndErrors) {
  const CliRun ok = run("info " + testing::data_path("cube.off"));
  EXPECT_EQ(ok.status, 0);
  EXPECT_NE(ok.out.find("closed: yes"), std::string::npos) << ok.out;
  const CliRun bad = run("info " + testing::data_path("bad_truncated.stl"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.out.find("byte 80"), std::string::npos) << bad.out;
  EXPECT_EQ(run("info").status, 2);
  EXPECT_EQ(run("info x.stl bogus=1").status, 2);
}

TEST(Cli, ConvertBetweenEveryFormat) {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_io_cli";
  std::filesystem::create_directories(dir);
  std::string prev = testing::data_path("cube.obj");
  std::vector<std::string> exts = {"stl", "off", "json", "obj"};
  if (io::has_3mf()) exts.insert(exts.begin() + 2, "3mf");
  for (const std::string& ext : exts) {
    const std::string out = (dir / ("cube." + ext)).string();
    const CliRun r = run("convert " + prev + " " + out + " merge_coplanar=true");
    ASSERT_EQ(r.status, 0) << r.out;
    const CliRun info = run("info " + out + " --json merge_coplanar=true");
    EXPECT_NE(info.out.find("\"faces\": 6,"), std::string::npos) << ext << "\n" << info.out;
    EXPECT_NE(info.out.find("\"volume\": 1,"), std::string::npos) << ext << "\n" << info.out;
    prev = out;
  }
  EXPECT_EQ(run("convert " + prev + " x.ply").status, 2);
}

}  // namespace
}  // namespace cellforge
