// SampleStore: the stochastic stratified samples of de Goes et al. 2006, Section 3.1.
// Each face carries a jittered stratified pattern in barycentric coordinates at a density D
// (samples per unit area, at least kMinSamplesPerFace per face: the paper asks for at least
// one; the quadratic error model needs three, and with a 3 x 3 stratification the estimate
// stays within 10% of a dense measurement on every analytic scene, the twisted bar
// included, where 2 x 2 misses its peaks by up to 15%). Samples
// follow splits and welds: as a MeshListener the store re-expresses each sample in the barycentric
// coordinates of the face that now holds it, so the density is kept without drawing new samples; a
// face left with none, or with a count far from D * area, gets a fresh pattern.
//
// Storage: one pool of samples in which each face owns a contiguous range, so that measuring
// a face streams through memory (with a linked list per face, chasing scattered samples cost
// as much as evaluating the surface at them). A split partitions its parent's range in place
// into the two children's; a weld of two adjacent ranges (the usual case: the children of
// one split) joins them in place, otherwise the merged range and any new pattern go to the
// end of the pool. Ranges left behind are garbage; when they outweigh the live samples the
// pool is compacted in face order. No allocation per operation once the pool has grown.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/adapt/measurement_rotation.h"
#include "core/adapt/surface_probe.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {

class SampleStore final : public MeshListener {
 public:
  static constexpr std::uint32_t kMinSamplesPerFace = 9;
  static constexpr std::uint32_t kMaxSamplesPerFace = 256;
  // compact() gives a buffer back when its capacity exceeds kReleaseFactor times the live
  // samples (or times kReleaseFloor, below which buffers are too small to matter: 768 KB).
  static constexpr std::size_t kReleaseFactor = 4;
  static constexpr std::size_t kReleaseFloor = std::size_t{1} << 16;

  SampleStore(double density, std::uint64_t seed);

  // Fresh patterns on every face of `mesh` (positions define the areas).
  void reset(const Mesh48& mesh);
  void set_density(double density) { density_ = density; }
  // Faces whose model reading reaches `floor` read the larger of it and their edges' peaks
  // (error_model.h, EdgePeak: three evaluations at the quarter points of each edge and one at
  // the interpolant's peak, a dozen per face). Only faces near the split bound need it: the
  // adapter sets the floor below T + eps by more than the quadratic model under-reads a peak
  // (adapter.cpp, kPeakSearchBand), by at most `largest_under_reading` (relative). Below the
  // floor the peaks count less, by kPeakRamp times the model's distance to it, down to where a
  // peak under-read by that much no longer counts: faces read below that are not searched. So
  // the reading has no jump: it moves by at most reading_gain() times what the model's reading
  // or the peaks move (ErrorPredictor's bound). floor 0 (the default): no search.
  // `interior_ceiling`: the reading from which a face is split whatever it holds inside (the
  // split bound, T + eps); its interior peak is looked for only below it (evaluate_faces).
  void set_peak_search(double floor, double largest_under_reading,
                       double interior_ceiling = std::numeric_limits<double>::infinity());
  // Below the peak search floor, the edge peaks count less by this much per unit of the model
  // reading's distance to the floor (set_peak_search). Steeper, fewer faces are searched;
  // gentler, the reading moves less with the model (reading_gain).
  static constexpr double kPeakRamp = 1.0;
  // The most the face's reading can move, per unit of movement of its model reading and its
  // edge peaks, while both stay within `bound` of their last values: 1 + kPeakRamp where the
  // ramped peaks could then be the reading below the floor, 1 elsewhere. (Inline:
  // ErrorPredictor::select asks it for every skipped face.)
  double reading_gain(Face f, double bound) const {
    const double model = model_error_[f.idx], peaks = peak_error_[f.idx];
    if (peak_floor_ <= 0.0 || model - bound >= peak_floor_) return 1.0;
    // Below the floor the reading follows the model with slope kPeakRamp where the ramped peaks
    // read above it. Whether they could, for a model reading within the bound, is linear in it:
    // the range's ends decide. An unsearched face's peaks are taken as under-read by the most
    // assumed (they then read above the model exactly from search_start_ on).
    for (double m : {std::max(0.0, model - bound), std::min(model + bound, peak_floor_)}) {
      const double p = peaks >= 0.0 ? peaks + bound : (1.0 + largest_under_reading_) * m;
      if (p - kPeakRamp * (peak_floor_ - m) >= m) return 1.0 + kPeakRamp;
    }
    return 1.0;
  }
  // The largest reading the face can have once its model reading and its edge peaks each rose
  // by at most `rise` from their last values (reading_gain's assumption; an unsearched face's
  // peaks under-read by the most assumed): the reading itself at those raised values, since it
  // does not decrease in either. At most face_error + reading_gain * rise, and often well
  // below: where the model is the reading, the ramped peaks must rise by the ramp's share of
  // the gap before they count (ErrorPredictor::select).
  double reading_upper(Face f, double rise) const;
  // The smallest reading it can have once both fell by at most `rise` (an unsearched face's
  // peaks by any amount).
  double reading_lower(Face f, double rise) const;
  double density() const { return density_; }
  // The measurement rotation (measurement_rotation.h): each face has a turn every kRotation
  // steps, and set_step() names the step whose turn it is. Predictive sampling (ErrorPredictor)
  // measures every face on its turn, full sampling every face every step: both measure it
  // then, and so the interior peak is looked for only then (evaluate_faces).
  // set_every_turn(): every face's turn (the initial frame, where both modes measure them all:
  // so that it is settled, a fixed point of a static surface, Adapter::initialize).
  static constexpr std::uint32_t kRotation = MeasurementRotation::kRotation;
  void set_step(std::uint64_t step) { rotation_.set_step(step); }
  void set_every_turn() { rotation_.set_every_turn(); }
  const MeasurementRotation& rotation() const { return rotation_; }
  // The turns in blocks of consecutive face ids (MeasurementRotation::group_in_order): after a
  // renumbering along a space-filling curve, each turn measures patches of neighbours.
  void group_turns_in_order() { rotation_.group_in_order(); }
  bool on_turn(Face f) const { return rotation_.on_turn(f); }

