#include "core/topology/fixed_critical_points.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <tuple>
#include <unordered_map>

namespace dynamesh {
namespace {

// Points bucketed by cells of side `cell` (world units): the neighbours of a point within
// `cell` lie in the 27 buckets around its own.
class PointBuckets {
 public:
  PointBuckets(const std::vector<CriticalPoint>& points, double cell)
      : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i)
      buckets_[key(cell_of(points[i].position))].push_back(i);
  }
  template <class Visit>
  void for_each_near(const Vec3& p, Visit&& visit) const {
    const std::array<std::int64_t, 3> c = cell_of(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = buckets_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == buckets_.end()) continue;
          for (const std::size_t j : it->second)
            if ((points_[j].position - p).norm() < cell_) visit(j);
        }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)),
            static_cast<std::int64_t>(std::floor(p.y() / cell_)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0] & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(c[2] & 0x1fffff);
  }
  const std::vector<CriticalPoint>& points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> buckets_;
};

// Removes points that Newton reached from two neighbouring cells (closer than `merge`).
std::vector<CriticalPoint> without_duplicates(std::vector<CriticalPoint> found, double merge) {
  std::sort(found.begin(), found.end(), [](const CriticalPoint& a, const CriticalPoint& b) {
    return std::make_tuple(a.value, a.position.x(), a.position.y(), a.position.z()) <
           std::make_tuple(b.value, b.position.x(), b.position.y(), b.position.z());
  });
  const PointBuckets near(found, merge);
  std::vector<char> dropped(found.size(), 0);
  std::vector<CriticalPoint> out;
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (dropped[i]) continue;
    out.push_back(found[i]);
    near.for_each_near(found[i].position, [&](std::size_t j) {
      if (j > i && found[j].index == found[i].index) dropped[j] = 1;
    });
  }
  return out;
}

}  // namespace

FixedCriticalPoints find_fixed_critical_points(const CubicBSplineField& field,
                                               const FixedCriticalPointsOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ScalarVolume& c = field.coefficients();
  const VoxelGrid& grid = c.grid;
  const int nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  const Vec3 spacing = grid.spacing();
  const double diagonal = spacing.norm();
  // The coefficients are the field up to the B-spline's light smoothing; a cell is looked at
  // when its nodes' values come within two diagonals of the band (|grad G| is about 1).
  const double lo = options.min_value - options.min_persistence - 2 * diagonal;
  const double hi = options.max_value + options.min_persistence + 2 * diagonal;
  const auto at = [&](int i, int j, int k) { return static_cast<double>(c.at(i, j, k)); };
  // Central differences in voxel coordinates: grad_u G = 0 exactly where grad_p G = 0.
  const auto gradient_u = [&](int i, int j, int k) {
    return Vec3(at(std::min(i + 1, nx - 1), j, k) - at(std::max(i - 1, 0), j, k),
                at(i, std::min(j + 1, ny - 1), k) - at(i, std::max(j - 1, 0), k),
                at(i, j, std::min(k + 1, nz - 1)) - at(i, j, std::max(k - 1, 0)));
  };
  const FieldJet jet = [&](const Vec3& p, Vec3& g, Mat3& h) {
    return field.value_gradient_hessian(p, g, h);
  };
  std::vector<CriticalPoint> found;
  FixedCriticalPoints out;
  for (int k = 1; k + 2 < nz; ++k) {
    if (k % 16 == 0) report(options.progress, "critical points", static_cast<double>(k) / nz);
    for (int j = 1; j + 2 < ny; ++j)
      for (int i = 1; i + 2 < nx; ++i) {
        double vmin = HUGE_VAL, vmax = -HUGE_VAL;
        for (int q = 0; q < 8; ++q) {
          const double v = at(i + (q & 1), j + (q >> 1 & 1), k + (q >> 2 & 1));
          vmin = std::min(vmin, v);
          vmax = std::max(vmax, v);
        }
        if (vmax < lo || vmin > hi) continue;
        std::array<bool, 3> negative{false, false, false}, positive{false, false, false};
        for (int q = 0; q < 8; ++q) {
          const Vec3 g = gradient_u(i + (q & 1), j + (q >> 1 & 1), k + (q >> 2 & 1));
          for (int a = 0; a < 3; ++a) {
            negative[a] = negative[a] || g[a] <= 0;
            positive[a] = positive[a] || g[a] >= 0;
          }
        }
        if (!(negative[0] && positive[0] && negative[1] && positive[1] && negative[2] &&
              positive[2]))
          continue;
        // From the cell's centre, within the cell and one more around it.
        Box3 region;
        for (int q = 0; q < 8; ++q)
          region.extend(grid.to_world(
              Vec3(i - 1 + 3 * (q & 1), j - 1 + 3 * (q >> 1 & 1), k - 1 + 3 * (q >> 2 & 1))));
        CriticalPoint cp;
        if (!refine_critical_point(jet, grid.to_world(Vec3(i + 0.5, j + 0.5, k + 0.5)), region,
                                   1e-9 * diagonal, cp))
          continue;
        if (cp.value < options.min_value - options.min_persistence ||
            cp.value > options.max_value + options.min_persistence)
          continue;
        found.push_back(cp);
      }
  }
  out.points = without_duplicates(std::move(found), 0.25 * spacing.minCoeff());
  out.candidates = out.points.size();
  out.spacing = spacing.maxCoeff();
  report(options.progress, "critical points", 1.0);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

FixedCriticalPoints cancel_shallow_pairs(const FixedCriticalPoints& all,
                                         const FixedCriticalPointsOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<CriticalPoint>& found = all.points;
  FixedCriticalPoints out;
  out.candidates = found.size();
  out.spacing = all.spacing;
  // Pairs of adjacent index, cancelled smallest persistence first.
  const double radius =
      options.pair_radius > 0 ? options.pair_radius : 3.0 * std::sqrt(3.0) * all.spacing;
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  if (options.min_persistence > 0 && !found.empty()) {
    const PointBuckets near(found, radius);
    for (std::size_t a = 0; a < found.size(); ++a)
      near.for_each_near(found[a].position, [&](std::size_t b) {
        const double persistence = std::abs(found[a].value - found[b].value);
        if (b > a && std::abs(found[a].index - found[b].index) == 1 &&
            persistence < options.min_persistence)
          pairs.emplace_back(persistence, a, b);
      });
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> gone(found.size(), 0);
  for (const auto& [persistence, a, b] : pairs) {
    if (gone[a] || gone[b]) continue;
    gone[a] = gone[b] = 1;
    out.cancelled += 2;
  }
  // `found` is sorted by value: so are the points kept.
  for (std::size_t a = 0; a < found.size(); ++a)
    if (!gone[a] && found[a].value >= options.min_value && found[a].value <= options.max_value)
      out.points.push_back(found[a]);
  out.seconds =
      all.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace dynamesh
