#include "app/cli/run_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "app/cli/run_summary.h"
#include "app/offscreen/offscreen_render.h"
#include "app/render/color_mode.h"
#include "app/render/color_scale.h"
#include "core/adapt/adapter.h"
#include "core/adapt/workload_check.h"
#include "core/io/atomic_file.h"
#include "core/io/mesh_export.h"
#include "core/io/number_text.h"
#include "core/io/stats_csv.h"
#include "core/io/vtk_export.h"
#include "core/topology/fixed_critical_points.h"

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

// The budgets hold while the scene loads too: --max-memory bounds what a loader plans to
// allocate (mri: the volume's preprocessing), and --max-seconds, counted from the start of
// the run, is checked at every progress report of the load (a load has nothing to deliver
// when it is stopped: one line, exit status 2).
std::unique_ptr<Surface> build_scene(RunOptions& o, std::ostream& log) {
  try {
    const SceneInfo* info = nullptr;
    const std::vector<SceneInfo> scenes = list_scenes();
    for (const SceneInfo& s : scenes)
      if (s.name == o.scene) info = &s;
    const ProgressCallback print = progress_printer(o, log);
    const auto deadline = o.adapt.deadline;
    const double max_seconds = o.max_seconds;
    const ProgressCallback progress = [&print, deadline, max_seconds](std::string_view stage,
                                                                      double fraction) {
      if (std::chrono::steady_clock::now() > deadline) {
        std::ostringstream msg;
        msg << "the time budget (--max-seconds " << max_seconds << ") ran out while loading the "
            << "scene (" << stage << " " << static_cast<int>(100 * fraction) << "%)";
        throw std::invalid_argument(msg.str());
      }
      if (print) print(stage, fraction);
    };
    std::unique_ptr<Surface> surface =
        make_scene(o.scene, o.params, o.scene_text, progress, o.max_memory_mb);
    apply_scene_defaults(o, *info);  // make_scene has rejected an unknown name
    return surface;
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// Every file the run has written so far, so that a run that fails part way (a formula that
// turns bad at a later time) leaves none of its output behind: bad input, no output file.
// A run that ends by an exception (also before its first step: a refusal after the output
// directories were made) removes them as it unwinds; a finished run calls keep().
class RunOutputs {
 public:
  RunOutputs() = default;
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;
  ~RunOutputs() { remove_all(); }
  void add(std::string path) { paths_.push_back(std::move(path)); }
  void keep() { paths_.clear(); }
  // Newest first, so that a directory the run created goes after its frames (fs::remove
  // leaves a directory that is not empty).
  void remove_all() {
    std::error_code ignored;
    for (auto p = paths_.rbegin(); p != paths_.rend(); ++p) fs::remove(*p, ignored);
    paths_.clear();
  }

 private:
  std::vector<std::string> paths_;
};

// Fails early, before any work, when an output cannot be written.
void check_outputs(const RunOptions& o, RunOutputs& written) {
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
    const bool created = fs::create_directories(*dir, ec);
    if (ec || !fs::is_directory(*dir))
      throw UsageError("cannot create directory " + *dir + ": " + ec.message());
    if (created) written.add(*dir);  // a failed run leaves no empty directory behind
  }
}

// Memory the budgets allow, estimated before anything is allocated: per triangle the mesh,
// its adaptation bookkeeping and a snapshot (measured: about kBytesPerTriangle at 2M
// triangles on capsule-bend), per sample 12 bytes twice (the pool may hold as much garbage
// as live samples before it is compacted). A face holds at most 256 samples.
void check_memory_budget(const RunOptions& o) {
  constexpr double kBytesPerTriangle = 600.0, kBytesPerSample = 24.0, kMiB = 1024.0 * 1024.0;
  const double triangles = static_cast<double>(o.adapt.max_triangles);
  const double samples = std::min(static_cast<double>(o.adapt.max_samples), 256.0 * triangles);
  const double mb = (triangles * kBytesPerTriangle + samples * kBytesPerSample) / kMiB;
  if (mb > o.max_memory_mb) {
    std::ostringstream msg;
    msg << "the budgets (--max-triangles " << o.adapt.max_triangles << ", --max-samples "
        << o.adapt.max_samples << ") could need about " << std::lround(mb)
        << " MiB, more than --max-memory " << o.max_memory_mb
        << "; lower them or raise --max-memory";
    throw UsageError(msg.str());
  }
}

// Feasibility before any work (workload_check.h): at t0 and, for a run with steps, at four
// more times up to t1.
void check_workload(const RunOptions& o, Surface& surface) {
  const auto [first, last] = std::minmax_element(o.keyframes.begin(), o.keyframes.end());
  WorkloadBudget budget;
  budget.threshold = o.adapt.threshold;
  budget.density = o.adapt.density;
  budget.max_triangles = static_cast<double>(o.adapt.max_triangles);
  budget.max_samples = static_cast<double>(o.adapt.max_samples);
  budget.hopeless = o.scene == "expr" ? 1.0 : 10.0;
  set_edge_length_demand(budget, o.scene, surface, o.edge_length);
  const std::string reason = workload_refusal(surface, budget, *first, *last);
  if (!reason.empty()) throw UsageError("scene " + o.scene + " " + reason);
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
      << (s.budget_hit ? "  (triangle budget hit)" : "")
      << (s.sample_budget_hit ? "  (sample budget hit)" : "")
      << (s.time_budget_hit ? "  (time budget hit)" : "") << "\n";
  log.unsetf(std::ios::floatfield);
}

// Topology events (issue 16) on stderr whatever --quiet says: they change what the run means.
void log_topology(std::ostream& log, const StepStats& s) {
  for (const TopologyEvent& e : s.topology_events)
    log << "topology: " << to_string(e.kind) << " at t=" << std::fixed << std::setprecision(4)
        << e.time << " near (" << std::setprecision(3) << e.position.x() << ", " << e.position.y()
        << ", " << e.position.z() << ")\n";
  for (const std::string& why : s.repair_refusals)
    log << "topology: no local repair at step " << s.step << ": " << why << "\n";
  if (s.splits_held > 0)
    log << "topology: " << s.splits_held << " split(s) held at step " << s.step
        << " (no face split beyond depth " << s.held_depth
        << ": the mesh's topology could not follow F's; max error " << std::setprecision(3)
        << s.max_error << ")\n";
  if (s.local_repairs > 0 && !s.rebuilt)
    log << "topology: repaired locally at step " << s.step << " (" << s.repair_faces_replaced
        << " faces near the event replaced, the patch contoured at spacing " << std::setprecision(3)
        << s.repair_spacing << "; the other vertices kept)\n";
  if (s.folds_remeshed > 0 && !s.rebuilt)
    log << "topology: " << s.folds_remeshed << " faces left folded by the correction at step "
        << s.step << " re-meshed locally from F's contour (the other vertices kept)\n";
  if (s.rebuilt)
    log << "topology: mesh rebuilt from F's contour at step " << s.step << " (t=" << std::fixed
        << std::setprecision(4) << s.time << "; no vertex survives a rebuild"
        << (s.folds_repaired > 0 ? "; " + std::to_string(s.folds_repaired) +
                                       " faces were left folded by the correction"
                                 : std::string())
        << ")\n";
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
  if (o.color == "region") {
    const std::shared_ptr<const VolumeImage> image = surface.volume_image();
    if (!image || !image->atlas)
      throw UsageError(
          "--color region needs a label atlas: --scene mri with --atlas FILE.nii[.gz] (Colin27 "
          "from mricron-data has AAL by default)");
  }
  return f;
}

std::string frame_name(const std::string& dir, std::uint64_t step, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05llu.%s", static_cast<unsigned long long>(step), ext);
  return (fs::path(dir) / name).string();
}

// Offscreen frames (--render): one renderer for the whole run, so that only what changed
// goes to the GPU and the camera fitted to the first frame stays put while the mesh moves.
// With --color-range run the frames wait until the run is over: their colour scale spans
// every frame's values, which only the last step knows (they are kept in memory meanwhile).
class FrameRenderer {
 public:
  FrameRenderer(const RunOptions& o, double threshold, RunOutputs& outputs)
      : dir_(o.render_dir), outputs_(outputs) {
    options_.width = o.width;
    options_.height = o.height;
    options_.style.mode = *parse_color_mode(o.color);
    options_.style.colors = o.colors;
    options_.style.colors.threshold = threshold;
    options_.style.wireframe = o.wireframe;
    options_.view = o.camera;
    deferred_ = o.colors.range == ColorRange::kRun;
  }
  void render(const MeshSnapshot& snap, std::uint64_t step) {
    if (deferred_) {
      pending_.push_back(snap);
      return;
    }
    draw(snap, step);
  }
  // Draws the frames that waited for the whole run.
  void finish() {
    FieldStats whole_run;
    const std::string field(color_mode_field(options_.style.mode));
    for (const MeshSnapshot& snap : pending_)
      if (const ScalarField* f = field.empty() ? nullptr : snap.field(field))
        whole_run = merge(whole_run, field_stats(f->values));
    for (const MeshSnapshot& snap : pending_) {
      if (!renderer_) renderer_ = std::make_unique<OffscreenRenderer>();
      if (&snap == &pending_.front()) renderer_->restart_color_range(whole_run);
      draw(snap, snap.step);
    }
    pending_.clear();
  }
  int frames() const { return frames_; }

 private:
  void draw(const MeshSnapshot& snap, std::uint64_t step) {
    if (!renderer_) renderer_ = std::make_unique<OffscreenRenderer>();
    const std::string path = frame_name(dir_, step, "png");
    try {
      renderer_->render_to_png(snap, options_, path);
    } catch (const std::runtime_error& e) {
      // A frame size the OpenGL implementation cannot make (--size 16384x16384) is bad input,
      // found at the first frame.
      if (frames_ > 0 || std::string(e.what()).rfind("render target", 0) != 0) throw;
      throw UsageError("--size " + std::to_string(options_.width) + "x" +
                       std::to_string(options_.height) + ": " + e.what() +
                       "; choose a smaller size");
    }
    outputs_.add(path);
    ++frames_;
  }

  std::string dir_;
  RunOutputs& outputs_;
  OffscreenOptions options_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  bool deferred_ = false;
  std::vector<MeshSnapshot> pending_;
  int frames_ = 0;
};

// --export DIR: a PLY and a VTK PolyData file per exported step, and the ParaView collection
// naming the latter with their times.
class FrameExporter {
 public:
  FrameExporter(std::string dir, RunOutputs& outputs) : dir_(std::move(dir)), outputs_(outputs) {}
  void write(const MeshSnapshot& snap) {
    const std::string ply = frame_name(dir_, snap.step, "ply");
    write_ply(ply, snap);
    outputs_.add(ply);
    const std::string vtp = frame_name(dir_, snap.step, "vtp");
    write_vtp(vtp, snap);
    outputs_.add(vtp);
    collection_.emplace_back(snap.time, fs::path(vtp).filename().string());
  }
  void finish() {
    const std::string pvd = (fs::path(dir_) / "frames.pvd").string();
    write_pvd(pvd, collection_);
    outputs_.add(pvd);
  }

 private:
  std::string dir_;
  RunOutputs& outputs_;
  std::vector<std::pair<double, std::string>> collection_;
};

// The animation's times: --steps per keyframe segment, in order (t0, t1 is one segment).
std::vector<double> step_times(const RunOptions& o) {
  std::vector<double> times;
  for (std::size_t k = 0; k + 1 < o.keyframes.size(); ++k)
    for (int i = 1; i <= o.steps; ++i)
      times.push_back(o.keyframes[k] + (o.keyframes[k + 1] - o.keyframes[k]) * i / o.steps);
  return times;
}

// --no-geometric is an ablation: without the normal and tangential correction the vertices
// stay where they were while the surface moves, and splits alone only add triangles (each
// new vertex lies on the surface, its old neighbours do not): sinc reaches a 2M-triangle
// budget by its third step and then runs for minutes. Such a run stops at the first step
// the mesh is left behind, with the reason, instead.
void fail_if_left_behind(const RunOptions& o, const StepStats& s) {
  const double bound = o.adapt.threshold + o.adapt.epsilon;
  if (o.adapt.geometric || !(s.max_error > bound)) return;
  throw UsageError("--no-geometric: at step " + std::to_string(s.step) + " the mesh is " +
                   format_significant(s.max_error, 3) +
                   " from the surface, beyond T + eps = " + format_significant(bound, 3) +
                   ": without vertex correction splits cannot follow a moving surface (use "
                   "--no-geometric on a static interval, e.g. --steps 0 or --t1 equal to --t0)");
}

// A surface whose critical points are fixed (mri, issue 16): how many the run watches, when
// any, on stderr whatever --quiet says, like the events they announce.
void log_fixed_critical_points(std::ostream& log, const Surface& surface, double threshold) {
  const auto* field = dynamic_cast<const FixedCriticalField*>(&surface);
  if (!field) return;
  const FixedCriticalPoints& p = field->fixed_critical_points(threshold);
  if (p.points.empty()) return;  // no monitor is kept: the run is what it was
  log << "topology: " << p.points.size() << " critical point(s) of F can change the layer's "
      << "topology in this run (" << p.candidates << " found, " << p.cancelled
      << " cancelled in pairs of persistence below T; " << format_significant(p.seconds, 2)
      << " s)\n";
}

// Adapts over the whole animation, writing what was asked for along the way.
void run_steps(const RunOptions& o, Adapter& adapter, const SnapshotFields& fields,
               StatsCsvWriter* csv, FrameExporter* exporter, FrameRenderer* frames,
               RunSummary& summary, std::vector<double>& step_seconds, std::ostream& log) {
  const int total_steps = static_cast<int>(step_times(o).size());
  auto record = [&](const StepStats& s) {
    summary.add(s);
    log_topology(log, s);
    if (csv) csv->write(s, summary.total_splits, summary.total_welds);
    if (!o.quiet) log_step(log, s, total_steps);
    if (o.check) {
      const CheckReport report = adapter.mesh().check();
      if (!report.ok()) throw std::logic_error("mesh invariants broken: " + report.summary(5));
    }
    if (s.step % static_cast<std::uint64_t>(o.export_every) != 0) return;
    if (exporter || frames) {
      const MeshSnapshot snap = adapter.snapshot(fields);
      if (exporter) exporter->write(snap);
      if (frames) frames->render(snap, s.step);
    }
  };
  // With --topology-events off no point is watched (Adapter::watch_topology): nothing to say.
  if (o.adapt.topology_events) log_fixed_critical_points(log, adapter.surface(), o.adapt.threshold);
  record(adapter.initialize());
  summary.keyframe_triangles.push_back(adapter.stats().triangles);
  const std::vector<double> times = step_times(o);
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (std::chrono::steady_clock::now() > o.adapt.deadline) summary.time_budget_hit = true;
    if (summary.time_budget_hit) break;  // --max-seconds: the run ends with what it has
    const StepStats& s = adapter.step(times[i]);
    step_seconds.push_back(s.seconds.total);
    record(s);
    fail_if_left_behind(o, s);
    if ((i + 1) % static_cast<std::size_t>(o.steps) == 0)
      summary.keyframe_triangles.push_back(s.triangles);
  }
}

}  // namespace

