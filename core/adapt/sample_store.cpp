#include "core/adapt/sample_store.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "core/adapt/error_model.h"
#include "core/allocator_policy.h"
#include "core/mesh/bisection_map.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

// SplitMix64: a counter-based generator, so a pattern depends only on its key (draw_pattern).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double uniform01(std::uint64_t& state) {
  state = mix(state);
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

// |(p1 - p0) x (p2 - p0)|^2: the face's doubled area, squared.
double doubled_area_squared(const Mesh48& mesh, Face f) {
  const auto v = mesh.vertices(f);
  const Vec3& a = mesh.position(v[0]);
  return (mesh.position(v[1]) - a).cross(mesh.position(v[2]) - a).squaredNorm();
}

double face_area(const Mesh48& mesh, Face f) {
  return 0.5 * std::sqrt(doubled_area_squared(mesh, f));
}

// One edge's part of SampleStore::edge_peaks, with what sharing it with the face across needs.
struct EdgeReading {
  double peak = 0.0;         // the largest residual found along the edge
  double largest = 0.0;      // the largest residual among the points evaluated on it
  double nearest_end = 0.0;  // of those points the nearest to an end, as a share of the edge
  bool tied = false;         // EdgePeak::tied
};

// Edge e joins vertices e + 1 (t = 0) and e + 2 (t = 1).
EdgeReading read_edge(const SurfaceProbe& probe, const Vec3 p[3], const Vec2 uv[3], int e) {
  const auto at = [&](double t) {
    Vec3 b = Vec3::Zero();
    b[(e + 1) % 3] = 1.0 - t;
    b[(e + 2) % 3] = t;
    return probe.residual_at(p, uv, b);
  };
  const Vec3 quarter = at(0.25), half = at(0.5), three_quarters = at(0.75);
  const EdgePeak peak = edge_peak(quarter, half, three_quarters);
  const double q = quarter.norm(), h = half.norm(), tq = three_quarters.norm();
  // At a quarter point the interpolant's peak is a point already evaluated: the same b, the
  // same bits (a quarter of the peaks land there; the lattice's middle is t = 32 / 64).
  const double at_peak = peak.t == 0.5    ? h
                         : peak.t == 0.25 ? q
                         : peak.t == 0.75 ? tq
                                          : at(peak.t).norm();
  EdgeReading r;
  // The measured peak, and the interpolant's where it reads higher (as the quadratic
  // model's maximum counts beside the samples). From 0: the maximum over the three edges is
  // then the one max({0, ...}) over all fifteen values (a NaN skipped alike).
  r.peak = std::max({0.0, q, h, tq, peak.value, at_peak});
  r.largest = std::max({0.0, q, h, tq, at_peak});
  r.nearest_end = std::min({0.25, peak.t, 1.0 - peak.t});
  r.tied = peak.tied;
  return r;
}

// Whether some coordinate is (nearly) zero at both ends: only then can a point of the edge get
// a zero coordinate whose sign depends on the order of the barycentric sum, and with it on
// the face (SampleStore::shared_edge_peaks).
template <class V>
bool zero_at_both_ends(const V& a, const V& b) {
  for (int i = 0; i < a.size(); ++i)
    if (std::abs(a[i]) < 1e-290 && std::abs(b[i]) < 1e-290) return true;
  return false;
}

}  // namespace

void SampleStore::prefetch_face(const Mesh48& mesh, Face f) const {
  if (!mesh.is_alive(f)) return;
  for (Vertex v : mesh.vertices(f)) __builtin_prefetch(mesh.position(v).data());
  __builtin_prefetch(samples_.data() + face_start_[f.idx]);
}

SampleStore::SampleStore(double density, std::uint64_t seed) : density_(density), seed_(seed) {
  // Keeps parallel.cpp, and with it the engine's OpenMP wait policy, in every program that
  // measures samples (parallel.h).
  static_cast<void>(engine_wait_policy());
  // Likewise the allocator policy (allocator_policy.h): the pool's buffers, given back when
  // the mesh shrinks (compact), must go back to the system too.
  static_cast<void>(engine_allocator_policy());
}

