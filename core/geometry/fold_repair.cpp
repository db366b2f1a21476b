#include "core/geometry/fold_repair.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/geometry/mesh_quality.h"
#include "core/geometry/surface_move.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

Vec3 face_normal(const Mesh48& mesh, Face f) {
  const auto v = mesh.vertices(f);
  const Vec3& a = mesh.position(v[0]);
  return (mesh.position(v[1]) - a).cross(mesh.position(v[2]) - a);
}

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  double smallest = 180.0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
    smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / M_PI);
  }
  return smallest;
}

// Whether the triangle's smallest angle is below the limit, given its edges e1 = b - a,
// e2 = c - a (the face normal's), bc = c - b, the face normal's squared norm normal2 =
// |e1 x e2|^2 and sin2_limit = sin^2 of the limit (at most 90 degrees). A degenerate triangle
// is below. This runs on every face of every frame, so without a square root, a division or a
// data-dependent branch. By the sines: the angle at a corner between edges u, w has
// sin^2 = normal2 / (|u|^2 |w|^2), smallest at the corner between the two longest edges (the
// largest product). A sine below sin(limit) means an angle below the limit or above
// 180 degrees minus it, and then the other two angles are below the limit; and the smallest
// angle (at most 60 degrees) is below the limit only if its sine is. So: below exactly when
// normal2 < sin2_limit * (the largest product), with the normal's norm the screen has anyway:
// three products and a comparison instead of the cosine test at all three corners (three dot
// products, six products, six comparisons), which this replaced on 2026-11-24; the verdicts
// differ only by rounding, within 1e-9 degrees of the limit
// (FoldScreen.SliversAreTheFacesBelowTheFloorMeasuredIndependently). Inlined into the screen's
// face pass, which has e1, e2 and the normal already.
[[gnu::always_inline]] inline bool below_angle_edges(const Vec3& e1, const Vec3& e2, const Vec3& bc,
                                                     double normal2, double sin2_limit) {
  const double lab = e1.squaredNorm(), lbc = bc.squaredNorm(), lca = e2.squaredNorm();
  const double widest = std::max(std::max(lab * lca, lab * lbc), lca * lbc);
  return !(normal2 > 0) | (normal2 < sin2_limit * widest);
}

// sin^2 of the angle floor, for below_angle_edges (a floor above 90 degrees as 90: every
// triangle but one with a right angle between its two longest edges is below it anyway).
double sin2_floor(double min_angle_deg) {
  const double s = std::sin(std::min(min_angle_deg, 90.0) * M_PI / 180.0);
  return s * s;
}

}  // namespace

bool folded_against_surface(const Mesh48& mesh, const Surface& surface, Face f) {
  const Vec3 n = face_normal(mesh, f);
  if (!(n.squaredNorm() > 0)) return true;  // degenerate: no orientation at all
  for (Vertex v : mesh.vertices(f))
    if (n.dot(surface_normal_at(surface, mesh, v)) <= 0) return true;
  return false;
}

namespace {

// The surface normals at the corners of a vertex's star, each vertex once: the ring's are
// taken when the star is made and kept while only the centre moves (relax_vertex's trial moves),
// the centre's at each score. The verdicts are folded_against_surface's (the same normals, in
// the same order), at 1 + valence evaluations of grad F per star instead of 3 per face, and for
// a trial move at one.
class StarNormals {
 public:
  StarNormals(const Mesh48& mesh, const Surface& surface, Vertex v)
      : mesh_(mesh), surface_(surface), centre_(v) {
    mesh.for_each_corner_around(v, [&](Corner c) {
      for (Vertex w : mesh.vertices(c.face))
        if (w != v && !find(w) && count_ < kMax) {
          vertex_[count_] = w;
          normal_[count_++] = surface_normal_at(surface, mesh, w);
        }
    });
  }
  // The star's worst face with the centre where it is now. A face scores its smallest angle in
  // degrees when it is not folded, -1 when it is (so that unfolding always counts as an
  // improvement).
  double score() const {
    const Vec3 centre_normal = surface_normal_at(surface_, mesh_, centre_);
    double worst = 180.0;
    mesh_.for_each_corner_around(
        centre_, [&](Corner c) { worst = std::min(worst, face_score(c.face, centre_normal)); });
    return worst;
  }

