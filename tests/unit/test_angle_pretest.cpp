// The weld pass's angle pre-test (core/adapt/angle_pretest.h): where it calls a triangle clear
// of the angle guard's limits, angles_within (the exact test) agrees; and it does call the
// triangles of a 4-8 mesh clear, else it would save nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/adapt/angle_pretest.h"
#include "core/geometry/mesh_quality.h"

namespace dynamesh {
namespace {

// A triangle with angles alpha at a and beta at b (degrees), scaled by s and turned in 3D.
void triangle(double alpha, double beta, double s, Vec3& a, Vec3& b, Vec3& c) {
  const double gamma = 180.0 - alpha - beta;
  const double ab = s, ac = s * std::sin(beta * M_PI / 180.0) / std::sin(gamma * M_PI / 180.0);
  a = Vec3(0.3, -0.2, 0.1);
  const Vec3 x = Vec3(1, 2, 2).normalized(), y = Vec3(2, 1, -2).normalized();
  b = a + ab * x;
  c = a + ac * (std::cos(alpha * M_PI / 180.0) * x + std::sin(alpha * M_PI / 180.0) * y);
}

TEST(AnglePretest, ClearOnlyWhereTheExactTestAgrees) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> near(-1e-3, 1e-3), any(0.5, 179.0), scale(-12, 3);
  const double limits[][2] = {{10.0, 160.0}, {30.0, 120.0}, {1.0, 179.0}};
  int checked = 0;
  for (const auto& l : limits) {
    const AngleCosines cosines(l[0], l[1]);
    for (int i = 0; i < 200000; ++i) {
      // Half of the triangles with an angle within 1e-3 degrees of a limit, half anywhere.
      double alpha = any(rng);
      if (i % 2 == 0) alpha = (i % 4 == 0 ? l[0] : l[1]) + near(rng);
      const double rest = 180.0 - alpha;
      const double beta = rest * std::uniform_real_distribution<double>(0.01, 0.99)(rng);
      Vec3 a, b, c;
      triangle(alpha, beta, std::pow(10.0, scale(rng)), a, b, c);
      if (!angles_clearly_within(a, b, c, cosines)) continue;
      ++checked;
      ASSERT_TRUE(angles_within(a, b, c, l[0], l[1]))
          << alpha << " " << beta << " limits " << l[0] << " " << l[1];
    }
  }
  EXPECT_GT(checked, 10000);
  // A 4-8 mesh's triangles (45-45-90, and stretched by the motion) are clear; near a limit not.
  const AngleCosines guard(10.0, 160.0);
  Vec3 a, b, c;
  for (double alpha : {45.0, 30.0, 60.0, 90.0, 20.0}) {
    triangle(alpha, 45.0, 1e-3, a, b, c);
    EXPECT_TRUE(angles_clearly_within(a, b, c, guard)) << alpha;
  }
  triangle(10.0 + 1e-9, 45.0, 1.0, a, b, c);
  EXPECT_FALSE(angles_clearly_within(a, b, c, guard));
  triangle(9.0, 45.0, 1.0, a, b, c);
  EXPECT_FALSE(angles_clearly_within(a, b, c, guard));
  EXPECT_FALSE(angles_within(a, b, c, 10.0, 160.0));
  EXPECT_FALSE(angles_clearly_within(a, a, c, guard));  // degenerate
}

}  // namespace
}  // namespace dynamesh
