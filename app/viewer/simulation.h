// Simulation: the viewer's side of the engine — one Surface (a scene from the catalogue) and
// the Adapter that keeps a mesh adapted to it. The viewer never touches the mesh: it sends
// the controls and the time it wants (a StepRequest) and shows the snapshots that come back.
// step() runs on the SimulationDriver's worker thread, one call at a time.
//
// What a request does, given what was asked for the previous one:
//   - restart or another seed: a new Adapter on the surface already built, initialised at the
//     request's time;
//   - another scene or other text options (a volume file): a new surface from the catalogue
//     (make_scene), then as above;
//   - scene parameters added or changed: set on the surface already built (for `mri` this
//     avoids reading and segmenting the volume again), then as above; an override removed
//     needs the scene's default, so a new surface;
//   - other adaptation options (T, eps, density, smoothing, budget): Adapter::set_options,
//     then one step (at the same time if the time did not change): the mesh adapts to the new
//     options from where it is;
//   - another time: one Adapter::step;
//   - nothing but the snapshot fields (the colour mode changed): a new snapshot, no step.
// A request that fails (bad parameter, unreadable volume) gives an error and drops the
// adapter; the viewer keeps showing the last good snapshot. The same controls are not tried
// again until they change or a restart is asked for.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/adapt/step_stats.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {

// What a person can steer (DESIGN.md "Viewer"; names and defaults as dynamesh-cli run's).
struct SimulationControls {
  std::string scene = "capsule-bend";
  ParameterOverrides scene_parameters;  // --param KEY=VALUE, the last value of a key wins
  TextOptions scene_text;               // --volume FILE (mri)
  double threshold = 0.008;             // T
  double epsilon = 0.002;               // hysteresis half-width (the CLI's default T/4)
  double density = 2000.0;              // samples per unit area
  double k = 2.0;                       // Equation 1 curvature sensitivity
  int smooth_iterations = 1;
  // A vertex within this fraction of its ring's mean edge of its ring's centroid is left in
  // place (SmoothingOptions::settled_offset; 0, the paper's: every vertex moves).
  double smooth_settled = 0.0;
  double edge_length = 0.0;  // > 0: target edge length (sphere: its right half); 0: scene's L
  int max_triangles = 2'000'000;
  unsigned seed = 1;

  bool operator==(const SimulationControls&) const = default;
};

// The adapter's options for these controls.
AdaptOptions adapt_options(const SimulationControls& controls);

struct StepRequest {
  double time = 0.0;  // normalised animation time
  SimulationControls controls;
  bool restart = false;  // re-initialise from the base mesh at `time`
  // Per-vertex fields the snapshot carries besides the error (which it always has); surface
  // point quantities the viewer can colour by ("intensity") are added when the scene has them.
  SnapshotFields fields;
  std::uint64_t id = 0;  // echoed in the result: which request a result answers
};

// Where a request's time went (the first adapted frame of a scan: issue 14). Wall seconds,
// and the process's CPU seconds over the same span (all threads: OpenMP's team included).
struct StepTimings {
  double build_seconds = 0.0, build_cpu_seconds = 0.0;  // a new surface (mri: read, prepare)
  double adapt_seconds = 0.0, adapt_cpu_seconds = 0.0;  // initialisation or step
  double snapshot_seconds = 0.0;
};

struct StepResult {
  std::shared_ptr<const MeshSnapshot> snapshot;  // null when the request failed
  StepStats stats;                               // the adapter's last step (initialisation: step 0)
  bool stepped = false;                      // the adapter ran for this request: `stats` are new
  std::string error;                         // non-empty: the request failed
  std::string scene;                         // the scene the adapter runs on
  TextOptions scene_text;                    // and its text options (the formula of expr)
  std::vector<SurfaceParameter> parameters;  // its parameters, current values and ranges
  std::uint64_t request_id = 0;              // StepRequest::id of the request answered
  StepTimings timings;
};

class Simulation {
 public:
  // `progress` (optional, called on the worker thread) hears the stages of building a scene
  // from a file (the mri scan: reading, segmenting, distance transform).
  explicit Simulation(ProgressCallback progress = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Never throws: failures come back in StepResult::error.
  StepResult step(const StepRequest& request);

 private:
  // The surface for `controls`: the current one with new parameter values when only those
  // changed, otherwise a new one from the catalogue. Throws what make_scene throws.
  std::unique_ptr<Surface> surface_for(const SimulationControls& controls);
  void rebuild(const StepRequest& request, StepTimings& timings);
  SnapshotFields snapshot_fields(const SnapshotFields& requested) const;

  std::unique_ptr<Surface> surface_;
  std::unique_ptr<Adapter> adapter_;          // refers to *surface_
  SimulationControls built_;                  // the controls surface_ and adapter_ run with
  std::optional<SimulationControls> failed_;  // the controls of the last failure
  std::string failure_;
  ProgressCallback progress_;
};

}  // namespace dynamesh
