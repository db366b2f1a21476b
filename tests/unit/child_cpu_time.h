// CPU time (user + system) of this process's reaped children, for tests that bound what a
// run of the real binary costs: on a loaded machine wall time also counts the time other
// processes held the cores, CPU time only the run's own work.
#pragma once

#include <sys/resource.h>

namespace dynamesh::test {

inline double children_cpu_seconds() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace dynamesh::test