  // Errors of every sample of the given faces (all live faces) against the surface, in
  // parallel; updates each face's error. A face whose samples the quadratic model cannot
  // explain (error_model.h) gets a denser stratified pattern (4x, up to
  // kMaxSamplesPerFace) and is measured again: sampling adapts to where the error is not
  // smooth at the triangle's scale, instead of trusting a sparse maximum there.
  // A call is one pass: the mesh and its positions do not change within it, so an edge
  // shared by two searched faces has its peaks evaluated once (edge_peaks_shared).
  // A face at or above the peak search's start (set_peak_search) whose fitted model peaks
  // inside it (QuadraticErrorModel::interior_peak) is also measured there; where the residual
  // there exceeds the model's reading, the point is kept as one more sample of the face and
  // the face read with it. This is looked for once per face between splits, welds and new
  // patterns (peak_check_due), so that it cannot grow a face's samples step after step, and only
  // at measurements that both sampling modes make: the face's first after its samples changed,
  // or one on its turn (on_turn). Then both modes keep the same samples, and predictive sampling
  // need not measure a face only to look for its peak. The price: a face that comes to read in
  // the search band between its turns is looked at up to kRotation steps later (its edges are
  // searched at every measurement). The model
  // assumes the residual quadratic over the face; a crest inside it that the nine stratified
  // samples straddle breaks that, and the model under-reads it (sinc, T = 0.002: a face of 9
  // samples read 0.983 (T + eps) where a lattice of order 60 finds 1.137 inside it). Kept as a
  // sample, the point is read again at every later measurement, follows splits and welds,
  // counts in weld_error, and its residual's change is what ErrorPredictor's bound covers, as
  // every sample's is: the reading stays a function of fixed points of the face.
  void evaluate_faces(const Mesh48& mesh, const SurfaceProbe& probe,
                      const std::vector<Face>& faces);
  void evaluate_all(const Mesh48& mesh, const SurfaceProbe& probe);
  // How many times so far a face read an edge's peak that its neighbour had found in the same
  // pass, instead of evaluating the edge again.
  std::uint64_t edge_peaks_shared() const { return edge_peaks_shared_; }
  // On by default; off, every face evaluates its own edges (the reference the tests compare
  // with).
  void share_edge_peaks(bool on) { share_edge_peaks_ = on; }
  // The L-infinity error the weld planned in `plan` would leave: every sample of the star
  // measured against the two (one) parent triangles, with the quadratic model (and, at or
  // above the peak search floor, the parents' edge peaks, as evaluate_faces would read them).
  // The estimate also covers the restored edge's midpoint (where the removed vertex sat),
  // measured first: when its error already exceeds `ceiling` the weld cannot be allowed,
  // and that lower bound is returned without evaluating the samples. Likewise a sample or a
  // half above `ceiling` ends the measurement early: the result is then a lower bound above
  // `ceiling`, which is all a weld decision needs.
  double weld_error(const Mesh48& mesh, const SurfaceProbe& probe, const DiamondChange& plan,
                    double ceiling = std::numeric_limits<double>::infinity()) const {
    return weld_error(mesh, probe, plan, ceiling, weld_midpoint_error(mesh, probe, plan));
  }
  // The same, the restored edge's midpoint already read (weld_midpoint_error): a caller that
  // rejects most welds on that one reading pays for it once.
  double weld_error(const Mesh48& mesh, const SurfaceProbe& probe, const DiamondChange& plan,
                    double ceiling, double midpoint) const;
  // The error at the restored edge's midpoint, where the removed vertex sat: a lower bound of
  // weld_error's reading at any ceiling. One evaluation.
  static double weld_midpoint_error(const Mesh48& mesh, const SurfaceProbe& probe,
                                    const DiamondChange& plan);
  // New patterns drawn from now on take their jitter from (seed, epoch, the face's corners'
  // positions, size) alone, so that two runs making the same changes to the mesh draw the same
  // patterns whatever else they measured, and whatever the mesh's numbering. The adapter sets it to
  // the sub-step's number before sampling: a face redrawn in a later sub-step gets new luck.
  void set_pattern_epoch(std::uint64_t epoch) { epoch_ = epoch; }
  // How many times a face's samples changed other than by a split or weld: a pattern drawn,
  // or a sample kept at a face's interior peak (evaluate_faces). When it is unchanged across a
  // measurement, every face's samples are where they were, and so is every weld_error reading.
  std::uint64_t sample_changes() const { return patterns_drawn_ + peaks_kept_; }
  // Draws new patterns for faces whose sample count is below half or above twice
  // max(1, D * area); returns how many faces were redrawn. Their errors need evaluating.
  std::size_t refresh_patterns(const Mesh48& mesh);
  // The same for the listed faces only, in the list's order. Predictive sampling: select()
  // lists every face refresh_patterns(mesh) would redraw (pattern_outdated), so the mesh-wide
  // test rides on its face pass instead of a pass of its own (3% of a capsule-bend step's
  // instructions at 10^5 triangles).
  std::size_t refresh_patterns(const Mesh48& mesh, const std::vector<Face>& faces);
  // Whether face f needs a new pattern, given q = |(p1 - p0) x (p2 - p0)|^2 as computed there
  // (its area is 0.5 sqrt(q)). Most faces' counts are far from both limits: q against the
  // limits squared, with a relative margin of 1e-12 (far above the few roundings between q and
  // the rounded D * area), decides those without the area's square root and rounding; the
  // others are decided on the area itself, as refresh_patterns always did.
  bool pattern_outdated(Face f, double q) const {
    const double count = face_count_[f.idx];
    const double scaled = 0.25 * density_ * density_ * q;  // (D * area)^2
    // Within limits for sure: the target (at least kMinSamplesPerFace) is at most 2 * count,
    // and either the pattern was densified, or count <= 2 * kMinSamplesPerFace, or the target
    // is above count / 2.
    constexpr double kMargin = 1e-12;
    const bool within = count >= kMinSamplesPerFace &&
                        scaled < 4.0 * count * count * (1.0 - kMargin) &&
                        (face_dense_[f.idx] || count <= 2 * kMinSamplesPerFace ||
                         scaled > 0.25 * count * count * (1.0 + kMargin));
    return !within && pattern_outdated_at_area(f, 0.5 * std::sqrt(q));
  }

