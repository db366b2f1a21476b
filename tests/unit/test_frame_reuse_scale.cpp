// Curvature-frame reuse (tangential_smoothing.cpp, frame_reusable) on a surface with a rest
// map: what counts is a vertex's slide over the material (in rest space), not the move the
// material carries it by, which only turns its frame (the mesh-normal guard sees that: at
// most kFrameReuseAngle = 0.05 rad). Until session 12 the whole move counted, against 0.05 of
// the ring's mean edge, so a fine mesh carried by more than that a step (capsule-bend at 10^6
// triangles: ~3e-3, about an edge) evaluated nearly every frame every step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>

#include "core/geometry/tangential_smoothing.h"
#include "core/mesh/base_meshes.h"

namespace dynamesh {
namespace {

// |p|^2 - 1, whose material turns by `rotation` (the rest map): every frame known in closed
// form (normal p, both curvatures 1), carried with the material.
class TurningSphere final : public ImplicitSurface {
 public:
  std::string name() const override { return "turning-sphere"; }
  bool has_rest_map() const override { return true; }
  Vec3 to_rest(const Vec3& p) const override { return rotation.transpose() * p; }
  Vec3 from_rest(const Vec3& q) const override { return rotation * q; }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3::Constant(-1.0));
    box.extend(Vec3::Constant(1.0));
    return box;
  }
  Mesh48 base_mesh() const override {
    Box3 cube;
    cube.extend(Vec3::Constant(-0.5));
    cube.extend(Vec3::Constant(0.5));
    Mesh48 mesh = make_box_mesh(cube, {2, 2, 2});
    for (Vertex v : mesh.live_vertices()) mesh.position(v).normalize();
    return mesh;
  }
  double value(const Vec3& p) const override { return p.squaredNorm() - 1.0; }
  double value_gradient(const Vec3& p, Vec3& gradient) const override {
    gradient = 2.0 * p;
    return p.squaredNorm() - 1.0;
  }
  Mat3 hessian(const Vec3&) const override { return 2.0 * Mat3::Identity(); }

  Mat3 rotation{Mat3::Identity()};
};

// The base mesh split uniformly `levels` times, every vertex on the sphere.
Mesh48 fine_mesh(const TurningSphere& s, int levels) {
  Mesh48 mesh = s.base_mesh();
  for (int l = 0; l < levels; ++l)
    for (Face f : mesh.live_faces())
      if (mesh.is_alive(f)) mesh.split(f);
  for (Vertex v : mesh.live_vertices()) mesh.position(v).normalize();
  return mesh;
}

