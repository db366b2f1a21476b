#include "core/surface/volume/cuberille_base_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/surface/projection.h"
#include "core/surface/volume/connected_components.h"
#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// Bit d of a 2x2x2 configuration is the cell at offset (d & 1, (d >> 1) & 1, d >> 2).
bool group_connected(unsigned config, bool inside) {
  unsigned members = 0;
  for (unsigned d = 0; d < 8; ++d)
    if (((config >> d) & 1u) == (inside ? 1u : 0u)) members |= 1u << d;
  if (members == 0) return true;
  unsigned reached = members & (~members + 1);  // lowest member
  for (bool grew = true; grew;) {
    grew = false;
    for (unsigned d = 0; d < 8; ++d) {
      if (!((reached >> d) & 1u)) continue;
      for (unsigned axis = 0; axis < 3; ++axis) {
        const unsigned n = d ^ (1u << axis);  // face neighbour within the 2x2x2 block
        if (((members >> n) & 1u) && !((reached >> n) & 1u)) {
          reached |= 1u << n;
          grew = true;
        }
      }
    }
  }
  return reached == members;
}

// A cuberille's boundary is a 2-manifold at a lattice vertex exactly when the inside cells
// and the outside cells around it are each face-connected within the 2x2x2 block.
std::array<bool, 256> manifold_table() {
  std::array<bool, 256> ok{};
  for (unsigned c = 0; c < 256; ++c) ok[c] = group_connected(c, true) && group_connected(c, false);
  return ok;
}

// Fills every 2x2x2 block around a non-manifold vertex until none is left (filling only
// grows the inside, so this ends), filling enclosed holes each round.
std::size_t make_manifold(MaskVolume& cells) {
  static const std::array<bool, 256> ok = manifold_table();
  const auto& n = cells.grid.dims;
  std::size_t added = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int k = 1; k < n[2]; ++k)
      for (int j = 1; j < n[1]; ++j)
        for (int i = 1; i < n[0]; ++i) {
          unsigned config = 0;
          for (unsigned d = 0; d < 8; ++d)
            config |= unsigned(cells.at(i - 1 + (d & 1), j - 1 + ((d >> 1) & 1), k - 1 + (d >> 2)))
                      << d;
          if (ok[config]) continue;
          for (unsigned d = 0; d < 8; ++d) {
            std::uint8_t& c = cells.at(i - 1 + (d & 1), j - 1 + ((d >> 1) & 1), k - 1 + (d >> 2));
            added += c == 0;
            c = 1;
          }
          changed = true;
        }
    added += fill_holes(cells);
  }
  return added;
}

// The counter-clockwise quad (p00, p10, p11, p01) as two triangles whose shared diagonal is
// their refinement edge (newest vertex first).
void add_quad(std::vector<Triangle>& out, std::uint32_t p00, std::uint32_t p10, std::uint32_t p11,
              std::uint32_t p01) {
  out.push_back({p10, p11, p00});
  out.push_back({p01, p00, p11});
}

}  // namespace