void SampleStore::grow_faces(std::size_t capacity) {
  if (face_start_.size() >= capacity) return;
  face_start_.resize(capacity, 0);
  face_count_.resize(capacity, 0);
  face_error_.resize(capacity, 0.0);
  face_sum_.resize(capacity, 0.0);
  face_dense_.resize(capacity, 0);
  measured_.resize(capacity, 0);
  model_error_.resize(capacity, 0.0);
  peak_error_.resize(capacity, -1.0);
  edge_slots_.resize(3 * capacity);
  peak_checked_.resize(capacity, 0);
  rotation_.grow(capacity);
}

void SampleStore::clear_face(std::uint32_t f) {
  garbage_ += face_count_[f];
  face_start_[f] = 0;
  face_count_[f] = 0;
}

SampleStore::Sample* SampleStore::allocate(std::uint32_t f, std::uint32_t n) {
  clear_face(f);
  face_start_[f] = static_cast<std::uint32_t>(samples_.size());
  face_count_[f] = n;
  samples_.resize(samples_.size() + n);
  return samples_.data() + face_start_[f];
}

void SampleStore::compact_if_wasteful() {
  // Amortised O(1) per sample: a compaction halves the pool at least.
  if (garbage_ >= 4096 && 2 * garbage_ >= samples_.size()) compact();
}

void SampleStore::compact() {
  // The pool and its spare keep the capacity they grew to, so that refining again allocates
  // nothing. But a mesh that shrinks for good would hold its peak's samples for ever: the
  // default sphere has 1.6M live samples at R = 9 and 17k back at R = 0.6, where the two
  // buffers held 115 MB (and the resident memory grew whenever a later peak reached pages
  // of them that an earlier one had not). So a buffer more than kReleaseFactor times larger
  // than the live samples is given back; the factor is the hysteresis that keeps a mesh
  // going up and down by less than that from reallocating.
  const std::size_t live = n_samples();
  const auto oversized = [live](const std::vector<Sample>& v) {
    return v.capacity() > kReleaseFactor * std::max(live, kReleaseFloor);
  };
  if (oversized(spare_)) spare_ = std::vector<Sample>();
  spare_.clear();
  spare_.reserve(live);
  for (std::size_t f = 0; f < face_count_.size(); ++f) {
    const auto first = samples_.begin() + face_start_[f];
    face_start_[f] = static_cast<std::uint32_t>(spare_.size());
    spare_.insert(spare_.end(), first, first + face_count_[f]);
  }
  samples_.swap(spare_);
  garbage_ = 0;
  if (oversized(spare_)) spare_ = std::vector<Sample>();
}

std::uint32_t SampleStore::target_count(const Mesh48& mesh, Face f) const {
  return target_count(face_area(mesh, f));
}

std::uint32_t SampleStore::target_count(double area) const {
  const double n = std::round(density_ * area);
  return static_cast<std::uint32_t>(std::clamp(n, double{kMinSamplesPerFace}, 1e6));
}

