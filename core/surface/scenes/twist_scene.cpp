#include "core/surface/scenes/twist_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/surface/box_base_mesh.h"
#include "core/surface/parameter_table.h"

namespace dynamesh {

namespace {

using P = TwistScene::Params;
// Ranges: what a default run (T = 0.008, 50 steps) adapts within its budgets in seconds (issue
// 15: every value in a documented range works). The twist rate turns pi / h grows as the bar
// shortens, and the shear of the cross-section's rim with r: h = 0.5, r = 1, p = 16 and
// turns = 3 take 2-11 s of CPU and at most 19k triangles; h = 0.2, h = 20, r = 2, p = 32 or
// turns = 4 ran for minutes on this machine (the smoothing's fold repair under shear).
const std::array<ParameterSpec<P>, 5> kSpecs{{
    {"h", &P::h, 0.5, 5.0, "half-length of the bar along x"},
    {"r", &P::r, 0.01, 1.0, "half-width of the cross-section |y|^p + |z|^p = r^p"},
    {"p", &P::p, 2.0, 16.0, "exponent of the cross-section (2: round, large: square)"},
    {"s", &P::s, 2.0, 64.0, "exponent joining sides and ends (large: flat ends, sharp rims)"},
    {"turns", &P::turns, -3.0, 3.0, "turns of the twist over the whole bar at t = 1"},
}};

}  // namespace

TwistScene::TwistScene() {
  update();
}

void TwistScene::set_time(double t) {
  Surface::set_time(t);
  update();
}

void TwistScene::update() {
  bar_ = LpBar{params_.h, params_.r, params_.p, params_.s};
  twist_ = TwistMap(time() * params_.turns * std::numbers::pi / params_.h);
  scale_ = bounds().diagonal();
}

std::vector<SurfaceParameter> TwistScene::parameters() const {
  return describe_parameters(kSpecs, params_);
}

void TwistScene::set_parameter(const std::string& name, double value) {
  assign_parameter(kName, kSpecs, params_, name, value);
  update();
}

Box3 TwistScene::bounds() const {
  if (twist_.rate() == 0.0) return bar_.bounds();
  // A turned cross-section stays within the disc through the corners of the Lp ball, of
  // radius r 2^(1/2 - 1/p) (p >= 2).
  const double reach = params_.r * std::pow(2.0, 0.5 - 1.0 / params_.p);
  Box3 box;
  box.extend(Vec3(-params_.h, -reach, -reach));
  box.extend(Vec3(params_.h, reach, reach));
  return box;
}

double TwistScene::value(const Vec3& p) const {
  return bar_.value(twist_.to_rest(p));
}

double TwistScene::value_gradient(const Vec3& p, Vec3& gradient) const {
  return mapped_value_gradient(bar_, twist_, p, gradient);
}

Mat3 TwistScene::hessian(const Vec3& p) const {
  return mapped_hessian(bar_, twist_, p);
}

double TwistScene::value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const {
  return mapped_jet(bar_, twist_, p, gradient, hessian);
}

Mesh48 TwistScene::base_mesh() const {
  // The rest bar's bounding box with 2 x 2 quads across and at least 6 along the bar, more when
  // twisted so that neighbouring cross-sections turn by at most 30 degrees (a quad of the
  // section spans 90). F0 + 1 is a norm (homogeneous of degree one), so the ray from the centre
  // through a box vertex v meets the rest surface exactly at v / (F0(v) + 1); the twist then
  // carries that point into place.
  const double turn = std::abs(twist_.rate()) * 2.0 * params_.h;
  const int along = std::max(6, static_cast<int>(std::ceil(turn / (std::numbers::pi / 6.0))));
  const LpBar bar = bar_;
  const TwistMap twist = twist_;
  return make_projected_box_mesh(*this, bar_.bounds(), {along, 2, 2}, [bar, twist](const Vec3& v) {
    return twist.to_world(v / (bar.value(v) + 1.0));
  });
}

}  // namespace dynamesh
