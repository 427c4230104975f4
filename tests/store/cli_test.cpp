// `cellforge db` end to end on both backends.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "store/store_fixture.h"

extern char** environ;

namespace cellforge::testing {
namespace {

struct CliRun {
  int status = -1;
  std::string out;
};

CliRun cli(std::vector<std::string> args) {
  args.insert(args.begin(), CELLFORGE_BIN);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int fds[2];
  CliRun r;
  if (pipe(fds) != 0) return r;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  pid_t pid;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;)
    r.out.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  if (rc == 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return r;
}

// cli() with standard output sent to `path` (stderr captured instead), and standard
// input read from `input` when given.
CliRun cli_to(std::vector<std::string> args, const std::string& path,
              const std::string& input = "") {
  args.insert(args.begin(), CELLFORGE_BIN);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int fds[2];
  CliRun r;
  if (pipe(fds) != 0) return r;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, path.c_str(), O_WRONLY, 0);
  if (!input.empty()) posix_spawn_file_actions_addopen(&actions, 0, input.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  pid_t pid;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;)
    r.out.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  if (rc == 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return r;
}

// The names in `db list` output, space-separated in order.
std::string names_in(const std::string& list) {
  std::string out;
  std::size_t at = 0;
  while (at < list.size()) {
    const std::size_t end = list.find('\n', at);
    const std::string line = list.substr(at, end - at);
    const std::size_t cut = line.find("  version ");
    if (cut != std::string::npos) out += (out.empty() ? "" : " ") + line.substr(0, cut);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return out;
}

using Cli = StoreTest;

TEST_P(Cli, SaveListInfoSqlLoadRemove) {
  CliRun r = cli(
      {"db", "save", "example:box_with_hole", "--name", "x'); DROP TABLE volumes;--", "--db", db_});
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("version 1"), std::string::npos) << r.out;
  r = cli({"db", "save", "example:box", "--name", "x'); DROP TABLE volumes;--", "--db", db_});
  EXPECT_NE(r.out.find("version 2"), std::string::npos) << r.out;

  r = cli({"db", "list", "--db", db_});
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("x'); DROP TABLE volumes;--  version 2  solid  6 faces"), std::string::npos)
      << r.out;

  r = cli({"db", "info", "x'); DROP TABLE volumes;--", "--version", "1", "--db", db_});
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("version: 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("volume: 8"), std::string::npos) << r.out;  // 3x3x1 less the 1x1 hole

  r = cli({"db", "sql", "SELECT COUNT(*) AS n FROM face_loops WHERE kind = 'inner'", "--json",
           "--db", db_});
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "[\n {\"n\": 2}\n]\n");
  r = cli({"db", "sql", "DROP TABLE volumes", "--db", db_});
  EXPECT_EQ(r.status, 1);
  // A row limit for printing, and a time limit.
  r = cli({"db", "sql", "SELECT vertex_key FROM vertices ORDER BY volume_id, vertex_key",
           "--limit", "3", "--db", db_});
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("(3 rows)"), std::string::npos) << r.out;
  const std::string slow =
      GetParam() == "postgresql"
          ? "SELECT pg_sleep(30)"
          : "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n) SELECT COUNT(*) FROM n";
  r = cli({"db", "sql", slow, "--timeout", "0.5", "--db", db_});
  EXPECT_EQ(r.status, 1);
  r = cli({"db", "sql", "SELECT 1", "--timeout", "soon", "--db", db_});
  EXPECT_EQ(r.status, 2);

  r = cli({"db", "load", "x'); DROP TABLE volumes;--", "-o", "-", "--version", "1", "--db", db_});
  ASSERT_EQ(r.status, 0);
  auto direct = store_->get("x'); DROP TABLE volumes;--", 1);
  ASSERT_TRUE(direct.ok());
  EXPECT_NE(r.out.find("inner={["), std::string::npos);

  // A partial load: the top face of the box with a hole (z = 1), its two loops.
  r = cli({"db", "load", "x'); DROP TABLE volumes;--", "--version", "1", "--faces",
           "f.nz = 1 AND v.version = 1", "-o", "-", "--db", db_});
  ASSERT_EQ(r.status, 0) << r.out;
  std::size_t faces = 0;
  for (std::size_t at = 0; (at = r.out.find("\nF ", at)) != std::string::npos; ++at) ++faces;
  EXPECT_EQ(faces + (r.out.rfind("F ", 0) == 0), 1u) << r.out;
  EXPECT_NE(r.out.find("inner={["), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("front=- back=-"), std::string::npos) << r.out;
  r = cli({"db", "load", "x'); DROP TABLE volumes;--", "--faces", "1 = 1); DROP TABLE faces; --",
           "-o", "-", "--db", db_});
  EXPECT_EQ(r.status, 1);

