// QuadraticErrorModel (core/adapt/error_model.h) against brute force: residuals that are
// exactly r(b) = A b1 b2 + B b2 b0 + C b0 b1 must be fitted exactly, and the model's maximum
// must equal max |r| found on a dense barycentric grid (exactly for a scalar residual, whose
// maximum is in closed form; within the lattice's 1% for a vector one).
#include <gtest/gtest.h>

#include <random>

#include "core/adapt/error_model.h"

namespace dynamesh {
namespace {

Vec3 quadratic(const Eigen::Matrix3d& coefficients, const Vec3& b) {
  const Vec3 w(b[1] * b[2], b[2] * b[0], b[0] * b[1]);
  return coefficients.transpose() * w;
}

double dense_maximum(const Eigen::Matrix3d& coefficients) {
  constexpr int kOrder = 600;
  double best = 0.0;
  for (int i = 0; i <= kOrder; ++i)
    for (int j = 0; i + j <= kOrder; ++j)
      best = std::max(best, quadratic(coefficients, Vec3(kOrder - i - j, i, j) / kOrder).norm());
  return best;
}

Vec3 random_barycentric(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double a = u(rng), b = u(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return Vec3(1 - a - b, a, b);
}

// A model fitted to 16 random samples of the quadratic with these coefficients.
QuadraticErrorModel fitted(const Eigen::Matrix3d& coefficients, std::mt19937_64& rng) {
  QuadraticErrorModel model;
  for (int s = 0; s < 16; ++s) {
    const Vec3 b = random_barycentric(rng);
    model.add(b, quadratic(coefficients, b));
  }
  return model;
}

TEST(QuadraticErrorModel, ScalarMaximumMatchesDenseSearch) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  int interior_maxima = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
    c.col(0) = Vec3(n(rng), n(rng), n(rng));
    const QuadraticErrorModel::Result r = fitted(c, rng).evaluate();
    ASSERT_TRUE(r.resolved);
    const double dense = dense_maximum(c);
    // The dense grid can only under-estimate the true maximum, by O(h^2).
    EXPECT_GE(r.error, dense * (1 - 1e-9)) << trial;
    EXPECT_LE(r.error, dense * (1 + 1e-4)) << trial;
    if (r.error > 0.25 * c.col(0).cwiseAbs().maxCoeff() * (1 + 1e-6)) ++interior_maxima;
  }
  // Both branches (edge midpoint, interior stationary point) were exercised.
  EXPECT_GT(interior_maxima, 30);
  EXPECT_LT(interior_maxima, 270);
}

TEST(QuadraticErrorModel, VectorMaximumWithinOnePercentOfDenseSearch) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    Eigen::Matrix3d c;
    for (int i = 0; i < 9; ++i) c(i / 3, i % 3) = n(rng);
    const QuadraticErrorModel::Result r = fitted(c, rng).evaluate();
    ASSERT_TRUE(r.resolved);
    const double dense = dense_maximum(c);
    EXPECT_GE(r.error, 0.99 * dense) << trial;
    EXPECT_LE(r.error, dense * (1 + 1e-4)) << trial;
  }
}

TEST(QuadraticErrorModel, SamplesAlongOneEdgeAreNotTrusted) {
  QuadraticErrorModel model;
  for (int s = 1; s < 10; ++s) {
    const double a = s / 10.0;
    model.add(Vec3(0.0, a, 1 - a), Vec3(0.3 * a * (1 - a), 0, 0));
  }
  const QuadraticErrorModel::Result r = model.evaluate();
  EXPECT_FALSE(r.resolved);
  EXPECT_DOUBLE_EQ(r.error, model.sample_max());
}

TEST(QuadraticErrorModel, NonQuadraticResidualIsNotTrusted) {
  // Half a ripple across the face: a quadratic vanishing at the corners explains little.
  std::mt19937_64 rng(3);
  QuadraticErrorModel model;
  for (int s = 0; s < 36; ++s) {
    const Vec3 b = random_barycentric(rng);
    model.add(b, Vec3(std::sin(12.0 * b[1]) * 0.01, 0, 0));
  }
  EXPECT_FALSE(model.evaluate().resolved);
}

