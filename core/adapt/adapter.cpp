#include "core/adapt/adapter.h"

#include "core/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>

#include "core/geometry/fold_repair.h"
#include "core/geometry/mesh_quality.h"
#include "core/geometry/tangential_smoothing.h"
#include "core/mesh/spatial_order.h"
#include "core/surface/projection.h"
#include "core/topology/topology_events.h"

namespace dynamesh {
namespace {

// The paper's error is the L-infinity distance over each triangle, estimated from its samples
// (Section 3.1); splits are decided at T + eps. Sparse samples with the quadratic model
// (error_model.h) under-read a face's true peak by up to 33% on the twisted bar at T = 0.004
// (measured against a dense exact-distance measurement, seeds 1-8; the peaks lie on the
// faces' edges, EdgePeak), so a face read at or above 0.7 (T + eps) could be above T + eps:
// those faces have their edges searched for the peak (and, so that the reading has no jump
// there, the faces just below, where the peaks count less: SampleStore::set_peak_search).
// The assumption: faces read below 0.7 (T + eps) are under-read by less than 1 / 0.7 - 1 = 43%.
constexpr double kPeakSearchBand = 0.7;

void set_peak_search(SampleStore& samples, const AdaptOptions& o) {
  samples.set_peak_search(kPeakSearchBand * (o.threshold + o.epsilon), 1.0 / kPeakSearchBand - 1.0,
                          o.threshold + o.epsilon);
}

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

struct SplitEntry {
  double urgency;
  std::uint32_t face, stamp;
  bool operator<(const SplitEntry& o) const { return urgency < o.urgency; }  // largest on top
};

// A face's record for the event-free bound on refinement (AdaptOptions::hold_stalled_splits,
// Adapter::split_pass): the error and depth of the ancestor its split pass last measured on
// track, and whether the face is held (not split again while it lives).
struct SplitLineage {
  float error = 0.0f;
  std::uint32_t pass = 0;  // the split pass that recorded it (0: none)
  std::int16_t depth = 0;
  std::uint8_t held = 0;
};

struct WeldEntry {
  double error;
  std::uint32_t vertex;
  bool pathological = false;                  // welded before every other vertex (angle guard)
  bool operator<(const WeldEntry& o) const {  // pathological first, then smallest error
    if (pathological != o.pathological) return o.pathological;
    return error > o.error;
  }
};

}  // namespace

// Follows every split and weld: brings new vertices onto the surface, stamps changed face
// slots (so stale queue entries are recognised), remembers which faces a split touched and
// when each vertex was born (for temporal coherence).
class Adapter::Tracker final : public MeshListener {
 public:
  Tracker(const SurfaceProbe& probe, Adapter& adapter) : probe_(probe), adapter_(adapter) {}

