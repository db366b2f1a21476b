#include "core/topology/triangle_pairing.h"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/max_cardinality_matching.hpp>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

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

using Triangle = std::array<std::uint32_t, 3>;

std::uint64_t directed_key(std::uint32_t from, std::uint32_t to) {
  return (std::uint64_t{from} << 32) | to;
}

bool has_vertex(const Triangle& t, std::uint32_t v) {
  return t[0] == v || t[1] == v || t[2] == v;
}

double smallest_angle(const std::vector<Vec3>& p, const Triangle& t) {
  double smallest = M_PI;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[t[(i + 1) % 3]] - p[t[i]], v = p[t[(i + 2) % 3]] - p[t[i]];
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  return smallest;
}

// across[3 f + i]: the pairable triangle across f's edge (t[i], t[i+1]), or -1.
std::vector<std::int64_t> pairable_neighbours(const std::vector<Triangle>& triangles,
                                              const std::vector<char>& exempt) {
  std::unordered_map<std::uint64_t, std::uint32_t> face_of;
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      face_of[directed_key(triangles[f][i], triangles[f][(i + 1) % 3])] = f;
  std::vector<std::int64_t> across(3 * triangles.size(), -1);
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    if (exempt[f]) continue;
    for (int i = 0; i < 3; ++i) {
      const auto it = face_of.find(directed_key(triangles[f][(i + 1) % 3], triangles[f][i]));
      if (it != face_of.end() && !exempt[it->second]) across[3 * f + i] = it->second;
    }
  }
  return across;
}

// The shortest dual path from the single triangle `from` to another single one, both ends
// included; empty when none is reachable.
std::vector<std::uint32_t> path_to_single(const std::vector<std::int64_t>& across,
                                          const std::vector<std::int64_t>& partner,
                                          std::uint32_t from) {
  std::vector<std::int64_t> previous(partner.size(), -1);
  previous[from] = from;
  std::deque<std::uint32_t> queue{from};
  while (!queue.empty()) {
    const std::uint32_t f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const std::int64_t g = across[3 * f + i];
      if (g < 0 || previous[g] >= 0) continue;
      previous[g] = f;
      if (partner[g] < 0) {
        std::vector<std::uint32_t> path{static_cast<std::uint32_t>(g)};
        while (path.back() != from)
          path.push_back(static_cast<std::uint32_t>(previous[path.back()]));
        std::reverse(path.begin(), path.end());
        return path;
      }
      queue.push_back(static_cast<std::uint32_t>(g));
    }
  }
  return {};
}

