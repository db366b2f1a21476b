#include "core/adapt/adapt_options_check.h"

#include <cmath>

namespace dynamesh {

std::string adapt_option_problem(const AdaptOptions& o) {
  if (!(std::isfinite(o.threshold) && o.threshold > 0))
    return "--threshold must be positive (try 0.008)";
  if (!(std::isfinite(o.epsilon) && o.epsilon >= 0)) return "--epsilon must not be negative";
  if (!(std::isfinite(o.density) && o.density > 0))
    return "--density must be positive (samples per unit area)";
  if (o.max_triangles < kMinTriangleBudget)
    return "--max-triangles must be at least " + std::to_string(kMinTriangleBudget);
  const SmoothingOptions& s = o.smoothing;
  if (!(std::isfinite(s.k) && s.k >= 0)) return "--k must not be negative";
  if (s.iterations < 0 || s.iterations > kMaxSmoothIterations)
    return "--smooth-iters must be between 0 and " + std::to_string(kMaxSmoothIterations);
  if (!(s.settled_offset >= 0 && s.settled_offset < 1))
    return "--smooth-settled must be at least 0 and below 1 (a fraction of an edge)";
  return {};
}

}  // namespace dynamesh
