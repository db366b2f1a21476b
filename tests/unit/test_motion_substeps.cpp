// The sub-step count of a motion (motion_substeps.h): the largest edge strain over the step
// divided by the limit, rounded up, at most max_substeps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/adapt/motion_substeps.h"
#include "core/mesh/base_meshes.h"

namespace dynamesh {
namespace {

// A 4 x 4 grid of unit cells in the plane y = 0 with vertex 0 (a corner) moved by `move`
// along y: its edges to its neighbours (lengths 1 and sqrt 2) strain by |move| / length.
MotionEstimate estimate_for_corner_move(double move) {
  const Mesh48 mesh = make_grid_mesh(4, 4, Vec2(0, 0), Vec2(4, 4));
  std::vector<Vec3> displacement(mesh.vertex_capacity(), Vec3::Zero());
  displacement[0] = Vec3(0, move, 0);
  return estimate_substeps(mesh, displacement, SubstepOptions{});
}

TEST(MotionSubsteps, StrainOverTheLimitCutsTheStep) {
  // Strain 1.0 on a unit edge against the limit 0.25: four sub-steps.
  const MotionEstimate e = estimate_for_corner_move(1.0);
  EXPECT_DOUBLE_EQ(e.strain, 1.0);
  EXPECT_EQ(e.substeps, 4);
  EXPECT_EQ(estimate_for_corner_move(0.1).substeps, 1);
}

// A strain beyond INT_MAX times the limit (a layer's vertex Newton sent across a gap: 1.56e16
// on the dumbbell started 2 mm deep with events off) took the most sub-steps as
// min(32, int(ceil(need))), a conversion out of range: INT_MIN sub-steps, so the step took
// none and published the old mesh at the new time without a word.
TEST(MotionSubsteps, AnEnormousStrainTakesTheMostSubsteps) {
  const MotionEstimate e = estimate_for_corner_move(1e16);
  EXPECT_GT(e.strain, 1e15);
  EXPECT_EQ(e.substeps, SubstepOptions{}.max_substeps);
}

}  // namespace
}  // namespace dynamesh
