#include "core/geometry/tangential_smoothing.h"

#include <omp.h>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/geometry/mesh_quality.h"
#include "core/geometry/surface_move.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

struct Frame {
  PrincipalCurvatures k;
  double l1 = 0, l2 = 0;  // curvature magnitudes |k1|, |k2| (Equation 1 normalises them: Weights)
};

// How Equation 1 reads a frame's curvature magnitudes: raw, or normalised to [0, 1] by the
// mesh-wide range (the original implementation's choice), applied where the move reads them
// rather than in a pass of its own over every frame.
struct Weights {
  bool raw = false;
  double lo = 0.0, range = 0.0;
  double operator()(double l) const { return raw ? l : range > 0 ? (l - lo) / range : 0.0; }
};

// One range of faces' partial sum of a vertex's one-ring (sum_rings).
struct RingSum {
  Vec3 sum{Vec3::Zero()};
  Vec3 normal{Vec3::Zero()};  // area-weighted face normals (the mesh normal, frame reuse)
  double weight = 0.0;
  double length = 0.0;  // edge lengths
  std::uint16_t edges = 0;
  std::uint8_t boundary = 0;
  // The sum_rings call that started it (0: none); one of an earlier call reads as untouched
  // (zero). In the struct's padding: still 72 bytes.
  std::uint32_t call = 0;
};
static_assert(sizeof(RingSum) == 72, "RingSum::call is meant to fit in the padding");
const RingSum kUntouched{};  // what a sum not started in this call stands for

// A vertex's curvature frame as last evaluated (frame reuse, SmoothingWorkspace).
struct CachedFrame {
  PrincipalCurvatures k;
  Vec3 at{Vec3::Zero()};           // where it was evaluated
  Vec3 rest{Vec3::Zero()};         // its rest-space point then (surfaces with a rest map)
  Vec3 mesh_normal{Vec3::Zero()};  // the vertex's unit mesh normal then
  std::uint64_t call = 0;          // smooth_once call it was evaluated in (+1; 0 = none)
};

}  // namespace

// The state one iteration reads (old positions) and writes (candidates).
struct SmoothingWorkspace::Buffers {
  std::vector<Frame> frame;
  std::vector<Vec3> position;
  std::vector<Vec2> uv;
  std::vector<std::uint8_t> moved;
  std::vector<double> value;        // implicit: F where the moved vertex landed
  std::vector<Vec3> gradient;       // ... and grad F (SmoothingWorkspace::landed)
  std::vector<Vec3> centroid;       // of each vertex's one-ring
  std::vector<Vec3> mesh_normal;    // unit, area-weighted (zero if degenerate)
  std::vector<double> mean_edge;    // mean length of the ring's edges
  std::vector<CachedFrame> cached;  // frame reuse (SmoothingWorkspace)
  // Each vertex's turn to be evaluated afresh (frame_reusable (a)): its id modulo
  // kFrameReuseCalls when its slot was made, kept through a renumbering.
  std::vector<std::uint8_t> phase;
  std::uint64_t calls = 0;                      // smooth_once calls with this workspace
  bool reuse = false;                           // frames may be reused (a caller's workspace)
  std::size_t reused = 0;                       // frames reused by the last call
  std::vector<std::vector<RingSum>> ring_sums;  // per range of faces, while summing
  std::uint32_t ring_call = 0;                  // sum_rings calls (RingSum::call)
  std::vector<std::uint8_t> boundary;           // per vertex: on an open boundary
  std::vector<Face> check, next_check;
  OrderedCollector<Face> bad_collector;  // the faces failing the guards, in face order
};

SmoothingWorkspace::SmoothingWorkspace() : buffers_(std::make_unique<Buffers>()) {}
SmoothingWorkspace::~SmoothingWorkspace() = default;

void SmoothingWorkspace::forget_frames() {
  for (CachedFrame& c : buffers_->cached) c.call = 0;
}

bool SmoothingWorkspace::landed(Vertex v, double& value, Vec3& gradient) const {
  const Buffers& w = *buffers_;
  if (v.idx >= w.moved.size() || !w.moved[v.idx] || v.idx >= w.value.size()) return false;
  value = w.value[v.idx];
  gradient = w.gradient[v.idx];
  return true;
}

