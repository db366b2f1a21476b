// Test affordance (issue 12): where the panel's named widgets are and what the viewer shows,
// so a test can move the sliders with a real mouse and keyboard (xdotool under Xvfb) without
// hard-coded pixels, and see what they did. Written only when the environment names a file:
// DYNAMESH_WIDGET_REPORT=FILE (viewer_app.cpp); one "key value..." line each:
//   widget LABEL X0 Y0 X1 Y1   a widget's rectangle in window pixels (spaces in LABEL: '_')
//   active LABEL               the widget being dragged or typed into, if any
//   threshold T, epsilon E, density D, k K   the controls as the panel holds them
//   results N, busy 0|1        results taken so far; whether a step is being computed
//   step S, triangles N, mean_aspect A   the mesh on screen (A: mean R / 2r, measured here)
//   samples N, mean_error E    the adapter's sample count and mean sampled error then
//   probe X Y Z, probe_voxel I J K, probe_intensity V, probe_depth D, probe_region N NAME
//                              the probed point (a click on the layer or in a slice) and
//                              what the scan says there (volume_probe.h)
//   frames N                   frames drawn so far (they go on while a scan loads)
//   progress STAGE P%          while a scan loads: what the panel shows
//   scene NAME, scene_text KEY VALUE   the scene on screen and its text options (volume)
//   error MESSAGE              the last request failed (red, under the scene)
//   open_error MESSAGE         the last scan opened could not be read (red, under the scene)
//   bounds X0 Y0 Z0 X1 Y1 Z1   the mesh's bounding box
//   widget slice_i|slice_j|slice_k X0 Y0 X1 Y1   the slice images normal to voxel axis i, j,
//                              k (slice_panel.h): across the first other axis (voxel -1/2 at
//                              X0, dims - 1/2 at X1), up the second (-1/2 at Y1)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/viewer/simulation.h"
#include "app/viewer/volume_probe.h"
#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

struct WidgetRect {
  std::string label;
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool active = false;  // being dragged or typed into
};

struct ShownState {
  std::uint64_t results = 0;
  bool busy = false;
  const MeshSnapshot* mesh = nullptr;  // null before the first mesh
  std::size_t samples = 0;             // the last step's
  double mean_error = 0.0;
  const VolumeProbe* probe = nullptr;  // null: nothing probed
  std::uint64_t frames = 0;            // frames drawn so far
  std::string progress;                // loading a scan: stage and percentage
  std::string scene;                   // the scene on screen and its text options
  const TextOptions* scene_text = nullptr;
  std::string error;       // the last request failed: the red message under the scene
  std::string open_error;  // the last scan opened could not be read: its red message
};

std::string widget_report(const std::vector<WidgetRect>& widgets,
                          const SimulationControls& controls, const ShownState& shown);

// Mean aspect ratio R / (2 r) over the snapshot's triangles (0 when it has none).
double mean_aspect_ratio(const MeshSnapshot& mesh);

}  // namespace dynamesh