// The material turns by `angle` about a fixed axis through the centre and carries the mesh
// (each vertex's normal turns by `angle` with it; no vertex slides over the material).
void turn(TurningSphere& s, Mesh48& mesh, double angle) {
  const Mat3 q = Eigen::AngleAxisd(angle, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  s.rotation = q * s.rotation;
  for (Vertex v : mesh.live_vertices()) mesh.position(v) = q * mesh.position(v);
}

// Each call carries the vertices by up to 0.008 (0.008 rad): about 0.3 of an edge, six times
// what the whole-move bound allowed. A frame is then reused until its mesh normal turned by
// 0.05 rad (six calls, 0.048 rad), and the smoothing differs from the one with every frame
// fresh by what a normal 0.05 rad off moves a vertex: its move towards its ring's centroid
// (under an edge) taken in a tangent plane tilted by that much, twice for safety.
TEST(FrameReuseScale, FramesAreReusedWhereTheMaterialCarriesTheVertices) {
  TurningSphere s;
  Mesh48 mesh = fine_mesh(s, 6);
  const std::size_t n = mesh.n_vertices();
  // Mean edge length (an interior edge counted from both its faces).
  double edge = 0.0;
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    edge += (a - b).norm() + (b - c).norm() + (c - a).norm();
  }
  edge /= 3.0 * static_cast<double>(mesh.n_faces());
  constexpr double kTurn = 0.008;       // rad
  ASSERT_GT(kTurn, 5.0 * 0.05 * edge);  // the whole-move bound would reuse (almost) nothing
  SmoothingWorkspace workspace;
  SmoothingOptions o;
  smooth_tangentially(mesh, s, o, &workspace);
  double worst = 0.0;
  std::size_t least = n, most = 0;
  for (int call = 0; call < 24; ++call) {
    turn(s, mesh, kTurn);
    Mesh48 fresh = mesh;
    const SmoothingResult r = smooth_tangentially(mesh, s, o, &workspace);
    smooth_tangentially(fresh, s, o);  // no workspace: every frame evaluated
    for (Vertex v : mesh.live_vertices())
      worst = std::max(worst, (mesh.position(v) - fresh.position(v)).norm());
    if (call >= 8) {  // past the first cycle of fresh evaluations
      least = std::min(least, r.frames_reused);
      most = std::max(most, r.frames_reused);
    }
    mesh = fresh;  // the next call starts where the reference is (differences do not add up)
  }
  std::printf(
      "vertices %zu, mean edge %.4f, frames reused per call %zu..%zu, largest difference %.3g "
      "edges\n",
      n, edge, least, most, worst / edge);
  EXPECT_GT(least, n / 2);
  EXPECT_LE(most, n - n / 8 + 1);  // the rotating fresh evaluation (every 8 calls)
  EXPECT_LT(worst, 2.0 * 0.05 * edge);
}

// SmoothingOptions::rest_points: the rest points the caller carried the vertices from are
// read instead of mapping each vertex back. Given the right ones, the smoothing is the one that
// maps back (the same frames reused, the same positions); given rest points off by a tenth of
// an edge to one side and then the other, it sees every vertex slide a fifth of an edge each
// time and reuses no frame.
TEST(FrameReuseScale, RestPointsGivenByTheCallerAreRead) {
  TurningSphere s;
  const Mesh48 start = fine_mesh(s, 4);
  const double edge =
      (start.position(start.vertex(Face(0), 0)) - start.position(start.vertex(Face(0), 1))).norm();
  Mesh48 mapped = start, given = start, shifted = start;
  SmoothingWorkspace mapped_work, given_work, shifted_work;
  SmoothingOptions o;
  std::size_t reused = 0, reused_shifted = 0;
  for (int call = 0; call < 12; ++call) {
    std::vector<Vec3> rest(given.vertex_capacity()), off(shifted.vertex_capacity());
    for (Vertex v : given.live_vertices()) rest[v.idx] = s.to_rest(given.position(v));
    for (Vertex v : shifted.live_vertices())
      off[v.idx] = s.to_rest(shifted.position(v)) + Vec3(call % 2 ? 0.1 * edge : -0.1 * edge, 0, 0);
    const Mat3 before = s.rotation;
    turn(s, given, 0.004);
    s.rotation = before;
    turn(s, shifted, 0.004);
    s.rotation = before;
    turn(s, mapped, 0.004);
    SmoothingOptions with_rest = o, with_off = o;
    with_rest.rest_points = &rest;
    with_off.rest_points = &off;
    const SmoothingResult a = smooth_tangentially(mapped, s, o, &mapped_work);
    const SmoothingResult b = smooth_tangentially(given, s, with_rest, &given_work);
    const SmoothingResult c = smooth_tangentially(shifted, s, with_off, &shifted_work);
    EXPECT_EQ(a.frames_reused, b.frames_reused) << call;
    for (Vertex v : mapped.live_vertices())
      ASSERT_EQ(mapped.position(v), given.position(v)) << "call " << call;
    reused += b.frames_reused;
    reused_shifted += c.frames_reused;
  }
  EXPECT_GT(reused, 6 * start.n_vertices());
  EXPECT_EQ(reused_shifted, 0u);
}

}  // namespace
}  // namespace dynamesh
