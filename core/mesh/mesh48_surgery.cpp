// Mesh48::replace_region: cutting a region out of the mesh and filling the hole with new base
// triangles (issue 16, local repair of a topology change). Kept apart from the stellar
// operators in mesh48.cpp: surgery is rare (once per event) and may cost O(mesh).
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/mesh/mesh48.h"

namespace dynamesh {

namespace {

std::uint64_t directed(std::uint32_t from, std::uint32_t to) {
  return (std::uint64_t{from} << 32) | to;
}

}  // namespace

std::vector<Vertex> Mesh48::replace_region(
    const std::vector<Face>& removed, const std::vector<Vertex>& existing,
    const std::vector<Vec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const std::vector<int>& depths) {
  const auto fail = [](const std::string& what) {
    throw std::logic_error("replace_region: " + what);
  };
  std::vector<char> gone(faces_.size(), 0);
  for (const Face f : removed) {
    if (f.idx >= faces_.size() || !is_alive(f)) fail("a removed face is not alive");
    gone[f.idx] = 1;
  }
  // Ids the new vertices will have are not known before allocation: validate over provisional
  // ones past the capacity.
  const std::size_t n_existing = existing.size();
  const auto provisional = [&](std::uint32_t i) {
    return i < n_existing ? existing[i].idx
                          : static_cast<std::uint32_t>(vertex_face_.size() + (i - n_existing));
  };
  for (const Vertex v : existing)
    if (v.idx >= vertex_face_.size() || !is_alive(v)) fail("an existing vertex is not alive");
  // The hole's border: halfedges of remaining faces whose neighbour is removed.
  std::unordered_map<std::uint64_t, std::uint32_t> border;
  for (const Face f : removed)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t t = faces_[f.idx].twin[i];
      if (t == kInvalidIndex || gone[t / 3]) continue;
      const Halfedge h(t);
      border.emplace(directed(from_vertex(h).idx, to_vertex(h).idx), t);
    }
  if (!depths.empty() && depths.size() != triangles.size()) fail("one depth per triangle");
  const auto depth_of = [&](std::size_t k) { return depths.empty() ? 0 : depths[k]; };
  std::unordered_map<std::uint64_t, std::uint32_t> inner;  // new halfedges: 3 * triangle + i
  for (std::uint32_t k = 0; k < triangles.size(); ++k) {
    const auto& t = triangles[k];
    for (int i = 0; i < 3; ++i) {
      if (t[i] >= n_existing + positions.size()) fail("a triangle refers to an unknown vertex");
      if (t[i] == t[(i + 1) % 3]) fail("a triangle repeats a vertex");
      const std::uint64_t key = directed(provisional(t[(i + 1) % 3]), provisional(t[(i + 2) % 3]));
      if (!inner.emplace(key, 3 * k + i).second) fail("an edge is used twice in one direction");
    }
  }
  std::size_t matched = 0;
  for (const auto& [key, h] : inner) {
    const std::uint64_t reverse = (key << 32) | (key >> 32);
    const auto it = inner.find(reverse);
    if (it != inner.end()) {
      if ((h % 3 == 0) != (it->second % 3 == 0)) fail("a refinement edge is not shared");
      continue;
    }
    const auto bt = border.find(reverse);
    if (bt == border.end()) fail("an edge is neither shared nor on the border");
    // A refinement edge on the border is a diamond of an old face and a new one, alike deep,
    // or a new half diamond against an old face one bisection coarser, whose leg it is.
    const int old_depth = faces_[bt->second / 3].depth, new_depth = depth_of(h / 3);
    if (bt->second % 3 == 0) {
      if (h % 3 != 0) fail("an old face's refinement edge on the border is not shared");
      if (old_depth != new_depth)
        fail("a diamond across the border joins faces of different depths");
    } else if (h % 3 == 0 ? old_depth + 1 != new_depth : old_depth != new_depth) {
      fail("the faces across the border are not as deep as the 4-8 rule wants");
    }
    ++matched;
  }
  if (matched != border.size()) fail("the triangles do not close the hole");