// Stratified: the barycentric triangle is cut into k^2 congruent cells (k(k+1)/2 upright,
// k(k-1)/2 inverted), k^2 >= the target, and one uniformly jittered sample is drawn per cell.
void SampleStore::draw_pattern(const Mesh48& mesh, std::uint32_t f, std::uint32_t min_count) {
  face_error_[f] = 0.0;
  face_sum_[f] = 0.0;  // every new sample's error is 0
  measured_[f] = 0;
  face_dense_[f] = min_count > 0;
  peak_checked_[f] = 0;
  const std::uint32_t n = std::max(target_count(mesh, Face(f)), min_count);
  const auto k = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  Sample* out = allocate(f, static_cast<std::uint32_t>(k * k));
  ++patterns_drawn_;
  // The jitter depends only on where the face is (its corners' positions, bit for bit), the
  // pattern's size and the epoch (set_pattern_epoch): not on how many patterns were drawn
  // before it, nor on the face's id. Predictive sampling measures fewer faces and so densifies
  // fewer; with patterns numbered in the order they were drawn, every pattern drawn after the
  // first such face differed from full sampling's, and with it the decisions (sinc, T = 0.002:
  // the first split differed at step 14 of 100). Ids would change with a renumbering.
  std::uint64_t key = mix(seed_ ^ mix(epoch_ ^ (std::uint64_t{n} << 40)));
  for (Vertex v : mesh.vertices(Face(f)))
    for (int i = 0; i < 3; ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, &mesh.position(v)[i], sizeof bits);
      key = mix(key ^ bits);
    }
  std::uint64_t state = key;
  const double h = 1.0 / k;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k - i; ++j) {
      for (int inverted = 0; inverted < (j < k - i - 1 ? 2 : 1); ++inverted) {
        double r1 = uniform01(state), r2 = uniform01(state);
        if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
        // Cell corner and edge vectors in (b1, b2); the inverted cell is the point reflection.
        const double s = inverted ? -1.0 : 1.0;
        const double c1 = (j + inverted) * h, c2 = (i + inverted) * h;
        *out++ = {static_cast<float>(c1 + s * r1 * h), static_cast<float>(c2 + s * r2 * h), 0.0f};
      }
    }
  }
}

void SampleStore::reset(const Mesh48& mesh) {
  samples_.clear();
  garbage_ = 0;
  // Every per-face array anew, with the defaults grow_faces gives a new slot.
  face_start_.clear();
  face_count_.clear();
  face_error_.clear();
  face_sum_.clear();
  face_dense_.clear();
  measured_.clear();
  model_error_.clear();
  peak_error_.clear();
  peak_checked_.clear();
  rotation_.reset();
  grow_faces(mesh.face_capacity());
  for (Face f : mesh.live_faces()) draw_pattern(mesh, f.idx);
}

bool SampleStore::evaluate_face(const Mesh48& mesh, const SurfaceProbe& probe, Face f, Sample& kept,
                                bool& kept_one) {
  const auto v = mesh.vertices(f);
  const Vec3 p[3] = {mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])};
  const Vec2 uv[3] = {mesh.uv(v[0]), mesh.uv(v[1]), mesh.uv(v[2])};
  QuadraticErrorModel model;
  Sample* const first = samples_.data() + face_start_[f.idx];
  Sample* const last = first + face_count_[f.idx];
  double sum = 0.0;  // face_sum_
  if (probe.parametric()) {
    for (Sample* x = first; x != last; ++x) {
      const Vec3 b = x->barycentric();
      const Vec3 r = probe.residual_at(p, uv, b);
      x->error = static_cast<float>(r.norm());
      sum += static_cast<double>(x->error);
      model.add(b, r);
    }
  } else {
    // The common implicit case without the vector residual's detour (one evaluation and
    // one square root per sample).
    for (Sample* x = first; x != last; ++x) {
      const Vec3 b = x->barycentric();
      const double r =
          probe.signed_distance_in_triangle(p, b[0] * p[0] + b[1] * p[1] + b[2] * p[2]);
      x->error = static_cast<float>(std::abs(r));
      sum += static_cast<double>(x->error);
      model.add(b, r);
    }
  }
  face_sum_[f.idx] = sum;
  QuadraticErrorModel::Result r = model.evaluate();
  const bool check = peak_check_due(f, r.error) && r.resolved;
  if (check) peak_checked_[f.idx] = 1;
  Vec3 at;
  if (check && face_count_[f.idx] < kMaxSamplesPerFace && model.interior_peak(at)) {
    // The candidate as it would be stored (float coordinates) and read again: a later
    // measurement of the face adds the same residual at the same point, last.
    Sample x = Sample::at(at);
    const Vec3 b = x.barycentric();
    double error;
    if (probe.parametric()) {
      const Vec3 residual = probe.residual_at(p, uv, b);
      error = residual.norm();
      if (error > r.error) model.add(b, residual);
    } else {
      const double residual =
          probe.signed_distance_in_triangle(p, b[0] * p[0] + b[1] * p[1] + b[2] * p[2]);
      error = std::abs(residual);
      if (error > r.error) model.add(b, residual);
    }
    // Kept only where the model under-read it: elsewhere it would tell nothing the reading
    // does not already say.
    if (error > r.error) {
      x.error = static_cast<float>(error);
      kept = x;
      kept_one = true;
      r = model.evaluate();
    }
  }
  model_error_[f.idx] = r.error;
  const bool search = peak_floor_ > 0.0 && r.error >= search_start_;
  peak_error_[f.idx] = search ? shared_edge_peaks(mesh, probe, f, p, uv) : -1.0;
  face_error_[f.idx] = search ? peak_reading(r.error, peak_error_[f.idx]) : r.error;
  measured_[f.idx] = 1;
  return r.resolved;
}

