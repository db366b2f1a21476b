// Is a frame an embedded, well-shaped manifold? An independent judge for tests: it reads only
// the plain triangle list and positions (never the mesh's own links or counters) and decides
// self-intersection exactly, with CGAL's exact predicates (Epick), so a fold or a tangle that
// no angle statistic shows is still caught. Tests only: the engine stays free of CGAL.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/adapt/mesh_snapshot.h"
#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"

namespace dynamesh::test {

struct MeshValidity {
  long vertices = 0, triangles = 0, edges = 0;
  long boundary_edges = 0;         // used by one triangle
  long non_manifold_edges = 0;     // used by three or more, or twice in the same direction
  long non_manifold_vertices = 0;  // a vertex whose triangle fan is not one disc or half-disc
  long degenerate_triangles = 0;   // a repeated corner or zero area (exactly collinear corners)
  long components = 0;             // connected through shared edges
  long euler() const { return vertices - edges + triangles; }
  // Pairs of triangles that meet anywhere but a vertex or edge they share; -1 when the
  // triangle list is not a manifold surface (CGAL's test needs a halfedge structure).
  long self_intersecting_pairs = -1;
  double min_angle_deg = 180.0;  // smallest interior angle over all triangles
  double max_aspect = 1.0;       // circumradius over twice the inradius (1 = equilateral)

  bool manifold() const {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 && degenerate_triangles == 0;
  }
  // An embedded closed manifold: what every published frame of a closed surface must be.
  bool embedded_closed_manifold() const {
    return manifold() && boundary_edges == 0 && self_intersecting_pairs == 0;
  }
  // Open surfaces (height fields): the same, with a boundary allowed.
  bool embedded_manifold() const { return manifold() && self_intersecting_pairs == 0; }
  // One line for a failing assertion.
  std::string describe() const;
};

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

MeshValidity check_mesh_validity(const std::vector<Vec3>& positions, const Triangles& triangles);
MeshValidity check_mesh_validity(const Mesh48& mesh);
MeshValidity check_mesh_validity(const MeshSnapshot& snapshot);
// A PLY or OBJ file, as the CLI exports it (read with the project's reader).
MeshValidity check_mesh_validity_of_file(const std::string& path);

}  // namespace dynamesh::test
