#include "core/topology/local_repair.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "core/geometry/nearest_triangle.h"
#include "core/surface/projection.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/triangle_pairing.h"

namespace dynamesh {

namespace {

using Triangle = std::array<std::uint32_t, 3>;
using Loop = std::vector<std::uint32_t>;  // vertex ids in the order of their halfedges

// Loops of the directed edges (from -> to): empty when some vertex starts two of them (a
// pinched border, two loops through one vertex).
std::vector<Loop> loops_of(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  for (const auto& [a, b] : edges)
    if (!next.emplace(a, b).second) return {};
  std::vector<Loop> loops;
  std::unordered_map<std::uint32_t, char> seen;
  for (const auto& [a, b] : edges) {
    if (seen.count(a)) continue;
    Loop loop;
    std::uint32_t v = a;
    while (!seen.count(v)) {
      seen[v] = 1;
      loop.push_back(v);
      const auto it = next.find(v);
      if (it == next.end()) return {};  // open: not a loop
      v = it->second;
    }
    if (v != a) return {};
    loops.push_back(std::move(loop));
  }
  return loops;
}

// The cut faces, in slot order (an attempt's copy only gains faces: every flagged slot is live).
std::vector<Face> cut_faces(const std::vector<char>& cut) {
  std::vector<Face> faces;
  for (std::size_t i = 0; i < cut.size(); ++i)
    if (cut[i]) faces.emplace_back(static_cast<std::uint32_t>(i));
  return faces;
}

// The faces to cut, closed so that no remaining face has its refinement edge on the border.
// A worklist from the cut faces: a face whose refinement edge borders a cut face g is one of g's
// three neighbours. Sweeping every face of the mesh until none changed cost a sweep per face
// along the longest chain of refinement edges, and with level_border's rounds it was 71% of
// CliHostile's ripple (a repair_locally of 9-40 s on 52,000-67,000 faces) before the patches
// spread too widely were no longer tried.
void close_cut(const Mesh48& mesh, std::vector<char>& cut) {
  std::vector<Face> work = cut_faces(cut);
  while (!work.empty()) {
    const Face g = work.back();
    work.pop_back();
    for (int i = 0; i < 3; ++i) {
      const Face f = mesh.neighbor(g, i);
      if (f.is_valid() && !cut[f.idx] && mesh.neighbor(f, 0) == g) {
        cut[f.idx] = 1;
        work.push_back(f);
      }
    }
  }
}

// The new triangles all get one depth D: inside a piece of the patch every edge is a pair's
// refinement edge or a leg shared by two faces, so the piece has one depth. Across the seam
// (the old faces' legs, by the closure) the 4-8 rule (Mesh48::check) wants the old face alike
// deep, or one coarser when the new triangle's refinement edge lies on the seam (a half
// diamond whose partner the next split of it forces on the old side). So the border is cut
// down until its faces are of two adjacent depths at most -- the issue's "weld the region
// down": where the old side is finer than the patch it is cut away and the queues refine it
// again. Returns whether the cut grew.
// The border's faces are found from the cut's side (the remaining neighbours of cut faces, some
// more than once), not by a sweep over every face of the mesh.
bool level_border(const Mesh48& mesh, std::vector<char>& cut) {
  bool any = false;
  std::vector<Face> border;
  for (;;) {
    int coarsest = -1;
    border.clear();
    for (const Face g : cut_faces(cut))
      for (int i = 0; i < 3; ++i) {
        const Face f = mesh.neighbor(g, i);
        if (!f.is_valid() || cut[f.idx]) continue;
        border.push_back(f);
        const int d = mesh.depth(f);
        if (coarsest < 0 || d < coarsest) coarsest = d;
      }
    bool grew = false;
    for (const Face f : border)
      if (mesh.depth(f) > coarsest + 1) cut[f.idx] = grew = 1;
    if (!grew) return any;
    any = true;
    close_cut(mesh, cut);
  }
}

std::uint64_t edge_key(std::uint32_t from, std::uint32_t to) {
  return (std::uint64_t{from} << 32) | to;
}

// Calls visit(face, from, to) for every border halfedge: a halfedge of a remaining face whose
// neighbour is cut.
template <class Visit>
void for_each_border_halfedge(const Mesh48& mesh, const std::vector<char>& cut, Visit visit) {
  for (const Face f : mesh.live_faces()) {
    if (cut[f.idx]) continue;
    for (int i = 0; i < 3; ++i) {
      const Face across = mesh.neighbor(f, i);
      if (!across.is_valid() || !cut[across.idx]) continue;
      const Halfedge h(3 * f.idx + static_cast<std::uint32_t>(i));
      visit(f, mesh.from_vertex(h).idx, mesh.to_vertex(h).idx);
    }
  }
}

// The depth of the remaining face on each border halfedge (from, to).
std::unordered_map<std::uint64_t, int> border_depths(const Mesh48& mesh,
                                                     const std::vector<char>& cut) {
  std::unordered_map<std::uint64_t, int> depth;
  for_each_border_halfedge(mesh, cut, [&](Face f, std::uint32_t from, std::uint32_t to) {
    depth[edge_key(from, to)] = mesh.depth(f);
  });
  return depth;
}

int patch_depth(const std::unordered_map<std::uint64_t, int>& depths) {
  int d = 0;
  for (const auto& [edge, depth] : depths) d = std::max(d, depth);
  return d;
}

// The loops whose new triangles cannot all be paired: a loop's side holds as many new
// triangles as the loop has edges, modulo 2 (a disk), and one per edge of a coarser old
// face is a half diamond, left out of the pairing; the rest must be even.
std::ptrdiff_t odd_loops(const Mesh48& mesh, const std::vector<char>& cut,
                         const std::vector<Loop>& loops) {
  const auto depths = border_depths(mesh, cut);
  const int d = patch_depth(depths);
  std::ptrdiff_t odd = 0;
  for (const Loop& loop : loops) {
    std::size_t at_depth = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const auto it = depths.find(edge_key(loop[k], loop[(k + 1) % loop.size()]));
      at_depth += it != depths.end() && it->second == d;
    }
    odd += at_depth % 2;
  }
  return odd;
}

// Where the border passes twice through one vertex (the cut touches itself there, as it can
// around coarse faces next to the event) the loops are not simple: the vertex's whole fan is
// cut too, then the cut is closed and levelled again. Returns whether anything was pinched.
bool unpinch(const Mesh48& mesh, std::vector<char>& cut) {
  std::unordered_map<std::uint32_t, int> starts;
  for_each_border_halfedge(mesh, cut,
                           [&](Face, std::uint32_t from, std::uint32_t) { ++starts[from]; });
  bool pinched = false;
  for (const auto& [v, count] : starts) {
    if (count < 2) continue;
    pinched = true;
    mesh.for_each_corner_around(Vertex(v), [&](Corner c) { cut[c.face.idx] = 1; });
  }
  if (!pinched) return false;
  close_cut(mesh, cut);
  level_border(mesh, cut);
  return true;
}

// Remaining faces that the cut encloses: a piece of the remaining mesh (faces joined across
// edges) that lies wholly within the cut's reach from the event and has at most a sixteenth of
// the cut's faces. Levelling grows the cut around coarse faces, which it keeps, and leaves such
// islands (a single diamond, whose border is a loop of 4 edges, inside a cut of 738 faces
// around the wide blobs' thinning neck): the patch has no loop for them, and the repair was
// refused. They are cut too. (A larger piece within reach is what is left of a small blob at
// a merge, 2 folds when it was cut as well: the blobs along x in 20 steps.) Returns whether
// any was found.
bool cut_islands(const Mesh48& mesh, std::vector<char>& cut, const Vec3& centre) {
  double reach = 0;
  std::size_t cut_faces = 0;
  for (const Face f : mesh.live_faces()) {
    if (!cut[f.idx]) continue;
    ++cut_faces;
    for (const Vertex v : mesh.vertices(f))
      reach = std::max(reach, (mesh.position(v) - centre).norm());
  }
  std::vector<char> seen(cut.size(), 0);
  std::vector<Face> piece, stack;
  bool found = false;
  for (const Face start : mesh.live_faces()) {
    if (cut[start.idx] || seen[start.idx]) continue;
    piece.clear();
    stack.assign(1, start);
    seen[start.idx] = 1;
    bool within = true;
    while (!stack.empty()) {
      const Face f = stack.back();
      stack.pop_back();
      piece.push_back(f);
      for (const Vertex v : mesh.vertices(f))
        within = within && (mesh.position(v) - centre).norm() <= reach;
      for (int i = 0; i < 3; ++i) {
        const Face n = mesh.neighbor(f, i);
        if (n.is_valid() && !cut[n.idx] && !seen[n.idx]) {
          seen[n.idx] = 1;
          stack.push_back(n);
        }
      }
    }
    if (!within || 16 * piece.size() > cut_faces) continue;
    for (const Face f : piece) cut[f.idx] = 1;
    found = true;
  }
  return found;
}

using SplitPlacement = std::function<void(Mesh48&, const DiamondChange&)>;

// Puts a split's new vertex where `place` does, or (empty) at split_point_on_surface.
void place_split(Mesh48& mesh, const DiamondChange& change, const SplitPlacement& place,
                 const ImplicitSurface& surface) {
  if (place) {
    place(mesh, change);
  } else {
    mesh.position(change.vertex) = split_point_on_surface(surface, mesh.position(change.parents[0]),
                                                          mesh.position(change.parents[1]));
  }
}

// The splits an attempt makes (levelling its border up, mending a loop's parity), made on a
// copy of the mesh that tells no listener: they are recorded in order and made again on the
// mesh itself only when the attempt succeeds, so that a failed attempt leaves the mesh as it was
// (on Colin27 and on the dumbbell after motion9 every attempt of the ladder failed, and each
// could split diamonds that stayed). As they happen, a split face's new child takes its cut
// flag (children[0] keeps the parent's slot, Mesh48.h) and the new vertex is placed by the
// caller's rule (LocalRepairOptions::place_split_vertex), the one the mesh's listeners apply
// when the splits are made again: the plan is made on the positions the mesh will have.
class TrialSplits : public MeshListener {
 public:
  TrialSplits(const ImplicitSurface& surface, const SplitPlacement& place, std::vector<char>& cut)
      : surface_(surface), place_(place), cut_(cut) {}
  Vertex split(Mesh48& mesh, Face f) {
    const Vertex v = mesh.split(f);  // after_split below grows the cut flags
    if (v.is_valid()) faces.push_back(f);
    return v;
  }
  void after_split(Mesh48& mesh, const DiamondChange& change) override {
    cut_.resize(mesh.face_capacity(), 0);
    for (int h = 0; h < change.count; ++h) {
      const Bisection& b = change.halves[static_cast<std::size_t>(h)];
      cut_[b.children[1].idx] = cut_[b.children[0].idx];
    }
    place_split(mesh, change, place_, surface_);
    born.push_back(change.vertex);
    born_at.push_back(mesh.position(change.vertex));
  }
  void after_weld(Mesh48&, const DiamondChange&) override {}
  void after_renumber(Mesh48&, const Renumbering&) override {}
  std::vector<Face> faces;    // given to split(), in order
  std::vector<Vertex> born;   // every split's vertex (those split() forced first included)
  std::vector<Vec3> born_at;  // where each was put (a vertex in the cut is gone after the surgery)

