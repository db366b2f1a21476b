// The error next to a critical point of F (issue 16): the two blobs 0.0015 in a before
// they merge (a = 0.59; they touch at 0.5 sqrt(ln 4) = 0.5887), their tips 0.02 apart about the
// saddle of F at the origin. The error is SCENES.md's Newton distance (distance_to_surface); the
// probe's first-order |F| / |grad F| under-reads it there, by more than the dense test's 10% slack
// at the distances the adapter's bound allows, unless the saddle is known to the probe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/adapt/surface_probe.h"
#include "core/surface/scene_registry.h"
#include "core/surface/surface_distance.h"

namespace dynamesh {
namespace {

struct Worst {
  double relative = 0.0;  // largest |probe - Newton| / Newton
  int points = 0;
};

// Points of the plane y = 0.0007 around the tips whose Newton distance lies between 0.005 and
// 0.012: T + eps = 0.01 at the CLI's defaults.
Worst compare(const SurfaceProbe& probe, const ImplicitSurface& surface) {
  Worst worst;
  for (int i = -40; i <= 40; ++i) {
    for (int k = -20; k <= 20; ++k) {
      const Vec3 x(0.002 * i, 0.0007, 0.002 * k);
      const double newton = distance_to_surface(surface, x);
      if (newton < 0.005 || newton > 0.012) continue;
      ++worst.points;
      worst.relative =
          std::max(worst.relative, std::abs(std::abs(probe.signed_distance(x)) - newton) / newton);
    }
  }
  return worst;
}

TEST(SingularDistance, NearASaddleTheErrorIsNewtonsDistance) {
  const auto surface = make_scene(
      "expr", {},
      {{"implicit", "0.5 - exp(-((x-0.59)^2+y^2+z^2)/0.25) - exp(-((x+0.59)^2+y^2+z^2)/0.25)"},
       {"bounds", "-1.8,-0.8,-0.8,1.8,0.8,0.8"}});
  const auto& F = dynamic_cast<const ImplicitSurface&>(*surface);
  SurfaceProbe probe(*surface);
  const Worst first_order = compare(probe, F);
  ASSERT_GT(first_order.points, 100);
  std::printf("%d points, first order off by up to %.3f\n", first_order.points,
              first_order.relative);
  // What the first-order distance misses here (this is what the fix is for).
  EXPECT_GT(first_order.relative, 0.10);
  probe.set_singular_points({Vec3::Zero()});
  const Worst known = compare(probe, F);
  EXPECT_EQ(known.points, first_order.points);
  EXPECT_LT(known.relative, 1e-6);
}

// Away from it (the saddle known but far) the first-order distance stays, as before.
TEST(SingularDistance, FarFromTheSaddleTheFirstOrderDistanceStays) {
  const auto surface = make_scene(
      "expr", {}, {{"implicit", "x^2 + y^2 + z^2 - 0.09"}, {"bounds", "-1,-1,-1,1,1,1"}});
  SurfaceProbe plain(*surface), known(*surface);
  known.set_singular_points({Vec3(0.9, 0.9, 0.9)});
  const Vec3 x(0.0, 0.305, 0.0);
  EXPECT_EQ(plain.signed_distance(x), known.signed_distance(x));
  Vec3 g;
  const double f = dynamic_cast<const ImplicitSurface&>(*surface).value_gradient(x, g);
  EXPECT_DOUBLE_EQ(plain.signed_distance(x), f / g.norm());
}

}  // namespace
}  // namespace dynamesh