  // L-infinity error of the face as of its last evaluation: the larger of its largest sample
  // error and the maximum of the quadratic model fitted to its samples (error_model.h), and,
  // at or above the peak search floor, its edges' peaks.
  double face_error(Face f) const { return face_error_[f.idx]; }
  std::uint32_t count(Face f) const { return face_count_[f.idx]; }
  // False when the face's samples changed (split, weld, new pattern) since it was last
  // measured: face_error is then 0, not a measurement.
  bool measured(Face f) const { return f.idx < measured_.size() && measured_[f.idx]; }
  // True when the face's pattern was densified because its samples did not fit the
  // quadratic error model (evaluate_faces).
  bool densified(Face f) const { return face_dense_[f.idx]; }
  // Rewrites the pool with every face's range in face order, dropping the ranges left
  // behind. Measuring does this by itself whenever those outweigh the live samples.
  void compact();
  std::size_t n_samples() const { return samples_.size() - garbage_; }
  // Samples the pool and its spare have room for (their memory, in samples): at most
  // kReleaseFactor times max(n_samples(), kReleaseFloor) each right after compact().
  std::size_t held_samples() const { return samples_.capacity() + spare_.capacity(); }
  // Visits the face's samples as fn(barycentric Vec3, error).
  template <class Fn>
  void for_each_sample(Face f, Fn&& fn) const;

