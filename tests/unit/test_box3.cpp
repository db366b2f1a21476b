// Box3's point and box tests: closed boxes (the boundary belongs to the box), which is what
// the six places that used to spell them out by hand relied on (critical points on a grid's
// face, a birth's extent, a clear level's region, a fill's border box, an atlas's overlap).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/geometry/vector_types.h"

namespace dynamesh {
namespace {

const Box3 kUnit{Vec3(0, 0, 0), Vec3(1, 2, 3)};

TEST(Box3, ContainsItsBoundaryAndNothingBeyond) {
  EXPECT_TRUE(kUnit.contains(Vec3(0.5, 1, 1.5)));
  EXPECT_TRUE(kUnit.contains(Vec3(0, 0, 0)));
  EXPECT_TRUE(kUnit.contains(Vec3(1, 2, 3)));
  EXPECT_TRUE(kUnit.contains(Vec3(1, 0.5, 0)));
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 below(0.5, 1, 1.5), above = below;
    below[axis] = std::nextafter(0.0, -1.0);
    above[axis] = std::nextafter(kUnit.max[axis], 10.0);
    EXPECT_FALSE(kUnit.contains(below)) << axis;
    EXPECT_FALSE(kUnit.contains(above)) << axis;
  }
  EXPECT_FALSE(kUnit.contains(Vec3(std::numeric_limits<double>::quiet_NaN(), 1, 1)));
  EXPECT_FALSE(Box3().contains(Vec3::Zero()));  // the empty box
}

TEST(Box3, OverlapsWhereTheyShareAPointEitherWayRound) {
  for (int axis = 0; axis < 3; ++axis) {
    Box3 touching = kUnit, apart = kUnit;
    touching.min[axis] = kUnit.max[axis];
    touching.max[axis] = kUnit.max[axis] + 1;
    apart.min[axis] = std::nextafter(kUnit.max[axis], 10.0);
    apart.max[axis] = kUnit.max[axis] + 1;
    EXPECT_TRUE(kUnit.overlaps(touching) && touching.overlaps(kUnit)) << axis;
    EXPECT_FALSE(kUnit.overlaps(apart) || apart.overlaps(kUnit)) << axis;
  }
  const Box3 inner{Vec3(0.2, 0.2, 0.2), Vec3(0.3, 0.3, 0.3)};
  EXPECT_TRUE(kUnit.overlaps(inner) && inner.overlaps(kUnit));
  EXPECT_FALSE(kUnit.overlaps(Box3()));
}

TEST(Box3, GrownByAMarginOnEverySide) {
  const Box3 g = kUnit.grown(0.25);
  EXPECT_EQ(g.min, Vec3::Constant(-0.25));
  EXPECT_EQ(g.max, Vec3(1.25, 2.25, 3.25));
  EXPECT_TRUE(g.contains(Vec3(-0.25, 2.25, 0)));
  EXPECT_FALSE(kUnit.contains(Vec3(-0.25, 2.25, 0)));
}

}  // namespace
}  // namespace dynamesh
