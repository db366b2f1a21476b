#include "core/adapt/workload_estimate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/io/number_text.h"

namespace dynamesh {
namespace {

double max_curvature(const PrincipalCurvatures& k) {
  return std::max(std::abs(k.k1), std::abs(k.k2));
}

WorkloadEstimate parametric_workload(const ParametricSurface& s, int n) {
  WorkloadEstimate w;
  const ParameterDomain d = s.domain();
  const Vec2 step = (d.max - d.min) / n;
  const double cell = step.x() * step.y();
  for (int j = 0; j < n && w.problem.empty(); ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 uv = d.min + Vec2((i + 0.5) * step.x(), (j + 0.5) * step.y());
      const ParametricDerivatives der = s.derivatives(uv);
      const double da = der.su.cross(der.sv).norm() * cell;
      const double k = max_curvature(s.curvatures(uv));
      if (!std::isfinite(da) || !std::isfinite(k) || !der.s.allFinite()) {
        w.problem = "the surface or its derivatives are not finite (or overflow) at (u, v) = " +
                    format_point(uv);
        break;
      }
      w.area += da;
      w.curvature += k * da;
    }
  return w;
}

// Squares of the parameter domain split in four while S at their centre or edge midpoints
// is farther than T from the bilinear interpolation of their corners (what a mesh vertex
// there would correct), counted up to `limit` leaves. The curvature integral misses what
// the grid cannot resolve (sin(1000 x) on a 48-point grid); this does not, as long as a
// square's five test points see the detail, and it stops as soon as the budget is exceeded.
double parametric_refined_cells(const ParametricSurface& s, double threshold, double limit,
                                std::string& problem) {
  const ParameterDomain d = s.domain();
  constexpr int kStart = 64;
  const Vec2 size = (d.max - d.min) / kStart;
  const double smallest = 1e-9 * std::max(size.x(), size.y());
  struct Square {
    Vec2 min, size;
  };
  std::vector<Square> stack;
  for (int j = 0; j < kStart; ++j)
    for (int i = 0; i < kStart; ++i)
      stack.push_back({d.min + Vec2(i * size.x(), j * size.y()), size});
  double leaves = 0;
  while (!stack.empty() && leaves <= limit) {
    const Square q = stack.back();
    stack.pop_back();
    const Vec3 c00 = s.position(q.min), c10 = s.position(q.min + Vec2(q.size.x(), 0)),
               c01 = s.position(q.min + Vec2(0, q.size.y())), c11 = s.position(q.min + q.size);
    const Vec2 half = 0.5 * q.size;
    double deviation = (s.position(q.min + half) - 0.25 * (c00 + c10 + c01 + c11)).norm();
    deviation =
        std::max(deviation, (s.position(q.min + Vec2(half.x(), 0)) - 0.5 * (c00 + c10)).norm());
    deviation =
        std::max(deviation, (s.position(q.min + Vec2(0, half.y())) - 0.5 * (c00 + c01)).norm());
    if (!std::isfinite(deviation) || !c11.allFinite()) {
      problem = "the surface is not finite (or overflows) near (u, v) = " + format_point(q.min);
      return leaves;
    }
    if (deviation <= threshold) {
      leaves += 1;
      continue;
    }
    if (half.x() < smallest) {
      problem =
          "the surface does not become smooth at any scale near (u, v) = " + format_point(q.min) +
          " (a jump or a singularity)";
      return leaves;
    }
    for (int k = 0; k < 4; ++k)
      stack.push_back({q.min + Vec2((k & 1) * half.x(), (k >> 1) * half.y()), half});
  }
  return leaves + static_cast<double>(stack.size());
}

// A sign change of F between a and b: a zero of F, or a jump across 0. Bisected until the
// interval is 1e-12 of the edge; a continuous F then differs by next to nothing at its ends.
bool is_jump(const ImplicitSurface& s, Vec3 a, Vec3 b, double fa, double fb) {
  const double scale = std::abs(fa) + std::abs(fb);
  for (int k = 0; k < 40; ++k) {
    const Vec3 m = 0.5 * (a + b);
    const double fm = s.value(m);
    if (!std::isfinite(fm)) return true;
    if ((fm < 0) == (fa < 0))
      a = m, fa = fm;
    else
      b = m, fb = fm;
  }
  return std::abs(fb - fa) > 1e-6 * scale;
}

WorkloadEstimate implicit_workload(const ImplicitSurface& s, int n) {
  WorkloadEstimate w;
  const Box3 box = s.bounds();
  // An odd number of points puts the box's centre and middle planes on the grid, where
  // formulas have their singular points (atan2(y, x) on the z axis, 1 / x on x = 0).
  n += 1 - n % 2;
  const Vec3 h = box.size() / (n - 1);
  auto point = [&](int i, int j, int k) { return Vec3(box.min + Vec3(i, j, k).cwiseProduct(h)); };
  std::vector<double> f(static_cast<std::size_t>(n) * n * n);
  auto at = [&](int i, int j, int k) -> double& {
    return f[(static_cast<std::size_t>(k) * n + j) * n + i];
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) at(i, j, k) = s.value(point(i, j, k));
  const double cell_area[3] = {h.y() * h.z(), h.x() * h.z(), h.x() * h.y()};
  const double k_resolved = 2.0 / h.minCoeff();
  for (int axis = 0; axis < 3 && w.problem.empty(); ++axis) {
    const int di = axis == 0, dj = axis == 1, dk = axis == 2;
    for (int k = 0; k + dk < n && w.problem.empty(); ++k)
      for (int j = 0; j + dj < n && w.problem.empty(); ++j)
        for (int i = 0; i + di < n; ++i) {
          const double fa = at(i, j, k), fb = at(i + di, j + dj, k + dk);
          if (!std::isfinite(fa) || !std::isfinite(fb)) {
            w.problem = "F is not finite at " + format_point(point(i, j, k));
            break;
          }
          if ((fa < 0) == (fb < 0)) continue;
          const Vec3 a = point(i, j, k), b = point(i + di, j + dj, k + dk);
          const Vec3 p = a + (fa / (fa - fb)) * (b - a);
          Vec3 g;
          s.value_gradient(p, g);
          const double k_point = max_curvature(s.curvatures(p));
          if (!g.allFinite() || !std::isfinite(k_point)) {
            w.problem = "the gradient or curvature of F is not finite on the surface near " +
                        format_point(p);
            break;
          }
          if (is_jump(s, a, b, fa, fb)) {
            w.problem = "F jumps across zero near " + format_point(p) +
                        " (a step or a pole, not a surface a mesh can follow)";
            break;
          }
          const Vec3 normal = g.normalized();
          const double weight = normal.cwiseAbs().sum();
          // A crossing on a critical point of F (where the level set merges, splits or
          // pinches: the torus pinch at t = 0.5) has no normal; it is one point of the
          // surface, so it adds nothing to the area.
          if (!(weight > 0)) continue;
          // Every crossing stands for cell_area / |n_axis| of the surface; summed over the
          // three axes that counts each piece (|n_x| + |n_y| + |n_z|) times.
          const double da = cell_area[axis] / weight;
          // Near a critical point of F on the surface (a merge or a pinch at its instant) the
          // level set is a cone, whose curvature ~1/r at distance r from the apex is unbounded
          // while its integral over a cell is ~h: a crossing a rounding error from the apex
          // (two torus pinches at t = 0.5, where F there is 1e-12 and not 0) read 1e10 and
          // refused the run. A grid of spacing h tells no curvature radius below h / 2 anyway.
          const double k_max = std::min(k_point, k_resolved);
          w.area += da;
          w.curvature += k_max * da;
        }
  }
  return w;
}

}  // namespace

WorkloadEstimate estimate_workload(const Surface& surface, double threshold, double density,
                                   double max_triangles, int resolution) {
  const bool parametric = surface.kind() == SurfaceKind::kParametric;
  WorkloadEstimate w =
      parametric ? parametric_workload(static_cast<const ParametricSurface&>(surface), resolution)
                 : implicit_workload(static_cast<const ImplicitSurface&>(surface), resolution);
  w.triangles = w.curvature / (2.0 * threshold);
  if (parametric && w.problem.empty()) {
    // Two triangles per square.
    const double cells = parametric_refined_cells(static_cast<const ParametricSurface&>(surface),
                                                  threshold, 0.5 * max_triangles, w.problem);
    w.triangles = std::max(w.triangles, 2.0 * cells);
  }
  w.samples = density * w.area;
  if (w.problem.empty() && !(std::isfinite(w.triangles) && std::isfinite(w.samples)))
    w.problem =
        "the surface's area or curvature overflows (area " + format_significant(w.area, 6) + ")";
  return w;
}

}  // namespace dynamesh
