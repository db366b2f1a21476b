#include "core/geometry/nearest_triangle.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {

// Ericson, Real-Time Collision Detection, 5.1.5.
Vec3 nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

namespace {

Box3 box_of(const std::array<Vec3, 3>& t) {
  Box3 box;
  for (const Vec3& p : t) box.extend(p);
  return box;
}

// Cells of side h over `box`, at least one along each axis.
std::array<int, 3> cells_over(const Box3& box, double h) {
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a)
    n[a] = std::max(1, static_cast<int>(std::floor((box.max[a] - box.min[a]) / h)) + 1);
  return n;
}

double cell_count(const std::array<int, 3>& n) {
  return static_cast<double>(n[0]) * n[1] * n[2];
}

}  // namespace

NearestTriangleIndex::NearestTriangleIndex(std::vector<std::array<Vec3, 3>> triangles)
    : triangles_(std::move(triangles)) {
  if (triangles_.empty()) return;
  // Cells about as large as a triangle: each is listed in a few cells, and a query near the
  // triangles finds its answer within a shell or two. At most ~8 cells per triangle, so that
  // a few large triangles over a wide box do not make the grid outgrow the list.
  double extent = 0.0;
  for (const auto& t : triangles_) {
    const Box3 b = box_of(t);
    box_.extend(b.min);
    box_.extend(b.max);
    extent += b.size().maxCoeff();
  }
  cell_size_ = std::max(extent / static_cast<double>(triangles_.size()),
                        1e-9 * std::max(box_.size().maxCoeff(), 1e-300));
  const double most = 8.0 * static_cast<double>(triangles_.size()) + 64.0;
  cells_ = cells_over(box_, cell_size_);
  while (cell_count(cells_) > most) {
    cell_size_ *= std::cbrt(cell_count(cells_) / most) * 1.01;
    cells_ = cells_over(box_, cell_size_);
  }
  // Counting sort into the cells; each cell lists its triangles in increasing index order.
  first_.assign(static_cast<std::size_t>(cell_count(cells_)) + 1, 0);
  const auto for_each_cell = [&](const std::array<Vec3, 3>& t, auto visit) {
    const Box3 b = box_of(t);
    const Cell lo = cell_of(b.min), hi = cell_of(b.max);
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) visit(cell_index({x, y, z}));
  };
  for (const auto& t : triangles_) for_each_cell(t, [&](std::size_t c) { ++first_[c + 1]; });
  for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
  listed_.resize(first_.back());
  std::vector<std::uint32_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t k = 0; k < triangles_.size(); ++k)
    for_each_cell(triangles_[k],
                  [&](std::size_t c) { listed_[next[c]++] = static_cast<std::uint32_t>(k); });
}

NearestTriangleIndex::Cell NearestTriangleIndex::cell_of(const Vec3& p) const {
  Cell c{};
  for (int a = 0; a < 3; ++a) {
    const double x = std::floor((p[a] - box_.min[a]) / cell_size_);
    c[a] = static_cast<int>(std::clamp(x, 0.0, static_cast<double>(cells_[a] - 1)));
  }
  return c;
}

std::size_t NearestTriangleIndex::cell_index(const Cell& c) const {
  return (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(cells_[1]) +
          static_cast<std::size_t>(c[1])) *
             static_cast<std::size_t>(cells_[0]) +
         static_cast<std::size_t>(c[0]);
}

void NearestTriangleIndex::visit(const Cell& c, const Vec3& p, Hit& best) const {
  const std::size_t i = cell_index(c);
  for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k) {
    const std::size_t t = listed_[k];
    const auto& [a, b, cc] = triangles_[t];
    const double d = (nearest_on_triangle(p, a, b, cc) - p).squaredNorm();
    if (d < best.squared_distance || (d == best.squared_distance && t < best.triangle))
      best = {t, d};
  }
}

NearestTriangleIndex::Hit NearestTriangleIndex::nearest(const Vec3& p,
                                                        double max_squared_distance) const {
  Hit best;
  best.squared_distance = max_squared_distance;
  if (triangles_.empty()) return best;
  const Cell home = cell_of(p);
  int last_shell = 0;
  for (int a = 0; a < 3; ++a) last_shell = std::max({last_shell, home[a], cells_[a] - 1 - home[a]});
  const auto in_grid = [&](int a, int x) { return x >= 0 && x < cells_[a]; };
  for (int k = 0; k <= last_shell; ++k) {
    // A triangle listed only in cells k or more cells away (in the largest coordinate) from
    // p's own lies at least k - 1 cells from p, even when p lies outside the grid (its cell
    // is then the nearest border cell); the rounding of cell_of is allowed for.
    const double lower = (k - 1 - 1e-6) * cell_size_;
    if (lower > 0 && lower * lower > best.squared_distance) break;
    for (int dz = -k; dz <= k; ++dz) {
      const int z = home[2] + dz;
      if (!in_grid(2, z)) continue;
      for (int dy = -k; dy <= k; ++dy) {
        const int y = home[1] + dy;
        if (!in_grid(1, y)) continue;
        // On the shell's faces in z or y every x of the row; inside them, only its two ends.
        const bool whole_row = std::abs(dz) == k || std::abs(dy) == k;
        const int step = whole_row ? 1 : std::max(2 * k, 1);
        for (int dx = -k; dx <= k; dx += step) {
          const int x = home[0] + dx;
          if (in_grid(0, x)) visit({x, y, z}, p, best);
        }
      }
    }
  }
  return best;
}

}  // namespace dynamesh
