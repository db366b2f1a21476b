// A cheap, conservative pre-test of the angle guard (AngleGuardOptions, adapt_options.h):
// whether every interior angle of a triangle lies clearly inside (min_deg, max_deg), without a
// square root, a division or a cosine of the limits per triangle. The weld pass asks it of every
// face of every weld candidate's star within T + eps (Adapter::pathological_star), where
// angles_within (mesh_quality.h) cost 25% of the pass's parallel part at 10^5 triangles; a 4-8
// mesh's triangles are near 45-45-90, far from the limits.
//
// Exact where it answers: it compares each corner's cosine u.v / (|u| |v|) with limits moved
// inward by kSlack (1e-6), through squares (u.v)^2 against limit^2 |u|^2 |v|^2. Those products
// are correct to a few ulps (relative ~1e-15), far inside the slack, so "clearly within" here
// implies angles_within's answer (whose own margin is 1e-9 in the cosine). Anything else (an
// angle near a limit, a degenerate or huge triangle) says "not clear" and the caller asks
// angles_within.
#pragma once

#include <cmath>

#include "core/geometry/vector_types.h"

namespace dynamesh {

struct AngleCosines {
  static constexpr double kSlack = 1e-6;
  // For a corner's cosine c: c < upper (angle > min_deg) and c > lower (angle < max_deg).
  double upper = -1.0, lower = 1.0;  // default: nothing is clear
  AngleCosines() = default;
  // Limits that do not straddle 90 degrees (min_deg below it, max_deg above) leave the
  // pre-test off.
  AngleCosines(double min_deg, double max_deg)
      : upper(std::cos(min_deg * M_PI / 180.0) - kSlack),
        lower(std::cos(max_deg * M_PI / 180.0) + kSlack) {
    if (!(upper > 0.0 && lower < 0.0)) upper = -1.0, lower = 1.0;
  }
};

inline bool angles_clearly_within(const Vec3& a, const Vec3& b, const Vec3& c,
                                  const AngleCosines& limits) {
  // upper > 0 > lower, or the limits left the pre-test off (AngleCosines): nothing is clear.
  if (!(limits.upper > 0.0 && limits.lower < 0.0)) return false;
  const Vec3* corner[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = *corner[(i + 1) % 3] - *corner[i], v = *corner[(i + 2) % 3] - *corner[i];
    const double d = u.dot(v), q = u.squaredNorm() * v.squaredNorm();
    // Degenerate, or so small or large that the squares leave the normal range: not clear.
    if (!(q > 1e-200 && q < 1e200)) return false;
    // A cosine >= 0 need only stay below upper, one < 0 above lower.
    const double limit = d >= 0.0 ? limits.upper : limits.lower;
    if (!(d * d < limit * limit * q)) return false;
  }
  return true;
}

}  // namespace dynamesh
