// polynomial_atan2 (the bend map's atan2) against the C library's correctly rounded atan2, over
// every quadrant, every reduction interval of the approximation and magnitudes from 1e-300 to
// 1e300, and at the special values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "core/surface/polynomial_atan.h"

namespace dynamesh {
namespace {

// Units in the last place of |x| (the spacing of doubles at x).
double ulp(double x) {
  x = std::abs(x);
  return std::nextafter(x, std::numeric_limits<double>::infinity()) - x;
}

// Within 4 ulp of the reference; where the result was folded from pi (x < 0), within 4 ulp of
// pi (the subtraction's own rounding), which is what any atan2 built on atan(|y/x|) can give.
void expect_close(double y, double x) {
  const double ref = std::atan2(y, x), got = polynomial_atan2(y, x);
  const double tolerance = 4.0 * (x < 0 ? ulp(std::numbers::pi) : std::max(ulp(ref), 0.0));
  ASSERT_LE(std::abs(got - ref), tolerance) << "y=" << y << " x=" << x << " ref=" << ref;
}

TEST(PolynomialAtan, WithinFourUlpOfTheLibraryOverAllQuadrantsAndScales) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  for (int i = 0; i < 200000; ++i) {
    const double a = angle(rng), r = std::pow(10.0, exponent(rng));
    expect_close(r * std::sin(a), r * std::cos(a));
  }
  // The bend map's own range: b = 1 - kappa y near 1, a = kappa x small.
  std::uniform_real_distribution<double> small(-0.5, 0.5);
  for (int i = 0; i < 200000; ++i) expect_close(small(rng), 1.0 + small(rng));
}

TEST(PolynomialAtan, ReductionBoundariesAndAxes) {
  // The approximation switches at |y/x| = 0.66 and tan(3 pi/8); both sides of each, every
  // quadrant.
  for (double t : {0.66, 2.41421356237309504880, 1.0, 1e-8, 1e8})
    for (double s : {std::nextafter(t, 0.0), t, std::nextafter(t, 10.0)})
      for (double sx : {1.0, -1.0})
        for (double sy : {1.0, -1.0}) expect_close(sy * s, sx * 1.0);
  for (double x : {1.0, -1.0, 1e-300, -1e-300}) {
    expect_close(0.0, x);
    expect_close(-0.0, x);
    expect_close(x, 0.0);
    expect_close(x, -0.0);
  }
}

TEST(PolynomialAtan, SpecialValuesAreTheLibrarys) {
  const double inf = std::numeric_limits<double>::infinity();
  for (double y : {0.0, -0.0, 1.0, -1.0, inf, -inf})
    for (double x : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
      const double ref = std::atan2(y, x), got = polynomial_atan2(y, x);
      EXPECT_EQ(std::signbit(got), std::signbit(ref)) << y << " " << x;
      EXPECT_NEAR(got, ref, 4.0 * ulp(std::numbers::pi)) << y << " " << x;
    }
  EXPECT_TRUE(std::isnan(polynomial_atan2(std::nan(""), 1.0)));
  EXPECT_TRUE(std::isnan(polynomial_atan2(1.0, std::nan(""))));
}

}  // namespace
}  // namespace dynamesh
