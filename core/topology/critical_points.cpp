#include "core/topology/critical_points.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>

namespace dynamesh {

namespace {

bool changes_sign(const std::size_t corner[8], const std::vector<Vec3>& gradients, int axis) {
  bool negative = false, positive = false;
  for (int c = 0; c < 8; ++c) {
    negative = negative || gradients[corner[c]][axis] <= 0;
    positive = positive || gradients[corner[c]][axis] >= 0;
  }
  return negative && positive;
}

}  // namespace

bool refine_critical_point(const FieldJet& evaluate, const Vec3& start, const Box3& region,
                           double tolerance, CriticalPoint& out) {
  Vec3 x = start, g;
  Mat3 h;
  for (int iteration = 0; iteration < 30; ++iteration) {
    evaluate(x, g, h);
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(h);
    const Vec3 lambda = eigen.eigenvalues();
    const double scale = lambda.cwiseAbs().maxCoeff();
    if (!(scale > 0) || lambda.cwiseAbs().minCoeff() < 1e-6 * scale) return false;  // degenerate
    const Vec3 step =
        eigen.eigenvectors() * (eigen.eigenvectors().transpose() * g).cwiseQuotient(lambda);
    x -= step;
    if (!region.contains(x) || !x.allFinite()) return false;
    if (step.norm() < tolerance) {
      out.position = x;
      out.value = evaluate(x, g, h);
      const Vec3 at = h.selfadjointView<Eigen::Lower>().eigenvalues();
      out.index = static_cast<int>((at.array() < 0).count());
      out.curvature = at.cwiseAbs().maxCoeff();
      return true;
    }
  }
  return false;
}

GridField sample_field(const ImplicitSurface& surface, const ContourGrid& grid) {
  const auto [nx, ny, nz] = grid.cells;
  const std::int64_t n = static_cast<std::int64_t>(nx + 1) * (ny + 1) * (nz + 1);
  GridField field;
  field.values.resize(static_cast<std::size_t>(n));
  field.gradients.resize(static_cast<std::size_t>(n));
  for (std::int64_t q = 0; q < n; ++q) {
    const int i = static_cast<int>(q % (nx + 1)), j = static_cast<int>(q / (nx + 1) % (ny + 1));
    const int k = static_cast<int>(q / (static_cast<std::int64_t>(nx + 1) * (ny + 1)));
    const auto s = static_cast<std::size_t>(q);
    field.values[s] = surface.value_gradient(grid.point(i, j, k), field.gradients[s]);
  }
  return field;
}

std::vector<CriticalPoint> find_critical_points(const ImplicitSurface& surface,
                                                const ContourGrid& grid, const GridField& field,
                                                double max_abs_value) {
  // Plain ints, not a structured binding: clang before 16 cannot capture bindings in a lambda.
  const int nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  auto id = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * (ny + 1) + j) * (nx + 1) + i;
  };
  const Vec3 h = grid.spacing();
  const double tolerance = 1e-9 * h.norm();
  const FieldJet jet = [&](const Vec3& p, Vec3& gradient, Mat3& hessian) {
    return surface.value_gradient_hessian(p, gradient, hessian);
  };
  std::vector<CriticalPoint> found;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::size_t corner[8];
        for (int c = 0; c < 8; ++c) corner[c] = id(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
        const auto& g = field.gradients;
        if (!changes_sign(corner, g, 0) || !changes_sign(corner, g, 1) ||
            !changes_sign(corner, g, 2))
          continue;
        // Where the cell's values could reach: no critical point with |F| <= max_abs_value
        // lies in a cell whose corners are all far above it (F varies little where grad F is
        // small, and the corners bound the gradient's size over the cell).
        double lo = HUGE_VAL, grad = 0;
        for (const std::size_t c : corner) {
          lo = std::min(lo, std::abs(field.values[c]));
          grad = std::max(grad, g[c].norm());
        }
        if (lo > max_abs_value + grad * h.norm()) continue;
        const Vec3 centre = grid.point(i, j, k) + 0.5 * h;
        Box3 region;
        region.extend(Vec3(centre - 1.5 * h));
        region.extend(Vec3(centre + 1.5 * h));
        CriticalPoint cp;
        if (!refine_critical_point(jet, centre, region, tolerance, cp)) continue;
        if (std::abs(cp.value) > max_abs_value || !grid.box.contains(cp.position)) continue;
        bool duplicate = false;
        for (const CriticalPoint& other : found)
          duplicate = duplicate || (other.position - cp.position).norm() < 0.25 * h.minCoeff();
        if (!duplicate) found.push_back(cp);
      }
  std::sort(found.begin(), found.end(), [](const CriticalPoint& a, const CriticalPoint& b) {
    return std::make_tuple(a.position.x(), a.position.y(), a.position.z()) <
           std::make_tuple(b.position.x(), b.position.y(), b.position.z());
  });
  return found;
}

}  // namespace dynamesh
