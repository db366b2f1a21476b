#include "core/surface/volume/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynamesh {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Scratch for one line: input copy and the lower envelope (parabola sites v, boundaries z).
struct LineScratch {
  std::vector<float> f;
  std::vector<std::uint32_t> feature;
  std::vector<int> v;
  std::vector<double> z;
  void resize(int n) {
    f.resize(n);
    feature.resize(n);
    v.resize(n);
    z.resize(n + 1);
  }
};

// Felzenszwalb-Huttenlocher 2012, Algorithm "DT(f)" in one dimension with sample spacing h:
// d(q) = min_p h^2 (q - p)^2 + f(p). Sites with f = inf hold no parabola and are skipped.
// With `Features`, the index carried by the minimising site goes along (feature transform).
template <bool Features>
void envelope_1d(LineScratch& s, int n, double h, float* d, std::uint32_t* feature,
                 std::size_t stride) {
  for (int q = 0; q < n; ++q) {
    s.f[q] = d[q * stride];
    if constexpr (Features) s.feature[q] = feature[q * stride];
  }
  const double h2 = h * h;
  const auto intersection = [&](int p, int q) {
    // Where the parabolas of sites p < q meet, in units of samples.
    return ((s.f[q] + h2 * q * q) - (s.f[p] + h2 * p * p)) / (2.0 * h2 * (q - p));
  };
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (s.f[q] == kInf) continue;
    double at = -std::numeric_limits<double>::infinity();
    while (k >= 0) {
      at = intersection(s.v[k], q);
      if (at > s.z[k]) break;
      --k;
      at = -std::numeric_limits<double>::infinity();
    }
    ++k;
    s.v[k] = q;
    s.z[k] = at;
    s.z[k + 1] = std::numeric_limits<double>::infinity();
  }
  if (k < 0) return;  // no site on this line: leave it at infinity
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (s.z[k + 1] < q) ++k;
    const int p = s.v[k];
    d[q * stride] = static_cast<float>(h2 * (q - p) * (q - p) + s.f[p]);
    if constexpr (Features) feature[q * stride] = s.feature[p];
  }
}

// One pass along `axis` over every line, in parallel; `nearest` is null without features.
template <bool Features>
void pass(float* squared, std::uint32_t* nearest, const VoxelGrid& grid, int axis, double h) {
  const auto& d = grid.dims;
  const std::size_t stride = axis == 0 ? 1 : axis == 1 ? d[0] : std::size_t(d[0]) * d[1];
  const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;  // the two other axes
  const auto lines = static_cast<std::ptrdiff_t>(std::size_t(d[a1]) * d[a2]);
#pragma omp parallel
  {
    LineScratch scratch;
    scratch.resize(d[axis]);
#pragma omp for schedule(static)
    for (std::ptrdiff_t line = 0; line < lines; ++line) {
      int ijk[3] = {0, 0, 0};
      ijk[a1] = static_cast<int>(line % d[a1]);
      ijk[a2] = static_cast<int>(line / d[a1]);
      const std::size_t start = grid.index(ijk[0], ijk[1], ijk[2]);
      envelope_1d<Features>(scratch, d[axis], h, squared + start,
                            Features ? nearest + start : nullptr, stride);
    }
  }
}

Vec3 voxel_of(const VoxelGrid& grid, std::uint32_t index) {
  const std::size_t nx = grid.dims[0], nxy = nx * grid.dims[1];
  return Vec3(double(index % nx), double((index / nx) % grid.dims[1]), double(index / nxy));
}

}  // namespace

DistanceTransformResult distance_transform(const MaskVolume& mask, std::uint8_t target,
                                           const ProgressCallback& progress,
                                           std::string_view stage) {
  const std::size_t n = mask.values.size();
  DistanceTransformResult r;
  reserve_huge(r.squared, n);
  reserve_huge(r.nearest, n);
  r.squared.assign(n, kInf);
  r.nearest.assign(n, kNone);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(n); ++v) {
    if (mask.values[v] == target) {
      r.squared[v] = 0.0f;
      r.nearest[v] = static_cast<std::uint32_t>(v);
    }
  }
  const Vec3 spacing = mask.grid.spacing();
  for (int axis = 0; axis < 3; ++axis) {
    pass<true>(r.squared.data(), r.nearest.data(), mask.grid, axis, spacing[axis]);
    report(progress, stage, (axis + 1) / 3.0);
  }
  return r;
}

void squared_distance_transform(const MaskVolume& mask, std::uint8_t target,
                                std::vector<float>& squared) {
  const auto n = static_cast<std::ptrdiff_t>(mask.values.size());
  reserve_huge(squared, mask.values.size());
  squared.resize(mask.values.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t v = 0; v < n; ++v) squared[v] = mask.values[v] == target ? 0.0f : kInf;
  const Vec3 spacing = mask.grid.spacing();
  for (int axis = 0; axis < 3; ++axis)
    pass<false>(squared.data(), nullptr, mask.grid, axis, spacing[axis]);
}