  // Largest and mean error over all samples of live faces.
  struct Summary {
    double max_error = 0.0, mean_error = 0.0;
    std::size_t samples = 0;
  };
  Summary summary(const Mesh48& mesh) const;

  void after_split(Mesh48& mesh, const DiamondChange& change) override;
  void after_weld(Mesh48& mesh, const DiamondChange& change) override;
  // Each face keeps its samples and error under its new id; the pool is then compacted in
  // the new face order, so that measuring faces in id order streams through it.
  void after_renumber(Mesh48& mesh, const Renumbering& renumbering) override;

 private:
  struct Sample {
    float b1, b2;  // barycentric coordinates of vertices 1 and 2; b0 = 1 - b1 - b2
    float error;
    // The sample at barycentric point b, its coordinates rounded as stored (error 0).
    static Sample at(const Vec3& b) {
      return {static_cast<float>(b[1]), static_cast<float>(b[2]), 0.0f};
    }
    // The point it is read at, from the stored coordinates.
    Vec3 barycentric() const { return {1.0 - b1 - b2, b1, b2}; }
  };

  void grow_faces(std::size_t capacity);
  // Gives up the face's range (it becomes garbage) and leaves the face empty.
  void clear_face(std::uint32_t f);
  // Gives the face a new, uninitialised range of n samples at the end of the pool.
  Sample* allocate(std::uint32_t f, std::uint32_t n);
  void compact_if_wasteful();
  void draw_pattern(const Mesh48& mesh, std::uint32_t f, std::uint32_t min_count = 0);
  static constexpr std::int64_t kPrefetchAhead = 4;
  void prefetch_face(const Mesh48& mesh, Face f) const;
  // Measures one face; returns whether its error estimate is resolved. A sample it keeps at
  // the face's interior peak is written to `kept` (and `kept_one` set), to be appended to the
  // face's range by the caller (the pool is shared).
  bool evaluate_face(const Mesh48& mesh, const SurfaceProbe& probe, Face f, Sample& kept,
                     bool& kept_one);
  // Appends `x` to the face's samples (its range moves to the end of the pool unless it is
  // there already).
  void append_sample(std::uint32_t f, const Sample& x);
  // The largest residual found along the triangle's three edges (EdgePeak).
  static double edge_peaks(const SurfaceProbe& probe, const Vec3 p[3], const Vec2 uv[3]);
  // The same for the live face f (corners p, uv), each edge found once per pass: an edge's
  // peak is kept in its slot (edge_slots_) and read by the face across it, where that face
  // would find the same value to the bit (sample_store.cpp, shared_edge_peaks).
  double shared_edge_peaks(const Mesh48& mesh, const SurfaceProbe& probe, Face f, const Vec3 p[3],
                           const Vec2 uv[3]);
  // Starts a pass of evaluate_faces: every edge slot filled before is stale.
  void new_pass(const SurfaceProbe& probe);
  // Whether this measurement of the face, its model reading `reading`, looks for its interior
  // peak (evaluate_faces): at or above the search's start and below the interior ceiling
  // (set_peak_search), not yet looked for since its samples changed, and the face's first
  // measurement since they changed or one on its turn. Above the ceiling the face is split
  // whatever it holds inside, and a peak kept there changes no decision; it only raised the
  // readings of faces spanning a gap in F (the mesh's topology not F's) over their ancestors',
  // and the split pass's stall bound (Adapter::split_pass), which holds faces whose error does
  // not fall, restarted its count at each rise: the dumbbell split, unwatched, held its splits
  // only at depth 16 and ran into the 5,000-triangle budget in step 3 (229 such restarts in
  // that pass); with the ceiling 38 restarts, held at depth 10, 1,426 triangles.
  bool peak_check_due(Face f, double reading) const {
    return peak_floor_ > 0.0 && reading >= search_start_ && reading < interior_ceiling_ &&
           !peak_checked_[f.idx] && (!measured_[f.idx] || on_turn(f));
  }
  // The reading of a face whose model reads `model` (>= search_start_) and whose edges peak at
  // `peaks` (set_peak_search).
  double peak_reading(double model, double peaks) const;
  std::uint32_t target_count(const Mesh48& mesh, Face f) const;
  std::uint32_t target_count(double area) const;
  bool pattern_outdated_at_area(Face f, double area) const;
  double sample_sum(std::uint32_t f) const;  // face f's sample errors summed in range order

