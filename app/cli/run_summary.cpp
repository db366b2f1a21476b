#include "app/cli/run_summary.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace dynamesh {
namespace {

std::string number(double x) {
  if (!std::isfinite(x)) return "null";
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

// A "Name:   1234 kB" field of /proc/self/status in MiB; -1 when absent.
double status_field_mb(const std::string& text, const std::string& name) {
  const auto at = text.find("\n" + name + ":");
  if (at == std::string::npos) return -1.0;
  std::istringstream in(text.substr(at + name.size() + 2));
  double kb = -1.0;
  in >> kb;
  return in ? kb / 1024.0 : -1.0;
}

}  // namespace

void RunSummary::measure_resident_memory() {
  std::ifstream in("/proc/self/status");
  std::ostringstream text;
  text << "\n" << in.rdbuf();
  resident_mb = status_field_mb(text.str(), "VmRSS");
  peak_resident_mb = status_field_mb(text.str(), "VmHWM");
}

void RunSummary::add(const StepStats& s) {
  total_splits += s.splits;
  total_welds += s.welds;
  budget_hit = budget_hit || s.budget_hit;
  sample_budget_hit = sample_budget_hit || s.sample_budget_hit;
  time_budget_hit = time_budget_hit || s.time_budget_hit;
  steps_done = s.step;
  if (s.triangles > peak_triangles) {
    peak_triangles = s.triangles;
    peak_triangles_step = s.step;
  }
  if (s.max_error > worst_max_error) {
    worst_max_error = s.max_error;
    worst_max_error_step = s.step;
  }
  topology_events.insert(topology_events.end(), s.topology_events.begin(), s.topology_events.end());
  rebuilds += s.rebuilt;
  local_repairs += s.local_repairs;
}

std::string to_json(const RunSummary& s) {
  std::ostringstream out;
  const StepStats& l = s.last;
  out << "{\"scene\":\"" << s.scene << "\",\"steps\":" << s.steps << ",\"time\":" << number(l.time)
      << ",\"triangles\":" << l.triangles << ",\"vertices\":" << l.vertices
      << ",\"max_sample_error\":" << number(l.max_error)
      << ",\"mean_sample_error\":" << number(l.mean_error) << ",\"samples\":" << l.samples
      << ",\"splits\":" << s.total_splits << ",\"welds\":" << s.total_welds
      << ",\"seconds_per_step\":" << number(s.seconds_per_step_median)
      << ",\"preparation_seconds\":" << number(s.preparation_seconds)
      << ",\"valence_min\":" << s.quality.valence_min
      << ",\"valence_max\":" << s.quality.valence_max
      << ",\"min_angle_deg\":" << number(s.quality.min_angle_deg)
      << ",\"max_aspect_ratio\":" << number(s.quality.max_aspect)
      << ",\"mean_aspect_ratio\":" << number(s.quality.mean_aspect)
      << ",\"vertices_kept\":" << l.vertices_kept
      << ",\"kept_fraction\":" << number(l.kept_fraction)
      << ",\"survivor_displacement_mean\":" << number(l.survivor_displacement_mean)
      << ",\"budget_hit\":" << (s.budget_hit ? "true" : "false")
      << ",\"sample_budget_hit\":" << (s.sample_budget_hit ? "true" : "false")
      << ",\"time_budget_hit\":" << (s.time_budget_hit ? "true" : "false")
      << ",\"steps_done\":" << s.steps_done << ",\"peak_triangles\":" << s.peak_triangles
      << ",\"peak_triangles_step\":" << s.peak_triangles_step
      << ",\"worst_max_sample_error\":" << number(s.worst_max_error)
      << ",\"worst_max_sample_error_step\":" << s.worst_max_error_step
      << ",\"keyframe_triangles\":[";
  for (std::size_t i = 0; i < s.keyframe_triangles.size(); ++i)
    out << (i ? "," : "") << s.keyframe_triangles[i];
  out << "]"
      << ",\"resident_mb\":" << number(s.resident_mb >= 0 ? s.resident_mb : NAN)
      << ",\"peak_resident_mb\":" << number(s.peak_resident_mb >= 0 ? s.peak_resident_mb : NAN)
      << ",\"rebuilds\":" << s.rebuilds << ",\"local_repairs\":" << s.local_repairs
      << ",\"topology_events\":[";
  for (std::size_t i = 0; i < s.topology_events.size(); ++i) {
    const TopologyEvent& e = s.topology_events[i];
    out << (i ? "," : "") << "{\"time\":" << number(e.time) << ",\"kind\":\"" << to_string(e.kind)
        << "\",\"position\":[" << number(e.position.x()) << ',' << number(e.position.y()) << ','
        << number(e.position.z()) << "]}";
  }
  out << "]}";
  return out.str();
}

}  // namespace dynamesh
