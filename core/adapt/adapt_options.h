// Options of the adaptation (de Goes et al. 2006, Section 3; defaults from DESIGN.md).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/geometry/tangential_smoothing.h"

namespace dynamesh {

struct AdaptOptions {
  double threshold = 0.008;  // T: target geometric error (scene units)
  double epsilon = 0.002;    // eps: hysteresis half-width; weld below T - eps, split above T + eps
  double density = 2000.0;   // D: samples per unit area (at least one per triangle)
  std::uint64_t seed = 1;    // sample jitter; runs with the same seed are identical
  std::size_t max_triangles = 2'000'000;  // refinement stops at this budget (reported)
  bool structural = true;                 // split and weld
  bool geometric = true;                  // normal and tangential correction
  SmoothingOptions smoothing;
};

}  // namespace dynamesh