void SampleStore::set_peak_search(double floor, double largest_under_reading,
                                  double interior_ceiling) {
  peak_floor_ = floor;
  interior_ceiling_ = interior_ceiling;
  largest_under_reading_ = largest_under_reading;
  // There, a peak under-read by largest_under_reading reads no more than the model.
  search_start_ = floor * kPeakRamp / (largest_under_reading + kPeakRamp);
}

double SampleStore::peak_reading(double model, double peaks) const {
  return std::max(model, peaks - kPeakRamp * std::max(0.0, peak_floor_ - model));
}

double SampleStore::reading_upper(Face f, double rise) const {
  // evaluate_face's reading, max(model, peaks - kPeakRamp * max(0, floor - model)) from the
  // search's start on and the model below it, does not decrease in the model (the search
  // starting only adds a maximum) nor in the peaks.
  const double model = model_error_[f.idx] + rise;
  if (!(peak_floor_ > 0.0 && model >= search_start_)) return model;
  const double peaks = peak_error_[f.idx];
  return peak_reading(model, peaks >= 0.0 ? peaks + rise : (1.0 + largest_under_reading_) * model);
}

double SampleStore::reading_lower(Face f, double rise) const {
  // The reading is at least the model's; where the model stays at or above the search's start
  // the face is searched and its peaks count as they then read.
  const double model = model_error_[f.idx] - rise, peaks = peak_error_[f.idx];
  if (!(peak_floor_ > 0.0 && model >= search_start_ && peaks >= 0.0)) return model;
  return peak_reading(model, peaks - rise);
}

double SampleStore::edge_peaks(const SurfaceProbe& probe, const Vec3 p[3], const Vec2 uv[3]) {
  double worst = 0.0;
  for (int e = 0; e < 3; ++e) worst = std::max(worst, read_edge(probe, p, uv, e).peak);
  return worst;
}

void SampleStore::new_pass(const SurfaceProbe& probe) {
  if (++pass_ == kSlotBusy) {  // after 2^31 passes: every slot made stale by hand
    for (EdgeSlot& slot : edge_slots_) slot.pass = 0;
    pass_ = 1;
  }
  // Parametric surfaces interpolate (u, v) from the face's first corner, unwrapped across a
  // periodic seam and wrapped back: the same edge point's (u, v) could differ in its last bits
  // between the two faces. Elsewhere (u, v) is the edge's own.
  share_edges_ = share_edge_peaks_;
  if (share_edges_ && probe.parametric()) {
    const ParameterDomain d = static_cast<const ParametricSurface&>(probe.surface()).domain();
    share_edges_ = !d.periodic_u && !d.periodic_v;
  }
}

