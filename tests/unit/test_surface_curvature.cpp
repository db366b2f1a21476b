// Principal curvatures of the scenes against closed forms (sign convention of surface.h:
// positive where the surface bends away from its normal, a sphere with outward normal has
// +1/R). Every expected value is derived here, independently of the scene code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/surface/scenes/capsule_bend_scene.h"
#include "core/surface/scenes/sinc_scene.h"
#include "core/surface/scenes/sphere_scene.h"
#include "core/surface/scenes/twist_scene.h"
#include "test_surface_support.h"

namespace dynamesh {
namespace {

using testing::Random;
constexpr double kPi = std::numbers::pi;

TEST(SurfaceCurvature, SphereHasBothCurvaturesOneOverRadius) {
  SphereScene s;
  Random rnd(11);
  // The paper's radii 0.6, 1.0, 1.6 and 9.0 (SCENES.md).
  for (const double t : {0.0, 0.1886, 0.3622, 1.0}) {
    s.set_time(t);
    const double R = 0.6 * std::pow(9.0 / 0.6, t);
    for (int i = 0; i < 20; ++i) {
      const Vec3 n = rnd.unit_vector();
      const PrincipalCurvatures c = s.curvatures(R * n);
      EXPECT_NEAR(c.k1, 1.0 / R, 1e-10 / R);
      EXPECT_NEAR(c.k2, 1.0 / R, 1e-10 / R);
      EXPECT_LE((c.normal - n).norm(), 1e-12);
      EXPECT_NEAR(c.dir1.dot(n), 0.0, 1e-12);
      EXPECT_NEAR(c.dir2.dot(n), 0.0, 1e-12);
      EXPECT_NEAR(c.dir1.dot(c.dir2), 0.0, 1e-12);
    }
  }
}

TEST(SurfaceCurvature, StraightCapsuleCylinderAndCaps) {
  CapsuleBendScene s;  // t = 0: no bend
  const double h = 1.5, r = 0.4;
  Random rnd(12);
  for (int i = 0; i < 20; ++i) {
    const double x = rnd.uniform(-0.9 * h, 0.9 * h), a = rnd.uniform(0, 2 * kPi);
    const Vec3 radial(0, std::cos(a), std::sin(a));
    const PrincipalCurvatures c = s.curvatures(Vec3(x, 0, 0) + r * radial);
    EXPECT_NEAR(c.k1, 1.0 / r, 1e-9);
    EXPECT_NEAR(c.k2, 0.0, 1e-9);
    EXPECT_LE((c.normal - radial).norm(), 1e-12);
    EXPECT_NEAR(std::abs(c.dir1.x()), 0.0, 1e-9);  // around the axis
    EXPECT_NEAR(std::abs(c.dir2.x()), 1.0, 1e-9);  // along the axis
  }
  for (int i = 0; i < 20; ++i) {
    Vec3 d = rnd.unit_vector();
    d.x() = std::max(std::abs(d.x()), 0.05);  // a point of the +x cap ...
    d.normalize();
    const double side = i % 2 ? 1.0 : -1.0;  // ... or its mirror on the -x cap
    const Vec3 p = Vec3(side * h, 0, 0) + r * Vec3(side * d.x(), d.y(), d.z());
    const PrincipalCurvatures c = s.curvatures(p);
    EXPECT_NEAR(c.k1, 1.0 / r, 1e-9);
    EXPECT_NEAR(c.k2, 1.0 / r, 1e-9);
  }
}

// Bent, the cylinder part is a piece of torus around the bending axis (parallel to z through
// (0, 1/kappa, 0)) with major radius 1/kappa and minor radius r: at tube angle v (v = 0 on the
// outside) its curvatures are 1/r and cos v / (1/kappa + r cos v).
TEST(SurfaceCurvature, BentCapsuleIsATorusPiece) {
  CapsuleBendScene s;
  const double h = 1.5, r = 0.4;
  Random rnd(13);
  for (const double t : {0.3, 0.7, 1.0}) {
    s.set_time(t);
    const double kappa = kPi * t / (2 * h), R = 1 / kappa;
    for (int i = 0; i < 20; ++i) {
      const double x = rnd.uniform(-0.9 * h, 0.9 * h), v = rnd.uniform(0, 2 * kPi);
      const double theta = kappa * x, rho = R + r * std::cos(v);
      // Rest point (x, -r cos v, r sin v) has rho = R - q.y; world: rho (sin, -cos) about axis.
      const Vec3 p(rho * std::sin(theta), R - rho * std::cos(theta), r * std::sin(v));
      const PrincipalCurvatures c = s.curvatures(p);
      const double k_around = std::cos(v) / (R + r * std::cos(v));
      EXPECT_NEAR(c.k1, std::max(1.0 / r, k_around), 1e-8) << "t=" << t << " v=" << v;
      EXPECT_NEAR(c.k2, std::min(1.0 / r, k_around), 1e-8) << "t=" << t << " v=" << v;
      const Vec3 centre(R * std::sin(theta), R - R * std::cos(theta), 0);
      EXPECT_LE((c.normal - (p - centre) / r).norm(), 1e-9);
    }
  }
}

// The sinc profile f(r) = A sin(b r) exp(k r) / (b r) differentiated by hand (product and
// quotient rules, a different route from the scene's sinc-derivative composition).
struct SincProfile {
  double A, b, k;
  double d1(double r) const {
    const double s = std::sin(b * r), c = std::cos(b * r), e = std::exp(k * r);
    return A * e * (b * c / r + k * s / r - s / (r * r)) / b;
  }
  double d2(double r) const {
    const double s = std::sin(b * r), c = std::cos(b * r), e = std::exp(k * r);
    const double g = b * c / r + k * s / r - s / (r * r);  // f' = A e g / b
    const double dg = -b * b * s / r - b * c / (r * r) + k * b * c / r - k * s / (r * r) -
                      b * c / (r * r) + 2 * s / (r * r * r);
    return A * e * (k * g + dg) / b;
  }
};

// The point (x, z) = r (cos phi, sin phi) of the sinc, whose (u, v) is (z, x) (sinc_scene.h).
Vec2 sinc_uv(double r, double phi) {
  return r * Vec2(std::sin(phi), std::cos(phi));
}

// For the height field y = f(r) with normal Su x Sv (pointing to +y), a surface of revolution:
// radial curvature -f'' / (1 + f'^2)^(3/2), circumferential -f' / (r sqrt(1 + f'^2)), both
// positive for a dome f'' < 0, f' < 0 (it bends away from its upward normal).
void expect_sinc_curvatures(const SincScene& s, const SincProfile& f, double r, double phi,
                            double tol) {
  const double d1 = f.d1(r), d2 = f.d2(r);
  const double k_radial = -d2 / std::pow(1 + d1 * d1, 1.5);
  const double k_circ = -d1 / (r * std::sqrt(1 + d1 * d1));
  const PrincipalCurvatures c = s.curvatures(sinc_uv(r, phi));
  EXPECT_NEAR(c.k1, std::max(k_radial, k_circ), tol) << "r=" << r;
  EXPECT_NEAR(c.k2, std::min(k_radial, k_circ), tol) << "r=" << r;
  const Vec3 normal = Vec3(-d1 * std::cos(phi), 1, -d1 * std::sin(phi)).normalized();
  EXPECT_LE((c.normal - normal).norm(), 1e-12);
  if (std::abs(k_radial - k_circ) > 1e-3) {
    const Vec3 radial = Vec3(std::cos(phi), d1, std::sin(phi)).normalized();
    const Vec3& dir = k_radial > k_circ ? c.dir1 : c.dir2;
    EXPECT_NEAR(std::abs(dir.dot(radial)), 1.0, 1e-9) << "r=" << r;
  }
}

TEST(SurfaceCurvature, SincAsASurfaceOfRevolution) {
  SincScene s;
  Random rnd(14);
  for (const double t : {0.1, 0.25, 0.6, 0.9}) {
    s.set_time(t);
    const SincProfile f{0.6 * std::sin(2 * kPi * t), 4 * kPi, -0.5};
    for (int i = 0; i < 30; ++i) {
      expect_sinc_curvatures(s, f, rnd.uniform(0.05, 1.0), rnd.uniform(0, 2 * kPi), 1e-8);
    }
    // Near the centre the circumferential curvature grows like alpha kappa / r (cone tip).
    expect_sinc_curvatures(s, f, 1e-2, 0.3, 1e-7);
  }
}

TEST(SurfaceCurvature, SincRidgeHasZeroCircumferentialCurvature) {
  SincScene s;
  s.set_time(0.25);  // alpha(t) = 0.6
  const SincProfile f{0.6, 4 * kPi, -0.5};
  // The first ring extremum (f' = 0) lies between the zeros of sinc at r = 1/4 and r = 1/2.
  double lo = 0.26, hi = 0.49;
  ASSERT_LT(f.d1(lo) * f.d1(hi), 0.0);
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f.d1(lo) * f.d1(mid) <= 0 ? hi : lo) = mid;
  }
  const double ridge = 0.5 * (lo + hi);
  for (const double phi : {0.0, 1.0, 2.5, 4.0}) {
    const PrincipalCurvatures c = s.curvatures(sinc_uv(ridge, phi));
    // A trough of the (negative) ring: f'' > 0, so it bends towards the upward normal, radial
    // curvature -f'' < 0; around the ring 0.
    EXPECT_NEAR(c.k1, 0.0, 1e-8);
    EXPECT_NEAR(c.k2, -f.d2(ridge), 1e-8);
    EXPECT_NEAR(std::abs(c.dir1.dot(Vec3(-std::sin(phi), 0, std::cos(phi)))), 1.0, 1e-9);
  }
}

