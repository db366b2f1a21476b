// The median of a benchmark's per-step samples (the upper middle one for an even count; 0 for
// none): the figure the step benchmarks report, robust against the VM's occasional slow step.
#pragma once

#include <algorithm>
#include <vector>

namespace dynamesh {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace dynamesh