 private:
  const ImplicitSurface& surface_;
  const SplitPlacement& place_;
  std::vector<char>& cut_;
};

// The other way to level the border (level_border): its faces more than one bisection coarser
// than the deepest are split, until none is. Needed where the faces next to the event are the
// coarse ones: after motion9's smoothing the dumbbell's neck was covered by base faces (depth 0)
// among faces of depth 2, and cutting the deep ones spread the cut over 226 of the mesh's 408
// faces, with 4 or 5 border loops against the contour's 2. Returns whether the border is level.
bool raise_border(Mesh48& mesh, std::vector<char>& cut, TrialSplits& splits) {
  constexpr int kMaxRounds = 8;
  for (int round = 0; round < kMaxRounds; ++round) {
    int deepest = -1;
    std::vector<Face> border;
    for (const Face f : mesh.live_faces()) {
      if (cut[f.idx]) continue;
      for (int i = 0; i < 3; ++i) {
        const Face across = mesh.neighbor(f, i);
        if (!across.is_valid() || !cut[across.idx]) continue;
        border.push_back(f);
        deepest = std::max(deepest, mesh.depth(f));
        break;
      }
    }
    bool split = false;
    for (const Face f : border)
      if (!cut[f.idx] && mesh.depth(f) + 1 < deepest && splits.split(mesh, f).is_valid())
        split = true;
    if (!split) return true;
    close_cut(mesh, cut);  // a child's refinement edge may lie on the border
  }
  return false;
}

// Border halfedges (of remaining faces whose neighbour is cut) as (from, to) vertex ids.
std::vector<std::pair<std::uint32_t, std::uint32_t>> border_of(const Mesh48& mesh,
                                                               const std::vector<char>& cut) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for_each_border_halfedge(
      mesh, cut, [&](Face, std::uint32_t from, std::uint32_t to) { edges.emplace_back(from, to); });
  return edges;
}

Vec3 centroid(const std::vector<Vec3>& positions, const Loop& loop) {
  Vec3 c = Vec3::Zero();
  for (const std::uint32_t v : loop) c += positions[v];
  return c / static_cast<double>(loop.size());
}

// Indices into a and b of the closest pair of vertices between the two loops: where zipping starts.
std::pair<std::size_t, std::size_t> nearest_pair(const std::vector<Vec3>& positions, const Loop& a,
                                                 const Loop& b) {
  std::size_t i0 = 0, j0 = 0;
  double nearest = HUGE_VAL;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double d = (positions[a[i]] - positions[b[j]]).squaredNorm();
      if (d < nearest) nearest = d, i0 = i, j0 = j;
    }
  return {i0, j0};
}