// Why the face across an edge reads, to the bit, the peak this face found (then it takes it
// from the slot). Both evaluate the same points: edge_peaks goes from vertex e + 1 to e + 2,
// the face across (consistently oriented) the other way, and t' = 1 - t is exact for the
// quarter points and the lattice's k / 64 (edge_peak: -s and -slope are exact, so every
// lattice value is the mirrored one's; the first maximum is the mirrored one unless another
// lattice point ties, EdgePeak::tied). A point's coordinates are (1 - t) a + t b plus the
// opposite corner times 0: the same sum but for the sign of a zero coordinate, which can
// differ only where both ends have that coordinate zero (zero_at_both_ends). What remains is
// the implicit residual's cap (SurfaceProbe::signed_distance_in_triangle), which looks at the
// distance to all three corners. A point's reading r is uncapped when |r| is below half its
// distance to each corner (were it capped, |r| would be at least the nearest corner's
// distance, up to rounding): to the edge's ends at least nearest_end times the edge's length,
// to the opposite corner at least that corner's height over the edge. The face that fills a
// slot checks its own; the face that reads it checks its height against the largest residual
// evaluated (then it is uncapped there too, and reads the same signed distance). The 1e-9 of
// the corners' coordinates keeps the rounding of those distances far below the factor 2.
double SampleStore::shared_edge_peaks(const Mesh48& mesh, const SurfaceProbe& probe, Face f,
                                      const Vec3 p[3], const Vec2 uv[3]) {
  const bool implicit = !probe.parametric();
  const double scale =
      1e-9 * std::max({p[0].cwiseAbs().maxCoeff(), p[1].cwiseAbs().maxCoeff(),
                       p[2].cwiseAbs().maxCoeff(), std::numeric_limits<double>::min()});
  double worst = 0.0;
  for (int e = 0; e < 3; ++e) {
    const Halfedge twin = mesh.twin(Halfedge(f, e));
    const int a = (e + 1) % 3, b = (e + 2) % 3;
    if (!share_edges_ || !twin.is_valid() || zero_at_both_ends(p[a], p[b]) ||
        (!implicit && zero_at_both_ends(uv[a], uv[b]))) {
      worst = std::max(worst, read_edge(probe, p, uv, e).peak);
      continue;
    }
    // The distances the cap could bind at, on this face (implicit only).
    const Vec3 edge = p[b] - p[a];
    const double length = edge.norm();
    const double height = implicit ? edge.cross(p[e] - p[a]).norm() / length
                                   : std::numeric_limits<double>::infinity();
    EdgeSlot& slot = edge_slots_[std::min(Halfedge(f, e).idx, twin.idx)];
    std::atomic_ref<std::uint32_t> state(slot.pass);
    std::uint32_t seen = state.load(std::memory_order_acquire);
    if (seen == pass_ && height > scale && 2.0 * slot.largest <= height) {
      worst = std::max(worst, slot.peak);
      std::atomic_ref<std::uint64_t>(edge_peaks_shared_).fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    const EdgeReading r = read_edge(probe, p, uv, e);
    worst = std::max(worst, r.peak);
    const double reach = std::min(height, implicit ? r.nearest_end * length : height);
    const bool fill = !r.tied && reach > scale && 2.0 * r.largest <= reach &&
                      std::isfinite(r.peak) && std::isfinite(r.largest);
    if (fill && (seen & ~kSlotBusy) != pass_ &&
        state.compare_exchange_strong(seen, pass_ | kSlotBusy, std::memory_order_acquire)) {
      slot.peak = r.peak;
      slot.largest = r.largest;
      state.store(pass_, std::memory_order_release);
    }
  }
  return worst;
}

void SampleStore::evaluate_faces(const Mesh48& mesh, const SurfaceProbe& probe,
                                 const std::vector<Face>& faces) {
  grow_faces(mesh.face_capacity());
  compact_if_wasteful();
  new_pass(probe);
  // Member scratch buffers: this runs after every split, so it must not allocate.
  std::vector<Face>& pending = pending_;
  std::vector<Face>& next = next_pending_;
  std::vector<std::uint8_t>& unresolved = unresolved_;
  pending.assign(faces.begin(), faces.end());
  while (!pending.empty()) {
    const auto n = static_cast<std::int64_t>(pending.size());
    unresolved.assign(pending.size(), 0);
    keep_.assign(pending.size(), 0);
    kept_.resize(pending.size());
    // Chunks of 256 faces where there are many (their prefetching runs ahead along a chunk), of
    // 16 where a few hundred or thousand are measured, so that both threads get some.
    const int chunk = n > kParallelMin ? 256 : 16;
#pragma omp parallel for schedule(dynamic, chunk) if (n > kParallelMinCostly)
    for (std::int64_t i = 0; i < n; ++i) {
      // A face's vertices lie anywhere in memory: fetch those of a face a few ahead while
      // this one is measured, and its samples.
      if (i + kPrefetchAhead < n)
        prefetch_face(mesh, pending[static_cast<std::size_t>(i + kPrefetchAhead)]);
      const Face f = pending[static_cast<std::size_t>(i)];
      const auto k = static_cast<std::size_t>(i);
      bool kept = false;
      if (mesh.is_alive(f)) unresolved[k] = !evaluate_face(mesh, probe, f, kept_[k], kept);
      keep_[k] = kept;
    }
    // Keep the interior peaks and densify, sequentially (the pool is shared); then measure the
    // densified faces again. A face left unresolved with its kept peak is densified: its new
    // pattern replaces the sample.
    next.clear();
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const Face f = pending[i];
      if (keep_[i]) append_sample(f.idx, kept_[i]);
      if (!unresolved[i] || face_count_[f.idx] >= kMaxSamplesPerFace) continue;
      draw_pattern(mesh, f.idx, std::min(4 * face_count_[f.idx], kMaxSamplesPerFace));
      next.push_back(f);
    }
    pending.swap(next);
  }
}

