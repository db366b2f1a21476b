// Adapter: keeps a 4-8 mesh adapted to a deforming surface S(t) (de Goes et al. 2006).
// Each step, in this order (DESIGN.md): normal correction (vertices onto S(t)), tangential
// correction (Equation 1), sampling (every sample's error), welds of every vertex whose
// post-weld error is below T (criteria.h; smallest first, cascading), then splits of every edge
// whose diamond's error is above T + eps (largest first). The mesh at the end of a step is
// the one that was measured.
//
// Geometric correction repairs what the deformation since the previous step did: when S(t)
// has not changed (same time, same parameters), both corrections are skipped, so a static
// surface is a fixed point of step() — no drift, no flicker.
//
// The adapter owns the mesh and its samples; the outside world reads it through mesh(),
// stats() and snapshot() and steers it through set_options() and step().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/adapt/adapt_options.h"
#include "core/adapt/angle_pretest.h"
#include "core/adapt/criteria.h"
#include "core/adapt/error_predictor.h"
#include "core/adapt/mesh_snapshot.h"
#include "core/adapt/sample_store.h"
#include "core/adapt/step_stats.h"
#include "core/adapt/surface_probe.h"
#include "core/mesh/mesh48.h"
#include "core/parallel.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct MeshTopologySummary;  // core/topology/topology_events.h

class TopologyMonitor;
struct TopologyCheck;

// Per-vertex fields a snapshot can carry (each costs time; curvature the most).
struct SnapshotFields {
  bool error = true;       // mean sampled error of the incident faces
  bool curvature = false;  // largest |principal curvature| of S at the vertex
  bool valence = false;
  bool level = false;
  // Surface point quantities by name (Surface::point_quantities(), e.g. "intensity").
  std::vector<std::string> quantities;
};

class Adapter {
 public:
  // `surface` must outlive the adapter; the adapter sets its time.
  Adapter(Surface& surface, const AdaptOptions& options, CriterionList criteria);
  ~Adapter();
  Adapter(const Adapter&) = delete;
  Adapter& operator=(const Adapter&) = delete;

  // Base mesh at the surface's current time, refined until within tolerance, relaxed
  // (AdaptOptions::initial_relaxation_rounds) and settled: step 0, a fixed point of step()
  // at the same time.
  const StepStats& initialize();
  // One step to time t.
  const StepStats& step(double t);

  // Takes effect at the next step (a new density redraws patterns as needed).
  void set_options(const AdaptOptions& options, CriterionList criteria);
  const AdaptOptions& options() const { return options_; }

  const Mesh48& mesh() const { return mesh_; }
  const SampleStore& samples() const { return samples_; }
  // Bounds of the faces predictive sampling did not measure this step.
  const ErrorPredictor& predictor() const { return predictor_; }
  const Surface& surface() const { return surface_; }
  const StepStats& stats() const { return stats_; }
  MeshSnapshot snapshot(const SnapshotFields& fields = {}) const;

  // Renumbers the mesh's elements (Mesh48::renumber); everything the adapter keeps per
  // element follows. Between steps; the automatic renumbering (AdaptOptions::renumber) uses
  // spatial_renumbering.
  void renumber(const Renumbering& renumbering);

 private:
  class Tracker;

