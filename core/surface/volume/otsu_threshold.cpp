#include "core/surface/volume/otsu_threshold.h"

#include <algorithm>
#include <cstdint>

namespace dynamesh {

double otsu_threshold(const std::vector<float>& values, int bins) {
  if (values.empty()) return 0.0;
  const auto [lo_it, hi_it] = std::minmax_element(values.begin(), values.end());
  const double lo = *lo_it, hi = *hi_it;
  if (!(hi > lo)) return lo;
  const double scale = bins / (hi - lo);
  std::vector<std::uint64_t> histogram(bins, 0);
  for (const float v : values) {
    ++histogram[std::min(bins - 1, static_cast<int>((v - lo) * scale))];
  }
  // Between-class variance w0 w1 (mu0 - mu1)^2 with bin centres as intensities, scanned
  // with running sums (Otsu 1979, Eq. 18).
  double total = 0.0, total_sum = 0.0;
  for (int b = 0; b < bins; ++b) {
    total += static_cast<double>(histogram[b]);
    total_sum += static_cast<double>(histogram[b]) * (b + 0.5);
  }
  double w0 = 0.0, sum0 = 0.0, best = -1.0;
  int best_bin = 0;
  for (int b = 0; b + 1 < bins; ++b) {
    w0 += static_cast<double>(histogram[b]);
    sum0 += static_cast<double>(histogram[b]) * (b + 0.5);
    const double w1 = total - w0;
    if (w0 == 0.0 || w1 == 0.0) continue;
    const double diff = sum0 / w0 - (total_sum - sum0) / w1;
    const double between = w0 * w1 * diff * diff;
    if (between > best) {
      best = between;
      best_bin = b;
    }
  }
  return lo + (best_bin + 1) / scale;
}

}  // namespace dynamesh
