// Scene `mri` (SCENES.md; de Goes et al. 2006, Section 4.5): isolayers of a brain in an MR
// volume, F(p, t) = D(p) + d(t) with D the smooth signed distance to the segmented brain's
// boundary (MriLayers) and d(t) = depth_max * t the depth of the layer below it. The layers
// are coloured by the MR intensity (intensity_at), as a physician inspects them for
// dysplastic lesions (curvilinear reformatting).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/surface/surface.h"
#include "core/surface/volume/mri_layers.h"
#include "core/surface/volume/volume_image.h"

namespace dynamesh {

struct MriOptions {
  std::filesystem::path volume_path = kDefaultMriVolume;
  std::filesystem::path mask_path;  // --mask: a brain mask on the volume's grid; empty: none
  double threshold = 0.0;           // segmentation threshold (intensity); 0 or negative: Otsu
  double depth_max = 15.0;          // mm, depth of the layer at t = 1
  // Ball radius of the morphological closing of the brain mask, mm (the `closing` scene
  // parameter), at least kMinClosingMm (see kClosingHelp).
  double closing_radius_mm = 5.0;
  // Whether closing_radius_mm was given (taken as is) or is the default (sized to the
  // brain, SegmentationOptions::closing_reference_ml).
  bool closing_given = false;
  double max_memory_mb = 0.0;  // preprocessing memory budget (MriLayersOptions); 0: none
  ProgressCallback progress;   // loading / segmenting / distance transform, also on re-segmenting
};

// The `closing` parameter's range and meaning. With 5 mm (the default) every layer from 0 to
// 20 mm on Colin27 is one solid without holes; below ~3 mm the sulci stay open, the layers
// fold into them and may have handles (genus > 0) or split into pieces as t grows: the
// topology check of core/topology reports such events and re-bases the mesh (issue 16).
inline constexpr double kMaxClosingMm = 20.0;
// Below 2 mm the closing leaves slits (sulci a few mm wide and up to 30 mm deep) that the
// layer dives into: measured on Colin27 at T = 0.5 mm, closing 2 gives a clean layer (10,286
// triangles, smallest angle 11 deg), 1 mm a layer with 2,633 self-intersecting triangle
// pairs, 0.5 mm and 0 run into the triangle budget (max error 1.3-4 mm, slivers of 1e-6
// deg): refinement keeps splitting across the slit, whose two sheets lie closer than the
// triangles that would have to separate them. Such values are refused. Measured again with
// the events of issue 16 (README, "Topology events of the layers"): closing 0 failed at every
// depth tried (0, 2, 5, 10, 20 mm), closing 1 worked at 20 mm only.
inline constexpr double kMinClosingMm = 2.0;
inline constexpr const char* kClosingHelp =
    "radius in mm of the morphological closing of the brain mask (bridges sulci; by default "
    "5 mm, more for a brain larger than 1.7 L); at least 2: a smaller closing leaves slits "
    "narrower than the layer's triangles, which refinement cannot follow; give 2 to keep the "
    "most sulci";

class MriSurface final : public ImplicitSurface, public FixedCriticalField {
 public:
  static constexpr const char* kName = "mri";
  static constexpr const char* kIntensity = "intensity";
  static constexpr const char* kDescription =
      "brain isolayers at depth depth_max * t below the surface of a segmented MR volume "
      "(paper 4.5)";

  MriSurface(MriLayers layers, double depth_max, ProgressCallback progress = {});

  std::string name() const override { return kName; }
  // depth_max in [0, max_depth - 1] mm; threshold in [0, max intensity] (0: Otsu; changing
  // it re-segments and recomputes the distance, about a second).
  std::vector<SurfaceParameter> parameters() const override;
  void set_parameter(const std::string& name, double value) override;
  // The mask's box grown by 2 mm: every layer lies inside it.
  Box3 bounds() const override;
  // A box of quads around the brain, each vertex moved along the ray from the deepest point
  // to the first crossing of the current layer (so the base mesh is a closed sphere-like
  // net even where the layer is not star-shaped), then Newton-projected.
  Mesh48 base_mesh() const override;
  // Where the layer has a feature narrower than the base's cells next to a critical point of
  // D (mri_start_depth): an earlier time clear of them, from which the adapter carries the
  // mesh to the requested one; NaN when the requested time is clear.
  double mild_time() const override;

  double value(const Vec3& p) const override { return layers_.distance(p) + depth(); }
  double value_gradient(const Vec3& p, Vec3& gradient) const override {
    return layers_.distance_gradient(p, gradient) + depth();
  }
  Mat3 hessian(const Vec3& p) const override;

  // F = D + d(t): the layers change topology only where d(t) passes -D at one of D's critical
  // points, fixed in space (issue 16). The adapter watches them when some of those that matter
  // at its threshold lie within [0, depth_max]; the cuberille or a contour of F re-bases the
  // mesh when a local repair cannot be made.
  bool may_change_topology() const override { return true; }
  // D's critical points with -D in [0, depth_max], pairs of persistence below `resolution`
  // cancelled; kept per resolution and depth_max until the distance changes.
  const FixedCriticalPoints& fixed_critical_points(double resolution) const override;
  double time_offset() const override { return depth(); }

  // "intensity": the T1 intensity (trilinear), what the layers are coloured by.
  std::vector<std::string> point_quantities() const override { return {kIntensity}; }
  double point_quantity(const std::string& name, const Vec3& p) const override;

  // Progress of re-segmenting when `threshold` changes; the registry clears the callback it
  // was built with, so the surface never calls a reporter that its caller has destroyed.
  void set_progress(ProgressCallback progress) { progress_ = std::move(progress); }

  double depth() const { return depth_max_ * time(); }
  double depth_max() const { return depth_max_; }
  // MR intensity at a world point (trilinear) and its range / display window.
  double intensity_at(const Vec3& p) const { return layers_.intensity_at(p); }
  Vec2 intensity_range() const { return layers_.intensity_range(); }
  Vec2 intensity_window() const { return layers_.intensity_window(); }
  const MriLayers& layers() const { return layers_; }
  // The scan for the renderer and picking (read-only, shared with every snapshot), with the
  // label atlas once one is set.
  std::shared_ptr<const VolumeImage> volume_image() const override { return image_; }
  void set_atlas(std::shared_ptr<const LabelAtlas> atlas);

 private:
  Vec3 first_crossing(const Vec3& origin, const Vec3& direction) const;

  MriLayers layers_;
  double depth_max_;
  mutable std::map<std::pair<double, double>, FixedCriticalPoints> critical_points_;
  ProgressCallback progress_;
  std::shared_ptr<const VolumeImage> image_;
};

// Reads, segments and transforms the volume (progress through options.progress); throws
// std::runtime_error for an unreadable file, std::invalid_argument for bad options or a
// volume where nothing is segmented.
std::unique_ptr<MriSurface> make_mri_surface(const MriOptions& options = {});

}  // namespace dynamesh
