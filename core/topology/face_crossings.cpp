#include "core/topology/face_crossings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace dynamesh {

namespace {

using Corners = std::array<Vec3, 3>;

Corners corners_of(const Mesh48& mesh, Face f) {
  const auto v = mesh.vertices(f);
  return {mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])};
}

// Whether the open segment p q passes through the open triangle t (Moller-Trumbore).
bool segment_crosses(const Vec3& p, const Vec3& q, const Corners& t) {
  const Vec3 d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (std::abs(det) <= 1e-12 * scale) return false;  // parallel (or degenerate)
  const Vec3 s = p - t[0];
  const double u = s.dot(h) / det;
  if (u <= 0 || u >= 1) return false;
  const Vec3 k = s.cross(e1);
  const double v = d.dot(k) / det;
  if (v <= 0 || u + v >= 1) return false;
  const double at = e2.dot(k) / det;
  return at > 0 && at < 1;
}

struct Box {
  Vec3 lo, hi;
};

Box box_of(const Corners& c) {
  return {c[0].cwiseMin(c[1]).cwiseMin(c[2]), c[0].cwiseMax(c[1]).cwiseMax(c[2])};
}

bool disjoint(const Box& a, const Box& b) {
  return (a.lo.array() > b.hi.array()).any() || (a.hi.array() < b.lo.array()).any();
}

bool triangles_cross(const Corners& a, const Corners& b) {
  for (int i = 0; i < 3; ++i) {
    if (segment_crosses(a[i], a[(i + 1) % 3], b)) return true;
    if (segment_crosses(b[i], b[(i + 1) % 3], a)) return true;
  }
  return false;
}

}  // namespace

std::size_t count_face_crossings(const Mesh48& mesh, const std::vector<Face>& faces,
                                 std::size_t enough) {
  std::vector<Corners> all;
  std::vector<std::array<std::uint32_t, 3>> ids;
  std::vector<Box> boxes;
  Box bounds{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
  double extent = 0.0;
  for (const Face g : mesh.live_faces()) {
    const Corners c = corners_of(mesh, g);
    const auto v = mesh.vertices(g);
    all.push_back(c);
    ids.push_back({v[0].idx, v[1].idx, v[2].idx});
    boxes.push_back(box_of(c));
    bounds.lo = bounds.lo.cwiseMin(boxes.back().lo);
    bounds.hi = bounds.hi.cwiseMax(boxes.back().hi);
    extent += (boxes.back().hi - boxes.back().lo).maxCoeff();
  }
  if (all.empty() || faces.empty()) return 0;
  // The faces' boxes binned on a uniform grid of cells about twice a face's mean extent, at
  // most ~ 8 per face (and 1024 per side) in all: a whole re-based mesh (rebuild_if_crossed) is
  // tested against itself without testing every pair of its faces.
  const Vec3 size = (bounds.hi - bounds.lo).cwiseMax(Vec3::Constant(1e-300));
  const double budget = 8.0 * static_cast<double>(all.size());
  double cell = std::max({2.0 * extent / static_cast<double>(all.size()),
                          std::cbrt(size.prod() / budget), size.maxCoeff() / 1024.0});
  if (!(cell > 0.0)) cell = 1.0;  // every face a point, all at one place
  std::array<long, 3> dims{};
  for (int a = 0; a < 3; ++a)
    dims[a] = std::clamp(static_cast<long>(std::ceil(size[a] / cell)), 1L, 1024L);
  const auto range = [&](const Box& b, std::array<long, 3>& lo, std::array<long, 3>& hi) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::clamp(static_cast<long>((b.lo[a] - bounds.lo[a]) / cell), 0L, dims[a] - 1);
      hi[a] = std::clamp(static_cast<long>((b.hi[a] - bounds.lo[a]) / cell), 0L, dims[a] - 1);
    }
  };
  // Counting sort of (cell, face) into a compressed row list.
  const std::size_t n_cells = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  std::vector<std::uint32_t> start(n_cells + 1, 0), members;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < n_cells; ++c) start[c + 1] += start[c];
      members.resize(start[n_cells]);
      fill.assign(start.begin(), start.end() - 1);
    }
    for (std::size_t k = 0; k < all.size(); ++k) {
      std::array<long, 3> lo, hi;
      range(boxes[k], lo, hi);
      for (long z = lo[2]; z <= hi[2]; ++z)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long x = lo[0]; x <= hi[0]; ++x) {
            const std::size_t c = static_cast<std::size_t>((z * dims[1] + y) * dims[0] + x);
            if (pass == 0)
              ++start[c + 1];
            else
              members[fill[c]++] = static_cast<std::uint32_t>(k);
          }
    }
  }
  std::vector<std::uint32_t> seen(all.size(), 0);  // per face tested: which g were looked at
  std::uint32_t stamp = 0;
  std::size_t count = 0;
  for (const Face f : faces) {
    const Corners a = corners_of(mesh, f);
    const auto v = mesh.vertices(f);
    const Box box = box_of(a);
    ++stamp;
    std::array<long, 3> lo, hi;
    range(box, lo, hi);
    for (long z = lo[2]; z <= hi[2]; ++z)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t c = static_cast<std::size_t>((z * dims[1] + y) * dims[0] + x);
          for (std::uint32_t m = start[c]; m < start[c + 1]; ++m) {
            const std::uint32_t k = members[m];
            if (seen[k] == stamp) continue;
            seen[k] = stamp;
            if (disjoint(boxes[k], box)) continue;
            bool shares = false;
            for (const Vertex x : v)
              shares = shares || std::find(ids[k].begin(), ids[k].end(), x.idx) != ids[k].end();
            if (shares || !triangles_cross(a, all[k])) continue;
            if (++count >= enough) return count;
          }
        }
  }
  return count;
}

}  // namespace dynamesh
