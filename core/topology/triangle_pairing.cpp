#include "core/topology/triangle_pairing.h"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/max_cardinality_matching.hpp>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace dynamesh {

namespace {

struct SharedEdge {
  double length;
  std::uint32_t a, b;  // the two triangles
};

std::vector<SharedEdge> shared_edges(const std::vector<Vec3>& positions,
                                     const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::unordered_map<std::uint64_t, std::uint32_t> face_of;  // directed edge -> face
  face_of.reserve(3 * triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t key = (std::uint64_t{triangles[f][i]} << 32) | triangles[f][(i + 1) % 3];
      if (!face_of.emplace(key, f).second)
        throw std::invalid_argument(
            "pairing: an edge is used twice in the same direction (non-manifold or "
            "inconsistently oriented)");
    }
  std::vector<SharedEdge> edges;
  edges.reserve(3 * triangles.size() / 2);
  for (const auto& [key, f] : face_of) {
    const auto from = static_cast<std::uint32_t>(key >> 32), to = static_cast<std::uint32_t>(key);
    if (from > to) continue;
    const auto it = face_of.find((std::uint64_t{to} << 32) | from);
    if (it == face_of.end() || it->second == f) continue;
    edges.push_back({(positions[from] - positions[to]).norm(), f, it->second});
  }
  // Longest first; ties broken by face ids so that the result does not depend on hashing.
  std::sort(edges.begin(), edges.end(), [](const SharedEdge& x, const SharedEdge& y) {
    return std::tie(y.length, x.a, x.b) < std::tie(x.length, y.a, y.b);
  });
  return edges;
}

}  // namespace

std::vector<std::int64_t> pair_triangles(
    const std::vector<Vec3>& positions,
    const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const std::vector<SharedEdge> edges = shared_edges(positions, triangles);
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  using GraphVertex = boost::graph_traits<Graph>::vertex_descriptor;
  Graph dual(triangles.size());
  for (const SharedEdge& e : edges) boost::add_edge(e.a, e.b, dual);

  const GraphVertex none = boost::graph_traits<Graph>::null_vertex();
  std::vector<GraphVertex> mate(triangles.size(), none);
  for (const SharedEdge& e : edges)
    if (mate[e.a] == none && mate[e.b] == none) mate[e.a] = e.b, mate[e.b] = e.a;

  // Augment the greedy matching to a maximum one.
  const auto index = boost::get(boost::vertex_index, dual);
  boost::edmonds_augmenting_path_finder<Graph, GraphVertex*, decltype(index)> augment(
      dual, mate.data(), index);
  while (augment.augment_matching()) {
  }
  augment.get_current_matching(mate.data());

  std::vector<std::int64_t> partner(triangles.size(), -1);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    if (mate[f] != none) partner[f] = static_cast<std::int64_t>(mate[f]);
  return partner;
}

namespace {

// Local index i of f's edge (f[i+1], f[i+2]) that g has reversed.
int shared_edge(const std::array<std::uint32_t, 3>& f, const std::array<std::uint32_t, 3>& g) {
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t a = f[(i + 1) % 3], b = f[(i + 2) % 3];
    for (int j = 0; j < 3; ++j)
      if (g[j] == b && g[(j + 1) % 3] == a) return i;
  }
  return -1;
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> refinement_edge_first(
    const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const std::vector<std::int64_t>& partner) {
  std::vector<std::array<std::uint32_t, 3>> rotated(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    const int i =
        partner[f] < 0 ? -1 : shared_edge(t, triangles[static_cast<std::size_t>(partner[f])]);
    if (i < 0) throw std::logic_error("pairing: a triangle shares no edge with its partner");
    rotated[f] = {t[i], t[(i + 1) % 3], t[(i + 2) % 3]};
  }
  return rotated;
}

}  // namespace dynamesh