  // One sub-step to time t: the paper's step (correction, repair, sampling, welds, splits).
  // `rest_points_fresh`: plan_substeps() recorded the rest points at this sub-step's start.
  // Returns whether the surface had changed (and the vertices were corrected).
  const StepStats& initialize_here();
  bool advance(double t, bool rest_points_fresh);
  // Sub-steps needed from `from` to `to` (motion_substeps.h); leaves the surface at `from`.
  // Sets `rest_points_planned` when it recorded the rest points (at `from`), so that the
  // first sub-step does not record them again (a whole evaluation pass over the vertices).
  int plan_substeps(double from, double to, bool& rest_points_planned);
  // After plan_substeps() chose one sub-step: its evaluations at the step's end time are the
  // normal correction's first Newton iterates (projection_starts_).
  bool starts_planned_ = false;
  // plan_substeps() found the step small enough to skip the screen after correction
  // (FoldRepairOptions::prescreen_above_strain).
  bool small_motion_ = false;
  void repair(const FoldRepairOptions& options);
  // Checks the frame about to be published for folds and slivers; repairs and re-measures.
  void publish_repaired();
  void normal_correction();
  void tangential_correction();
  void sampling();
  // Measures the faces' samples (and, with predictive sampling, records what they were
  // measured against).
  void measure(const std::vector<Face>& faces);
  void weld_pass();
  // Measures the skipped faces of weld_candidates_' ambiguous stars, all at once, and
  // decides their keys (weld_pass).
  template <class Key>
  void decide_ambiguous_stars(Key&& weld_key);
  void split_pass(bool initial);
  // Weld and split passes at the current surface until neither changes the mesh (a few
  // rounds): the settled state initialize() publishes, a fixed point of step() on a static
  // surface.
  void settle();
  // The first mesh, relaxed as a motion would (AdaptOptions::initial_relaxation_rounds).
  void relax();
  // Largest urgency of the applicable criteria if f's error were `error`.
  double split_urgency(Face f, double error, bool initial) const;
  // An error at or below which split_urgency is at most 1 for every face (the criteria's
  // Criterion::split_error_floor): faces reading no more are not asked about.
  double split_error_floor(bool initial) const;
  // `error`: the post-weld error; `current`: the star's error now.
  bool weld_allowed(const DiamondChange& plan, double error, double current) const;
  // The range the star's current error lies in: exact unless some of its faces were not
  // measured this step (predictive sampling), then widened by their reading ranges
  // (ErrorPredictor::reading_range).
  struct ErrorRange {
    double lo, hi;
  };
  ErrorRange star_error_range(const DiamondChange& plan) const;
  // Appends the star's faces that were skipped this step (their error only known within a
  // bound) to `out`.
  void append_skipped_faces(const DiamondChange& plan, std::vector<Face>& out) const;
  // Measures them, so that star_error_range becomes exact.
  void measure_star(const DiamondChange& plan);
  // The largest post-weld error any applicable criterion could allow for a star whose error
  // is now `current` (pruning bound).
  double weld_ceiling(const DiamondChange& plan, double current) const;
  bool pathological(Face f) const;
  bool split_refused(Face f) const;
  bool pathological_star(const DiamondChange& plan) const;
  AngleCosines star_angle_cosines_;  // pathological_star's pre-test, set by weld_pass()
  void finish_stats();
  // AdaptOptions::renumber: along a Morton curve when the numbering has scattered.
  void renumber_if_scattered();
  void record_rest_points();
  // Topology change (issue 16, topology_events.h): starts watching F when the surface may
  // change topology; each step, reports F's events and, when the mesh's topology no longer
  // matches F's, repairs it locally around each event (local_repair.h) or, when that fails,
  // rebuilds the mesh from F's contour (a global re-base: no vertex survives it).
  void watch_topology();
  void check_topology();
  // The monitor's critical points near F = 0, where the error is measured by Newton's method
  // (SurfaceProbe::set_singular_points).
  void note_singular_points();
  // True when the local repairs leave the mesh with F's topology (TopologyCheck); why not is
  // added to the step's repair_refusals.
  bool repair_topology_locally(const TopologyCheck& check);
  // After a local repair: the stores follow the mesh's surgery; `born` are its new vertices.
  void adopt_repair(const std::vector<Vertex>& born);
  // After the geometric correction and its fold repair: rebuilds when faces are still turned
  // over (next to an event the neck moves fast and the coarse rebuilt mesh folds). Returns
  // whether the mesh was changed (re-meshed, rebuilt, or patches made and undone).
  bool rebuild_if_folded();
  // Before a frame is published: the split vertices the fold guard kept off F this step are
  // projected onto it (the guard off), and the faces around them measured and refined; the
  // fold repair before publishing follows.
  void place_guarded_vertices();
  void forget_guarded_vertices();
  // After publish_repaired: faces it left folded are re-meshed (rebuild_if_folded) and the
  // frame screened again.
  void remesh_published_folds();
  // The faces left folded re-meshed by F's contour around them, when they lie together; true
  // when the mesh then has `topology` and no folded face (else the caller re-bases; the mesh
  // may have been changed: `changed` says so).
  bool remesh_folds_locally(const MeshTopologySummary& topology, bool& changed);
  // At the end of a step with local repairs: re-bases when the faces near them cross the mesh.
  void rebuild_if_crossed();
  // A global re-base to a mesh of Euler characteristic `euler` and `components` components
  // (0: not known, Morse theory gives only the characteristic). Throws std::invalid_argument
  // when no base mesh with that topology can be placed on the surface now (the run stops
  // with that reason rather than refine a wrong mesh without end).
  void rebuild_from_base(long euler, long components);
  // rebuild_from_base, except on a surface with fixed critical points (mri), whose layers no
  // coarse contour resolves: the mesh then keeps its topology, as it did before events were
  // watched, with the reason among the step's repair_refusals. True when it was rebuilt.
  bool rebuild_or_keep(long euler, long components);
  // From now on no face deeper than 4 bisections below the deepest is split: after an event
  // neither repaired nor rebuilt, or (`stalled`: why) a face whose error did not fall
  // (split_pass).
  void hold_splits(const std::string& stalled = {});
  Mesh48 mid_run_base_mesh(long euler, long components);
  // True when the surface's time or parameters differ from the previous step's.
  bool surface_changed();

