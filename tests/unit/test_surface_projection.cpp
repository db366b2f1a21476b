// Newton projection (projection.h) and the error distance (surface_distance.h): projection
// lands on every implicit scene from nearby points at all times; the deformed scenes agree
// with their maps (rest points carried forward by the inverse maps derived here lie on
// F = 0); the safeguards report failure instead of returning garbage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/surface/projection.h"
#include "core/surface/scenes/capsule_bend_scene.h"
#include "core/surface/scenes/sinc_scene.h"
#include "core/surface/scenes/sphere_scene.h"
#include "core/surface/scenes/twist_scene.h"
#include "core/surface/surface_distance.h"
#include "test_surface_support.h"

namespace dynamesh {
namespace {

using testing::Random;
constexpr double kPi = std::numbers::pi;
constexpr double kH = 1.5, kR = 0.4;  // SCENES.md defaults of capsule-bend and twist

// ---- rest-shape points and the inverse maps, derived from SCENES.md ------------------------

// A point of the rest capsule: cylinder (|x| <= h) or cap, from two uniform numbers.
Vec3 rest_capsule_point(Random& rnd) {
  const double a = rnd.uniform(0, 2 * kPi);
  if (rnd.uniform(0, 1) < 0.7) return {rnd.uniform(-kH, kH), kR * std::cos(a), kR * std::sin(a)};
  const double polar = rnd.uniform(0, 0.5 * kPi), side = rnd.uniform(0, 1) < 0.5 ? -1 : 1;
  return {side * (kH + kR * std::cos(polar)), kR * std::sin(polar) * std::cos(a),
          kR * std::sin(polar) * std::sin(a)};
}

// A point of the rest Lp bar: x = h c, cross-section radius N = r (1 - |c|^s)^(1/s) and
// (y, z) = N (sgn cos a |cos a|^(2/p), sgn sin a |sin a|^(2/p)), so |y|^p + |z|^p = N^p.
Vec3 rest_bar_point(Random& rnd, double p = 4, double s = 8) {
  const double c = rnd.uniform(-1, 1), a = rnd.uniform(0, 2 * kPi);
  const double N = kR * std::pow(1 - std::pow(std::abs(c), s), 1 / s);
  const auto lp = [p](double w) { return std::copysign(std::pow(std::abs(w), 2 / p), w); };
  return {kH * c, N * lp(std::cos(a)), N * lp(std::sin(a))};
}

// Inverse of SCENES.md's bend: theta = q.x / rho0, rho = rho0 - q.y,
// p = (rho sin theta, rho0 - rho cos theta, q.z).
Vec3 bend_forward(const Vec3& q, double kappa) {
  if (kappa <= 1e-9) return q;
  const double rho0 = 1 / kappa, theta = q.x() / rho0, rho = rho0 - q.y();
  return {rho * std::sin(theta), rho0 - rho * std::cos(theta), q.z()};
}

// Inverse of SCENES.md's twist: rotate (q.y, q.z) back by -phi = tau q.x (x is unchanged).
Vec3 twist_forward(const Vec3& q, double tau) {
  const double a = tau * q.x();
  return {q.x(), std::cos(a) * q.y() - std::sin(a) * q.z(),
          std::sin(a) * q.y() + std::cos(a) * q.z()};
}

double bend_curvature(double t) {
  return kPi * t / (2 * kH);
}
double twist_rate(double t) {
  return t * 3 * kPi / (2 * kH);
}

// ---- the scenes' surfaces are their maps' images -----------------------------------------------

TEST(SurfaceMaps, BentRestCapsulePointsSatisfyF) {
  CapsuleBendScene s;
  Random rnd(21);
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    s.set_time(t);
    for (int i = 0; i < 100; ++i) {
      const Vec3 q = rest_capsule_point(rnd);
      const Vec3 p = bend_forward(q, bend_curvature(t));
      EXPECT_NEAR(s.value(p), 0.0, 1e-13) << "t=" << t << " q=" << q.transpose();
      EXPECT_LE((s.bend().to_world(q) - p).norm(), 1e-13);
      EXPECT_LE((s.bend().to_rest(p) - q).norm(), 1e-13);
    }
  }
}

TEST(SurfaceMaps, TwistedRestBarPointsSatisfyF) {
  TwistScene s;
  Random rnd(22);
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    s.set_time(t);
    for (int i = 0; i < 100; ++i) {
      const Vec3 q = rest_bar_point(rnd);
      const Vec3 p = twist_forward(q, twist_rate(t));
      EXPECT_NEAR(s.value(p), 0.0, 1e-13) << "t=" << t << " q=" << q.transpose();
      EXPECT_LE((s.twist().to_world(q) - p).norm(), 1e-13);
      EXPECT_LE((s.twist().to_rest(p) - q).norm(), 1e-13);
    }
  }
}