  void after_split(Mesh48& mesh, const DiamondChange& change) override {
    grow(mesh);
    const bool placed = probe_.put_split_vertex(mesh, change);
    if (!placed) ++projection_failures;
    birth_step[change.vertex.idx] = current_step;
    // A vertex the fold guard kept off F (SurfaceProbe::project_split_vertex) lowers no error:
    // its faces are held until it is placed (Adapter::place_guarded_vertices).
    const bool guarded = !placed && probe_.split_fold_guard();
    if (guarded) adapter_.guarded_vertices_.push_back(change.vertex);
    for (int h = 0; h < change.count; ++h) {
      const Bisection& b = change.halves[h];
      lineage[b.children[1].idx] = lineage[b.children[0].idx];  // children[0] is the parent
      std::vector<std::uint8_t>& held = adapter_.guard_held_;
      if (held.size() < mesh.face_capacity()) held.resize(mesh.face_capacity(), 0);
      held[b.children[1].idx] = held[b.children[0].idx] |= guarded;
    }
    for (int h = 0; h < change.count; ++h)
      for (Face f : change.halves[h].children) {
        touch(f);
        if (recording_ring_changes) ring_changed(mesh, f);
      }
    ++vertices_created;
  }
  void after_weld(Mesh48& mesh, const DiamondChange& change) override {
    grow(mesh);
    for (int h = 0; h < change.count; ++h) {
      touch(change.halves[h].children[0]);
      lineage[change.halves[h].children[0].idx] = SplitLineage{};
      ++stamp[change.halves[h].children[1].idx];
      if (recording_ring_changes) ring_changed(mesh, change.halves[h].children[0]);
    }
  }
  // The tracker's own per-element data, and the adapter's (its listener for those).
  void after_renumber(Mesh48&, const Renumbering& r) override {
    renumber_elements(stamp, r.face, r.n_faces);
    renumber_elements(lineage, r.face, r.n_faces);
    renumber_elements(birth_step, r.vertex, r.n_vertices);
    renumber_handles(touched, r.face);
    renumber_handles(rings_changed, r.vertex);
    Adapter& a = adapter_;
    // Vertices born since these were recorded have no entry: NaN, never a position.
    a.carried_valid_ = false;
    for (std::vector<Vec3>* points : {&a.start_positions_, &a.rest_points_, &a.displacement_}) {
      points->resize(r.vertex.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
      renumber_elements(*points, r.vertex, r.n_vertices);
    }
    renumber_elements(a.projection_starts_, r.vertex, r.n_vertices);
    a.starts_planned_ = false;
    renumber_handles(a.to_measure_, r.face);
    for (std::vector<Face>& faces : a.bad_faces_) renumber_handles(faces, r.face);
  }
  // Every vertex whose one-ring a split or weld changed is a corner of one of the faces it
  // left (the welded vertex itself is gone).
  void ring_changed(const Mesh48& mesh, Face f) {
    for (Vertex v : mesh.vertices(f)) rings_changed.push_back(v);
  }

  // A new mesh (initial, re-based, locally repaired): no face held by split_pass, none on record.
  void forget_lineages(const Mesh48& mesh) { lineage.assign(mesh.face_capacity(), SplitLineage{}); }
  void grow(const Mesh48& mesh) {
    if (stamp.size() < mesh.face_capacity()) stamp.resize(mesh.face_capacity(), 0);
    if (lineage.size() < mesh.face_capacity()) lineage.resize(mesh.face_capacity());
    if (birth_step.size() < mesh.vertex_capacity()) birth_step.resize(mesh.vertex_capacity(), 0);
  }
  void touch(Face f) {
    ++stamp[f.idx];
    touched.push_back(f);
  }

  std::vector<std::uint32_t> stamp;
  std::vector<SplitLineage> lineage;  // per face slot (Adapter::split_pass)
  std::vector<std::uint64_t> birth_step;
  std::vector<Face> touched;
  // Since the last fold screen that found nothing (Adapter::publish_repaired).
  bool recording_ring_changes = false;
  std::vector<Vertex> rings_changed;
  std::uint64_t current_step = 0;
  std::size_t vertices_created = 0, projection_failures = 0;

 private:
  const SurfaceProbe& probe_;
  Adapter& adapter_;
};

Adapter::Adapter(Surface& surface, const AdaptOptions& options, CriterionList criteria)
    : surface_(surface),
      probe_(surface),
      options_(options),
      criteria_(std::move(criteria)),
      samples_(options.density, options.seed),
      tracker_(std::make_unique<Tracker>(probe_, *this)) {
  set_peak_search(samples_, options);
}

Adapter::~Adapter() = default;

void Adapter::set_options(const AdaptOptions& options, CriterionList criteria) {
  // References recorded before full sampling took over may be stale.
  if (options.sampling != options_.sampling) predictor_.invalidate();
  options_ = options;
  criteria_ = std::move(criteria);
  samples_.set_density(options.density);
  set_peak_search(samples_, options);
}

const StepStats& Adapter::initialize() {
  // A family whose base mesh does not refine well everywhere (Surface::mild_time) is adapted
  // where it is mild and carried to the requested time by the motion safeguards (sub-steps,
  // fold repair), which keep every frame embedded; the detour is not a frame.
  const double t0 = surface_.time(), mild = surface_.mild_time();
  if (!options_.geometric || std::isnan(mild) || mild == t0) return initialize_here();
  surface_.set_time(mild);
  initialize_here();
  double seconds = stats_.seconds.total;
  // In kMildSteps steps, so that the detour stays within the sub-step cap
  // (SubstepOptions::max_substeps): one step of 3 turns hit it and left 6.9-degree angles.
  constexpr int kMildSteps = 8;
  for (int k = 1; k <= kMildSteps; ++k)
    seconds += step(k == kMildSteps ? t0 : mild + (t0 - mild) * k / kMildSteps).seconds.total;
  // The first frame, as initialize_here() leaves it: step 0, every vertex born with it, and
  // settled, so that a static surface is a fixed point from here on (the detour's last step
  // ended, like any step, with splits its weld pass has not seen).
  step_ = 0;
  tracker_->current_step = 0;
  for (Vertex v : mesh_.live_vertices()) tracker_->birth_step[v.idx] = 0;
  stats_ = StepStats{};
  stats_.time = t0;
  Stopwatch clock;
  // Every face measured on its turn, as initialize_here() measures them: the interior peaks the
  // detour's steps left for later turns are looked for now (SampleStore::on_turn).
  samples_.set_every_turn();
  measure(mesh_.live_faces());
  if (options_.structural) settle();
  stats_.seconds.weld = clock.lap();
  publish_repaired();
  renumber_if_scattered();
  finish_stats();
  stats_.seconds.total += seconds;
  return stats_;
}

const StepStats& Adapter::initialize_here() {
  Stopwatch clock;
  mesh_ = surface_.base_mesh();
  // The tracker places new vertices before the samples are redistributed over them.
  mesh_.add_listener(tracker_.get());
  mesh_.add_listener(&samples_);
  mesh_.add_listener(&predictor_);
  mesh_.add_listener(&smoothing_workspace_);
  smoothing_workspace_.forget_frames();
  predictor_.invalidate();
  step_ = 0;
  stats_ = StepStats{};
  stats_.time = surface_.time();
  ++surface_epoch_;   // the surface may have been changed since the last step
  surface_changed();  // remember the state the initial mesh was made for
  tracker_->current_step = 0;
  tracker_->grow(mesh_);
  tracker_->forget_lineages(mesh_);
  samples_.reset(mesh_);
  samples_.set_every_turn();  // until the first step (sampling)
  stats_.seconds.project = clock.lap();
  if (options_.sampling == Sampling::kPredictive)
    predictor_.begin_step(mesh_, probe_, start_positions_, step_);
  measure(mesh_.live_faces());
  stats_.seconds.sample = clock.lap();
  if (options_.structural) {
    // Refine to the weld bound (criteria.h, SplitQuery::initial), then settle: the result is
    // a fixed point of step() on a static surface.
    split_pass(true);
    stats_.seconds.split = clock.lap();
    settle();
    stats_.seconds.weld = clock.lap();
    relax();
    stats_.seconds.smooth = clock.lap();
  }
  watch_topology();
  publish_repaired();
  renumber_if_scattered();
  finish_stats();
  return stats_;
}

const StepStats& Adapter::step(double t) {
  const double from = surface_.time();
  stats_ = StepStats{};
  stats_.step = ++step_;
  ++tracker_->current_step;
  stats_.time = t;
  start_positions_ = mesh_.positions();  // copy-assignment reuses the capacity
  probe_.set_split_fold_guard(false);    // until a topology repair (check_topology)
  forget_guarded_vertices();
  repair_centres_.clear();
  vertices_at_start_ = mesh_.n_vertices();
  // Sub-steps (motion_substeps.h): the requested time is reached through equal sub-steps, each
  // one the paper's whole step, so that no sub-step moves the surface far against the mesh.
  Stopwatch clock;
  bool planned = false;
  starts_planned_ = false;
  int n = plan_substeps(from, t, planned);
  stats_.seconds.project = clock.lap();
  bool corrected = false;
  double start = from;
  int done = 0;
  bool replanned = false;
  // Sub-step k of n ends at start + (t - start) s^2, s = k / n once a topology change replanned
  // the step (below), else at start + (t - start) k / n.
  bool graded = false;
  for (int k = 1; k <= n; ++k) {
    const std::size_t repairs = stats_.local_repairs;
    const bool rebuilt = stats_.rebuilt;
    const double s = static_cast<double>(k) / n;
    corrected |=
        advance(k == n ? t : start + (t - start) * (graded ? s * s : s), k == 1 && planned);
    // A topology repair or rebuild within the step (issue 16) replaced the mesh the sub-steps
    // were planned on, next to where the surface moves fastest (a new neck widens, new tips
    // recede, both as the square root of the time since the event): the rest of the step is
    // planned again on the new mesh (once: a step holds at most 2 * max_substeps sub-steps),
    // in sub-steps growing as the square of their number, so that each moves the neck or the
    // tips alike (sqrt(t - t_event) grows by equal amounts). Equal sub-steps give the first
    // one after the repair most of the neck's widening: at 20 steps the blobs' merge (x axis)
    // then left 27 faces folded and the fold net rebuilt the mesh; graded, none.
    if (!replanned && k < n && (stats_.local_repairs != repairs || stats_.rebuilt != rebuilt)) {
      replanned = true;
      graded = true;
      done += k;
      start = surface_.time();
      const double strain = stats_.motion_strain;
      n = plan_substeps(start, t, planned);
      stats_.substeps += done;  // those taken, and those planned now
      stats_.motion_strain = std::max(strain, stats_.motion_strain);
      k = 0;
    }
  }
  if (topology_) place_guarded_vertices();
  // A static surface stays a fixed point of step(): nothing moved, nothing to look at again.
  if (corrected || stats_.splits || stats_.welds) publish_repaired();
  if (topology_) remesh_published_folds();
  if (topology_) rebuild_if_crossed();
  renumber_if_scattered();
  finish_stats();
  return stats_;
}

int Adapter::plan_substeps(double from, double to, bool& rest_points_planned) {
  small_motion_ = false;
  if (!options_.geometric || !options_.substeps.enabled || from == to) return 1;
  const bool carry = probe_.follows_material();
  if (carry) record_rest_points();
  rest_points_planned = carry;
  surface_.set_time(to);
  const bool implicit = !probe_.parametric();
  predict_displacements(mesh_, probe_, carry ? &rest_points_ : nullptr, displacement_,
                        implicit ? &projection_starts_ : nullptr);
  const MotionEstimate e = estimate_substeps(mesh_, displacement_, options_.substeps);
  surface_.set_time(from);
  // One sub-step ends at `to`, where the starts were evaluated (a topology rebuild before
  // the correction would renumber the vertices: not then).
  starts_planned_ = implicit && e.substeps == 1 && !topology_;
  stats_.substeps = e.substeps;
  stats_.motion_strain = e.strain;
  small_motion_ = e.substeps == 1 && e.strain <= options_.fold_repair.prescreen_above_strain;
  return e.substeps;
}

bool Adapter::advance(double t, bool rest_points_fresh) {
  Stopwatch clock;
  PhaseSeconds& seconds = stats_.seconds;
  if (options_.geometric && probe_.follows_material() && !rest_points_fresh) record_rest_points();
  surface_.set_time(t);
  ++surface_epoch_;
  if (topology_) check_topology();
  const bool correct = options_.geometric && surface_changed();
  if (correct) normal_correction();
  seconds.project += clock.lap();
  if (correct) tangential_correction();
  // A small motion in one go is screened once, before publishing (prescreen_above_strain).
  const bool screen = correct && !(small_motion_ && !topology_);
  if (screen) repair(options_.fold_repair);
  if (correct && topology_) rebuild_if_folded();
  // From a clean screen on, only splits and welds change the mesh before the frame is
  // published (no vertex moves): publish_repaired() looks again only where they did.
  tracker_->rings_changed.clear();
  tracker_->recording_ring_changes = screen && !topology_ && options_.fold_repair.enabled &&
                                     stats_.folds_left == 0 && stats_.slivers_left == 0;
  seconds.smooth += clock.lap();
  sampling();
  seconds.sample += clock.lap();
  if (options_.structural) weld_pass();
  seconds.weld += clock.lap();
  if (options_.structural) split_pass(false);
  seconds.split += clock.lap();
  return correct;
}

void Adapter::repair(const FoldRepairOptions& options) {
  const FoldReport r = repair_folds(mesh_, surface_, options, &fold_screen_);
  stats_.folds_found += r.folded;
  stats_.slivers_found += r.slivers;
  stats_.repair_moves += r.moved;
  stats_.folds_left = r.remaining_folded;
  stats_.slivers_left = r.remaining_slivers;
}

void Adapter::publish_repaired() {
  // Splits place new vertices on the surface between their parents: over a crease that can
  // fold or thin a face. A frame is published only after a last look (and, if needed, a
  // repair, a fresh measurement and the splits it asks for, and a look again at what those
  // splits changed: on mri's way back up they thinned faces to 6.3 degrees after a repair
  // had left none below 10).
  if (!options_.geometric || !options_.fold_repair.enabled) return;
  Stopwatch clock;
  std::vector<Face>& folded = bad_faces_[0];
  std::vector<Face>& slivers = bad_faces_[1];
  // At most this many repairs before a frame is published; what the last screen finds is
  // reported (folds_left, slivers_left), never hidden.
  constexpr int kMaxRepairs = 4;
  for (int repairs = 0;; ++repairs) {
    // Both screens give the same verdicts; the one around changed rings walks each ring and
    // sums its corners' normals afresh (~25x the full screen's cost per face, measured on twist
    // at 1.5-3k faces): worth it only when few rings changed, as at 10^6 triangles.
    const bool few_changed = tracker_->rings_changed.size() * 8 <= mesh_.n_faces();
    if (tracker_->recording_ring_changes && options_.fold_repair.screen_changed_only && few_changed)
      find_bad_faces_around(mesh_, surface_, options_.fold_repair.min_angle_deg,
                            tracker_->rings_changed, folded, slivers, &fold_screen_);
    else
      find_bad_faces(mesh_, surface_, options_.fold_repair.min_angle_deg, folded, slivers,
                     &fold_screen_);
    tracker_->recording_ring_changes = false;
    stats_.folds_left = folded.size();
    stats_.slivers_left = slivers.size();
    if ((folded.empty() && slivers.empty()) || repairs == kMaxRepairs) {
      stats_.seconds.smooth += clock.lap();
      return;
    }
    repair(options_.fold_repair);
    stats_.seconds.smooth += clock.lap();
    // The repair moved vertices after they were measured: measure again, and refine where a
    // move pushed a face above T + eps (a weld pass here could undo what the repair fixed).
    // After a clean repair only those splits change the mesh: the next screen looks where
    // they did.
    sampling();
    stats_.seconds.sample += clock.lap();
    const bool clean = stats_.folds_left == 0 && stats_.slivers_left == 0;
    tracker_->rings_changed.clear();
    tracker_->recording_ring_changes = clean && !topology_;
    const std::size_t created = tracker_->vertices_created;
    if (options_.structural) split_pass(false);
    stats_.seconds.split += clock.lap();
    if (clean && tracker_->vertices_created == created) {  // nothing changed since
      tracker_->recording_ring_changes = false;
      return;
    }
  }
}

void Adapter::rebuild_from_base(long euler, long components) {
  // As initialize() does, but within a step: every vertex is born now (none survives), local
  // repairs of this step included.
  Mesh48 base = mid_run_base_mesh(euler, components);
  held_depth_ = -1;  // the new mesh has F's topology
  forget_guarded_vertices();
  stats_.local_repairs = 0;
  stats_.repair_faces_replaced = 0;
  stats_.repair_spacing = 0.0;
  mesh_ = std::move(base);
  mesh_.add_listener(tracker_.get());
  mesh_.add_listener(&samples_);
  mesh_.add_listener(&predictor_);  // (was missing: split vertices kept a freed id's frame)
  predictor_.invalidate();
  mesh_.add_listener(&smoothing_workspace_);
  smoothing_workspace_.forget_frames();
  tracker_->grow(mesh_);
  tracker_->forget_lineages(mesh_);
  for (const Vertex v : mesh_.live_vertices()) tracker_->birth_step[v.idx] = step_;
  samples_.reset(mesh_);
  samples_.evaluate_all(mesh_, probe_);
  if (options_.structural) split_pass(true);
}

void Adapter::adopt_repair(const std::vector<Vertex>& born) {
  // The mesh told no listener about the surgery (Mesh48::replace_region): the new vertices
  // are born now, every face is looked at again and its samples drawn afresh (the sampling
  // that follows in this step measures them all).
  tracker_->grow(mesh_);
  // The faces held for an error that did not fall (split_pass) may have gone with the old
  // topology: every face may be split again.
  tracker_->forget_lineages(mesh_);
  guard_held_.assign(guard_held_.size(), 0);  // face slots the surgery freed may be reused
  for (const Vertex v : born) tracker_->birth_step[v.idx] = step_;
  for (const Face f : mesh_.live_faces()) tracker_->touch(f);
  samples_.reset(mesh_);
  predictor_.invalidate();
  smoothing_workspace_.forget_frames();
}

bool Adapter::surface_changed() {
  std::vector<double> parameters;
  for (const SurfaceParameter& p : surface_.parameters()) parameters.push_back(p.value);
  const bool changed = surface_.time() != last_time_ || parameters != last_parameters_;
  last_time_ = surface_.time();
  last_parameters_ = std::move(parameters);
  return changed;
}

void Adapter::record_rest_points() {
  const auto n = static_cast<std::int64_t>(mesh_.vertex_capacity());
  rest_points_.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    if (mesh_.is_alive(v)) rest_points_[static_cast<std::size_t>(i)] = probe_.rest_point(mesh_, v);
  }
}

void Adapter::normal_correction() {
  const auto n = static_cast<std::int64_t>(mesh_.vertex_capacity());
  // Surfaces with a rest map: each vertex first goes where its material point went (recorded
  // before the time changed), so the projection below only removes rounding and drift.
  // Without one, the vertex moves with the surface's normal velocity v = -F_t grad F /
  // |grad F|^2: Newton's first iterate from p at the new time, -F(p) grad F / |grad F|^2 with
  // F(p) = F_t dt (p was on the surface), is exactly that prediction; on a distance field
  // (mri) it moves along the distance gradient. Sub-steps keep dt small enough for it to hold.
  const bool carry = probe_.follows_material() && rest_points_.size() >= mesh_.vertex_capacity();
  // One sub-step: plan_substeps() already evaluated F and grad F where the projection starts
  // (the carried point, or the vertex itself), at this time; used once.
  const bool planned = starts_planned_ && projection_starts_.size() >= mesh_.vertex_capacity();
  starts_planned_ = false;
  std::size_t failures = 0;
  // Implicit: F and grad F where each vertex lands are kept (ErrorPredictor::note) for the
  // smoothing's moves in both sampling modes (tangential_correction: the modes must place the
  // vertices alike) and, predictive, for the predictor (begin_step).
  const auto* implicit =
      probe_.parametric() ? nullptr : &static_cast<const ImplicitSurface&>(surface_);
  const bool keep = implicit && options_.sampling == Sampling::kPredictive;
  if (implicit) predictor_.grow_for(mesh_);
  // One sub-step only: the slide is measured over the whole step (ErrorPredictor::begin_step).
  carried_from_rest_ = carry;
  carried_valid_ = keep && carry && stats_.substeps <= 1;
  if (carried_valid_) carried_.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : failures) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    if (!mesh_.is_alive(v)) continue;
    const auto k = static_cast<std::size_t>(i);
    if (carry && !planned) probe_.carry_vertex(mesh_, v, rest_points_[k]);
    if (!implicit) {
      if (!probe_.project_vertex(mesh_, v)) ++failures;
      continue;
    }
    if (carried_valid_) carried_[k] = planned ? projection_starts_[k].point : mesh_.position(v);
    // Both modes alike, without SurfaceProbe::trusted_step (ProjectionOptions::quadratic_beyond,
    // issue 16): full sampling took it (project_vertex) and predictive sampling did not, so the
    // modes put vertices in different places and decided differently (twist, T = 0.001: in the
    // first step after the mild time). Predictive, the default, is the one every topology
    // variant was judged with; with the trusted step the torus pinched in 10 steps leaves two
    // faces folded after the correction and is rebuilt (test TorusPinchIn10StepsKeepsItsVertices).
    const ProjectionResult r = planned ? project_to_surface(*implicit, projection_starts_[k])
                                       : project_to_surface(*implicit, mesh_.position(v));
    mesh_.position(v) = r.point;
    if (!r.converged) ++failures;
    predictor_.note(v, r.point, r.value, r.gradient, surface_epoch_);
  }
  tracker_->projection_failures += failures;
}

