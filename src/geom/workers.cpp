// geom/workers.h.
//
// One job at a time: the caller publishes it (a work function, a count, a counter of
// the next k), wakes the workers and takes k's itself like any of them; a worker
// joins only while the job is published, and the caller withdraws it, then waits for
// the workers still inside, before returning (the job lives on its stack).
#include "cellforge/geom/workers.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "cellforge/geom/filtered.h"

namespace cellforge::inline geom {

namespace {

thread_local bool on_a_worker = false;

struct Job {
  const std::function<void(std::size_t)>* work = nullptr;
  std::size_t count = 0;
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> exact{0};    // exact evaluations on the workers
  std::exception_ptr error;             // the first by k, under the pool's lock
  std::size_t error_k = 0;
};

class Pool {
 public:
  explicit Pool(int workers) {
    for (int i = 0; i < workers; ++i)
      threads_.emplace_back([this] {
        on_a_worker = true;
        serve();
      });
  }
  // Never destroyed (see instance()): the workers wait until the process ends.

  int workers() const { return static_cast<int>(threads_.size()); }

  // False when the workers are taken: the caller then runs the job alone.
  bool run(Job& job) {
    bool expected = false;
    if (on_a_worker || threads_.empty() || !busy_.compare_exchange_strong(expected, true)) return false;
    {
      std::lock_guard hold(lock_);
      job_ = &job;
      ++generation_;
    }
    wake_.notify_all();
    take(job);
    {
      std::unique_lock hold(lock_);
      job_ = nullptr;  // no worker joins from here on
      done_.wait(hold, [&] { return inside_ == 0; });
    }
    busy_.store(false);
    return true;
  }

  static void take(Job& job) {
    for (std::size_t k = job.next++; k < job.count; k = job.next++) {
      try {
        (*job.work)(k);
      } catch (...) {
        std::lock_guard hold(instance().lock_);
        if (!job.error || k < job.error_k) {
          job.error = std::current_exception();
          job.error_k = k;
        }
      }
    }
  }

  static Pool& instance() {
    // Leaked on purpose: destroying it at exit would join threads that other static
    // destructors may still be waiting on.
    static Pool* pool = new Pool(std::max(1, static_cast<int>(std::thread::hardware_concurrency())) - 1);
    return *pool;
  }

 private:
  void serve() {
    std::uint64_t seen = 0;
    for (;;) {
      Job* job = nullptr;
      {
        std::unique_lock hold(lock_);
        wake_.wait(hold, [&] { return generation_ != seen; });
        seen = generation_;
        if (job_ == nullptr) continue;  // withdrawn already
        job = job_;
        ++inside_;
      }
      const std::size_t before = exact_evaluations();
      take(*job);
      job->exact += exact_evaluations() - before;
      {
        std::lock_guard hold(lock_);
        --inside_;
      }
      done_.notify_all();
    }
  }

  std::vector<std::thread> threads_;
  std::atomic<bool> busy_{false};
  std::mutex lock_;
  std::condition_variable wake_, done_;
  Job* job_ = nullptr;
  std::uint64_t generation_ = 0;
  int inside_ = 0;
};

}  // namespace

void run_on_workers(std::size_t count, const std::function<void(std::size_t)>& work) {
  if (count == 0) return;
  if (count == 1) {
    work(0);
    return;
  }
  Job job;
  job.work = &work;
  job.count = count;
  if (Pool::instance().run(job)) {
    exact_evaluations() += job.exact.load();
  } else {
    Pool::take(job);  // all here, in order
  }
  if (job.error) std::rethrow_exception(job.error);
}

int worker_capacity() { return Pool::instance().workers() + 1; }

}  // namespace cellforge::inline geom
