// Critical points of F(., t) (issue 16, event detection): the level set F = 0 changes topology
// only where it passes a point with grad F = 0 (Morse theory), so watching the value of F at
// its critical points over time finds every merge, split and pinch from F itself. Found by grid
// bracketing (a cell whose corners' gradients change sign in all three components may hold a
// zero of grad F) and Newton's method on grad F = 0 with the exact Hessian; degenerate ones
// (singular Hessian: a circle of minima, a flat far field) are skipped, since a generic event
// happens at a non-degenerate critical point.
#pragma once

#include <functional>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/surface/surface.h"
#include "core/topology/marching_tetrahedra.h"

namespace dynamesh {

struct CriticalPoint {
  Vec3 position{Vec3::Zero()};
  double value = 0.0;  // F there
  int index = 0;       // negative eigenvalues of the Hessian: 0 minimum, 1 and 2 saddles, 3 maximum
  double curvature = 0.0;  // the Hessian's largest |eigenvalue| there
};

// Newton's method on grad F = 0 from `start`, with `evaluate` giving F, grad F and Hess F at a
// point; false when it leaves `region`, meets a singular Hessian (a degenerate point) or does
// not converge. On success `out` holds the point, F there, its Morse index and curvature.
using FieldJet = std::function<double(const Vec3& p, Vec3& gradient, Mat3& hessian)>;
bool refine_critical_point(const FieldJet& evaluate, const Vec3& start, const Box3& region,
                           double tolerance, CriticalPoint& out);

// F and grad F at every grid point (x fastest). Serial on purpose: a coarse grid of a few
// thousand points costs well under a millisecond, and an OpenMP region on busy cores cost
// 100 times that (measured 0.65 ms serial vs 66 ms with two threads on blobs).
struct GridField {
  std::vector<double> values;
  std::vector<Vec3> gradients;
};
GridField sample_field(const ImplicitSurface& surface, const ContourGrid& grid);

// Critical points inside the grid's box whose |F| is at most max_abs_value, from the field
// sampled on that grid; deterministic order (by position).
std::vector<CriticalPoint> find_critical_points(const ImplicitSurface& surface,
                                                const ContourGrid& grid, const GridField& field,
                                                double max_abs_value);

}  // namespace dynamesh