// With kappa = 0 the profile is smooth at the centre (f'(0) = 0) and both curvatures there are
// -f''(0) = -alpha(t) beta^2 sinc''(0) = alpha(t) beta^2 / 3 (a dome under the upward normal).
TEST(SurfaceCurvature, SincCentreWithoutDecayIsUmbilic) {
  SincScene s;
  s.set_parameter("kappa", 0.0);
  s.set_time(0.25);
  const PrincipalCurvatures c = s.curvatures(Vec2::Zero());
  const double expected = 0.6 * std::pow(4 * kPi, 2) / 3;
  EXPECT_NEAR(c.k1, expected, 1e-9);
  EXPECT_NEAR(c.k2, expected, 1e-9);
  EXPECT_LE((c.normal - Vec3::UnitY()).norm(), 1e-15);
}

TEST(SurfaceCurvature, TwistRestFaceIsFlat) {
  TwistScene s;  // t = 0: no twist
  // Middle of the +y face: the cross-section leaves its tangent like z^4 and the side leaves
  // its tangent like x^8, so both curvatures vanish there exactly.
  const PrincipalCurvatures c = s.curvatures(Vec3(0, 0.4, 0));
  EXPECT_NEAR(c.k1, 0.0, 1e-12);
  EXPECT_NEAR(c.k2, 0.0, 1e-12);
  EXPECT_LE((c.normal - Vec3::UnitY()).norm(), 1e-15);
  // Off centre along x the side y = r (1 - (x/h)^8)^(1/8) curves by about 7 r x^6 / h^8.
  const double x = 0.3, y = 0.4 * std::pow(1 - std::pow(x / 1.5, 8), 0.125);
  const PrincipalCurvatures d = s.curvatures(Vec3(x, y, 0));
  EXPECT_NEAR(d.k2, 0.0, 1e-12);
  EXPECT_NEAR(d.k1, 0.0, 1e-3);
  EXPECT_GE(d.k1, 0.0);
}

