// A synthetic T1 "brain" for the mri tests: a ball of radius kBallRadius around kBallCentre,
// intensity 80 + z (60..100, so colouring by intensity has something to show) on a
// background of 0, stored as int16 NIfTI with an oblique sform and anisotropic voxels. Its
// isolayer at depth d is the sphere of radius kBallRadius - d.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "test_nifti_files.h"
#include "test_volume_fixtures.h"

namespace dynamesh::test {

inline constexpr double kBallRadius = 20.0;
inline const Vec3 kBallCentre(4.0, -3.0, 10.0);
inline const Vec3 kBallSpacing(0.9, 1.0, 1.2);

// Writes the ball into a fresh scratch directory named `name`; returns the file.
inline std::filesystem::path write_ball_file(const std::string& name = "mri_ball") {
  const auto path = scratch_dir(name) / "ball.nii.gz";
  const VoxelGrid grid = oblique_grid({60, 54, 46}, kBallSpacing, 0.35, Vec3(1, 1, 0), kBallCentre);
  std::vector<std::int16_t> values;
  for (int k = 0; k < 46; ++k)
    for (int j = 0; j < 54; ++j)
      for (int i = 0; i < 60; ++i) {
        const Vec3 p = grid.to_world(Vec3(i, j, k)) - kBallCentre;
        values.push_back(
            static_cast<std::int16_t>(p.norm() <= kBallRadius ? std::lround(80.0 + p.z()) : 0));
      }
  nifti_1_header h = make_header({60, 54, 46}, DT_INT16, 16);
  set_sform(h, grid.linear, grid.offset);
  write_nifti(path, h, values);
  return path;
}

}  // namespace dynamesh::test