 private:
  static constexpr int kMax = 32;
  const Vec3* find(Vertex w) const {
    for (int i = 0; i < count_; ++i)
      if (vertex_[i] == w) return &normal_[i];
    return nullptr;
  }
  double face_score(Face f, const Vec3& centre_normal) const {
    const auto v = mesh_.vertices(f);
    const Vec3 n = face_normal(mesh_, f);
    bool folded = !(n.squaredNorm() > 0);
    for (int i = 0; i < 3 && !folded; ++i) {
      const Vec3* cached = v[i] == centre_ ? &centre_normal : find(v[i]);
      const Vec3 normal = cached ? *cached : surface_normal_at(surface_, mesh_, v[i]);
      folded = n.dot(normal) <= 0;
    }
    if (folded) return -1.0;
    return smallest_angle_deg(mesh_.position(v[0]), mesh_.position(v[1]), mesh_.position(v[2]));
  }

  const Mesh48& mesh_;
  const Surface& surface_;
  Vertex centre_;
  std::array<Vertex, kMax> vertex_;
  std::array<Vec3, kMax> normal_;
  int count_ = 0;
};

double star_score(const Mesh48& mesh, const Surface& surface, Vertex v) {
  return StarNormals(mesh, surface, v).score();
}

// Moves v towards its one-ring's centroid (uniform weights: the repair wants well-shaped
// triangles, not the grading the smoothing keeps) in its tangent plane, onto the surface; keeps
// the move (full or half) only if the worst face of its star improves.
bool relax_vertex(Mesh48& mesh, const Surface& surface, Vertex v, std::size_t& failures) {
  if (mesh.is_boundary(v) && surface.kind() == SurfaceKind::kImplicit) return false;
  Vec3 centroid = Vec3::Zero();
  int count = 0;
  double shortest = std::numeric_limits<double>::infinity();
  mesh.for_each_corner_around(v, [&](Corner c) {
    const auto w = mesh.vertices(c.face);
    const Vec3& next = mesh.position(w[static_cast<std::size_t>((c.local + 1) % 3)]);
    centroid += next + mesh.position(w[static_cast<std::size_t>((c.local + 2) % 3)]);
    count += 2;
    shortest = std::min(shortest, (next - mesh.position(v)).norm());
  });
  if (count == 0) return false;
  centroid /= count;
  const Vec3 n = surface_normal_at(surface, mesh, v);
  const Vec3 d = centroid - mesh.position(v);
  const Vec3 move = d - d.dot(n) * n;
  const StarNormals star(mesh, surface, v);  // the ring stays put while v moves
  const double before = star.score();
  const Vec3 old_position = mesh.position(v);
  const Vec2 old_uv = mesh.uv(v);
  const auto* par = dynamic_cast<const ParametricSurface*>(&surface);
  const auto* imp = dynamic_cast<const ImplicitSurface*>(&surface);
  // The star's worst face after moving v by `step` (v is put back), or -inf if the move failed.
  auto try_move = [&](const Vec3& step, Vec3& position, Vec2& uv) {
    position = old_position;
    uv = old_uv;
    const bool ok = par ? parametric_move(*par, mesh, v, step, uv, position)
                        : implicit_move(*imp, mesh, v, step, position, failures);
    if (!ok) return -std::numeric_limits<double>::infinity();
    mesh.position(v) = position;
    mesh.uv(v) = uv;
    const double score = star.score();
    mesh.position(v) = old_position;
    mesh.uv(v) = old_uv;
    return score;
  };
  Vec3 position;
  Vec2 uv;
  for (double scale : {1.0, 0.5, 0.25}) {
    if (try_move(scale * move, position, uv) > before) {
      mesh.position(v) = position;
      mesh.uv(v) = uv;
      return true;
    }
  }
  // Where the surface bends strongly under the ring, the tangent-plane centroid can be where
  // v already is (the ring's pull is all along the normal) while its triangles are thin:
  // measured on mri's way back up from 20 mm, vertices of faces left at 5-9 degrees had
  // centroid moves 0.4-0.9 mm long, 62% of them with a tangential part below 0.05 mm, and the faces
  // stayed below 10 degrees frame after frame (down to 4.9985). Then a pattern search: 8
  // tangent directions at a tenth, a thirtieth and a hundredth of v's shortest edge; the move
  // that makes the star's worst face best is kept (the largest step that improves). With it
  // every frame of that sweep stays above 10 degrees, with predictive and full sampling. With
  // steps of a third instead, full sampling's last frame kept 15 folded faces, after a sub-step
  // of 155 splits (5x the usual) around vertices the search had moved (one trajectory each).
  // n is a unit normal (surface_normal_at), so t1, t2, n are orthonormal.
  const Vec3 t1 = n.unitOrthogonal();
  const Vec3 t2 = n.cross(t1);
  for (double fraction : {0.1, 1.0 / 30.0, 0.01}) {
    double best = before;
    Vec3 best_position = old_position;
    Vec2 best_uv = old_uv;
    for (int k = 0; k < 8; ++k) {
      const double a = k * M_PI / 4;
      const double score =
          try_move(fraction * shortest * (std::cos(a) * t1 + std::sin(a) * t2), position, uv);
      if (score > best) best = score, best_position = position, best_uv = uv;
    }
    if (best > before) {
      mesh.position(v) = best_position;
      mesh.uv(v) = best_uv;
      return true;
    }
  }
  return false;
}

}  // namespace

