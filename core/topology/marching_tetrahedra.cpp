#include "core/topology/marching_tetrahedra.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace dynamesh {

namespace {

// Cube corners by bits (x = 1, y = 2, z = 4); the six tetrahedra of the Kuhn triangulation all
// contain the diagonal 0-7 and walk along one path 0 -> 7 of axis steps each.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                             {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};

using Triangle = std::array<std::uint32_t, 3>;

class Extractor {
 public:
  Extractor(const ContourGrid& grid, const std::vector<double>& values, double margin)
      : grid_(grid), values_(values), margin_(margin) {}

  ContourMesh run() {
    const auto [nx, ny, nz] = grid_.cells;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) cube(i, j, k);
    return std::move(out_);
  }

 private:
  std::uint64_t index(int i, int j, int k) const {
    const auto [nx, ny, nz] = grid_.cells;
    (void)nz;
    return (static_cast<std::uint64_t>(k) * (ny + 1) + j) * (nx + 1) + i;
  }

  void cube(int i, int j, int k) {
    std::uint64_t corner[8];
    for (int c = 0; c < 8; ++c) corner[c] = index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
    for (const auto& tet : kTets) {
      std::uint64_t ids[4];
      for (int c = 0; c < 4; ++c) ids[c] = corner[tet[c]];
      tetrahedron(ids);
    }
  }

  Vec3 position(std::uint64_t id) const {
    const auto [nx, ny, nz] = grid_.cells;
    (void)nz;
    const int i = static_cast<int>(id % (nx + 1));
    const int j = static_cast<int>(id / (nx + 1) % (ny + 1));
    const int k = static_cast<int>(id / (static_cast<std::uint64_t>(nx + 1) * (ny + 1)));
    return grid_.point(i, j, k);
  }

  bool inside(std::uint64_t id) const { return values_[id] < 0.0; }

  // The contour vertex on grid edge (a, b), a inside and b outside; one per edge.
  std::uint32_t crossing(std::uint64_t a, std::uint64_t b) {
    const std::uint64_t key = std::min(a, b) * values_.size() + std::max(a, b);
    const auto [it, fresh] =
        vertex_of_.emplace(key, static_cast<std::uint32_t>(out_.positions.size()));
    if (fresh) {
      const double fa = values_[a], fb = values_[b];
      const double s = std::clamp(fa / (fa - fb), margin_, 1.0 - margin_);
      out_.positions.push_back((1.0 - s) * position(a) + s * position(b));
      out_.edges.push_back({position(a), position(b)});
    }
    return it->second;
  }

  // Adds (a, b, c) facing from the inside corner `in` towards the outside corner `out`.
  void emit(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint64_t in,
            std::uint64_t out) {
    const Vec3& pa = out_.positions[a];
    const Vec3 n = (out_.positions[b] - pa).cross(out_.positions[c] - pa);
    if (n.dot(position(out) - position(in)) < 0) std::swap(b, c);
    out_.triangles.push_back({a, b, c});
  }

  void tetrahedron(const std::uint64_t ids[4]) {
    std::uint64_t in[4], out[4];
    int n_in = 0, n_out = 0;
    for (int c = 0; c < 4; ++c) (inside(ids[c]) ? in[n_in++] : out[n_out++]) = ids[c];
    if (n_in == 0 || n_out == 0) return;
    if (n_in == 1) {
      emit(crossing(in[0], out[0]), crossing(in[0], out[1]), crossing(in[0], out[2]), in[0],
           out[0]);
    } else if (n_in == 3) {
      emit(crossing(in[0], out[0]), crossing(in[1], out[0]), crossing(in[2], out[0]), in[0],
           out[0]);
    } else {
      // The quad's corners in cyclic order around the tetrahedron's middle section.
      const std::uint32_t q[4] = {crossing(in[0], out[0]), crossing(in[0], out[1]),
                                  crossing(in[1], out[1]), crossing(in[1], out[0])};
      // The shorter diagonal gives the better pair of triangles.
      const auto& p = out_.positions;
      if ((p[q[0]] - p[q[2]]).squaredNorm() <= (p[q[1]] - p[q[3]]).squaredNorm()) {
        emit(q[0], q[1], q[2], in[0], out[1]);
        emit(q[0], q[2], q[3], in[1], out[0]);
      } else {
        emit(q[0], q[1], q[3], in[0], out[0]);
        emit(q[1], q[2], q[3], in[1], out[1]);
      }
    }
  }