int run_command(const RunOptions& options, std::ostream& out, std::ostream& log) {
  RunOptions o = options;
  if (o.t0 < 0 || o.t0 > 1 || o.t1 < 0 || o.t1 > 1)
    throw UsageError("--t0 and --t1 must lie in [0, 1] (normalised animation time)");
  if (o.keyframes.empty()) o.keyframes = {o.t0, o.t1};
  if (o.steps == 0) o.keyframes.resize(1);  // adapt once, at the first time
  const auto start = std::chrono::steady_clock::now();
  if (o.max_seconds > 0)
    o.adapt.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(o.max_seconds));
  std::unique_ptr<Surface> surface = build_scene(o, log);
  const double preparation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RunOutputs written;
  check_outputs(o, written);
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
  if (!o.render_dir.empty())
    frames = std::make_unique<FrameRenderer>(o, o.adapt.threshold, written);
  std::unique_ptr<FrameExporter> exporter;
  if (!o.export_dir.empty()) exporter = std::make_unique<FrameExporter>(o.export_dir, written);
  check_memory_budget(o);
  try {
    check_workload(o, *surface);
  } catch (const std::invalid_argument& e) {  // the surface's own checks at a later time
    throw UsageError(e.what());
  }
  surface->set_time(o.keyframes.front());
  Adapter adapter(*surface, o.adapt, criteria_for(o, *surface));
  RunSummary summary;
  summary.scene = o.scene;
  summary.steps = static_cast<int>(step_times(o).size());
  summary.preparation_seconds = preparation_seconds;
  std::vector<double> step_seconds;
  try {
    run_steps(o, adapter, fields, csv.get(), exporter.get(), frames.get(), summary, step_seconds,
              log);
    if (frames) frames->finish();
    if (exporter) exporter->finish();
    if (!o.export_final_path.empty()) write_mesh(o.export_final_path, adapter.snapshot(fields));
    if (csv) csv->close();
  } catch (const std::invalid_argument& e) {
    // A surface that turns bad during the run (a formula that becomes NaN at some t) throws
    // std::invalid_argument before the mesh is touched: bad input, exit status 2, and none of
    // the run's files stay (the CSV and final mesh were never committed).
    written.remove_all();
    throw UsageError(e.what());
  } catch (...) {
    written.remove_all();
    throw;
  }
  written.keep();
  summary.last = adapter.stats();
  if (step_seconds.empty()) step_seconds.push_back(summary.last.seconds.total);
  std::nth_element(step_seconds.begin(), step_seconds.begin() + step_seconds.size() / 2,
                   step_seconds.end());
  summary.seconds_per_step_median = step_seconds[step_seconds.size() / 2];
  summary.quality = measure_quality(adapter.mesh());
  summary.measure_resident_memory();
  if (frames && !o.quiet)
    log << "wrote " << frames->frames() << " frame(s) to " << o.render_dir << "\n";
  // Budget hits are reported even with --quiet: the result is not what was asked for.
  if (summary.budget_hit)
    log << "note: the triangle budget (--max-triangles " << o.adapt.max_triangles
        << ") stopped refinement; errors may exceed T + eps\n";
  if (summary.sample_budget_hit)
    log << "note: the sample budget (--max-samples " << o.adapt.max_samples
        << ") stopped refinement; errors may exceed T + eps\n";
  if (summary.time_budget_hit)
    log << "note: the time budget (--max-seconds " << o.max_seconds << ") stopped the run after "
        << summary.steps_done << " of " << summary.steps << " steps; errors may exceed T + eps\n";
  out << to_json(summary) << std::endl;
  return 0;
}

}  // namespace dynamesh
