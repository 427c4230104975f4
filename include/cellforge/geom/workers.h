// The process's worker threads: started on first use (one fewer than the hardware
// threads, the caller being one) and kept, so that a parallel stage costs a wake-up,
// not a thread's start. Starting and joining a thread took 90 us to 1.4 ms on the
// 2-core machine the project is measured on; a Boolean has a dozen parallel stages.
//
//   run_on_workers(count, [&](std::size_t k) { ... });
//
// runs work(k) for every k in [0, count), on this thread and the workers, each k once,
// in no particular order, and returns when all are done. Callers make results that do
// not depend on which thread ran which k (every k fills its own part), so where the
// workers are taken (by another caller, or because this is one of them: a parallel
// stage inside another) every k runs here in order. The exact evaluations made on the
// workers are counted on this thread (filtered.h). An exception thrown by a work item
// is thrown here once all have stopped (the first one, by k).
#pragma once
#include <cstddef>
#include <functional>

namespace cellforge::inline geom {

void run_on_workers(std::size_t count, const std::function<void(std::size_t)>& work);

// The number of worker threads plus the caller: what run_on_workers can use at once.
int worker_capacity();

}  // namespace cellforge::geom