ScalarVolume signed_distance(const MaskVolume& mask, const ProgressCallback& progress) {
  const ProgressCallback half = [&](std::string_view stage, double f) {
    report(progress, stage, 0.5 * f);
  };
  const ProgressCallback second = [&](std::string_view stage, double f) {
    report(progress, stage, 0.5 + 0.5 * f);
  };
  const DistanceTransformResult to_inside = distance_transform(mask, 1, half);
  const DistanceTransformResult to_outside = distance_transform(mask, 0, second);
  if (mask.values.empty() || to_inside.nearest[0] == kNone || to_outside.nearest[0] == kNone) {
    throw std::invalid_argument("signed distance of an empty or full mask");
  }
  ScalarVolume result(mask.grid, 0.0f);
  const VoxelGrid& grid = mask.grid;
  const auto n = static_cast<std::ptrdiff_t>(mask.values.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t v = 0; v < n; ++v) {
    const bool inside = mask.values[v] != 0;
    const std::uint32_t f = inside ? to_outside.nearest[v] : to_inside.nearest[v];
    const Vec3 u = voxel_of(grid, static_cast<std::uint32_t>(v)) - voxel_of(grid, f);
    // The segment f -> x leaves f's cell (|s_i| <= 1/2) at lambda = min_i 1/(2 |u_i|).
    const double lambda = 0.5 / u.cwiseAbs().maxCoeff();
    const double distance = (1.0 - lambda) * (grid.linear * u).norm();
    result.values[v] = static_cast<float>(inside ? -distance : distance);
  }
  return result;
}

namespace {

// Where the level set passes near an interface voxel: the Newton foot point and the unit
// normal there (world coordinates).
struct Foot {
  Vec3 point;
  Vec3 normal;
};

Foot foot_point(const ScalarVolume& field, const Mat3& to_voxel_t, int i, int j, int k,
                double level) {
  const auto& d = field.grid.dims;
  const auto diff = [&](int axis) {
    int lo[3] = {i, j, k}, hi[3] = {i, j, k};
    lo[axis] = std::max(lo[axis] - 1, 0);
    hi[axis] = std::min(hi[axis] + 1, d[axis] - 1);
    const double span = hi[axis] - lo[axis];
    return span > 0 ? (field.at(hi[0], hi[1], hi[2]) - field.at(lo[0], lo[1], lo[2])) / span : 0.0;
  };
  const Vec3 g = to_voxel_t * Vec3(diff(0), diff(1), diff(2));
  const Vec3 x = field.grid.to_world(Vec3(i, j, k));
  const double g2 = g.squaredNorm();
  if (g2 < 1e-30) return {x, Vec3::Zero()};
  return {x - ((field.at(i, j, k) - level) / g2) * g, g / std::sqrt(g2)};
}

}  // namespace

ScalarVolume signed_distance_to_level(const ScalarVolume& field, double level,
                                      const ProgressCallback& progress) {
  const VoxelGrid& grid = field.grid;
  const auto& d = grid.dims;
  MaskVolume interface(grid, 0);
  const Mat3 to_voxel_t = grid.linear.inverse().transpose();
  // Pass 1: mark the interface voxels (a face neighbour on the other side of the level).
#pragma omp parallel for schedule(static)
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) {
        const bool in = field.at(i, j, k) > level;
        const auto differs = [&](int a, int b, int c) {
          return grid.contains(a, b, c) && (field.at(a, b, c) > level) != in;
        };
        if (differs(i - 1, j, k) || differs(i + 1, j, k) || differs(i, j - 1, k) ||
            differs(i, j + 1, k) || differs(i, j, k - 1) || differs(i, j, k + 1)) {
          interface.values[grid.index(i, j, k)] = 1;
        }
      }
  // Pass 2: foot points of the interface voxels only, addressed through a slot table.
  std::vector<std::uint32_t> slot;
  reserve_huge(slot, field.values.size());
  slot.assign(field.values.size(), kNone);
  std::vector<Foot> feet;
  for (std::size_t v = 0; v < field.values.size(); ++v) {
    if (!interface.values[v]) continue;
    slot[v] = static_cast<std::uint32_t>(feet.size());
    const Vec3 ijk = voxel_of(grid, static_cast<std::uint32_t>(v));
    feet.push_back(foot_point(field, to_voxel_t, int(ijk[0]), int(ijk[1]), int(ijk[2]), level));
  }
  if (feet.empty()) {
    throw std::invalid_argument("signed distance: no voxel pair straddles the level " +
                                std::to_string(level));
  }
  const DistanceTransformResult nearest = distance_transform(interface, 1, progress);
  ScalarVolume result(grid, 0.0f);
  const auto n = static_cast<std::ptrdiff_t>(field.values.size());
  const double band = 4.0 * grid.spacing().maxCoeff();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t v = 0; v < n; ++v) {
    const Vec3 x = grid.to_world(voxel_of(grid, static_cast<std::uint32_t>(v)));
    const Foot* best = &feet[slot[nearest.nearest[v]]];
    double distance = (x - best->point).norm();
    if (distance < band) {
      // Near the level set the nearest interface voxel need not carry the nearest foot
      // point: try those around it, then measure to the best one's tangent plane, which is
      // exact to first order where the Euclidean distance to a sample of the surface is not
      // (sqrt(delta^2 + s^2) for a foot at lateral offset s).
      const Vec3 f = voxel_of(grid, nearest.nearest[v]);
      for (int c = 0; c < 27; ++c) {
        const int i = int(f[0]) + c % 3 - 1, j = int(f[1]) + (c / 3) % 3 - 1,
                  k = int(f[2]) + c / 9 - 1;
        if (!grid.contains(i, j, k)) continue;
        const std::uint32_t w = slot[grid.index(i, j, k)];
        if (w == kNone) continue;
        const double dw = (x - feet[w].point).norm();
        if (dw < distance) {
          distance = dw;
          best = &feet[w];
        }
      }
      if (best->normal != Vec3::Zero()) distance = std::abs((x - best->point).dot(best->normal));
    }
    result.values[v] = static_cast<float>(field.values[v] > level ? -distance : distance);
  }
  return result;
}

}  // namespace dynamesh
