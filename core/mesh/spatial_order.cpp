#include "core/mesh/spatial_order.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace dynamesh {
namespace {

// Interleaves the bits of a 21-bit integer with two zero bits each (one axis of a Morton code).
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

Renumbering spatial_renumbering(const Mesh48& mesh) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.is_alive(Vertex(v))) continue;
    lo = lo.cwiseMin(mesh.position(Vertex(v)));
    hi = hi.cwiseMax(mesh.position(Vertex(v)));
  }
  const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(1e-300));
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(mesh.n_faces());
  for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.is_alive(Face(f))) continue;
    const auto v = mesh.vertices(Face(f));
    const Vec3 c = (mesh.position(v[0]) + mesh.position(v[1]) + mesh.position(v[2])) / 3.0;
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double s = std::clamp((c[a] - lo[a]) / extent[a], 0.0, 1.0);
      code |= spread_bits(static_cast<std::uint64_t>(s * 2097151.0)) << a;
    }
    keyed.emplace_back(code, f);
  }
  std::sort(keyed.begin(), keyed.end());  // ties (equal codes) by old id: deterministic
  Renumbering r;
  r.face.assign(mesh.face_capacity(), kInvalidIndex);
  r.vertex.assign(mesh.vertex_capacity(), kInvalidIndex);
  std::uint32_t next_vertex = 0;
  for (std::uint32_t i = 0; i < keyed.size(); ++i) {
    const std::uint32_t f = keyed[i].second;
    r.face[f] = i;
    for (const Vertex v : mesh.vertices(Face(f)))
      if (r.vertex[v.idx] == kInvalidIndex) r.vertex[v.idx] = next_vertex++;
  }
  r.n_faces = keyed.size();
  r.n_vertices = next_vertex;
  return r;
}

double scattered_face_share(const Mesh48& mesh, std::size_t probes) {
  const std::size_t capacity = mesh.face_capacity();
  if (capacity == 0 || probes == 0) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, capacity / probes);
  std::size_t live = 0, scattered = 0;
  for (std::size_t f = 0; f < capacity; f += stride) {
    if (!mesh.is_alive(Face(static_cast<std::uint32_t>(f)))) continue;
    const auto v = mesh.vertices(Face(static_cast<std::uint32_t>(f)));
    const std::uint32_t lo = std::min({v[0].idx, v[1].idx, v[2].idx});
    const std::uint32_t hi = std::max({v[0].idx, v[1].idx, v[2].idx});
    ++live;
    scattered += hi - lo > kLocalityWindow;
  }
  return live ? static_cast<double>(scattered) / static_cast<double>(live) : 0.0;
}

}  // namespace dynamesh
