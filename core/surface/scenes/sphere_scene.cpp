#include "core/surface/scenes/sphere_scene.h"

#include <array>
#include <cmath>

#include "core/surface/box_base_mesh.h"
#include "core/surface/parameter_table.h"

namespace dynamesh {

namespace {

using P = SphereScene::Params;
const std::array<ParameterSpec<P>, 3> kSpecs{{
    {"R0", &P::R0, 0.01, 100.0, "radius at t = 0"},
    {"R1", &P::R1, 0.01, 100.0, "radius at t = 1 (R(t) = R0 (R1/R0)^t)"},
    {"L", &P::L, 1e-3, 10.0, "target edge length on the half x >= 0"},
}};

}  // namespace

SphereScene::SphereScene() {
  update();
}

void SphereScene::set_time(double t) {
  Surface::set_time(t);
  update();
}

void SphereScene::update() {
  radius_ = params_.R0 * std::pow(params_.R1 / params_.R0, time());
}

std::vector<SurfaceParameter> SphereScene::parameters() const {
  return describe_parameters(kSpecs, params_);
}

void SphereScene::set_parameter(const std::string& name, double value) {
  assign_parameter(kName, kSpecs, params_, name, value);
  update();
}

Box3 SphereScene::bounds() const {
  Box3 box;
  box.extend(Vec3::Constant(-radius_));
  box.extend(Vec3::Constant(radius_));
  return box;
}

double SphereScene::value_gradient(const Vec3& p, Vec3& gradient) const {
  const double d = p.norm();
  // The centre has no gradient; zero makes projection stop there instead of dividing by zero.
  gradient = d > 0.0 ? Vec3(p / d) : Vec3::Zero();
  return d - radius_;
}

Mat3 SphereScene::hessian(const Vec3& p) const {
  const double d = p.norm();
  if (!(d > 0.0)) return Mat3::Zero();
  const Vec3 n = p / d;
  return (Mat3::Identity() - n * n.transpose()) / d;
}

Mesh48 SphereScene::base_mesh() const {
  // A cube of 2 x 2 quads per face, pushed radially onto the sphere: 26 vertices, valences 3
  // (cube corners) and 4.
  const double r = radius_;
  return make_projected_box_mesh(*this, bounds(), {2, 2, 2},
                                 [r](const Vec3& v) { return Vec3(r * v.normalized()); });
}

}  // namespace dynamesh