namespace {

// Whether the screen must ask the surface about a face, given its normal and its corners'
// summed (area-weighted) mesh normals: it is degenerate or turned more than 60 degrees from a
// corner's mesh normal N: fn.N <= |fn| |N| / 2, tested as fn.N <= 0 or 4 (fn.N)^2 <= |fn|^2 |N|^2
// (no square root, and no branch: nearly every face passes). The corners' N and |N|^2 are the
// buffers' (|N|^2 once per vertex rather than once per face and corner, the same number).
bool suspect(const Vec3& fn, const FoldScreenBuffers& b, const std::array<Vertex, 3>& corners) {
  const double fn2 = fn.squaredNorm();
  bool s = !(fn2 > 0);
  for (Vertex v : corners) {
    const double d = fn.dot(b.vertex_normal[v.idx]);
    s |= (d <= 0) | (4.0 * d * d <= fn2 * b.vertex_normal2[v.idx]);
  }
  return s;
}

// 1 folded, 2 sliver, 0 neither: the screen's verdict on face f with corners `corners`, given
// its normal and its corners' summed mesh normals in `b`. `sliver`: below_angle_edges' verdict.
std::uint8_t verdict(const Mesh48& mesh, const Surface& surface, Face f,
                     const std::array<Vertex, 3>& corners, const Vec3& fn,
                     const FoldScreenBuffers& b, bool sliver) {
  if (suspect(fn, b, corners) && folded_against_surface(mesh, surface, f)) return 1;
  return sliver ? 2 : 0;
}

bool face_below_angle(const Mesh48& mesh, Face f, const Vec3& normal, double sin2_limit) {
  const auto v = mesh.vertices(f);
  const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
  return below_angle_edges(b - a, c - a, c - b, normal.squaredNorm(), sin2_limit);
}

}  // namespace

