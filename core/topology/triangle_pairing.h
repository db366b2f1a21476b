// Pairing the triangles of a closed manifold mesh across shared edges, so that each pair is a
// quad whose shared edge (its diagonal) becomes the refinement edge of both triangles: a
// triangulated quadrangulation, the base a 4-8 mesh needs (DESIGN.md, "The 4-8 mesh").
// A pairing is a perfect matching of the dual graph; one exists on every closed manifold
// triangle mesh, whose dual graph is cubic and bridgeless (Petersen's theorem). Triangles are
// first paired greedily across their longest shared edges (a quad's diagonal is its longest
// edge when its triangles are well shaped), then Edmonds' augmenting paths
// (boost::edmonds_augmenting_path_finder) complete the matching.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh {

// partner[f] is the triangle paired with f, or -1 when f is left unpaired (only possible on
// an open mesh or a component with an odd number of triangles). Throws std::invalid_argument
// for non-manifold or inconsistently oriented input.
std::vector<std::int64_t> pair_triangles(
    const std::vector<Vec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles);

// The triangles rotated newest vertex first, (apex, a, b), so that the edge (a, b) each shares
// with its partner is its refinement edge (Mesh48::from_base_triangles' convention). Every
// triangle must have a partner.
std::vector<std::array<std::uint32_t, 3>> refinement_edge_first(
    const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const std::vector<std::int64_t>& partner);

}  // namespace dynamesh