// Zips the border loop `a` (halfedges a_k -> a_k+1 of remaining faces) to the patch loop `b`
// (halfedges b_k -> b_k+1 of patch triangles): the strip holds every a_k+1 -> a_k and
// b_k+1 -> b_k, walking `a` backwards and `b` forwards (the same way round) from their
// nearest pair of vertices, each step advancing the loop that is behind in arc length (the
// classic contour-stitching rule: the two loops differ in sampling, so shortest rungs alone
// would fan one vertex over half the other loop).
void zip(const std::vector<Vec3>& positions, const Loop& a, const Loop& b,
         std::vector<Triangle>& out) {
  const std::size_t na = a.size(), nb = b.size();
  const auto [first_a, first_b] = nearest_pair(positions, a, b);
  const std::size_t i0 = first_a, j0 = first_b;
  const auto A = [&](std::size_t s) { return a[(i0 + na - s % na) % na]; };  // backwards
  const auto B = [&](std::size_t s) { return b[(j0 + s) % nb]; };
  // How far round each loop each vertex is, as a fraction of the whole turn about the border
  // loop's axis (its vector area) through its centroid: unlike arc length, the turn does not
  // depend on how jagged or finely sampled a loop is. Arc length when a loop does not wind
  // once about that axis.
  Vec3 axis = Vec3::Zero(), centre = Vec3::Zero();
  for (std::size_t i = 0; i < na; ++i) {
    axis += positions[a[i]].cross(positions[a[(i + 1) % na]]);
    centre += positions[a[i]];
  }
  centre /= static_cast<double>(na);
  axis.normalize();
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const auto angle = [&](std::uint32_t v) {
    const Vec3 d = positions[v] - centre;
    return std::atan2(d.dot(e2), d.dot(e1));
  };
  const auto fractions = [&](std::size_t n, const auto& at) {
    std::vector<double> f(n + 1, 0.0), length(n + 1, 0.0);
    for (std::size_t s = 0; s < n; ++s) {
      double d = angle(at(s + 1)) - angle(at(s));
      d -= 2 * M_PI * std::round(d / (2 * M_PI));
      f[s + 1] = f[s] + d;
      length[s + 1] = length[s] + (positions[at(s + 1)] - positions[at(s)]).norm();
    }
    if (std::abs(std::abs(f[n]) - 2 * M_PI) > 0.5) {
      for (std::size_t s = 0; s <= n; ++s) f[s] = length[s] / std::max(length[n], 1e-300);
      return f;
    }
    const double total = f[n];
    double high = 0;
    for (double& x : f) x = high = std::clamp(std::max(high, x / total), 0.0, 1.0);
    return f;
  };
  const std::vector<double> fa = fractions(na, A), fb = fractions(nb, B);
  std::size_t sa = 0, sb = 0;
  while (sa < na || sb < nb) {
    if (sb == nb || (sa < na && fa[sa + 1] <= fb[sb + 1])) {
      out.push_back({A(sa), A(sa + 1), B(sb)});
      ++sa;
    } else {
      out.push_back({B(sb + 1), B(sb), A(sa)});
      ++sb;
    }
  }
}

struct Patch {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Loop> loops;
};

// F's contour (F = the level `level_rule` gives, if any: LocalRepairOptions::contour_level) on
// a grid of `h` with a grid point on `centre`, reaching `reach` from it: the triangles whose
// every corner is `inside`; empty loops and triangles when its border is pinched.
int patch_grid_half_cells(double reach, double h) {
  return static_cast<int>(std::ceil((reach + h) / h));
}
std::size_t patch_grid_cells(double reach, double h) {
  const auto side = static_cast<std::size_t>(2 * patch_grid_half_cells(reach, h));
  return side * side * side;
}

using ContourLevel = std::function<double(const Box3&, double)>;

template <class Inside>
Patch contour_patch(const ImplicitSurface& surface, const Vec3& centre, double reach, double h,
                    const Inside& inside_hole, const ContourLevel& level_rule) {
  const int n = patch_grid_half_cells(reach, h);
  ContourGrid grid;
  grid.box.min = centre - Vec3::Constant(n * h);
  grid.box.max = centre + Vec3::Constant(n * h);
  grid.cells = {2 * n, 2 * n, 2 * n};
  const double level = level_rule ? level_rule(grid.box, std::sqrt(3.0) * h) : 0.0;
  constexpr double kMargin = 0.05;
  // F zero to within rounding at a grid point counts as outside, as the event monitor counts a
  // critical point (topology_events.cpp): at an event on a step time the point on the event is
  // the double cone's tip, and the rounding of F there must not keep a neck the monitor
  // reported gone (the torus pinched at t = 0.75). That alone is not enough: the grid's points
  // beside the tip lie within its resolution of zero too, on either side (the torus pinched
  // at 135 degrees, t = 0.3: inside, and joined past the tip by the grid's face diagonals), so
  // a caller that knows F's critical points moves the level off zero there.
  std::vector<double> values = sample_grid(surface, grid);
  for (double& v : values) v -= level;
  double largest = 0;
  for (const double v : values) largest = std::max(largest, std::abs(v));
  for (double& v : values)
    if (std::abs(v) <= 1e-12 * largest) v = 0.0;
  const ContourMesh contour = marching_tetrahedra(grid, values, kMargin, /*open=*/true);
  Patch patch;
  std::vector<std::int64_t> index(contour.positions.size(), -1);
  std::vector<Vec3> placed(contour.positions.size());
  for (std::size_t v = 0; v < placed.size(); ++v)
    placed[v] = root_on_edge(surface, contour.edges[v], kMargin, level);
  std::vector<signed char> in(placed.size(), -1);  // each vertex asked once
  for (const Triangle& t : contour.triangles) {
    bool inside = true;
    for (const std::uint32_t v : t) {
      if (in[v] < 0) in[v] = inside_hole(placed[v]) ? 1 : 0;
      inside = inside && in[v];
    }
    if (!inside) continue;
    Triangle local;
    for (int i = 0; i < 3; ++i) {
      if (index[t[i]] < 0) {
        index[t[i]] = static_cast<std::int64_t>(patch.positions.size());
        patch.positions.push_back(placed[t[i]]);
      }
      local[i] = static_cast<std::uint32_t>(index[t[i]]);
    }
    patch.triangles.push_back(local);
  }
  // Newton polishes what the margin moved off F, unless it would travel far (near the
  // critical point it may run to the other sheet: contour_base_mesh.cpp).
  for (Vec3& p : patch.positions) {
    const ProjectionResult r = project_to_surface(surface, p);
    if (r.converged && (r.point - p).norm() <= 0.1 * h) p = r.point;
  }
  std::unordered_map<std::uint64_t, char> directed;
  for (const Triangle& t : patch.triangles)
    for (int i = 0; i < 3; ++i) directed[(std::uint64_t{t[i]} << 32) | t[(i + 1) % 3]] = 1;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> open;
  for (const Triangle& t : patch.triangles)
    for (int i = 0; i < 3; ++i)
      if (!directed.count((std::uint64_t{t[(i + 1) % 3]} << 32) | t[i]))
        open.emplace_back(t[i], t[(i + 1) % 3]);
  patch.loops = loops_of(open);
  if (patch.loops.empty() && !open.empty()) patch.triangles.clear();
  return patch;
}

// Where the new triangles' corners will be: the border's vertices are still where the
// previous step left them (the normal correction that follows moves them onto F).
std::vector<Vec3> on_surface(const ImplicitSurface& surface, std::vector<Vec3> positions,
                             std::size_t border_vertices) {
  for (std::size_t v = 0; v < border_vertices; ++v) {
    const ProjectionResult r = project_to_surface(surface, positions[v]);
    if (r.converged) positions[v] = r.point;
  }
  return positions;
}

// Cosine between a triangle's normal and grad F at its centroid (positive: faces outwards).
double facing(const ImplicitSurface& surface, const std::vector<Vec3>& p, const Triangle& t) {
  const Vec3 n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
  Vec3 g;
  surface.value_gradient((p[t[0]] + p[t[1]] + p[t[2]]) / 3.0, g);
  const double d = n.norm() * g.norm();
  return d > 0 ? n.dot(g) / d : -1.0;
}

