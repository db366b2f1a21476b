// Distance transforms: exact against brute force on random masks; the signed distance of a
// rasterised ball and ellipsoid against their closed-form / numerically exact distances, on
// anisotropic oblique grids.
#include <gtest/gtest.h>

#include <random>

#include "core/surface/volume/distance_transform.h"
#include "test_volume_fixtures.h"

namespace dynamesh {
namespace {

TEST(DistanceTransform, EqualsBruteForceOnRandomMasksWithAnisotropicSpacing) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    const VoxelGrid grid = test::oblique_grid({13, 9, 7}, Vec3(0.7, 1.3, 2.1), 0.4 * trial,
                                              Vec3(1, -1, 2), Vec3::Zero());
    MaskVolume mask(grid, 0);
    std::bernoulli_distribution feature(trial < 3 ? 0.02 : 0.4);
    for (auto& v : mask.values) v = feature(rng) ? 1 : 0;
    mask.values[trial * 17] = 1;  // at least one feature
    const DistanceTransformResult r = distance_transform(mask, 1);
    for (std::size_t v = 0; v < mask.values.size(); ++v) {
      const Vec3 x = grid.to_world(Vec3(double(v % 13), double((v / 13) % 9), double(v / 117)));
      double best = 1e300;
      for (std::size_t f = 0; f < mask.values.size(); ++f) {
        if (!mask.values[f]) continue;
        const Vec3 y = grid.to_world(Vec3(double(f % 13), double((f / 13) % 9), double(f / 117)));
        best = std::min(best, (x - y).squaredNorm());
      }
      ASSERT_NEAR(r.squared[v], best, 1e-4 * (1.0 + best)) << "voxel " << v;
      const std::uint32_t f = r.nearest[v];
      ASSERT_EQ(mask.values[f], 1);
      const Vec3 y = grid.to_world(Vec3(double(f % 13), double((f / 13) % 9), double(f / 117)));
      ASSERT_NEAR((x - y).squaredNorm(), best, 1e-4 * (1.0 + best));
    }
  }
}

TEST(DistanceTransform, EmptyOrFullMaskIsRejected) {
  const VoxelGrid grid =
      test::oblique_grid({4, 4, 4}, Vec3::Ones(), 0, Vec3::UnitZ(), Vec3::Zero());
  EXPECT_THROW(signed_distance(MaskVolume(grid, 0)), std::invalid_argument);
  EXPECT_THROW(signed_distance(MaskVolume(grid, 1)), std::invalid_argument);
}

// Largest |D - exact| over the voxels within `band` mm of the surface.
double max_error(const ScalarVolume& d, const std::function<double(const Vec3&)>& exact,
                 double band) {
  double worst = 0.0;
  for (int k = 0; k < d.grid.dims[2]; ++k)
    for (int j = 0; j < d.grid.dims[1]; ++j)
      for (int i = 0; i < d.grid.dims[0]; ++i) {
        const double e = exact(d.grid.to_world(Vec3(i, j, k)));
        if (std::abs(e) <= band) worst = std::max(worst, std::abs(d.at(i, j, k) - e));
      }
  return worst;
}

TEST(SignedDistance, BallOnObliqueAnisotropicGridWithinHalfAVoxel) {
  const Vec3 spacing(0.8, 1.0, 1.3), centre(3.0, -2.0, 5.0);
  const VoxelGrid grid = test::oblique_grid({48, 40, 32}, spacing, 0.5, Vec3(1, 2, 3), centre);
  const double radius = 13.7;
  const auto exact = [&](const Vec3& p) { return (p - centre).norm() - radius; };
  const MaskVolume mask = test::rasterise<std::uint8_t>(
      grid, [&](const Vec3& p) { return exact(p) <= 0.0; }, 1, 0);
  const ScalarVolume d = signed_distance(mask);
  const double err = max_error(d, exact, 12.0);
  RecordProperty("max_error_mm", std::to_string(err));
  // A binary mask only says the surface lies between an inside and an outside voxel centre;
  // across a voxel that gap is up to its diagonal, so half the diagonal is the resolution.
  EXPECT_LE(err, 0.5 * spacing.norm());
  // Sign is right everywhere.
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    EXPECT_EQ(d.values[v] < 0.0f, mask.values[v] == 1);
  }
}

TEST(SignedDistance, EllipsoidWithinHalfAVoxel) {
  const Vec3 spacing(1.0, 0.9, 1.2), centre(-4.0, 1.0, 2.0), axes(16.0, 11.0, 8.0);
  const Mat3 frame = Eigen::AngleAxisd(0.7, Vec3(0, 1, 1).normalized()).toRotationMatrix();
  const VoxelGrid grid = test::oblique_grid({44, 40, 36}, spacing, 0.3, Vec3(1, 0, 1), centre);
  const auto exact = [&](const Vec3& p) {
    return test::ellipsoid_distance(frame.transpose() * (p - centre), axes);
  };
  const MaskVolume mask = test::rasterise<std::uint8_t>(
      grid, [&](const Vec3& p) { return exact(p) <= 0.0; }, 1, 0);
  const ScalarVolume d = signed_distance(mask);
  // Beyond a few mm inside, the ellipsoid's medial surface (where the nearest point jumps) is
  // reached and a voxel's nearest outside voxel may lie on the other side of it; compare in a
  // band around the surface.
  const double err = max_error(d, exact, 4.0);
  RecordProperty("max_error_mm", std::to_string(err));
  EXPECT_LE(err, 0.5 * spacing.norm());
}

TEST(SignedDistanceToLevel, SubVoxelOnASmoothField) {
  // field = R - |p - c| is smooth and its zero level is the sphere: the foot points are
  // exact to second order, so the distance is far better than the voxel size.
  const Vec3 spacing(0.8, 1.0, 1.3), centre(1.0, 2.0, -1.0);
  const VoxelGrid grid = test::oblique_grid({40, 36, 28}, spacing, 0.9, Vec3(2, 1, 0), centre);
  const double radius = 11.3;
  ScalarVolume field(grid, 0.0f);
  for (int k = 0; k < 28; ++k)
    for (int j = 0; j < 36; ++j)
      for (int i = 0; i < 40; ++i)
        field.at(i, j, k) =
            static_cast<float>(radius - (grid.to_world(Vec3(i, j, k)) - centre).norm());
  const ScalarVolume d = signed_distance_to_level(field, 0.0);
  const double err = max_error(
      d, [&](const Vec3& p) { return (p - centre).norm() - radius; }, 2.0);
  RecordProperty("max_error_mm", std::to_string(err));
  EXPECT_LE(err, 0.05);
  EXPECT_THROW(signed_distance_to_level(field, 1e6), std::invalid_argument);
}

}  // namespace
}  // namespace dynamesh
