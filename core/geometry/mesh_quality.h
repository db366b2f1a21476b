// Mesh quality measures: angles, aspect ratios, valences, edge-length spread. Computed from
// positions and connectivity only, so they judge any mesh the same way (and a test can judge
// the adapter's meshes without trusting the adapter).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>

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

// Cosine of one triangle's smallest angle (the one opposite its shortest edge), 1 when
// degenerate. Hot loops compare cosines instead of taking three atan2 per face: the angle is
// decreasing in its cosine on [0, pi]. (Inline: the smoothing's guard asks it twice for every
// face with a moved corner.)
inline double smallest_angle_cosine(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, bc = c - b, ca = a - c;
  const double lab = ab.squaredNorm(), lbc = bc.squaredNorm(), lca = ca.squaredNorm();
  // The angle opposite the shortest edge lies between the two other edges.
  Vec3 u, v;
  if (lab <= lbc && lab <= lca) {
    u = a - c, v = b - c;
  } else if (lbc <= lca) {
    u = b - a, v = c - a;
  } else {
    u = a - b, v = c - b;
  }
  const double norms = std::sqrt(u.squaredNorm() * v.squaredNorm());
  return norms > 0 ? u.dot(v) / norms : 1.0;
}

// Smallest and largest interior angle of one triangle, in degrees.
std::array<double, 2> angle_range_deg(const Vec3& a, const Vec3& b, const Vec3& c);

// Exactly whether angle_range_deg(a, b, c) lies within [min_deg, max_deg], mostly without its
// three atan2: each angle's cosine is compared with the limits' first, and only a triangle
// with an angle within 1e-9 of a limit's cosine (or degenerate) takes angle_range_deg's path.
bool angles_within(const Vec3& a, const Vec3& b, const Vec3& c, double min_deg, double max_deg);

// Distribution of the aspect ratio over the faces: percentiles (nearest rank) and a
// histogram. A 4-8 mesh of right isosceles triangles sits at 1.207 everywhere; the tail
// (p99, max) is what tangential motion and deformation stretch.
struct AspectDistribution {
  static constexpr std::array<double, 8> kEdges = {1.0, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0};
  double p50 = 0, p90 = 0, p99 = 0, max = 0;
  // bin i counts ratios in [kEdges[i], kEdges[i + 1]); the last bin is [10, inf).
  std::array<std::size_t, kEdges.size()> histogram{};
  std::size_t triangles = 0;
};

AspectDistribution aspect_distribution(const Mesh48& mesh);

// Edge lengths of the edges whose midpoint satisfies `region` (every edge once). `ratio`
// (longest / shortest) and `cv` (standard deviation / mean) measure the spread: a uniform
// region (an edge-length criterion) should have a small one.
struct EdgeLengthSpread {
  std::size_t edges = 0;
  double min = 0, max = 0, mean = 0, stddev = 0;
  double ratio() const { return min > 0 ? max / min : 0.0; }
  double cv() const { return mean > 0 ? stddev / mean : 0.0; }
};

EdgeLengthSpread edge_length_spread(
    const Mesh48& mesh,
    const std::function<bool(const Vec3&)>& region = [](const Vec3&) { return true; });

}  // namespace dynamesh
