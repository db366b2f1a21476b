// A renumbering of a mesh's live elements in random order (tests): unlike
// spatial_renumbering, it moves nearly every element, so a listener that does not follow
// it is caught.
#pragma once

#include <algorithm>
#include <numeric>
#include <random>

#include "core/mesh/mesh48.h"

namespace dynamesh {

inline Renumbering random_renumbering(const Mesh48& mesh, std::mt19937& rng) {
  Renumbering r;
  r.n_vertices = mesh.n_vertices();
  r.n_faces = mesh.n_faces();
  std::vector<std::uint32_t> vertex_ids(r.n_vertices), face_ids(r.n_faces);
  std::iota(vertex_ids.begin(), vertex_ids.end(), 0u);
  std::iota(face_ids.begin(), face_ids.end(), 0u);
  std::shuffle(vertex_ids.begin(), vertex_ids.end(), rng);
  std::shuffle(face_ids.begin(), face_ids.end(), rng);
  r.vertex.assign(mesh.vertex_capacity(), kInvalidIndex);
  r.face.assign(mesh.face_capacity(), kInvalidIndex);
  std::size_t next = 0;
  for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
    if (mesh.is_alive(Vertex(v))) r.vertex[v] = vertex_ids[next++];
  next = 0;
  for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f)
    if (mesh.is_alive(Face(f))) r.face[f] = face_ids[next++];
  return r;
}

}  // namespace dynamesh
