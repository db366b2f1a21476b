// The verdict on a surface's workload before any mesh is built (issue 15), shared by
// dynamesh-cli and the viewer so that both refuse the same surfaces with the same reason: at
// a few times over the animation the surface must be finite, continuous (workload_estimate.h)
// and within the triangle and sample budgets at the requested T.
#pragma once

#include <string>

#include "core/surface/surface.h"

namespace dynamesh {

struct WorkloadBudget {
  double threshold = 0.008;  // T
  double density = 2000.0;   // samples per unit area
  double max_triangles = 2e6;
  double max_samples = 5e7;
  // Refuse only when the estimate exceeds this many times max_triangles: 1 for a typed
  // formula; more for a built-in scene, whose documented ranges are meant to run and whose
  // triangle budget may be a deliberate cap (the run then reports the hit).
  double hopeless = 1.0;
  // An edge-length cap L (0: none) over `edge_length_share` of the area (the sphere's x >= 0
  // half: 0.5) needs at least that area / (sqrt(3)/4 L^2) triangles, whatever T says: an
  // in-range L = 0.001 on the sphere ran for ever towards 10^9 triangles.
  double edge_length = 0.0;
  double edge_length_share = 1.0;
  bool edge_length_from_scene = false;  // the scene's parameter L, not the user's edge length
};

// How the budgets are called where the message is read (the CLI's option names, the
// viewer's control names).
struct WorkloadWords {
  std::string threshold = "--threshold";
  std::string density = "--density";
  std::string max_triangles = "--max-triangles";
  std::string max_samples = "--max-samples";
  std::string edge_length = "--edge-length";
  std::string scene_edge_length = "--param L";
};

// Sets the budget's edge-length demand as default_criteria (criteria.h) adapts `scene`: the
// sphere's x >= 0 half at `edge_length` if positive, else at its parameter L; any other scene
// everywhere at a positive `edge_length`. One rule for dynamesh-cli and the viewer.
void set_edge_length_demand(WorkloadBudget& budget, const std::string& scene,
                            const Surface& surface, double edge_length);

// Estimates the workload at `checks` evenly spaced times of [t_first, t_last] (one when they
// are equal) and returns why the surface is refused ("at t = 0.5: the surface needs ..."), or
// an empty string. Leaves the surface at t_first. With `problems` false only the budgets are
// judged: a surface that is not finite or not continuous at some time, or whose set_time
// refuses that time, is left to be found when the mesh gets there (the viewer shows the mesh
// up to that time). Otherwise throws what the surface's set_time throws
// (std::invalid_argument: its own checks at a later time).
std::string workload_refusal(Surface& surface, const WorkloadBudget& budget, double t_first,
                             double t_last, const WorkloadWords& words = {}, int checks = 5,
                             bool problems = true);

}  // namespace dynamesh