void Adapter::tangential_correction() {
  // A step that needed sub-steps moves fast against the mesh: frames go stale within it, so
  // none is reused (tangential_smoothing.cpp, frame_reusable). Nor on parametric surfaces:
  // on sinc, reuse let skipped faces' errors escape the predictor's bound (5.8x of it over
  // 100 steps, PredictiveAnimation/sinc; 0.79x without reuse). The cause was the bound's
  // missing cubic term (error_predictor.h; reuse slides faces across curvature changes): with
  // it, reuse on sinc uses 0.36 of the bound (1.16 without it, same safety factor). Measured
  // (issue 17, sinc at T = 0.002, 100 steps, one thread): reuse would save 1.3% of the
  // instructions (the frames' 150 M of 6,123 M fall to 100 M: the ripples move under the
  // vertices, so only a third of the frames qualify), for no change in the counts that
  // matters (splits 5,488 against 5,500). Not switched on for that.
  SmoothingOptions smoothing = options_.smoothing;
  smoothing.reuse_frames = smoothing.reuse_frames && stats_.substeps == 1 && !probe_.parametric();
  // Each vertex's rest point is the one it was carried from (normal_correction): frame reuse
  // reads it instead of mapping the vertex back.
  if (carried_from_rest_) smoothing.rest_points = &rest_points_;
  carried_from_rest_ = false;
  // Where the normal correction left each vertex, F and grad F (normal_correction): the moves
  // start from their second-order landing points.
  if (!probe_.parametric()) {
    smoothing.evaluations = &predictor_.evaluations();
    smoothing.evaluations_epoch = surface_epoch_;
  }
  const SmoothingResult r = smooth_tangentially(mesh_, surface_, smoothing, &smoothing_workspace_);
  tracker_->projection_failures += r.projection_failures;
  if (!probe_.parametric()) {
    // Where the smoothing moved a vertex, its projection's F and grad F (ErrorPredictor::note):
    // in both modes, as normal_correction keeps them (a relaxation round's moves start there).
    predictor_.grow_for(mesh_);
    const auto n = static_cast<std::int64_t>(mesh_.vertex_capacity());
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::int64_t i = 0; i < n; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      double value;
      Vec3 gradient;
      if (mesh_.is_alive(v) && smoothing_workspace_.landed(v, value, gradient))
        predictor_.note(v, mesh_.position(v), value, gradient, surface_epoch_);
    }
  }
  stats_.smoothing_moved += r.moved;
  stats_.smoothing_reverted += r.reverted;
  stats_.frames_reused += r.frames_reused;
}