void SampleStore::append_sample(std::uint32_t f, const Sample& x) {
  const std::uint32_t start = face_start_[f], n = face_count_[f];
  if (start + n != samples_.size()) {
    const auto end = static_cast<std::uint32_t>(samples_.size());
    samples_.resize(samples_.size() + n);
    std::copy_n(samples_.begin() + start, n, samples_.begin() + end);
    garbage_ += n;
    face_start_[f] = end;
  }
  samples_.push_back(x);
  ++face_count_[f];
  face_sum_[f] += static_cast<double>(x.error);  // the range's last sample
  ++peaks_kept_;
}

void SampleStore::evaluate_all(const Mesh48& mesh, const SurfaceProbe& probe) {
  evaluate_faces(mesh, probe, mesh.live_faces());
}

double SampleStore::weld_midpoint_error(const Mesh48& mesh, const SurfaceProbe& probe,
                                        const DiamondChange& plan) {
  const auto& pv0 = plan.halves[0].parent_vertices;
  const Vec3 p0[3] = {mesh.position(pv0[0]), mesh.position(pv0[1]), mesh.position(pv0[2])};
  const Vec2 uv0[3] = {mesh.uv(pv0[0]), mesh.uv(pv0[1]), mesh.uv(pv0[2])};
  return probe.error_at(p0, uv0, Vec3(0.0, 0.5, 0.5));
}

double SampleStore::weld_error(const Mesh48& mesh, const SurfaceProbe& probe,
                               const DiamondChange& plan, double ceiling, double midpoint) const {
  if (midpoint > ceiling) return midpoint;
  double worst = midpoint;
  for (int h = 0; h < plan.count; ++h) {
    const Bisection& half = plan.halves[h];
    const auto& pv = half.parent_vertices;
    const Vec3 p[3] = {mesh.position(pv[0]), mesh.position(pv[1]), mesh.position(pv[2])};
    const Vec2 uv[3] = {mesh.uv(pv[0]), mesh.uv(pv[1]), mesh.uv(pv[2])};
    QuadraticErrorModel model;
    for (int child = 0; child < 2; ++child) {
      for_each_sample(half.children[child], [&](const Vec3& b, double) {
        if (model.sample_max() > ceiling) return;  // decided: skip the remaining samples
        const Vec3 pb = to_parent_coordinates(b, child);
        model.add(pb, probe.residual_at(p, uv, pb));
      });
    }
    const bool decided = model.sample_max() > ceiling;
    const QuadraticErrorModel::Result fit =
        decided ? QuadraticErrorModel::Result{} : model.evaluate();
    double estimate = decided ? model.sample_max() : fit.error;
    // The same reading the parent would get once welded (evaluate_face): were its edge peak
    // left out here, a weld just below the bound could be split again at once, step after step.
    if (peak_floor_ > 0.0 && estimate >= search_start_ && estimate <= ceiling) {
      // And the interior peak evaluate_face would keep (its reading is then at least that
      // residual; weld_error does not refit the model with it).
      Vec3 at;
      if (fit.resolved && model.interior_peak(at)) {
        estimate =
            std::max(estimate, probe.residual_at(p, uv, Sample::at(at).barycentric()).norm());
      }
      estimate = peak_reading(estimate, edge_peaks(probe, p, uv));
    }
    worst = std::max(worst, estimate);
    if (worst > ceiling) return worst;
  }
  return worst;
}

