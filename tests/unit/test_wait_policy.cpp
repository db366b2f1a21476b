// The engine's OpenMP wait policy (core/parallel.h): every program that links the engine runs
// with libgomp's workers asleep between parallel loops, not spinning, unless the user chose a
// policy. This test binary is such a program. Until 2026-11-27 the engine set the variable from
// its .preinit_array, where glibc's environment is not yet set up: engine_wait_policy() said
// "passive" while libgomp never saw it, and each worker spun ~7 ms of CPU after every loop
// (measured below: 6-8 ms per loop then, 0.06 ms now), which on a busy 2-core machine took the
// core a late thread needed.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "core/parallel.h"
#include "tests/bench/process_cpu_time.h"

namespace dynamesh {
namespace {

// Why the engine's policy is not this process's to check, or null when it is.
const char* not_the_engines_policy() {
  const char* marker = std::getenv("DYNAMESH_OMP_WAIT_POLICY");
  const bool engine = marker != nullptr && std::strcmp(marker, "engine") == 0;
  if (!engine && (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")))
    return "the user's OMP_WAIT_POLICY / GOMP_SPINCOUNT decide";
  if (std::string(engine_wait_policy()) == "default")
    return "the engine could not set the policy here (under valgrind?)";
  return nullptr;
}

TEST(WaitPolicy, EngineSetsPassiveWhereLibgompSeesIt) {
  if (const char* why = not_the_engines_policy()) GTEST_SKIP() << why;
  EXPECT_STREQ(engine_wait_policy(), "passive");
  // What libgomp read when it was loaded: the process's environment (the re-executed image's).
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  ASSERT_NE(policy, nullptr);
  EXPECT_STREQ(policy, "passive");
}

TEST(WaitPolicy, WorkersSleepAfterAParallelLoop) {
  if (const char* why = not_the_engines_policy()) GTEST_SKIP() << why;
  // After each loop the main thread sleeps 20 ms: the CPU the process uses meanwhile is its
  // workers' (spinning: libgomp's default spins ~300,000 times, several ms, before sleeping).
  constexpr int kLoops = 10;
  double idle_cpu = 0.0;
  for (int loop = 0; loop < kLoops; ++loop) {
    double sum = 0.0;
#pragma omp parallel for num_threads(2) reduction(+ : sum)
    for (int i = 0; i < 200000; ++i) sum += 1e-9 * i;
    ASSERT_GT(sum, 0.0);
    const double before = process_cpu_seconds();
    usleep(20000);
    idle_cpu += process_cpu_seconds() - before;
  }
  EXPECT_LT(idle_cpu / kLoops, 1e-3) << "seconds of CPU per loop while the main thread slept";
}

}  // namespace
}  // namespace dynamesh
