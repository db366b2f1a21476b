#include "core/parallel.h"

#include <cstdlib>

namespace dynamesh {
namespace {

const char* g_policy = "default";

// Runs from the executable's .preinit_array (see parallel.h): before libgomp reads its
// environment. Only ever adds a variable; a user's own setting is kept.
void choose_wait_policy(int, char**, char**) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) {
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