// Twisted at rate tau, the flat face through (0, r, 0) becomes the ruled surface
// S(x, w) = (x, r cos(tau x) - w sin(tau x), r sin(tau x) + w cos(tau x)); at (0, 0) its first
// form is [[1 + r^2 tau^2, r tau], [r tau, 1]] and its second (outward normal +y, sign of
// surface.h) [[r tau^2, tau], [tau, 0]], so K = -tau^2, H = -r tau^2 / 2 and
// k = -r tau^2 / 2 +- tau sqrt(1 + r^2 tau^2 / 4).
TEST(SurfaceCurvature, TwistedFaceMatchesRuledSurface) {
  TwistScene s;
  const double r = 0.4;
  for (const double t : {0.2, 0.5, 1.0}) {
    s.set_time(t);
    const double tau = t * 3 * kPi / (2 * 1.5);
    const double mean = -r * tau * tau / 2, root = tau * std::sqrt(1 + r * r * tau * tau / 4);
    const PrincipalCurvatures c = s.curvatures(Vec3(0, r, 0));
    EXPECT_NEAR(c.k1, mean + root, 1e-9) << "t=" << t;
    EXPECT_NEAR(c.k2, mean - root, 1e-9) << "t=" << t;
    EXPECT_LE((c.normal - Vec3::UnitY()).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace dynamesh
