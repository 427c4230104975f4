// How a program built on cellforge can have the kernel back its heap with huge pages.
//
// A Boolean of two spheres of 262,000 triangles each touches about 200 MB that it has
// just allocated. Each 4 KiB page costs a fault the first time it is touched, and on
// a virtual machine a fault costs microseconds (7.8 us measured here): 96,000 faults,
// a third of the run. With transparent huge pages (2 MiB) the same run faults 5,400
// times and takes 0.79 s instead of 1.2 s (docs/benchmarks.md, "Page faults").
//
// Linux gives huge pages to the memory a program asks for with madvise(MADV_HUGEPAGE)
// when /sys/kernel/mm/transparent_hugepage/enabled is "madvise" (Debian's default);
// glibc's malloc does that for its heap under the tunable glibc.malloc.hugetlb=1,
// which it reads from the environment when the program starts and never again.
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace cellforge::inline geom {

// Runs the program again, at once, with GLIBC_TUNABLES extended by
// glibc.malloc.hugetlb=1 (execv of /proc/self/exe with the same argv): call it first
// in main(). Returns without doing anything when the environment already says
// glibc.malloc.hugetlb, when CELLFORGE_HUGE_PAGES=0, when the kernel gives huge pages
// to every program or to none, under valgrind (which follows no exec), or when the
// exec fails. Only glibc's malloc reads the tunable; with another C library or
// allocator it changes nothing.
void prefer_huge_pages(char** argv);

// Keeps memory that the program frees for its own later allocations instead of giving
// it back to the system (glibc's mallopt: no trimming of the heap's top below 1 GiB,
// blocks below 32 MiB, glibc's largest threshold, from the heap): a large Boolean
// allocates and frees its arrays stage by stage, and the next stage then reuses pages
// already faulted in. Blocks of 32 MiB and more get mappings of their own, returned
// when freed: kept in the heap, a big array freed early left a hole that later arrays
// of other sizes did not fit, and the peak grew by it (sphere - sphere fn 1024, on
// 2026-12-03: 593 MB with every block in the heap, 523 MB with blocks of 8 MiB and
// more mapped). On 2026-12-07 blocks from 8 to 32 MiB were moved to the heap: the
// peak 353 -> 358 MB there, the run on two threads 1.25-1.44 -> 1.24-1.30 s (each
// thread's arena reuses its own freed blocks). For a program that runs one large
// job, not for a long-lived one whose memory use falls for good.
void keep_freed_memory();

// Puts back the GLIBC_TUNABLES that the program had before prefer_huge_pages, for a
// program it is about to start that should run as it would on its own.
void restore_tunables_for_children();

// An allocator whose construct() with no arguments default-initializes: a vector of a
// trivially constructible type resized through it is left as the allocation gives it,
// not zeroed. A big array that is filled anyway is then written once, not twice, and
// first touched where it is filled (on threads, where the filling is), not in a pass of
// its own on one thread: 56 MB of boxes and groups for two spheres of 10^6 triangles
// took 0.11-0.18 s to zero on this machine, where fresh memory costs 2-3 ms a MB.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
// A vector whose resize(n) leaves trivially constructible elements unset.
template <class T>
using RawVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace cellforge::inline geom