void Adapter::sampling() {
  samples_.set_pattern_epoch(surface_epoch_);
  samples_.set_step(step_);  // whose turn it is: both modes measure those faces (select too)
  if (options_.sampling == Sampling::kFull) {
    samples_.refresh_patterns(mesh_);
    measure(mesh_.live_faces());
    stats_.faces_measured += mesh_.n_faces();
    return;
  }
  predictor_.begin_step(mesh_, probe_, start_positions_, step_, surface_epoch_,
                        carried_valid_ ? &carried_ : nullptr);
  carried_valid_ = false;
  stats_.evaluations_reused += predictor_.reused_evaluations();
  predictor_.select(mesh_, probe_, samples_,
                    {split_error_floor(false),
                     [&](Face f, double error) { return split_urgency(f, error, false) > 1.0; }},
                    to_measure_);
  // select() listed every face whose pattern is outdated; the same patterns as the mesh-wide
  // refresh_patterns(mesh_) draws, in the same (face) order.
  samples_.refresh_patterns(mesh_, to_measure_);
  measure(to_measure_);
  stats_.faces_measured += to_measure_.size();
}

void Adapter::measure(const std::vector<Face>& faces) {
  samples_.evaluate_faces(mesh_, probe_, faces);
  if (options_.sampling == Sampling::kPredictive) predictor_.record(mesh_, probe_, faces);
}

