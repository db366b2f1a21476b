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
#include <functional>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh {

// partner[f] is the triangle paired with f, or -1 when f is left unpaired (only possible on
// an open mesh or a component with an odd number of triangles). Throws std::invalid_argument
// for non-manifold or inconsistently oriented input.
std::vector<std::int64_t> pair_triangles(
    const std::vector<Vec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles);

// Mending a pairing of an open patch (a local repair's new triangles: triangle_pairing.cpp
// explains the walk). A triangulated disk's dual graph is not cubic and bridgeless, so its
// triangles often have no perfect matching (Petersen's theorem is about closed meshes); the
// maximum matching leaves a few triangles single, and edge flips or edge splits along a dual
// path between two single triangles pass the single one along until it meets the other.
struct PairingMendOptions {
  // Where the vertex splitting the edge (a, b) goes (e.g. its midpoint moved onto F).
  std::function<Vec3(const Vec3& a, const Vec3& b)> split_point;
  // Whether a triangle of the mended patch may be made (e.g. it faces along grad F).
  std::function<bool(const std::vector<Vec3>& positions, const std::array<std::uint32_t, 3>& t)>
      acceptable;
  // Vertices below this id are shared with the rest of a mesh, where an edge between two of
  // them may exist already: no flip makes such an edge.
  std::uint32_t fixed_vertices = 0;
  int max_operations = 256;
};

struct MendedPairing {
  std::vector<std::int64_t> partner;  // -1 for the exempt triangles (and if not complete)
  bool complete = false;              // every triangle not exempt has a partner
  int flips = 0, splits = 0;
};

// Pairs the triangles whose `exempt` flag is 0 among themselves (exempt ones take no partner
// and are never changed), flipping and splitting edges between pairable triangles (appending
// the new vertices to `positions`, the new triangles to `triangles`, not exempt) until every
// one has a partner or no flip or split is acceptable.
MendedPairing pair_triangles_mending(std::vector<Vec3>& positions,
                                     std::vector<std::array<std::uint32_t, 3>>& triangles,
                                     std::vector<char>& exempt, const PairingMendOptions& options);

// The triangles rotated newest vertex first, (apex, a, b), so that the edge (a, b) each shares
// with its partner is its refinement edge (Mesh48::from_base_triangles' convention). Every
// triangle must have a partner.
std::vector<std::array<std::uint32_t, 3>> refinement_edge_first(
    const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const std::vector<std::int64_t>& partner);

}  // namespace dynamesh