// A gentle bend (kappa just above SCENES.md's 1e-9 cut-off) must stay accurate: the textbook
// form rho0 - rho cancels catastrophically there.
TEST(SurfaceMaps, GentleBendIsAccurate) {
  CapsuleBendScene s;
  s.set_time(2e-9 * 2 * kH / kPi);  // kappa = 2e-9
  const Vec3 p(0.3, 0.4, 0.0);      // on the straight capsule up to O(kappa)
  EXPECT_NEAR(s.value(p), 0.0, 1e-9);
  EXPECT_LE((s.bend().to_world(s.bend().to_rest(p)) - p).norm(), 1e-15);
}

// ---- projection -------------------------------------------------------------------------------

struct Case {
  const ImplicitSurface* surface;
  std::vector<Vec3> points;  // on the surface
  double feature;            // smallest radius of curvature (or thickness) nearby
};

void expect_projects_back(const Case& c, Random& rnd) {
  const ImplicitSurface& s = *c.surface;
  for (const Vec3& on : c.points) {
    const double offset = rnd.uniform(0, 0.1 * c.feature);
    const Vec3 start = on + offset * rnd.unit_vector();
    const ProjectionResult r = project_to_surface(s, start);
    ASSERT_TRUE(r.converged) << s.name() << " t=" << s.time() << " from " << start.transpose();
    // Converged means |F| / |grad F| (the distance to first order) below 1e-10 of the scene's
    // size: |F| < 1e-10 relative to scale, whatever F's units.
    Vec3 g;
    const double f = s.value_gradient(r.point, g);
    EXPECT_LT(std::abs(f) / g.norm(), 1e-10 * s.length_scale()) << s.name() << " t=" << s.time();
    EXPECT_DOUBLE_EQ(r.residual, std::abs(s.value(r.point)));
    EXPECT_LE((r.point - start).norm(), 1.5 * offset + 1e-12) << s.name() << " t=" << s.time();
    EXPECT_LE(r.iterations, 8);
  }
}

TEST(SurfaceProjection, LandsOnSphereCapsuleBendAndTwistAtAllTimes) {
  SphereScene sphere;
  CapsuleBendScene capsule;
  TwistScene twist;
  Random rnd(23);
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    sphere.set_time(t);
    capsule.set_time(t);
    twist.set_time(t);
    Case sc{&sphere, {}, sphere.radius()}, cc{&capsule, {}, kR}, tc{&twist, {}, 0.0};
    for (int i = 0; i < 100; ++i) {
      sc.points.push_back(sphere.radius() * rnd.unit_vector());
      cc.points.push_back(bend_forward(rest_capsule_point(rnd), bend_curvature(t)));
      tc.points.push_back(twist_forward(rest_bar_point(rnd), twist_rate(t)));
    }
    // The bar's smallest radius of curvature (its rims) measured on these very points.
    double k_max = 0;
    for (const Vec3& p : tc.points) k_max = std::max(k_max, std::abs(twist.curvatures(p).k1));
    tc.feature = 1 / k_max;
    expect_projects_back(sc, rnd);
    expect_projects_back(cc, rnd);
    expect_projects_back(tc, rnd);
  }
}

TEST(SurfaceProjection, SphereTakesOneStep) {
  SphereScene s;
  const ProjectionResult r = project_to_surface(s, Vec3(0.3, -0.2, 0.9));
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LE((r.point - 0.6 * Vec3(0.3, -0.2, 0.9).normalized()).norm(), 1e-15);
}

TEST(SurfaceProjection, PointOnSurfaceTakesNoStep) {
  SphereScene s;
  const ProjectionResult r = project_to_surface(s, Vec3(0, 0, 0.6));
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.point, Vec3(0, 0, 0.6));
}

TEST(SurfaceProjection, VanishingGradientIsReportedNotGarbage) {
  SphereScene s;  // no gradient at the centre
  const ProjectionResult r = project_to_surface(s, Vec3::Zero());
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.point, Vec3::Zero());
  EXPECT_DOUBLE_EQ(r.residual, 0.6);
  EXPECT_EQ(distance_to_surface(s, Vec3::Zero()), std::numeric_limits<double>::infinity());
}

