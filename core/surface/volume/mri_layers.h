// MriLayers: everything the mri scene precomputes from an MR volume (SCENES.md, mri; paper
// Section 4.5): the intensity volume, the solid brain mask, and the smooth signed distance
// D(p) to the brain's boundary in mm (negative inside), whose level sets D = -d are the
// isolayers at depth d.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/surface/volume/bspline_field.h"
#include "core/surface/volume/progress.h"
#include "core/surface/volume/segmentation.h"
#include "core/surface/volume/trilinear_sampler.h"
#include "core/topology/fixed_critical_points.h"

namespace dynamesh {

// The Colin27 single-subject brain, brain-extracted (Debian package mricron-data).
inline constexpr const char* kDefaultMriVolume = "/usr/share/mricron/templates/ch2bet.nii.gz";

struct MriLayersOptions {
  std::filesystem::path volume_path = kDefaultMriVolume;
  // A brain mask on the volume's grid (nonzero = brain), used instead of the threshold;
  // empty: the built-in segmentation.
  std::filesystem::path mask_path;
  // Otsu's threshold after 1 mm smoothing, and a 5 mm closing: measured on Colin27, the raw
  // mask's isolayers have handles and islands (sulci, open ventricles) at most depths, while
  // after a 5 mm closing every layer from 0 to 20 mm is one solid without holes.
  SegmentationOptions segmentation{.smoothing_sigma_mm = 1.0,
                                   .threshold = 0.0,
                                   // 3 mm: parts left by a 2 mm opening (4 mm thick)
                                   // become sub-millimetre tongues under the two 1.5 mm
                                   // blurs below, 1-2 mm from the layer (the optic chiasm
                                   // on Colin27 at 1.1 mm voxels); split vertices were
                                   // projected onto them and refinement ran away.
                                   .opening_radius_mm = 3.0,
                                   .closing_radius_mm = 5.0,
                                   // Measured: Colin27 with its header set to 2 mm voxels
                                   // (a brain twice as large, sulci twice as wide, 13.6 L)
                                   // keeps sulci open under a 5 mm closing and refinement
                                   // runs away in them; closed by 10 mm it adapts (22,748
                                   // triangles, area 4.13x the 1 mm layer's). The same
                                   // runaway happens on the 1 mm brain with no closing. An
                                   // adult brain (Colin27: 1.66 L after the opening) is
                                   // closed by 5 mm; larger ones in proportion.
                                   .closing_reference_ml = 1700.0,
                                   // A neck's cross-section is ~100 cm^2; a brain cropped
                                   // tightly may graze the border (ch2better: 1 cm^2).
                                   .max_border_contact_mm2 = 1000.0,
                                   // A macaque brain (inia19) holds 0.1 L, a human one 1-1.8
                                   // L; the upper limit admits Colin27 with its header set
                                   // to 2 mm voxels (13.6 L, the voxel-size tests).
                                   .min_volume_ml = 10.0,
                                   .max_volume_ml = 20000.0,
                                   // A raw T1 with skull works out of the box.
                                   .extract_brain = true,
                                   .extraction = {}};
  // The distance is measured to the 1/2 level of the mask blurred by `boundary_smoothing_mm`
  // (sub-voxel, instead of the voxel staircase), then blurred by `distance_smoothing_mm`
  // before the B-spline. Measured on a NIfTI ball of radius 20 mm with 0.9-1.2 mm voxels
  // (test_mri_surface.cpp): the layers' principal curvatures are then off by 15% (depth 0)
  // and 10% (depth 10 mm) on average; with a 1 mm boundary blur the depth-0 layer was off by
  // 18%, and without blurring the distance, curvature was dominated by staircase noise (90%
  // off on a 13.7 mm ball). The price is a bias of about sigma^2 / R in the value.
  double boundary_smoothing_mm = 1.5;
  double distance_smoothing_mm = 1.5;
  // Memory budget of the preprocessing, MiB: a volume whose estimate
  // (kPreprocessingBytesPerVoxel per voxel) exceeds it is refused before the work. 0: none.
  double max_memory_mb = 0.0;
};

// Peak bytes per voxel of reading, segmenting and transforming (intensity, smoothed copy,
// masks, the distance transform's squared distances and feature indices, the brain
// extraction's labels, the distance and its B-spline): measured 38 on Colin27 (peak
// resident 261-269 MB for 7.1 M voxels, whole run, ch2bet and ch2).
inline constexpr double kPreprocessingBytesPerVoxel = 40.0;

// Wall-clock seconds of each preprocessing stage.
struct MriTimings {
  double read = 0.0, segment = 0.0, distance = 0.0, critical_points = 0.0;
  double total() const { return read + segment + distance + critical_points; }
};

class MriLayers {
 public:
  // Reads, segments and transforms; stages "reading", "segmenting", "distance transform",
  // "critical points"
  // are reported through `progress`. Throws std::runtime_error (unreadable file) or
  // std::invalid_argument (nothing segmented).
  static MriLayers build(const MriLayersOptions& options, const ProgressCallback& progress = {});
  // From an intensity volume already in memory (tests, other readers); volume_path and
  // mask_path unused; `mask` (same grid, nonzero = brain), when given, replaces the threshold.
  static MriLayers from_intensity(ScalarVolume intensity, const MriLayersOptions& options,
                                  const ProgressCallback& progress = {},
                                  std::optional<MaskVolume> mask = std::nullopt);
  // Whether the brain comes from a given mask (then the threshold is unused).
  bool mask_given() const { return given_mask_.has_value(); }

