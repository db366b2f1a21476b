// The one place that decides which Simulation the viewer runs. When the adapter lands,
// return it here (keeping UniformSimulation for a "no adaptation" comparison if wanted).
#include "app/viewer/simulation.h"
#include "app/viewer/uniform_simulation.h"

namespace dynamesh {

std::unique_ptr<Simulation> make_simulation() {
  return std::make_unique<UniformSimulation>();
}

}  // namespace dynamesh
