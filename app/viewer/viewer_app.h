// The viewer: one window, one ViewerState, the renderer, and a SimulationDriver whose worker
// thread produces snapshots. run() is the frame loop; a scripted run (--frames N
// --screenshot FILE) plays N steps, writes the window to FILE and returns.
#pragma once

#include <memory>

#include "app/viewer/viewer_args.h"

namespace dynamesh {

// Returns the process exit status.
int run_viewer(const ViewerArgs& args);

}  // namespace dynamesh
