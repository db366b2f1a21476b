// The process's CPU time (all threads), for benchmarks on a shared machine: wall time also
// counts the time other processes held the cores, CPU time only the work.
#pragma once

#include <time.h>

namespace dynamesh {

inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace dynamesh
