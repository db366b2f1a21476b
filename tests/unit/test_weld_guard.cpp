// The angle guard's weld (AdaptOptions::angle_guard.weld_first, adapter.cpp weld_pass) on a
// star built so that the guard used to decide on a lower bound of the post-weld error.
//
// weld_pass measures a candidate's post-weld error only as far as the criteria's ceiling for
// the star's current error needs (SampleStore::weld_error stops at the first reading above
// it). When the star reads below (T + eps) / 1.05, that ceiling is below T + eps, and a star
// that is not allowed to weld returns a lower bound. The guard, which welds a badly shaped
// star whenever the weld keeps the error within T + eps, used to trust that lower bound: here
// the restored edge's midpoint (measured first) reads 1.05 T, above the ceiling but within
// T + eps, while the welded triangles read 1.31 T inside. The weld was made, read above
// T + eps and split straight back: a weld and a split every step of a static surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/adapt/adapter.h"
#include "core/adapt/criteria.h"
#include "core/mesh/base_meshes.h"

namespace dynamesh {
namespace {

constexpr double kT = 0.008, kEps = 0.002;

// x = a u + k (u^2 - 0.9 u v + v^2) over the unit square, with y = u, z = v. The linear part is
// interpolated exactly by any triangle, so the residual of a flat triangle is that of the
// quadratic alone (closed forms below); its slope a = 20 makes the triangles around the
// square's centre thin (angles of ~6 and ~174 degrees), so the guard judges the centre's star.
// k puts the errors where the flaw lives: the two base triangles 0.3448 k = 1.31 T (split on
// the way to T), the centre's four children 0.25 k = 0.95 T (weld ceiling max(T, 1.05 * 0.95 T)
// = 1.0006 T), the restored diagonal's midpoint 0.275 k = 1.05 T.
class SteepBowl final : public ParametricSurface {
 public:
  static constexpr double kSlope = 20.0, kCurvature = 0.0305;
  std::string name() const override { return "steep-bowl"; }
  ParameterDomain domain() const override { return ParameterDomain{}; }
  Vec3 position(const Vec2& uv) const override {
    const double u = uv.x(), v = uv.y();
    return {kSlope * u + kCurvature * (u * u - 0.9 * u * v + v * v), u, v};
  }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3(0.0, 0.0, 0.0));
    box.extend(Vec3(kSlope + 2.0 * kCurvature, 1.0, 1.0));
    return box;
  }
  Mesh48 base_mesh() const override {
    Mesh48 mesh = make_grid_mesh(1, 1, Vec2(0, 0), Vec2(1, 1));
    for (const Vertex v : mesh.live_vertices()) mesh.position(v) = position(mesh.uv(v));
    return mesh;
  }
};

// Largest |residual| of the flat triangle over the surface, on a barycentric lattice: the
// test's own measurement, from the surface's positions only.
double dense_error(const SteepBowl& s, const std::array<Vec2, 3>& uv) {
  constexpr int kN = 300;
  double worst = 0.0;
  for (int i = 0; i <= kN; ++i)
    for (int j = 0; i + j <= kN; ++j) {
      const double b1 = double(i) / kN, b2 = double(j) / kN, b0 = 1.0 - b1 - b2;
      const Vec3 x = b0 * s.position(uv[0]) + b1 * s.position(uv[1]) + b2 * s.position(uv[2]);
      worst = std::max(worst, (x - s.position(b0 * uv[0] + b1 * uv[1] + b2 * uv[2])).norm());
    }
  return worst;
}

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    return std::acos(std::clamp((q - p).normalized().dot((r - p).normalized()), -1.0, 1.0));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * 180.0 / std::acos(-1.0);
}

// The construction does what the header says, measured independently of the engine.
TEST(WeldGuard, TheStarReadsAboveTheBoundOnlyInsideItsParents) {
  const SteepBowl s;
  const Vec2 p00(0, 0), p10(1, 0), p11(1, 1), p01(0, 1), m(0.5, 0.5);
  // The weld restores the diagonal p00-p11 (the base triangles' refinement edge).
  const double welded = std::max(dense_error(s, {p10, p11, p00}), dense_error(s, {p01, p00, p11}));
  double children = 0.0;
  for (const auto& t : {std::array<Vec2, 3>{m, p00, p10},
                        {m, p10, p11},
                        {m, p11, p01},
                        std::array<Vec2, 3>{m, p01, p00}})
    children = std::max(children, dense_error(s, t));
  const double midpoint =
      (0.5 * (s.position(p00) + s.position(p11)) - s.position(0.5 * (p00 + p11))).norm();
  const GeometricErrorCriterion criterion(kT, kEps);
  EXPECT_GT(welded, 1.04 * (kT + kEps));                               // 1.0517 (T + eps)
  EXPECT_LT(children, 0.96 * kT);                                      // 0.953 T
  EXPECT_GT(midpoint, 1.04 * criterion.weld_error_ceiling(children));  // 1.048 T / 1.0006 T
  EXPECT_LT(midpoint, 0.85 * (kT + kEps));                             // 0.839 (T + eps)
  // Thin: the guard applies to every child.
  for (const auto& t : {std::array<Vec2, 3>{m, p00, p10},
                        {m, p10, p11},
                        {m, p11, p01},
                        std::array<Vec2, 3>{m, p01, p00}})
    EXPECT_LT(smallest_angle_deg(s.position(t[0]), s.position(t[1]), s.position(t[2])), 10.0);
}

class WeldGuardSampling : public ::testing::TestWithParam<Sampling> {};

// The star is not welded: its post-weld error is above T + eps. Before the fix the guard
// welded it on the midpoint's reading, once per settling round (4 welds and 5 splits in
// initialize()) and then once every step of the static surface.
TEST_P(WeldGuardSampling, DoesNotWeldAStarThatReadsAboveTheBoundInside) {
  SteepBowl surface;
  AdaptOptions o;
  o.threshold = kT;
  o.epsilon = kEps;
  o.geometric = false;  // the star stays where it is built
  o.density = 1.0;      // the minimum pattern (the residual is quadratic: the model is exact)
  o.sampling = GetParam();
  ASSERT_TRUE(o.angle_guard.weld_first);
  CriterionList criteria;
  criteria.push_back(std::make_unique<GeometricErrorCriterion>(kT, kEps));
  Adapter adapter(surface, o, std::move(criteria));
  const StepStats& first = adapter.initialize();
  EXPECT_EQ(first.splits, 1u);  // the diagonal, once
  EXPECT_EQ(first.welds, 0u);
  EXPECT_EQ(first.pathological_welds, 0u);
  EXPECT_EQ(adapter.mesh().n_faces(), 4u);
  EXPECT_LE(first.max_error, kT);
  // A static surface is a fixed point.
  for (int k = 0; k < 3; ++k) {
    const StepStats& st = adapter.step(surface.time());
    EXPECT_EQ(st.welds, 0u) << "step " << k;
    EXPECT_EQ(st.splits, 0u) << "step " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, WeldGuardSampling,
                         ::testing::Values(Sampling::kPredictive, Sampling::kFull),
                         [](const auto& info) {
                           return info.param == Sampling::kFull ? "Full" : "Predictive";
                         });

}  // namespace
}  // namespace dynamesh
