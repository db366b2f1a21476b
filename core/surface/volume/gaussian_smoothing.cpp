#include "core/surface/volume/gaussian_smoothing.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dynamesh {
namespace {

std::vector<float> gaussian_kernel(double sigma_voxels) {
  const int radius = static_cast<int>(std::ceil(3.0 * sigma_voxels));
  std::vector<float> w(2 * radius + 1);
  double sum = 0.0;
  for (int t = -radius; t <= radius; ++t) {
    const double v = std::exp(-0.5 * t * t / (sigma_voxels * sigma_voxels));
    w[t + radius] = static_cast<float>(v);
    sum += v;
  }
  for (float& v : w) v = static_cast<float>(v / sum);
  return w;
}

// One axis: the volume is seen as [outer][n][inner] with `inner` contiguous values per
// position along the axis, so every pass but the first streams whole contiguous rows.
void convolve_axis(const std::vector<float>& in, std::vector<float>& out, std::size_t outer, int n,
                   std::size_t inner, const std::vector<float>& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
  const auto rows = static_cast<std::ptrdiff_t>(outer * static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t row = 0; row < rows; ++row) {
    const std::size_t o = static_cast<std::size_t>(row) / n;
    const int q = static_cast<int>(row % n);
    float* dst = out.data() + (o * n + q) * inner;
    std::fill(dst, dst + inner, 0.0f);
    for (int t = -radius; t <= radius; ++t) {
      const int src_q = std::clamp(q + t, 0, n - 1);
      const float* src = in.data() + (o * n + src_q) * inner;
      const float w = kernel[t + radius];
      for (std::size_t i = 0; i < inner; ++i) dst[i] += w * src[i];
    }
  }
}

}  // namespace

ScalarVolume gaussian_smoothed(const ScalarVolume& volume, double sigma_mm) {
  ScalarVolume result = volume;
  if (!(sigma_mm > 0.0)) return result;
  const auto& dims = volume.grid.dims;
  const Vec3 spacing = volume.grid.spacing();
  std::vector<float> scratch(result.values.size());
  std::size_t inner = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t outer = result.values.size() / (inner * dims[axis]);
    const double sigma_voxels = sigma_mm / spacing[axis];
    if (sigma_voxels >= 0.1 && dims[axis] > 1) {
      convolve_axis(result.values, scratch, outer, dims[axis], inner,
                    gaussian_kernel(sigma_voxels));
      result.values.swap(scratch);
    }
    inner *= dims[axis];
  }
  return result;
}

}  // namespace dynamesh
