// Analytic derivatives of every scene against fourth-order finite differences of its values,
// computed here from value() / position() only; and the interface's finite-difference defaults
// against closed forms on test surfaces that only provide values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/surface/scenes/capsule_bend_scene.h"
#include "core/surface/scenes/sinc_scene.h"
#include "core/surface/scenes/sphere_scene.h"
#include "core/surface/scenes/twist_scene.h"
#include "test_surface_support.h"

namespace dynamesh {
namespace {

using testing::fd4_gradient;
using testing::fd4_hessian;
using testing::Random;

constexpr int kSamples = 200;

// Checks value_gradient() and hessian() of `s` at p against differences of s.value(): the
// gradient with step h / 10 (truncation h^4 f^(5) dominates near the twist's axis), the Hessian
// with step h (rounding eps / h^2 dominates).
void expect_derivatives_match(const ImplicitSurface& s, const Vec3& p, double h) {
  const auto f = [&s](const Vec3& x) { return s.value(x); };
  Vec3 g;
  const double v = s.value_gradient(p, g);
  EXPECT_NEAR(v, s.value(p), 1e-14 * (1.0 + std::abs(v)));
  const Vec3 g_fd = fd4_gradient(f, p, 0.1 * h);
  EXPECT_LE((g - g_fd).norm(), 1e-8 * (1.0 + g.norm()))
      << s.name() << " t=" << s.time() << " p=" << p.transpose() << "\n g=" << g.transpose()
      << "\n fd=" << g_fd.transpose();
  const Mat3 H = s.hessian(p);
  const Mat3 H_fd = fd4_hessian(f, p, h);
  EXPECT_LE((H - H_fd).norm(), 1e-5 * (1.0 + H.norm()))
      << s.name() << " t=" << s.time() << " p=" << p.transpose() << "\nH=\n"
      << H << "\nfd=\n"
      << H_fd;
  // The combined jet (what curvatures() uses) is the same function to rounding (the twist's
  // bar computes its jet's gradient by another arithmetic path): the gradient the projection
  // sees and the one the smoothing sees do not drift apart.
  Vec3 g_jet;
  Mat3 H_jet;
  EXPECT_NEAR(s.value_gradient_hessian(p, g_jet, H_jet), v, 1e-15 * (1.0 + std::abs(v)));
  EXPECT_LE((g_jet - g).norm(), 1e-14 * (1.0 + g.norm())) << s.name();
  EXPECT_LE((H_jet - H).norm(), 1e-15 * (1.0 + H.norm())) << s.name();
}

TEST(SurfaceDerivatives, SphereGradientAndHessianMatchFiniteDifferences) {
  SphereScene s;
  Random rnd(1);
  for (int i = 0; i < kSamples; ++i) {
    s.set_time(rnd.uniform(0.0, 1.0));
    const double R = s.radius();
    Vec3 p;
    do p = rnd.in_box(Vec3::Constant(-1.5 * R), Vec3::Constant(1.5 * R));
    while (p.norm() < 0.2 * R);
    expect_derivatives_match(s, p, 1e-3 * R);
  }
}

TEST(SurfaceDerivatives, CapsuleBendGradientAndHessianMatchFiniteDifferences) {
  CapsuleBendScene s;
  const double h = 1.5, r = 0.4;
  Random rnd(2);
  for (int i = 0; i < kSamples; ++i) {
    s.set_time(rnd.uniform(0.0, 1.0));
    // Sample in rest space, away from the axis segment (no derivative) and from the circles
    // where cylinder meets caps (the Hessian jumps there): the stencil must not cross them.
    Vec3 q;
    do q = rnd.in_box(Vec3(-h - 2 * r, -2 * r, -2 * r), Vec3(h + 2 * r, 2 * r, 2 * r));
    while (std::abs(std::abs(q.x()) - h) < 0.02 || Vec2(q.y(), q.z()).norm() < 0.05);
    expect_derivatives_match(s, s.bend().to_world(q), 1e-3);
  }
}

TEST(SurfaceDerivatives, TwistGradientAndHessianMatchFiniteDifferences) {
  TwistScene s;
  const double h = 1.5, r = 0.4;
  Random rnd(3);
  for (int i = 0; i < kSamples; ++i) {
    s.set_time(rnd.uniform(0.0, 1.0));
    // Away from the x axis, where the cross-section's norm has a cone point.
    Vec3 q;
    do q = rnd.in_box(Vec3(-1.3 * h, -1.5 * r, -1.5 * r), Vec3(1.3 * h, 1.5 * r, 1.5 * r));
    while (Vec2(q.y(), q.z()).norm() < 0.05);
    expect_derivatives_match(s, s.twist().to_world(q), 1e-3);
  }
}

TEST(SurfaceDerivatives, TwistWithOtherExponentsMatchesFiniteDifferences) {
  TwistScene s;
  s.set_parameter("p", 2.5);
  s.set_parameter("s", 3.0);
  s.set_parameter("turns", -2.0);
  Random rnd(4);
  for (int i = 0; i < kSamples; ++i) {
    s.set_time(rnd.uniform(0.0, 1.0));
    Vec3 q;
    do q = rnd.in_box(Vec3(-2.0, -0.6, -0.6), Vec3(2.0, 0.6, 0.6));
    while (Vec2(q.y(), q.z()).norm() < 0.05 || std::abs(q.y()) < 0.01 || std::abs(q.z()) < 0.01);
    expect_derivatives_match(s, s.twist().to_world(q), 1e-3);
  }
}

TEST(SurfaceDerivatives, SincDerivativesMatchFiniteDifferences) {
  SincScene s;
  Random rnd(5);
  const double h = 1e-3;
  for (int i = 0; i < kSamples; ++i) {
    s.set_time(rnd.uniform(0.0, 1.0));
    Vec2 uv;
    do uv = Vec2(rnd.uniform(-1, 1), rnd.uniform(-1, 1));
    while (uv.norm() < 0.05);  // the cone tip at the centre (sinc_scene.h)
    const ParametricDerivatives d = s.derivatives(uv);
    // Differences of position() along u and v, embedded as functions of (u, v, 0).
    const auto component = [&s](int k) {
      return [&s, k](const Vec3& x) { return s.position(Vec2(x.x(), x.y()))(k); };
    };
    const Vec3 x(uv.x(), uv.y(), 0.0);
    EXPECT_LE((d.s - s.position(uv)).norm(), 1e-15);
    for (int k = 0; k < 3; ++k) {
      const Vec3 g = fd4_gradient(component(k), x, h);
      const Mat3 H = fd4_hessian(component(k), x, h);
      const double scale = 1.0 + std::abs(d.suu(k)) + std::abs(d.svv(k));
      EXPECT_NEAR(d.su(k), g(0), 1e-8 * scale) << "uv=" << uv.transpose();
      EXPECT_NEAR(d.sv(k), g(1), 1e-8 * scale) << "uv=" << uv.transpose();
      EXPECT_NEAR(d.suu(k), H(0, 0), 1e-5 * scale) << "uv=" << uv.transpose();
      EXPECT_NEAR(d.suv(k), H(0, 1), 1e-5 * scale) << "uv=" << uv.transpose();
      EXPECT_NEAR(d.svv(k), H(1, 1), 1e-5 * scale) << "uv=" << uv.transpose();
    }
  }
}

// ---- the interface's defaults, on surfaces that only give values ---------------------------

// Ellipsoid (x/a)^2 + (y/b)^2 + (z/c)^2 - 1: gradient 2 (x/a^2, y/b^2, z/c^2), Hessian
// diag(2/a^2, 2/b^2, 2/c^2).
class ValueOnlyEllipsoid final : public ImplicitSurface {
 public:
  Vec3 axes{1.0, 0.7, 0.4};
  std::string name() const override { return "ellipsoid"; }
  Box3 bounds() const override { return Box3{-axes, axes}; }
  Mesh48 base_mesh() const override { return {}; }
  double value(const Vec3& p) const override { return p.cwiseQuotient(axes).squaredNorm() - 1.0; }
};

TEST(SurfaceDefaults, ImplicitFiniteDifferencesMatchClosedForms) {
  ValueOnlyEllipsoid e;
  Random rnd(6);
  const Vec3 inv2 = e.axes.cwiseProduct(e.axes).cwiseInverse();
  for (int i = 0; i < 50; ++i) {
    const Vec3 p = rnd.in_box(-1.5 * e.axes, 1.5 * e.axes);
    Vec3 g;
    EXPECT_DOUBLE_EQ(e.value_gradient(p, g), e.value(p));
    EXPECT_LE((g - 2.0 * p.cwiseProduct(inv2)).norm(), 1e-8);
    const Mat3 H = e.hessian(p);
    EXPECT_LE((H - Mat3(2.0 * inv2.asDiagonal())).norm(), 1e-5);
  }
}

// Torus of radii R (centre circle) and a (tube), outward normal; only position() is given.
class ValueOnlyTorus final : public ParametricSurface {
 public:
  double R = 1.0, a = 0.3;
  std::string name() const override { return "torus"; }
  Box3 bounds() const override { return Box3{-Vec3(R + a, R + a, a), Vec3(R + a, R + a, a)}; }
  Mesh48 base_mesh() const override { return {}; }
  ParameterDomain domain() const override {
    return {Vec2::Zero(), Vec2::Constant(2.0 * std::numbers::pi), true, true};
  }
  Vec3 position(const Vec2& uv) const override {
    const double w = R + a * std::cos(uv.y());
    return {w * std::cos(uv.x()), w * std::sin(uv.x()), a * std::sin(uv.y())};
  }
};

TEST(SurfaceDefaults, ParametricFiniteDifferencesMatchClosedForms) {
  ValueOnlyTorus t;
  Random rnd(7);
  for (int i = 0; i < 50; ++i) {
    const double u = rnd.uniform(0, 6.28), v = rnd.uniform(0, 6.28);
    const double cu = std::cos(u), su = std::sin(u), cv = std::cos(v), sv = std::sin(v);
    const double w = t.R + t.a * cv;
    const ParametricDerivatives d = t.derivatives(Vec2(u, v));
    EXPECT_LE((d.su - Vec3(-w * su, w * cu, 0)).norm(), 1e-9);
    EXPECT_LE((d.sv - Vec3(-t.a * sv * cu, -t.a * sv * su, t.a * cv)).norm(), 1e-9);
    EXPECT_LE((d.suu - Vec3(-w * cu, -w * su, 0)).norm(), 1e-6);
    EXPECT_LE((d.suv - Vec3(t.a * sv * su, -t.a * sv * cu, 0)).norm(), 1e-6);
    EXPECT_LE((d.svv - Vec3(-t.a * cv * cu, -t.a * cv * su, -t.a * sv)).norm(), 1e-6);
    // Outward unit normal (cos v cos u, cos v sin u, sin v).
    EXPECT_LE((t.normal(Vec2(u, v)) - Vec3(cv * cu, cv * su, sv)).norm(), 1e-9);
  }
}

}  // namespace
}  // namespace dynamesh
