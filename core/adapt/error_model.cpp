#include "core/adapt/error_model.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dynamesh {
namespace {

// Barycentric lattice of order 8 (45 points): fine enough that the fitted quadratic's
// maximum between lattice points exceeds the lattice maximum by under 1%.
constexpr int kLatticeOrder = 8;
constexpr int kLatticePoints = (kLatticeOrder + 1) * (kLatticeOrder + 2) / 2;
constexpr double kMinExplained = 0.7;
// Below this reciprocal condition number (1-norm) the samples, crowded along one edge, leave
// a coefficient undetermined.
constexpr double kMinRcond = 1e-6;

Vec3 edge_weights(const Vec3& b) {
  return Vec3(b[1] * b[2], b[2] * b[0], b[0] * b[1]);
}

// The edge weights at every lattice point, computed once.
const std::array<Vec3, kLatticePoints>& lattice_weights() {
  static const std::array<Vec3, kLatticePoints> table = [] {
    std::array<Vec3, kLatticePoints> w;
    int n = 0;
    for (int i = 0; i <= kLatticeOrder; ++i)
      for (int j = 0; i + j <= kLatticeOrder; ++j)
        w[n++] = edge_weights(Vec3(kLatticeOrder - i - j, i, j) / kLatticeOrder);
    return w;
  }();
  return table;
}

double norm1(const Eigen::Matrix3d& m) {
  return m.cwiseAbs().colwise().sum().maxCoeff();
}

}  // namespace

void QuadraticErrorModel::add(const Vec3& b, const Vec3& residual) {
  const Vec3 w = edge_weights(b);
  add_normal(w);
  moment_.noalias() += w * residual.transpose();
  sum_squares_ += residual.squaredNorm();
  ++count_;
  sample_max_ = std::max(sample_max_, residual.norm());
  vector_ = vector_ || residual[1] != 0.0 || residual[2] != 0.0;
}

QuadraticErrorModel::Result QuadraticErrorModel::evaluate() const {
  const Result unresolved{sample_max_, false};
  if (count_ < 3) return unresolved;
  // An exact zero residual everywhere (a flat face of a plane) needs no model.
  if (sum_squares_ == 0.0) return {0.0, true};
  // The normal matrix is symmetric 3 x 3: its explicit inverse is cheaper than a
  // factorisation and gives the exact condition number.
  const Eigen::Matrix3d normal = normal_.selfadjointView<Eigen::Upper>();
  const Eigen::Matrix3d inverse = normal.inverse();
  if (!inverse.allFinite() || 1.0 / (norm1(normal) * norm1(inverse)) < kMinRcond) return unresolved;
  const Eigen::Matrix3d coefficients = inverse * moment_;  // row e: edge e's vector
  // Least squares: the explained part of sum |r|^2 is trace(C^T M).
  const double explained = (coefficients.transpose() * moment_).trace();
  if (count_ > 3 && explained < kMinExplained * sum_squares_) return unresolved;
  double model_max = 0.0;
  if (!vector_) {
    model_max = scalar_maximum(coefficients(0, 0), coefficients(1, 0), coefficients(2, 0));
  } else {
    double max2 = 0.0;
    for (const Vec3& w : lattice_weights())
      max2 = std::max(max2, (coefficients.transpose() * w).squaredNorm());
    model_max = std::sqrt(max2);
  }
  return {std::max(sample_max_, model_max), true};
}

bool QuadraticErrorModel::interior_peak(Vec3& at) const {
  if (count_ < 3) return false;
  const Eigen::Matrix3d inverse =
      Eigen::Matrix3d(normal_.selfadjointView<Eigen::Upper>()).inverse();
  if (!inverse.allFinite()) return false;
  const Eigen::Matrix3d coefficients = inverse * moment_;
  if (!vector_) {
    // The stationary point of scalar_maximum, kept only where it is the maximum.
    const double a = coefficients(0, 0), b = coefficients(1, 0), c = coefficients(2, 0);
    const double d = a - b - c, det = 4.0 * b * c - d * d;
    if (det == 0.0) return false;
    const double x = (2.0 * b * c + b * d) / det, y = (2.0 * b * c + c * d) / det;
    if (!(x > 0.0 && y > 0.0 && x + y < 1.0)) return false;
    const double z = 1.0 - x - y;
    if (std::abs(a * x * y + b * y * z + c * z * x) <
        0.25 * std::max({std::abs(a), std::abs(b), std::abs(c)}))
      return false;
    at = Vec3(z, x, y);
    return true;
  }
  double best = -1.0;
  int n = 0, best_i = 0, best_j = 0;
  for (int i = 0; i <= kLatticeOrder; ++i)
    for (int j = 0; i + j <= kLatticeOrder; ++j, ++n) {
      const double v = (coefficients.transpose() * lattice_weights()[n]).squaredNorm();
      if (v > best) best = v, best_i = i, best_j = j;
    }
  if (best_i == 0 || best_j == 0 || best_i + best_j == kLatticeOrder) return false;
  // Refined around the lattice's best point, twice, on lattices 4 times finer (the lattice's
  // spacing, 1/8, would leave the point up to 1/16 off the model's peak: a peak narrower than
  // the face is then measured on its flank).
  double x = static_cast<double>(best_i) / kLatticeOrder,
         y = static_cast<double>(best_j) / kLatticeOrder;
  for (double step = 0.25 / kLatticeOrder; step > 0.01 / kLatticeOrder; step *= 0.25) {
    const double cx = x, cy = y;
    for (int i = -4; i <= 4; ++i)
      for (int j = -4; j <= 4; ++j) {
        const double u = cx + i * step, v = cy + j * step;
        if (!(u > 0.0 && v > 0.0 && u + v < 1.0)) continue;
        const double value =
            (coefficients.transpose() * edge_weights(Vec3(1.0 - u - v, u, v))).squaredNorm();
        if (value > best) best = value, x = u, y = v;
      }
  }
  at = Vec3(1.0 - x - y, x, y);
  return true;
}

