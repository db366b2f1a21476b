#include "core/adapt/error_model.h"

#include <algorithm>
#include <array>

namespace dynamesh {
namespace {

// Barycentric lattice of order 8 (45 points): fine enough that the fitted quadratic's
// maximum between lattice points exceeds the lattice maximum by under 1%.
constexpr int kLatticeOrder = 8;
constexpr double kMinExplained = 0.7;

Vec3 edge_weights(const Vec3& b) {
  return Vec3(b[1] * b[2], b[2] * b[0], b[0] * b[1]);
}

}  // namespace

void QuadraticErrorModel::add(const Vec3& b, const Vec3& residual) {
  const Vec3 w = edge_weights(b);
  normal_.noalias() += w * w.transpose();
  moment_.noalias() += w * residual.transpose();
  sum_squares_ += residual.squaredNorm();
  ++count_;
  sample_max_ = std::max(sample_max_, residual.norm());
}

QuadraticErrorModel::Result QuadraticErrorModel::evaluate() const {
  const Result unresolved{sample_max_, false};
  if (count_ < 3) return unresolved;
  // An exact zero residual everywhere (a flat face of a plane) needs no model.
  if (sum_squares_ == 0.0) return {0.0, true};
  const Eigen::LDLT<Eigen::Matrix3d> solver(normal_);
  // Samples crowded along one edge leave a coefficient undetermined: trust the samples.
  if (solver.info() != Eigen::Success || solver.rcond() < 1e-6) return unresolved;
  const Eigen::Matrix3d coefficients = solver.solve(moment_);  // row e: edge e's vector
  // Least squares: the explained part of sum |r|^2 is trace(C^T M).
  const double explained = (coefficients.transpose() * moment_).trace();
  if (count_ > 3 && explained < kMinExplained * sum_squares_) return unresolved;
  double model_max = 0.0;
  for (int i = 0; i <= kLatticeOrder; ++i) {
    for (int j = 0; i + j <= kLatticeOrder; ++j) {
      const Vec3 b(kLatticeOrder - i - j, i, j);
      const Vec3 r = coefficients.transpose() * edge_weights(b / kLatticeOrder);
      model_max = std::max(model_max, r.norm());
    }
  }
  return {std::max(sample_max_, model_max), true};
}

}  // namespace dynamesh