void SmoothingWorkspace::after_split(Mesh48&, const DiamondChange& change) {
  // The new vertex may carry the id of one a weld freed: its frame is not that vertex's.
  if (change.vertex.idx < buffers_->cached.size()) buffers_->cached[change.vertex.idx].call = 0;
}

namespace {

using Work = SmoothingWorkspace::Buffers;

// Centroids of every vertex's one-ring, and which vertices lie on the boundary, in one pass
// over the faces that meets each edge once (from its lower-numbered halfedge): walking each
// vertex's ring instead chases faces scattered through memory. Uniform weights are the
// paper's; inverse edge-length weights (Fujiwara's scale-invariant Laplacian) make a graded
// ring a fixed point — with uniform weights a vertex at a level transition of the 4-8 mesh
// is pulled towards the coarse side, fine regions lose resolution and are split again, and
// the mesh grows cycle after cycle of a periodic deformation.
// In parallel: the faces are cut into kRingChunks fixed ranges, each summed into its own
// accumulators (an edge adds to both its ends, which other ranges' edges share), and each
// vertex's sums are the ranges' sums added in range order. The ranges do not depend on the
// thread count, so neither do the sums: floating-point addition is not associative, and with
// one accumulator array per *thread* (until 2026-11-24) a vertex whose faces two threads summed
// got other last bits with two threads than with one, and so did every frame after (issue 13;
// test ThreadCount.*). Re-summing only those vertices in the serial order was tried: before a
// renumbering, a split's children are numbered far apart, most vertices have faces in both
// halves, and the pass took 3.7x main's instructions with two threads (capsule-bend, 31k faces).
// Two ranges cost one thread an extra accumulator array (72 bytes a vertex) and give this loop
// two threads at most.
constexpr int kRingChunks = 2;

// The face pass: each range's sums (ring_sums); returns the number of ranges. Each vertex's
// sums are then combined by combine_ring.
int sum_rings(const Mesh48& mesh, bool scale_invariant, Work& w) {
  const std::size_t nv = mesh.vertex_capacity();
  const auto nf = static_cast<std::int64_t>(mesh.face_capacity());
  const int chunks = nf > kParallelMin ? kRingChunks : 1;
  w.ring_sums.resize(static_cast<std::size_t>(chunks));
  // A range's sums are started at a vertex's first touch in this call, not cleared for every
  // vertex first: at 10^6 triangles that clearing wrote 36 MB per range and call (issue 17).
  // The sums are the same: each starts from zero, as before.
  if (++w.ring_call == 0) {  // wrapped: every sum reads as untouched again
    for (auto& sums : w.ring_sums)
      for (RingSum& r : sums) r.call = 0;
    w.ring_call = 1;
  }
  const std::uint32_t call = w.ring_call;
  auto face_pass = [&](std::vector<RingSum>& all, std::int64_t begin, std::int64_t end) {
    auto sums = [&](Vertex v) -> RingSum& {
      RingSum& r = all[v.idx];
      if (r.call != call) {
        r = RingSum{};
        r.call = call;
      }
      return r;
    };
    for (std::int64_t f = begin; f < end; ++f) {
      const Face face(static_cast<std::uint32_t>(f));
      if (!mesh.is_alive(face)) continue;
      // Each corner's sums and position looked up once per face, not once per edge and again
      // for the normal. Every sum still receives the same additions in the same order (the
      // face's edges, then its normal); starting a sum a face then adds nothing to (an edge met
      // from its twin, no frame reuse) leaves zeros, which is what an untouched sum reads as.
      const auto v = mesh.vertices(face);
      RingSum* const corner_sums[3] = {&sums(v[0]), &sums(v[1]), &sums(v[2])};
      const Vec3* const corner[3] = {&mesh.position(v[0]), &mesh.position(v[1]),
                                     &mesh.position(v[2])};
      for (int e = 0; e < 3; ++e) {
        const Halfedge h(face, e);
        const Halfedge twin = mesh.twin(h);
        if (twin.is_valid() && twin.idx < h.idx) continue;  // met from the twin
        // Halfedge e runs from corner e + 1 to corner e + 2 (Mesh48::from_vertex, to_vertex).
        RingSum &sa = *corner_sums[(e + 1) % 3], &sb = *corner_sums[(e + 2) % 3];
        if (!twin.is_valid()) sa.boundary = sb.boundary = 1;
        const Vec3 &pa = *corner[(e + 1) % 3], &pb = *corner[(e + 2) % 3];
        const double length = (pa - pb).norm();
        const double weight = scale_invariant ? (length > 0 ? 1.0 / length : 0.0) : 1.0;
        sa.sum += weight * pb;
        sa.weight += weight;
        sb.sum += weight * pa;
        sb.weight += weight;
        sa.length += length;
        sb.length += length;
        ++sa.edges;
        ++sb.edges;
      }
      if (!w.reuse) continue;
      const Vec3 area_normal = (*corner[1] - *corner[0]).cross(*corner[2] - *corner[0]);
      for (RingSum* r : corner_sums) r->normal += area_normal;
    }
  };
#pragma omp parallel for schedule(static) if (chunks > 1) \
    num_threads(std::min(chunks, omp_get_max_threads()))
  for (int c = 0; c < chunks; ++c) {
    std::vector<RingSum>& sums = w.ring_sums[static_cast<std::size_t>(c)];
    sums.resize(nv);  // new slots read as untouched
    face_pass(sums, nf * c / chunks, nf * (c + 1) / chunks);
  }
  w.centroid.resize(nv);
  w.boundary.resize(nv);
  w.mesh_normal.resize(nv);
  w.mean_edge.resize(nv);
  return chunks;
}

// Vertex v's centroid, boundary flag, mesh normal and mean edge from the ranges' sums.
inline void combine_ring(const Mesh48& mesh, Vertex v, int chunks, Work& w) {
  const auto k = static_cast<std::size_t>(v.idx);
  auto touched = [&](const RingSum& r) { return r.call == w.ring_call; };
  const RingSum* total = touched(w.ring_sums[0][k]) ? &w.ring_sums[0][k] : &kUntouched;
  std::optional<RingSum> added;  // (not constructed unless two ranges touched the vertex)
  // The ranges that touched it, in order; the first as it is (x + 0 is not always x: -0).
  for (std::size_t c = 1; c < static_cast<std::size_t>(chunks); ++c) {
    const RingSum& r = w.ring_sums[c][k];
    if (!touched(r)) continue;
    if (total == &kUntouched) {
      total = &r;
      continue;
    }
    if (!added) total = &added.emplace(*total);
    added->sum += r.sum;
    added->normal += r.normal;
    added->weight += r.weight;
    added->length += r.length;
    added->edges = static_cast<std::uint16_t>(added->edges + r.edges);
    added->boundary |= r.boundary;
  }
  w.centroid[k] = total->weight > 0 ? Vec3(total->sum / total->weight) : mesh.position(v);
  w.boundary[k] = total->boundary;
  const double area2 = total->normal.norm();
  w.mesh_normal[k] = area2 > 0 ? Vec3(total->normal / area2) : Vec3(Vec3::Zero());
  w.mean_edge[k] = total->edges ? total->length / total->edges : 0.0;
}

// `implicit`: the surface as an ImplicitSurface, or null when it is parametric (cast once per
// call, not once per vertex: the cast was 0.6% of a capsule-bend step at 10^5 triangles).
PrincipalCurvatures curvature_of(const Surface& s, const ImplicitSurface* implicit,
                                 const Mesh48& mesh, Vertex v) {
  if (implicit) return implicit->curvatures(mesh.position(v));
  return static_cast<const ParametricSurface&>(s).curvatures(mesh.uv(v));
}

// Frame reuse. A vertex's curvature frame (normal, principal directions and curvatures) is
// a property of the surface at its position; from one step to the next a vertex moves little
// and the surface under it changes little, so the frame evaluated before is reused when all of
//   (a) it is less than kFrameReuseCalls calls old; vertex i is evaluated afresh on every
//       call where (phase_i + call) % kFrameReuseCalls == 0 (phase_i: i modulo
//       kFrameReuseCalls when the slot was made), so no frame lives longer;
//   (b) the vertex moved at most kFrameReuseAngle / |k|max since (so that, on the surface as
//       it was, its normal turned by at most kFrameReuseAngle radians) and at most
//       kFrameReuseAngle times its ring's mean edge length (a sudden jump, a flat region).
//       On a surface with a rest map (ImplicitSurface::has_rest_map) the move that counts is
//       the vertex's slide over the material, measured in rest space: the rest of its move
//       carries the frame with the material, which turns it (seen by (c)) but does not move
//       it across the surface's shape. The whole move scaled with the mesh, not with the
//       surface: at 10^6 triangles (capsule-bend, a step carrying a vertex ~3e-3, about an
//       edge) it let only 13-16% of the frames be reused;
//   (c) its mesh normal (area-weighted, of its one-ring) turned by at most kFrameReuseAngle
//       since: the mesh follows the surface, so this sees the surface turning under a vertex
//       that itself barely moved (rotation about an axis through it).
// Assumption: the curvature magnitudes and directions change by a small fraction over
// kFrameReuseCalls steps wherever (a)-(c) hold (smooth motion). A stale frame only changes
// Equation 1's weights and the tangent plane the move is made in by ~kFrameReuseAngle: the
// move is still projected onto the surface, and the guards below still judge the moved faces
// against the frames' normals (a fold turns a face by far more). No error bound depends on
// the frames: the sampled error still decides every split and weld. Frames are forgotten for
// vertices born by a split (SmoothingWorkspace::after_split) and when the caller replaces the
// mesh (forget_frames). The adapter reuses none in a step that needed sub-steps (a motion fast
// against the mesh); a sub-stepped twist (MotionFrames.AnalyticScenesReturnToStart) otherwise
// drifted 6.6% in triangles between its second and third cycles, against 1.2% without reuse.
constexpr std::uint64_t kFrameReuseCalls = 8;
constexpr double kFrameReuseAngle = 0.05;  // radians

void grow_phases(Work& w, std::size_t capacity) {
  for (std::size_t i = w.phase.size(); i < capacity; ++i)
    w.phase.push_back(static_cast<std::uint8_t>(i % kFrameReuseCalls));
}

// `rest`: the vertex's rest-space point, or nothing (no rest map: the whole move counts).
bool frame_reusable(const Work& w, std::size_t i, const Vec3& p, const Vec3* rest) {
  const CachedFrame& c = w.cached[i];
  if (c.call == 0 || (w.phase[i] + w.calls) % kFrameReuseCalls == 0 ||
      w.calls + 1 - c.call >= kFrameReuseCalls)
    return false;
  const double moved = rest ? (*rest - c.rest).norm() : (p - c.at).norm();
  const double kmax = std::max(std::abs(c.k.k1), std::abs(c.k.k2));
  if (moved * kmax > kFrameReuseAngle || moved > kFrameReuseAngle * w.mean_edge[i]) return false;
  const Vec3& n = w.mesh_normal[i];
  return n.dot(c.mesh_normal) >= std::cos(kFrameReuseAngle) && !n.isZero();
}

// The rings' sums combined and each vertex's frame (evaluated or reused), in one sweep over
// the vertices: frame reuse reads the mesh normal and mean edge just combined, and at 10^6
// triangles a separate sweep re-reads them from memory. Returns how Equation 1 is to read the
// frames' curvature magnitudes (the range is the live vertices', as before).
Weights compute_rings_and_frames(const Mesh48& mesh, const Surface& surface,
                                 const SmoothingOptions& o, Work& w) {
  const int chunks = sum_rings(mesh, o.scale_invariant_weights, w);
  const auto n = static_cast<std::int64_t>(mesh.vertex_capacity());
  // Every live vertex's frame is written below, and no other is read: no clearing pass.
  w.frame.resize(mesh.vertex_capacity());
  if (w.reuse && w.cached.size() < mesh.vertex_capacity()) {
    w.cached.resize(mesh.vertex_capacity());
    grow_phases(w, mesh.vertex_capacity());
  }
  double lo = 1e300, hi = 0.0;
  std::size_t reused = 0;
  const auto* implicit = dynamic_cast<const ImplicitSurface*>(&surface);
  const bool material = w.reuse && implicit && implicit->has_rest_map();
  const bool known_rest = o.rest_points && o.rest_points->size() >= mesh.vertex_capacity();
#pragma omp parallel for schedule(dynamic, 512) reduction(min   \
                                                          : lo) \
    reduction(max                                               \
              : hi) reduction(+ : reused) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    combine_ring(mesh, v, chunks, w);
    if (!mesh.is_alive(v)) continue;
    const auto k = static_cast<std::size_t>(i);
    Frame& f = w.frame[k];
    const Vec3 rest = !material    ? Vec3::Zero()
                      : known_rest ? (*o.rest_points)[k]
                                   : implicit->to_rest(mesh.position(v));
    if (w.reuse && frame_reusable(w, k, mesh.position(v), material ? &rest : nullptr)) {
      f.k = w.cached[k].k;
      ++reused;
    } else {
      f.k = curvature_of(surface, implicit, mesh, v);
      if (w.reuse)
        w.cached[k] = CachedFrame{f.k, mesh.position(v), rest, w.mesh_normal[k], w.calls + 1};
    }
    f.l1 = std::abs(f.k.k1);
    f.l2 = std::abs(f.k.k2);
    lo = std::min({lo, f.l1, f.l2});
    hi = std::max({hi, f.l1, f.l2});
  }
  w.reused = reused;
  return Weights{o.raw_curvature, lo, hi - lo};
}

