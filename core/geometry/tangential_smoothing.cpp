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
  double l1 = 0, l2 = 0;  // curvature magnitudes as used by Equation 1
};

// One thread's partial sum of a vertex's one-ring (compute_ring_centroids).
struct RingSum {
  Vec3 sum{Vec3::Zero()};
  double weight = 0.0;
  std::uint8_t boundary = 0;
};

}  // namespace

// The state one iteration reads (old positions) and writes (candidates).
struct SmoothingWorkspace::Buffers {
  std::vector<Frame> frame;
  std::vector<Vec3> position;
  std::vector<Vec2> uv;
  std::vector<std::uint8_t> moved;
  std::vector<Vec3> centroid;                   // of each vertex's one-ring
  std::vector<std::vector<RingSum>> ring_sums;  // per thread, while summing
  std::vector<std::uint8_t> boundary;           // per vertex: on an open boundary
  std::vector<std::uint8_t> bad;                // per face slot: fails the guards
  std::vector<Face> check, next_check;
};

SmoothingWorkspace::SmoothingWorkspace() : buffers_(std::make_unique<Buffers>()) {}
SmoothingWorkspace::~SmoothingWorkspace() = default;

namespace {

using Work = SmoothingWorkspace::Buffers;

// Centroids of every vertex's one-ring, and which vertices lie on the boundary, in one pass
// over the faces that meets each edge once (from its lower-numbered halfedge): walking each
// vertex's ring instead chases faces scattered through memory. Uniform weights are the
// paper's; inverse edge-length weights (Fujiwara's scale-invariant Laplacian) make a graded
// ring a fixed point — with uniform weights a vertex at a level transition of the 4-8 mesh
// is pulled towards the coarse side, fine regions lose resolution and are split again, and
// the mesh grows cycle after cycle of a periodic deformation.
// In parallel: each thread sums its share of the faces into its own accumulators (an edge
// adds to both its ends, which other threads' edges share), then the sums are combined.
void compute_ring_centroids(const Mesh48& mesh, bool scale_invariant, Work& w) {
  const std::size_t nv = mesh.vertex_capacity();
  const auto nf = static_cast<std::int64_t>(mesh.face_capacity());
  const int threads = nf > kParallelMin ? omp_get_max_threads() : 1;
  w.ring_sums.resize(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    std::vector<RingSum>& sums = w.ring_sums[static_cast<std::size_t>(omp_get_thread_num())];
    sums.assign(nv, RingSum{});
#pragma omp for schedule(static)
    for (std::int64_t f = 0; f < nf; ++f) {
      if (!mesh.is_alive(Face(static_cast<std::uint32_t>(f)))) continue;
      for (int e = 0; e < 3; ++e) {
        const Halfedge h(Face(static_cast<std::uint32_t>(f)), e);
        const Halfedge twin = mesh.twin(h);
        if (twin.is_valid() && twin.idx < h.idx) continue;  // met from the twin
        const Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h);
        if (!twin.is_valid()) sums[a.idx].boundary = sums[b.idx].boundary = 1;
        const Vec3 &pa = mesh.position(a), &pb = mesh.position(b);
        const double length = (pa - pb).norm();
        const double weight = scale_invariant ? (length > 0 ? 1.0 / length : 0.0) : 1.0;
        sums[a.idx].sum += weight * pb;
        sums[a.idx].weight += weight;
        sums[b.idx].sum += weight * pa;
        sums[b.idx].weight += weight;
      }
    }
  }
  w.centroid.resize(nv);
  w.boundary.resize(nv);
  const auto n = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    RingSum total = w.ring_sums[0][k];
    for (std::size_t t = 1; t < w.ring_sums.size(); ++t) {
      total.sum += w.ring_sums[t][k].sum;
      total.weight += w.ring_sums[t][k].weight;
      total.boundary |= w.ring_sums[t][k].boundary;
    }
    w.centroid[k] = total.weight > 0 ? Vec3(total.sum / total.weight)
                                     : mesh.position(Vertex(static_cast<std::uint32_t>(i)));
    w.boundary[k] = total.boundary;
  }
}

PrincipalCurvatures curvature_of(const Surface& s, const Mesh48& mesh, Vertex v) {
  if (const auto* p = dynamic_cast<const ParametricSurface*>(&s)) return p->curvatures(mesh.uv(v));
  return static_cast<const ImplicitSurface&>(s).curvatures(mesh.position(v));
}