// The single triangle `single` shares the edge (a, b) with `next`, whose partner g lies across
// one of next's other edges and the path's next triangle `after` across the third. Flipping
// (a, b), or splitting it, makes a triangle of next's side adjacent to g (paired with it) and
// another adjacent to `after`, which is the new single one (returned; -1 when neither flip nor
// split is acceptable). single = (a, b, c), next = (b, a, d):
//   flip:  (c, a, d) and (d, b, c);
//   split: (a, m, c) + (m, b, c) paired, and (b, m, d), (m, a, d).
std::int64_t pass_on(std::vector<Vec3>& positions, std::vector<Triangle>& triangles,
                     std::vector<char>& exempt, std::vector<std::int64_t>& partner,
                     std::uint32_t single, std::uint32_t next, const PairingMendOptions& options,
                     MendedPairing& out) {
  const Triangle s = triangles[single], n = triangles[next];
  int j = -1;
  for (int i = 0; i < 3 && j < 0; ++i)
    for (int k = 0; k < 3; ++k)
      if (n[k] == s[(i + 1) % 3] && n[(k + 1) % 3] == s[i]) j = i;
  if (j < 0) return -1;
  const std::uint32_t a = s[j], b = s[(j + 1) % 3], c = s[(j + 2) % 3];
  std::uint32_t d = n[0];
  for (const std::uint32_t v : n)
    if (v != a && v != b) d = v;
  const auto g = static_cast<std::uint32_t>(partner[next]);
  const bool g_on_ad = has_vertex(triangles[g], a) && has_vertex(triangles[g], d);
  const auto pair = [&](std::uint32_t x, std::uint32_t y) {
    partner[x] = y;
    partner[y] = x;
  };
  // g, next's old partner, is paired with whichever new triangle it shares an edge with:
  // `on_ad` (the one on edge a-d) or next; the other is the new single one, returned.
  const auto hand_over = [&](std::uint32_t on_ad) -> std::int64_t {
    const std::uint32_t kept = g_on_ad ? on_ad : next, left = g_on_ad ? next : on_ad;
    pair(kept, g);
    partner[left] = -1;
    return left;
  };

  // A flip keeps the count; taken when it makes no edge twice and no worse angle than 20
  // degrees or the quad had.
  bool edge_exists = options.fixed_vertices > c && options.fixed_vertices > d;
  for (std::size_t f = 0; f < triangles.size() && !edge_exists; ++f)
    edge_exists = has_vertex(triangles[f], c) && has_vertex(triangles[f], d);
  const Triangle t1{c, a, d}, t2{d, b, c};
  const double before = std::min(smallest_angle(positions, s), smallest_angle(positions, n));
  if (!edge_exists && options.acceptable(positions, t1) && options.acceptable(positions, t2) &&
      std::min(smallest_angle(positions, t1), smallest_angle(positions, t2)) >=
          std::min(before, 20.0 * M_PI / 180.0)) {
    triangles[single] = t1;
    triangles[next] = t2;
    ++out.flips;
    return hand_over(single);
  }

  const auto m = static_cast<std::uint32_t>(positions.size());
  positions.push_back(options.split_point(positions[a], positions[b]));
  const Triangle p{a, m, c}, q{m, b, c}, r{b, m, d}, w{m, a, d};
  for (const Triangle& t : {p, q, r, w})
    if (!options.acceptable(positions, t)) {
      positions.pop_back();
      return -1;
    }
  const auto Q = static_cast<std::uint32_t>(triangles.size()), W = Q + 1;
  triangles[single] = p;
  triangles[next] = r;
  triangles.push_back(q);
  triangles.push_back(w);
  exempt.resize(triangles.size(), 0);
  partner.resize(triangles.size(), -1);
  ++out.splits;
  pair(single, Q);
  return hand_over(W);
}

}  // namespace

MendedPairing pair_triangles_mending(std::vector<Vec3>& positions,
                                     std::vector<std::array<std::uint32_t, 3>>& triangles,
                                     std::vector<char>& exempt, const PairingMendOptions& options) {
  MendedPairing out;
  std::vector<std::uint32_t> index;
  std::vector<Triangle> pairable;
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    if (!exempt[f]) {
      index.push_back(f);
      pairable.push_back(triangles[f]);
    }
  const std::vector<std::int64_t> matched = pair_triangles(positions, pairable);
  out.partner.assign(triangles.size(), -1);
  for (std::size_t k = 0; k < matched.size(); ++k)
    if (matched[k] >= 0) out.partner[index[k]] = index[static_cast<std::size_t>(matched[k])];

  std::vector<std::int64_t>& partner = out.partner;
  int operations = 0;
  for (;;) {
    std::int64_t single = -1;
    for (std::size_t f = 0; f < triangles.size() && single < 0; ++f)
      if (!exempt[f] && partner[f] < 0) single = static_cast<std::int64_t>(f);
    if (single < 0) {
      out.complete = true;
      return out;
    }
    const std::vector<std::uint32_t> path = path_to_single(
        pairable_neighbours(triangles, exempt), partner, static_cast<std::uint32_t>(single));
    if (path.empty()) return out;  // a single triangle alone in its piece
    // The single triangle walks along the path: across a triangle paired with the path's next
    // one by the alternating swap (free), across any other by a flip or split, until it is
    // next to the other single one.
    std::uint32_t current = path[0];
    for (std::size_t i = 1;;) {
      const std::uint32_t next = path[i];
      if (i + 1 == path.size()) {
        partner[current] = next;
        partner[next] = current;
        break;
      }
      const std::uint32_t after = path[i + 1];
      if (partner[next] == after) {
        partner[current] = next;
        partner[next] = current;
        partner[after] = -1;
        current = after;
        i += 2;
        continue;
      }
      if (++operations > options.max_operations) return out;
      const std::int64_t passed =
          pass_on(positions, triangles, exempt, partner, current, next, options, out);
      if (passed < 0) return out;
      current = static_cast<std::uint32_t>(passed);
      i += 1;
    }
  }
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
