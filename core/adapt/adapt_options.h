// Options of the adaptation (de Goes et al. 2006, Section 3; defaults from DESIGN.md).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

#include "core/adapt/motion_substeps.h"
#include "core/geometry/fold_repair.h"
#include "core/geometry/tangential_smoothing.h"

namespace dynamesh {

// The original implementation's guard against pathological triangles (DESIGN.md, "The 4-8
// mesh"): a triangle with an angle below min_deg or above max_deg is pathological.
// weld_first: a weldable vertex with such a triangle in its star is welded before any other,
// even above T, as long as the weld keeps the error within T + eps (so the split pass has
// no reason to undo it). refuse_splits: an edge whose diamond holds one is not split
// (bisecting a sliver makes thinner slivers) -- off by default, because it leaves faces above
// T + eps (measured 1.36 (T + eps) on capsule-bend; test_smoothing_angle_guard.cpp).
struct AngleGuard {
  bool refuse_splits = false;
  bool weld_first = true;
  double min_deg = 10.0;
  double max_deg = 160.0;
};

// Which faces a step measures: those whose error could have left the range where no decision
// depends on it (error_predictor.h), or every face (the reference).
enum class Sampling { kPredictive, kFull };

struct AdaptOptions {
  double threshold = 0.008;  // T: target geometric error (scene units)
  double epsilon = 0.002;    // eps: hysteresis; split above T + eps, weld below T (criteria.h)
  double density = 2000.0;   // D: samples per unit area (at least one per triangle)
  std::uint64_t seed = 1;    // sample jitter; runs with the same seed are identical
  std::size_t max_triangles = 2'000'000;  // refinement stops at this budget (reported)
  // Budgets against hostile input (issue 15), reported like the triangle budget: refinement
  // stops when the sample pool holds more than max_samples (12 bytes each; a face holds up to
  // 256, so a huge density would otherwise fill memory long before max_triangles), or when
  // the wall clock passes `deadline`.
  std::size_t max_samples = 50'000'000;
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  bool structural = true;  // split and weld
  bool geometric = true;   // normal and tangential correction
  Sampling sampling = Sampling::kPredictive;
  // Watch F for merges, splits and pinches and rebuild the mesh when its topology no longer
  // matches (surfaces that say they may change topology; core/topology/topology_events.h).
  bool topology_events = true;
  // Repair an event locally (core/topology/local_repair.h) before falling back to rebuilding
  // the whole mesh; false always rebuilds (the benchmark's baseline).
  bool local_topology_repair = true;
  // Rebuild a distance field's layer from F's contour (a global re-base) when its event cannot
  // be repaired locally and a contour has the topology it must take; false keeps the mesh
  // (tests: the path where neither is possible, which holds the splits: Adapter::hold_splits).
  bool topology_rebase = true;
  // When an event is neither repaired nor rebuilt, hold the splits (Adapter::hold_splits) so
  // that the refinement ends; false lets it run (tests: a failed repair's own footprint).
  bool hold_splits_when_unrepaired = true;
  // Hold, without any event, the splits of a face whose error has not fallen by half in 4
  // bisections within one split pass (a smooth surface's falls to 1/16): where the mesh's
  // topology is not F's and no monitor says so (events off, or a surface that does not say it
  // may change topology) the refinement would not end (Adapter::split_pass). Then, as after an
  // event the mesh could not follow, no face is split more than 4 bisections below the
  // deepest (held_depth, splits_held).
  bool hold_stalled_splits = true;
  SmoothingOptions smoothing;
  // Rounds of smoothing, measurement and settling (welds and splits until quiet) at the
  // initial time, after the first refinement (Adapter::relax): refined from the base mesh's
  // edge midpoints, the first mesh has never been smoothed, and a motion's smoothing moves
  // vertices onto the curvature, where fewer triangles meet the bound; without these rounds
  // the twisted bar came back from every sweep 15% coarser than it started (0.84, 0.82, 0.87
  // over three cycles; with 20 rounds 1.02, 0.99, 0.96; test_motion_frames.cpp). 0: none.
  int initial_relaxation_rounds = 20;
  AngleGuard angle_guard;
  // Every frame embedded and well shaped, whatever the step size (DESIGN.md, "Quality bars"):
  // steps that move the surface far against the mesh are cut into sub-steps, and folds and
  // slivers left by the motion are relaxed away before the frame is published.
  SubstepOptions substeps;
  FoldRepairOptions fold_repair;
  // Memory locality (core/mesh/spatial_order.h): at the end of initialize() and of a step,
  // when more than renumber_scattered_share of the faces have corners further apart in the
  // vertex arrays than kLocalityWindow (splits append new vertices far from their parents),
  // the mesh is renumbered along a Morton curve. Results are those of an unrenumbered run up
  // to rounding (sums over a vertex's faces are taken in another order).
  bool renumber = true;
  double renumber_scattered_share = 0.15;
};

}  // namespace dynamesh