  Surface& surface_;
  SurfaceProbe probe_;
  AdaptOptions options_;
  CriterionList criteria_;
  Mesh48 mesh_;
  SampleStore samples_;
  ErrorPredictor predictor_;
  std::vector<Face> to_measure_;  // sampling()'s list, reused step to step
  // weld_pass()'s candidates in vertex order: a weld key (weld_pass), or ambiguous (the key
  // its post-weld error), reused step to step.
  struct WeldCandidate {
    double key = 0.0;
    std::uint32_t vertex = 0;
    bool ambiguous = false;
  };
  OrderedCollector<WeldCandidate> weld_collector_;
  std::vector<WeldCandidate> weld_candidates_;
  std::vector<Face> star_skipped_;  // measure_star()'s list, reused star to star
  // weld_pass()'s ambiguous candidates: each one's index in weld_candidates_, its weld's plan
  // and where its star's skipped faces begin in ambiguous_faces_, whose sample counts before
  // they were measured are in ambiguous_counts_ (decide_ambiguous_stars). Reused step to step.
  struct AmbiguousStar {
    std::uint32_t candidate = 0, first_face = 0;
    DiamondChange plan;
  };
  std::vector<AmbiguousStar> ambiguous_stars_;
  std::vector<Face> ambiguous_faces_;
  std::vector<std::uint32_t> ambiguous_counts_;
  // split_pass()'s faces with an urgency above 1 (and it), in face order, reused pass to pass.
  OrderedCollector<std::pair<double, Face>> urgent_collector_;
  std::vector<std::pair<double, Face>> urgent_;
  // finish_stats()'s per-vertex survivor displacements (-1: not a survivor), reused.
  std::vector<double> survivor_displacement_;
  std::unique_ptr<Tracker> tracker_;
  SmoothingWorkspace smoothing_workspace_;  // reused by every step's tangential correction
  StepStats stats_;
  std::uint64_t step_ = 0;
  // Numbers the surface states a step goes through (one per advance), so that F and grad F
  // evaluated where a vertex landed are reused only in the same state (ErrorPredictor::note).
  std::uint64_t surface_epoch_ = 0;
  std::uint32_t splits_since_clock_ = 0;  // the deadline is checked every 64 splits
  double last_time_ = 0.0;
  std::vector<double> last_parameters_;
  // Positions at the start of the current step (temporal coherence); reused step to step.
  std::vector<Vec3> start_positions_;
  // Rest-space points of the vertices before the surface's time changed (surfaces with a
  // rest map: SurfaceProbe::follows_material); reused step to step.
  std::vector<Vec3> rest_points_;
  // This sub-step's vertices were carried from rest_points_ (normal_correction). A flag, not
  // derived from rest_points_: relax() smooths without a carry, where they would be stale.
  bool carried_from_rest_ = false;
  // Where each vertex's material point went this step, before the projection and smoothing
  // moved it on (predictive sampling on a surface with a rest map: ErrorPredictor's slide);
  // valid when carried_valid_.
  std::vector<Vec3> carried_;
  bool carried_valid_ = false;
  std::size_t vertices_at_start_ = 0;
  std::vector<Vec3> displacement_;                  // predicted motion per vertex (plan_substeps)
  std::vector<ProjectionStart> projection_starts_;  // and where its Newton step started
  // Split vertices the fold guard kept off F this step, and per face slot whether a face is
  // held for one (Tracker::after_split, place_guarded_vertices).
  std::vector<Vertex> guarded_vertices_;
  std::vector<std::uint8_t> guard_held_;
  std::vector<Vec3> repair_centres_;  // of this step's local repairs (rebuild_if_crossed)
  int held_depth_ = -1;               // no split beyond it (hold_splits); -1: none
  std::uint32_t split_pass_id_ = 0;   // numbers the split passes (split_pass's lineages)
  std::vector<Face> bad_faces_[2];    // folded faces and slivers (publish_repaired)
  FoldScreenBuffers fold_screen_;     // the fold screen's scratch, kept (fold_repair.h)
  std::unique_ptr<TopologyMonitor> topology_;
};

}  // namespace dynamesh