double Adapter::split_urgency(Face f, double error, bool initial) const {
  const SplitQuery q{mesh_, f, error, initial};
  double urgency = 0.0;
  for (const auto& c : criteria_)
    if (c->applies_to(mesh_, f)) urgency = std::max(urgency, c->split_urgency(q));
  return urgency;
}

double Adapter::split_error_floor(bool initial) const {
  double floor = std::numeric_limits<double>::infinity();
  for (const auto& c : criteria_) floor = std::min(floor, c->split_error_floor(initial));
  return floor;
}

double Adapter::weld_ceiling(const DiamondChange& plan, double current) const {
  double ceiling = std::numeric_limits<double>::infinity();
  for (const auto& c : criteria_)
    if (c->applies_to(mesh_, plan)) ceiling = std::min(ceiling, c->weld_error_ceiling(current));
  return ceiling;
}

Adapter::ErrorRange Adapter::star_error_range(const DiamondChange& plan) const {
  ErrorRange r{0.0, 0.0};
  for (int h = 0; h < plan.count; ++h)
    for (Face f : plan.halves[h].children) {
      const ErrorPredictor::Range face = predictor_.reading_range(samples_, f);
      r.lo = std::max(r.lo, face.lo);
      r.hi = std::max(r.hi, face.hi);
    }
  return r;
}

void Adapter::append_skipped_faces(const DiamondChange& plan, std::vector<Face>& out) const {
  for (int h = 0; h < plan.count; ++h)
    for (Face f : plan.halves[h].children)
      if (predictor_.bound(samples_, f) > 0.0) out.push_back(f);
}

void Adapter::measure_star(const DiamondChange& plan) {
  star_skipped_.clear();  // no allocation per star (the weld pass measures stars one at a time)
  append_skipped_faces(plan, star_skipped_);
  measure(star_skipped_);
}

bool Adapter::weld_allowed(const DiamondChange& plan, double error, double current) const {
  const WeldQuery q{mesh_, plan, error, current};
  for (const auto& c : criteria_)
    if (c->applies_to(mesh_, plan) && !c->allows_weld(q)) return false;
  return true;
}

bool Adapter::pathological(Face f) const {
  const auto v = mesh_.vertices(f);
  return !angles_within(mesh_.position(v[0]), mesh_.position(v[1]), mesh_.position(v[2]),
                        options_.angle_guard.min_deg, options_.angle_guard.max_deg);
}

// The edge to split is the face's refinement edge; its incident angles are those of the
// face and of its neighbour across it (the diamond).
bool Adapter::split_refused(Face f) const {
  if (held_depth_ >= 0 && mesh_.depth(f) >= held_depth_) return true;  // hold_splits
  if (f.idx < guard_held_.size() && guard_held_[f.idx]) return true;   // a guarded vertex
  if (!options_.angle_guard.refuse_splits) return false;
  if (pathological(f)) return true;
  const Face other = mesh_.neighbor(f, 0);
  return other.is_valid() && pathological(other);
}

bool Adapter::pathological_star(const DiamondChange& plan) const {
  if (!options_.angle_guard.weld_first) return false;
  for (int h = 0; h < plan.count; ++h)
    for (Face f : plan.halves[h].children) {
      const auto v = mesh_.vertices(f);
      if (!angles_clearly_within(mesh_.position(v[0]), mesh_.position(v[1]), mesh_.position(v[2]),
                                 star_angle_cosines_) &&
          pathological(f))
        return true;
    }
  return false;
}

