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
  // Ten triangles on six points (found by a random search) whose import once had a
  // cell that its wedges did not agree on ("valid: no", exit 1 with --strict).
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_io_cli";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "wedges.obj").string();
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nv 1 1 0\n"
                         "f 3 1 4\nf 1 5 4\nf 1 3 5\nf 1 2 6\nf 2 4 1\nf 2 3 5\nf 4 5 3\n"
                         "f 6 2 4\nf 3 6 2\nf 4 2 3\n";
  const CliRun loose = run("info " + path);
  ASSERT_EQ(loose.status, 0) << loose.out;
  // Import now nests cells exactly and this mesh reads as a valid sheet model (no
  // mesh found by a random search of 400 more reads as invalid), but two of its
  // triangles cross (f2/f7): --strict fails it for that.
  EXPECT_NE(loose.out.find("valid: yes"), std::string::npos) << loose.out;
  EXPECT_NE(loose.out.find("self_intersections: 1 (f2/f7)"), std::string::npos) << loose.out;
  const CliRun strict = run("info " + path + " --strict");
  EXPECT_EQ(strict.status, 1) << strict.out;
  EXPECT_EQ(run("info " + path + " --strict --json").status, 1);

  // Two closed cubes that pass through each other: a valid model (two cells) whose
  // faces intersect, which a slicer would refuse. --strict fails it; without the
  // self-intersection check there is nothing left to fail.
  const std::string crossing = (dir / "crossing_cubes.obj").string();
  {
    std::ofstream out(crossing);
    const double offsets[2] = {0, 0.5};
    for (double o : offsets)
      for (int i = 0; i < 8; ++i)
        out << "v " << o + (i & 1) << ' ' << o + ((i >> 1) & 1) << ' ' << o + ((i >> 2) & 1)
            << '\n';
    const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                             {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (int c = 0; c < 2; ++c)
      for (const auto& q : quads)
        out << "f " << q[0] + 8 * c << ' ' << q[1] + 8 * c << ' ' << q[2] + 8 * c << ' '
            << q[3] + 8 * c << '\n';
  }
  const CliRun report = run("info " + crossing);
  ASSERT_EQ(report.status, 0) << report.out;
  EXPECT_NE(report.out.find("valid: yes"), std::string::npos) << report.out;
  EXPECT_EQ(run("info " + crossing + " --strict").status, 1);
  EXPECT_EQ(run("info " + crossing + " --strict --json").status, 1);
  EXPECT_EQ(run("info " + crossing + " --strict --no-self-intersections").status, 0);
  EXPECT_EQ(run("info " + valid + " --strict --json").status, 0);
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

// The progress line: on a terminal (script(1) gives the command one) it shows the
// stages; into a pipe, never. CELLFORGE_PROGRESS_AFTER=0 draws from the first stage.
TEST(Cli, ProgressOnlyOnATerminal) {
  const std::string file = testing::data_path("cube_binary.stl");
  const auto piped = testing::run_cli("info " + file);
  EXPECT_EQ(piped.status, 0);
  EXPECT_EQ(piped.out.find("self-intersections ("), std::string::npos) << piped.out;
  const auto shell = [](const std::string& cmd) {
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
    return out;
  };
  const std::string forced_pipe =
      shell("CELLFORGE_PROGRESS_AFTER=0 " + std::string(CELLFORGE_BIN) + " info " + file + " 2>&1");
  EXPECT_EQ(forced_pipe.find("self-intersections ("), std::string::npos) << forced_pipe;
  EXPECT_EQ(forced_pipe.find('\r'), std::string::npos);
  // Under a pseudo-terminal, with standard output kept apart from it.
  const std::string cmd = "CELLFORGE_PROGRESS_AFTER=0 script -qec '" + std::string(CELLFORGE_BIN) +
                          " info " + file + " > /dev/null' /dev/null 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string tty;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) tty.append(buf, n);
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 0);
  EXPECT_NE(tty.find("cellforge info: self-intersections ("), std::string::npos) << tty;
  EXPECT_NE(tty.find("\r\033[K"), std::string::npos);  // and the line is cleared at the end
}

}  // namespace
}  // namespace cellforge
