// Independent topology of a mesh and of an implicit solid, for the topology tests (issue 16):
//  - of a mesh, from its plain triangle list only: components (vertices joined by edges),
//    Euler characteristic, and whether it is a closed, oriented 2-manifold (every edge used
//    once in each direction, every vertex's faces one fan closing on itself);
//  - of the solid F < 0, from a fine voxel grid: its 6-connected components flood-filled, and
//    the Euler characteristic of the union of its closed voxels, V - E + F - C, whose boundary
//    surface has twice that characteristic. Nothing here reads the mesh's links or the
//    engine's contouring.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <numeric>
#include <vector>

#include "core/geometry/vector_types.h"
#include "mesh_measure.h"

namespace dynamesh::test {

struct MeshTopology {
  long components = 0;
  long euler = 0;
  long bad_edges = 0;     // used other than once in each direction
  long bad_vertices = 0;  // faces around the vertex not one closed fan
};

inline MeshTopology mesh_topology(const std::vector<Triple>& tris) {
  MeshTopology out;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
  for (const auto& [e, n] : directed)
    if (n != 1 || !directed.count({e.second, e.first})) ++out.bad_edges;
  long undirected = 0;
  for (const auto& [e, n] : directed)
    undirected += e.first < e.second || !directed.count({e.second, e.first});
  // Components by union-find over the edges.
  std::map<std::uint32_t, std::uint32_t> parent;
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : tris)
    for (auto v : t) parent.emplace(v, v);
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) parent[find(t[i])] = find(t[(i + 1) % 3]);
  for (const auto& [v, p] : parent) out.components += find(v) == v;
  out.euler = static_cast<long>(parent.size()) - undirected + static_cast<long>(tris.size());
  // Each vertex: follow next[a] = b over its faces (v, a, b); one cycle through all of them.
  std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> fan;
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) fan[t[i]][t[(i + 1) % 3]] = t[(i + 2) % 3];
  for (const auto& [v, next] : fan) {
    std::size_t steps = 0;
    std::uint32_t a = next.begin()->first;
    do {
      const auto it = next.find(a);
      if (it == next.end()) break;
      a = it->second;
      ++steps;
    } while (a != next.begin()->first && steps <= next.size());
    if (a != next.begin()->first || steps != next.size()) ++out.bad_vertices;
  }
  return out;
}

inline MeshTopology mesh_topology(const Mesh48& mesh) { return mesh_topology(triangle_list(mesh)); }

struct SolidTopology {
  long components = 0;
  long surface_euler = 0;  // 2 * chi(solid)
};

// Voxels of side box.size() / n (n along the longest side) whose centres have F < 0.
inline SolidTopology solid_topology(const std::function<double(const Vec3&)>& F, const Box3& box,
                                    int n) {
  const double h = box.size().maxCoeff() / n;
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) c[a] = std::max(1, static_cast<int>(std::ceil(box.size()[a] / h)));
  auto cell = [&](int i, int j, int k) { return (static_cast<long>(k) * c[1] + j) * c[0] + i; };
  std::vector<char> in(static_cast<std::size_t>(c[0]) * c[1] * c[2]);
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i)
        in[cell(i, j, k)] = F(box.min + h * Vec3(i + 0.5, j + 0.5, k + 0.5)) < 0;
  SolidTopology out;
  // Flood fill, 6-connected.
  std::vector<char> seen(in.size());
  std::vector<std::array<int, 3>> stack;
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i) {
        if (!in[cell(i, j, k)] || seen[cell(i, j, k)]) continue;
        ++out.components;
        stack.push_back({i, j, k});
        seen[cell(i, j, k)] = 1;
        while (!stack.empty()) {
          const auto p = stack.back();
          stack.pop_back();
          for (int a = 0; a < 3; ++a)
            for (int d : {-1, 1}) {
              auto q = p;
              q[a] += d;
              if (q[a] < 0 || q[a] >= c[a] || !in[cell(q[0], q[1], q[2])] ||
                  seen[cell(q[0], q[1], q[2])])
                continue;
              seen[cell(q[0], q[1], q[2])] = 1;
              stack.push_back(q);
            }
        }
      }
  // Cells of the closed cubical complex, keyed on a doubled lattice (odd coordinate = the
  // cell extends along that axis): chi = sum over cells of (-1)^dimension.
  std::vector<char> cells(static_cast<std::size_t>(2 * c[0] + 1) * (2 * c[1] + 1) * (2 * c[2] + 1));
  auto key = [&](int x, int y, int z) {
    return (static_cast<std::size_t>(z) * (2 * c[1] + 1) + y) * (2 * c[0] + 1) + x;
  };
  long chi = 0;
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i) {
        if (!in[cell(i, j, k)]) continue;
        for (int dz = 0; dz <= 2; ++dz)
          for (int dy = 0; dy <= 2; ++dy)
            for (int dx = 0; dx <= 2; ++dx) {
              const std::size_t kk = key(2 * i + dx, 2 * j + dy, 2 * k + dz);
              if (cells[kk]) continue;
              cells[kk] = 1;
              const int dim = (dx == 1) + (dy == 1) + (dz == 1);
              chi += dim % 2 == 0 ? 1 : -1;
            }
      }
  out.surface_euler = 2 * chi;
  return out;
}

}  // namespace dynamesh::test