  // Which vertices of the removed faces die: no remaining face, no new triangle.
  std::vector<char> used(vertex_face_.size(), 0);
  for (const auto& t : triangles)
    for (const std::uint32_t i : t)
      if (i < n_existing) used[existing[i].idx] = 1;
  std::vector<std::uint32_t> dying;
  for (const Face f : removed)
    for (const Vertex v : vertices(f)) {
      if (used[v.idx]) continue;
      bool keeps_a_face = false;
      for_each_corner_around(v,
                             [&](Corner c) { keeps_a_face = keeps_a_face || !gone[c.face.idx]; });
      if (keeps_a_face) fail("a border vertex is not used by the new triangles");
      used[v.idx] = 2;
      dying.push_back(v.idx);
    }

  // Apply.
  for (const Face f : removed) {
    FaceRecord& r = faces_[f.idx];
    std::fill(std::begin(r.v), std::end(r.v), kInvalidIndex);
    std::fill(std::begin(r.twin), std::end(r.twin), kInvalidIndex);
    free_faces_.push_back(f.idx);
    --n_live_faces_;
  }
  for (const std::uint32_t v : dying) {
    vertex_face_[v] = kInvalidIndex;
    lineage_[v] = Lineage{};
    free_vertices_.push_back(v);
    --n_live_vertices_;
  }
  // Split-born vertices whose parents died can no longer be welded either (before the new
  // vertices reuse the dead ids).
  for (std::uint32_t v = 0; v < vertex_face_.size(); ++v) {
    if (vertex_face_[v] == kInvalidIndex || lineage_[v].parent_a == kInvalidIndex) continue;
    if (vertex_face_[lineage_[v].parent_a] == kInvalidIndex ||
        vertex_face_[lineage_[v].parent_b] == kInvalidIndex)
      lineage_[v] = Lineage{};
  }
  std::vector<std::uint32_t> id(n_existing + positions.size());
  for (std::size_t i = 0; i < n_existing; ++i) id[i] = existing[i].idx;
  std::vector<Vertex> created;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::uint32_t v = allocate_vertex();
    positions_[v] = positions[i];
    uvs_[v] = Vec2::Zero();
    lineage_[v] = Lineage{};
    id[n_existing + i] = v;
    created.emplace_back(v);
  }
  std::vector<std::uint32_t> face_of(triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const auto& t = triangles[k];
    face_of[k] = allocate_face();
    set_face(face_of[k], id[t[0]], id[t[1]], id[t[2]], static_cast<std::uint8_t>(depth_of(k)));
    std::fill(std::begin(faces_[face_of[k]].twin), std::end(faces_[face_of[k]].twin),
              kInvalidIndex);
    for (const std::uint32_t i : t) {
      vertex_face_[id[i]] = face_of[k];
      // Border vertices lose their lineage: a weld would restore an edge that is gone.
      if (i < n_existing) lineage_[id[i]] = Lineage{};
    }
  }
  for (const auto& [key, h] : inner) {
    const std::uint64_t reverse = (key << 32) | (key >> 32);
    const auto it = inner.find(reverse);
    const std::uint32_t twin =
        it != inner.end() ? 3 * face_of[it->second / 3] + it->second % 3 : border.at(reverse);
    link(face_of[h / 3], static_cast<int>(h % 3), twin);
  }
  // Every vertex of the new triangles must be one fan (no pinch where two loops of the border
  // met at a vertex): O(mesh), once per event.
  std::vector<int> corners(vertex_face_.size(), 0);
  for (const FaceRecord& r : faces_)
    if (r.v[0] != kInvalidIndex)
      for (const std::uint32_t v : r.v) ++corners[v];
  for (const auto& t : triangles)
    for (const std::uint32_t i : t) {
      int fan = 0;
      for_each_corner_around(Vertex(id[i]), [&](Corner) { ++fan; });
      if (fan != corners[id[i]])
        fail("vertex " + std::to_string(id[i]) + " is not one fan (the mesh is now unusable)");
    }
  return created;
}

}  // namespace dynamesh
