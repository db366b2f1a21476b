#include "core/surface/volume/cuberille_base_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/parallel.h"
#include "core/surface/projection.h"
#include "core/surface/volume/connected_components.h"
#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

using Quad = std::array<std::uint32_t, 4>;

// The cuberille's faces meet non-manifoldly where two inside cells share only a lattice edge
// or corner (four faces on one edge, two umbrellas at one corner). Those cells are kept apart:
// at an edge with four faces, each face is glued to the other face of its own inside cell, and
// each corner gets one vertex per cycle of faces glued around it. Filling cells instead (as
// a "make manifold" pass would) bridges the outside gap between two sheets, and a base edge
// across a gap never gets shorter than the gap under refinement. Returns the quads with their
// corners renumbered; `lattice_corner[v]` is the lattice corner of new vertex v.
std::vector<Quad> split_shared_corners(const std::vector<Quad>& quads,
                                       const std::vector<std::size_t>& cell_of,
                                       std::vector<std::uint32_t>& lattice_corner) {
  const std::size_t n = quads.size();
  // Faces around each lattice edge.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> around;
  auto edge_key = [](std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
  };
  for (std::size_t q = 0; q < n; ++q)
    for (int e = 0; e < 4; ++e)
      around[edge_key(quads[q][e], quads[q][(e + 1) % 4])].push_back(std::uint32_t(q));
  auto partner = [&](std::size_t q, int e) {
    const auto& faces = around.at(edge_key(quads[q][e], quads[q][(e + 1) % 4]));
    for (std::uint32_t o : faces)
      if (o != q && (faces.size() == 2 || cell_of[o] == cell_of[q])) return std::size_t(o);
    throw std::logic_error("cuberille: a face edge without a partner");
  };
  // Union-find over (face, corner slot); slot k of face q is 4q + k.
  std::vector<std::uint32_t> parent(4 * n);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t q = 0; q < n; ++q)
    for (int e = 0; e < 4; ++e) {
      // Edge e runs from corner e to corner e + 1 of q; its partner holds both corners too.
      const std::size_t o = partner(q, e);
      for (const int k : {e, (e + 1) % 4}) {
        const std::uint32_t corner = quads[q][k];
        for (int m = 0; m < 4; ++m)
          if (quads[o][m] == corner)
            parent[find(std::uint32_t(4 * q + k))] = find(std::uint32_t(4 * o + m));
      }
    }
  std::vector<std::uint32_t> id(4 * n, kInvalidIndex);
  std::vector<Quad> out(n);
  lattice_corner.clear();
  for (std::size_t q = 0; q < n; ++q)
    for (int k = 0; k < 4; ++k) {
      std::uint32_t& slot = id[find(std::uint32_t(4 * q + k))];
      if (slot == kInvalidIndex) {
        slot = std::uint32_t(lattice_corner.size());
        lattice_corner.push_back(quads[q][k]);
      }
      out[q][k] = slot;
    }
  return out;
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
  std::vector<Quad> quads;
  std::vector<std::size_t> cell_of;  // the inside cell behind each quad
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
            cell_of.push_back(grid.index(i, j, k));
          }
      }
  s.quads = quads.size();
  {
    std::vector<std::uint32_t> lattice_corner;
    quads = split_shared_corners(quads, cell_of, lattice_corner);
    std::vector<Vec3> split(lattice_corner.size());
    for (std::size_t v = 0; v < split.size(); ++v) split[v] = positions[lattice_corner[v]];
    s.split_corners = split.size() - positions.size();
    positions.swap(split);
  }

  // Each quad separates an inside cell centre (F < 0) from an outside one (F > 0): bisection
  // between them finds a point of F = 0 on the quad's own sheet. A corner starts at the mean
  // of its quads' points and is Newton-projected from there; a Newton step that leaves the
  // corner's cell (near a medial axis |grad F| is small and the step long) is replaced by the
  // nearest of those points, which lie on the surface by construction.
  // Filled cavity cells have F > 0 at their centre: their quads have no
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
