// geom/memory.h: re-running the program with glibc.malloc.hugetlb=1.
#include "cellforge/geom/memory.h"

#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace cellforge::inline geom {
namespace {

// Where the tunables the program started with are kept across the exec ("-" for none).
constexpr const char* kBefore = "CELLFORGE_GLIBC_TUNABLES_BEFORE";

// Whether transparent huge pages go only to memory that asks for them: "always" needs
// no asking, "never" gives none.
bool kernel_gives_on_request() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(in, mode);
  return mode.find("[madvise]") != std::string::npos;
}

}  // namespace

void prefer_huge_pages(char** argv) {
#if defined(__GLIBC__)
  const char* off = std::getenv("CELLFORGE_HUGE_PAGES");
  if (off != nullptr && std::strcmp(off, "0") == 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb") != nullptr) return;
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) return;
  if (!kernel_gives_on_request()) return;
  const std::string before = tunables != nullptr ? tunables : "";
  const std::string after = before.empty() ? "glibc.malloc.hugetlb=1" : before + ":glibc.malloc.hugetlb=1";
  setenv(kBefore, tunables != nullptr ? tunables : "-", 1);
  setenv("GLIBC_TUNABLES", after.c_str(), 1);
  execv("/proc/self/exe", argv);
  // Still here: the exec failed; the program runs on as it was.
  if (tunables != nullptr)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
  unsetenv(kBefore);
#else
  (void)argv;
#endif
}

void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

void restore_tunables_for_children() {
  const char* before = std::getenv(kBefore);
  if (before == nullptr) return;
  if (std::strcmp(before, "-") == 0)
    unsetenv("GLIBC_TUNABLES");
  else
    setenv("GLIBC_TUNABLES", before, 1);
  unsetenv(kBefore);
}

}  // namespace cellforge::inline geom
