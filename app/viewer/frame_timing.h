// Frame timing of the viewer's loop, for scripted measurements (--run-for, --frame-log):
// per frame, the work the UI thread did (hand-off of a new snapshot, panel, drawing, swap)
// and whether a new step appeared. Waiting for events is not work and not counted.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dynamesh {

struct FrameSample {
  double at_ms = 0.0;       // since the loop started
  double work_ms = 0.0;     // whole frame: hand-off + UI + draw + swap
  double handoff_ms = 0.0;  // taking a new snapshot: GPU upload, colour field statistics
  double draw_ms = 0.0;     // 3D view + panel + swap (software GL renders here)
  bool new_step = false;    // a new step's mesh was shown
  std::size_t triangles = 0;
};

struct FrameSummary {
  std::size_t frames = 0, new_steps = 0;
  double seconds = 0.0, fps = 0.0;
  double work_median_ms = 0.0, work_p95_ms = 0.0, work_max_ms = 0.0;
  double handoff_max_ms = 0.0;
  double draw_median_ms = 0.0;
  // Frames without a new step: their cost is the renderer's alone.
  double quiet_work_max_ms = 0.0;
};

// Where the time to the first mesh on screen went (issue 14: a scan's first adapted frame),
// counted from the viewer's start (before its window opens) to the end of the first frame
// that shows a mesh. The worker's spans also carry the process's CPU time over them (all
// threads): on a shared machine the wall time is the load's, the CPU time the viewer's.
struct StartupTiming {
  double window_seconds = 0.0;                          // the window and its OpenGL context
  double build_seconds = 0.0, build_cpu_seconds = 0.0;  // the scene (mri: read, prepare)
  double adapt_seconds = 0.0, adapt_cpu_seconds = 0.0;  // the first adaptation
  double snapshot_seconds = 0.0;                        // its read-only copy
  double upload_ms = -1.0;                              // the first mesh to the GPU
  double first_draw_ms = 0.0;     // the first frame with the mesh (shaders compile here)
  double volume_upload_ms = 0.0;  // of which the scan's 3-D texture (uploaded when drawn)
  std::size_t frames_before = 0;  // frames before the mesh (panel, loading progress)
  double frames_before_ms = 0.0;  // and their work
  double first_mesh_seconds = 0.0, first_mesh_cpu_seconds = 0.0;
};

FrameSummary summarize(const std::vector<FrameSample>& frames, double seconds);
// One line, e.g. for the end of a scripted run.
std::string describe(const FrameSummary& s);
std::string describe(const StartupTiming& s);
// CSV with a header; throws std::runtime_error when the file cannot be written.
void write_frame_log(const std::vector<FrameSample>& frames, const std::string& path);

}  // namespace dynamesh
