#include "app/cli/run_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <ostream>

#include "app/cli/run_summary.h"
#include "app/offscreen/offscreen_render.h"
#include "app/render/color_mode.h"
#include "core/adapt/adapter.h"
#include "core/io/atomic_file.h"
#include "core/io/mesh_export.h"
#include "core/io/stats_csv.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

// Long loads (the mri volume: reading, segmenting, distance transform) report progress.
ProgressCallback progress_printer(const RunOptions& o, std::ostream& log) {
  if (o.quiet) return {};
  return [&log, last = std::string()](std::string_view stage, double fraction) mutable {
    const int percent = static_cast<int>(100 * fraction);
    const std::string line = std::string(stage) + " " + std::to_string(percent) + "%";
    if (line == last || (percent % 25 != 0 && percent != 99)) return;
    last = line;
    log << "loading: " << line << "\n";
  };
}

std::unique_ptr<Surface> build_scene(RunOptions& o, std::ostream& log) {
  try {
    const SceneInfo* info = nullptr;
    const std::vector<SceneInfo> scenes = list_scenes();
    for (const SceneInfo& s : scenes)
      if (s.name == o.scene) info = &s;
    std::unique_ptr<Surface> surface =
        make_scene(o.scene, o.params, o.scene_text, progress_printer(o, log));
    apply_scene_defaults(o, *info);  // make_scene has rejected an unknown name
    return surface;
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// Fails early, before any work, when an output cannot be written.
void check_outputs(const RunOptions& o) {
  if (!o.export_final_path.empty()) {
    const std::string ext = fs::path(o.export_final_path).extension().string();
    if (ext != ".ply" && ext != ".obj")
      throw UsageError("--export-final " + o.export_final_path + ": use a .ply or .obj file name");
    try {
      AtomicFile probe(o.export_final_path);  // removed again, unless committed
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--export-final: ") + e.what());
    }
  }
  for (const std::string* dir : {&o.export_dir, &o.render_dir}) {
    if (dir->empty()) continue;
    std::error_code ec;
    fs::create_directories(*dir, ec);
    if (ec || !fs::is_directory(*dir))
      throw UsageError("cannot create directory " + *dir + ": " + ec.message());
  }
}

CriterionList criteria_for(const RunOptions& o, const Surface& surface) {
  double scene_edge_length = 0.0;
  for (const SurfaceParameter& p : surface.parameters())
    if (p.name == "L") scene_edge_length = p.value;
  return default_criteria(o.scene, scene_edge_length, o.adapt, o.edge_length);
}

void log_step(std::ostream& log, const StepStats& s, int steps) {
  log << "step " << std::setw(4) << s.step << "/" << steps << "  t=" << std::fixed
      << std::setprecision(3) << s.time << "  triangles=" << s.triangles << "  +" << s.splits
      << " -" << s.welds << "  max_err=" << std::scientific << std::setprecision(2) << s.max_error
      << "  " << std::fixed << std::setprecision(1) << 1e3 * s.seconds.total << " ms"
      << (s.budget_hit ? "  (triangle budget hit)" : "") << "\n";
  log.unsetf(std::ios::floatfield);
}

// Topology events (issue 16) on stderr whatever --quiet says: they change what the run means.
void log_topology(std::ostream& log, const StepStats& s) {
  for (const TopologyEvent& e : s.topology_events)
    log << "topology: " << to_string(e.kind) << " at t=" << std::fixed << std::setprecision(4)
        << e.time << " near (" << std::setprecision(3) << e.position.x() << ", "
        << e.position.y() << ", " << e.position.z() << ")\n";
  if (s.rebuilt)
    log << "topology: mesh rebuilt from F's contour at step " << s.step << " (t=" << std::fixed
        << std::setprecision(4) << s.time << "; no vertex survives a rebuild)\n";
  log.unsetf(std::ios::floatfield);
}

// What a snapshot must carry for the chosen colour mode.
SnapshotFields fields_for(const RunOptions& o, const Surface& surface) {
  SnapshotFields f;
  f.curvature = o.color == "curvature";
  f.valence = o.color == "valence";
  f.level = o.color == "level";
  if (o.color == "intensity") {
    const auto q = surface.point_quantities();
    if (std::find(q.begin(), q.end(), "intensity") == q.end())
      throw UsageError("--color intensity needs a scene with MR intensity (--scene mri)");
    f.quantities = {"intensity"};
  }
  return f;
}

// Offscreen frames (--render): one renderer for the whole run, so that only what changed
// goes to the GPU and the camera fitted to the first frame stays put while the mesh moves.
class FrameRenderer {
 public:
  FrameRenderer(const RunOptions& o, double threshold) : dir_(o.render_dir) {
    options_.width = o.width;
    options_.height = o.height;
    options_.style.mode = *parse_color_mode(o.color);
    options_.style.colors.threshold = static_cast<float>(threshold);
  }
  void render(const MeshSnapshot& snap, std::uint64_t step);
  int frames() const { return frames_; }

 private:
  std::string dir_;
  OffscreenOptions options_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  int frames_ = 0;
};

std::string frame_name(const std::string& dir, std::uint64_t step, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05llu.%s", static_cast<unsigned long long>(step), ext);
  return (fs::path(dir) / name).string();
}

void FrameRenderer::render(const MeshSnapshot& snap, std::uint64_t step) {
  if (!renderer_) renderer_ = std::make_unique<OffscreenRenderer>();
  renderer_->render_to_png(snap, options_, frame_name(dir_, step, "png"));
  ++frames_;
}

}  // namespace

int run_command(const RunOptions& options, std::ostream& out, std::ostream& log) {
  RunOptions o = options;
  if (o.t0 < 0 || o.t0 > 1 || o.t1 < 0 || o.t1 > 1)
    throw UsageError("--t0 and --t1 must lie in [0, 1] (normalised animation time)");
  std::unique_ptr<Surface> surface = build_scene(o, log);
  check_outputs(o);
  std::unique_ptr<StatsCsvWriter> csv;
  if (!o.stats_path.empty()) {
    try {
      csv = std::make_unique<StatsCsvWriter>(o.stats_path);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--stats: ") + e.what());
    }
  }

  const SnapshotFields fields = fields_for(o, *surface);
  std::unique_ptr<FrameRenderer> frames;
  if (!o.render_dir.empty()) frames = std::make_unique<FrameRenderer>(o, o.adapt.threshold);
  surface->set_time(o.t0);
  Adapter adapter(*surface, o.adapt, criteria_for(o, *surface));
  RunSummary summary;
  summary.scene = o.scene;
  summary.steps = o.steps;
  std::vector<double> step_seconds;
  auto record = [&](const StepStats& s) {
    summary.total_splits += s.splits;
    summary.total_welds += s.welds;
    summary.budget_hit = summary.budget_hit || s.budget_hit;
    summary.topology_events.insert(summary.topology_events.end(), s.topology_events.begin(),
                                   s.topology_events.end());
    summary.rebuilds += s.rebuilt;
    log_topology(log, s);
    if (csv) csv->write(s, summary.total_splits, summary.total_welds);
    if (!o.quiet) log_step(log, s, o.steps);
    if (o.check) {
      const CheckReport report = adapter.mesh().check();
      if (!report.ok()) throw std::logic_error("mesh invariants broken: " + report.summary(5));
    }
    if (s.step % static_cast<std::uint64_t>(o.export_every) != 0) return;
    if (!o.export_dir.empty() || frames) {
      const MeshSnapshot snap = adapter.snapshot(fields);
      if (!o.export_dir.empty()) write_ply(frame_name(o.export_dir, s.step, "ply"), snap);
      if (frames) frames->render(snap, s.step);
    }
  };
  // A surface that turns bad during the run (a formula that becomes NaN at some t) throws
  // std::invalid_argument before the mesh is touched: bad input, exit status 2.
  try {
    record(adapter.initialize());
    for (int i = 1; i <= o.steps; ++i) {
      const double t = o.t0 + (o.t1 - o.t0) * i / o.steps;
      const StepStats& s = adapter.step(t);
      step_seconds.push_back(s.seconds.total);
      record(s);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  summary.last = adapter.stats();
  if (step_seconds.empty()) step_seconds.push_back(summary.last.seconds.total);
  std::nth_element(step_seconds.begin(), step_seconds.begin() + step_seconds.size() / 2,
                   step_seconds.end());
  summary.seconds_per_step_median = step_seconds[step_seconds.size() / 2];
  summary.quality = measure_quality(adapter.mesh());
  if (!o.export_final_path.empty()) write_mesh(o.export_final_path, adapter.snapshot(fields));
  if (frames && !o.quiet)
    log << "wrote " << frames->frames() << " frame(s) to " << o.render_dir << "\n";
  if (csv) csv->close();
  if (summary.budget_hit && !o.quiet)
    log << "note: the triangle budget (--max-triangles " << o.adapt.max_triangles
        << ") stopped refinement; errors may exceed T + eps\n";
  out << to_json(summary) << std::endl;
  return 0;
}

}  // namespace dynamesh
