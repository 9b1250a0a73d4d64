#include "huge_page_heap.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <unistd.h>
#if defined(__GLIBC__)
#include <gnu/libc-version.h>
#endif

namespace pfgen::cli {
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

#if defined(__GLIBC__) && defined(__linux__)
bool glibc_has_hugetlb_tunable() {
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2) return false;
  return major > 2 || (major == 2 && minor >= 35);
}

// The kernel gives huge pages to a region only when asked (madvise) in the mode "[madvise]";
// "[always]" gives them anyway and "[never]" never does, so only "[madvise]" gains.
bool kernel_gives_huge_pages_when_asked() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(mode, line) && line.find("[madvise]") != std::string::npos;
}
#endif

}  // namespace

void use_huge_page_heap(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  // Opt-in: whether huge pages pay depends on the machine (docs/benchmarks.md).
  const char* opt_in = std::getenv("PFGEN_HUGE_PAGES");
  if (opt_in == nullptr || std::strcmp(opt_in, "1") != 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables != nullptr ? tunables : "";
  // Already set (by the user, or by this function before the execution): never execute twice.
  if (before.find("glibc.malloc.hugetlb") != std::string::npos) return;
  if (!glibc_has_hugetlb_tunable() || !kernel_gives_huge_pages_when_asked()) return;
  const std::string after = before.empty() ? kTunable : before + ":" + kTunable;
  if (setenv("GLIBC_TUNABLES", after.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Only reached when the execution failed: carry on as this process, environment as it was.
  if (tunables != nullptr)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

}  // namespace pfgen::cli
