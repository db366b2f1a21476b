// Newton projection onto an implicit surface F = 0 (SCENES.md, "Error of a mesh"; the normal
// correction of de Goes et al. 2006, Section 3.3):
//   x <- x - F(x) grad F(x) / |grad F(x)|^2
// until the first-order distance |F| / |grad F| is below tolerance * length_scale(). Each step is
// safeguarded: a vanishing or non-finite gradient stops the iteration (not converged), a step
// longer than the scene is shortened, and a step that makes |F| grow is halved until it does not.
// The result always says whether it converged; it is never garbage silently.
#pragma once

#include <cstdint>

#include "core/geometry/vector_types.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct ProjectionOptions {
  // Relative to the surface's length_scale(); 1e-10 is SCENES.md's |F| < 1e-10 for a signed
  // distance F on a scene of size about 1, and scale-free otherwise.
  double tolerance = 1e-10;
  int max_iterations = 64;
  int max_halvings = 30;
  // Longest single step, in length units; 0: the surface's length_scale(). Where |grad F| is
  // small (near a medial axis, between nearly touching sheets) a Newton step can jump across
  // the scene; callers that know the local scale (a split edge's length) bound it here.
  double max_step = 0.0;
  // Beyond this length (0: never) a Newton step is not trusted to the linear model: next to a
  // critical point of F, where |grad F| -> 0, -F grad F / |grad F|^2 grows without bound while
  // the surface moves a finite distance (a new neck widens, a tip recedes, as sqrt(2 |F| /
  // |lambda|)). There the step is the quadratic model's (newton_step_bounded()). Callers set
  // it to the local edge length: within it a long step cannot turn a face over.
  double quadratic_beyond = 0.0;
};

// The safeguarded Newton step from x (F = f, grad F = g there, g nonzero): -f g / |g|^2, or,
// when that is longer than options.quadratic_beyond, the nearest root of F's quadratic model
// along -sign(f) grad F, else (no root that way) along the Hessian's eigenvector whose eigenvalue
// has the sign that brings F to zero (sqrt(2 |f| / |lambda|)), else the Newton step shortened
// to quadratic_beyond. Never longer than the Newton step.
Vec3 newton_step_bounded(const ImplicitSurface& surface, const Vec3& x, double f, const Vec3& g,
                         const ProjectionOptions& options);

struct ProjectionResult {
  Vec3 point{Vec3::Zero()};  // the last iterate (the start point if no step was taken)
  bool converged = false;
  int iterations = 0;     // Newton steps taken
  double residual = 0.0;  // |F(point)|
  // F and grad F at `point`, the projection's last evaluation: a caller that needs them where
  // the vertex ends (ErrorPredictor::begin_step) need not evaluate them again.
  double value = 0.0;
  Vec3 gradient{Vec3::Zero()};
};

// F and grad F evaluated at `point` while the surface was in the state its owner numbered
// `epoch` (0: none).
struct PointEvaluation {
  Vec3 point{Vec3::Zero()};
  double value = 0.0;
  Vec3 gradient{Vec3::Zero()};
  std::uint64_t epoch = 0;
};

// Thread-safe (only const surface evaluations) and allocation-free.
ProjectionResult project_to_surface(const ImplicitSurface& surface, const Vec3& x,
                                    const ProjectionOptions& options = {});

// A start point with F and grad F already evaluated there (at the surface's current time).
struct ProjectionStart {
  Vec3 point{Vec3::Zero()};
  double value = 0.0;
  Vec3 gradient{Vec3::Zero()};
};
// The same iteration from a start whose evaluation is known: the result is bit for bit the
// one project_to_surface(surface, start.point) gives, one evaluation cheaper.
ProjectionResult project_to_surface(const ImplicitSurface& surface, const ProjectionStart& start,
                                    const ProjectionOptions& options = {});

}  // namespace dynamesh
