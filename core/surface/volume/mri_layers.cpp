#include "core/surface/volume/mri_layers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/io/dicom_series.h"
#include "core/io/nifti_volume.h"
#include "core/surface/volume/distance_transform.h"
#include "core/surface/volume/gaussian_smoothing.h"
#include "core/surface/volume/orthogonal_resampling.h"

namespace dynamesh {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double percentile(std::vector<float>& values, double fraction) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(fraction * (values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

// A mask file on the volume's grid: the same dimensions and the same voxel placement (to
// 1e-3 mm), else the mask would be read in another space.
MaskVolume read_mask(const std::filesystem::path& path, const VoxelGrid& volume_grid) {
  if (!std::filesystem::is_regular_file(path))
    throw std::invalid_argument("mask '" + path.string() +
                                "' is not a readable file (--mask takes a NIfTI .nii or .nii.gz "
                                "file on the volume's grid)");
  NiftiVolume file;
  try {
    file = read_nifti_volume(path);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument("mask: " + std::string(e.what()));
  }
  const VoxelGrid& g = file.volume.grid;
  const double tolerance = 1e-3;
  if (g.dims != volume_grid.dims || !g.linear.isApprox(volume_grid.linear, tolerance) ||
      (g.offset - volume_grid.offset).norm() > tolerance) {
    std::ostringstream s;
    s << "mask '" << path.string() << "' is not on the volume's grid (dimensions " << g.dims[0]
      << "x" << g.dims[1] << "x" << g.dims[2] << " vs " << volume_grid.dims[0] << "x"
      << volume_grid.dims[1] << "x" << volume_grid.dims[2]
      << ", or another voxel placement); resample it to the volume first";
    throw std::invalid_argument(s.str());
  }
  MaskVolume mask(g, 0);
  for (std::size_t v = 0; v < mask.values.size(); ++v)
    mask.values[v] = file.volume.values[v] != 0.0f ? 1 : 0;
  return mask;
}

// A brain must span enough voxels to be segmented at all: with voxels so large that even the
// largest plausible brain (SegmentationOptions::max_volume_ml) would fill fewer than 1000
// of them (e.g. a sform scaled 100x: 1e6 mm^3 voxels), the volume is refused at once
// instead of after the segmentation.
void check_voxels_can_hold_a_brain(const VoxelGrid& grid, const SegmentationOptions& o) {
  constexpr double kMinBrainVoxels = 1000.0;
  if (!(o.max_volume_ml > 0.0)) return;
  const double largest = o.max_volume_ml * 1000.0 / kMinBrainVoxels;  // mm^3
  if (grid.voxel_volume() <= largest) return;
  std::ostringstream s;
  s << "voxels of " << grid.voxel_volume() << " mm^3 (spacing " << grid.spacing().transpose()
    << " mm): a brain of at most " << o.max_volume_ml << " ml would span fewer than "
    << kMinBrainVoxels << " of them (at most " << largest << " mm^3 each); check the header's "
    << "sform/qform and pixdim";
  throw std::invalid_argument(s.str());
}

// Refuses, before the preprocessing allocates, a volume whose estimate exceeds the budget.
void check_memory_budget(const VoxelGrid& grid, double max_memory_mb) {
  if (!(max_memory_mb > 0.0)) return;
  const double mb =
      static_cast<double>(grid.count()) * kPreprocessingBytesPerVoxel / (1024.0 * 1024.0);
  if (mb <= max_memory_mb) return;
  std::ostringstream s;
  s << "preprocessing " << grid.dims[0] << "x" << grid.dims[1] << "x" << grid.dims[2]
    << " voxels needs about " << std::lround(mb) << " MiB, more than the memory budget ("
    << "--max-memory " << max_memory_mb << "); crop or downsample the volume, or raise the budget";
  throw std::invalid_argument(s.str());
}

}  // namespace

MriLayers MriLayers::build(const MriLayersOptions& options, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  report(progress, "reading", 0.0);
  // A folder is a DICOM series: converted to a temporary NIfTI (dicom_series.h), read, and
  // the temporary file removed.
  std::optional<ConvertedDicomSeries> dicom;
  if (std::filesystem::is_directory(options.volume_path)) dicom.emplace(options.volume_path);
  NiftiVolume file = read_nifti_volume(dicom ? dicom->nifti() : options.volume_path,
                                       [&](double f) { report(progress, "reading", f); });
  dicom.reset();
  std::optional<MaskVolume> mask;
  if (!options.mask_path.empty()) mask = read_mask(options.mask_path, file.volume.grid);
  const double read_seconds = seconds_since(start);
  MriLayers layers = from_intensity(std::move(file.volume), options, progress, std::move(mask));
  layers.timings_.read = read_seconds;
  layers.source_ = options.volume_path.string();
  return layers;
}

MriLayers MriLayers::from_intensity(ScalarVolume intensity, const MriLayersOptions& options,
                                    const ProgressCallback& progress,
                                    std::optional<MaskVolume> mask) {
  if (mask && mask->grid.dims != intensity.grid.dims)
    throw std::invalid_argument("the mask's grid differs from the volume's");
  check_voxels_can_hold_a_brain(intensity.grid, options.segmentation);
  check_memory_budget(intensity.grid, options.max_memory_mb);
  if (!has_orthogonal_axes(intensity.grid)) {
    // A sheared placement: preprocessing on a grid with perpendicular axes (see
    // orthogonal_resampling.h), the background taken as the volume's minimum.
    const VoxelGrid grid = orthogonal_grid_around(intensity.grid);
    check_memory_budget(grid, options.max_memory_mb);
    const float background = *std::min_element(intensity.values.begin(), intensity.values.end());
    intensity = resampled(intensity, grid, background);
    if (mask) mask = resampled(*mask, grid);
  }
  MriLayers layers;
  layers.given_mask_ = std::move(mask);
  layers.options_ = options;
  layers.source_ = "(memory)";
  layers.intensity_ = std::move(intensity);
  layers.sampler_ = TrilinearSampler(layers.intensity_.grid);
  const auto [lo, hi] =
      std::minmax_element(layers.intensity_.values.begin(), layers.intensity_.values.end());
  layers.range_ = Vec2(*lo, *hi);
  layers.resegment(progress);
  return layers;
}

void MriLayers::set_threshold(double threshold, const ProgressCallback& progress) {
  options_.segmentation.threshold = threshold;
  resegment(progress);
}

void MriLayers::set_closing(double radius_mm, const ProgressCallback& progress) {
  options_.segmentation.closing_radius_mm = radius_mm;
  options_.segmentation.closing_reference_ml = 0.0;  // a radius given is taken as is
  resegment(progress);
}

void MriLayers::resegment(const ProgressCallback& progress) {
  auto start = std::chrono::steady_clock::now();
  segmentation_ = given_mask_ ? segment_mask(*given_mask_, options_.segmentation, progress)
                              : segment_volume(intensity_, options_.segmentation, progress);
  timings_.segment = seconds_since(start);
  start = std::chrono::steady_clock::now();
  ScalarVolume indicator;
  indicator.grid = segmentation_.mask.grid;
  reserve_huge(indicator.values, segmentation_.mask.values.size());
  indicator.values.assign(segmentation_.mask.values.begin(), segmentation_.mask.values.end());
  gaussian_smooth(indicator, options_.boundary_smoothing_mm);
  report(progress, "distance transform", 0.1);
  ScalarVolume distance = signed_distance_to_level(
      indicator, 0.5, [&](std::string_view s, double f) { report(progress, s, 0.1 + 0.8 * f); });
  indicator = {};
  gaussian_smooth(distance, options_.distance_smoothing_mm);
  distance_ = CubicBSplineField(std::move(distance));
  report(progress, "distance transform", 1.0);
  timings_.distance = seconds_since(start);
  analyse_mask();
  // The layers' topology changes only at D's critical points, which no depth moves (issue 16):
  // found once here, for every depth from the surface down to the deepest point.
  FixedCriticalPointsOptions o;
  // 1 mm more either side: the partners of shallow pairs at the band's ends.
  o.min_value = -max_depth_ - 1.0;
  o.max_value = 1.0;
  o.progress = progress;
  critical_points_ = find_fixed_critical_points(distance_, o);
  timings_.critical_points = critical_points_.seconds;
}

void MriLayers::analyse_mask() {
  const MaskVolume& mask = segmentation_.mask;
  const ScalarVolume& d = distance_.coefficients();
  std::vector<float> inside;
  inside.reserve(segmentation_.voxels);
  mask_bounds_ = Box3();
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  std::size_t deepest = 0;
  for (int k = 0; k < mask.grid.dims[2]; ++k)
    for (int j = 0; j < mask.grid.dims[1]; ++j)
      for (int i = 0; i < mask.grid.dims[0]; ++i) {
        const std::size_t v = mask.grid.index(i, j, k);
        if (!mask.values[v]) continue;
        if (intensity_.values[v] > range_[0]) inside.push_back(intensity_.values[v]);
        lo = lo.cwiseMin(Vec3(i, j, k));
        hi = hi.cwiseMax(Vec3(i, j, k));
        if (d.values[v] < d.values[deepest]) deepest = v;
      }
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi[0] + 0.5 : lo[0] - 0.5, (c & 2) ? hi[1] + 0.5 : lo[1] - 0.5,
                      (c & 4) ? hi[2] + 0.5 : lo[2] - 0.5);
    mask_bounds_.extend(mask.grid.to_world(corner));
  }
  const std::size_t nx = mask.grid.dims[0], nxy = nx * mask.grid.dims[1];
  deepest_point_ = mask.grid.to_world(Vec3(
      double(deepest % nx), double((deepest / nx) % mask.grid.dims[1]), double(deepest / nxy)));
  max_depth_ = -distance_.value(deepest_point_);
  window_ = Vec2(percentile(inside, 0.01), percentile(inside, 0.99));
}

}  // namespace dynamesh
