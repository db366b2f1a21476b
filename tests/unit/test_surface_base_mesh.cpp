// Base meshes of the scenes: the scene's topology (measured from the plain triangle list),
// the 4-8 invariants (Mesh48::check), vertices on the surface, faces oriented like the
// surface's normal, and no degenerate triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/surface/scene_registry.h"
#include "core/surface/scenes/sinc_scene.h"
#include "mesh_measure.h"

namespace dynamesh {
namespace {

constexpr double kTimes[] = {0.0, 0.25, 0.5, 0.75, 1.0};

double min_angle_deg(const Mesh48& mesh) {
  double best = 180;
  for (const test::Triple& t : test::triangle_list(mesh)) {
    for (int i = 0; i < 3; ++i) {
      const Vec3& a = mesh.position(Vertex(t[i]));
      const Vec3 u = mesh.position(Vertex(t[(i + 1) % 3])) - a;
      const Vec3 v = mesh.position(Vertex(t[(i + 2) % 3])) - a;
      best = std::min(best, std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / std::numbers::pi);
    }
  }
  return best;
}

Vec3 centroid(const Mesh48& mesh, const test::Triple& t) {
  return (mesh.position(Vertex(t[0])) + mesh.position(Vertex(t[1])) + mesh.position(Vertex(t[2]))) /
         3;
}

TEST(SurfaceBaseMesh, ClosedScenesHaveSphereTopologyOnTheSurfaceFacingOut) {
  for (const char* name : {"sphere", "capsule-bend", "twist"}) {
    auto scene = make_scene(name);
    auto& s = dynamic_cast<ImplicitSurface&>(*scene);
    for (const double t : kTimes) {
      s.set_time(t);
      const Mesh48 mesh = s.base_mesh();
      const CheckReport report = mesh.check();
      EXPECT_TRUE(report.ok()) << name << " t=" << t << "\n" << report.summary();
      const test::Topology topo = test::topology(mesh);
      EXPECT_EQ(topo.boundary_edges, 0) << name;  // every halfedge has a twin
      EXPECT_EQ(topo.euler(), 2) << name;
      for (const Vertex v : mesh.live_vertices()) {
        EXPECT_LT(std::abs(s.value(mesh.position(v))), 1e-10) << name << " t=" << t;
      }
      for (const test::Triple& tri : test::triangle_list(mesh)) {
        Vec3 g;
        s.value_gradient(centroid(mesh, tri), g);
        // Outward: coarse faces of the twisted bar cut across its rounded corners (up to
        // about 75 degrees from the normal at their centroid), but none is turned over.
        EXPECT_GT(test::face_area_vector(mesh, tri).normalized().dot(g.normalized()), 0.2)
            << name << " t=" << t;
      }
      EXPECT_GT(test::enclosed_volume(mesh), 0.0);
      // Above the 10 degrees under which the authors' guard refuses to split (DESIGN.md).
      EXPECT_GT(min_angle_deg(mesh), 10.0) << name << " t=" << t;
    }
  }
}

TEST(SurfaceBaseMesh, SincIsAnOpenGridOverTheParameterSquare) {
  SincScene s;
  for (const double t : kTimes) {
    s.set_time(t);
    const Mesh48 mesh = s.base_mesh();
    const CheckReport report = mesh.check();
    EXPECT_TRUE(report.ok()) << "t=" << t << "\n" << report.summary();
    const test::Topology topo = test::topology(mesh);
    EXPECT_EQ(topo.euler(), 1);  // a disc
    EXPECT_EQ(topo.boundary_edges, 4 * 8);
    for (const Vertex v : mesh.live_vertices()) {
      const Vec2& uv = mesh.uv(v);
      EXPECT_LE(uv.cwiseAbs().maxCoeff(), 1.0);
      const bool on_square_boundary = uv.cwiseAbs().maxCoeff() == 1.0;
      EXPECT_EQ(mesh.is_boundary(v), on_square_boundary) << uv.transpose();
      EXPECT_EQ(mesh.position(v), s.position(uv));
    }
    EXPECT_GT(min_angle_deg(mesh), 10.0) << "t=" << t;
    // Faces turn like the surface's normal Su x Sv (towards +y).
    for (const test::Triple& tri : test::triangle_list(mesh)) {
      const Vec2 uv =
          (mesh.uv(Vertex(tri[0])) + mesh.uv(Vertex(tri[1])) + mesh.uv(Vertex(tri[2]))) / 3;
      EXPECT_GT(test::face_area_vector(mesh, tri).dot(s.normal(uv)), 0.0);
    }
  }
}

}  // namespace
}  // namespace dynamesh
