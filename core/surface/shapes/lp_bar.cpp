#include "core/surface/shapes/lp_bar.h"

#include "core/surface/shapes/lp_norm.h"

namespace dynamesh {

double LpBar::value(const Vec3& q) const {
  const double section = lp_norm(Vec2(q.y(), q.z()), p) / radius;
  return lp_norm(Vec2(section, q.x() / half_length), s) - 1.0;
}

double LpBar::value_gradient(const Vec3& q, Vec3& gradient) const {
  const LpNormJet section = lp_norm_jet(Vec2(q.y(), q.z()), p, false);
  const LpNormJet outer = lp_norm_jet(Vec2(section.value / radius, q.x() / half_length), s, false);
  gradient << outer.gradient(1) / half_length, outer.gradient(0) / radius * section.gradient;
  return outer.value - 1.0;
}

ScalarJet LpBar::jet(const Vec3& q) const {
  // Chain rule through w = (|(y, z)|_p / r, x / h): Hess F0 = sum_ij d2N_s/dw_i dw_j grad w_i
  // grad w_j^T + dN_s/dw_0 Hess w_0 (w_1 is linear).
  const LpNormJet section = lp_norm_jet(Vec2(q.y(), q.z()), p, true);
  const LpNormJet outer = lp_norm_jet(Vec2(section.value / radius, q.x() / half_length), s, true);
  Vec3 grad_w0, grad_w1;
  grad_w0 << 0.0, section.gradient / radius;
  grad_w1 << 1.0 / half_length, 0.0, 0.0;
  ScalarJet j;
  j.value = outer.value - 1.0;
  j.gradient = outer.gradient(0) * grad_w0 + outer.gradient(1) * grad_w1;
  const Mat3 cross = grad_w0 * grad_w1.transpose();
  j.hessian = outer.hessian(0, 0) * grad_w0 * grad_w0.transpose() +
              outer.hessian(0, 1) * (cross + cross.transpose()) +
              outer.hessian(1, 1) * grad_w1 * grad_w1.transpose();
  j.hessian.bottomRightCorner<2, 2>() += outer.gradient(0) / radius * section.hessian;
  return j;
}

Box3 LpBar::bounds() const {
  Box3 box;
  box.extend(Vec3(-half_length, -radius, -radius));
  box.extend(Vec3(half_length, radius, radius));
  return box;
}

}  // namespace dynamesh