  r = cli({"db", "rm", "x'); DROP TABLE volumes;--", "--db", db_});
  EXPECT_EQ(r.status, 0);
  r = cli({"db", "rm", "x'); DROP TABLE volumes;--", "--db", db_});
  EXPECT_EQ(r.status, 1);
  r = cli({"db", "save", "no_such_file.stl", "--name", "n", "--db", db_});
  EXPECT_EQ(r.status, 1);
  r = cli({"db", "save", "example:box", "--name", "", "--db", db_});
  EXPECT_EQ(r.status, 1);
  r = cli({"db", "list", "--db", db_});
  EXPECT_EQ(r.out, "");
}

// Issue 18's command line: a real parser for every db command.
TEST_P(Cli, ArgumentsHaveOneSetOfRules) {
  ASSERT_EQ(cli({"db", "save", "example:box", "--name", "part", "--db", db_}).status, 0);
  ASSERT_EQ(cli({"db", "save", "example:box_with_hole", "--name", "part", "--db", db_}).status, 0);
  // --version takes a whole number: 1.5, 1e3 and 1abc used to load version 1.
  for (const char* v : {"1.5", "1e3", "1abc", "0", "-1", ""}) {
    const CliRun r = cli({"db", "info", "part", "--version", v, "--db", db_});
    EXPECT_EQ(r.status, 2) << v << ": " << r.out;
  }
  EXPECT_EQ(cli({"db", "info", "part", "--version", "2", "--db", db_}).status, 0);
  // Unknown options are errors everywhere (db info used to ignore them), and rm
  // does not take -o, so that `db rm -o --db x.db` cannot read --db as the name.
  EXPECT_EQ(cli({"db", "info", "part", "--bogus", "--db", db_}).status, 2);
  const CliRun rm_o = cli({"db", "rm", "-o", "--db", db_});
  EXPECT_EQ(rm_o.status, 2) << rm_o.out;
  EXPECT_EQ(names_in(cli({"db", "list", "--db", db_}).out), "part");
  // A name beginning with '-' is saved, loaded and removed after --.
  ASSERT_EQ(cli({"db", "save", "example:box", "--db", db_, "--name", "-odd"}).status, 0);
  const CliRun loaded = cli({"db", "load", "-o", "-", "--db", db_, "--", "-odd"});
  EXPECT_EQ(loaded.status, 0) << loaded.out;
  EXPECT_NE(loaded.out.find("group=box"), std::string::npos) << loaded.out;  // the dump
  EXPECT_EQ(cli({"db", "info", "--db", db_, "--", "-odd"}).status, 0);
  EXPECT_EQ(cli({"db", "rm", "--db", db_, "--", "-odd"}).status, 0);
  EXPECT_EQ(names_in(cli({"db", "list", "--db", db_}).out), "part");
  // --help for the command and each subcommand, exit 0.
  for (std::vector<std::string> help :
       {std::vector<std::string>{"db", "--help"}, {"db", "save", "--help"}, {"db", "sql", "-h"}}) {
    const CliRun r = cli(help);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("Usage: cellforge db"), std::string::npos) << r.out;
  }
}

TEST_P(Cli, IssueNineteenHabits) {
  // db save names the volume after the file's stem.
  const std::string stl = std::string(CELLFORGE_TEST_DATA) + "/cube_binary.stl";
  CliRun r = cli({"db", "save", stl, "--db", db_});
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("saved cube_binary version 1"), std::string::npos) << r.out;
  ASSERT_EQ(cli({"db", "save", "example:box", "--db", db_}).status, 0);
  EXPECT_EQ(names_in(cli({"db", "list", "--db", db_}).out), "box cube_binary");
  // db rm --version N removes one version.
  ASSERT_EQ(cli({"db", "save", "example:box_with_hole", "--name", "box", "--db", db_}).status, 0);
  r = cli({"db", "rm", "box", "--version", "1", "--db", db_});
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("removed box version 1"), std::string::npos) << r.out;
  EXPECT_EQ(cli({"db", "info", "box", "--version", "1", "--db", db_}).status, 1);
  EXPECT_EQ(cli({"db", "info", "box", "--version", "2", "--db", db_}).status, 0);
  EXPECT_EQ(cli({"db", "rm", "box", "--version", "1", "--db", db_}).status, 1);
  // db save - reads standard input, with the format and the name given.
  r = cli({"db", "save", "-", "--db", db_});
  EXPECT_EQ(r.status, 2) << r.out;  // needs --name
  const std::string off = std::string(CELLFORGE_TEST_DATA) + "/cube.off";
  r = cli_to({"db", "save", "-", "--name", "piped", "--format", "off", "--db", db_}, "/dev/null",
             off);
  EXPECT_EQ(r.status, 0) << r.out;
  r = cli({"db", "info", "piped", "--db", db_});
  EXPECT_NE(r.out.find("faces: 6"), std::string::npos) << r.out;
  // db load -o - --format F writes that format to standard output.
  r = cli({"db", "load", "piped", "-o", "-", "--format", "obj", "--db", db_});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("# ", 0) == 0 || r.out.find("\nv ") != std::string::npos ||
                r.out.rfind("v ", 0) == 0,
            true)
      << r.out;
}