// Equation 1's d: the part of p - c on the tangent plane of normal n.
inline Vec3 tangential_offset(const Vec3& p, const Vec3& centroid, const Vec3& normal) {
  const Vec3 vec = p - centroid;
  return vec - vec.dot(normal) * normal;
}

// Equation 1's tangential move of a vertex whose tangential offset from its ring centroid is d.
Vec3 equation1_move(const Frame& f, const Vec3& d, const SmoothingOptions& o, const Weights& l) {
  const double k = o.k;
  return -(f.k.dir1.dot(d) * std::exp(-k * l(f.l1)) * f.k.dir1 +
           f.k.dir2.dot(d) * std::exp(-k * l(f.l2)) * f.k.dir2);
}

// A face is acceptable when none of its vertices moved, or when it faces the same way as the
// surface and its smallest angle is not pushed below the limit (or is no worse than it was).
// `cos_limit`: the cosine of the limit angle.
bool face_acceptable(const Mesh48& mesh, const Work& w, Face f, double cos_limit) {
  const auto v = mesh.vertices(f);
  if (!w.moved[v[0].idx] && !w.moved[v[1].idx] && !w.moved[v[2].idx]) return true;
  const Vec3 &a = w.position[v[0].idx], &b = w.position[v[1].idx], &c = w.position[v[2].idx];
  const Vec3 surface_normal =
      w.frame[v[0].idx].k.normal + w.frame[v[1].idx].k.normal + w.frame[v[2].idx].k.normal;
  if ((b - a).cross(c - a).dot(surface_normal) <= 0) return false;
  const double now = smallest_angle_cosine(a, b, c);
  if (now <= cos_limit) return true;
  return now <=
         smallest_angle_cosine(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]));
}