void find_bad_faces(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                    std::vector<Face>& folded, std::vector<Face>& slivers,
                    FoldScreenBuffers* buffers) {
  folded.clear();
  slivers.clear();
  FoldScreenBuffers local;
  FoldScreenBuffers& b = buffers ? *buffers : local;
  // Mesh-only screen: a face turned against its corners' area-weighted mesh normals (more
  // than 60 degrees; a smooth adapted mesh bends far less between neighbours), or below the
  // angle floor. Only those evaluate the surface.
  // Each face's normal and angle verdict once (in parallel), the normals summed into their
  // corners in face order (the sums, hence the verdicts, are those of a serial pass). Below
  // kParallelMin faces (twist at 100 steps: 2k) the face passes run fused, two instead of four:
  // the screen is three quarters of what the safeguards cost on a small motion, the sub-step
  // plan's strain pass the rest. With the branch-free below_angle, BM_SafeguardChecks went from
  // 5.71 to 5.12 ms per 100 steps (medians of 32 interleaved runs, 2-core VM at load 4,
  // 2026-11-24); with the angle test inlined on the normal's edges and each corner's |N|^2 once
  // per vertex (a pass over the vertices), the screen's instructions over those 100 steps went
  // from 73.9M to 61.2M (callgrind, 2026-11-24), and with the angle tested by the sines on the
  // normal's own squared norm (below_angle_edges) to 52.1M (every published mesh of those 100
  // steps, and of twist in 30 and 10 steps, bit-identical).
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  const auto nv = static_cast<std::int64_t>(mesh.vertex_capacity());
  const double sin2_limit = sin2_floor(min_angle_deg);
  b.normal.resize(static_cast<std::size_t>(n));
  b.kind.resize(static_cast<std::size_t>(n));
  b.vertex_normal.assign(static_cast<std::size_t>(nv), Vec3::Zero());
  b.vertex_normal2.resize(static_cast<std::size_t>(nv));
  // Face i's normal, and 2 in kind[i] when it is below the angle floor (0 for dead slots);
  // with `sum`, the normal summed into its corners too.
  auto shape = [&](std::int64_t i, auto sum) {
    const Face f(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    if (!mesh.is_alive(f)) {
      b.kind[k] = 0;
      return;
    }
    const auto v = mesh.vertices(f);
    const Vec3 &p0 = mesh.position(v[0]), &p1 = mesh.position(v[1]), &p2 = mesh.position(v[2]);
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    const Vec3 normal = e1.cross(e2);
    b.normal[k] = normal;
    b.kind[k] = below_angle_edges(e1, e2, p2 - p1, normal.squaredNorm(), sin2_limit) ? 2 : 0;
    if constexpr (decltype(sum)::value)
      for (Vertex c : v) b.vertex_normal[c.idx] += normal;
  };
  // Every live face's normal into its corners with slots in [first, last), in face order.
  auto sum_into_corners = [&](std::uint32_t first, std::uint32_t last) {
    for (std::int64_t i = 0; i < n; ++i) {
      const Face f(static_cast<std::uint32_t>(i));
      if (!mesh.is_alive(f)) continue;
      for (Vertex v : mesh.vertices(f))
        if (v.idx >= first && v.idx < last)
          b.vertex_normal[v.idx] += b.normal[static_cast<std::size_t>(i)];
    }
  };
  auto square_vertex_normal = [&](std::int64_t i) {
    const auto k = static_cast<std::size_t>(i);
    b.vertex_normal2[k] = b.vertex_normal[k].squaredNorm();
  };
  // Face i's verdict (kind[i] from shape()).
  auto judge = [&](std::int64_t i) {
    const Face f(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    if (!mesh.is_alive(f)) return;
    b.kind[k] = verdict(mesh, surface, f, mesh.vertices(f), b.normal[k], b, b.kind[k] == 2);
  };
  auto collect = [&](std::int64_t i) {
    const auto k = b.kind[static_cast<std::size_t>(i)];
    if (k == 1) folded.push_back(Face(static_cast<std::uint32_t>(i)));
    if (k == 2) slivers.push_back(Face(static_cast<std::uint32_t>(i)));
  };
  if (n > kParallelMin) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) shape(i, std::false_type{});
      // Each thread sums into its own range of vertex slots, going over every face in face
      // order: each sum is the serial pass's, the same additions in the same order, with no two
      // threads writing one vertex. (It was one thread's pass while the other waited: issue 17.)
#pragma omp parallel
    {
      const auto threads = static_cast<std::int64_t>(omp_get_num_threads());
      const auto t = static_cast<std::int64_t>(omp_get_thread_num());
      sum_into_corners(static_cast<std::uint32_t>(nv * t / threads),
                       static_cast<std::uint32_t>(nv * (t + 1) / threads));
    }
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < nv; ++i) square_vertex_normal(i);
    std::int64_t bad = 0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : bad)
    for (std::int64_t i = 0; i < n; ++i) judge(i), bad += b.kind[static_cast<std::size_t>(i)] != 0;
    // Usually none: then the lists stay empty without a pass over the faces.
    if (bad)
      for (std::int64_t i = 0; i < n; ++i) collect(i);
  } else {
    for (std::int64_t i = 0; i < n; ++i) shape(i, std::true_type{});
    for (std::int64_t i = 0; i < nv; ++i) square_vertex_normal(i);
    for (std::int64_t i = 0; i < n; ++i) judge(i), collect(i);
  }
}

