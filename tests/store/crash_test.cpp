// A save is one transaction: a child process killed with SIGKILL in the middle of
// a large save leaves the earlier version intact and the database writable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using Crash = StoreTest;

TEST_P(Crash, KillDuringSaveKeepsThePreviousVersion) {
  const Model small = build(unit_cube());
  ASSERT_OK(store_->put("part", small));
  const Model large = grid_sheet(250);  // 125000 faces, ~800000 rows

  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(ready[0]);
    auto store = open_store(db_);
    if (!store) _exit(2);
    bool told = false;
    PutOptions o;
    o.progress = [&](std::uint64_t rows) {
      if (!told && rows >= 100000) {
        told = true;
        const char c = 'x';
        (void)!write(ready[1], &c, 1);
        pause();  // wait mid-transaction for the SIGKILL
      }
    };
    (void)store.value()->put("part", large, o);
    _exit(3);  // the save finished: the parent fails the test
  }
  close(ready[1]);
  char c = 0;
  const bool signalled = read(ready[0], &c, 1) == 1;
  close(ready[0]);
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(signalled) << "the child never reached the middle of its save";
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  auto fresh = open_again();
  ASSERT_NE(fresh, nullptr);
  auto versions = fresh->versions("part");
  ASSERT_OK(versions);
  ASSERT_EQ(versions->size(), 1u);
  auto got = fresh->get("part");
  ASSERT_OK(got);
  EXPECT_VALID(got.value());
  expect_same_model(small, got.value());
  auto rows = fresh->query("SELECT COUNT(*) FROM loop_edges");
  ASSERT_OK(rows);
  EXPECT_EQ(*rows->rows[0][0], "24");  // nothing of the killed save remains
  if (GetParam() == "sqlite") {
    auto check = fresh->query("PRAGMA integrity_check");
    ASSERT_OK(check);
    EXPECT_EQ(*check->rows[0][0], "ok");
  }
  // The lock died with the child: the next save goes through.
  auto v2 = fresh->put("part", grid_sheet(10));
  ASSERT_OK(v2);
  EXPECT_EQ(v2->version, 2);
}

CELLFORGE_BACKENDS(Crash);

}  // namespace
}  // namespace cellforge::testing