  const ContourGrid& grid_;
  const std::vector<double>& values_;
  double margin_;
  std::unordered_map<std::uint64_t, std::uint32_t> vertex_of_;
  ContourMesh out_;
};

}  // namespace

Vec3 ContourGrid::spacing() const {
  return Vec3(box.size().array() / Vec3(cells[0], cells[1], cells[2]).array());
}

Vec3 ContourGrid::point(int i, int j, int k) const {
  return box.min + Vec3(i, j, k).cwiseProduct(spacing());
}

ContourGrid make_contour_grid(const Box3& box, double spacing) {
  if (box.empty() || !(spacing > 0) || !std::isfinite(spacing))
    throw std::invalid_argument("contour: empty box or spacing not positive");
  ContourGrid grid;
  grid.box = box;
  for (int a = 0; a < 3; ++a)
    grid.cells[a] = std::max(2, static_cast<int>(std::ceil(box.size()[a] / spacing)));
  return grid;
}

std::vector<double> sample_grid(const ImplicitSurface& surface, const ContourGrid& grid) {
  const auto [nx, ny, nz] = grid.cells;
  const std::int64_t n = static_cast<std::int64_t>(nx + 1) * (ny + 1) * (nz + 1);
  std::vector<double> values(static_cast<std::size_t>(n));
  for (std::int64_t id = 0; id < n; ++id) {
    const int i = static_cast<int>(id % (nx + 1));
    const int j = static_cast<int>(id / (nx + 1) % (ny + 1));
    const int k = static_cast<int>(id / (static_cast<std::int64_t>(nx + 1) * (ny + 1)));
    values[static_cast<std::size_t>(id)] = surface.value(grid.point(i, j, k));
  }
  return values;
}

ContourMesh marching_tetrahedra(const ContourGrid& grid, const std::vector<double>& values,
                                double margin, bool open) {
  const auto [nx, ny, nz] = grid.cells;
  if (values.size() != static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1))
    throw std::invalid_argument("contour: value count does not match the grid");
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const bool side = i == 0 || j == 0 || k == 0 || i == nx || j == ny || k == nz;
        const double f = values[(static_cast<std::size_t>(k) * (ny + 1) + j) * (nx + 1) + i];
        if (!std::isfinite(f))
          throw std::invalid_argument("contour: F is not finite at a grid point");
        if (side && f < 0 && !open)
          throw std::invalid_argument(
              "the surface is not inside its bounds: F < 0 on the bounding box's side");
      }
  return Extractor(grid, values, margin).run();
}

Vec3 root_on_edge(const ImplicitSurface& surface, const std::array<Vec3, 2>& edge, double margin,
                  double level) {
  double a = 0.0, b = 1.0;
  double fa = surface.value(edge[0]) - level, fb = surface.value(edge[1]) - level;
  int side = 0;
  for (int i = 0; i < 40 && fa < 0 && fb >= 0; ++i) {
    const double s = (a * fb - b * fa) / (fb - fa);
    const double fs = surface.value((1 - s) * edge[0] + s * edge[1]) - level;
    if (fs < 0) {
      a = s, fa = fs;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = s, fb = fs;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
    if (b - a < 1e-12) break;
  }
  const double s = std::clamp(0.5 * (a + b), margin, 1.0 - margin);
  return (1 - s) * edge[0] + s * edge[1];
}

}  // namespace dynamesh