void find_bad_faces_around(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                           const std::vector<Vertex>& vertices, std::vector<Face>& folded,
                           std::vector<Face>& slivers, FoldScreenBuffers* buffers) {
  folded.clear();
  slivers.clear();
  FoldScreenBuffers local;
  FoldScreenBuffers& b = buffers ? *buffers : local;
  // This call's marks: a slot is done when its mark equals `call`. Arrays only grow (new
  // slots start unmarked); on the counter's wrap every mark is cleared once.
  if (++b.call == 0) {
    std::fill(b.face_mark.begin(), b.face_mark.end(), 0u);
    std::fill(b.vertex_mark.begin(), b.vertex_mark.end(), 0u);
    b.call = 1;
  }
  const std::uint32_t call = b.call;
  if (b.face_mark.size() < mesh.face_capacity()) b.face_mark.resize(mesh.face_capacity(), 0u);
  if (b.vertex_mark.size() < mesh.vertex_capacity()) {
    b.vertex_mark.resize(mesh.vertex_capacity(), 0u);
    b.vertex_normal.resize(mesh.vertex_capacity());
    b.vertex_normal2.resize(mesh.vertex_capacity());
  }
  // A corner's mesh normal as find_bad_faces sums it (its faces' normals in ascending face
  // order, from zero), once per vertex per call; the ring (a handful of faces) is sorted by
  // insertion as it is walked.
  std::vector<Face>& ring = b.ring;
  auto mesh_normal = [&](Vertex v) {
    if (b.vertex_mark[v.idx] == call) return;
    b.vertex_mark[v.idx] = call;
    ring.clear();
    mesh.for_each_corner_around(v, [&](Corner c) {
      ring.push_back(c.face);
      for (std::size_t k = ring.size() - 1; k > 0 && ring[k] < ring[k - 1]; --k)
        std::swap(ring[k], ring[k - 1]);
    });
    Vec3 sum = Vec3::Zero();
    for (Face f : ring) sum += face_normal(mesh, f);
    b.vertex_normal[v.idx] = sum;
    b.vertex_normal2[v.idx] = sum.squaredNorm();
  };
  const double sin2_limit = sin2_floor(min_angle_deg);
  // Every live face with a corner in `vertices`, once.
  for (Vertex v : vertices) {
    if (!mesh.is_alive(v)) continue;
    mesh.for_each_corner_around(v, [&](Corner c) {
      const Face f = c.face;
      if (b.face_mark[f.idx] == call) return;
      b.face_mark[f.idx] = call;
      const auto w = mesh.vertices(f);
      for (Vertex u : w) mesh_normal(u);
      const Vec3 normal = face_normal(mesh, f);
      const std::uint8_t k =
          verdict(mesh, surface, f, w, normal, b, face_below_angle(mesh, f, normal, sin2_limit));
      if (k == 1) folded.push_back(f);
      if (k == 2) slivers.push_back(f);
    });
  }
  // In face order, as find_bad_faces lists them (these lists are short: usually empty).
  std::sort(folded.begin(), folded.end());
  std::sort(slivers.begin(), slivers.end());
}

