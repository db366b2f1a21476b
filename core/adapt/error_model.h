// QuadraticErrorModel: the L-infinity error of a flat triangle over a smooth surface, from
// its samples. Stochastic samples alone miss the peak of the error between them by up to
// (cell size / circumradius)^2 of its value — about 20% with 16 samples per triangle —
// so the adapter would stop refining too early.
//
// The residual r(b) (parametric: x(b) - S(uv(b)); implicit: the signed distance) is a smooth
// function of the barycentric coordinates b that vanishes at the three vertices, which lie
// on the surface. To second order it is therefore r(b) = A b1 b2 + B b2 b0 + C b0 b1 with one
// coefficient vector per edge. The model fits A, B, C to the samples by least squares and
// takes the maximum of |r| over the triangle: in closed form for a scalar residual (a
// quadratic's extremum lies at an edge midpoint or at its one stationary point), on a fine
// barycentric lattice for a vector one; the triangle's error is the larger of that and the
// largest sample. This improves on the paper's pure sampling (Section 3.1).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/geometry/vector_types.h"

namespace dynamesh {

class QuadraticErrorModel {
 public:
  void add(const Vec3& b, const Vec3& residual);
  // A scalar residual (an implicit surface's signed distance): add(b, (r, 0, 0)), cheaper.
  void add(const Vec3& b, double residual) {
    const Vec3 w(b[1] * b[2], b[2] * b[0], b[0] * b[1]);
    add_normal(w);
    moment_.col(0) += residual * w;
    sum_squares_ += residual * residual;
    ++count_;
    sample_max_ = std::max(sample_max_, std::abs(residual));
  }
  // Largest sample error seen.
  double sample_max() const { return sample_max_; }
  // max(sample_max, the fitted model's maximum over the triangle); sample_max alone when
  // the samples cannot determine the model (fewer than 3, or degenerate) or the model does
  // not fit them (it explains under 70% of their squared residual: the residual is not
  // quadratic over this triangle, e.g. it spans half a ripple, and extrapolating the fit
  // would overshoot).
  double estimate() const { return evaluate().error; }
  struct Result {
    double error = 0.0;
    // False when the samples could not determine or did not fit the model: the error is
    // then only the largest sample, and more samples are needed to trust it.
    bool resolved = false;
  };
  Result evaluate() const;
  // Where the fitted model peaks strictly inside the triangle, when it does (else false): the
  // place to measure again (SampleStore keeps a sample there). Scalar residual: the model's
  // stationary point, when it lies inside and no edge midpoint reads more (scalar_maximum);
  // vector residual: the largest of the lattice evaluate() uses (order 8), when that point is
  // not on an edge, refined on two lattices 4 and 16 times finer around it. A peak on an edge is
  // the edge peaks' to find (EdgePeak). The model must be resolved (evaluate()), else the location
  // means nothing.
  bool interior_peak(Vec3& at) const;

 private:
  // The upper triangle of the symmetric sum of w w^T (this runs for every sample).
  void add_normal(const Vec3& w) {
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) normal_(i, j) += w[i] * w[j];
  }
  // Sum of w w^T, w = (b1b2, b2b0, b0b1); only the upper triangle is accumulated.
  Eigen::Matrix3d normal_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d moment_ = Eigen::Matrix3d::Zero();  // sum of w r^T
  double sum_squares_ = 0.0;                          // sum of |r|^2
  int count_ = 0;
  double sample_max_ = 0.0;
  bool vector_ = false;  // some residual had a non-zero second or third component
};

// EdgePeak: where along one edge of a triangle its residual peaks, from the residual at the
// edge's quarter points. On a saddle-shaped patch (the twisted bar's sides, paper Section 5)
// |r| is largest on the triangle's edges, and a residual whose curvature varies across a
// long edge (a rounded rim) is not quadratic there: its peak moves off the midpoint and rises
// above the quadratic model's A / 4 (by up to 33% on twist at T = 0.004, where the nine
// stratified samples of a face lie inside it and only extrapolate to the edge). Along the
// edge r(t) = t (1 - t) q(t) vanishes at both ends; q is interpolated by the quadratic through
// r(1/4), r(1/2), r(3/4), which makes r exact to fourth order, and the quartic's maximum over
// a lattice of the edge is its peak: the place to measure again.
struct EdgePeak {
  double t = 0.5;      // where the interpolant peaks, in (0, 1)
  double value = 0.0;  // its magnitude there
  // Another lattice point reads the same positive value: the edge read the other way round
  // (from its other face) would peak at another t (SampleStore's shared edge peaks).
  bool tied = false;
};
EdgePeak edge_peak(const Vec3& quarter, const Vec3& half, const Vec3& three_quarters);

// Largest |a b1 b2 + b b2 b0 + c b0 b1| over the triangle b >= 0, b0 + b1 + b2 = 1 (exact): the
// scalar model's maximum, and the predictor's bound on a scalar residual's quadratic change
// (inline: ErrorPredictor::select calls it for every skipped face). On an edge only one term
// survives, largest at the midpoint (a / 4, ...); inside, r is a quadratic in (x, y) = (b1, b2)
// whose stationary point solves
//   [-2c, d; d, -2b] (x, y) = (-c, -b),  d = a - b - c.
inline double scalar_maximum(double a, double b, double c) {
  double best = 0.25 * std::max({std::abs(a), std::abs(b), std::abs(c)});
  const double d = a - b - c;
  const double det = 4.0 * b * c - d * d;
  if (det != 0.0) {
    const double x = (2.0 * b * c + b * d) / det, y = (2.0 * b * c + c * d) / det;
    if (x > 0.0 && y > 0.0 && x + y < 1.0) {
      const double z = 1.0 - x - y;
      best = std::max(best, std::abs(a * x * y + b * y * z + c * z * x));
    }
  }
  return best;
}

}  // namespace dynamesh
