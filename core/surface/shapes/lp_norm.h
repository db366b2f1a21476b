// The Lp norm of a plane vector, (|w0|^p + |w1|^p)^(1/p), with its gradient and Hessian: the
// building block of the twist scene's superelliptic bar (SCENES.md), which is an Ls norm of
// (Lp norm of (y, z) / r, x / h).
#pragma once

#include "core/geometry/vector_types.h"

namespace dynamesh {

struct LpNormJet {
  double value = 0.0;
  Vec2 gradient{Vec2::Zero()};
  Mat2 hessian{Mat2::Zero()};
};

// Requires p >= 2 (so that the Hessian is bounded on the axes). At w = 0 the norm is not
// differentiable: gradient and Hessian are returned as zero.
double lp_norm(const Vec2& w, double p);
LpNormJet lp_norm_jet(const Vec2& w, double p, bool with_hessian);

}  // namespace dynamesh