// Undoes moves around unacceptable faces until none is left (Jacobi moves interact): every
// face is checked once, in parallel (listed in face order, as a serial check lists them);
// afterwards only the faces around undone moves.
std::size_t apply_guards(const Mesh48& mesh, Work& w, double limit_deg) {
  const double cos_limit = std::cos(limit_deg * M_PI / 180.0);
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  w.bad_collector.collect(n, w.check, [&](std::int64_t i, Face& f) {
    f = Face(static_cast<std::uint32_t>(i));
    return mesh.is_alive(f) && !face_acceptable(mesh, w, f, cos_limit);
  });
  std::size_t reverted = 0;
  for (int round = 0; round < 8 && !w.check.empty(); ++round) {
    w.next_check.clear();
    for (Face f : w.check) {
      if (face_acceptable(mesh, w, f, cos_limit)) continue;
      for (Vertex v : mesh.vertices(f)) {
        if (!w.moved[v.idx]) continue;
        w.moved[v.idx] = 0;
        w.position[v.idx] = mesh.position(v);
        w.uv[v.idx] = mesh.uv(v);
        ++reverted;
        mesh.for_each_corner_around(v, [&](Corner c) { w.next_check.push_back(c.face); });
      }
    }
    w.check.swap(w.next_check);
  }
  return reverted;
}

