// The typed surfaces' derivatives (from their formulas' tapes, on jets) against closed forms
// written out here by hand: the sphere, the torus, and the formulas of assets/examples; the
// bench's sinc against the compiled sinc scene. Central differences, the old way, miss these
// tolerances by orders of magnitude (errors ~1e-8 for gradients, ~1e-5 for Hessians), so the
// tests fail if a surface falls back to them.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <numbers>
#include <string>

#include "core/surface/scene_registry.h"
#include "core/surface/scenes/sinc_scene.h"
#include "test_surface_support.h"

namespace dynamesh {
namespace {

using testing::Random;

constexpr double kPi = std::numbers::pi;

std::unique_ptr<Surface> expr(const TextOptions& options) {
  return make_scene("expr", {}, options);
}

double relative_error(const Mat3& got, const Mat3& expected) {
  return (got - expected).norm() / (1.0 + expected.norm());
}

double relative_error(const Vec3& got, const Vec3& expected) {
  return (got - expected).norm() / (1.0 + expected.norm());
}

struct Closed {
  double value;
  Vec3 gradient;
  Mat3 hessian;
};

// Checks value, value_gradient and hessian of the implicit surface `s` at points in `box`
// (kept where `usable` says the closed form is smooth) at several times.
template <class Form, class Usable>
void expect_implicit(Surface& surface, const Box3& box, const Form& closed, const Usable& usable,
                     std::initializer_list<double> times = {0.0, 0.15, 0.3, 0.8}) {
  auto& s = dynamic_cast<ImplicitSurface&>(surface);
  Random rnd(7);
  int checked = 0;
  for (const double t : times) {
    s.set_time(t);
    for (int i = 0; i < 60; ++i) {
      const Vec3 p = rnd.in_box(box.min, box.max);
      if (!usable(p)) continue;
      ++checked;
      const Closed c = closed(p, t);
      Vec3 g;
      const double v = s.value_gradient(p, g);
      EXPECT_NEAR(v, c.value, 1e-14 * (1 + std::abs(c.value))) << p.transpose() << " t=" << t;
      EXPECT_NEAR(s.value(p), v, 1e-15 * (1 + std::abs(v)));
      EXPECT_LE(relative_error(g, c.gradient), 1e-13)
          << p.transpose() << " t=" << t << "\n got " << g.transpose() << "\n expected "
          << c.gradient.transpose();
      EXPECT_LE(relative_error(s.hessian(p), c.hessian), 1e-12)
          << p.transpose() << " t=" << t << "\n got\n"
          << s.hessian(p) << "\n expected\n"
          << c.hessian;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(ExprDerivatives, SphereMatchesClosedForm) {
  auto s = expr({{"implicit", "sqrt(x^2+y^2+z^2) - 0.6*(9/0.6)^t"}, {"bounds", "-2,-2,-2,2,2,2"}});
  expect_implicit(
      *s, Box3{Vec3::Constant(-2), Vec3::Constant(2)},
      [](const Vec3& p, double t) {
        const double r = p.norm();
        const Vec3 n = p / r;
        return Closed{r - 0.6 * std::pow(9 / 0.6, t), n,
                      (Mat3::Identity() - n * n.transpose()) / r};
      },
      [](const Vec3& p) { return p.norm() > 0.05; },
      {0.0, 0.1, 0.2, 0.3});  // (the radius outgrows the box after t = 0.3)
}

TEST(ExprDerivatives, BreathingEllipsoidMatchesClosedForm) {
  auto s =
      expr({{"implicit", "(x/(1+0.3*sin(2*pi*t)))^2 + (y/0.7)^2 + (z/(0.5-0.2*sin(2*pi*t)))^2 - 1"},
            {"bounds", "-1.5,-1,-1,1.5,1,1"}});
  expect_implicit(
      *s, Box3{Vec3(-1.5, -1, -1), Vec3(1.5, 1, 1)},
      [](const Vec3& p, double t) {
        const double a = 1 + 0.3 * std::sin(2 * kPi * t), b = 0.7,
                     c = 0.5 - 0.2 * std::sin(2 * kPi * t);
        const Vec3 k(1 / (a * a), 1 / (b * b), 1 / (c * c));
        return Closed{(p.array().square() * k.array()).sum() - 1, Vec3(2 * k.array() * p.array()),
                      Mat3(Vec3(2 * k).asDiagonal())};
      },
      [](const Vec3&) { return true; });
}

TEST(ExprDerivatives, TorusMatchesClosedForm) {
  // F = sqrt((rho - 1)^2 + z^2) - R(t), rho = sqrt(x^2 + y^2); with q = rho - 1 and
  // d = sqrt(q^2 + z^2): F_rho = q/d, F_z = z/d, F_rho,rho = z^2/d^3, F_zz = q^2/d^3,
  // F_rho,z = -q z/d^3, and rho's own derivatives x/rho, y/rho, (I - m m^T)/rho in the plane.
  const std::string torus_obj = std::string(DYNAMESH_SOURCE_DIR) + "/assets/examples/torus.obj";
  auto s = expr({{"implicit", "sqrt((sqrt(x^2+y^2)-1)^2+z^2) - 0.4 - 0.1*sin(2*pi*t)"},
                 {"bounds", "-1.8,-1.8,-0.8,1.8,1.8,0.8"},
                 {"base-mesh", torus_obj}});
  expect_implicit(
      *s, Box3{Vec3(-1.8, -1.8, -0.8), Vec3(1.8, 1.8, 0.8)},
      [](const Vec3& p, double t) {
        const double rho = std::hypot(p.x(), p.y()), q = rho - 1, z = p.z();
        const double d = std::sqrt(q * q + z * z), d3 = d * d * d;
        const double Fr = q / d, Fz = z / d, Frr = z * z / d3, Fzz = q * q / d3, Frz = -q * z / d3;
        const Vec3 m(p.x() / rho, p.y() / rho, 0.0);  // d rho / d p
        Mat3 rho_hess = Mat3::Zero();                 // (I - m m^T) / rho in the xy plane
        rho_hess.topLeftCorner<2, 2>() =
            (Mat2::Identity() - m.head<2>() * m.head<2>().transpose()) / rho;
        const Vec3 ez = Vec3::UnitZ();
        Closed c;
        c.value = d - 0.4 - 0.1 * std::sin(2 * kPi * t);
        c.gradient = Fr * m + Fz * ez;
        c.hessian = Frr * m * m.transpose() + Fr * rho_hess + Fzz * ez * ez.transpose() +
                    Frz * (m * ez.transpose() + ez * m.transpose());
        return c;
      },
      [](const Vec3& p) {
        const double rho = std::hypot(p.x(), p.y());
        return rho > 0.05 && std::hypot(rho - 1, p.z()) > 0.05;
      });
}

TEST(ExprDerivatives, PulsingBlobMatchesClosedForm) {
  // F = r - 0.8 (1 + 0.3 s(t) S), S = sin 4x sin 4y sin 4z.
  auto s = expr(
      {{"implicit", "sqrt(x^2+y^2+z^2) - 0.8*(1 + 0.3*sin(2*pi*t)*sin(4*x)*sin(4*y)*sin(4*z))"},
       {"bounds", "-1.5,-1.5,-1.5,1.5,1.5,1.5"}});
  expect_implicit(
      *s, Box3{Vec3::Constant(-1.5), Vec3::Constant(1.5)},
      [](const Vec3& p, double t) {
        const double r = p.norm(), a = 0.8 * 0.3 * std::sin(2 * kPi * t);
        const Vec3 n = p / r;
        const Vec3 sn(std::sin(4 * p.x()), std::sin(4 * p.y()), std::sin(4 * p.z()));
        const Vec3 cs(std::cos(4 * p.x()), std::cos(4 * p.y()), std::cos(4 * p.z()));
        const double S = sn.prod();
        const Vec3 dS(4 * cs.x() * sn.y() * sn.z(), 4 * sn.x() * cs.y() * sn.z(),
                      4 * sn.x() * sn.y() * cs.z());
        Mat3 HS;
        HS.diagonal().setConstant(-16 * S);
        HS(0, 1) = HS(1, 0) = 16 * cs.x() * cs.y() * sn.z();
        HS(0, 2) = HS(2, 0) = 16 * cs.x() * sn.y() * cs.z();
        HS(1, 2) = HS(2, 1) = 16 * sn.x() * cs.y() * cs.z();
        return Closed{r - 0.8 * (1 + 0.3 * std::sin(2 * kPi * t) * S), n - a * dS,
                      (Mat3::Identity() - n * n.transpose()) / r - a * HS};
      },
      [](const Vec3& p) { return p.norm() > 0.05; });
}

// Checks a parametric surface's derivatives() against closed forms over its domain.
template <class Form>
void expect_parametric(Surface& surface, const Form& closed) {
  auto& s = dynamic_cast<ParametricSurface&>(surface);
  const ParameterDomain domain = s.domain();
  Random rnd(9);
  for (const double t : {0.0, 0.15, 0.3, 0.8}) {
    s.set_time(t);
    for (int i = 0; i < 60; ++i) {
      const Vec2 uv(rnd.uniform(domain.min.x(), domain.max.x()),
                    rnd.uniform(domain.min.y(), domain.max.y()));
      const ParametricDerivatives got = s.derivatives(uv), want = closed(uv, t);
      EXPECT_LE(relative_error(got.s, want.s), 1e-15) << uv.transpose() << " t=" << t;
      EXPECT_LE(relative_error(s.position(uv), want.s), 1e-15);
      EXPECT_LE(relative_error(got.su, want.su), 1e-13) << uv.transpose() << " t=" << t;
      EXPECT_LE(relative_error(got.sv, want.sv), 1e-13) << uv.transpose() << " t=" << t;
      EXPECT_LE(relative_error(got.suu, want.suu), 1e-12) << uv.transpose() << " t=" << t;
      EXPECT_LE(relative_error(got.suv, want.suv), 1e-12) << uv.transpose() << " t=" << t;
      EXPECT_LE(relative_error(got.svv, want.svv), 1e-12) << uv.transpose() << " t=" << t;
    }
  }
}

TEST(ExprDerivatives, TravellingWaveMatchesClosedForm) {
  // y = A e(x) sin(phi), e = exp(-x^2), phi = 2 pi (1.5 x + z - 2 t).
  auto s =
      expr({{"height", "0.12*sin(2*pi*(1.5*x + z - 2*t))*exp(-x^2)"}, {"domain", "-1,1,-1,1"}});
  expect_parametric(*s, [](const Vec2& uv, double t) {
    const double z = uv.x(), x = uv.y(), A = 0.12;  // (u, v) = (z, x): normal up
    const double phi = 2 * kPi * (1.5 * x + z - 2 * t), sp = std::sin(phi), cp = std::cos(phi);
    const double e = std::exp(-x * x), e1 = -2 * x * e, e2 = (4 * x * x - 2) * e;
    const double px = 3 * kPi, pz = 2 * kPi;
    ParametricDerivatives d;
    d.s = Vec3(x, A * e * sp, z);
    d.su = Vec3(0, A * e * cp * pz, 1);
    d.sv = Vec3(1, A * (e1 * sp + e * cp * px), 0);
    d.suu = Vec3(0, -A * e * sp * pz * pz, 0);
    d.suv = Vec3(0, A * (e1 * cp * pz - e * sp * px * pz), 0);
    d.svv = Vec3(0, A * (e2 * sp + 2 * e1 * cp * px - e * sp * px * px), 0);
    return d;
  });
}

TEST(ExprDerivatives, WobblingTubeMatchesClosedForm) {
  // S = (sin u w, v, cos u w), w = 1 + a cos 3v, a = 0.3 sin 2 pi t: Su x Sv points outwards.
  auto s =
      expr({{"parametric",
             "sin(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v)); v; cos(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v))"},
            {"domain", "0,2*pi,-1,1"},
            {"periodic", "u"}});
  expect_parametric(*s, [](const Vec2& uv, double t) {
    const double u = uv.x(), v = uv.y(), a = 0.3 * std::sin(2 * kPi * t);
    const double w = 1 + a * std::cos(3 * v), wv = -3 * a * std::sin(3 * v),
                 wvv = -9 * a * std::cos(3 * v);
    const double c = std::cos(u), sn = std::sin(u);
    ParametricDerivatives d;
    d.s = Vec3(sn * w, v, c * w);
    d.su = Vec3(c * w, 0, -sn * w);
    d.sv = Vec3(sn * wv, 1, c * wv);
    d.suu = Vec3(-sn * w, 0, -c * w);
    d.suv = Vec3(c * wv, 0, -sn * wv);
    d.svv = Vec3(sn * wvv, 0, c * wvv);
    return d;
  });
}

TEST(ExprDerivatives, SincMatchesTheCompiledScene) {
  // The benchmark's formula of the sinc scene, against the scene's closed forms, away from the
  // origin (where the typed quotient sin(4 pi r)/(4 pi r) loses digits and the scene switches
  // to a series).
  SincScene sinc;
  auto typed = expr({{"height",
                      "0.6*sin(2*pi*t)*(sqrt(x^2+z^2) < 1e-9 ? 1 : "
                      "sin(4*pi*sqrt(x^2+z^2))/(4*pi*sqrt(x^2+z^2)))*exp(-0.5*sqrt(x^2+z^2))"}});
  const auto& h = dynamic_cast<const ParametricSurface&>(*typed);
  Random rnd(11);
  for (const double t : {0.1, 0.3, 0.7}) {
    sinc.set_time(t);
    typed->set_time(t);
    for (int i = 0; i < 100; ++i) {
      const Vec2 uv(rnd.uniform(-1, 1), rnd.uniform(-1, 1));
      if (uv.norm() < 0.1) continue;
      const ParametricDerivatives a = h.derivatives(uv), b = sinc.derivatives(uv);
      EXPECT_LE(relative_error(a.s, b.s), 1e-14);
      EXPECT_LE(relative_error(a.su, b.su), 1e-12) << uv.transpose();
      EXPECT_LE(relative_error(a.sv, b.sv), 1e-12) << uv.transpose();
      EXPECT_LE(relative_error(a.suu, b.suu), 1e-11) << uv.transpose();
      EXPECT_LE(relative_error(a.suv, b.suv), 1e-11) << uv.transpose();
      EXPECT_LE(relative_error(a.svv, b.svv), 1e-11) << uv.transpose();
    }
  }
  // At the origin the formula's branch is the constant 1 and exp(-0.5 r) has a cone tip:
  // finite derivatives, no NaN, and the gradient of a symmetric function, zero.
  const ParametricDerivatives o = h.derivatives(Vec2::Zero());
  EXPECT_TRUE(o.su.allFinite() && o.sv.allFinite() && o.suu.allFinite() && o.suv.allFinite() &&
              o.svv.allFinite());
  EXPECT_EQ(o.su.y(), 0.0);
  EXPECT_EQ(o.sv.y(), 0.0);
}

}  // namespace
}  // namespace dynamesh
