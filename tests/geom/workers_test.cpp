// The process's worker threads (geom/workers.h): every k once, whatever the nesting,
// the callers at once, the exceptions and the exact-evaluation count.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cellforge/geom/filtered.h"
#include "cellforge/geom/workers.h"

namespace cellforge {
namespace {

// How many times each k ran.
std::vector<int> runs_of(std::size_t count) {
  std::vector<std::atomic<int>> runs(count);
  geom::run_on_workers(count, [&](std::size_t k) { ++runs[k]; });
  std::vector<int> out;
  for (auto& r : runs) out.push_back(r.load());
  return out;
}

TEST(Workers, EveryItemRunsOnce) {
  EXPECT_GE(geom::worker_capacity(), 1);
  for (std::size_t count : {0u, 1u, 2u, 3u, 17u, 1000u}) {
    const std::vector<int> runs = runs_of(count);
    ASSERT_EQ(runs.size(), count);
    for (std::size_t k = 0; k < count; ++k) EXPECT_EQ(runs[k], 1) << "k = " << k << " of " << count;
  }
}

TEST(Workers, NestedJobsRunWhole) {
  // A job inside a job finds the workers taken and runs on its own thread.
  std::vector<std::atomic<int>> runs(8 * 50);
  geom::run_on_workers(8, [&](std::size_t i) {
    geom::run_on_workers(50, [&](std::size_t j) { ++runs[i * 50 + j]; });
  });
  for (std::size_t k = 0; k < runs.size(); ++k) EXPECT_EQ(runs[k].load(), 1) << k;
}

TEST(Workers, CallersAtOnce) {
  // Four threads each run 200 jobs; one at a time has the workers, the others run
  // theirs alone; every item of every job runs once.
  std::atomic<int> wrong{0};
  std::vector<std::thread> callers;
  for (int c = 0; c < 4; ++c)
    callers.emplace_back([&] {
      for (int job = 0; job < 200; ++job) {
        const std::vector<int> runs = runs_of(1 + static_cast<std::size_t>(job % 7));
        for (int r : runs) wrong += r != 1;
      }
    });
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST(Workers, TheFirstExceptionByItemIsThrown) {
  for (int trial = 0; trial < 50; ++trial) {
    std::atomic<int> ran{0};
    try {
      geom::run_on_workers(40, [&](std::size_t k) {
        ++ran;
        if (k == 9 || k == 31) throw std::runtime_error("item " + std::to_string(k));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 9");
    }
    EXPECT_EQ(ran.load(), 40);  // the others still ran (a job stops as a whole)
  }
}

TEST(Workers, ExactEvaluationsAreCountedOnTheCaller) {
  const std::size_t before = geom::exact_evaluations();
  geom::run_on_workers(100, [&](std::size_t k) { geom::exact_evaluations() += k; });
  EXPECT_EQ(geom::exact_evaluations() - before, 99u * 100u / 2u);
}

}  // namespace
}  // namespace cellforge