TEST_P(Cli, SqlJsonIsJson) {
  // Blobs, non-finite reals and repeated column names: each used to give invalid or
  // ambiguous JSON.
  const std::string blob = GetParam() == "sqlite" ? "x'00ff22'" : "'\\x00ff22'::bytea";
  const std::string inf = GetParam() == "sqlite" ? "9e999" : "'Infinity'::float8";
  const std::string nan = GetParam() == "sqlite" ? "NULL" : "'NaN'::float8";
  const CliRun r = cli({"db", "sql",
                        "SELECT 1 AS a, 2 AS a, " + blob + " AS b, " + inf + " AS big, " + nan +
                            " AS n, '12' AS t, 2.5 AS a_2",
                        "--json", "--db", db_});
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out,
            "[\n {\"a\": 1, \"a_3\": 2, \"b\": \"\\\\x00ff22\", \"big\": null, \"n\": null, "
            "\"t\": \"12\", \"a_2\": 2.5}\n]\n");
}

// db sql prints rows as they are read: the rows before a failing row are on
// standard output when the command fails (a buffered answer would print none).
TEST_P(Cli, SqlOutputStreams) {
  const std::string failing =
      GetParam() == "sqlite"
          ? "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 10) "
            "SELECT CASE WHEN i <= 3 THEN i ELSE abs(-9223372036854775804 - i) END AS i FROM n"
          : "SELECT CASE WHEN i <= 3 THEN i ELSE 1 / (i - i) END AS i "
            "FROM generate_series(1, 10) AS i";
  CliRun r = cli({"db", "sql", failing, "--json", "--db", db_});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out.substr(0, r.out.find("cellforge db:")),
            "[\n {\"i\": 1},\n {\"i\": 2},\n {\"i\": 3}")
      << r.out;
  r = cli({"db", "sql", failing, "--db", db_});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out.substr(0, r.out.find("cellforge db:")), "i\n-\n1\n2\n3\n") << r.out;
  // Complete answers end as before; the table is as wide as its widest value.
  r = cli({"db", "sql", "SELECT 7 AS i UNION ALL SELECT 12345", "--db", db_});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "i\n-----\n7\n12345\n(2 rows)\n");
}

TEST_P(Cli, ACommandOnAMissingDatabaseSaysSo) {
  if (GetParam() != "sqlite") {
    // PostgreSQL: a database is a server's, never created by a command.
    EXPECT_EQ(cli({"db", "list", "--db", db_}).status, 0);
    return;
  }
  const std::string missing = db_ + ".missing.db";
  for (std::vector<std::string> args : {std::vector<std::string>{"db", "list"},
                                        {"db", "info", "x"},
                                        {"db", "sql", "SELECT 1"},
                                        {"db", "rm", "x"},
                                        {"db", "load", "x", "-o", "-"}}) {
    args.push_back("--db");
    args.push_back(missing);
    const CliRun r = cli_to(args, "/dev/null");  // standard error is what is read
    EXPECT_EQ(r.status, 1) << args[1] << ": " << r.out;
    EXPECT_NE(r.out.find("no database " + missing), std::string::npos) << r.out;
    EXPECT_FALSE(std::ifstream(missing).good()) << args[1] << " created " << missing;
  }
}

TEST_P(Cli, WritingToAFullDeviceFails) {
  ASSERT_EQ(cli({"db", "save", "example:box", "--name", "part", "--db", db_}).status, 0);
  for (std::vector<std::string> args : {std::vector<std::string>{"db", "list"},
                                        {"db", "load", "part", "-o", "-"},
                                        {"db", "sql", "SELECT * FROM vertices"},
                                        {"db", "info", "part"}}) {
    args.push_back("--db");
    args.push_back(db_);
    const CliRun r = cli_to(args, "/dev/full");
    EXPECT_EQ(r.status, 1) << args[1] << ": " << r.out;
    EXPECT_NE(r.out.find("cannot write standard output"), std::string::npos) << r.out;
  }
}

CELLFORGE_BACKENDS(Cli);

}  // namespace
}  // namespace cellforge::testing