Mesh48 make_cuberille_base_mesh(const ImplicitSurface& surface, const Box3& box,
                                const CuberilleOptions& options, CuberilleStats* stats) {
  const double h = options.cell_size;
  if (!(h > 0.0) || box.empty()) throw std::invalid_argument("cuberille: empty box or cell size");
  // One empty cell of margin on every side, so the inside never touches the lattice's border.
  VoxelGrid grid;
  const Vec3 origin = box.min - Vec3::Constant(h);
  for (int a = 0; a < 3; ++a) grid.dims[a] = static_cast<int>(std::ceil(box.size()[a] / h)) + 2;
  grid.linear = h * Mat3::Identity();
  grid.offset = origin + Vec3::Constant(0.5 * h);  // cell centres
  MaskVolume cells(grid, 0);
  const auto count = static_cast<std::int64_t>(grid.count());
  const int nx = grid.dims[0], ny = grid.dims[1];
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < count; ++v) {
    const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
              k = static_cast<int>(v / (std::int64_t(nx) * ny));
    const bool border =
        i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == grid.dims[2] - 1;
    cells.values[static_cast<std::size_t>(v)] =
        !border && surface.value(grid.to_world(Vec3(i, j, k))) < 0.0 ? 1 : 0;
  }
  if (keep_largest_component(cells) == 0)
    throw std::invalid_argument(surface.name() + ": no cell of the base lattice lies inside");
  CuberilleStats s;
  s.cells_added = fill_holes(cells);
  s.cells_added += make_manifold(cells);

  // Lattice corners used by boundary quads, numbered on first use.
  const std::array<int, 3> corners{grid.dims[0] + 1, grid.dims[1] + 1, grid.dims[2] + 1};
  const std::size_t corner_count = static_cast<std::size_t>(corners[0]) * corners[1] * corners[2];
  std::vector<std::uint32_t> id(corner_count, kInvalidIndex);
  std::vector<Vec3> positions;
  auto corner = [&](std::array<int, 3> c) {
    std::uint32_t& slot =
        id[c[0] + std::size_t(corners[0]) * (c[1] + std::size_t(corners[1]) * c[2])];
    if (slot == kInvalidIndex) {
      slot = static_cast<std::uint32_t>(positions.size());
      positions.push_back(origin + h * Vec3(c[0], c[1], c[2]));
    }
    return slot;
  };
  std::vector<Triangle> triangles;
  std::vector<std::array<std::uint32_t, 4>> quads;
  for (int k = 0; k < grid.dims[2]; ++k)
    for (int j = 0; j < grid.dims[1]; ++j)
      for (int i = 0; i < grid.dims[0]; ++i) {
        if (!cells.at(i, j, k)) continue;
        ++s.inside_cells;
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            std::array<int, 3> n{i, j, k};
            n[axis] += side ? 1 : -1;
            if (cells.at(n[0], n[1], n[2])) continue;
            // (b, c) span the face with e_b x e_c pointing from inside to outside.
            int b = (axis + 1) % 3, c = (axis + 2) % 3;
            if (!side) std::swap(b, c);
            auto at = [&](int db, int dc) {
              std::array<int, 3> p{i, j, k};
              p[axis] += side;
              p[b] += db;
              p[c] += dc;
              return corner(p);
            };
            quads.push_back({at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
          }
      }
  s.quads = quads.size();

  // Each quad separates an inside cell centre (F < 0) from an outside one (F > 0): bisection
  // between them finds a point of F = 0 on the quad's own sheet. A corner starts at the mean
  // of its quads' points and is Newton-projected from there; a Newton step that leaves the
  // corner's cell (near a medial axis |grad F| is small and the step long) is replaced by the
  // nearest of those points, which lie on the surface by construction.
  // Cells added to make the boundary manifold have F > 0 at their centre: their quads have no
  // crossing (valid = false) and their corners rely on Newton alone.
  std::vector<Vec3> crossing(quads.size());
  std::vector<std::uint8_t> valid(quads.size(), 0);
  const auto nq = static_cast<std::int64_t>(quads.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < nq; ++q) {
    const std::size_t iq = static_cast<std::size_t>(q);
    const Vec3 centre = 0.25 * (positions[quads[iq][0]] + positions[quads[iq][1]] +
                                positions[quads[iq][2]] + positions[quads[iq][3]]);
    const Vec3 normal = (positions[quads[iq][1]] - positions[quads[iq][0]])
                            .cross(positions[quads[iq][3]] - positions[quads[iq][0]])
                            .normalized();
    Vec3 in = centre - 0.5 * h * normal, out = centre + 0.5 * h * normal;
    if (!(surface.value(in) < 0.0 && surface.value(out) >= 0.0)) continue;
    valid[iq] = 1;
    for (int it = 0; it < 40; ++it) {
      const Vec3 mid = 0.5 * (in + out);
      (surface.value(mid) < 0.0 ? in : out) = mid;
    }
    crossing[iq] = 0.5 * (in + out);
  }
  std::vector<std::vector<std::uint32_t>> incident(positions.size());
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (std::uint32_t v : quads[q]) incident[v].push_back(static_cast<std::uint32_t>(q));
  const auto nv = static_cast<std::int64_t>(positions.size());
  ProjectionOptions local;
  local.max_step = h;  // Newton must not leave the corner's neighbourhood
  std::vector<Vec3> placed = positions;
  std::vector<std::uint8_t> unplaced(positions.size(), 0);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t iv = 0; iv < nv; ++iv) {
    const auto v = static_cast<std::size_t>(iv);
    Vec3 start = Vec3::Zero();
    int crossings = 0;
    for (std::uint32_t q : incident[v])
      if (valid[q]) {
        start += crossing[q];
        ++crossings;
      }
    if (crossings == 0) {
      unplaced[v] = 1;
      continue;
    }
    start /= crossings;
    const ProjectionResult r = project_to_surface(surface, start, local);
    if (r.converged && (r.point - positions[v]).norm() <= h) {
      placed[v] = r.point;
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t q : incident[v])
      if (valid[q] && (crossing[q] - start).squaredNorm() < best) {
        best = (crossing[q] - start).squaredNorm();
        placed[v] = crossing[q];
      }
  }
  // Corners of added cells only: from the mean of their placed quad neighbours.
  std::vector<std::vector<std::uint32_t>> ring(positions.size());
  for (const auto& q : quads)
    for (int e = 0; e < 4; ++e) {
      ring[q[e]].push_back(q[(e + 1) % 4]);
      ring[q[(e + 1) % 4]].push_back(q[e]);
    }
  for (bool progress = true; progress;) {
    progress = false;
    for (std::size_t v = 0; v < positions.size(); ++v) {
      if (!unplaced[v]) continue;
      Vec3 start = Vec3::Zero();
      int known = 0;
      for (std::uint32_t w : ring[v])
        if (!unplaced[w]) {
          start += placed[w];
          ++known;
        }
      if (!known) continue;
      start /= known;
      const ProjectionResult r = project_to_surface(surface, start, local);
      placed[v] = r.converged && (r.point - start).norm() <= 2.0 * h ? r.point : start;
      unplaced[v] = 0;
      progress = true;
    }
  }
  positions.swap(placed);
  for (const auto& q : quads) add_quad(triangles, q[0], q[1], q[2], q[3]);
  if (stats) *stats = s;
  return Mesh48::from_base_triangles(std::move(positions), {}, triangles);
}

}  // namespace dynamesh
