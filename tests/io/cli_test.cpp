// `cellforge info` and `cellforge convert` end to end.
#include "support/cli.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

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
        "\"groups\": 1", "\"euler_characteristic\": 1", "\"valid\": true", "\"closed\": true",
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

TEST(Cli, EveryCommandHasHelp) {
  for (const char* command : {"info", "convert", "make", "db", "bool", "demo"}) {
    for (const char* flag : {"--help", "-h"}) {
      const CliRun r = run(std::string(command) + " " + flag);
      EXPECT_EQ(r.status, 0) << command << " " << flag << ": " << r.out;
      EXPECT_NE(r.out.find(std::string("cellforge ") + command), std::string::npos) << r.out;
    }
    EXPECT_EQ(run(std::string("help ") + command).status, 0) << command;
  }
  // Unknown options are errors, not ignored.
  EXPECT_EQ(run("info " + testing::data_path("cube.off") + " --bogus").status, 2);
  EXPECT_EQ(run("convert a.obj b.stl --bogus").status, 2);
  EXPECT_EQ(run("bool union a.stl b.stl -o c.stl --threads 1.5").status, 2);
  EXPECT_EQ(run("demo extra").status, 2);
}

TEST(Cli, InfoStrictFailsOnAnInvalidModel) {
  const std::string valid = testing::data_path("cube.off");
  EXPECT_EQ(run("info " + valid + " --strict").status, 0);
  // Ten triangles on six points (found by a random search) whose import has a cell
  // that its wedges do not agree on: read, reported "valid: no", exit 0 without
  // --strict and 1 with it. Should import ever make it valid, --strict must exit 0:
  // the exit code follows the report either way.
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_io_cli";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "wedges.obj").string();
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nv 1 1 0\n"
                         "f 3 1 4\nf 1 5 4\nf 1 3 5\nf 1 2 6\nf 2 4 1\nf 2 3 5\nf 4 5 3\n"
                         "f 6 2 4\nf 3 6 2\nf 4 2 3\n";
  const CliRun loose = run("info " + path);
  ASSERT_EQ(loose.status, 0) << loose.out;
  const bool invalid = loose.out.find("valid: no") != std::string::npos;
  EXPECT_TRUE(invalid) << "the model became valid; the strict check below still holds\n"
                       << loose.out;
  const CliRun strict = run("info " + path + " --strict");
  EXPECT_EQ(strict.status, invalid ? 1 : 0) << strict.out;
  EXPECT_EQ(run("info " + path + " --strict --json").status, invalid ? 1 : 0);
}

TEST(Cli, DashIsStandardInputAndOutput) {
  const std::string off = testing::data_path("cube.off");
  const CliRun in = run("info - --format off < " + off);
  EXPECT_EQ(in.status, 0) << in.out;
  EXPECT_NE(in.out.find("closed: yes"), std::string::npos) << in.out;
  EXPECT_EQ(run("info - < " + off).status, 1);  // no format named
  const CliRun piped =
      run("convert " + off + " - --to obj 2>/dev/null | " + std::string(CELLFORGE_BIN) +
          " convert - - --from obj --to json 2>/dev/null | " + std::string(CELLFORGE_BIN) +
          " info - --format json --json");
  EXPECT_EQ(piped.status, 0) << piped.out;
  EXPECT_NE(piped.out.find("\"volume\": 1,"), std::string::npos) << piped.out;
}

TEST(Cli, ConvertSaysWhatTheFormatDrops) {
  const std::string wires = testing::data_path("wire_point.obj");
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_io_cli";
  std::filesystem::create_directories(dir);
  const CliRun stl = run("convert " + wires + " " + (dir / "wp.stl").string());
  EXPECT_EQ(stl.status, 0) << stl.out;
  EXPECT_NE(stl.out.find("warning: "), std::string::npos) << stl.out;
  EXPECT_NE(stl.out.find("wire edge"), std::string::npos) << stl.out;
  EXPECT_NE(stl.out.find("not written: stl holds faces only"), std::string::npos) << stl.out;
  const CliRun obj = run("convert " + wires + " " + (dir / "wp.json").string());
  EXPECT_EQ(obj.status, 0);
  EXPECT_EQ(obj.out.find("warning"), std::string::npos) << obj.out;
}

TEST(Cli, InfoToAFullDeviceFails) {
  // Standard output on /dev/full: every write fails with ENOSPC (the commands used to
  // lose the output and exit 0). run() adds 2>&1 at the end, so the status is echoed.
  const std::string off = testing::data_path("cube.off");
  for (const std::string& args :
       {"info " + off, "info " + off + " --json", "convert " + off + " - --to stl",
        std::string("make cube -o - --format obj")}) {
    const CliRun r = run(args + " >/dev/full 2>/dev/null; echo \"exit $?\"");
    EXPECT_EQ(r.out, "exit 1\n") << args;
  }
}

}  // namespace
}  // namespace cellforge
