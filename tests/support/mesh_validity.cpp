// The exact judge of tests/support/mesh_validity.h. Combinatorics by plain counting over the
// triangle list; geometry with CGAL's exact predicates (degeneracy, self-intersection).
#include "tests/support/mesh_validity.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "core/geometry/mesh_quality.h"
#include "core/surface/expression/triangle_mesh_file.h"

namespace dynamesh::test {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;

struct DisjointSets {
  std::vector<std::uint32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
  long count_roots(const std::vector<std::uint32_t>& members) {
    std::vector<std::uint32_t> roots;
    for (auto m : members) roots.push_back(find(m));
    std::sort(roots.begin(), roots.end());
    return std::unique(roots.begin(), roots.end()) - roots.begin();
  }
};

Point to_point(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

// Edge use (undirected count, and directed count to catch inconsistent orientation) and the
// components of the triangles joined through shared edges.
void count_edges_and_components(const Triangles& tris, MeshValidity& v) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> faces_of_edge;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::uint32_t f = 0; f < tris.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const auto a = tris[f][i], b = tris[f][(i + 1) % 3];
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
      ++directed[{a, b}];
    }
  DisjointSets sets(tris.size());
  v.edges = static_cast<long>(faces_of_edge.size());
  for (const auto& [edge, faces] : faces_of_edge) {
    v.boundary_edges += faces.size() == 1;
    const bool misoriented = directed[edge] > 1 || directed[{edge.second, edge.first}] > 1;
    v.non_manifold_edges += faces.size() > 2 || misoriented;
    for (std::size_t i = 1; i < faces.size(); ++i) sets.join(faces[0], faces[i]);
  }
  std::vector<std::uint32_t> all(tris.size());
  std::iota(all.begin(), all.end(), 0u);
  v.components = sets.count_roots(all);
}

// A vertex is manifold when its incident triangles form one fan: joined through the edges
// at the vertex, they must be a single group.
void count_non_manifold_vertices(const Triangles& tris, std::size_t n_positions, MeshValidity& v) {
  std::vector<std::vector<std::uint32_t>> faces_at(n_positions);
  for (std::uint32_t f = 0; f < tris.size(); ++f)
    for (auto c : tris[f]) faces_at[c].push_back(f);
  for (std::uint32_t vertex = 0; vertex < n_positions; ++vertex) {
    const auto& fan = faces_at[vertex];
    if (fan.empty()) continue;
    ++v.vertices;
    DisjointSets sets(fan.size());
    std::map<std::uint32_t, std::uint32_t> first_with_corner;  // other corner -> fan index
    for (std::uint32_t i = 0; i < fan.size(); ++i)
      for (auto c : tris[fan[i]]) {
        if (c == vertex) continue;
        const auto [it, inserted] = first_with_corner.emplace(c, i);
        if (!inserted) sets.join(i, it->second);
      }
    std::vector<std::uint32_t> members(fan.size());
    std::iota(members.begin(), members.end(), 0u);
    v.non_manifold_vertices += sets.count_roots(members) > 1;
  }
}

void measure_shapes(const std::vector<Vec3>& p, const Triangles& tris, MeshValidity& v) {
  for (const auto& t : tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] ||
        CGAL::collinear(to_point(p[t[0]]), to_point(p[t[1]]), to_point(p[t[2]]))) {
      ++v.degenerate_triangles;
      v.min_angle_deg = 0.0;
      v.max_aspect = INFINITY;
      continue;
    }
    v.min_angle_deg = std::min(v.min_angle_deg, angle_range_deg(p[t[0]], p[t[1]], p[t[2]])[0]);
    v.max_aspect = std::max(v.max_aspect, aspect_ratio(p[t[0]], p[t[1]], p[t[2]]));
  }
}

// CGAL needs a halfedge structure, so this runs only on manifold triangle lists.
long count_self_intersections(const std::vector<Vec3>& p, const Triangles& tris) {
  CgalMesh mesh;
  std::vector<CgalMesh::Vertex_index> index(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) index[i] = mesh.add_vertex(to_point(p[i]));
  for (const auto& t : tris)
    if (mesh.add_face(index[t[0]], index[t[1]], index[t[2]]) == CgalMesh::null_face()) return -1;
  std::vector<std::pair<CgalMesh::Face_index, CgalMesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
  return static_cast<long>(pairs.size());
}

}  // namespace

std::string MeshValidity::describe() const {
  std::ostringstream s;
  s << triangles << " triangles, " << vertices << " vertices, " << components
    << " component(s), euler " << euler() << ", boundary edges " << boundary_edges
    << ", non-manifold edges " << non_manifold_edges << ", non-manifold vertices "
    << non_manifold_vertices << ", degenerate triangles " << degenerate_triangles
    << ", self-intersecting pairs " << self_intersecting_pairs << ", smallest angle "
    << min_angle_deg << " deg, worst aspect " << max_aspect;
  return s.str();
}

MeshValidity check_mesh_validity(const std::vector<Vec3>& positions, const Triangles& triangles) {
  MeshValidity v;
  v.triangles = static_cast<long>(triangles.size());
  for (const auto& t : triangles)
    for (auto c : t)
      if (c >= positions.size()) {
        v.non_manifold_edges = -1;  // not even a triangle list over these positions
        return v;
      }
  count_edges_and_components(triangles, v);
  count_non_manifold_vertices(triangles, positions.size(), v);
  measure_shapes(positions, triangles, v);
  if (v.manifold()) v.self_intersecting_pairs = count_self_intersections(positions, triangles);
  return v;
}

MeshValidity check_mesh_validity(const Mesh48& mesh) {
  std::vector<Vec3> positions(mesh.vertex_capacity(), Vec3::Zero());
  for (std::uint32_t i = 0; i < mesh.vertex_capacity(); ++i)
    if (mesh.is_alive(Vertex(i))) positions[i] = mesh.position(Vertex(i));
  Triangles triangles;
  for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
    if (!mesh.is_alive(Face(f))) continue;
    const auto c = mesh.vertices(Face(f));
    triangles.push_back({c[0].idx, c[1].idx, c[2].idx});
  }
  return check_mesh_validity(positions, triangles);
}

MeshValidity check_mesh_validity(const MeshSnapshot& snapshot) {
  std::vector<Vec3> positions(snapshot.n_vertices());
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = Vec3(snapshot.positions[3 * i], snapshot.positions[3 * i + 1],
                        snapshot.positions[3 * i + 2]);
  Triangles triangles(snapshot.n_triangles());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    triangles[f] = {snapshot.triangles[3 * f], snapshot.triangles[3 * f + 1],
                    snapshot.triangles[3 * f + 2]};
  return check_mesh_validity(positions, triangles);
}

MeshValidity check_mesh_validity_of_file(const std::string& path) {
  const TriangleMesh mesh = read_triangle_mesh(path);
  return check_mesh_validity(mesh.positions, mesh.triangles);
}

}  // namespace dynamesh::test
