#include "core/surface/scenes/blobs_scene.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/surface/parameter_table.h"
#include "core/topology/contour_base_mesh.h"

namespace dynamesh {

namespace {

using P = BlobsScene::Params;
const std::array<ParameterSpec<P>, 4> kSpecs{{
    {"tau", &P::tau, 0.05, 1.9, "iso-level: the surface is where the two Gaussians sum to tau"},
    {"s", &P::s, 0.05, 5.0, "width of each Gaussian"},
    {"a_near", &P::a_near, 0.0, 10.0, "half the distance between the centres at t = 0.5"},
    {"a_far", &P::a_far, 0.0, 10.0, "half the distance between the centres at t = 0 and 1"},
}};

}  // namespace

double BlobsScene::separation_at(const Params& p, double t) {
  const double u = 2.0 * t - 1.0;
  return p.a_near + (p.a_far - p.a_near) * u * u;
}

void BlobsScene::set_time(double t) {
  Surface::set_time(t);
  a_ = separation_at(params_, t);
}

std::vector<SurfaceParameter> BlobsScene::parameters() const {
  return describe_parameters(kSpecs, params_);
}

void BlobsScene::set_parameter(const std::string& name, double value) {
  assign_parameter(kName, kSpecs, params_, name, value);
  a_ = separation_at(params_, time());
}

Box3 BlobsScene::bounds() const {
  // SCENES.md: x in [-(a_far + 2s), a_far + 2s], y and z in [-2s, 2s]; the larger of the two
  // separations so that swapping a_near and a_far keeps the blobs inside.
  const double x = std::max(params_.a_near, params_.a_far) + 2.0 * params_.s;
  const double yz = 2.0 * params_.s;
  Box3 box;
  box.extend(Vec3(-x, -yz, -yz));
  box.extend(Vec3(x, yz, yz));
  return box;
}

Mesh48 BlobsScene::base_mesh() const {
  return make_contour_base_mesh(*this);
}

double BlobsScene::value(const Vec3& p) const {
  Vec3 g;
  return value_gradient(p, g);
}

double BlobsScene::value_gradient(const Vec3& p, Vec3& gradient) const {
  const double inv_s2 = 1.0 / (params_.s * params_.s);
  const Vec3 d1 = p - Vec3(a_, 0, 0), d2 = p - Vec3(-a_, 0, 0);
  const double e1 = std::exp(-d1.squaredNorm() * inv_s2), e2 = std::exp(-d2.squaredNorm() * inv_s2);
  gradient = 2.0 * inv_s2 * (e1 * d1 + e2 * d2);
  return params_.tau - e1 - e2;
}

Mat3 BlobsScene::hessian(const Vec3& p) const {
  const double inv_s2 = 1.0 / (params_.s * params_.s);
  Mat3 h = Mat3::Zero();
  for (const double c : {a_, -a_}) {
    const Vec3 d = p - Vec3(c, 0, 0);
    const double e = std::exp(-d.squaredNorm() * inv_s2);
    h += 2.0 * inv_s2 * e * (Mat3::Identity() - 2.0 * inv_s2 * d * d.transpose());
  }
  return h;
}

}  // namespace dynamesh
