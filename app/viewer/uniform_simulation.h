// A stand-in Simulation until the adapter is plugged in: the scene's base mesh refined
// uniformly to a fixed triangle count, its vertices brought onto S(t) every step. No
// adaptation, but real scenes, real deformation and real per-vertex fields (error at face
// centroids, mean curvature, valence, level), so the viewer can be exercised end to end.
#pragma once

#include <memory>

#include "app/viewer/simulation.h"
#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

class UniformSimulation : public Simulation {
 public:
  explicit UniformSimulation(std::size_t target_triangles = 8000)
      : target_triangles_(target_triangles) {}
  StepResult step(const StepRequest& request) override;
  std::string description() const override { return "demo: uniform refinement, no adaptation"; }

 private:
  void rebuild(const SimulationControls& controls);
  void move_onto_surface();
  std::vector<ScalarField> fields() const;

  std::size_t target_triangles_;
  std::unique_ptr<Surface> surface_;
  Mesh48 mesh_;
  SimulationControls built_for_;
};

}  // namespace dynamesh
