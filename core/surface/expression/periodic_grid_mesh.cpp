#include "core/surface/expression/periodic_grid_mesh.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynamesh {

Mesh48 make_periodic_grid_mesh(int nx, int ny, const Vec2& uv_min, const Vec2& uv_max,
                               bool periodic_u, bool periodic_v) {
  auto check = [](int n, bool periodic, const char* axis) {
    if (n < 1 || (periodic && (n < 4 || n % 2 != 0)))
      throw std::invalid_argument(
          std::string("periodic grid: ") + std::to_string(n) + " quads along " + axis +
          (periodic ? "; a periodic direction needs an even count >= 4" : "; needs at least 1"));
  };
  check(nx, periodic_u, "u");
  check(ny, periodic_v, "v");
  // Distinct vertex columns / rows: the closing one is the first again.
  const int cols = periodic_u ? nx : nx + 1;
  const int rows = periodic_v ? ny : ny + 1;
  std::vector<Vec3> positions;
  std::vector<Vec2> uvs;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const Vec2 s(static_cast<double>(i) / nx, static_cast<double>(j) / ny);
      const Vec2 uv = uv_min + s.cwiseProduct(uv_max - uv_min);
      uvs.push_back(uv);
      positions.emplace_back(uv.x(), 0.0, uv.y());
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>((j % rows) * cols + (i % cols));
  };
  // The same checkerboard of diagonals as make_grid_mesh: each triangle newest vertex first,
  // its refinement edge the quad's diagonal.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::uint32_t p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1),
                          p01 = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        triangles.push_back({p10, p11, p00});
        triangles.push_back({p01, p00, p11});
      } else {
        triangles.push_back({p00, p10, p01});
        triangles.push_back({p11, p01, p10});
      }
    }
  }
  return Mesh48::from_base_triangles(std::move(positions), std::move(uvs), triangles);
}

}  // namespace dynamesh