// Zips like zip() (the same start, the same two kinds of triangles), choosing the order of the
// loops' steps by dynamic programming over all of them (Fuchs, Kedem and Uselton's optimal
// contour stitching): the order whose worst triangle faces most along grad F (cosines above
// 0.5 all count as good), then the shortest rungs. A greedy walk follows the loops' jagged
// sampling into triangles turned over where a coarse patch meets a border of coarse faces.
// Returns the worst cosine.
double zip_facing(const ImplicitSurface& surface, const std::vector<Vec3>& positions, const Loop& a,
                  const Loop& b, std::vector<Triangle>& out) {
  const std::size_t na = a.size(), nb = b.size();
  const auto [first_a, first_b] = nearest_pair(positions, a, b);
  const std::size_t i0 = first_a, j0 = first_b;
  const auto A = [&](std::size_t s) { return a[(i0 + na - s % na) % na]; };  // backwards
  const auto B = [&](std::size_t s) { return b[(j0 + s) % nb]; };
  struct Best {
    double worst = -HUGE_VAL, length = HUGE_VAL;
    char from = 0;  // 'a': reached by a step along a, 'b': along b
  };
  const auto better = [](double worst, double length, const Best& than) {
    return worst > than.worst || (worst == than.worst && length < than.length);
  };
  constexpr double kGood = 0.5;
  std::vector<Best> best((na + 1) * (nb + 1));
  const auto at = [&](std::size_t sa, std::size_t sb) -> Best& { return best[sa * (nb + 1) + sb]; };
  at(0, 0) = {HUGE_VAL, 0.0, 0};
  for (std::size_t sa = 0; sa <= na; ++sa)
    for (std::size_t sb = 0; sb <= nb; ++sb) {
      if (sa == 0 && sb == 0) continue;
      Best& here = at(sa, sb);
      if (sa > 0) {  // every state is reached from (0, 0): the steps only grow
        const Best& prev = at(sa - 1, sb);
        const Triangle t{A(sa - 1), A(sa), B(sb)};
        const double worst = std::min(prev.worst, std::min(kGood, facing(surface, positions, t)));
        const double length = prev.length + (positions[A(sa)] - positions[B(sb)]).norm();
        if (better(worst, length, here)) here = {worst, length, 'a'};
      }
      if (sb > 0) {
        const Best& prev = at(sa, sb - 1);
        const Triangle t{B(sb), B(sb - 1), A(sa)};
        const double worst = std::min(prev.worst, std::min(kGood, facing(surface, positions, t)));
        const double length = prev.length + (positions[A(sa)] - positions[B(sb)]).norm();
        if (better(worst, length, here)) here = {worst, length, 'b'};
      }
    }
  std::vector<Triangle> strip;
  for (std::size_t sa = na, sb = nb; sa > 0 || sb > 0;) {
    if (at(sa, sb).from == 'a') {
      strip.push_back({A(sa - 1), A(sa), B(sb)});
      --sa;
    } else {
      strip.push_back({B(sb), B(sb - 1), A(sa)});
      --sb;
    }
  }
  out.insert(out.end(), strip.rbegin(), strip.rend());
  return at(na, nb).worst;
}

// The strip's rungs follow the loops' jagged sampling, and a rung can cross its neighbour on
// the surface: a triangle turned over. Flipping the edge it shares with another new triangle
// (the quad's other diagonal) unfolds it when both new triangles then face outwards. Returns
// whether every triangle faces outwards.
template <class MayJoin>
bool unfold_by_flips(const ImplicitSurface& surface, const std::vector<Vec3>& p,
                     const MayJoin& may_join, std::vector<Triangle>& triangles) {
  const auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
  std::unordered_map<std::uint64_t, std::uint32_t> half;  // directed edge -> 3 * triangle + i
  const auto enter = [&](std::uint32_t k) {
    for (std::uint32_t i = 0; i < 3; ++i)
      half[key(triangles[k][i], triangles[k][(i + 1) % 3])] = 3 * k + i;
  };
  const auto leave = [&](std::uint32_t k) {
    for (int i = 0; i < 3; ++i) half.erase(key(triangles[k][i], triangles[k][(i + 1) % 3]));
  };
  for (std::uint32_t k = 0; k < triangles.size(); ++k) enter(k);
  for (int pass = 0; pass < 8; ++pass) {
    bool flipped = false, all_good = true;
    for (std::uint32_t k = 0; k < triangles.size(); ++k) {
      if (facing(surface, p, triangles[k]) > 0) continue;
      all_good = false;
      for (std::uint32_t i = 0; i < 3; ++i) {
        const Triangle t = triangles[k];
        const std::uint32_t u = t[i], v = t[(i + 1) % 3], w = t[(i + 2) % 3];
        const auto it = half.find(key(v, u));
        if (it == half.end()) continue;  // on the border
        const std::uint32_t k2 = it->second / 3;
        const Triangle& t2 = triangles[k2];
        const std::uint32_t x = t2[(it->second % 3 + 2) % 3];
        if (x == w || half.count(key(w, x)) || half.count(key(x, w))) continue;
        const Triangle a{w, u, x}, b{x, v, w};
        if (!may_join(w, x, a, b)) continue;
        if (std::min(facing(surface, p, a), facing(surface, p, b)) <=
            std::min(facing(surface, p, t), facing(surface, p, t2)))
          continue;
        leave(k);
        leave(k2);
        triangles[k] = a;
        triangles[k2] = b;
        enter(k);
        enter(k2);
        flipped = true;
        break;
      }
    }
    if (all_good) return true;
    if (!flipped) break;
  }
  bool ok = true;
  for (const Triangle& t : triangles)
    if (facing(surface, p, t) <= 0) ok = false;
  return ok;
}

// Whether every new triangle follows F: its centroid and edge midpoints within `h` (the
// patch's spacing) of F, by the first-order distance or by Newton's, whichever is nearer
// (either overstates it where |grad F| is small). The contour's own triangles lie within
// about h^2 / R of F; a strip across a gap between the cut's border and the patch does not:
// on Colin27 with closing 2 swept in 32 steps, a patch 2.2 mm across joined to a border 12 mm
// out left triangles 10 mm long and 1.3 mm off F (T = 0.5 mm), whose refinement placed its
// vertices ever farther off and ran into the triangle budget (60,000 triangles, 29 mm).
bool follows_surface(const ImplicitSurface& surface, const std::vector<Vec3>& p,
                     const std::vector<Triangle>& triangles, double h) {
  const auto near = [&](const Vec3& x) {
    Vec3 g;
    const double f = surface.value_gradient(x, g);
    if (std::abs(f) <= h * g.norm()) return true;
    const ProjectionResult r = project_to_surface(surface, x);
    return r.converged && (r.point - x).norm() <= h;
  };
  for (const Triangle& t : triangles) {
    const Vec3 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    if (!near((a + b + c) / 3.0) || !near(0.5 * (a + b)) || !near(0.5 * (b + c)) ||
        !near(0.5 * (c + a)))
      return false;
  }
  return true;
}

// The patch's contour spacing, from the seam: its faces at the patch's depth D are as fine as
// the queues made them for the threshold T there, and the patch's new faces (base faces at D,
// which welds cannot take coarser) should be no finer, or the repaired region stays
// over-refined for the rest of the run. Marching tetrahedra's triangles on a grid of spacing
// h have edges of about 0.55 h (measured on the blobs' contoured base: mean 0.082 at
// h = 0.15), so h = seam edge / 0.55; the split queue refines what is too coarse for T. At
// least `finest` (what the caller asks), at most `coarsest` (the watching grid's cell: a
// coarser contour could miss what the watching grid saw).
double patch_spacing(const Mesh48& mesh, const std::vector<Loop>& loops,
                     const std::unordered_map<std::uint64_t, int>& seam_depth, int depth,
                     double finest, double coarsest) {
  constexpr double kEdgePerSpacing = 0.55;
  double length = 0;
  std::size_t count = 0;
  for (const Loop& loop : loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
      const auto it = seam_depth.find(edge_key(a, b));
      if (it == seam_depth.end() || it->second != depth) continue;
      length += (mesh.position(Vertex(a)) - mesh.position(Vertex(b))).norm();
      ++count;
    }
  if (count == 0) return finest;
  return std::clamp(length / static_cast<double>(count) / kEdgePerSpacing, finest,
                    std::max(finest, coarsest));
}

