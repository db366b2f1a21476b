#include "core/adapt/workload_check.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/adapt/workload_estimate.h"
#include "core/io/number_text.h"

namespace dynamesh {
namespace {

std::string whole(double x) {
  return std::to_string(std::llround(x));
}

std::string refusal(const WorkloadEstimate& w, const WorkloadBudget& b, const WorkloadWords& words,
                    bool problems) {
  if (!w.problem.empty()) return problems ? w.problem : std::string();
  if (w.triangles > b.hopeless * b.max_triangles)
    return "the surface needs at least about " + format_significant(w.triangles, 2) +
           " triangles at " + words.threshold + " " + format_significant(b.threshold, 2) +
           " (curvature integral " + format_significant(w.curvature, 2) + " over area " +
           format_significant(w.area, 2) + "), more than " + words.max_triangles + " " +
           whole(b.max_triangles) + "; raise " + words.threshold + " or the budget";
  if (b.edge_length > 0) {
    const double needed =
        b.edge_length_share * w.area / (std::sqrt(3.0) / 4.0 * b.edge_length * b.edge_length);
    const std::string& name =
        b.edge_length_from_scene ? words.scene_edge_length : words.edge_length;
    if (needed > b.hopeless * b.max_triangles)
      return "edges of at most " + name + " " + format_significant(b.edge_length, 2) +
             " need at least about " + format_significant(needed, 2) + " triangles over area " +
             format_significant(b.edge_length_share * w.area, 2) + ", more than " +
             words.max_triangles + " " + whole(b.max_triangles) + "; raise " + name +
             " or the budget";
  }
  if (w.samples > b.max_samples)
    return "the surface needs about " + format_significant(w.samples, 2) + " samples (" +
           words.density + " " + format_significant(b.density, 2) + " over area " +
           format_significant(w.area, 2) + "), more than " + words.max_samples + " " +
           whole(b.max_samples) + "; lower " + words.density + " or raise the budget";
  return {};
}

}  // namespace

void set_edge_length_demand(WorkloadBudget& budget, const std::string& scene,
                            const Surface& surface, double edge_length) {
  budget.edge_length = edge_length > 0 ? edge_length : 0.0;
  budget.edge_length_share = 1.0;
  budget.edge_length_from_scene = false;
  if (scene != "sphere") return;
  budget.edge_length_share = 0.5;  // its x >= 0 half
  if (edge_length > 0) return;
  for (const SurfaceParameter& p : surface.parameters())
    if (p.name == "L") {
      budget.edge_length = p.value;
      budget.edge_length_from_scene = true;
    }
}

std::string workload_refusal(Surface& surface, const WorkloadBudget& budget, double t_first,
                             double t_last, const WorkloadWords& words, int checks, bool problems) {
  if (t_first == t_last) checks = 1;
  std::string reason;
  for (int c = 0; c < checks && reason.empty(); ++c) {
    const double t = checks == 1 ? t_first : t_first + (t_last - t_first) * c / (checks - 1);
    try {
      surface.set_time(t);
    } catch (const std::invalid_argument&) {
      if (problems) throw;
      continue;
    }
    reason =
        refusal(estimate_workload(surface, budget.threshold, budget.density, budget.max_triangles),
                budget, words, problems);
    if (!reason.empty()) reason = "at t = " + format_significant(t, 2) + ": " + reason;
  }
  surface.set_time(t_first);
  return reason;
}

}  // namespace dynamesh
