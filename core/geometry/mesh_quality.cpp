#include "core/geometry/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dynamesh {
namespace {

double angle_deg(const Vec3& at, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - at, v = q - at;
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI;
}

}  // namespace

double aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (!(area > 0)) return std::numeric_limits<double>::infinity();
  const double s = 0.5 * (la + lb + lc);
  const double circumradius = la * lb * lc / (4 * area), inradius = area / s;
  return circumradius / (2 * inradius);
}

std::array<double, 2> angle_range_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double x = angle_deg(a, b, c), y = angle_deg(b, c, a), z = angle_deg(c, a, b);
  return {std::min({x, y, z}), std::max({x, y, z})};
}

bool angles_within(const Vec3& a, const Vec3& b, const Vec3& c, double min_deg, double max_deg) {
  // The cosines are correct to ~1e-15 where the triangle is not degenerate, and atan2's angles
  // to ~1e-14 degrees: outside a margin of 1e-9 in the cosine both decide alike. A degenerate
  // corner gives a NaN cosine, which fails both tests and goes the exact way.
  constexpr double kMargin = 1e-9;
  const double upper = std::cos(min_deg * M_PI / 180.0) - kMargin;  // angle > min_deg
  const double lower = std::cos(max_deg * M_PI / 180.0) + kMargin;  // angle < max_deg
  const Vec3* corner[3] = {&a, &b, &c};
  bool clear = true;
  for (int i = 0; i < 3 && clear; ++i) {
    const Vec3 u = *corner[(i + 1) % 3] - *corner[i], v = *corner[(i + 2) % 3] - *corner[i];
    const double cosine = u.dot(v) / std::sqrt(u.squaredNorm() * v.squaredNorm());
    clear = cosine < upper && cosine > lower;
  }
  if (clear) return true;
  const auto range = angle_range_deg(a, b, c);
  return !(range[0] < min_deg || range[1] > max_deg);
}

AspectDistribution aspect_distribution(const Mesh48& mesh) {
  AspectDistribution d;
  std::vector<double> ratios;
  ratios.reserve(mesh.n_faces());
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    const double r = aspect_ratio(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]));
    ratios.push_back(r);
    const auto bin = std::upper_bound(d.kEdges.begin(), d.kEdges.end(), r) - d.kEdges.begin();
    ++d.histogram[static_cast<std::size_t>(std::max<std::ptrdiff_t>(bin - 1, 0))];
  }
  d.triangles = ratios.size();
  if (ratios.empty()) return d;
  std::sort(ratios.begin(), ratios.end());
  // Nearest-rank percentile: the smallest value with at least p of the faces at or below it.
  auto percentile = [&](double p) {
    const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(ratios.size())));
    return ratios[std::clamp<std::size_t>(rank, 1, ratios.size()) - 1];
  };
  d.p50 = percentile(0.50);
  d.p90 = percentile(0.90);
  d.p99 = percentile(0.99);
  d.max = ratios.back();
  return d;
}

EdgeLengthSpread edge_length_spread(const Mesh48& mesh,
                                    const std::function<bool(const Vec3&)>& region) {
  EdgeLengthSpread s;
  s.min = std::numeric_limits<double>::infinity();
  double sum = 0, sum2 = 0;
  for (Face f : mesh.live_faces()) {
    for (int e = 0; e < 3; ++e) {
      // Each interior edge is seen from both faces: count it from the lower face id only.
      const Face other = mesh.neighbor(f, e);
      if (other.is_valid() && other.idx < f.idx) continue;
      const Vec3& a = mesh.position(mesh.vertex(f, (e + 1) % 3));
      const Vec3& b = mesh.position(mesh.vertex(f, (e + 2) % 3));
      if (!region(0.5 * (a + b))) continue;
      const double len = (a - b).norm();
      ++s.edges;
      sum += len;
      sum2 += len * len;
      s.min = std::min(s.min, len);
      s.max = std::max(s.max, len);
    }
  }
  if (s.edges == 0) return EdgeLengthSpread{};
  const auto n = static_cast<double>(s.edges);
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

MeshQuality measure_quality(const Mesh48& mesh) {
  MeshQuality q;
  q.min_angle_deg = 180.0;
  double sum_min_angle = 0, sum_aspect = 0;
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    const double angles[3] = {angle_deg(a, b, c), angle_deg(b, c, a), angle_deg(c, a, b)};
    const double lo = std::min({angles[0], angles[1], angles[2]});
    q.min_angle_deg = std::min(q.min_angle_deg, lo);
    q.max_angle_deg = std::max({q.max_angle_deg, angles[0], angles[1], angles[2]});
    sum_min_angle += lo;
    const double r = aspect_ratio(a, b, c);
    q.max_aspect = std::max(q.max_aspect, r);
    sum_aspect += r;
    ++q.triangles;
  }
  if (q.triangles) {
    q.mean_min_angle_deg = sum_min_angle / static_cast<double>(q.triangles);
    q.mean_aspect = sum_aspect / static_cast<double>(q.triangles);
  }
  q.valence_min = std::numeric_limits<int>::max();
  for (Vertex v : mesh.live_vertices()) {
    const int val = mesh.valence(v);
    q.valence_min = std::min(q.valence_min, val);
    q.valence_max = std::max(q.valence_max, val);
    if (!mesh.is_boundary(v)) ++q.valence_histogram[static_cast<std::size_t>(std::min(val, 15))];
  }
  if (mesh.n_vertices() == 0) q.valence_min = 0;
  return q;
}

}  // namespace dynamesh
