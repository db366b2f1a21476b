// Mesh48::renumber: every live element moved to the id a Renumbering gives it (renumbering.h).
#include <stdexcept>
#include <string>

#include "core/mesh/mesh48.h"

namespace dynamesh {
namespace {

// True when `new_id` maps exactly the live slots (is_alive(i)) one to one onto 0..count-1.
template <class Alive>
bool is_compacting_bijection(const std::vector<std::uint32_t>& new_id, std::size_t capacity,
                             std::size_t count, Alive alive) {
  if (new_id.size() != capacity) return false;
  std::vector<char> taken(count, 0);
  for (std::size_t i = 0; i < capacity; ++i) {
    const std::uint32_t j = new_id[i];
    if (!alive(i)) {
      if (j != kInvalidIndex) return false;
      continue;
    }
    if (j >= count || taken[j]) return false;
    taken[j] = 1;
  }
  return true;
}

}  // namespace

void Mesh48::renumber(const Renumbering& r) {
  const auto& nv = r.vertex;
  const auto& nf = r.face;
  if (r.n_vertices != n_live_vertices_ || r.n_faces != n_live_faces_ ||
      !is_compacting_bijection(nv, vertex_capacity(), n_live_vertices_,
                               [&](std::size_t i) { return vertex_face_[i] != kInvalidIndex; }) ||
      !is_compacting_bijection(nf, face_capacity(), n_live_faces_,
                               [&](std::size_t i) { return faces_[i].v[0] != kInvalidIndex; }))
    throw std::invalid_argument(
        "Mesh48::renumber: not a one-to-one map of the live elements onto 0..n-1");

  std::vector<FaceRecord> faces(n_live_faces_);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    if (nf[f] == kInvalidIndex) continue;
    const FaceRecord& old = faces_[f];
    FaceRecord& rec = faces[nf[f]];
    rec.depth = old.depth;
    for (int i = 0; i < 3; ++i) {
      rec.v[i] = nv[old.v[i]];
      const std::uint32_t t = old.twin[i];
      rec.twin[i] = t == kInvalidIndex ? kInvalidIndex : 3 * nf[t / 3] + t % 3;
    }
  }
  std::vector<std::uint32_t> vertex_face(n_live_vertices_);
  std::vector<Lineage> lineage(n_live_vertices_);
  for (std::size_t v = 0; v < vertex_face_.size(); ++v) {
    if (nv[v] == kInvalidIndex) continue;
    vertex_face[nv[v]] = nf[vertex_face_[v]];
    Lineage l = lineage_[v];
    if (l.parent_a != kInvalidIndex) {
      // A split-born vertex's parents outlive it (neither can be welded first).
      if (nv[l.parent_a] == kInvalidIndex || nv[l.parent_b] == kInvalidIndex)
        throw std::logic_error("Mesh48::renumber: vertex " + std::to_string(v) +
                               " has a dead parent");
      l.parent_a = nv[l.parent_a];
      l.parent_b = nv[l.parent_b];
    }
    lineage[nv[v]] = l;
  }
  faces_ = std::move(faces);
  vertex_face_ = std::move(vertex_face);
  lineage_ = std::move(lineage);
  renumber_elements(positions_, nv, n_live_vertices_);
  renumber_elements(uvs_, nv, n_live_vertices_);
  free_faces_.clear();
  free_vertices_.clear();
  for (MeshListener* l : listeners_) l->after_renumber(*this, r);
}

}  // namespace dynamesh