  double density_;
  double peak_floor_ = 0.0;
  double largest_under_reading_ = 0.0;
  double search_start_ = 0.0;  // faces read below it are not searched (set_peak_search)
  double interior_ceiling_ = std::numeric_limits<double>::infinity();  // (peak_check_due)
  std::uint64_t seed_;
  std::uint64_t epoch_ = 0;              // set_pattern_epoch
  std::uint64_t patterns_drawn_ = 0;     // sample_changes()
  std::uint64_t peaks_kept_ = 0;         // samples kept at interior peaks (sample_changes)
  std::vector<Sample> samples_, spare_;  // spare_: compaction's target, kept for its capacity
                                         // (up to kReleaseFactor times the live samples)
  std::size_t garbage_ = 0;              // samples in no face's range
  std::vector<std::uint32_t> face_start_, face_count_;
  std::vector<double> face_error_;
  // The sum of each face's sample errors, in the order of its range (summary(): reading the
  // samples of every face each step for the mean streamed ~100 MB at 10^6 triangles, and was
  // 2.2% of a capsule-bend step's instructions at 10^5). Kept by everything that writes a
  // sample's error or changes a face's range: evaluate_face, append_sample, draw_pattern, the
  // splits and welds; sample_sum() computes it afresh.
  std::vector<double> face_sum_;
  std::vector<std::uint8_t> face_dense_;      // pattern densified for an unresolved estimate
  std::vector<std::uint8_t> measured_;        // measured() per face
  std::vector<double> model_error_;           // the quadratic model's reading (reading_gain)
  std::vector<double> peak_error_;            // its edges' peaks (-1: not searched)
  std::vector<Face> pending_, next_pending_;  // evaluate_faces' work lists
  // One slot per halfedge id; an edge uses its lower halfedge's. Valid when `pass` is the
  // current pass_; pass_ | kSlotBusy while one thread fills it (std::atomic_ref).
  struct EdgeSlot {
    double peak = 0.0;     // the edge's peak (edge_peaks)
    double largest = 0.0;  // the largest residual evaluated on it (the reader's guard)
    std::uint32_t pass = 0;
  };
  static constexpr std::uint32_t kSlotBusy = std::uint32_t{1} << 31;
  std::vector<EdgeSlot> edge_slots_;
  std::uint32_t pass_ = 0;
  bool share_edge_peaks_ = true;
  bool share_edges_ = false;  // this pass may share them (new_pass)
  std::uint64_t edge_peaks_shared_ = 0;
  std::vector<std::uint8_t> peak_checked_;  // peak_check_due: the interior peak was looked for
  MeasurementRotation rotation_;            // each face's turn (on_turn)
  std::vector<std::uint8_t> unresolved_;    // per-face flags (evaluate_faces, refresh_patterns)
  std::vector<std::uint8_t> keep_;          // evaluate_faces: a sample to append, per face
  std::vector<Sample> kept_;                // and that sample
};

template <class Fn>
void SampleStore::for_each_sample(Face f, Fn&& fn) const {
  const Sample* x = samples_.data() + face_start_[f.idx];
  for (std::uint32_t i = 0; i < face_count_[f.idx]; ++i)
    fn(x[i].barycentric(), static_cast<double>(x[i].error));
}

}  // namespace dynamesh
