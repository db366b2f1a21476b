#include "core/adapt/error_predictor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/adapt/error_model.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

// The vertices' first-order data give the change of the residual's quadratic and cubic
// parts along the edges (c, d); the sampled reading moves with the rest too: the cubic term
// inside the face that no edge sees, higher terms, and the least-squares fit's response to
// them (error_model.h). Measured, bound usage (a skipped face's fresh reading's change over
// its bound, max over 100 steps over [0, 1] at T = 0.002, test_predictive_sampling.cpp):
// without d, twist 1.4 with a factor 8 (the cubic change on its rims; before the edge peak
// search the trajectory happened to avoid it: 0.69); with d, 0.14-0.17 with 8 and 0.24-0.42
// with 4 (twist, capsule-bend, sinc, sphere). With 5: twist 0.238, capsule-bend 0.245, sinc
// 0.242, sphere 0.192; with the quadratic part's exact maximum on implicit surfaces (this
// code, up to 1/4 smaller than the estimate it replaced): twist 0.275, capsule-bend 0.324,
// sinc 0.332 (parametric: unchanged), sphere 0.200, a margin of 3 on the largest.
constexpr double kSafety = 5.0;

// A face whose edges all changed by a factor within 1 +- s, on a surface whose curvatures did
// not change, reads up to (1 + s)^2 of its error (the residual grows as the square of the
// face's size at a given curvature): 2 s of it, to first order. The vertices' data do not
// see this where the face stretches across a curvature jump (a C1 seam: the capsule's
// cylinder meeting its caps, bent by capsule-bend): without this term, skipped faces on the
// seams' inner side used 0.99 of their bound there (1.29 with kMaxTravelFraction 0.1),
// with it 0.25 (PredictiveAnimation/capsule_bend, T = 0.002). Added only in steps whose
// vertices were carried with the material (a rest map): there the seam stays under the same
// faces and the slide guard does not see the face stretching across it. Without a rest map
// a seam moves relative to the corners, which the slide guard (the whole move) measures;
// applied there too, the term measured the twist's sheared sides needlessly
// (21% -> 28% of its faces, Cli.SamplingOptionChoosesWhatIsMeasured above 0.5).
constexpr double kStrainGain = 2.0;

// Over the triangle, max of b_i b_j |b_j - b_i| on one edge's term (at 2 t - 1 = 1 / sqrt 3),
// and of their sum over the three edges (numerically, on a 600-point lattice: 0.11756).
constexpr double kCubicEdge = 0.0962250448649376;  // 1 / (6 sqrt 3)
constexpr double kCubicSum = 0.1176;

// The largest and the summed change of the three edges' coefficient vectors.
struct Change {
  double largest = 0.0, sum = 0.0;
};
Change change(const float (&now)[3][3], const float (&then)[3][3]) {
  Change out;
  for (int e = 0; e < 3; ++e) {
    double d2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(now[e][c]) - then[e][c];
      d2 += d * d;
    }
    const double d = std::sqrt(d2);
    out.largest = std::max(out.largest, d);
    out.sum += d;
  }
  return out;
}

// The residual along an edge, r(t) = t (1 - t) (c + d (2 t - 1)), with the slopes r'(0) =
// start and r'(1) = end at its ends: c and d from those slopes (a vector for parametric
// surfaces, the scalar first component for implicit ones; the same operations either way).
template <class T>
T quadratic_part(const T& start, const T& end) {
  return 0.5 * (start - end);
}
template <class T>
T cubic_part(const T& start, const T& end) {
  return -0.5 * (start + end);
}

// The largest change over the triangle of the residual's quadratic part, sum_e b_i b_j dc_e,
// where the residual is a vector (parametric): with the maxima of sum b_i b_j (1/3) and of
// b_i b_j (1/4). Where it is scalar (implicit) select() takes its exact maximum
// (scalar_maximum, at most this estimate and at least 3/4 of it: x = (1, 1, 0) gives 1/4, not
// 1/3).
double quadratic_change(const float (&now)[3][3], const float (&then)[3][3]) {
  const Change c = change(now, then);
  return std::min(c.largest / 3.0, c.sum / 4.0);
}

// The largest relative change of an edge's length.
double strain(const float (&now)[3], const float (&then)[3]) {
  double out = 0.0;
  for (int e = 0; e < 3; ++e)
    out = std::max(out, std::abs(static_cast<double>(now[e]) / then[e] - 1.0));
  return out;
}

}  // namespace