void Adapter::weld_pass() {
  star_angle_cosines_ = AngleCosines(options_.angle_guard.min_deg, options_.angle_guard.max_deg);
  // Post-weld errors of every weldable vertex, in parallel (each sample belongs to the star
  // of its face's newest vertex only, so this costs at most one evaluation per sample).
  const auto n = static_cast<std::int64_t>(mesh_.vertex_capacity());
  // Pathological vertices (angle guard) are welded whenever the weld keeps the error within
  // T + eps; they are flagged by a negative key and go first.
  const double guard_limit = options_.threshold + options_.epsilon;
  // The key of a weld candidate: its post-weld error, measured only as far as the criteria's
  // ceiling for the star's current error needs; NaN when the weld is not allowed.
  // With predictive sampling the current error is known within a range (star_error_range);
  // the criteria allow more welds the larger it is (criteria.h), so a decision that is the
  // same at both ends is the decision; otherwise the candidate is `ambiguous` and decided
  // again once its star is measured.
  // `known`: the post-weld error when it was already measured in full (weld_error read no
  // more than its ceiling) on the star's present samples and positions, else NaN. It stands
  // for weld_error's reading at any ceiling: where that reading would be below its ceiling it
  // is `known` itself; above, it is a lower bound that only tells "above the ceiling", as
  // `known` does, and the guard's second reading below would be `known` again.
  // The restored edge's midpoint is weld_error's first reading and a lower bound of it. Where
  // it reads above both the guard's limit and the ceiling at any current error (the criteria's
  // ceilings do not fall as the current error grows), no weld is allowed and the guard welds
  // none: the candidate is rejected without the star's range or angles, the same key weld_key
  // gives it (most candidates of an adapted mesh: welding would coarsen it a level).
  constexpr double kNoWeld = std::numeric_limits<double>::quiet_NaN();
  const double no_ceiling = std::numeric_limits<double>::infinity();
  auto weld_key = [&](const DiamondChange& plan, bool& ambiguous, double& known) {
    const bool exact = !std::isnan(known);
    ambiguous = false;
    const double midpoint = exact ? 0.0 : SampleStore::weld_midpoint_error(mesh_, probe_, plan);
    if (midpoint > guard_limit && midpoint > weld_ceiling(plan, no_ceiling)) return kNoWeld;
    const ErrorRange current = star_error_range(plan);
    const double ceiling = weld_ceiling(plan, current.hi);
    double error = exact ? known : samples_.weld_error(mesh_, probe_, plan, ceiling, midpoint);
    if (error <= ceiling) known = error;
    const bool allowed = weld_allowed(plan, error, current.hi);
    ambiguous = allowed && current.lo < current.hi && !weld_allowed(plan, error, current.lo);
    if (ambiguous) return kNoWeld;
    if (allowed) return pathological_star(plan) ? -1.0 - error : error;
    if (error > guard_limit || !pathological_star(plan)) return kNoWeld;
    // Above the ceiling weld_error stopped early: `error` is only a lower bound of the
    // post-weld error (the ceiling is below T + eps when the star reads below (T + eps) / 1.05).
    // The guard must see the error itself up to its own limit, else it welds a star that
    // reads above T + eps once welded (and is split straight back). Rare: measured again.
    if (error > ceiling && !exact)
      error = samples_.weld_error(mesh_, probe_, plan, guard_limit, midpoint);
    return error <= guard_limit ? -1.0 - error : kNoWeld;
  };
  // An ambiguous star (its key NaN, its post-weld error `known` in full: ambiguity needs the
  // weld allowed at the range's top, so the reading was below its ceiling) is decided once
  // its skipped faces are measured. Measuring leaves the samples where they were unless a
  // face's pattern was densified or it kept an interior peak: then the post-weld error is
  // read again.
  auto decide_measured = [&](const DiamondChange& plan, double known) {
    const std::uint64_t changes = samples_.sample_changes();
    measure_star(plan);
    if (samples_.sample_changes() != changes) known = std::numeric_limits<double>::quiet_NaN();
    bool ambiguous = false;
    return weld_key(plan, ambiguous, known);
  };
  auto decided_key = [&](const DiamondChange& plan) {
    bool ambiguous = false;
    double known = std::numeric_limits<double>::quiet_NaN();
    const double k = weld_key(plan, ambiguous, known);
    return ambiguous ? decide_measured(plan, known) : k;
  };
  // The keys in parallel; the candidates (a key, or ambiguous) listed in vertex order, as the
  // serial sweep below needs them (OrderedCollector).
  weld_collector_.collect(n, weld_candidates_, [&](std::int64_t i, WeldCandidate& c) {
    DiamondChange plan;
    c.vertex = static_cast<std::uint32_t>(i);
    if (!mesh_.plan_weld(Vertex(c.vertex), plan)) return false;
    bool a = false;
    double known = std::numeric_limits<double>::quiet_NaN();
    const double k = weld_key(plan, a, known);
    c.key = a ? known : k;  // ambiguous: its post-weld error, for now
    c.ambiguous = a;
    return a || !std::isnan(k);
  });
  auto entry = [](double k, std::uint32_t v) {
    return k < 0 ? WeldEntry{-1.0 - k, v, true} : WeldEntry{k, v, false};
  };
  decide_ambiguous_stars(weld_key);
  std::priority_queue<WeldEntry> queue;
  for (const WeldCandidate& c : weld_candidates_)
    if (!std::isnan(c.key)) queue.push(entry(c.key, c.vertex));
  tracker_->touched.clear();
  DiamondChange plan;
  while (!queue.empty()) {
    const Vertex v(queue.top().vertex);
    const bool forced = queue.top().pathological;
    queue.pop();
    if (!mesh_.plan_weld(v, plan)) continue;
    mesh_.weld(v);
    ++stats_.welds;
    stats_.pathological_welds += forced;
    // Welding may make the merged faces' newest vertices weldable: the cascade.
    for (int h = 0; h < plan.count; ++h) {
      const Vertex apex = plan.halves[h].parent_vertices[0];
      DiamondChange next;
      if (!mesh_.plan_weld(apex, next)) continue;
      const double k = decided_key(next);
      if (!std::isnan(k)) queue.push(entry(k, apex.idx));
    }
  }
  // Merged faces need their errors against their new shape before the split pass.
  std::vector<Face> merged;
  for (Face f : tracker_->touched)
    if (mesh_.is_alive(f)) merged.push_back(f);
  std::sort(merged.begin(), merged.end());
  merged.erase(std::unique(merged.begin(), merged.end()), merged.end());
  measure(merged);
}

// Ambiguous stars (predictive sampling only) are measured before they are decided. Each face
// belongs to the star of its newest vertex only (Mesh48::plan_weld), so measuring one star
// changes no other star's range or samples: every star is still ambiguous, with the same
// post-weld error, however many others were measured first. So their skipped faces are
// measured in one call, in parallel (they were measured star by star, serially: at 10^6
// triangles ~1,200 stars and ~20 ms a step), with the same readings: a face's measurement
// depends on its own samples and corners only (and an edge peak read from the slot the face
// across filled, when it did, is the one this face would find: shared_edge_peaks). A star's
// post-weld error, `known`, stands unless measuring changed its samples (a pattern densified
// or an interior peak kept, each of which adds samples to the face), as decide_measured
// judges one star. The keys are then decided in parallel, as the first were.
template <class Key>
void Adapter::decide_ambiguous_stars(Key&& weld_key) {
  ambiguous_stars_.clear();
  ambiguous_faces_.clear();
  AmbiguousStar star;
  for (std::size_t i = 0; i < weld_candidates_.size(); ++i) {
    WeldCandidate& c = weld_candidates_[i];
    if (!c.ambiguous) continue;
    DiamondChange& plan = star.plan;
    if (!mesh_.plan_weld(Vertex(c.vertex), plan)) {  // (the mesh has not changed since)
      c = WeldCandidate{std::numeric_limits<double>::quiet_NaN(), c.vertex, false};
      continue;
    }
    star.candidate = static_cast<std::uint32_t>(i);
    star.first_face = static_cast<std::uint32_t>(ambiguous_faces_.size());
    ambiguous_stars_.push_back(star);
    append_skipped_faces(plan, ambiguous_faces_);
  }
  if (ambiguous_stars_.empty()) return;
  ambiguous_counts_.resize(ambiguous_faces_.size());
  for (std::size_t j = 0; j < ambiguous_faces_.size(); ++j)
    ambiguous_counts_[j] = samples_.count(ambiguous_faces_[j]);
  measure(ambiguous_faces_);
  const auto n = static_cast<std::int64_t>(ambiguous_stars_.size());
#pragma omp parallel for schedule(dynamic, 16) if (n > kParallelMinCostly)
  for (std::int64_t j = 0; j < n; ++j) {
    const AmbiguousStar& s = ambiguous_stars_[static_cast<std::size_t>(j)];
    const std::size_t last = j + 1 < n
                                 ? ambiguous_stars_[static_cast<std::size_t>(j + 1)].first_face
                                 : ambiguous_faces_.size();
    WeldCandidate& c = weld_candidates_[s.candidate];
    bool changed = false;
    for (std::size_t k = s.first_face; k < last; ++k)
      changed = changed || samples_.count(ambiguous_faces_[k]) != ambiguous_counts_[k];
    double known = changed ? std::numeric_limits<double>::quiet_NaN() : c.key;
    bool ambiguous = false;
    c.key = weld_key(s.plan, ambiguous, known);
    c.ambiguous = false;
  }
}

