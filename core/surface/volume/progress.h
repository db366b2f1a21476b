// Progress reports of long preprocessing (reading, segmenting, distance transform): the
// stage's name and the fraction of that stage done, 0..1. Called from the thread that runs
// the preprocessing, never from inside a parallel region.
#pragma once

#include <functional>
#include <string_view>

namespace dynamesh {

using ProgressCallback = std::function<void(std::string_view stage, double fraction)>;

inline void report(const ProgressCallback& progress, std::string_view stage, double fraction) {
  if (progress) progress(stage, fraction);
}

}  // namespace dynamesh
