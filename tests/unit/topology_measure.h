// Independent topology of an implicit solid, for the topology tests (issue 16): of F < 0 on a
// fine voxel grid, its 6-connected components flood-filled, and the Euler characteristic of the
// union of its closed voxels, V - E + F - C, whose boundary surface has twice that
// characteristic. Nothing here reads the mesh or the engine's contouring (the mesh's own
// topology comes from tests/support/mesh_validity.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh::test {

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