void Adapter::settle() {
  // A weld pass and a split pass undo each other only through the estimate's noise: a face
  // split above T + eps is measured afresh on its children's samples (redrawn when a child
  // holds too few), and the weld that would undo it may then pass the no-gain rule, whose
  // ceiling is T + eps itself (criteria.h). Such a pair settles in one more round, since the
  // welded face keeps the samples its weld was judged on; the cap only guards against a
  // pathological estimate.
  constexpr int kMaxRounds = 4;
  for (int round = 0; round < kMaxRounds; ++round) {
    const std::size_t before = stats_.splits + stats_.welds;
    weld_pass();
    split_pass(false);
    if (stats_.splits + stats_.welds == before) return;
  }
}

void Adapter::relax() {
  if (!options_.geometric || !options_.smoothing.enabled) return;
  for (int round = 0; round < options_.initial_relaxation_rounds; ++round) {
    // A round is what a step does to the mesh, without the motion: smoothing (Equation 1),
    // every face measured where the vertices now are, welds and splits until quiet.
    start_positions_ = mesh_.positions();
    tangential_correction();
    samples_.refresh_patterns(mesh_);
    // The predictor's references must be taken from the vertices' frames where they now are.
    if (options_.sampling == Sampling::kPredictive)
      predictor_.begin_step(mesh_, probe_, start_positions_, step_);
    measure(mesh_.live_faces());
    settle();
  }
}

void Adapter::split_pass(bool initial) {
  // The event-free bound (AdaptOptions::hold_stalled_splits). On a smooth surface a face's error
  // falls as its area, by half with every bisection (error ~ curvature h^2 / 8): within one
  // pass, a face split k times below an ancestor has about 2^-k of that ancestor's error. Where
  // the mesh's topology is not F's (a neck F no longer has, a cavity the mesh lacks) the faces
  // spanning the gap keep an error of about the gap's half-width however often they are split,
  // and the split queue refined them without end (the dumbbell's split unwatched: 50,000
  // triangles in one step; Colin27 with closing 2 at 4 mm deep: 445,000-522,000). So within a
  // pass each face carries the error and depth of the last ancestor on track: a face
  // kStallLevels bisections below it whose error has not fallen by half (a smooth surface's has
  // fallen to 1/16) is held, and not split again while it lives, and from then on no face
  // deeper than 4 bisections below the deepest now (hold_splits); the error stays above T and
  // is reported (splits_held, held_depth). An error at least doubled on the way (a feature the
  // coarser faces' samples missed) restarts the count; an error halved restarts it from there.
  // A smaller rise is the stall itself read through other samples: the dumbbell's gap faces read
  // 2.85-3.70 mm at every depth from 2 to 15, and restarted on every new maximum (200 times in
  // one pass) the hold engaged anywhere from depth 10 to 16 with the sample seed, and with seed 4
  // the pass ran into the 5,000-triangle budget (MriEvents.DumbbellUnwatchedHoldsForEverySeed).
  // Only in steps (an initial mesh or a re-base refines from faces far coarser than the features
  // they span, whose error stays up until they are finer than the features), and only without a
  // topology monitor, whose events hold the splits when they cannot be followed: a repair's patch
  // is as coarse against the new neck, and the diagonal blobs' merge tripped the bound in the
  // step after it (test TopologyEvents.DiagonalBlobsMergeAndSeparate). And only with the vertex
  // correction: without it (--no-geometric) the old vertices stay off the moving surface, so no
  // split lowers the error, whatever the topology; that run stops on its own at the first step
  // above T + eps (test CliOptions.NoGeometricStopsWhenTheMeshIsLeftBehind).
  constexpr int kStallLevels = 4;
  constexpr double kStallFall = 0.5;
  const bool bound =
      options_.hold_stalled_splits && options_.geometric && !initial && step_ > 0 && !topology_;
  const std::uint32_t pass = bound ? ++split_pass_id_ : 0;
  if (bound) tracker_->grow(mesh_);
  // The urgencies in parallel, the queue filled in face order as a serial scan fills it (the
  // queue breaks ties by its insertion history, not by face).
  const double floor = split_error_floor(initial);
  urgent_collector_.collect(static_cast<std::int64_t>(mesh_.face_capacity()), urgent_,
                            [&](std::int64_t i, std::pair<double, Face>& hit) {
                              const Face f(static_cast<std::uint32_t>(i));
                              if (!mesh_.is_alive(f)) return false;
                              const double error = samples_.face_error(f);
                              if (!(error > floor)) return false;
                              hit = {split_urgency(f, error, initial), f};
                              return hit.first > 1.0;
                            });
  std::priority_queue<SplitEntry> queue;
  for (const auto& [u, f] : urgent_) queue.push({u, f.idx, tracker_->stamp[f.idx]});
  const std::size_t created_before = tracker_->vertices_created;
  while (!queue.empty()) {
    const SplitEntry e = queue.top();
    queue.pop();
    const Face f(e.face);
    if (!mesh_.is_alive(f) || tracker_->stamp[f.idx] != e.stamp) continue;
    if (mesh_.n_faces() + 4 > options_.max_triangles) {
      stats_.budget_hit = true;
      break;
    }
    if (samples_.n_samples() > options_.max_samples) {
      stats_.sample_budget_hit = true;
      break;
    }
    // The clock is read every 64 splits (a split costs microseconds).
    if ((++splits_since_clock_ & 63) == 0 && std::chrono::steady_clock::now() > options_.deadline) {
      stats_.time_budget_hit = true;
      break;
    }
    if (split_refused(f)) {
      ++stats_.splits_refused;
      if (held_depth_ >= 0 && mesh_.depth(f) >= held_depth_) ++stats_.splits_held;
      continue;
    }
    // Where the bound is off (a topology monitor), a folded face (fold_repair.h) is not split:
    // it reads high for its fold, not its size, and its split vertex, projected from a midpoint
    // on the wrong side of F, lands up to 4 edges away (SurfaceProbe::project_split_vertex), so
    // its children are no smaller and fold too. Colin27 swept in 4 steps with the sample seed 3:
    // after a 1-face re-mesh at 3.86 mm deep, one pass made 23,693 splits (two thirds of them of
    // folded faces), to depth 236 with edges of 6-69 mm, into the triangle budget with 23,063
    // faces folded. The fold is the fold repair's and the re-mesh's (rebuild_if_folded) to mend.
    if (topology_ && folded_against_surface(mesh_, surface_, f)) {
      ++stats_.splits_refused;
      continue;
    }
    if (bound) {
      SplitLineage& l = tracker_->lineage[f.idx];
      const double error = samples_.face_error(f);
      const int depth = mesh_.depth(f);
      const bool rose = error > l.error / kStallFall, fell = error <= kStallFall * l.error;
      if (!l.held && l.pass == pass && !rose && !fell && depth - l.depth >= kStallLevels) {
        // The faces beside it span the same gap, and each pass would give them 4 bisections
        // more (the dumbbell unwatched: the 5,000-triangle budget by step 3): from now on, as
        // after an event the mesh could not follow, no face is split far below the deepest.
        l.held = 1;
        hold_splits("a face's error did not fall by half in " + std::to_string(kStallLevels) +
                    " bisections: the mesh's topology is not F's there");
      }
      if (l.held) {
        ++stats_.splits_refused;
        ++stats_.splits_held;
        continue;
      }
      if (l.pass != pass || rose || fell)
        l = {static_cast<float>(error), pass, static_cast<std::int16_t>(depth), 0};
    }
    tracker_->touched.clear();
    if (!mesh_.split(f).is_valid()) {
      ++stats_.splits_refused;  // at the mesh's depth limit
      continue;
    }
    measure(tracker_->touched);
    for (Face t : tracker_->touched) {
      if (!mesh_.is_alive(t)) continue;
      const double u = split_urgency(t, samples_.face_error(t), initial);
      if (u > 1.0) queue.push({u, t.idx, tracker_->stamp[t.idx]});
    }
  }
  stats_.splits += tracker_->vertices_created - created_before;
}

