#include "core/parallel.h"

#include <cstdlib>
#include <cstring>

namespace dynamesh {
namespace {

const char* g_policy = "default";

// Runs from the executable's .preinit_array (see parallel.h): before libgomp reads its
// environment. Only ever adds a variable; a user's own setting is kept. The environment is
// read from `envp`, which the loader passes (getenv may not see it this early).
void choose_wait_policy(int, char**, char** envp) {
  for (char** e = envp; e && *e; ++e)
    if (std::strncmp(*e, "OMP_WAIT_POLICY=", 16) == 0 ||
        std::strncmp(*e, "GOMP_SPINCOUNT=", 15) == 0) {
      g_policy = "user";
      return;
    }
  if (setenv("OMP_WAIT_POLICY", "passive", 0) == 0) g_policy = "passive";
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
