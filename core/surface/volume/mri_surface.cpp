#include "core/surface/volume/mri_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/surface/parameter_table.h"
#include "core/surface/volume/mri_base_mesh.h"

namespace dynamesh {
namespace {

constexpr double kBoundsMargin = 2.0;  // mm
// mm, cells of the cuberille base (cuberille_base_mesh.h). Measured on Colin27 with its
// header rewritten (see /work/notes/issue-14.md): 8 mm adapts 0.8-1.05, 1.5 mm, 1x1x1.2,
// oblique; 1.1 and 2 mm still refine without end; 5 mm passed those two but failed others.
constexpr double kBaseCellSize = 8.0;

}  // namespace

MriSurface::MriSurface(MriLayers layers, double depth_max, ProgressCallback progress)
    : layers_(std::move(layers)), depth_max_(depth_max), progress_(std::move(progress)) {
  auto image = std::make_shared<VolumeImage>();
  image->intensity = std::make_shared<const ScalarVolume>(layers_.intensity());
  image->window = layers_.intensity_window();
  image_ = std::move(image);
  const double limit = std::max(0.0, layers_.max_depth() - 1.0);
  if (!(depth_max >= 0.0 && depth_max <= limit)) {
    throw std::invalid_argument("mri: depth_max " + std::to_string(depth_max) + " outside [0, " +
                                std::to_string(limit) + "] (the brain's deepest point lies " +
                                std::to_string(layers_.max_depth()) + " mm deep)");
  }
}

std::vector<SurfaceParameter> MriSurface::parameters() const {
  return {{"depth_max", depth_max_, 0.0, std::max(0.0, layers_.max_depth() - 1.0),
           "depth in mm of the layer at t = 1 below the brain's surface"},
          {"threshold", layers_.options().segmentation.threshold, 0.0, layers_.intensity_range()[1],
           "segmentation intensity threshold; 0 means Otsu's (currently " +
               std::to_string(layers_.segmentation().threshold) + ")"},
          {"closing", layers_.segmentation().closing_radius_mm, kMinClosingMm, kMaxClosingMm,
           kClosingHelp}};
}

void MriSurface::set_parameter(const std::string& name, double value) {
  const std::vector<SurfaceParameter> list = parameters();
  for (const SurfaceParameter& p : list) {
    if (p.name != name) continue;
    check_parameter_value(kName, p, value);
    if (name == "depth_max") {
      depth_max_ = value;
    } else if (name == "closing") {
      if (value == layers_.segmentation().closing_radius_mm) return;
      layers_.set_closing(value, progress_);
      critical_points_.clear();
      depth_max_ = std::min(depth_max_, std::max(0.0, layers_.max_depth() - 1.0));
    } else if (value != layers_.options().segmentation.threshold) {
      // The same threshold again needs no work (the registry re-applies what a factory
      // already built with).
      layers_.set_threshold(value, progress_);
      critical_points_.clear();
      depth_max_ = std::min(depth_max_, std::max(0.0, layers_.max_depth() - 1.0));
    }
    return;
  }
  throw std::invalid_argument(unknown_parameter_message(kName, name, list));
}

const FixedCriticalPoints& MriSurface::fixed_critical_points(double resolution) const {
  const auto key = std::make_pair(resolution, depth_max_);
  auto it = critical_points_.find(key);
  if (it != critical_points_.end()) return it->second;
  FixedCriticalPointsOptions o;
  o.min_value = -depth_max_;
  o.max_value = 0.0;
  o.min_persistence = resolution;
  return critical_points_.emplace(key, cancel_shallow_pairs(layers_.critical_points(), o))
      .first->second;
}

void MriSurface::set_atlas(std::shared_ptr<const LabelAtlas> atlas) {
  auto image = std::make_shared<VolumeImage>(*image_);  // the intensities stay shared
  image->atlas = std::move(atlas);
  image_ = std::move(image);
}

double MriSurface::point_quantity(const std::string& name, const Vec3& p) const {
  if (name == kIntensity) return intensity_at(p);
  return Surface::point_quantity(name, p);
}

Box3 MriSurface::bounds() const {
  return layers_.mask_bounds().grown(kBoundsMargin);
}

Mat3 MriSurface::hessian(const Vec3& p) const {
  Vec3 g;
  Mat3 h;
  layers_.distance_hessian(p, g, h);
  return h;
}

// Sphere tracing (J. Hart, "Sphere tracing", The Visual Computer 12, 1996) from inside: D is
// close to a distance, so steps of 0.8 |F| cannot jump over the layer; then bisection.
Vec3 MriSurface::first_crossing(const Vec3& origin, const Vec3& direction) const {
  const double far = bounds().diagonal();
  double inside = 0.0, s = 0.0;
  while (s < far) {
    const double f = value(origin + s * direction);
    if (f > 0.0) break;
    inside = s;
    s += std::max(0.8 * -f, 0.1);
  }
  double outside = std::min(s, far);
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (inside + outside);
    (value(origin + mid * direction) > 0.0 ? outside : inside) = mid;
  }
  return origin + outside * direction;
}

Mesh48 MriSurface::base_mesh() const {
  MriBaseMeshOptions options;
  options.cell_size = kBaseCellSize;
  return make_mri_base_mesh(*this, options);
}

double MriSurface::mild_time() const {
  if (!(depth_max_ > 0.0) || !(depth() > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  MriBaseMeshOptions options;
  options.cell_size = kBaseCellSize;
  // Pairs of persistence below mri's suggested T cancelled, as the adapter's monitor does at
  // that T: a lobe or handle that lives over less depth than that is not a feature the mesh
  // must show.
  constexpr double kResolution = 0.5;  // mm
  const double start = mri_start_depth(fixed_critical_points(kResolution).points, depth(), options);
  if (start == depth()) return std::numeric_limits<double>::quiet_NaN();
  // A base that is F's whole contour (the cuberille misses part of the layer: a neck thinner
  // than its cells) already has what the mesh must follow: the dumbbell started 2 mm deep, 0.8
  // mm before its split, is meshed from it (434 triangles, embedded). Carried from 0 mm instead,
  // its split was repaired with 104 faces at the finest patch spacing, and the run kept 2,700
  // triangles against 374 to its end.
  MriBaseMeshInfo info;
  make_mri_base_mesh(*this, options, &info);
  if (info.contour_whole) return std::numeric_limits<double>::quiet_NaN();
  return start / depth_max_;
}

std::unique_ptr<MriSurface> make_mri_surface(const MriOptions& options) {
  if (!std::isfinite(options.threshold) || !std::isfinite(options.depth_max) ||
      options.depth_max < 0.0) {
    throw std::invalid_argument("mri: threshold and depth_max must be finite, depth_max >= 0");
  }
  MriLayersOptions layer_options;
  layer_options.volume_path = options.volume_path;
  layer_options.mask_path = options.mask_path;
  layer_options.max_memory_mb = options.max_memory_mb;
  layer_options.segmentation.threshold = options.threshold;
  layer_options.segmentation.closing_radius_mm = options.closing_radius_mm;
  if (options.closing_given) layer_options.segmentation.closing_reference_ml = 0.0;
  return std::make_unique<MriSurface>(MriLayers::build(layer_options, options.progress),
                                      options.depth_max, options.progress);
}

}  // namespace dynamesh