// Splits (on the attempt's copy) every face that reaches within r of the event and has an edge
// longer than half of r, until none has. Where the mesh near the event is coarse against the
// cut (a brain layer's faces are up to 10 mm across where it is flat, the cut's radius 4 mm),
// a cut of whole faces reaches far beyond r, its closure and levelling farther still, and the
// patch (F's contour within r) is joined to that border by a strip of long triangles that
// does not follow F: on Colin27 with closing 2 the cut at the cavity's rim, radius 4 mm,
// reached 24 mm away and took in the cavity's other side (a second border loop 18-34 mm away,
// where the contour near the event has one). Returns why not when nothing was split or the
// splits did not end (else empty).
const char* const kNothingToRefine = "no coarse face near the event";
const char* refine_near(Mesh48& mesh, const Vec3& centre, double r, TrialSplits& splits) {
  // Each round halves the coarse faces' legs; a split vertex the placement rule put far off
  // (next to a ridge of F) would keep a face coarse round after round: the splits are bounded.
  constexpr int kMaxRounds = 8;
  constexpr std::size_t kMaxSplits = 2048;
  const double longest = 0.5 * r;
  bool any = false;
  std::vector<Face> coarse;
  for (int round = 0; round < kMaxRounds; ++round) {
    coarse.clear();
    for (const Face f : mesh.live_faces()) {
      const auto v = mesh.vertices(f);
      const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
      const double edge2 =
          std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      if (edge2 > longest * longest &&
          (nearest_on_triangle(centre, a, b, c) - centre).squaredNorm() <= r * r)
        coarse.push_back(f);
    }
    bool split = false;
    for (const Face f : coarse)
      if (mesh.is_alive(f) && splits.split(mesh, f).is_valid()) split = any = true;
    if (!split) break;
    if (splits.faces.size() > kMaxSplits) return "the faces near the event stay coarse when split";
  }
  return any ? "" : kNothingToRefine;
}

const char* const kBudgetSpent = "the repair's work budget (grid cells) is spent";
const char* const kTooWideToFill = "the cut is too wide to fill within the work budget";
const char* const kNothingToRaise = "the cut's border is level";

// The cut as a region of space to fill with F's contour (an attempt's fill mode): a point is
// in it when the mesh's face nearest to it is a cut one and it lies at least `gap` from the
// cut's border. Where the faces around the event are long and thin against the cut's radius,
// no cut suits a patch within the radius: Colin27 with closing 2 swept to 4 mm in 4 steps, the
// layer's faces at the cavity's rim stretched to 2-7 mm, the cut levelled down reached 12-42 mm
// with 2 to 7 border loops (F's contour there has one), levelled up it had one loop 4-14 mm
// out, and the strip joining the patch to it turned over where F bends round the rim. All 290
// attempts in the last sub-step failed, and the frame was published crossing itself (77 pairs
// with the sample seed 3) or, with other sampling, the folds left ran the refinement into the
// triangle budget (60,002 triangles, 27 mm). Filled, the first rung's cut is taken. The mesh
// follows F to within T, so its nearest face tells which part of F a point belongs to.
class HoleFill {
 public:
  HoleFill(const Mesh48& mesh, const std::vector<char>& cut, const std::vector<Face>& removed,
           const std::vector<Loop>& loops, const Vec3& centre) {
    for (const Loop& loop : loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        border_.push_back(
            {mesh.position(Vertex(loop[k])), mesh.position(Vertex(loop[(k + 1) % loop.size()]))});
    Box3 box;
    box.extend(centre);
    for (const Face f : removed)
      for (const Vertex v : mesh.vertices(f)) {
        const Vec3& p = mesh.position(v);
        box.extend(p);
        reach = std::max(reach, (p - centre).norm());
      }
    // The faces that may be nearest to a point within the cut's box grown by half the margin:
    // the cut's, and the remaining ones whose boxes reach into the box grown by the margin
    // (any other lies farther than half the margin from such a point).
    margin_ = 0.25 * reach;
    box_ = box.grown(0.5 * margin_);
    const Box3 near = box.grown(margin_);
    std::vector<std::array<Vec3, 3>> faces;
    for (const Face f : mesh.live_faces()) {
      const auto v = mesh.vertices(f);
      const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
      if (!cut[f.idx] && !Box3{a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)}.overlaps(near))
        continue;
      faces.push_back({a, b, c});
      in_cut_.push_back(cut[f.idx] != 0);
    }
    nearest_ = NearestTriangleIndex(std::move(faces));
  }
  bool inside(const Vec3& p, double gap) const;
  double reach = 0.0;  // of the cut's vertices from the event

 private:
  std::vector<std::pair<Vec3, Vec3>> border_;
  NearestTriangleIndex nearest_;  // the listed faces,
  std::vector<char> in_cut_;      // and whether each is a cut one
  Box3 box_;
  double margin_ = 0.0;
};

bool HoleFill::inside(const Vec3& p, double gap) const {
  if (!box_.contains(p)) return false;
  for (const auto& [a, b] : border_) {
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    if ((a + t * ab - p).squaredNorm() < gap * gap) return false;
  }
  // The first nearest face in the list's order, as a plain search over every face finds it,
  // through a grid of the faces (on Colin27 a plain search was a fifth of a run's CPU, in the
  // failed repairs of a layer's rim). Farther than half the margin from every listed face, a
  // face not listed may be nearer; and such a point of F is not on the mesh's sheet there anyway.
  const NearestTriangleIndex::Hit hit = nearest_.nearest(p, 0.25 * margin_ * margin_);
  return hit.triangle != NearestTriangleIndex::kNone && in_cut_[hit.triangle];
}

// What a successful attempt does to the mesh: its splits (in order), then the surgery.
struct RepairPlan {
  std::vector<Face> splits;
  std::vector<Vertex> born;     // the vertices the splits made, in order
  std::vector<Vec3> born_at;    // where the splits put them
  std::vector<Vec3> positions;  // every vertex slot's, on the copy after the surgery
  std::vector<Face> removed;
  std::vector<Vertex> existing;
  std::vector<Vec3> created;
  std::vector<Triangle> triangles;
  int depth = 0;
};

