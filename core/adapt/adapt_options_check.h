// The limits a user's adaptation options must respect, in one place for every program that
// takes them from a user: dynamesh-cli run, the viewer's command line and its saved state.
// Each program wrote these checks itself (the same rules twice, and the triangle budget's floor
// differed: 2 for the CLI, 8 for the viewer).
#pragma once

#include <string>

#include "core/adapt/adapt_options.h"

namespace dynamesh {

// The most smoothing iterations a step may be asked for (Equation 1 applied this many times).
inline constexpr int kMaxSmoothIterations = 1000;
// The most steps a run (dynamesh-cli run --steps, the viewer's --steps and --frames) may be
// asked for: large enough for any real use, small enough that nothing wraps or runs for days.
inline constexpr int kMaxSteps = 10'000'000;
// The smallest triangle budget (AdaptOptions::max_triangles) a user may set.
inline constexpr int kMinTriangleBudget = 2;

// The first option outside its own range, as one line naming it by the command-line option both
// programs share ("--density must be positive (samples per unit area)"); empty when none is.
// Each field alone: the hysteresis against the threshold (eps < T) is the caller's to check,
// since only it knows where T came from (the CLI takes a scene's suggested T after loading it).
std::string adapt_option_problem(const AdaptOptions& options);

}  // namespace dynamesh
