// Per-step statistics over time, for the panel's plots (not saved: it is a record, not a
// setting).
#pragma once

#include <vector>

#include "app/viewer/simulation.h"

namespace dynamesh {

struct StatsHistory {
  static constexpr std::size_t kCapacity = 4000;
  std::vector<float> time, triangles, max_error, step_ms;

  void add(double t, const StepStatistics& s) {
    if (time.size() >= kCapacity) clear();
    time.push_back(static_cast<float>(t));
    triangles.push_back(static_cast<float>(s.triangles));
    max_error.push_back(static_cast<float>(s.max_error));
    step_ms.push_back(static_cast<float>(1e3 * s.seconds));
  }
  void clear() { *this = StatsHistory{}; }
};

}  // namespace dynamesh