SmoothingResult smooth_once(Mesh48& mesh, const Surface& surface, const SmoothingOptions& o,
                            Work& w) {
  const std::size_t cap = mesh.vertex_capacity();
  // Filled by the move loop below (each slot's old place, then its move), not copied whole
  // first: one sweep over the vertices instead of three.
  w.position.resize(cap);
  w.uv.resize(cap);
  w.moved.resize(cap);
  w.value.resize(cap);
  w.gradient.resize(cap);
  // Ring centroids first: frame reuse reads the mesh normals they sum.
  const Weights weights = compute_rings_and_frames(mesh, surface, o, w);
  ++w.calls;
  const auto* par = dynamic_cast<const ParametricSurface*>(&surface);
  const auto* imp = dynamic_cast<const ImplicitSurface*>(&surface);
  const auto n = static_cast<std::int64_t>(cap);
  // A family that moves its points only normal to an axis: the move keeps the coordinate along
  // it (Surface::invariant_axis).
  const Vec3 axis = imp ? imp->invariant_axis() : Vec3::Zero();
  const double settled2 = o.settled_offset * o.settled_offset;
  // (A vertex's entry in o.evaluations, if any: checked against its place and the epoch.)
  const bool known =
      imp && o.evaluations && o.evaluations_epoch != 0 && o.evaluations->size() >= cap;
  std::size_t failures = 0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : failures) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    w.moved[k] = 0;
    if (!mesh.is_alive(v)) continue;
    // Unmoved (settled, failed, or a guard undoes it), the vertex stays where it is.
    w.position[k] = mesh.position(v);
    w.uv[k] = mesh.uv(v);
    const Vec3 d = tangential_offset(mesh.position(v), w.centroid[k], w.frame[k].k.normal);
    if (d.squaredNorm() < settled2 * (w.mean_edge[k] * w.mean_edge[k])) continue;
    Vec3 move = equation1_move(w.frame[k], d, o, weights);
    move -= move.dot(axis) * axis;
    Vec3 landing;
    const PointEvaluation* at_p = known ? &(*o.evaluations)[k] : nullptr;
    const bool from_landing =
        at_p && at_p->epoch == o.evaluations_epoch && at_p->point == mesh.position(v);
    if (from_landing) landing = second_order_landing(*at_p, w.frame[k].k, move);
    const bool ok = par ? parametric_move(*par, mesh, v, move, w.uv[k], w.position[k])
                        : !w.boundary[k] && implicit_move(*imp, mesh, v, move, w.position[k],
                                                          failures, &w.value[k], &w.gradient[k],
                                                          from_landing ? &landing : nullptr);
    w.moved[k] = ok ? 1 : 0;
  }
  SmoothingResult r;
  r.projection_failures = failures;
  r.frames_reused = w.reused;
  r.reverted = apply_guards(mesh, w, o.min_angle_deg);
  std::size_t moved = 0;
