// Independent measurements of a mesh for tests: computed from the plain triangle list
// (vertex triples and positions), never from the mesh's own links or counters.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "core/mesh/mesh48.h"

namespace dynamesh::test {

using Triple = std::array<std::uint32_t, 3>;

inline std::vector<Triple> triangle_list(const Mesh48& mesh) {
  std::vector<Triple> out;
  for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.is_alive(Face(f))) continue;
    const auto v = mesh.vertices(Face(f));
    out.push_back({v[0].idx, v[1].idx, v[2].idx});
  }
  return out;
}

// Faces as a set of vertex triples in storage order (newest vertex first, so the set also
// records every refinement edge).
inline std::set<Triple> face_set(const Mesh48& mesh) {
  const auto list = triangle_list(mesh);
  return {list.begin(), list.end()};
}

struct Topology {
  long vertices = 0, edges = 0, faces = 0, boundary_edges = 0;
  long euler() const { return vertices - edges + faces; }
};

inline Topology topology(const Mesh48& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_use;
  std::set<std::uint32_t> used;
  Topology t;
  for (const Triple& tri : triangle_list(mesh)) {
    ++t.faces;
    for (int i = 0; i < 3; ++i) {
      used.insert(tri[i]);
      const auto a = tri[i], b = tri[(i + 1) % 3];
      ++edge_use[{std::min(a, b), std::max(a, b)}];
    }
  }
  t.vertices = static_cast<long>(used.size());
  t.edges = static_cast<long>(edge_use.size());
  for (const auto& [e, n] : edge_use) t.boundary_edges += n == 1;
  return t;
}

inline double boundary_length(const Mesh48& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_use;
  for (const Triple& tri : triangle_list(mesh))
    for (int i = 0; i < 3; ++i) {
      const auto a = tri[i], b = tri[(i + 1) % 3];
      ++edge_use[{std::min(a, b), std::max(a, b)}];
    }
  double length = 0;
  for (const auto& [e, n] : edge_use)
    if (n == 1) length += (mesh.position(Vertex(e.first)) - mesh.position(Vertex(e.second))).norm();
  return length;
}

inline Vec3 face_area_vector(const Mesh48& mesh, const Triple& t) {
  const Vec3 &a = mesh.position(Vertex(t[0])), &b = mesh.position(Vertex(t[1])),
             &c = mesh.position(Vertex(t[2]));
  return 0.5 * (b - a).cross(c - a);
}

inline double total_area(const Mesh48& mesh) {
  double area = 0;
  for (const Triple& t : triangle_list(mesh)) area += face_area_vector(mesh, t).norm();
  return area;
}

// Enclosed volume of a closed, outward-oriented mesh (divergence theorem).
inline double enclosed_volume(const Mesh48& mesh) {
  double volume = 0;
  for (const Triple& t : triangle_list(mesh)) {
    const Vec3 &a = mesh.position(Vertex(t[0])), &b = mesh.position(Vertex(t[1])),
               &c = mesh.position(Vertex(t[2]));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace dynamesh::test