// One attempt at cut radius r, patch spacing h (or coarser, up to max_h, to match the seam), on
// a copy of `original`: when it succeeds, `plan` says what to do to the mesh.
LocalRepairResult attempt(const Mesh48& original, const ImplicitSurface& surface,
                          const SplitPlacement& place, const ContourLevel& level,
                          const Vec3& centre, double r, double h, double max_h, bool islands,
                          bool raise, bool refine, bool fill, std::size_t grid_cells_left,
                          RepairPlan& plan) {
  LocalRepairResult result;
  const auto refuse = [&](const std::string& why) {
    result.why_not = why;
    return result;
  };

  // 1. The cut, with every border loop even: the new triangles filling a loop's side number
  // as many as its edges, modulo 2, and where the patch leaves a loop alone (a split: one cap
  // per loop) they are paired among themselves.
  Mesh48 mesh = original;
  mesh.clear_listeners();
  std::vector<char> cut(mesh.face_capacity(), 0);
  TrialSplits splits(surface, place, cut);
  mesh.add_listener(&splits);
  if (refine) {
    const std::string why = refine_near(mesh, centre, r, splits);
    if (!why.empty()) return refuse(why);
  }
  for (const Face f : mesh.live_faces())
    for (const Vertex v : mesh.vertices(f))
      if ((mesh.position(v) - centre).norm() <= r) cut[f.idx] = 1;
  close_cut(mesh, cut);
  // The border levelled down (the finer faces cut away), or up (the coarser ones split,
  // raise_border) when the caller asks: where the faces next to the event are the coarse ones,
  // levelling down spreads the cut.
  if (!raise) {
    level_border(mesh, cut);
  } else if (!raise_border(mesh, cut, splits)) {
    return refuse("the cut's border could not be levelled up");
  } else if (splits.faces.empty()) {
    return refuse(kNothingToRaise);
  }
  for (int round = 0; round < 4 && islands && cut_islands(mesh, cut, centre); ++round) {
    close_cut(mesh, cut);
    level_border(mesh, cut);
  }
  std::vector<Loop> mesh_loops = loops_of(border_of(mesh, cut));
  for (int round = 0; round < 8 && mesh_loops.empty() && unpinch(mesh, cut); ++round)
    mesh_loops = loops_of(border_of(mesh, cut));
  if (mesh_loops.empty()) return refuse("nothing to cut near the event, or its border is pinched");
  const auto count_odd = [&](const std::vector<char>& c, const std::vector<Loop>& loops) {
    return odd_loops(mesh, c, loops);
  };
  // An odd loop is mended by cutting one more face g next to it, alone: one whose
  // refinement edge leads to a coarser face (not a diamond) and which is no remaining face's
  // refinement neighbour, so that the cut stays closed. The loop's length changes by one (or
  // three). In a 4-8 mesh such faces are where the refinement level changes; a diamond would
  // take its partner along and keep the parity.
  for (int round = 0; round < 16 && count_odd(cut, mesh_loops) > 0; ++round) {
    const Loop& odd = *std::find_if(mesh_loops.begin(), mesh_loops.end(),
                                    [&](const Loop& l) { return odd_loops(mesh, cut, {l}) > 0; });
    bool fixed = false;
    for (std::size_t k = 0; k < odd.size() && !fixed; ++k)
      mesh.for_each_corner_around(Vertex(odd[k]), [&](Corner corner) {
        const Face g = corner.face;
        if (fixed || cut[g.idx] || mesh.is_paired(g)) return;
        for (int i = 0; i < 3; ++i) {
          const Face n = mesh.neighbor(g, i);
          if (n.is_valid() && !cut[n.idx] && mesh.neighbor(n, 0) == g) return;
        }
        std::vector<char> trial = cut;
        trial[g.idx] = 1;
        level_border(mesh, trial);
        std::vector<Loop> loops = loops_of(border_of(mesh, trial));
        if (!loops.empty() && count_odd(trial, loops) < count_odd(cut, mesh_loops)) {
          cut = std::move(trial);
          mesh_loops = std::move(loops);
          fixed = true;
        }
      });
    if (fixed) continue;
    // None there (a uniformly refined region is all diamonds): split a diamond beside the
    // loop, whose four children are such faces, and look again.
    Face diamond;
    for (std::size_t k = 0; k < odd.size() && !diamond.is_valid(); ++k)
      mesh.for_each_corner_around(Vertex(odd[k]), [&](Corner corner) {
        const Face f = corner.face, partner = mesh.neighbor(f, 0);
        if (!diamond.is_valid() && !cut[f.idx] && mesh.is_paired(f) && partner.is_valid() &&
            !cut[partner.idx])
          diamond = f;
      });
    if (!diamond.is_valid() || !splits.split(mesh, diamond).is_valid())
      return refuse("no cut with even border loops");
    close_cut(mesh, cut);  // a child's refinement edge may lie on the border
    level_border(mesh, cut);
    mesh_loops = loops_of(border_of(mesh, cut));
    if (mesh_loops.empty()) return refuse("the cut's border is pinched");
  }
  if (count_odd(cut, mesh_loops) > 0) return refuse("no cut with even border loops");
  std::vector<Face> removed;
  for (const Face f : mesh.live_faces())
    if (cut[f.idx]) removed.push_back(f);
  if (removed.size() == mesh.n_faces()) return refuse("the cut takes the whole mesh");
  const std::unordered_map<std::uint64_t, int> seam_depth = border_depths(mesh, cut);
  const int depth = patch_depth(seam_depth);
  h = patch_spacing(mesh, mesh_loops, seam_depth, depth, h, max_h);

  // 2. The patch: F's contour within r - h / 2 of the event, so that a strip about an edge
  // wide separates it from the cut's border (which lies beyond r).
  // The grid reaches as far as the patch, not the cut: its triangles are the same (the same
  // lattice, a grid point on the event), and its cost no longer grows with a spreading cut
  // (at the dumbbell's split after motion9 the cut reached 20 mm, a grid of 162^3 cells at the
  // finest spacing; 34^3 now).
  // Or, filling the cut (HoleFill), the contour wherever the cut was, to within half a spacing
  // of its border, on a grid as wide as the cut: no strip longer than about an edge.
  Patch patch;
  if (fill) {
    const HoleFill hole(mesh, cut, removed, mesh_loops, centre);
    const std::size_t cells = patch_grid_cells(hole.reach, h);
    if (cells > grid_cells_left) return refuse(kTooWideToFill);
    result.grid_cells = cells;
    const double gap = 0.5 * h;
    patch = contour_patch(
        surface, centre, hole.reach, h, [&](const Vec3& p) { return hole.inside(p, gap); }, level);
  } else {
    const double keep = r - 0.5 * h;
    const std::size_t cells = patch_grid_cells(keep, h);
    if (cells > grid_cells_left) return refuse(kBudgetSpent);
    result.grid_cells = cells;
    patch = contour_patch(
        surface, centre, keep, h, [&](const Vec3& p) { return (p - centre).norm() <= keep; },
        level);
  }
  if (patch.loops.size() != mesh_loops.size())
    return refuse("the contour near the event has " + std::to_string(patch.loops.size()) +
                  " border loops, the cut " + std::to_string(mesh_loops.size()));

  // Local numbering: the border's vertices first (existing), then the patch's (new).
  std::vector<Vertex> existing;
  std::unordered_map<std::uint32_t, std::uint32_t> local_of;
  std::vector<Vec3> positions;
  for (const Loop& loop : mesh_loops)
    for (const std::uint32_t v : loop) {
      local_of[v] = static_cast<std::uint32_t>(existing.size());
      existing.emplace_back(v);
      positions.push_back(mesh.position(Vertex(v)));
    }
  const auto offset = static_cast<std::uint32_t>(existing.size());
  positions.insert(positions.end(), patch.positions.begin(), patch.positions.end());
  std::vector<Triangle> triangles;
  for (const Triangle& t : patch.triangles)
    triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});

  // 3. Stitch each border loop to the nearest patch loop (one each).
  std::vector<Loop> patch_loops = patch.loops;
  std::vector<Vec3> patch_centres;
  for (Loop& b : patch_loops) {
    for (std::uint32_t& v : b) v += offset;
    patch_centres.push_back(centroid(positions, b));
  }
  // Each loop's partner, and the loops in local numbering.
  std::vector<char> taken(patch_loops.size(), 0);
  std::vector<std::pair<Loop, std::size_t>> zipped;
  for (const Loop& loop : mesh_loops) {
    Loop a;
    for (const std::uint32_t v : loop) a.push_back(local_of[v]);
    const Vec3 c = centroid(positions, a);
    std::size_t best = patch_loops.size();
    for (std::size_t k = 0; k < patch_loops.size(); ++k)
      if (!taken[k] && (best == patch_loops.size() ||
                        (patch_centres[k] - c).norm() < (patch_centres[best] - c).norm()))
        best = k;
    taken[best] = 1;
    zipped.emplace_back(std::move(a), best);
  }
  const std::vector<Triangle> patch_triangles = triangles;
  // The greedy strips first (their rungs follow both loops evenly); should a triangle stay
  // turned over after the flips, the strips whose order has the best worst triangle.
  const auto stitch = [&](bool best_order) {
    triangles = patch_triangles;
    for (const auto& [a, k] : zipped) {
      std::vector<Triangle> strip;
      if (!best_order || zip_facing(surface, positions, a, patch_loops[k], strip) <= 0) {
        strip.clear();
        zip(positions, a, patch_loops[k], strip);
      }
      triangles.insert(triangles.end(), strip.begin(), strip.end());
    }
  };
  stitch(false);

  // 4. Unfold, then pair the new triangles. A flip may join two of the border's vertices
  // (an ear on the seam) where no remaining face joins them already and the ear has at most
  // one seam edge of a coarser face (its refinement edge, a half diamond below); the other
  // is a leg, across which the old face is alike deep.
  const auto coarse_seam_edges = [&](const Triangle& t) {
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      if (a >= offset || b >= offset) continue;
      const auto it = seam_depth.find(edge_key(existing[b].idx, existing[a].idx));
      n += it != seam_depth.end() && it->second < depth;
    }
    return n;
  };
  const auto may_join = [&](std::uint32_t w, std::uint32_t x, const Triangle& t1,
                            const Triangle& t2) {
    if (w >= offset || x >= offset) return true;
    bool joined = false;
    mesh.for_each_corner_around(existing[w], [&](Corner c) {
      if (cut[c.face.idx]) return;
      for (const Vertex v : mesh.vertices(c.face)) joined = joined || v == existing[x];
    });
    return !joined && coarse_seam_edges(t1) <= 1 && coarse_seam_edges(t2) <= 1;
  };
  const std::vector<Vec3> placed = on_surface(surface, positions, offset);
  if (!unfold_by_flips(surface, placed, may_join, triangles)) {
    stitch(true);
    if (!unfold_by_flips(surface, placed, may_join, triangles))
      return refuse("a new triangle would be turned over");
  }
  if (!follows_surface(surface, placed, triangles, h))
    return refuse("a new triangle lies farther from F than the patch's spacing");
  // A new triangle on an edge of a coarser old face is a half diamond: that edge is its
  // refinement edge (the old face's leg), and it is left out of the pairing.
  std::vector<int> half_at(triangles.size(), -1);  // its seam edge's apex corner
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const Triangle& t = triangles[k];
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      if (a >= offset || b >= offset) continue;
      const auto it = seam_depth.find(edge_key(existing[b].idx, existing[a].idx));
      if (it != seam_depth.end() && it->second < depth) half_at[k] = i;
    }
  }
  // The rest are paired, the matching mended by flips and splits where none is perfect
  // (triangle_pairing.h): new vertices on F, no new triangle turned over.
  std::vector<char> exempt(triangles.size(), 0);
  for (std::size_t k = 0; k < triangles.size(); ++k) exempt[k] = half_at[k] >= 0;
  PairingMendOptions mend;
  mend.split_point = [&](const Vec3& a, const Vec3& b) {
    return split_point_on_surface(surface, a, b);
  };
  mend.acceptable = [&](const std::vector<Vec3>& p, const Triangle& t) {
    return facing(surface, p, t) > 0;
  };
  mend.fixed_vertices = offset;
  MendedPairing pairing;
  try {
    pairing = pair_triangles_mending(positions, triangles, exempt, mend);
  } catch (const std::invalid_argument& e) {
    return refuse(std::string("the new triangles are not a manifold: ") + e.what());
  }
  if (!pairing.complete) return refuse("the new triangles cannot all be paired");
  std::vector<Triangle> to_pair;
  std::vector<std::int64_t> partner;
  std::vector<std::size_t> paired_index, local(triangles.size(), 0);
  for (std::size_t k = 0; k < triangles.size(); ++k)
    if (!exempt[k]) {
      local[k] = to_pair.size();
      to_pair.push_back(triangles[k]);
      paired_index.push_back(k);
    }
  for (const std::size_t k : paired_index)
    partner.push_back(
        static_cast<std::int64_t>(local[static_cast<std::size_t>(pairing.partner[k])]));
  const std::vector<Triangle> paired = refinement_edge_first(to_pair, partner);
  std::vector<Triangle> ordered(triangles.size());
  for (std::size_t k = 0; k < paired.size(); ++k) ordered[paired_index[k]] = paired[k];
  for (std::size_t k = 0; k < half_at.size(); ++k)
    if (half_at[k] >= 0) {
      const Triangle& t = triangles[k];
      const int i = half_at[k];
      ordered[k] = {t[i], t[(i + 1) % 3], t[(i + 2) % 3]};
    }
  result.pairing_flips = pairing.flips;
  result.pairing_splits = pairing.splits;
  const std::vector<Vec3> created(positions.begin() + offset, positions.end());
  try {  // on the copy first: the surgery may be refused only once it has begun
    mesh.replace_region(removed, existing, created, ordered,
                        std::vector<int>(ordered.size(), depth));
  } catch (const std::logic_error& e) {
    return refuse(e.what());
  }
  result.repaired = true;
  result.removed_faces = removed.size();
  result.added_faces = ordered.size();
  result.spacing = h;
  plan.splits = std::move(splits.faces);
  plan.born = std::move(splits.born);
  plan.born_at = std::move(splits.born_at);
  plan.positions = std::move(mesh.positions());
  plan.removed = std::move(removed);
  plan.existing = std::move(existing);
  plan.created = created;
  plan.triangles = std::move(ordered);
  plan.depth = depth;
  return result;
}

