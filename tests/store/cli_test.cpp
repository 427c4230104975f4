// `cellforge db` end to end on both backends.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

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

CELLFORGE_BACKENDS(Cli);

}  // namespace
}  // namespace cellforge::testing
