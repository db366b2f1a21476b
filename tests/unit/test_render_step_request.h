// A StepRequest for the viewer's Simulation, as the tests of the simulation and of the formula
// panel make them.
#pragma once

#include "app/viewer/simulation.h"

namespace dynamesh::test {

inline StepRequest at(double t, const SimulationControls& c, bool restart = false) {
  StepRequest r;
  r.time = t;
  r.controls = c;
  r.restart = restart;
  return r;
}

}  // namespace dynamesh::test