namespace {

// edge_peak's lattice: t = k / 64 (k = 1 ... 63), s = 4 t - 2, s^2 and t (1 - t), computed once
// by the same double operations the loop did at each point (IEEE at compile time as at run
// time: the same bits), so that the loop only evaluates the quartic.
constexpr int kIntervals = 64;
struct EdgeLattice {
  double t[kIntervals - 1], s[kIntervals - 1], s2[kIntervals - 1], w[kIntervals - 1];
};
constexpr EdgeLattice make_edge_lattice() {
  EdgeLattice l{};
  for (int k = 1; k < kIntervals; ++k) {
    const double t = static_cast<double>(k) / kIntervals, s = 4.0 * t - 2.0;
    l.t[k - 1] = t;
    l.s[k - 1] = s;
    l.s2[k - 1] = s * s;
    l.w[k - 1] = t * (1.0 - t);
  }
  return l;
}
constexpr EdgeLattice kEdgeLattice = make_edge_lattice();

// The first largest of the lattice's values, and whether another point ties with it.
EdgePeak first_largest(const double (&value)[kIntervals - 1]) {
  EdgePeak best;
  for (int i = 0; i < kIntervals - 1; ++i) {
    if (value[i] > best.value)
      best = {kEdgeLattice.t[i], value[i], false};
    else if (value[i] == best.value && value[i] > 0.0)
      best.tied = true;
  }
  return best;
}

}  // namespace

EdgePeak edge_peak(const Vec3& quarter, const Vec3& half, const Vec3& three_quarters) {
  // q at t = 1/4, 1/2, 3/4 (t (1 - t) = 3/16, 1/4, 3/16), as a quadratic in s = 4 t - 2 (-1, 0, 1).
  const Vec3 q0 = half * 4.0, qm = quarter * (16.0 / 3.0), qp = three_quarters * (16.0 / 3.0);
  const Vec3 slope = 0.5 * (qp - qm), bend = 0.5 * (qp + qm) - q0;
  // A lattice of 64 intervals: between its points the quartic rises by under 0.1% of its peak
  // (its second derivative is at most ~10 peak over the edge), and the peak is measured again.
  const EdgeLattice& l = kEdgeLattice;
  double value[kIntervals - 1];
  if (slope[1] == 0.0 && slope[2] == 0.0 && bend[1] == 0.0 && bend[2] == 0.0 && q0[1] == 0.0 &&
      q0[2] == 0.0) {
    // A scalar residual (implicit surfaces): the same values without a square root per point.
    // The norm of (x, 0, 0) is sqrt(x * x), which is |x| exactly in binary floating point
    // unless x * x underflows or overflows; there the norm is taken as above.
    bool plain = true;
    for (int i = 0; i < kIntervals - 1; ++i) {
      const double magnitude = std::abs(q0[0] + l.s[i] * slope[0] + l.s2[i] * bend[0]);
      plain = plain & (magnitude > 1e-150) & (magnitude < 1e150);
      value[i] = l.w[i] * magnitude;
    }
    if (!plain) {
      for (int i = 0; i < kIntervals - 1; ++i) {
        const double x = q0[0] + l.s[i] * slope[0] + l.s2[i] * bend[0];
        if (!(std::abs(x) > 1e-150 && std::abs(x) < 1e150)) value[i] = l.w[i] * std::sqrt(x * x);
      }
    }
    return first_largest(value);
  }
  for (int i = 0; i < kIntervals - 1; ++i)
    value[i] = l.w[i] * (q0 + l.s[i] * slope + l.s2[i] * bend).norm();
  return first_largest(value);
}

}  // namespace dynamesh