// The vertices a replay's splits make on the mesh, after the mesh's own listeners have placed
// them; placed here by split_point_on_surface when the caller gave no rule.
class ReplaySplits : public MeshListener {
 public:
  ReplaySplits(const ImplicitSurface& surface, const SplitPlacement& place)
      : surface_(surface), place_(place) {}
  void after_split(Mesh48& mesh, const DiamondChange& change) override {
    if (!place_) place_split(mesh, change, place_, surface_);
    born.push_back(change.vertex);
  }
  void after_weld(Mesh48&, const DiamondChange&) override {}
  void after_renumber(Mesh48&, const Renumbering&) override {}
  std::vector<Vertex> born;

 private:
  const ImplicitSurface& surface_;
  const SplitPlacement& place_;
};

// Makes a successful attempt's splits and surgery on the mesh itself, telling its listeners
// of the splits as any split does (the surgery they learn of from the caller, Mesh48.h).
LocalRepairResult carry_out(Mesh48& mesh, const ImplicitSurface& surface,
                            const SplitPlacement& place, RepairPlan& plan,
                            LocalRepairResult result) {
  const auto refuse = [&](const std::string& why) {
    result.repaired = false;
    result.why_not = why;
    return result;
  };
  // The same splits of the same mesh give the same ids (free lists included), and the same rule
  // puts their vertices at the same places, so the surgery planned on the copy fits. That is
  // checked: should a split fail, or make another vertex or put it elsewhere than on the copy,
  // the splits made stay (the listeners know them) and the mesh keeps its topology.
  ReplaySplits replay(surface, place);
  mesh.add_listener(&replay);
  bool failed = false;
  for (std::size_t k = 0; k < plan.splits.size() && !failed; ++k)
    failed = !mesh.split(plan.splits[k]).is_valid();
  mesh.remove_listener(&replay);
  if (failed) return refuse("a split made on the copy failed on the mesh");
  if (replay.born != plan.born) return refuse("the splits made other vertices than on the copy");
  // Compared with where the copy's splits put them, not with the copy after its surgery: a
  // split vertex inside the cut is gone there, and its slot may hold a patch vertex (seen on
  // the three blobs in a row in 40 steps, with patches re-meshed at the necks the step before:
  // the split's repair at t = 0.925 was refused so, and the mesh rebuilt).
  for (std::size_t k = 0; k < replay.born.size(); ++k)
    if (mesh.position(replay.born[k]) != plan.born_at[k])
      return refuse(
          "a split put its vertex elsewhere than on the copy (the repair's rule is not "
          "the mesh's listeners')");
  // No copy kept against a failed surgery: replace_region reads only the connectivity, which is
  // now the copy's, and the lists the copy's surgery accepted (it throws for a bug only).
  result.new_vertices =
      mesh.replace_region(plan.removed, plan.existing, plan.created, plan.triangles,
                          std::vector<int>(plan.triangles.size(), plan.depth));
  result.planned_positions = std::move(plan.positions);
  return result;
}

}  // namespace