// F = |p|^2 + 1 has no zero; Newton stalls at the minimum instead of wandering off.
class NoZero final : public ImplicitSurface {
 public:
  std::string name() const override { return "no-zero"; }
  Box3 bounds() const override { return Box3{Vec3::Constant(-1), Vec3::Constant(1)}; }
  Mesh48 base_mesh() const override { return {}; }
  double value(const Vec3& p) const override { return p.squaredNorm() + 1; }
  double value_gradient(const Vec3& p, Vec3& g) const override {
    g = 2 * p;
    return value(p);
  }
};

TEST(SurfaceProjection, NoZeroIsReportedNotGarbage) {
  NoZero s;
  const ProjectionResult r = project_to_surface(s, Vec3(0.5, 0.2, -0.1));
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.point.allFinite());
  EXPECT_LE(r.point.norm(), Vec3(0.5, 0.2, -0.1).norm());
  EXPECT_GE(r.residual, 1.0);
  EXPECT_GT(distance_to_surface(s, Vec3(0.5, 0.2, -0.1)), 0.5);
}

class NotANumber final : public ImplicitSurface {
 public:
  std::string name() const override { return "nan"; }
  Box3 bounds() const override { return Box3{Vec3::Constant(-1), Vec3::Constant(1)}; }
  Mesh48 base_mesh() const override { return {}; }
  double value(const Vec3&) const override { return std::numeric_limits<double>::quiet_NaN(); }
};

TEST(SurfaceProjection, NonFiniteValueIsReportedNotGarbage) {
  NotANumber s;
  const ProjectionResult r = project_to_surface(s, Vec3(0.1, 0.2, 0.3));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.point, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(distance_to_surface(s, Vec3(0.1, 0.2, 0.3)), std::numeric_limits<double>::infinity());
}

TEST(SurfaceProjection, ParallelResultsEqualSerialOnes) {
  TwistScene s;
  s.set_time(0.8);
  Random rnd(24);
  std::vector<Vec3> starts;
  for (int i = 0; i < 4000; ++i)
    starts.push_back(twist_forward(rest_bar_point(rnd), twist_rate(0.8)) +
                     0.02 * rnd.unit_vector());
  std::vector<Vec3> serial(starts.size()), parallel(starts.size());
  for (std::size_t i = 0; i < starts.size(); ++i)
    serial[i] = project_to_surface(s, starts[i]).point;
#pragma omp parallel for
  for (int i = 0; i < static_cast<int>(starts.size()); ++i) {
    parallel[i] = project_to_surface(s, starts[i]).point;
  }
  EXPECT_EQ(serial, parallel);
}

// ---- the error distance (SCENES.md, "Error of a mesh") ------------------------------------------

TEST(SurfaceDistance, ImplicitMatchesClosedForms) {
  SphereScene sphere;
  sphere.set_time(0.5);
  CapsuleBendScene capsule;  // t = 0: F is the exact signed distance
  Random rnd(25);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p = rnd.in_box(Vec3::Constant(-3), Vec3::Constant(3));
    if (p.norm() > 0.1) {
      EXPECT_NEAR(distance_to_surface(sphere, p), std::abs(p.norm() - sphere.radius()), 1e-12);
    }
    const Vec3 q = rest_capsule_point(rnd) + 0.03 * rnd.unit_vector();
    const Vec3 c(std::clamp(q.x(), -kH, kH), 0, 0);
    EXPECT_NEAR(distance_to_surface(capsule, q), std::abs((q - c).norm() - kR), 1e-12);
  }
}

TEST(SurfaceDistance, ParametricIsDistanceToTheEvaluatedPoint) {
  SincScene s;
  s.set_time(0.25);
  const Vec2 uv(0.3, -0.2);
  const Vec3 on = s.position(uv);
  EXPECT_EQ(distance_to_surface(s, on, uv), 0.0);
  EXPECT_NEAR(distance_to_surface(s, on + Vec3(0, 0.01, 0), uv), 0.01, 1e-15);
  EXPECT_NEAR(distance_to_surface(s, on + Vec3(0.003, 0, 0.004), uv), 0.005, 1e-15);
}

}  // namespace
}  // namespace dynamesh