void ErrorPredictor::invalidate() {
  std::fill(has_reference_.begin(), has_reference_.end(), 0);
  radius_.fill(std::numeric_limits<double>::infinity());
}

void ErrorPredictor::keep_parametric_data(const SurfaceProbe& probe) {
  if (probe.parametric() == parametric_) return;
  parametric_ = probe.parametric();
  if (!parametric_) return;
  tangents_.resize(frame_.size());
  vector_reference_.resize(reference_.size());
}

void ErrorPredictor::grow(const Mesh48& mesh) {
  if (frame_.size() < mesh.vertex_capacity()) {
    frame_.resize(mesh.vertex_capacity());
    if (parametric_) tangents_.resize(mesh.vertex_capacity());
    frame_step_.resize(mesh.vertex_capacity(), 0);
    moved_.resize(mesh.vertex_capacity(), 0.0f);
    slid_.resize(mesh.vertex_capacity(), 0.0f);
    evaluated_.resize(mesh.vertex_capacity());
  }
  if (reference_.size() < mesh.face_capacity()) {
    reference_.resize(mesh.face_capacity());
    if (parametric_) vector_reference_.resize(mesh.face_capacity());
    has_reference_.resize(mesh.face_capacity(), 0);
    bound_.resize(mesh.face_capacity(), 0.0);
    rise_.resize(mesh.face_capacity(), 0.0);
    travel_.resize(mesh.face_capacity(), 0.0f);
  }
}

void ErrorPredictor::refresh_vertex(const Mesh48& mesh, const SurfaceProbe& probe, Vertex v,
                                    std::uint64_t epoch) {
  VertexFrame& frame = frame_[v.idx];
  if (probe.parametric()) {
    const auto& s = static_cast<const ParametricSurface&>(probe.surface());
    const ParametricDerivatives d = s.derivatives(mesh.uv(v));
    tangents_[v.idx] = Tangents{d.su, d.sv};
    const Vec3 n = d.su.cross(d.sv);
    const double length = n.norm();
    frame.normal = length > 0 ? Vec3(n / length) : Vec3::Zero();
    frame.offset = 0.0;
  } else {
    const auto& s = static_cast<const ImplicitSurface&>(probe.surface());
    Vec3 g;
    const PointEvaluation& e = evaluated_[v.idx];
    const bool known = epoch != 0 && e.epoch == epoch && e.point == mesh.position(v);
    if (known) g = e.gradient;
    const double value = known ? e.value : s.value_gradient(mesh.position(v), g);
    const double norm = g.norm();
    frame.normal = norm > 0 ? Vec3(g / norm) : Vec3::Zero();
    frame.offset = norm > 0 ? std::abs(value) / norm : std::numeric_limits<double>::infinity();
  }
  frame_step_[v.idx] = step_ + 1;
}

void ErrorPredictor::begin_step(const Mesh48& mesh, const SurfaceProbe& probe,
                                const std::vector<Vec3>& start_positions, std::uint64_t step,
                                std::uint64_t epoch, const std::vector<Vec3>* material_positions) {
  step_ = step;
  keep_parametric_data(probe);
  grow(mesh);
  const auto n = static_cast<std::int64_t>(mesh.vertex_capacity());
  std::size_t reused = 0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : reused) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(v)) continue;
    const PointEvaluation& e = evaluated_[static_cast<std::size_t>(i)];
    reused += epoch != 0 && e.epoch == epoch && e.point == mesh.position(v);
    refresh_vertex(mesh, probe, v, epoch);
    const auto k = static_cast<std::size_t>(i);
    // A vertex without a start (born this step, or NaN after a renumbering): infinitely far.
    const auto distance = [&](const std::vector<Vec3>& from) {
      const auto d = k < from.size() ? static_cast<float>((mesh.position(v) - from[k]).norm())
                                     : std::numeric_limits<float>::infinity();
      return d <= std::numeric_limits<float>::max() ? d : std::numeric_limits<float>::infinity();
    };
    moved_[k] = distance(start_positions);
    slid_[k] = material_positions ? distance(*material_positions) : moved_[k];
  }
  reused_evaluations_ = probe.parametric() ? 0 : reused;
  carried_ = material_positions != nullptr;
}