FoldReport repair_folds(Mesh48& mesh, const Surface& surface, const FoldRepairOptions& options,
                        FoldScreenBuffers* buffers) {
  FoldReport report;
  if (!options.enabled) return report;
  std::vector<Face> folded, slivers;
  find_bad_faces(mesh, surface, options.min_angle_deg, folded, slivers, buffers);
  report.folded = folded.size();
  report.slivers = slivers.size();
  if (folded.empty() && slivers.empty()) return report;  // the usual case: one pass, no repair
  std::vector<Vertex> active, next;
  std::vector<std::uint32_t> seen(mesh.vertex_capacity(), 0);
  for (const auto* list : {&folded, &slivers})
    for (Face f : *list)
      for (Vertex v : mesh.vertices(f)) active.push_back(v);
  std::size_t failures = 0;
  // relax_vertex reads only v's and its ring's positions (and parameters): a vertex that found
  // no better place is not tried again until one of those has moved, since it would find none
  // again, move for move. Where the mesh cannot be unfolded (its topology is not F's: a neck F no
  // longer has, whose faces span the gap) the rings widen over the whole mesh round after round,
  // and the same vertices were tried in vain 12 times per call, at every sub-step (the dumbbell
  // split with events off, test MriEvents.DumbbellSplitUnwatchedEndsBounded). `moves` counts the
  // moves kept; moved_at[v]: the count after v's last, failed_at[v]: the count at its last
  // failure (-1: none).
  std::int64_t moves = 0;
  std::vector<std::int64_t> moved_at(mesh.vertex_capacity(), 0),
      failed_at(mesh.vertex_capacity(), -1);
  const auto fails_again = [&](Vertex v) {
    const std::int64_t failed = failed_at[v.idx];
    if (failed < 0 || moved_at[v.idx] > failed) return false;
    bool still = true;
    mesh.for_each_corner_around(v, [&](Corner c) {
      for (Vertex w : mesh.vertices(c.face)) still = still && moved_at[w.idx] <= failed;
    });
    return still;
  };
  for (std::uint32_t round = 1;
       round <= static_cast<std::uint32_t>(options.max_rounds) && !active.empty(); ++round) {
    next.clear();
    for (Vertex v : active) {
      if (seen[v.idx] == round) continue;
      seen[v.idx] = round;
      if (!fails_again(v)) {
        if (relax_vertex(mesh, surface, v, failures)) {
          ++report.moved;
          moved_at[v.idx] = ++moves;
        } else {
          failed_at[v.idx] = moves;
        }
      }
      if (star_score(mesh, surface, v) >= options.min_angle_deg) continue;
      // Still bad: its neighbours relax next round, to make room.
      next.push_back(v);
      mesh.for_each_corner_around(v, [&](Corner c) {
        for (Vertex w : mesh.vertices(c.face))
          if (w != v) next.push_back(w);
      });
    }
    active.swap(next);
  }
  find_bad_faces(mesh, surface, options.min_angle_deg, folded, slivers, buffers);
  report.remaining_folded = folded.size();
  report.remaining_slivers = slivers.size();
  return report;
}

}  // namespace dynamesh
