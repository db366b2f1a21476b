// The sphere near its floor (issue 17). A right-isosceles triangle with hypotenuse 2r on a
// sphere of radius R has error R - sqrt(R^2 - r^2) ~ r^2 / (2R) (its circumcentre's depth)
// and area r^2, so at error T no 4-8 mesh of right-isosceles triangles covers the sphere's
// 4 pi R^2 with fewer than 4 pi R^2 / (2 R T) = 2 pi R / T triangles: 6,283 at T = 1e-3,
// R = 1. Issue 17 asks for 1.25x; the box base mesh gives 9,216 (1.47x), and neither an
// octahedron (12,288) nor equiangular boxes of 3..6 quads per side (9,120 to 10,752) did
// better: every face at one 4-8 level must be within ~10% of the same error for a level to
// land near the floor, and these bases vary more than that. This pins today's 1.47x.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"

namespace dynamesh {
namespace {

TEST(SphereBaseMesh, AdaptedSphereCountAgainstTheRightIsoscelesFloor) {
  auto surface = make_scene("sphere");
  surface->set_parameter("R0", 1.0);
  surface->set_parameter("R1", 1.0);
  surface->set_time(0.0);
  AdaptOptions o;
  o.threshold = 1e-3;
  o.epsilon = o.threshold / 4;
  // The geometric error everywhere (the scene's default is multi-criteria).
  CriterionList criteria;
  criteria.push_back(std::make_unique<GeometricErrorCriterion>(o.threshold, o.epsilon));
  Adapter adapter(*surface, o, std::move(criteria));
  adapter.initialize();
  const double R = 1.0;
  const double floor = 2 * std::numbers::pi * R / o.threshold;
  const auto triangles = static_cast<double>(adapter.mesh().n_faces());
  EXPECT_LE(triangles, 1.5 * floor);
  // And not by being coarser than asked: the dense error is within the band.
  const auto dense = test::dense_error(adapter.mesh(), *surface, 20000.0, 3);
  EXPECT_LE(dense.max_error, (o.threshold + o.epsilon) * 1.10);
  RecordProperty("triangles", std::to_string(adapter.mesh().n_faces()));
  RecordProperty("floor", std::to_string(floor));
  // A few steps of a static sphere keep it there.
  for (int i = 0; i < 3; ++i) adapter.step(0.0);
  EXPECT_EQ(static_cast<double>(adapter.mesh().n_faces()), triangles);
}

}  // namespace
}  // namespace dynamesh
