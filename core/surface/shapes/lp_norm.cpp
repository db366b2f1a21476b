// With n = |w|_p and u_i = |w_i| / n (so that sum u_i^p = 1):
//   d n / d w_i          = sign(w_i) u_i^(p-1)  =: g_i
//   d^2 n / d w_i d w_j  = (p - 1) / n * (delta_ij u_i^(p-2) - g_i g_j).
// Evaluated by factoring out the larger component m: n = m (1 + t^p)^(1/p) with t = min/m,
// which cannot overflow and needs two pow() calls; u_max^p = 1/(1+t^p), u_min^p = t^p/(1+t^p).
#include "core/surface/shapes/lp_norm.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {

double lp_norm(const Vec2& w, double p) {
  const double a = std::abs(w(0)), b = std::abs(w(1));
  const double m = std::max(a, b);
  if (!(m > 0.0)) return 0.0;
  const double t = std::min(a, b) / m;
  return m * std::pow(1.0 + std::pow(t, p), 1.0 / p);
}

LpNormJet lp_norm_jet(const Vec2& w, double p, bool with_hessian) {
  LpNormJet jet;
  const double abs_w[2] = {std::abs(w(0)), std::abs(w(1))};
  const int big = abs_w[0] >= abs_w[1] ? 0 : 1;
  const double m = abs_w[big];
  if (!(m > 0.0)) return jet;
  const double tp = std::pow(abs_w[1 - big] / m, p);
  const double sum = 1.0 + tp;
  jet.value = m * std::pow(sum, 1.0 / p);
  double u_pm1[2], u_pm2[2];  // u_i^(p-1), u_i^(p-2)
  const double u_p[2] = {big == 0 ? 1.0 / sum : tp / sum, big == 1 ? 1.0 / sum : tp / sum};
  for (int i = 0; i < 2; ++i) {
    const double u = abs_w[i] / jet.value;
    if (u > 0.0) {
      u_pm1[i] = u_p[i] / u;
      u_pm2[i] = u_pm1[i] / u;
    } else {  // 0^(p-1) = 0 for p > 1; 0^(p-2) is 1 for p = 2, else 0
      u_pm1[i] = 0.0;
      u_pm2[i] = p == 2.0 ? 1.0 : 0.0;
    }
    jet.gradient(i) = std::copysign(u_pm1[i], w(i));
  }
  if (!with_hessian) return jet;
  const double c = (p - 1.0) / jet.value;
  jet.hessian = -c * jet.gradient * jet.gradient.transpose();
  jet.hessian(0, 0) += c * u_pm2[0];
  jet.hessian(1, 1) += c * u_pm2[1];
  return jet;
}

}  // namespace dynamesh
