// The synthetic dumbbell of the mri event tests (test_mri_events.cpp, test_local_repair.cpp).
#pragma once

#include <cmath>
#include <memory>

#include "core/surface/volume/mri_surface.h"
#include "test_volume_fixtures.h"

namespace dynamesh {

// Two balls of radius 12 mm, centres 32 mm apart on x, joined by a cylinder of radius 5 mm:
// a "brain" whose layers split in two at about 3 mm deep (the neck's radius, less the bias of
// the distance's smoothing) and vanish below 9 mm (the balls' centres).
constexpr double kLobeRadius = 12.0, kNeckRadius = 5.0, kLobeOffset = 16.0;
// The deepest point lies 9.2 mm deep (the blurs round the balls' distance off at the centres).
constexpr double kDepthMax = 8.0;
inline ScalarVolume dumbbell_volume() {
  VoxelGrid grid;
  grid.dims = {72, 36, 36};
  grid.offset = Vec3(-35.5, -17.5, -17.5);
  return test::rasterise<float>(
      grid,
      [](const Vec3& p) {
        const Vec3 a(-kLobeOffset, 0, 0), b(kLobeOffset, 0, 0);
        return (p - a).norm() <= kLobeRadius || (p - b).norm() <= kLobeRadius ||
               (std::abs(p.x()) <= kLobeOffset && p.tail<2>().norm() <= kNeckRadius);
      },
      100.0f, 0.0f);
}

inline std::unique_ptr<MriSurface> make_dumbbell(double depth_max) {
  const ScalarVolume intensity = dumbbell_volume();
  MriLayersOptions o;
  o.segmentation.closing_radius_mm = 0.0;  // keep the neck
  o.segmentation.closing_reference_ml = 0.0;
  o.segmentation.min_volume_ml = 1.0;
  return std::make_unique<MriSurface>(MriLayers::from_intensity(intensity, o), depth_max);
}

}  // namespace dynamesh
