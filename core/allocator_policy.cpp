#include "core/allocator_policy.h"

#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dynamesh {
namespace {

const char* g_policy = "default";

bool user_set_thresholds(char** envp) {
  for (char** e = envp; e && *e; ++e) {
    if (std::strncmp(*e, "MALLOC_MMAP_THRESHOLD_=", 23) == 0 ||
        std::strncmp(*e, "MALLOC_TRIM_THRESHOLD_=", 23) == 0)
      return true;
    if (std::strncmp(*e, "GLIBC_TUNABLES=", 15) == 0 &&
        (std::strstr(*e, "mmap_threshold") || std::strstr(*e, "trim_threshold")))
      return true;
  }
  return false;
}

// Runs from the executable's .preinit_array (as parallel.cpp's wait policy): before any
// static constructor allocates, so every block of the program is placed by the same rule.
void choose_allocator_policy([[maybe_unused]] int argc, [[maybe_unused]] char** argv, char** envp) {
  if (user_set_thresholds(envp)) {
    g_policy = "user";
    return;
  }
#if defined(__GLIBC__)
  // Fixing the mmap threshold also stops glibc from raising the trim threshold: the free
  // top of the heap is given back above glibc's default 128 kB again.
  if (mallopt(M_MMAP_THRESHOLD, static_cast<int>(kMmapThreshold)) == 1)
    g_policy = "fixed thresholds";
#endif
}

// In a static library this entry is kept only when the object file is linked, which
// engine_allocator_policy()'s use by SampleStore ensures.
__attribute__((section(".preinit_array"),
               used)) void (*const preinit_entry)(int, char**, char**) = choose_allocator_policy;

}  // namespace

const char* engine_allocator_policy() {
  return g_policy;
}

}  // namespace dynamesh