  // Re-segments with another threshold (<= 0: Otsu) and recomputes the distance.
  void set_threshold(double threshold, const ProgressCallback& progress = {});
  // Re-segments with another closing radius (mm, 0: none) and recomputes the distance.
  void set_closing(double radius_mm, const ProgressCallback& progress = {});
  const MriLayersOptions& options() const { return options_; }

  // Signed distance to the brain boundary, mm, negative inside (C2 cubic B-spline).
  double distance(const Vec3& p) const { return distance_.value(p); }
  double distance_gradient(const Vec3& p, Vec3& g) const { return distance_.value_gradient(p, g); }
  double distance_hessian(const Vec3& p, Vec3& g, Mat3& h) const {
    return distance_.value_gradient_hessian(p, g, h);
  }
  // MR intensity at a world point (trilinear).
  double intensity_at(const Vec3& p) const { return sampler_(intensity_, p); }
  // Minimum and maximum intensity of the whole volume, and a display window: the 1st and
  // 99th percentiles of the intensities inside the mask, background (the minimum) excluded.
  Vec2 intensity_range() const { return range_; }
  Vec2 intensity_window() const { return window_; }

  const ScalarVolume& intensity() const { return intensity_; }
  const Segmentation& segmentation() const { return segmentation_; }
  const CubicBSplineField& distance_field() const { return distance_; }
  // World box around the mask's voxels (cells included).
  Box3 mask_bounds() const { return mask_bounds_; }
  // The deepest voxel centre (most negative D) and its depth: every layer d < max_depth
  // is non-empty and contains this point.
  Vec3 deepest_point() const { return deepest_point_; }
  double max_depth() const { return max_depth_; }
  // D's critical points with D in [-max_depth, 0], none cancelled (fixed_critical_points.h):
  // where some layer changes topology. Found with the distance (stage "critical points").
  const FixedCriticalPoints& critical_points() const { return critical_points_; }
  const MriTimings& timings() const { return timings_; }
  std::string source() const { return source_; }

 private:
  MriLayers() = default;
  void resegment(const ProgressCallback& progress);
  void analyse_mask();

  MriLayersOptions options_;
  std::string source_;
  ScalarVolume intensity_;
  std::optional<MaskVolume> given_mask_;
  Segmentation segmentation_;
  CubicBSplineField distance_;
  TrilinearSampler sampler_;
  Vec2 range_{Vec2::Zero()}, window_{Vec2::Zero()};
  Box3 mask_bounds_;
  Vec3 deepest_point_{Vec3::Zero()};
  double max_depth_ = 0.0;
  FixedCriticalPoints critical_points_;
  MriTimings timings_;
};

}  // namespace dynamesh
