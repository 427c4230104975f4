// Ranges of work on threads, with results that do not depend on the thread count.
//
//   std::vector<Out> parts = parallel_ranges<Out>(n, threads, [&](lo, hi, Out& out) {...});
//
// [0, n) is cut into contiguous ranges, one per thread (the calling thread takes the
// first); each range fills its own Out, and the caller reads the parts in order, so
// that concatenating them gives what one thread would have made. The body must only
// read shared state. The exact evaluations made on other threads are counted on
// this one (filtered.h), so that the report does not depend on the thread count.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include "cellforge/geom/filtered.h"
#include "cellforge/geom/workers.h"

namespace cellforge::boolean {

// The number of threads `requested` stands for: 0 is every hardware thread.
inline int thread_count(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// work(k) for k in [0, count), on the worker threads (geom/workers.h: k's in any
// order, the exact evaluations made on the others counted on this one).
template <class Work>
void on_threads(std::size_t count, Work&& work) {
  geom::run_on_workers(count, [&](std::size_t k) { work(k); });
}

template <class Out, class Body>
std::vector<Out> parallel_ranges(std::size_t n, int threads, Body&& body) {
  // Ranges too small to pay for a thread stay on this one.
  constexpr std::size_t kMinRange = 256;
  const std::size_t parts =
      std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(thread_count(threads)),
                                                     n / kMinRange));
  std::vector<Out> out(parts);
  on_threads(parts, [&](std::size_t k) { body(n * k / parts, n * (k + 1) / parts, out[k]); });
  return out;
}

// Jobs [0, n) of uneven sizes on threads, handed out one at a time; job k fills
// out[k], so reading the parts in order gives what one thread would have made.
template <class Out, class Body>
std::vector<Out> parallel_jobs(std::size_t n, int threads, Body&& body) {
  std::vector<Out> out(n);
  std::atomic<std::size_t> next{0};
  on_threads(std::min<std::size_t>(static_cast<std::size_t>(thread_count(threads)), std::max<std::size_t>(n, 1)),
             [&](std::size_t) {
               for (std::size_t k = next++; k < n; k = next++) body(k, out[k]);
             });
  return out;
}

}  // namespace cellforge::boolean
