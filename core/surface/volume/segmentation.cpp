#include "core/surface/volume/segmentation.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/surface/volume/connected_components.h"
#include "core/surface/volume/distance_transform.h"
#include "core/surface/volume/gaussian_smoothing.h"
#include "core/surface/volume/otsu_threshold.h"

namespace dynamesh {
namespace {

constexpr std::string_view kStage = "segmenting";

MaskVolume threshold_mask(const ScalarVolume& smoothed, double threshold) {
  MaskVolume mask(smoothed.grid, 0);
  const auto n = static_cast<std::ptrdiff_t>(smoothed.values.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t v = 0; v < n; ++v) mask.values[v] = smoothed.values[v] > threshold ? 1 : 0;
  return mask;
}

}  // namespace

void close_mask(MaskVolume& mask, double radius_mm) {
  if (!(radius_mm > 0.0)) return;
  const float r2 = static_cast<float>(radius_mm * radius_mm);
  const DistanceTransformResult to_inside = distance_transform(mask, 1);
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    mask.values[v] = to_inside.squared[v] <= r2 ? 1 : 0;
  }
  const DistanceTransformResult to_outside = distance_transform(mask, 0);
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    if (mask.values[v] && to_outside.squared[v] <= r2) mask.values[v] = 0;
  }
}

void open_mask(MaskVolume& mask, double radius_mm) {
  if (!(radius_mm > 0.0)) return;
  const float r2 = static_cast<float>(radius_mm * radius_mm);
  const DistanceTransformResult to_outside = distance_transform(mask, 0);
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    if (mask.values[v] && to_outside.squared[v] <= r2) mask.values[v] = 0;
  }
  const DistanceTransformResult to_inside = distance_transform(mask, 1);
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    mask.values[v] = to_inside.squared[v] <= r2 ? 1 : 0;
  }
}

Segmentation segment_volume(const ScalarVolume& intensity, const SegmentationOptions& options,
                            const ProgressCallback& progress) {
  Segmentation s;
  report(progress, kStage, 0.0);
  const ScalarVolume smoothed = gaussian_smoothed(intensity, options.smoothing_sigma_mm);
  report(progress, kStage, 0.3);
  s.otsu = !(options.threshold > 0.0);
  s.threshold = s.otsu ? otsu_threshold(smoothed.values) : options.threshold;
  s.mask = threshold_mask(smoothed, s.threshold);
  report(progress, kStage, 0.4);
  open_mask(s.mask, options.opening_radius_mm);
  s.components = keep_largest_component(s.mask);
  if (s.components == 0) {
    throw std::invalid_argument("segmentation: no voxel above the threshold " +
                                std::to_string(s.threshold));
  }
  report(progress, kStage, 0.5);
  close_mask(s.mask, options.closing_radius_mm);
  report(progress, kStage, 0.8);
  s.holes_filled = fill_holes(s.mask);
  s.voxels = static_cast<std::size_t>(std::count(s.mask.values.begin(), s.mask.values.end(), 1));
  report(progress, kStage, 1.0);
  return s;
}

}  // namespace dynamesh
