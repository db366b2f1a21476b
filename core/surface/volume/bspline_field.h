// A smooth scalar field over a voxel grid: the uniform cubic B-spline whose coefficients are
// the voxel values, evaluated at world points with its gradient and Hessian.
//
// Why this interpolant: the cubic B-spline is C2, so the Hessian (and the curvature of level
// sets that the adapter reads) is continuous; it reproduces linear functions exactly, so a
// distance field keeps |grad| = 1 where it is planar; and used without prefiltering it is a
// light low-pass (variance 1/3 voxel^2 per axis) that softens the voxel staircase of a
// distance transform of a binary mask. (M. Unser, "Splines: a perfect fit for signal and
// image processing", IEEE Signal Processing Magazine 16(6), 1999.)
//
// World points map to voxel coordinates through the grid's affine map, which may be oblique:
// grad_p = A^-T grad_u and H_p = A^-T H_u A^-1 (chain rule, A constant). Beyond the outermost
// voxel centres the field continues as its value at the nearest point of that box plus the
// distance to it, so it keeps growing away from the data and Newton steps come back.
#pragma once

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

class CubicBSplineField {
 public:
  CubicBSplineField() = default;
  explicit CubicBSplineField(ScalarVolume coefficients);

  double value(const Vec3& p) const;
  double value_gradient(const Vec3& p, Vec3& gradient) const;
  double value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const;

  const VoxelGrid& grid() const { return coefficients_.grid; }
  const ScalarVolume& coefficients() const { return coefficients_; }

 private:
  template <int Order>
  double evaluate(const Vec3& p, Vec3* gradient, Mat3* hessian) const;
  template <int Order>
  double evaluate_voxel(const Vec3& u, Vec3* gradient_u, Mat3* hessian_u) const;

  ScalarVolume coefficients_;
  Mat3 to_voxel_{Mat3::Identity()};  // A^-1
  Vec3 upper_{Vec3::Zero()};         // dims - 1: the box of voxel centres is [0, upper]
};

}  // namespace dynamesh