std::size_t SampleStore::refresh_patterns(const Mesh48& mesh) {
  // Which faces need a new pattern is decided in parallel (an area per face); drawing them
  // shares the pool, so it is sequential.
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  unresolved_.assign(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Face f(static_cast<std::uint32_t>(i));
    if (!mesh.is_alive(f)) continue;
    unresolved_[static_cast<std::size_t>(i)] = pattern_outdated(f, doubled_area_squared(mesh, f));
  }
  std::size_t redrawn = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    if (!unresolved_[static_cast<std::size_t>(i)]) continue;
    draw_pattern(mesh, static_cast<std::uint32_t>(i));
    ++redrawn;
  }
  return redrawn;
}

std::size_t SampleStore::refresh_patterns(const Mesh48& mesh, const std::vector<Face>& faces) {
  std::size_t redrawn = 0;
  for (Face f : faces) {
    if (!mesh.is_alive(f) || !pattern_outdated(f, doubled_area_squared(mesh, f))) continue;
    draw_pattern(mesh, f.idx);
    ++redrawn;
  }
  return redrawn;
}

bool SampleStore::pattern_outdated_at_area(Face f, double area) const {
  const std::uint32_t target = target_count(area), count = face_count_[f.idx];
  return count == 0 || 2 * count < target || (count > 2 * target && !face_dense_[f.idx]);
}

double SampleStore::sample_sum(std::uint32_t f) const {
  double sum = 0.0;
  for_each_sample(Face(f), [&](const Vec3&, double error) { sum += error; });
  return sum;
}

SampleStore::Summary SampleStore::summary(const Mesh48& mesh) const {
  const auto n = static_cast<std::int64_t>(mesh.face_capacity());
  // The faces' sums of their samples' errors (face_sum_) are added in kBlocks fixed ranges of
  // faces, the ranges' sums then in order: the same additions in the same order whatever the
  // thread count. (A reduction(+) adds each thread's partial sum: the mean's last bits depended
  // on the thread count, and so did every frame's stats; issue 13.) The maximum and the count
  // are exact in any order.
  constexpr std::int64_t kBlocks = 64;
  const std::int64_t blocks = n > kParallelMin ? kBlocks : 1;
  double max_error = 0.0, partial[kBlocks] = {};
  std::size_t samples = 0;
#pragma omp parallel for schedule(static) reduction(max : max_error) reduction(+ : samples) \
    if (n > kParallelMin)
  for (std::int64_t block = 0; block < blocks; ++block) {
    double sum = 0.0;
    for (std::int64_t i = n * block / blocks; i < n * (block + 1) / blocks; ++i) {
      const Face f(static_cast<std::uint32_t>(i));
      if (!mesh.is_alive(f)) continue;
      max_error = std::max(max_error, face_error_[f.idx]);
      sum += face_sum_[f.idx];
      samples += face_count_[f.idx];
    }
    partial[block] = sum;
  }
  double sum = 0.0;
  for (std::int64_t block = 0; block < blocks; ++block) sum += partial[block];
  Summary s;
  s.max_error = max_error;
  s.samples = samples;
  s.mean_error = samples ? sum / static_cast<double>(samples) : 0.0;
  return s;
}

