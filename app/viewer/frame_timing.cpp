#include "app/viewer/frame_timing.h"

#include <algorithm>
#include <cstdio>

#include "core/io/atomic_file.h"

namespace dynamesh {
namespace {

// Nearest-rank quantile of a copy.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

}  // namespace

FrameSummary summarize(const std::vector<FrameSample>& frames, double seconds) {
  FrameSummary s;
  s.frames = frames.size();
  s.seconds = seconds;
  s.fps = seconds > 0 ? static_cast<double>(frames.size()) / seconds : 0.0;
  std::vector<double> work, draw;
  for (const FrameSample& f : frames) {
    work.push_back(f.work_ms);
    draw.push_back(f.draw_ms);
    s.new_steps += f.new_step ? 1 : 0;
    s.work_max_ms = std::max(s.work_max_ms, f.work_ms);
    s.handoff_max_ms = std::max(s.handoff_max_ms, f.handoff_ms);
    if (!f.new_step) s.quiet_work_max_ms = std::max(s.quiet_work_max_ms, f.work_ms);
  }
  s.work_median_ms = quantile(work, 0.5);
  s.work_p95_ms = quantile(work, 0.95);
  s.draw_median_ms = quantile(draw, 0.5);
  return s;
}

std::string describe(const FrameSummary& s) {
  char text[400];
  std::snprintf(text, sizeof text,
                "%zu frames in %.2f s (%.1f fps), %zu new steps; frame ms: median %.1f, p95 %.1f, "
                "max %.1f (max without a new step %.1f); hand-off max %.1f ms; draw median %.1f ms",
                s.frames, s.seconds, s.fps, s.new_steps, s.work_median_ms, s.work_p95_ms,
                s.work_max_ms, s.quiet_work_max_ms, s.handoff_max_ms, s.draw_median_ms);
  return text;
}

std::string describe(const StartupTiming& s) {
  char text[600];
  std::snprintf(text, sizeof text,
                "first mesh on screen %.2f s after start (process CPU %.2f s): window %.2f s; "
                "scene built %.2f s (CPU %.2f s); first adaptation %.2f s (CPU %.2f s); "
                "snapshot %.3f s; mesh upload %.1f ms; first draw %.1f ms (of it the scan's 3-D "
                "texture upload %.1f ms); %zu frames before it took %.1f ms",
                s.first_mesh_seconds, s.first_mesh_cpu_seconds, s.window_seconds, s.build_seconds,
                s.build_cpu_seconds, s.adapt_seconds, s.adapt_cpu_seconds, s.snapshot_seconds,
                std::max(0.0, s.upload_ms), s.first_draw_ms, s.volume_upload_ms, s.frames_before,
                s.frames_before_ms);
  return text;
}

void write_frame_log(const std::vector<FrameSample>& frames, const std::string& path) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "frame,at_ms,work_ms,handoff_ms,draw_ms,new_step,triangles\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameSample& f = frames[i];
    out << i << ',' << f.at_ms << ',' << f.work_ms << ',' << f.handoff_ms << ',' << f.draw_ms << ','
        << (f.new_step ? 1 : 0) << ',' << f.triangles << '\n';
  }
  file.commit();
}

}  // namespace dynamesh
