#include "core/surface/scenes/sinc_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/mesh/base_meshes.h"
#include "core/surface/parameter_table.h"

namespace dynamesh {

namespace {

using P = SincScene::Params;
const std::array<ParameterSpec<P>, 3> kSpecs{{
    {"alpha", &P::alpha, -5.0, 5.0, "amplitude: alpha(t) = alpha sin(2 pi t)"},
    {"beta", &P::beta, 0.0, 100.0, "radial frequency of sinc(beta r)"},
    {"kappa", &P::kappa, -10.0, 10.0, "radial decay rate of exp(kappa r)"},
}};

// sinc(x) = sin(x)/x and its first two derivatives. The closed forms lose relative accuracy
// like eps/x^2 near 0, where the Taylor series (error below 1e-13 for |x| < 0.1) takes over.
struct Sinc {
  double value, d1, d2;
};

Sinc sinc(double x) {
  const double x2 = x * x;
  if (std::abs(x) < 0.1) {
    return {1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))),
            x * (-1.0 / 3.0 + x2 * (1.0 / 30.0 - x2 * (1.0 / 840.0 - x2 / 45360.0))),
            -1.0 / 3.0 + x2 * (1.0 / 10.0 - x2 * (1.0 / 168.0 - x2 / 6480.0))};
  }
  const double s = std::sin(x), c = std::cos(x);
  return {s / x, (x * c - s) / x2, ((2.0 - x2) * s - 2.0 * x * c) / (x2 * x)};
}

}  // namespace

SincScene::SincScene() {
  update();
}

void SincScene::set_time(double t) {
  Surface::set_time(t);
  update();
}

void SincScene::update() {
  amplitude_ = params_.alpha * std::sin(2.0 * std::numbers::pi * time());
}

std::vector<SurfaceParameter> SincScene::parameters() const {
  return describe_parameters(kSpecs, params_);
}

void SincScene::set_parameter(const std::string& name, double value) {
  assign_parameter(kName, kSpecs, params_, name, value);
  update();
}

ParameterDomain SincScene::domain() const {
  ParameterDomain d;
  d.min = Vec2(-1.0, -1.0);
  d.max = Vec2(1.0, 1.0);
  return d;
}

Box3 SincScene::bounds() const {
  // |sinc| <= 1 and exp(kappa r) <= max(1, exp(kappa sqrt(2))) on the square.
  const double y = std::abs(amplitude_) * std::max(1.0, std::exp(params_.kappa * std::sqrt(2.0)));
  Box3 box;
  box.extend(Vec3(-1.0, -y, -1.0));
  box.extend(Vec3(1.0, y, 1.0));
  return box;
}

SincScene::Profile SincScene::profile(double r) const {
  // f = A g(beta r) e(r) with g = sinc, e = exp(kappa r):
  //   f' = A e (beta g' + kappa g),  f'' = A e (beta^2 g'' + 2 beta kappa g' + kappa^2 g).
  const double b = params_.beta, k = params_.kappa;
  const Sinc g = sinc(b * r);
  const double ae = amplitude_ * std::exp(k * r);
  return {ae * g.value, ae * (b * g.d1 + k * g.value),
          ae * (b * b * g.d2 + 2.0 * b * k * g.d1 + k * k * g.value)};
}

Vec3 SincScene::position(const Vec2& uv) const {
  const double r = uv.norm();
  const double y = amplitude_ * sinc(params_.beta * r).value * std::exp(params_.kappa * r);
  return {uv.y(), y, uv.x()};  // (u, v) = (z, x): see sinc_scene.h
}

ParametricDerivatives SincScene::derivatives(const Vec2& uv) const {
  // y(u, v) = f(|uv|): grad y = f' uv/r, Hess y = f'' n n^T + (f'/r)(I - n n^T), n = uv/r,
  // all in (u, v); S = (v, y, u) puts them on the y axis of Su = (0, y_u, 1), Sv = (1, y_v, 0).
  const double r = uv.norm();
  const Profile f = profile(r);
  Vec2 grad = Vec2::Zero();
  Mat2 hess = f.d2f * Mat2::Identity();
  if (r > 0.0) {
    const Vec2 n = uv / r;
    const Mat2 nn = n * n.transpose();
    grad = f.df * n;
    hess = f.d2f * nn + (f.df / r) * (Mat2::Identity() - nn);
  }
  ParametricDerivatives d;
  d.s = Vec3(uv.y(), f.f, uv.x());
  d.su = Vec3(0.0, grad.x(), 1.0);
  d.sv = Vec3(1.0, grad.y(), 0.0);
  d.suu = Vec3(0.0, hess(0, 0), 0.0);
  d.suv = Vec3(0.0, hess(0, 1), 0.0);
  d.svv = Vec3(0.0, hess(1, 1), 0.0);
  return d;
}

Mesh48 SincScene::base_mesh() const {
  // 8 x 8 quads over the parameter square; every vertex evaluated at its (u, v).
  Mesh48 mesh = make_grid_mesh(8, 8, domain().min, domain().max);
  for (const Vertex v : mesh.live_vertices()) mesh.position(v) = position(mesh.uv(v));
  return mesh;
}

}  // namespace dynamesh
