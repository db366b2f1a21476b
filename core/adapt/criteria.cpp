#include "core/adapt/criteria.h"

#include <algorithm>
#include <cmath>

namespace dynamesh {

GeometricErrorCriterion::GeometricErrorCriterion(double threshold, double epsilon)
    : threshold_(threshold), split_above_(threshold + epsilon), weld_below_(threshold) {}

double GeometricErrorCriterion::split_urgency(const SplitQuery& q) const {
  return q.error / (q.initial ? threshold_ : split_above_);
}

// Exactly the bound allows_weld applies: below T always, up to T + eps without gain.
double GeometricErrorCriterion::weld_error_ceiling(double current_error) const {
  return std::max(weld_below_, std::min(split_above_, kNoGain * current_error));
}

// error / bound <= 1 exactly where error <= bound (a correctly rounded division is monotone).
double GeometricErrorCriterion::split_error_floor(bool initial) const {
  return initial ? threshold_ : split_above_;
}

bool GeometricErrorCriterion::allows_weld(const WeldQuery& q) const {
  return q.error < weld_below_ || (q.error <= split_above_ && q.error <= kNoGain * q.current_error);
}

EdgeLengthCriterion::EdgeLengthCriterion(double target_length)
    : target_(target_length),
      split_above_(target_length * std::pow(2.0, 0.25)),
      weld_below_(target_length) {}

double EdgeLengthCriterion::split_urgency(const SplitQuery& q) const {
  const Vec3& a = q.mesh.position(q.mesh.vertex(q.face, 1));
  const Vec3& b = q.mesh.position(q.mesh.vertex(q.face, 2));
  return (a - b).norm() / (q.initial ? target_ : split_above_);
}

bool EdgeLengthCriterion::allows_weld(const WeldQuery& q) const {
  const auto& p = q.plan.parents;
  return (q.mesh.position(p[0]) - q.mesh.position(p[1])).norm() < weld_below_;
}

HalfSpaceCriterion::HalfSpaceCriterion(std::unique_ptr<Criterion> inner, const Vec3& normal,
                                       double offset)
    : inner_(std::move(inner)), normal_(normal), offset_(offset) {}

std::string HalfSpaceCriterion::name() const {
  return inner_->name() + " (half-space)";
}

bool HalfSpaceCriterion::applies_to(const Mesh48& mesh, Face f) const {
  for (Vertex v : mesh.vertices(f))
    if (inside(mesh.position(v))) return true;
  return false;
}

bool HalfSpaceCriterion::applies_to(const Mesh48& mesh, const DiamondChange& plan) const {
  if (inside(mesh.position(plan.vertex))) return true;
  for (int h = 0; h < plan.count; ++h)
    for (Vertex v : plan.halves[h].parent_vertices)
      if (inside(mesh.position(v))) return true;
  return false;
}

CriterionList default_criteria(const std::string& scene, double scene_edge_length,
                               const AdaptOptions& options, double edge_length) {
  CriterionList list;
  auto error = std::make_unique<GeometricErrorCriterion>(options.threshold, options.epsilon);
  if (scene == "sphere") {
    const double length = edge_length > 0 ? edge_length : scene_edge_length;
    list.push_back(std::make_unique<HalfSpaceCriterion>(std::move(error), Vec3::UnitX(), 0.0));
    // x >= 0 is the half-space -x <= 0; the border plane x = 0 belongs to both sides.
    list.push_back(std::make_unique<HalfSpaceCriterion>(
        std::make_unique<EdgeLengthCriterion>(length), -Vec3::UnitX(), 1e-12));
    return list;
  }
  list.push_back(std::move(error));
  if (edge_length > 0) list.push_back(std::make_unique<EdgeLengthCriterion>(edge_length));
  return list;
}

}  // namespace dynamesh