void compute_frames(const Mesh48& mesh, const Surface& surface, const SmoothingOptions& o,
                    Work& w) {
  const auto n = static_cast<std::int64_t>(mesh.vertex_capacity());
  double lo = 1e300, hi = 0.0;
#pragma omp parallel for schedule(dynamic, 512) reduction(min   \
                                                          : lo) \
    reduction(max                                               \
              : hi) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(v)) continue;
    Frame& f = w.frame[static_cast<std::size_t>(i)];
    f.k = curvature_of(surface, mesh, v);
    f.l1 = std::abs(f.k.k1);
    f.l2 = std::abs(f.k.k2);
    lo = std::min({lo, f.l1, f.l2});
    hi = std::max({hi, f.l1, f.l2});
  }
  if (o.raw_curvature) return;
  // Normalised to [0, 1] by the mesh-wide range (the original implementation's choice).
  const double range = hi - lo;
  for (Frame& f : w.frame) {
    f.l1 = range > 0 ? (f.l1 - lo) / range : 0.0;
    f.l2 = range > 0 ? (f.l2 - lo) / range : 0.0;
  }
}

// Equation 1's tangential move of one vertex (towards its ring centroid).
Vec3 equation1_move(const Mesh48& mesh, Vertex v, const Frame& f, const Vec3& centroid,
                    const SmoothingOptions& o) {
  const double k = o.k;
  const Vec3 vec = mesh.position(v) - centroid;
  const Vec3 d = vec - vec.dot(f.k.normal) * f.k.normal;
  return -(f.k.dir1.dot(d) * std::exp(-k * f.l1) * f.k.dir1 +
           f.k.dir2.dot(d) * std::exp(-k * f.l2) * f.k.dir2);
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
// face is checked once, in parallel; afterwards only the faces around undone moves.
std::size_t apply_guards(const Mesh48& mesh, Work& w, double limit_deg) {
  const double cos_limit = std::cos(limit_deg * M_PI / 180.0);
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  w.bad.assign(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(dynamic, 1024) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (mesh.is_alive(f))
      w.bad[static_cast<std::size_t>(i)] = !face_acceptable(mesh, w, f, cos_limit);
  }
  w.check.clear();
  for (std::int64_t i = 0; i < n; ++i)
    if (w.bad[static_cast<std::size_t>(i)]) w.check.push_back(Face(static_cast<std::uint32_t>(i)));
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
  w.frame.assign(cap, Frame{});
  w.position = mesh.positions();
  w.uv = mesh.uvs();
  w.moved.assign(cap, 0);
  compute_frames(mesh, surface, o, w);
  compute_ring_centroids(mesh, o.scale_invariant_weights, w);
  const auto* par = dynamic_cast<const ParametricSurface*>(&surface);
  const auto* imp = dynamic_cast<const ImplicitSurface*>(&surface);
  const auto n = static_cast<std::int64_t>(cap);
  // A family that moves its points only normal to an axis: the move keeps the coordinate along
  // it (Surface::invariant_axis).
  const Vec3 axis = imp ? imp->invariant_axis() : Vec3::Zero();
  std::size_t failures = 0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : failures) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    if (!mesh.is_alive(v)) continue;
    Vec3 move = equation1_move(mesh, v, w.frame[k], w.centroid[k], o);
    move -= move.dot(axis) * axis;
    const bool ok =
        par ? parametric_move(*par, mesh, v, move, w.uv[k], w.position[k])
            : !w.boundary[k] && implicit_move(*imp, mesh, v, move, w.position[k], failures);
    w.moved[k] = ok ? 1 : 0;
  }
  SmoothingResult r;
  r.projection_failures = failures;
  r.reverted = apply_guards(mesh, w, o.min_angle_deg);
  for (std::size_t i = 0; i < cap; ++i) {
    if (!w.moved[i]) continue;
    mesh.position(Vertex(static_cast<std::uint32_t>(i))) = w.position[i];
    mesh.uv(Vertex(static_cast<std::uint32_t>(i))) = w.uv[i];
    ++r.moved;
  }
  return r;
}

}  // namespace

SmoothingResult smooth_tangentially(Mesh48& mesh, const Surface& surface,
                                    const SmoothingOptions& options,
                                    SmoothingWorkspace* workspace) {
  SmoothingResult total;
  if (!options.enabled) return total;
  std::optional<SmoothingWorkspace> local;
  Work& work = (workspace ? *workspace : local.emplace()).buffers();
  for (int it = 0; it < options.iterations; ++it) {
    const SmoothingResult r = smooth_once(mesh, surface, options, work);
    total.moved += r.moved;
    total.reverted += r.reverted;
    total.projection_failures += r.projection_failures;
  }
  return total;
}

}  // namespace dynamesh
