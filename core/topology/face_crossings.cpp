#include "core/topology/face_crossings.h"

#include <algorithm>
#include <array>

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
  for (const Face g : mesh.live_faces()) {
    const Corners c = corners_of(mesh, g);
    const auto v = mesh.vertices(g);
    all.push_back(c);
    ids.push_back({v[0].idx, v[1].idx, v[2].idx});
    boxes.push_back(box_of(c));
  }
  std::size_t count = 0;
  for (const Face f : faces) {
    const Corners a = corners_of(mesh, f);
    const auto v = mesh.vertices(f);
    const Box box = box_of(a);
    for (std::size_t k = 0; k < all.size(); ++k) {
      if (disjoint(boxes[k], box)) continue;
      bool shares = false;
      for (const Vertex x : v)
        shares = shares || std::find(ids[k].begin(), ids[k].end(), x.idx) != ids[k].end();
      if (shares || !triangles_cross(a, all[k])) continue;
      if (++count >= enough) return count;
    }
  }
  return count;
}

}  // namespace dynamesh