#pragma omp parallel for schedule(static) reduction(+ : moved) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!w.moved[k]) continue;
    mesh.position(Vertex(static_cast<std::uint32_t>(i))) = w.position[k];
    mesh.uv(Vertex(static_cast<std::uint32_t>(i))) = w.uv[k];
    ++moved;
  }
  r.moved = moved;
  return r;
}

}  // namespace

void SmoothingWorkspace::after_renumber(Mesh48&, const Renumbering& r) {
  Buffers& w = *buffers_;
  grow_phases(w, r.vertex.size());
  renumber_elements(w.phase, r.vertex, r.n_vertices);
  renumber_elements(w.cached, r.vertex, r.n_vertices);
  renumber_elements(w.moved, r.vertex, r.n_vertices);
  renumber_elements(w.value, r.vertex, r.n_vertices);
  renumber_elements(w.gradient, r.vertex, r.n_vertices);
}

SmoothingResult smooth_tangentially(Mesh48& mesh, const Surface& surface,
                                    const SmoothingOptions& options,
                                    SmoothingWorkspace* workspace) {
  SmoothingResult total;
  if (!options.enabled) return total;
  std::optional<SmoothingWorkspace> local;
  Work& work = (workspace ? *workspace : local.emplace()).buffers();
  work.reuse = workspace != nullptr && options.reuse_frames;
  for (int it = 0; it < options.iterations; ++it) {
    const SmoothingResult r = smooth_once(mesh, surface, options, work);
    total.moved += r.moved;
    total.reverted += r.reverted;
    total.projection_failures += r.projection_failures;
    total.frames_reused += r.frames_reused;
  }
  return total;
}

}  // namespace dynamesh