ErrorPredictor::Coefficients ErrorPredictor::coefficients(const Mesh48& mesh,
                                                          const SurfaceProbe& probe, Face f) const {
  const auto v = mesh.vertices(f);
  Vec3 edge[3];
  for (int e = 0; e < 3; ++e)
    edge[e] = mesh.position(v[(e + 2) % 3]) - mesh.position(v[(e + 1) % 3]);
  return coefficients(mesh, probe, v, edge);
}

ErrorPredictor::Coefficients ErrorPredictor::coefficients(const Mesh48& mesh,
                                                          const SurfaceProbe& probe,
                                                          const std::array<Vertex, 3>& v,
                                                          const Vec3 (&edges)[3]) const {
  Coefficients out{};
  for (int e = 0; e < 3; ++e) {
    const Vertex i = v[(e + 1) % 3], j = v[(e + 2) % 3];
    const VertexFrame &fi = frame_[i.idx], &fj = frame_[j.idx];
    const Vec3& edge = edges[e];
    // The residual's slopes along the edge at its ends, r'(0) and r'(1) (implicit: the distance
    // gradient n along the edge; parametric: the edge minus the surface's own step J duv).
    Vec3 start, end;
    if (probe.parametric()) {
      const auto& s = static_cast<const ParametricSurface&>(probe.surface());
      const Vec2 d = s.unwrap_near(mesh.uv(j), mesh.uv(i)) - mesh.uv(i);
      const Tangents &ti = tangents_[i.idx], &tj = tangents_[j.idx];
      start = edge - (ti.su * d[0] + ti.sv * d[1]);
      end = edge - (tj.su * d[0] + tj.sv * d[1]);
    } else {
      start = Vec3(edge.dot(fi.normal), 0.0, 0.0);
      end = Vec3(edge.dot(fj.normal), 0.0, 0.0);
    }
    const Vec3 c = quadratic_part(start, end), d = cubic_part(start, end);
    out.length[e] = static_cast<float>(edge.norm());
    for (int k = 0; k < 3; ++k) {
      out.c[e][k] = static_cast<float>(c[k]);
      out.d[e][k] = static_cast<float>(d[k]);
    }
  }
  return out;
}

