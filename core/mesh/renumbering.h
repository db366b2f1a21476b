// Renumbering: new ids for a mesh's vertex and face slots (Mesh48::renumber), and how data
// kept per element outside the mesh follows them (MeshListener::after_renumber).
//
// Why: a split takes a free slot or appends one, so after a refinement a face's corners lie
// anywhere in the vertex arrays (on average 270,000 ids apart at 10^6 triangles), and every
// pass over the faces that reads its corners misses the cache at each of them. A numbering
// along a space-filling curve (spatial_order.h) keeps neighbours close in memory: one face
// pass went from 56-70 ms to 16-22 ms at 10^6 triangles (bench_million.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mesh/handles.h"

namespace dynamesh {

// The new id of every old slot (kInvalidIndex for a dead slot). The live elements are
// numbered 0..n-1 with no gaps: after renumbering the mesh has no free slots.
struct Renumbering {
  std::vector<std::uint32_t> vertex;        // indexed by old vertex id
  std::vector<std::uint32_t> face;          // indexed by old face id
  std::size_t n_vertices = 0, n_faces = 0;  // live counts, the new capacities
};

// Moves per-element data (indexed by old id, possibly shorter than the old capacity: a
// listener that has not grown yet) to the new ids; the result has `count` entries, data of
// dead slots dropped, and slots nothing maps to value-initialised.
template <class T>
void renumber_elements(std::vector<T>& data, const std::vector<std::uint32_t>& new_id,
                       std::size_t count) {
  std::vector<T> moved(count);
  const std::size_t n = std::min(data.size(), new_id.size());
  for (std::size_t i = 0; i < n; ++i)
    if (new_id[i] != kInvalidIndex) moved[new_id[i]] = std::move(data[i]);
  data = std::move(moved);
}

// Maps a list of element handles (e.g. a work list) to the new ids, dropping dead ones.
template <class H>
void renumber_handles(std::vector<H>& handles, const std::vector<std::uint32_t>& new_id) {
  std::size_t kept = 0;
  for (const H h : handles)
    if (h.idx < new_id.size() && new_id[h.idx] != kInvalidIndex) handles[kept++] = H(new_id[h.idx]);
  handles.resize(kept);
}

}  // namespace dynamesh
