// VoxelGrid: the sampling lattice of a volume image and its map to world millimetres, and
// VoxelVolume<T>: one value per voxel on such a grid.
//
// Following NIfTI-1 (nifti1.h, "3D IMAGE (VOLUME) ORIENTATION AND LOCATION IN SPACE"), the
// integer index (i, j, k) names the *centre* of a voxel and an affine map takes it to world
// coordinates: p = linear * (i, j, k) + offset. The map may be oblique (a rotated sform or
// qform); its columns are the voxel axes in the world, so their lengths are the spacings.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/LU>

#include "core/geometry/vector_types.h"
#include "core/surface/volume/huge_pages.h"

namespace dynamesh {

struct VoxelGrid {
  std::array<int, 3> dims{0, 0, 0};
  Mat3 linear{Mat3::Identity()};  // voxel index -> world, columns are the voxel axes
  Vec3 offset{Vec3::Zero()};      // world position of voxel (0, 0, 0)

  std::size_t count() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
           static_cast<std::size_t>(dims[2]);
  }
  // Linear storage index, i fastest (the NIfTI on-disk order).
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * k);
  }
  bool contains(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < dims[0] && j < dims[1] && k < dims[2];
  }

  Vec3 to_world(const Vec3& ijk) const { return linear * ijk + offset; }
  Vec3 to_voxel(const Vec3& p) const { return linear.inverse() * (p - offset); }
  // Distance between neighbouring voxel centres along each index axis, in mm.
  Vec3 spacing() const { return linear.colwise().norm().transpose(); }
  double voxel_volume() const { return std::abs(linear.determinant()); }

  // World-space box around every voxel (each voxel taken as the cell of half-width 1/2
  // around its centre).
  Box3 world_bounds() const {
    Box3 box;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 ijk((corner & 1) ? dims[0] - 0.5 : -0.5, (corner & 2) ? dims[1] - 0.5 : -0.5,
                     (corner & 4) ? dims[2] - 0.5 : -0.5);
      box.extend(to_world(ijk));
    }
    return box;
  }
};

template <class T>
struct VoxelVolume {
  VoxelGrid grid;
  std::vector<T> values;  // grid.count() values, indexed by grid.index()

  VoxelVolume() = default;
  VoxelVolume(const VoxelGrid& g, T fill) : grid(g) {
    reserve_huge(values, g.count());
    values.assign(g.count(), fill);
  }

  T& at(int i, int j, int k) { return values[grid.index(i, j, k)]; }
  const T& at(int i, int j, int k) const { return values[grid.index(i, j, k)]; }
};

using ScalarVolume = VoxelVolume<float>;
using MaskVolume = VoxelVolume<std::uint8_t>;  // 1 inside, 0 outside

}  // namespace dynamesh
