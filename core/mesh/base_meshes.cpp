// Base meshes: quad grid, quad box, and Velho's 4-8 construction for any triangle mesh.
#include "core/mesh/base_meshes.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

namespace dynamesh {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// Splits the counter-clockwise quad (p00, p10, p11, p01) into two triangles whose shared
// diagonal is their refinement edge, alternating the diagonal with `parity`.
void add_quad(std::vector<Triangle>& out, std::uint32_t p00, std::uint32_t p10, std::uint32_t p11,
              std::uint32_t p01, bool parity) {
  if (parity) {
    out.push_back({p10, p11, p00});
    out.push_back({p01, p00, p11});
  } else {
    out.push_back({p00, p10, p01});
    out.push_back({p11, p01, p10});
  }
}

void require_positive(int n, const char* what) {
  if (n < 1) throw std::invalid_argument(std::string(what) + " must be at least 1");
}

}  // namespace

Mesh48 make_grid_mesh(int nx, int ny, const Vec2& uv_min, const Vec2& uv_max) {
  require_positive(nx, "grid: quads along u");
  require_positive(ny, "grid: quads along v");
  std::vector<Vec3> positions;
  std::vector<Vec2> uvs;
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const Vec2 s(static_cast<double>(i) / nx, static_cast<double>(j) / ny);
      const Vec2 uv = uv_min + s.cwiseProduct(uv_max - uv_min);
      uvs.push_back(uv);
      positions.emplace_back(uv.x(), 0.0, uv.y());
    }
  }
  std::vector<Triangle> triangles;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      add_quad(triangles, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
  return Mesh48::from_base_triangles(std::move(positions), std::move(uvs), triangles);
}

Mesh48 make_box_mesh(const Box3& box, const std::array<int, 3>& counts) {
  for (int n : counts) require_positive(n, "box: quads along an axis");
  if (box.empty()) throw std::invalid_argument("box: empty bounds");
  // Lattice points on the box's surface, numbered on first use.
  std::map<std::array<int, 3>, std::uint32_t> index;
  std::vector<Vec3> positions;
  auto id = [&](const std::array<int, 3>& ijk) {
    const auto [it, fresh] = index.emplace(ijk, static_cast<std::uint32_t>(positions.size()));
    if (fresh) {
      Vec3 p;
      for (int a = 0; a < 3; ++a)
        p[a] = box.min[a] + (box.max[a] - box.min[a]) * ijk[a] / counts[a];
      positions.push_back(p);
    }
    return it->second;
  };
  std::vector<Triangle> triangles;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      // (b, c) span the face with e_b x e_c pointing outwards.
      int b = (axis + 1) % 3, c = (axis + 2) % 3;
      if (side == 0) std::swap(b, c);
      for (int j = 0; j < counts[c]; ++j) {
        for (int i = 0; i < counts[b]; ++i) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> ijk{};
            ijk[axis] = side * counts[axis];
            ijk[b] = i + di;
            ijk[c] = j + dj;
            return id(ijk);
          };
          add_quad(triangles, corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1),
                   (i + j) % 2 == 0);
        }
      }
    }
  }
  return Mesh48::from_base_triangles(std::move(positions), {}, triangles);
}

Mesh48 make_48_mesh(const std::vector<Vec3>& positions, const std::vector<Vec2>& uvs,
                    const std::vector<Triangle>& triangles) {
  if (!uvs.empty() && uvs.size() != positions.size())
    throw std::invalid_argument("mesh: uv count differs from vertex count");
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (std::uint32_t v : triangles[f])
      if (v >= positions.size())
        throw std::invalid_argument("mesh: triangle " + std::to_string(f) +
                                    " refers to a missing vertex");
  // Keep only referenced vertices.
  std::vector<std::uint32_t> remap(positions.size(), kInvalidIndex);
  std::vector<Vec3> pos;
  std::vector<Vec2> uv;
  auto new_id = [&](std::uint32_t v) {
    if (remap[v] == kInvalidIndex) {
      remap[v] = static_cast<std::uint32_t>(pos.size());
      pos.push_back(positions[v]);
      uv.push_back(uvs.empty() ? Vec2::Zero() : uvs[v]);
    }
    return remap[v];
  };
  std::vector<Triangle> tris;
  tris.reserve(triangles.size());
  for (const Triangle& t : triangles) tris.push_back({new_id(t[0]), new_id(t[1]), new_id(t[2])});

  // Interior edges (each directed edge once, its reverse in the neighbour), longest first.
  struct SharedEdge {
    double length;
    std::uint32_t face_a, local_a, face_b;
  };
  std::unordered_map<std::uint64_t, std::uint32_t> halfedge_of;
  for (std::uint32_t f = 0; f < tris.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t key = (std::uint64_t{tris[f][(i + 1) % 3]} << 32) | tris[f][(i + 2) % 3];
      if (!halfedge_of.emplace(key, 3 * f + i).second)
        throw std::invalid_argument(
            "mesh: an edge is used twice in the same direction "
            "(non-manifold or inconsistently oriented)");
    }
  }
  std::vector<SharedEdge> shared;
  for (const auto& [key, h] : halfedge_of) {
    const auto from = static_cast<std::uint32_t>(key >> 32), to = static_cast<std::uint32_t>(key);
    if (from > to) continue;
    const auto it = halfedge_of.find((std::uint64_t{to} << 32) | from);
    if (it == halfedge_of.end()) continue;
    shared.push_back({(pos[from] - pos[to]).norm(), h / 3, h % 3, it->second / 3});
  }
  std::sort(shared.begin(), shared.end(), [](const SharedEdge& x, const SharedEdge& y) {
    return x.length != y.length ? x.length > y.length
                                : std::tie(x.face_a, x.local_a) < std::tie(y.face_a, y.local_a);
  });

  std::vector<bool> paired(tris.size(), false);
  std::vector<Triangle> out;
  out.reserve(4 * tris.size());
  auto add_vertex = [&](const Vec3& p, const Vec2& u) {
    pos.push_back(p);
    uv.push_back(u);
    return static_cast<std::uint32_t>(pos.size() - 1);
  };
  for (const SharedEdge& e : shared) {
    if (paired[e.face_a] || paired[e.face_b]) continue;
    paired[e.face_a] = paired[e.face_b] = true;
    // Face a = (p, q, r) with the shared edge (q, r); face b = (s, r, q).
    const Triangle& ta = tris[e.face_a];
    const std::uint32_t p = ta[e.local_a], q = ta[(e.local_a + 1) % 3], r = ta[(e.local_a + 2) % 3];
    const Triangle& tb = tris[e.face_b];
    const std::uint32_t s =
        tb[0] != q && tb[0] != r ? tb[0] : (tb[1] != q && tb[1] != r ? tb[1] : tb[2]);
    const std::uint32_t m = add_vertex(0.5 * (pos[q] + pos[r]), 0.5 * (uv[q] + uv[r]));
    out.push_back({m, p, q});
    out.push_back({m, r, p});
    out.push_back({m, s, r});
    out.push_back({m, q, s});
  }
  for (std::uint32_t f = 0; f < tris.size(); ++f) {
    if (paired[f]) continue;
    const auto [a, b, c] = tris[f];
    const std::uint32_t m =
        add_vertex((pos[a] + pos[b] + pos[c]) / 3.0, (uv[a] + uv[b] + uv[c]) / 3.0);
    out.push_back({m, a, b});
    out.push_back({m, b, c});
    out.push_back({m, c, a});
  }
  return Mesh48::from_base_triangles(std::move(pos), std::move(uv), out);
}

}  // namespace dynamesh