// EdgePeak: a residual that is exactly quartic along the edge, r(t) = t (1 - t) q(t) with q
// quadratic (a vector), is interpolated exactly from its quarter points, so the peak it
// reports is the true one within the lattice's step (checked by a search 100x finer); a
// lopsided peak (the quadratic model's midpoint reads a quarter low there) is found where it
// is, not at the midpoint.
TEST(EdgePeak, FindsAQuarticResidualsPeak) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  int off_midpoint = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a(n(rng), n(rng), n(rng)), b(n(rng), n(rng), n(rng)), c(n(rng), n(rng), n(rng));
    const auto r = [&](double t) { return Vec3(t * (1 - t) * (a + t * b + t * t * c)); };
    const EdgePeak peak = edge_peak(r(0.25), r(0.5), r(0.75));
    double best = 0.0, best_t = 0.0;
    for (int k = 1; k < 6400; ++k) {
      const double t = k / 6400.0, value = r(t).norm();
      if (value > best) best = value, best_t = t;
    }
    EXPECT_NEAR(peak.value, r(peak.t).norm(), 1e-12 * best) << trial;
    EXPECT_GE(peak.value, best * (1 - 2e-3)) << trial;
    EXPECT_LE(peak.value, best * (1 + 1e-12)) << trial;
    if (best > 1.2 * r(0.5).norm()) {
      ++off_midpoint;
      // Measured again where it reports the peak, the residual is the peak.
      EXPECT_GE(r(peak.t).norm(), best * (1 - 2e-3)) << trial << " true peak at " << best_t;
    }
  }
  EXPECT_GT(off_midpoint, 30) << "the trials must include peaks well off the midpoint";
}

// On a scalar residual (implicit surfaces, r = (x, 0, 0)) edge_peak takes |x| for the norm:
// it must report exactly what the norm gives on the same lattice (t = k / 64, the quartic
// through the quarter points), bit for bit, so that no reading changes.
TEST(EdgePeak, ScalarResidualReadsExactlyAsItsNorm) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  int ties = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double scale = std::pow(10.0, -12.0 + 12.0 * (trial % 7) / 6.0);
    double a = scale * n(rng), b = scale * n(rng), c = scale * n(rng);
    if (trial % 50 == 0) a = b = c = 0.0;  // no peak: the default one
    const auto r = [&](double t) { return Vec3(t * (1 - t) * (a + t * b + t * t * c), 0, 0); };
    const Vec3 quarter = r(0.25), half = r(0.5);
    // Every fifth edge symmetric about its middle: off the middle, its peak is tied.
    const Vec3 three_quarters = trial % 5 == 1 ? quarter : r(0.75);
    const EdgePeak peak = edge_peak(quarter, half, three_quarters);
    // The lattice and the interpolant as error_model.h states them, with Eigen's norm, scanned
    // for the first largest value and a later point equal to it.
    const Vec3 q0 = half * 4.0, qm = quarter * (16.0 / 3.0), qp = three_quarters * (16.0 / 3.0);
    const Vec3 slope = 0.5 * (qp - qm), bend = 0.5 * (qp + qm) - q0;
    double best = 0.0, best_t = 0.5;
    bool tied = false;
    for (int k = 1; k < 64; ++k) {
      const double t = k / 64.0, s = 4.0 * t - 2.0;
      const double value = t * (1.0 - t) * (q0 + s * slope + s * s * bend).norm();
      if (value > best)
        best = value, best_t = t, tied = false;
      else if (value == best && value > 0.0)
        tied = true;
    }
    EXPECT_EQ(peak.value, best) << trial;
    EXPECT_EQ(peak.t, best_t) << trial;
    EXPECT_EQ(peak.tied, tied) << trial;
    ties += tied;
  }
  EXPECT_GT(ties, 50);
}

// Read from its other end (the face across the edge), an edge's lattice values are the same,
// mirrored, to the bit; the peak's t is the mirrored one exactly when no other lattice point
// ties with it, and `tied` says when one does (SampleStore shares an edge's peak only then).
TEST(EdgePeak, ReadFromTheOtherEndMirrorsUnlessTied) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  int tied = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Vec3 quarter(n(rng), n(rng), n(rng)), half(n(rng), n(rng), n(rng)),
        three_quarters(n(rng), n(rng), n(rng));
    if (trial % 4 == 0) three_quarters = quarter;  // symmetric: every value has a mirror twin
    if (trial % 8 == 1)
      quarter[1] = quarter[2] = half[1] = half[2] = three_quarters[1] = three_quarters[2] =
          0.0;  // scalar
    const EdgePeak forward = edge_peak(quarter, half, three_quarters);
    const EdgePeak backward = edge_peak(three_quarters, half, quarter);
    EXPECT_EQ(forward.value, backward.value) << trial;
    EXPECT_EQ(forward.tied, backward.tied) << trial;
    if (forward.tied)
      ++tied;
    else
      EXPECT_EQ(forward.t, 1.0 - backward.t) << trial;
  }
  // The symmetric residuals that peak off the midpoint tie (those peaking at t = 1/2 do not).
  EXPECT_GT(tied, 100);
}

}  // namespace
}  // namespace dynamesh
