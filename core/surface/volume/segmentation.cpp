#include "core/surface/volume/segmentation.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/io/number_text.h"
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

// Area of the mask's voxel faces on the volume's six sides, in mm^2.
double border_contact_mm2(const MaskVolume& mask) {
  const auto& n = mask.grid.dims;
  const Vec3 h = mask.grid.spacing();
  const double face[3] = {h[1] * h[2], h[0] * h[2], h[0] * h[1]};  // normal along i, j, k
  double area = 0.0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (!mask.at(i, j, k)) continue;
        area += face[0] * ((i == 0) + (i == n[0] - 1)) + face[1] * ((j == 0) + (j == n[1] - 1)) +
                face[2] * ((k == 0) + (k == n[2] - 1));
      }
  return area;
}

constexpr const char* kHint =
    "; is this a skull-stripped brain? pass a brain mask with --mask FILE (e.g. from FSL BET "
    "or SynthStrip)";

void check_plausible(const MaskVolume& mask, const SegmentationOptions& o) {
  if (o.max_border_contact_mm2 > 0.0) {
    const double contact = border_contact_mm2(mask);
    if (contact > o.max_border_contact_mm2)
      throw std::invalid_argument(
          "segmentation: the brain component touches the volume's border "
          "over " +
          format_significant(contact / 100.0, 3) + " cm^2 (at most " +
          format_significant(o.max_border_contact_mm2 / 100.0, 3) + ")" + kHint);
  }
  const double ml = static_cast<double>(std::count(mask.values.begin(), mask.values.end(), 1)) *
                    mask.grid.voxel_volume() / 1000.0;
  if ((o.min_volume_ml > 0.0 && ml < o.min_volume_ml) ||
      (o.max_volume_ml > 0.0 && ml > o.max_volume_ml))
    throw std::invalid_argument("segmentation: the brain component holds " +
                                format_significant(ml, 3) + " ml, outside the plausible " +
                                format_significant(o.min_volume_ml, 3) + "-" +
                                format_significant(o.max_volume_ml, 3) + " ml" + kHint);
}

double closing_radius(const MaskVolume& mask, const SegmentationOptions& o) {
  if (!(o.closing_radius_mm > 0.0) || !(o.closing_reference_ml > 0.0)) return o.closing_radius_mm;
  const double ml = static_cast<double>(std::count(mask.values.begin(), mask.values.end(), 1)) *
                    mask.grid.voxel_volume() / 1000.0;
  return o.closing_radius_mm * std::max(1.0, std::cbrt(ml / o.closing_reference_ml));
}

Segmentation clean_mask(MaskVolume mask, const SegmentationOptions& options,
                        const ProgressCallback& progress, const std::string& where,
                        bool may_extract) {
  Segmentation s;
  s.mask = std::move(mask);
  report(progress, kStage, 0.4);
  std::vector<float> squared;  // one full-grid buffer for every distance transform below
  open_mask(s.mask, options.opening_radius_mm, squared);
  s.components = keep_largest_component(s.mask);
  if (s.components == 0)
    throw std::invalid_argument("segmentation: no voxel" + where + " is left by the " +
                                format_significant(options.opening_radius_mm, 3) + " mm opening" +
                                kHint);
  if (may_extract && options.extract_brain && options.max_border_contact_mm2 > 0.0 &&
      border_contact_mm2(s.mask) > options.max_border_contact_mm2) {
    s.mask = extract_brain(s.mask, options.extraction, squared);
    keep_largest_component(s.mask);
    s.extracted = true;
  }
  check_plausible(s.mask, options);
  report(progress, kStage, 0.5);
  s.closing_radius_mm = closing_radius(s.mask, options);
  close_mask(s.mask, s.closing_radius_mm, squared);
  squared = {};
  report(progress, kStage, 0.8);
  s.holes_filled = fill_holes(s.mask);
  s.voxels = static_cast<std::size_t>(std::count(s.mask.values.begin(), s.mask.values.end(), 1));
  report(progress, kStage, 1.0);
  return s;
}

}  // namespace

namespace {

// Dilation: mask := {squared distance to the voxels valued `target` <= r2}; with `erode`,
// erosion: mask := mask and not that. `squared` is the caller's reused buffer.
void dilate_into(MaskVolume& mask, std::uint8_t target, float r2, bool erode,
                 std::vector<float>& squared) {
  squared_distance_transform(mask, target, squared);
  const auto n = static_cast<std::ptrdiff_t>(mask.values.size());
  std::uint8_t* m = mask.values.data();
  const float* d = squared.data();
  if (erode) {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t v = 0; v < n; ++v) m[v] = m[v] && !(d[v] <= r2) ? 1 : 0;
  } else {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t v = 0; v < n; ++v) m[v] = d[v] <= r2 ? 1 : 0;
  }
}

}  // namespace

void close_mask(MaskVolume& mask, double radius_mm, std::vector<float>& scratch) {
  if (!(radius_mm > 0.0)) return;
  const float r2 = static_cast<float>(radius_mm * radius_mm);
  dilate_into(mask, 1, r2, false, scratch);  // dilation: within r of the inside
  dilate_into(mask, 0, r2, true, scratch);   // erosion: farther than r from the outside
}

void open_mask(MaskVolume& mask, double radius_mm, std::vector<float>& scratch) {
  if (!(radius_mm > 0.0)) return;
  const float r2 = static_cast<float>(radius_mm * radius_mm);
  dilate_into(mask, 0, r2, true, scratch);
  dilate_into(mask, 1, r2, false, scratch);
}

void close_mask(MaskVolume& mask, double radius_mm) {
  std::vector<float> scratch;
  close_mask(mask, radius_mm, scratch);
}

void open_mask(MaskVolume& mask, double radius_mm) {
  std::vector<float> scratch;
  open_mask(mask, radius_mm, scratch);
}

Segmentation segment_volume(const ScalarVolume& intensity, const SegmentationOptions& options,
                            const ProgressCallback& progress) {
  report(progress, kStage, 0.0);
  const ScalarVolume smoothed = gaussian_smoothed(intensity, options.smoothing_sigma_mm);
  report(progress, kStage, 0.3);
  const bool otsu = !(options.threshold > 0.0);
  const double threshold = otsu ? otsu_threshold(smoothed.values) : options.threshold;
  Segmentation s = clean_mask(threshold_mask(smoothed, threshold), options, progress,
                              " above the threshold " + std::to_string(threshold), true);
  s.otsu = otsu;
  s.threshold = threshold;
  return s;
}

Segmentation segment_mask(MaskVolume mask, const SegmentationOptions& options,
                          const ProgressCallback& progress) {
  report(progress, kStage, 0.0);
  for (std::uint8_t& v : mask.values) v = v ? 1 : 0;
  return clean_mask(std::move(mask), options, progress, " in the mask", false);
}

}  // namespace dynamesh
