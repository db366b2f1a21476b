// The sphere near its floor (issue 17). A right-isosceles triangle with hypotenuse 2r on a
// sphere of radius R has error R - sqrt(R^2 - r^2) ~ r^2 / (2R) (its circumcentre's depth)
// and area r^2, so at error T no 4-8 mesh of right-isosceles triangles covers the sphere's
// 4 pi R^2 with fewer than 4 pi R^2 / (2 R T) = 2 pi R / T triangles: 6,283 at T = 1e-3,
// R = 1. Issue 17 asks for 1.25x; the box base mesh gives 9,216 (1.47x), and neither an
// octahedron (12,288) nor equiangular boxes of 3..6 quads per side (9,120 to 10,752) did
// better: every face at one 4-8 level must be within ~10% of the same error for a level to
// land near the floor, and these bases vary more than that. This pins today's 1.47x.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/adapt/adapter.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "tests/support/error_only_adapter.h"

namespace dynamesh {
namespace {

TEST(SphereBaseMesh, AdaptedSphereCountAgainstTheRightIsoscelesFloor) {
  auto surface = make_scene("sphere");
  surface->set_parameter("R0", 1.0);
  surface->set_parameter("R1", 1.0);
  surface->set_time(0.0);
  AdaptOptions o;
  o.threshold = 1e-3;
  o.epsilon = o.threshold / 4;
  // The geometric error everywhere (the scene's default is multi-criteria).
  const std::unique_ptr<Adapter> owned = test::error_only_adapter(*surface, o);
  Adapter& adapter = *owned;
  const double R = 1.0;
  const double floor = 2 * std::numbers::pi * R / o.threshold;
  const auto triangles = static_cast<double>(adapter.mesh().n_faces());
  EXPECT_LE(triangles, 1.5 * floor);
  // And not by being coarser than asked: the dense error is within the band.
  const auto dense = test::dense_error(adapter.mesh(), *surface, 20000.0, 3);
  EXPECT_LE(dense.max_error, (o.threshold + o.epsilon) * 1.10);
  RecordProperty("triangles", std::to_string(adapter.mesh().n_faces()));
  RecordProperty("floor", std::to_string(floor));
  // A few steps of a static sphere keep it there.
  for (int i = 0; i < 3; ++i) adapter.step(0.0);
  EXPECT_EQ(static_cast<double>(adapter.mesh().n_faces()), triangles);
}

}  // namespace
}  // namespace dynamesh

namespace dynamesh {
namespace {

// The distance from the origin to triangle abc: to the plane where the foot of the
// perpendicular falls inside, else to the nearest edge.
double distance_from_origin(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto to_segment = [](const Vec3& p, const Vec3& q) {
    const Vec3 d = q - p;
    const double s = std::clamp(-p.dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (p + s * d).norm();
  };
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 foot = n * (a.dot(n) / n.squaredNorm());
  const bool inside = (b - a).cross(foot - a).dot(n) >= 0 && (c - b).cross(foot - b).dot(n) >= 0 &&
                      (a - c).cross(foot - c).dot(n) >= 0;
  if (inside) return foot.norm();
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

// Where the sphere's floor really is for a 4-8 mesh (issue 17). N / floor decomposes exactly
// over the faces: with e_f a face's exact error (R minus its distance from the centre, a
// closed form) and A_f its area,
//   N / (2 pi R / T) = (1 / 4 pi R^2) sum_f A_f (T / e_f) (2 R e_f / A_f),
// a "level" factor T / e_f and a "shape" factor 2 R e_f / A_f (1 for a small right-isosceles
// face, whose error is r^2 / 2R for area r^2). Refinement to T leaves every face at e_f <= T
// whose parent had more than T, and a 4-8 bisection halves a small right-isosceles face's
// error, so T / e_f lies in [1, 2). Along the chain of faces over one point the errors halve
// level by level, so as T sweeps an octave, T / e at that point sweeps [1, 2) log-uniformly:
// the octave's mean of the level factor is int_0^1 2^u du = 1 / ln 2 = 1.443 for ANY base
// (conformity splits only add). The right-isosceles floor is reached only where every face
// lands just under T, at particular R / T; no 4-8 base is within 1.25x of it at every scale.
// Measured here over an octave of T for the box base (figures in the note): the shape
// factor is 0.94-1.03, the level factor averages 1.585, the 1.443 of the argument times what
// 4-8 conformity adds (faces split only because a neighbour was: 0-24% of the area has
// e_f < 0.45 T); N / floor is 1.37-1.71 over the octave, 1.46 at T = 1e-3.
TEST(SphereBaseMesh, OctaveMeanOfTheLevelFactorIsOneOverLnTwo) {
  const double R = 1.0;
  constexpr int kPerOctave = 8;
  double ratio_sum = 0, level_sum = 0, best = 1e9, worst = 0;
  for (int j = 0; j < kPerOctave; ++j) {
    const double T = 1e-3 * std::pow(2.0, static_cast<double>(j) / kPerOctave);
    auto surface = make_scene("sphere");
    surface->set_parameter("R0", R);
    surface->set_parameter("R1", R);
    surface->set_time(0.0);
    AdaptOptions o;
    o.threshold = T;
    o.epsilon = T / 4;
    const std::unique_ptr<Adapter> owned = test::error_only_adapter(*surface, o);
    const Adapter& adapter = *owned;
    const Mesh48& mesh = adapter.mesh();
    double area = 0, level = 0, shape = 0, worst_error = 0, finer = 0;
    for (Face f : mesh.live_faces()) {
      const auto v = mesh.vertices(f);
      const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
      const double A = 0.5 * (b - a).cross(c - a).norm();
      const double e = R - distance_from_origin(a, b, c);
      worst_error = std::max(worst_error, e);
      area += A;
      level += A * T / e;
      shape += A * 2 * R * e / A;
      finer += e < 0.45 * T ? A : 0.0;  // below the octave: split for conformity
    }
    const double n = static_cast<double>(mesh.n_faces());
    const double ratio = n * T / (2 * std::numbers::pi * R);
    // The exact error keeps to the band (the adapter's sampled estimate is not trusted here).
    EXPECT_LE(worst_error, (T + o.epsilon) * 1.10) << "T = " << T;
    ratio_sum += ratio;
    level_sum += level / area;
    best = std::min(best, ratio);
    worst = std::max(worst, ratio);
    std::printf(
        "T %.6g triangles %zu N/floor %.3f level %.3f shape %.3f worst e/T %.3f finer %.3f\n", T,
        mesh.n_faces(), ratio, level / area, shape / area, worst_error / T, finer / area);
  }
  const double level_mean = level_sum / kPerOctave, ratio_mean = ratio_sum / kPerOctave;
  std::printf("octave: mean N/floor %.3f (best %.3f, worst %.3f), mean level factor %.3f\n",
              ratio_mean, best, worst, level_mean);
  // 1 / ln 2 less the estimate's slack (a face's sampled error may sit a little under its
  // exact error, which lets it stay coarser than T).
  EXPECT_GE(level_mean, 0.95 / std::numbers::ln2);
  EXPECT_LE(ratio_mean, 1.65);  // today's box base (1.555), so that a regression shows
}

}  // namespace
}  // namespace dynamesh