void SampleStore::after_split(Mesh48& mesh, const DiamondChange& change) {
  grow_faces(mesh.face_capacity());
  for (int h = 0; h < change.count; ++h) {
    const Bisection& half = change.halves[h];
    const std::uint32_t start = face_start_[half.parent.idx], n = face_count_[half.parent.idx];
    // Partition the parent's range in place: child 0's samples first, then child 1's.
    Sample* const first = samples_.data() + start;
    auto child_of = [](const Sample& x) {
      return bisection_child(Eigen::Vector3f(1.0f - x.b1 - x.b2, x.b1, x.b2));
    };
    Sample* const middle =
        std::partition(first, first + n, [&](const Sample& x) { return child_of(x) == 0; });
    for (Sample* x = first; x != first + n; ++x) {
      const Eigen::Vector3f c = to_child_coordinates(
          Eigen::Vector3f(1.0f - x->b1 - x->b2, x->b1, x->b2), x < middle ? 0 : 1);
      x->b1 = c[1];
      x->b2 = c[2];
    }
    const auto n0 = static_cast<std::uint32_t>(middle - first);
    const std::uint32_t c0 = half.children[0].idx, c1 = half.children[1].idx;
    face_start_[c0] = start;
    face_count_[c0] = n0;
    face_start_[c1] = start + n0;
    face_count_[c1] = n - n0;
    for (std::uint32_t c : {c0, c1}) {
      face_error_[c] = 0.0;
      measured_[c] = 0;
      peak_checked_[c] = 0;
      face_sum_[c] = sample_sum(c);  // the parent's samples, partitioned
      if (face_count_[c] < kMinSamplesPerFace) draw_pattern(mesh, c);
    }
  }
}

void SampleStore::after_weld(Mesh48& mesh, const DiamondChange& change) {
  for (int h = 0; h < change.count; ++h) {
    const Bisection& half = change.halves[h];
    const std::uint32_t c[2] = {half.children[0].idx, half.children[1].idx};
    for (int which = 0; which < 2; ++which) {
      Sample* const first = samples_.data() + face_start_[c[which]];
      for (Sample* x = first; x != first + face_count_[c[which]]; ++x) {
        const Eigen::Vector3f p =
            to_parent_coordinates(Eigen::Vector3f(1.0f - x->b1 - x->b2, x->b1, x->b2), which);
        x->b1 = p[1];
        x->b2 = p[2];
      }
    }
    const std::uint32_t s0 = face_start_[c[0]], n0 = face_count_[c[0]];
    const std::uint32_t s1 = face_start_[c[1]], n1 = face_count_[c[1]];
    std::uint32_t start;
    if (n1 == 0 || s0 + n0 == s1) {
      start = s0;  // the children of one split, untouched since: already one range
    } else if (n0 == 0 || s1 + n1 == s0) {
      start = s1;
    } else {
      start = static_cast<std::uint32_t>(samples_.size());
      samples_.resize(samples_.size() + n0 + n1);
      std::copy_n(samples_.begin() + s0, n0, samples_.begin() + start);
      std::copy_n(samples_.begin() + s1, n1, samples_.begin() + start + n0);
      garbage_ += n0 + n1;
    }
    face_count_[c[1]] = 0;
    const std::uint32_t parent = half.parent.idx;
    face_start_[parent] = start;
    face_count_[parent] = n0 + n1;
    face_error_[parent] = 0.0;
    measured_[parent] = 0;
    peak_checked_[parent] = 0;
    face_sum_[c[1]] = 0.0;                   // (an empty range)
    face_sum_[parent] = sample_sum(parent);  // the children's samples, merged
    if (face_count_[parent] > 2 * target_count(mesh, half.parent)) draw_pattern(mesh, parent);
  }
}

void SampleStore::after_renumber(Mesh48&, const Renumbering& r) {
  grow_faces(r.face.size());  // every slot with its defaults first (peak_error_: -1)
  renumber_elements(face_start_, r.face, r.n_faces);
  renumber_elements(face_count_, r.face, r.n_faces);
  renumber_elements(face_error_, r.face, r.n_faces);
  renumber_elements(face_sum_, r.face, r.n_faces);
  renumber_elements(face_dense_, r.face, r.n_faces);
  renumber_elements(measured_, r.face, r.n_faces);
  renumber_elements(model_error_, r.face, r.n_faces);
  renumber_elements(peak_error_, r.face, r.n_faces);
  renumber_elements(peak_checked_, r.face, r.n_faces);
  rotation_.renumber(r);
  unresolved_.clear();  // scratch of one call
  keep_.clear();
  compact();
}

}  // namespace dynamesh
