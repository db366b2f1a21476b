// atan2 by a rational approximation (Cephes' atan: Moshier, "Methods and Programs for
// Mathematical Functions", 1989; the same coefficients as Go's math.Atan), for hot paths.
//
// glibc's atan2 is correctly rounded and pays for it: on the capsule-bend scene, whose bend
// map (bend_map.cpp) takes one atan2 per evaluation, it was 10-12% of a step (perf, issue 17),
// much of it saving and restoring the rounding mode. This one is within a few ulp of it
// (test_polynomial_atan.cpp checks 4 ulp of the result, or 4 ulp of pi where the quadrant
// fold subtracts from pi), which is far below any tolerance of the geometry built on it.
#pragma once

#include <cmath>

namespace dynamesh {

namespace polynomial_atan_detail {

// atan(x) for 0 <= x <= 0.66: x + x^3 P(x^2) / Q(x^2).
inline double atan_small(double x) {
  constexpr double P0 = -8.750608600031904122785e-01, P1 = -1.615753718733365076637e+01,
                   P2 = -7.500855792314704667340e+01, P3 = -1.228866684490136173410e+02,
                   P4 = -6.485021904942025371773e+01;
  constexpr double Q0 = 2.485846490142306297962e+01, Q1 = 1.650270098316988542046e+02,
                   Q2 = 4.328810604912902668951e+02, Q3 = 4.853903996359136964868e+02,
                   Q4 = 1.945506571482613964425e+02;
  const double z = x * x;
  const double p = (((P0 * z + P1) * z + P2) * z + P3) * z + P4;
  const double q = ((((z + Q0) * z + Q1) * z + Q2) * z + Q3) * z + Q4;
  return x + x * (z * p / q);
}

// atan(x) for x >= 0 (inf included), reduced to [0, 0.66] by atan(x) = pi/2 - atan(1/x) above
// tan(3 pi/8) and atan(x) = pi/4 + atan((x - 1)/(x + 1)) between.
inline double atan_nonnegative(double x) {
  constexpr double kPiOver2 = 1.57079632679489655800e+00, kPiOver4 = 7.85398163397448278999e-01;
  constexpr double kMoreBits = 6.123233995736765886130e-17;  // pi/2 - kPiOver2
  constexpr double kTan3PiOver8 = 2.41421356237309504880;
  if (x <= 0.66) return atan_small(x);
  if (x > kTan3PiOver8) return kPiOver2 - atan_small(1.0 / x) + kMoreBits;
  return kPiOver4 + atan_small((x - 1.0) / (x + 1.0)) + 0.5 * kMoreBits;
}

}  // namespace polynomial_atan_detail

// atan2(y, x) in (-pi, pi]; zeros, infinities and NaN go to std::atan2 (their signs and
// conventions are its own).
inline double polynomial_atan2(double y, double x) {
  if (!(std::isfinite(x) && std::isfinite(y)) || (x == 0.0 && y == 0.0)) return std::atan2(y, x);
  const double ax = std::abs(x), ay = std::abs(y);
  // ay / ax may overflow to inf (x tiny): atan_nonnegative(inf) is pi/2, as it should be.
  double r = ax > 0.0 ? polynomial_atan_detail::atan_nonnegative(ay / ax) : 1.57079632679489661923;
  if (std::signbit(x)) r = 3.14159265358979311600 - r + 1.2246467991473532e-16;
  return std::signbit(y) ? -r : r;
}

}  // namespace dynamesh
