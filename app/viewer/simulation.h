// The hand-off between the viewer and whatever produces meshes (the adapter; until it is
// plugged in, a uniformly refined demo). The viewer never touches the mesh: it sends the
// controls it wants a step run with and shows the snapshots that come back.
//
// To plug the adapter in: implement Simulation (one object owning the Surface and the
// adapter), and return it from make_simulation() in simulation_factory.cpp. step() runs on
// the driver's worker thread, one call at a time.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

// What a person can steer (DESIGN.md "Viewer"; names and defaults as the CLI's options).
struct SimulationControls {
  std::string scene = "capsule-bend";
  std::vector<std::pair<std::string, double>> scene_parameters;  // --param KEY=VALUE
  double threshold = 0.008;                                      // T
  double epsilon = 0.0008;                                       // hysteresis band half-width
  double density = 2000.0;                                       // samples per unit area
  double k = 2.0;                                                // Equation 1 stiffness
  int smooth_iterations = 1;
  double edge_length = 0.25;  // sphere scene, right half
  int max_triangles = 2000000;
  unsigned seed = 1;

  bool operator==(const SimulationControls&) const = default;
};

struct StepRequest {
  double time = 0.0;  // normalised animation time of the step
  SimulationControls controls;
  // Rebuild from the base mesh (scene or scene parameters changed, or the user asked).
  bool restart = false;
};

struct StepStatistics {
  std::size_t triangles = 0, vertices = 0;
  double max_error = 0.0, mean_error = 0.0;
  std::size_t splits = 0, welds = 0;
  double seconds = 0.0;  // wall time of the step
  bool budget_hit = false;
};

struct StepResult {
  std::shared_ptr<const MeshSnapshot> snapshot;  // never null on success
  StepStatistics stats;
  std::string error;  // non-empty: the step failed (bad parameter...), snapshot may be null
};

class Simulation {
 public:
  virtual ~Simulation() = default;
  // One time step (or, with restart, initialisation at request.time) with the given
  // controls. Must not throw: failures go in StepResult::error.
  virtual StepResult step(const StepRequest& request) = 0;
  // One line for the panel, e.g. "adapter" or "demo: uniform refinement".
  virtual std::string description() const = 0;
};

// The simulation the viewer runs (see simulation_factory.cpp).
std::unique_ptr<Simulation> make_simulation();

}  // namespace dynamesh
