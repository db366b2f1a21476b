// Mesh quality measures: angles, aspect ratios, valences. Computed from positions and
// connectivity only, so they judge any mesh the same way.
#pragma once

#include <array>
#include <cstddef>

#include "core/mesh/mesh48.h"

namespace dynamesh {

struct MeshQuality {
  double min_angle_deg = 0.0, mean_min_angle_deg = 0.0, max_angle_deg = 0.0;
  // Aspect ratio R / (2 r) (circumradius over twice the inradius): 1 for an equilateral
  // triangle, 1.207 for a right isosceles one, unbounded for slivers.
  double max_aspect = 0.0, mean_aspect = 0.0;
  int valence_min = 0, valence_max = 0;
  std::array<std::size_t, 16> valence_histogram{};  // interior vertices; the last bin is 15+
  std::size_t triangles = 0;
};

MeshQuality measure_quality(const Mesh48& mesh);

// Aspect ratio R / (2 r) of one triangle; +infinity when degenerate.
double aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace dynamesh
