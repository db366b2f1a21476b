// What one adaptation step did and cost.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/topology/topology_event.h"

namespace dynamesh {

struct PhaseSeconds {
  double project = 0, smooth = 0, sample = 0, weld = 0, split = 0, total = 0;
  double renumber = 0;  // Adapter: renumbering the mesh along a space-filling curve (in total)
};

struct StepStats {
  std::uint64_t step = 0;  // 0 is the initialisation
  double time = 0.0;       // surface time t
  std::size_t triangles = 0, vertices = 0;
  std::size_t splits = 0;  // vertices created, forced splits included
  std::size_t welds = 0;
  double max_error = 0.0, mean_error = 0.0;  // over all samples, after the step
  std::size_t samples = 0;
  // Faces whose samples the sampling phase measured (all of them with full sampling; the
  // rest kept their last error within a bound: predictive sampling, error_predictor.h),
  // summed over the sub-steps.
  std::size_t faces_measured = 0;
  std::size_t vertices_kept = 0;  // vertices alive before and after the step
  // Temporal coherence (DESIGN.md, "Quality bars"): vertices_kept over the vertices alive at
  // the start of the step (1 on a static surface; re-meshing would give 0), and how far the
  // survivors moved during the step (normal and tangential correction), in scene units.
  double kept_fraction = 0.0;
  double survivor_displacement_mean = 0.0, survivor_displacement_max = 0.0;
  // Tangential correction: vertex moves kept and undone by its guards.
  std::size_t smoothing_moved = 0, smoothing_reverted = 0;
  // ... and the curvature frames it reused rather than evaluated (tangential_smoothing.cpp,
  // frame_reusable), summed over iterations and sub-steps.
  std::size_t frames_reused = 0;
  // Predictive sampling: vertices whose F and grad F the predictor took from the projection
  // that placed them (ErrorPredictor::note) instead of evaluating again.
  std::size_t evaluations_reused = 0;
  // Angle guard (AdaptOptions::angle_guard): splits refused, pathological vertices welded.
  std::size_t splits_refused = 0, pathological_welds = 0;
  std::size_t projection_failures = 0;
  // Motion (motion_substeps.h): sub-steps taken for this step (1: none), and the largest
  // predicted edge strain |d_a - d_b| / |a - b| over the whole step.
  int substeps = 1;
  double motion_strain = 0.0;
  // Fold repair (fold_repair.h), summed over the sub-steps: faces found folded or below the
  // angle floor, vertex moves made, and what is left in the published frame.
  std::size_t folds_found = 0, slivers_found = 0, repair_moves = 0;
  std::size_t folds_left = 0, slivers_left = 0;
  bool budget_hit = false;         // refinement stopped at AdaptOptions::max_triangles
  bool sample_budget_hit = false;  // ... at AdaptOptions::max_samples
  bool time_budget_hit = false;    // ... at AdaptOptions::deadline
  // Topology (issue 16; surfaces that may change topology): events found from F during the
  // step, how many were repaired locally (local_repair.h: only faces near the event are
  // replaced), whether the mesh was instead rebuilt from F's contour (the fallback: no vertex
  // survives a rebuild), and what watching and repairing cost (seconds; also in
  // seconds.project).
  std::vector<TopologyEvent> topology_events;
  std::size_t local_repairs = 0;
  std::size_t repair_faces_replaced = 0;  // faces the local repairs cut out
  double repair_spacing = 0.0;  // the coarsest contour spacing of this step's repair patches
  std::vector<std::string> repair_refusals;  // why a local repair was not done
  // Splits refused (also counted in splits_refused) because an event was neither repaired nor
  // rebuilt: no face deeper than held_depth is split (Adapter::hold_splits); -1 when none.
  std::size_t splits_held = 0;
  int held_depth = -1;
  bool rebuilt = false;
  // The mesh's elements were renumbered along a space-filling curve at the end of the step
  // (AdaptOptions::renumber): ids are not kept across such a step (survival is counted through
  // the renumbering).
  bool renumbered = false;
  std::size_t folds_repaired = 0;  // faces the correction turned over, which made it rebuild
  std::size_t folds_remeshed = 0;  // ... which were re-meshed locally instead (no rebuild)
  double topology_seconds = 0.0;
  PhaseSeconds seconds;
};

}  // namespace dynamesh