Vec3 split_point_on_surface(const ImplicitSurface& surface, const Vec3& a, const Vec3& b) {
  const Vec3 mid = 0.5 * (a + b);
  const ProjectionResult r = project_to_surface(surface, mid);
  return r.converged && (r.point - mid).norm() <= 0.5 * (a - b).norm() ? r.point : mid;
}

LocalRepairResult repair_locally(Mesh48& mesh, const ImplicitSurface& surface, const Vec3& centre,
                                 const LocalRepairOptions& options) {
  LocalRepairResult last;
  if (!(options.radius > 0) || !(options.spacing > 0)) {
    last.why_not = "no radius or spacing";
    return last;
  }
  // A matching or a strip that fails at one cut often succeeds at a slightly larger one (the
  // border and the patch's loops both change): a few cuts, the smallest first.
  const double h = options.spacing;
  // Each reason once, in the order met, with the number of attempts that gave it (on Colin27
  // the same mismatch of loops ended all 48 attempts: one line, not 48 times the same).
  std::vector<std::pair<std::string, int>> reasons;
  // The patch as coarse as the seam first (local_repair.h), then finer by steps down to the
  // finest spacing. With the mended pairing and the stitching by dynamic programming the
  // first attempt is taken on the examples (blobs, torus pinch); the ladder remains for a
  // contour whose loops do not match the cut's, and a finer patch still re-adapts better than
  // a global re-base. Down to a quarter of the finest spacing: just after a split the new tips
  // are sharper than the patch's grid (their radius of curvature grows as sqrt(t - t_event)),
  // and a grid point on the event (outside) leaves contour triangles across the tips that face
  // sideways (the wide blobs' split, s^2 = 0.35: turned over at every spacing down to 0.75 h).
  // Last, the same with the islands the levelled cut encloses cut as well (cut_islands): they
  // leave the cut more border loops than the contour, but cutting them where another cut
  // would do changes which attempt is taken (the blobs along x in 20 steps then folded after
  // the merge), so only where no cut without them would do.
  // All of it with F = 0 contoured first, then, where none would do, again with F = L off zero
  // (LocalRepairOptions::contour_level), if a critical point near the event asks for a level
  // at all (the coarsest grid asks for the largest): a repair F = 0 serves is made as before.
  // Contoured at a level, a new neck is wider than F's (the three blobs in a row, merged 0.0005
  // before a frame: the correction then thinned it, and the repaired region crossed the mesh).
  std::vector<double> coarsest;
  for (double most = std::max(h, options.max_spacing); most > h * 1.0001; most *= 0.85)
    coarsest.push_back(most);
  coarsest.push_back(h);
  struct Ladder {
    std::vector<double> finer;
    bool islands;
  };
  const Ladder ladders[3] = {
      {{1.0, 0.75}, false}, {{0.5, 0.35, 0.25}, false}, {{1.0, 0.75, 0.5, 0.35, 0.25}, true}};
  const double widest = coarsest.front();
  const double reach = 1.5 * options.radius + 2.0 * widest;
  const bool off_zero =
      options.contour_level &&
      options.contour_level({centre - Vec3::Constant(reach), centre + Vec3::Constant(reach)},
                            std::sqrt(3.0) * widest) != 0.0;
  const ContourLevel levels[2] = {ContourLevel{}, options.contour_level};
  for (int pass = 0; pass < (off_zero ? 2 : 1); ++pass) {
    const ContourLevel& level = levels[pass];
    std::size_t cells_used = 0;  // the work bound holds for each pass
    bool spent = false;
    for (const Ladder& ladder : ladders)
      for (const double grow : {1.0, 1.25, 1.5})
        for (const double finer : ladder.finer)
          for (const double most : coarsest) {
            if (finer < 1.0 && most > h) continue;  // the finer grids only at the finest spacing
            if (spent) break;
            // Each cut levelled down first (the finer faces cut away), then up (the coarser ones
            // split), unless levelling up would split nothing; then made after the faces near the
            // event are split finer than the cut (refine_near), unless none is coarse: last, so
            // that where the first two serve (the analytic scenes) nothing changes. Then the same
            // three with the patch filling the cut (HoleFill) instead of the radius: on Colin27
            // the layer's long faces at the cavity's rim left no cut whose border the patch
            // within the radius could be joined to.
            for (const int mode : {0, 1, 2, 3, 4, 5}) {
              if (spent || (mode >= 3 && !options.fill_cut)) break;
              RepairPlan plan;
              const LocalRepairResult r = attempt(
                  mesh, surface, options.place_split_vertex, level, centre, grow * options.radius,
                  finer * h, finer * most, ladder.islands, mode % 3 == 1, mode % 3 == 2, mode >= 3,
                  options.max_grid_cells - cells_used, plan);
              cells_used += r.grid_cells;
              if (r.repaired) return carry_out(mesh, surface, options.place_split_vertex, plan, r);
              spent = r.why_not == kBudgetSpent;
              if (r.why_not == kNothingToRaise || r.why_not == kNothingToRefine) continue;
              last = r;
              const auto seen =
                  std::find_if(reasons.begin(), reasons.end(),
                               [&](const auto& reason) { return reason.first == last.why_not; });
              if (seen == reasons.end())
                reasons.emplace_back(last.why_not, 1);
              else
                ++seen->second;
            }
          }
  }
  std::string why;
  for (const auto& [reason, attempts] : reasons)
    why += (why.empty() ? "" : "; ") + reason +
           (attempts > 1 ? " (" + std::to_string(attempts) + " attempts)" : "");
  last.why_not = why;
  return last;
}

}  // namespace dynamesh
