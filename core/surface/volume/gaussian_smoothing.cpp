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
// The first axis (inner == 1): each line is padded by its replicated ends into a scratch
// row, so the taps run without clamping over contiguous values and vectorise along q.
void convolve_lines(const std::vector<float>& in, std::vector<float>& out, std::size_t lines, int n,
                    const std::vector<float>& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
#pragma omp parallel
  {
    std::vector<float> padded(static_cast<std::size_t>(n + 2 * radius));
#pragma omp for schedule(static)
    for (std::ptrdiff_t line = 0; line < static_cast<std::ptrdiff_t>(lines); ++line) {
      const float* src = in.data() + static_cast<std::size_t>(line) * n;
      float* dst = out.data() + static_cast<std::size_t>(line) * n;
      std::fill(padded.begin(), padded.begin() + radius, src[0]);
      std::copy(src, src + n, padded.begin() + radius);
      std::fill(padded.begin() + radius + n, padded.end(), src[n - 1]);
      std::fill(dst, dst + n, 0.0f);
      for (int t = 0; t <= 2 * radius; ++t) {
        const float w = kernel[t];
        const float* p = padded.data() + t;
        for (int q = 0; q < n; ++q) dst[q] += w * p[q];
      }
    }
  }
}

void convolve_axis(const std::vector<float>& in, std::vector<float>& out, std::size_t outer, int n,
                   std::size_t inner, const std::vector<float>& kernel) {
  if (inner == 1) return convolve_lines(in, out, outer, n, kernel);
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

// Smooths `source` along every axis that needs it into `out`, with `scratch` as the
// ping-pong buffer; returns false (nothing written) when no axis needs smoothing. `source`
// may be `out`'s own values.
bool smooth_axes(const std::vector<float>& source, const VoxelGrid& grid, double sigma_mm,
                 std::vector<float>& out, std::vector<float>& scratch) {
  const auto& dims = grid.dims;
  const Vec3 spacing = grid.spacing();
  const std::vector<float>* in = &source;
  std::size_t inner = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t outer = source.size() / (inner * dims[axis]);
    const double sigma_voxels = sigma_mm / spacing[axis];
    if (sigma_voxels >= 0.1 && dims[axis] > 1) {
      // The first pass reads `source` and writes whichever buffer is not it.
      std::vector<float>& target = in == &out ? scratch : out;
      reserve_huge(target, source.size());
      target.resize(source.size());
      convolve_axis(*in, target, outer, dims[axis], inner, gaussian_kernel(sigma_voxels));
      if (&target == &scratch) out.swap(scratch);
      in = &out;
    }
    inner *= dims[axis];
  }
  return in == &out;
}

}  // namespace

ScalarVolume gaussian_smoothed(const ScalarVolume& volume, double sigma_mm) {
  ScalarVolume result;
  result.grid = volume.grid;
  std::vector<float> scratch;
  if (!(sigma_mm > 0.0) ||
      !smooth_axes(volume.values, volume.grid, sigma_mm, result.values, scratch))
    result.values = volume.values;
  return result;
}

void gaussian_smooth(ScalarVolume& volume, double sigma_mm) {
  if (!(sigma_mm > 0.0)) return;
  std::vector<float> scratch;
  smooth_axes(volume.values, volume.grid, sigma_mm, volume.values, scratch);
}

}  // namespace dynamesh