void Adapter::renumber(const Renumbering& renumbering) {
  // The mesh tells every listener: the tracker (which also moves the adapter's own per-vertex
  // arrays), the samples, the predictor and the smoothing workspace.
  mesh_.renumber(renumbering);
}

void Adapter::renumber_if_scattered() {
  if (!options_.renumber || scattered_face_share(mesh_) <= options_.renumber_scattered_share)
    return;
  Stopwatch clock;
  renumber(spatial_renumbering(mesh_));
  // Neighbours now have neighbouring ids: each turn of the rotation measures patches of them.
  samples_.group_turns_in_order();
  stats_.renumbered = true;
  stats_.seconds.renumber += clock.lap();
}

void Adapter::finish_stats() {
  stats_.triangles = mesh_.n_faces();
  stats_.vertices = mesh_.n_vertices();
  const SampleStore::Summary s = samples_.summary(mesh_);
  stats_.max_error = s.max_error;
  stats_.mean_error = s.mean_error;
  stats_.samples = s.samples;
  stats_.vertices_kept = 0;
  if (step_ > 0) {
    // Survivors: alive now and born before this step, so alive at its start (an id freed by
    // a weld and reused by a split this step carries this step's birth). Counted and measured
    // in one sweep over the vertices.
    // The distances in parallel, summed in vertex order (the mean's last bits are the serial
    // sum's, whatever the thread count).
    const auto n = static_cast<std::int64_t>(mesh_.vertex_capacity());
    std::vector<double>& moved = survivor_displacement_;
    moved.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::int64_t i = 0; i < n; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      moved[static_cast<std::size_t>(i)] =
          mesh_.is_alive(v) && tracker_->birth_step[v.idx] < step_
              ? (mesh_.position(v) - start_positions_[v.idx]).norm()
              : -1.0;
    }
    std::size_t kept = 0;
    double sum = 0, worst = 0;
    for (const double d : moved) {
      if (d < 0) continue;  // not a survivor (a distance is >= 0, or NaN)
      ++kept;
      sum += d;
      worst = std::max(worst, d);
    }
    stats_.vertices_kept = kept;
    stats_.kept_fraction = vertices_at_start_
                               ? static_cast<double>(kept) / static_cast<double>(vertices_at_start_)
                               : 1.0;
    stats_.survivor_displacement_mean = kept ? sum / static_cast<double>(kept) : 0.0;
    stats_.survivor_displacement_max = worst;
  }
  stats_.held_depth = held_depth_;
  stats_.projection_failures = tracker_->projection_failures;
  tracker_->projection_failures = 0;
  const PhaseSeconds& p = stats_.seconds;
  stats_.seconds.total = p.project + p.smooth + p.sample + p.weld + p.split + p.renumber;
}

MeshSnapshot Adapter::snapshot(const SnapshotFields& fields) const {
  const std::size_t n = mesh_.vertex_capacity();
  std::vector<Vec3> normals(n, Vec3::UnitZ());
  std::vector<ScalarField> scalars;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 1024) if (count > kParallelMin)
  for (std::int64_t i = 0; i < count; ++i) {
    const Vertex v(static_cast<std::uint32_t>(i));
    if (mesh_.is_alive(v)) normals[static_cast<std::size_t>(i)] = probe_.normal_at(mesh_, v);
  }
  if (fields.error) {
    // Mean of the incident faces' errors: interpolated over the faces it shows the error's
    // distribution (the paper's yellow-green-red pictures) rather than every vertex at its
    // worst neighbour.
    ScalarField error{"error", std::vector<float>(n, 0.0f)};
    std::vector<std::uint16_t> faces_seen(n, 0);
    for (Face f : mesh_.live_faces())
      for (Vertex v : mesh_.vertices(f)) {
        error.values[v.idx] += static_cast<float>(samples_.face_error(f));
        ++faces_seen[v.idx];
      }
    for (std::size_t i = 0; i < n; ++i)
      if (faces_seen[i]) error.values[i] /= faces_seen[i];
    scalars.push_back(std::move(error));
  }
  if (fields.curvature) {
    ScalarField curvature{"curvature", std::vector<float>(n, 0.0f)};
    const auto* par = dynamic_cast<const ParametricSurface*>(&surface_);
    const auto* imp = dynamic_cast<const ImplicitSurface*>(&surface_);
#pragma omp parallel for schedule(dynamic, 1024) if (count > kParallelMin)
    for (std::int64_t i = 0; i < count; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      if (!mesh_.is_alive(v)) continue;
      const PrincipalCurvatures k =
          par ? par->curvatures(mesh_.uv(v)) : imp->curvatures(mesh_.position(v));
      curvature.values[static_cast<std::size_t>(i)] =
          static_cast<float>(std::max(std::abs(k.k1), std::abs(k.k2)));
    }
    scalars.push_back(std::move(curvature));
  }
  if (fields.valence || fields.level) {
    ScalarField valence{"valence", std::vector<float>(n, 0.0f)};
    ScalarField level{"level", std::vector<float>(n, 0.0f)};
    for (Vertex v : mesh_.live_vertices()) {
      valence.values[v.idx] = static_cast<float>(mesh_.valence(v));
      level.values[v.idx] = static_cast<float>(mesh_.level(v));
    }
    if (fields.valence) scalars.push_back(std::move(valence));
    if (fields.level) scalars.push_back(std::move(level));
  }
  for (const std::string& name : fields.quantities) {
    ScalarField q{name, std::vector<float>(n, 0.0f)};
#pragma omp parallel for schedule(dynamic, 1024) if (count > kParallelMin)
    for (std::int64_t i = 0; i < count; ++i) {
      const Vertex v(static_cast<std::uint32_t>(i));
      if (mesh_.is_alive(v))
        q.values[static_cast<std::size_t>(i)] =
            static_cast<float>(surface_.point_quantity(name, mesh_.position(v)));
    }
    scalars.push_back(std::move(q));
  }
  MeshSnapshot snap = make_snapshot(mesh_, &normals, scalars);
  snap.volume = surface_.volume_image();
  snap.time = surface_.time();
  snap.step = step_;
  return snap;
}

}  // namespace dynamesh
