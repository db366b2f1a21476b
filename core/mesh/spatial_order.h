// A spatially coherent numbering of a mesh's elements (renumbering.h says why), and a cheap
// measure of how coherent the current one still is.
#pragma once

#include <cstdint>

#include "core/mesh/mesh48.h"
#include "core/mesh/renumbering.h"

namespace dynamesh {

// Faces along a Morton (Z-order) curve of their centroids in the mesh's bounding box, 21
// bits per axis; vertices in the order the faces first use them, so that a pass over the
// faces reads its corners almost sequentially. Live elements only (the result compacts).
Renumbering spatial_renumbering(const Mesh48& mesh);

// Corners of a face further apart than this many vertex ids are "scattered": 4096 positions
// are 96 KB, so the corners of a face within the window share the cache's working set.
inline constexpr std::uint32_t kLocalityWindow = 4096;

// The share of live faces whose corner ids span more than kLocalityWindow, estimated from at
// most ~`probes` face slots spread evenly over the face array (O(probes)). About 0.5 for an
// unordered numbering, a few percent right after spatial_renumbering at 10^5-10^6 faces;
// each split since then adds faces whose new corner was appended far away.
double scattered_face_share(const Mesh48& mesh, std::size_t probes = 8192);

}  // namespace dynamesh