void ErrorPredictor::select(const Mesh48& mesh, const SurfaceProbe& probe,
                            const SampleStore& samples, const SplitTest& would_split,
                            std::vector<Face>& measure) {
  keep_parametric_data(probe);
  grow(mesh);
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  flags_.resize(static_cast<std::size_t>(n));  // every slot written below (dead ones 0)
  const std::uint64_t phase = step_ % kRotation;
  // The strain term covers faces carried with the material across a seam; a face that moved
  // over the surface instead is covered by the slide guard (the whole move counts as slide).
  const double strain_gain = carried_ ? kStrainGain : 0.0;
  const bool implicit = !probe.parametric();
  // The curvature estimate is the largest rounded ratio |n_b - n_a| / chord over the edges.
  // An edge can raise a maximum c only if that ratio r exceeds c; then, with q the normals'
  // squared difference and u the unit roundoff, q > c^2 chord^2 (1 - 4u), and with
  // low = fl(c^2 kBelow) the rounded fl(low fl(chord^2)) is at most c^2 chord^2 kBelow (1 + u)^4,
  // below that for kBelow = 1 - 16 eps = 1 - 32u: every edge that can raise it passes the test
  // q > low chord^2, and only those pay a square root and a division (as estimate_substeps does
  // for the strain). The result is the same maximum in any order of the edges. NaN fails the
  // test, as std::max ignored it.
  constexpr double kBelow = 1.0 - 16.0 * std::numeric_limits<double>::epsilon();
  double curvature = 0.0;
#pragma omp parallel reduction(max : curvature) if (n > kParallelMin)
  {
    curvature = 0.0;  // (each thread's; the maximum is at least 0 anyway)
    double low = 0.0;
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t i = 0; i < n; ++i) {
      const Face f(static_cast<std::uint32_t>(i));
      const auto k = static_cast<std::size_t>(i);
      if (!mesh.is_alive(f)) {
        flags_[k] = 0;
        continue;
      }
      const auto v = mesh.vertices(f);
      Vec3 edge[3];  // edge e from corner e + 1 to corner e + 2
      double chord2[3], chord[3];
      float moved = 0.0f, slid = 0.0f, shortest2 = std::numeric_limits<float>::infinity();
      for (int e = 0; e < 3; ++e) {
        const Vertex a = v[(e + 1) % 3], b = v[(e + 2) % 3];
        edge[e] = mesh.position(b) - mesh.position(a);
        chord2[e] = edge[e].squaredNorm();
        chord[e] = std::sqrt(chord2[e]);  // what edge.norm() computes
        moved = std::max(moved, moved_[v[e].idx]);
        slid = std::max(slid, slid_[v[e].idx]);
        shortest2 = std::min(shortest2, static_cast<float>(chord2[e]));
        // Along a normal section of radius rho, the chord and the unit normals' difference are
        // 2 rho sin(phi / 2) and 2 sin(phi / 2): their ratio is exactly 1 / rho. A normal that
        // also turns about the edge (geodesic torsion) only makes the estimate larger. Each edge
        // once: from the face that sees it from its lower vertex id (or its only face).
        if ((a.idx < b.idx || !mesh.neighbor(f, e).is_valid()) && chord2[e] > 0) {
          const double q = (frame_[b.idx].normal - frame_[a.idx].normal).squaredNorm();
          if (q > low * (chord[e] * chord[e])) {
            curvature = std::max(curvature, std::sqrt(q) / chord[e]);
            low = curvature * curvature * kBelow;
          }
        }
      }
      travel_[k] += moved;  // reset by record()
      const bool slid_far =
          !(slid * slid <= static_cast<float>(kMaxSlideFraction * kMaxSlideFraction) * shortest2);
      // A face whose pattern no longer fits its area (SampleStore::pattern_outdated) gets a new
      // one before it is measured (Adapter::sampling); (p1 - p0) x (p2 - p0) as the samples
      // compute it (p2 - p0 is -edge[1] exactly).
      bool needed = !has_reference_[k] || !samples.measured(f) || samples.densified(f) ||
                    samples.on_turn(f) ||
                    samples.pattern_outdated(f, edge[2].cross(-edge[1]).squaredNorm());
      if (!needed && slid_far) {
        flags_[k] = 2;  // measured for its slide alone (guarded())
        continue;
      }
      if (!needed) {
        // The face's frames are this step's (begin_step), its reference its last measurement's.
        double quadratic, stretch;
        Change cubic;
        if (implicit) {
          // The residual is scalar: only each edge's first components (c, d) and its length
          // enter, computed as coefficients() computes them (quadratic_part, cubic_part: the
          // same floats; the length is the chord), without filling the zeros. The cubic change is
          // change()'s to the bit: the norm of (x, 0, 0) is sqrt(x * x), which is
          // |x| exactly (x, a difference of two floats, neither underflows nor overflows when
          // squared in double).
          const ScalarCoefficients& then = reference_[k];
          double x[3];
          float length[3];
          cubic = Change{};
          for (int e = 0; e < 3; ++e) {
            const double start = edge[e].dot(frame_[v[(e + 1) % 3].idx].normal);
            const double end = edge[e].dot(frame_[v[(e + 2) % 3].idx].normal);
            x[e] = static_cast<double>(static_cast<float>(quadratic_part(start, end))) - then.c[e];
            const double d = std::abs(
                static_cast<double>(static_cast<float>(cubic_part(start, end))) - then.d[e]);
            cubic.largest = std::max(cubic.largest, d);
            cubic.sum += d;
            length[e] = static_cast<float>(chord[e]);
          }
          quadratic = scalar_maximum(x[0], x[1], x[2]);
          stretch = strain(length, then.length);
        } else {
          const Coefficients now = coefficients(mesh, probe, v, edge);
          const Coefficients& then = vector_reference_[k];
          quadratic = quadratic_change(now.c, then.c);
          cubic = change(now.d, then.d);
          stretch = strain(now.length, then.length);
        }
        double offset = 0.0;
        for (Vertex x : v) offset = std::max(offset, frame_[x.idx].offset);
        const double residual =
            kSafety * (quadratic + std::min(cubic.largest * kCubicSum, cubic.sum * kCubicEdge) +
                       offset + strain_gain * stretch * samples.face_error(f));
        // The reading follows the residual at the samples and, near the split bound, on the
        // edges (SampleStore::set_peak_search).
        bound_[k] = residual * samples.reading_gain(f, residual);
        rise_[k] = residual;
        // The split decision needs only the top of the reading's range (reading_range: below
        // face_error + bound where the model is the reading; it halved the faces the twist
        // measured for the split bound, T = 1e-3), looked at only where the cheaper top could
        // split.
        const double e = samples.face_error(f);
        needed = would_split(f, e + bound_[k]) && would_split(f, reading_range(samples, f).hi);
      }
      flags_[k] = needed;
    }
  }
  // The smallest radius over the steps any reference can date from (kRotation): the shape
  // a face was measured on counts as much as today's.
  radius_[phase] = curvature > 0 ? 1.0 / curvature : std::numeric_limits<double>::infinity();
  curvature_radius_ = *std::min_element(radius_.begin(), radius_.end());
  const auto limit = static_cast<float>(kMaxTravelFraction * curvature_radius_);
  // In parallel, in face order (OrderedCollector).
  std::atomic<std::size_t> guarded{0};
  collector_.collect(n, measure, [&](std::int64_t i, Face& f) {
    f = Face(static_cast<std::uint32_t>(i));
    const auto k = static_cast<std::size_t>(i);
    if (!mesh.is_alive(f)) return false;
    if (flags_[k] == 2 || (!flags_[k] && !(travel_[k] <= limit))) {
      flags_[k] = 1;
      guarded.fetch_add(1, std::memory_order_relaxed);  // rare (guarded())
    }
    return flags_[k] != 0;
  });
  guarded_ = guarded.load();
  skipped_ = mesh.n_faces() - measure.size();
}

