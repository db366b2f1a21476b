#include "core/parallel.h"

#include <unistd.h>

#include <cstdlib>
#include <iterator>
#include <string_view>

namespace dynamesh {
namespace {

const char* g_policy = "default";

// Added to the environment with OMP_WAIT_POLICY when the engine re-executes its program (below),
// so that the new image knows the policy was the engine's and not the user's.
constexpr char kMarker[] = "DYNAMESH_OMP_WAIT_POLICY=engine";
constexpr char kPassive[] = "OMP_WAIT_POLICY=passive";

// Runs from the executable's .preinit_array (see parallel.h), before libgomp reads its
// environment. A variable cannot simply be added here: glibc's environ is not set up yet at
// this point (setenv builds an environment of its own, which libc's start-up then replaces with
// the kernel's, so libgomp never saw it: until 2026-11-27 the engine reported "passive" while
// libgomp's workers spun ~7 ms after every parallel loop, tests/unit/test_wait_policy.cpp). So
// when neither the user nor an earlier start set a policy, the program is executed again, once,
// with the same arguments and OMP_WAIT_POLICY=passive added to the environment the kernel passed
// (`envp`). Not under valgrind, which would lose the program at the exec (its tools run one
// thread at a time anyway); if the exec fails the program goes on with libgomp's default.
void choose_wait_policy(int, char** argv, char** envp) {
  bool marked = false, passive = false, user = false, valgrind = false;
  std::size_t count = 0;
  for (char** e = envp; e && *e; ++e, ++count) {
    const std::string_view v(*e);
    marked = marked || v == kMarker;
    passive = passive || v == kPassive;
    user = user || v.starts_with("OMP_WAIT_POLICY=") || v.starts_with("GOMP_SPINCOUNT=");
    valgrind = valgrind || (v.starts_with("LD_PRELOAD=") && v.find("vgpreload") != v.npos);
  }
  if (marked && passive) {
    g_policy = "passive";
    return;
  }
  if (user) {
    g_policy = "user";
    return;
  }
  static char* env[4096];
  if (valgrind || argv == nullptr || count + 3 > std::size(env)) return;
  std::size_t n = 0;
  for (char** e = envp; e && *e; ++e) env[n++] = *e;
  env[n++] = const_cast<char*>(kPassive);
  env[n++] = const_cast<char*>(kMarker);
  env[n] = nullptr;
  execve("/proc/self/exe", argv, env);  // returns only on failure
}

// In a static library this entry is kept only when the object file is linked, which
// engine_wait_policy()'s use by the Adapter ensures.
__attribute__((section(".preinit_array"),
               used)) void (*const preinit_entry)(int, char**, char**) = choose_wait_policy;

}  // namespace

const char* engine_wait_policy() {
  return g_policy;
}

}  // namespace dynamesh
