#include "core/surface/scenes/capsule_bend_scene.h"

#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/surface/box_base_mesh.h"
#include "core/surface/parameter_table.h"

namespace dynamesh {

namespace {

using P = CapsuleBendScene::Params;
const std::array<ParameterSpec<P>, 3> kSpecs{{
    {"h", &P::h, 0.05, 20.0, "half-length of the capsule's axis segment"},
    {"r", &P::r, 0.01, 5.0, "capsule radius"},
    {"bend", &P::bend, 0.0, 2.0 * std::numbers::pi,
     "total bend angle at t = 1 in radians (Theta(t) = bend * t)"},
}};

// Empty when the capsule stays a simple (non-self-intersecting) tube up to t = 1.
std::string fold_problem(const P& p) {
  std::ostringstream out;
  if (p.bend * p.r >= 2.0 * p.h) {
    out << "bend = " << p.bend << " with h = " << p.h << ", r = " << p.r
        << " pushes the inner side through the bending axis (needs bend < 2h/r = "
        << 2.0 * p.h / p.r << "); lower bend or r, or raise h";
  } else if (p.bend * (p.h + p.r) >= 2.0 * std::numbers::pi * p.h) {
    out << "bend = " << p.bend << " with h = " << p.h << ", r = " << p.r
        << " makes the two caps meet (needs bend < 2 pi h/(h + r) = "
        << 2.0 * std::numbers::pi * p.h / (p.h + p.r) << "); lower bend or r";
  }
  return out.str();
}

}  // namespace

CapsuleBendScene::CapsuleBendScene() {
  update();
}

void CapsuleBendScene::set_time(double t) {
  Surface::set_time(t);
  update();
}

void CapsuleBendScene::update() {
  capsule_ = Capsule{params_.h, params_.r};
  bend_ = BendMap(params_.bend * time() / (2.0 * params_.h));
  scale_ = bounds().diagonal();
}

std::vector<SurfaceParameter> CapsuleBendScene::parameters() const {
  return describe_parameters(kSpecs, params_);
}

void CapsuleBendScene::set_parameter(const std::string& name, double value) {
  Params next = params_;
  assign_parameter(kName, kSpecs, next, name, value);
  const std::string problem = fold_problem(next);
  if (!problem.empty()) throw std::invalid_argument(std::string(kName) + ": " + problem);
  params_ = next;
  update();
}

Box3 CapsuleBendScene::bounds() const {
  const double h = params_.h, r = params_.r;
  Box3 box;
  if (bend_.is_identity()) {
    box.extend(Vec3(-h - r, -r, -r));
    box.extend(Vec3(h + r, r, r));
    return box;
  }
  // The bent capsule lies in the annular sector rho in [1/k - r, 1/k + r], |theta| <= k (h + r)
  // around the bending axis; p.x = rho sin(theta), p.y = 1/k - rho cos(theta). Written without
  // 1/k - 1/k cancellations.
  const double k = bend_.curvature();
  const double theta = std::min(k * (h + r), std::numbers::pi);
  const double outer = 1.0 / k + r;
  const double x = theta >= 0.5 * std::numbers::pi ? outer : outer * std::sin(theta);
  const double half = std::sin(0.5 * theta);
  const double y = 2.0 * half * half / k + r * std::abs(std::cos(theta));
  box.extend(Vec3(-x, -r, -r));
  box.extend(Vec3(x, y, r));
  return box;
}

double CapsuleBendScene::value(const Vec3& p) const {
  return capsule_.value(bend_.to_rest(p));
}

double CapsuleBendScene::value_gradient(const Vec3& p, Vec3& gradient) const {
  return mapped_value_gradient(capsule_, bend_, p, gradient);
}

Mat3 CapsuleBendScene::hessian(const Vec3& p) const {
  return mapped_hessian(capsule_, bend_, p);
}

double CapsuleBendScene::value_gradient_hessian(const Vec3& p, Vec3& gradient,
                                                Mat3& hessian) const {
  return mapped_jet(capsule_, bend_, p, gradient, hessian);
}

Mesh48 CapsuleBendScene::base_mesh() const {
  // A box of 6 x 2 x 2 quads around the rest capsule; each vertex goes to its nearest point on
  // the rest capsule (radially on the cylinder, from the cap centre on the caps) and is then
  // bent into place.
  const double h = params_.h, r = params_.r;
  Box3 rest;
  rest.extend(Vec3(-h - r, -r, -r));
  rest.extend(Vec3(h + r, r, r));
  const Capsule capsule = capsule_;
  const BendMap bend = bend_;
  return make_projected_box_mesh(*this, rest, {6, 2, 2}, [capsule, bend](const Vec3& v) {
    return bend.to_world(capsule.closest_point(v));
  });
}

}  // namespace dynamesh