void ErrorPredictor::after_split(Mesh48& mesh, const DiamondChange& change) {
  grow(mesh);
  frame_step_[change.vertex.idx] = 0;
}

void ErrorPredictor::after_renumber(Mesh48&, const Renumbering& r) {
  renumber_elements(frame_, r.vertex, r.n_vertices);
  if (parametric_) renumber_elements(tangents_, r.vertex, r.n_vertices);
  renumber_elements(frame_step_, r.vertex, r.n_vertices);
  renumber_elements(moved_, r.vertex, r.n_vertices);
  renumber_elements(slid_, r.vertex, r.n_vertices);
  renumber_elements(evaluated_, r.vertex, r.n_vertices);
  renumber_elements(reference_, r.face, r.n_faces);
  if (parametric_) renumber_elements(vector_reference_, r.face, r.n_faces);
  renumber_elements(has_reference_, r.face, r.n_faces);
  renumber_elements(bound_, r.face, r.n_faces);
  renumber_elements(rise_, r.face, r.n_faces);
  renumber_elements(travel_, r.face, r.n_faces);
  flags_.clear();  // select's scratch
}

void ErrorPredictor::record(const Mesh48& mesh, const SurfaceProbe& probe,
                            const std::vector<Face>& faces) {
  keep_parametric_data(probe);
  grow(mesh);
  // Vertices born this step (splits) have no frame yet: listed here (each once: marked as
  // listed), their frames computed in parallel below.
  unframed_.clear();
  for (Face f : faces) {
    if (!mesh.is_alive(f)) continue;
    for (Vertex v : mesh.vertices(f))
      if (frame_step_[v.idx] != step_ + 1) {
        frame_step_[v.idx] = step_ + 1;
        unframed_.push_back(v);
      }
  }
  const auto m = static_cast<std::int64_t>(unframed_.size());
#pragma omp parallel for schedule(static) if (m > kParallelMinCostly)
  for (std::int64_t i = 0; i < m; ++i)
    refresh_vertex(mesh, probe, unframed_[static_cast<std::size_t>(i)]);
  // A face's coefficients cost a few hundred nanoseconds: the ~2,000 faces a twist step
  // measures (15,000 triangles) are worth both threads, which kParallelMin denied them.
  const auto n = static_cast<std::int64_t>(faces.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinCostly)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f = faces[static_cast<std::size_t>(i)];
    if (!mesh.is_alive(f)) continue;
    const Coefficients now = coefficients(mesh, probe, f);
    if (parametric_) {
      vector_reference_[f.idx] = now;
    } else {
      ScalarCoefficients& scalar = reference_[f.idx];
      for (int e = 0; e < 3; ++e) {
        scalar.c[e] = now.c[e][0];
        scalar.d[e] = now.d[e][0];
        scalar.length[e] = now.length[e];
      }
    }
    has_reference_[f.idx] = 1;
    bound_[f.idx] = 0.0;
    rise_[f.idx] = 0.0;
    travel_[f.idx] = 0.0f;
  }
}

}  // namespace dynamesh
