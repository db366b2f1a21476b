// Initial meshes of any genus from F alone (issue 16, item 1): a torus, a genus-2 double
// torus and two separate spheres typed as formulas, without --base-mesh, come out closed,
// oriented manifolds with the right Euler characteristic and number of components (measured
// from the triangle list and, independently, from a flood-filled voxel grid of F < 0), adapted
// within the error bound measured densely.
#include <gtest/gtest.h>

#include <string>

#include "core/adapt/adapter.h"
#include "core/mesh/mesh48.h"
#include "core/surface/expression/implicit_expression_surface.h"
#include "core/surface/scene_registry.h"
#include "core/topology/contour_base_mesh.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/triangle_pairing.h"
#include "dense_error.h"
#include "tests/support/mesh_validity.h"
#include "topology_measure.h"

namespace dynamesh {
namespace {

struct Shape {
  std::string name, formula, bounds;
  long components, euler;
};

const Shape kTorus{"torus", "(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09", "-1.5,-1.5,-0.5,1.5,1.5,0.5", 1, 0};
// A tube around Gerono's figure eight y^2 = x^2 (1 - x^2): two holes.
const Shape kDoubleTorus{"double torus", "(y^2 - x^2*(1-x^2))^2 + z^2 - 0.03",
                         "-1.3,-0.8,-0.4,1.3,0.8,0.4", 1, -2};
const Shape kTwoSpheres{"two spheres", "((x-0.8)^2+y^2+z^2-0.25)*((x+0.8)^2+y^2+z^2-0.25)",
                        "-1.5,-0.7,-0.7,1.5,0.7,0.7", 2, 4};

std::unique_ptr<Surface> typed(const Shape& s) {
  return make_scene("expr", {}, {{"implicit", s.formula}, {"bounds", s.bounds}});
}

void expect_embedded(const test::MeshValidity& v, const Shape& s, const std::string& when) {
  EXPECT_EQ(v.components, s.components) << s.name << " " << when;
  EXPECT_EQ(v.euler(), s.euler) << s.name << " " << when;
  EXPECT_TRUE(v.embedded_closed_manifold()) << s.name << " " << when << ": " << v.describe();
}

void expect_closed_manifold(const Mesh48& mesh, const Shape& s, const std::string& when) {
  expect_embedded(test::check_mesh_validity(mesh), s, when);
  const CheckReport report = mesh.check();
  EXPECT_TRUE(report.ok()) << s.name << " " << when << ": " << report.summary();
}

TEST(TopologyContour, ReferenceGridAgreesWithTheShapes) {
  // The independent reference itself: the voxelised solids have the expected topology.
  for (const Shape& s : {kTorus, kDoubleTorus, kTwoSpheres}) {
    const auto surface = typed(s);
    const auto& F = dynamic_cast<const ImplicitSurface&>(*surface);
    const test::SolidTopology ref =
        test::solid_topology([&](const Vec3& p) { return F.value(p); }, F.bounds(), 160);
    EXPECT_EQ(ref.components, s.components) << s.name;
    EXPECT_EQ(ref.surface_euler, s.euler) << s.name;
  }
}

TEST(TopologyContour, MarchingTetrahedraGivesAClosedOrientedManifold) {
  for (const Shape& s : {kTorus, kDoubleTorus, kTwoSpheres}) {
    const auto surface = typed(s);
    const auto& F = dynamic_cast<const ImplicitSurface&>(*surface);
    const ContourGrid grid = make_contour_grid(F.bounds(), F.bounds().size().maxCoeff() / 24);
    const ContourMesh contour = marching_tetrahedra(grid, sample_grid(F, grid));
    expect_embedded(test::check_mesh_validity(contour.positions, contour.triangles), s, "contour");
    // Pairing: a perfect matching on every closed component (Petersen).
    const auto partner = pair_triangles(contour.positions, contour.triangles);
    for (std::size_t f = 0; f < partner.size(); ++f) {
      ASSERT_GE(partner[f], 0) << s.name << ": triangle " << f << " unpaired";
      EXPECT_EQ(partner[static_cast<std::size_t>(partner[f])], static_cast<std::int64_t>(f));
    }
  }
}

TEST(TopologyContour, FormulasAloneGiveTheRightTopology) {
  for (const Shape& s : {kTorus, kDoubleTorus, kTwoSpheres}) {
    const auto surface = typed(s);
    const auto& F = dynamic_cast<const ImplicitSurface&>(*surface);
    ContourBaseInfo info;
    const Mesh48 base = make_contour_base_mesh(F, {}, &info);
    EXPECT_EQ(info.unpaired, 0u) << s.name;
    expect_closed_manifold(base, s, "base mesh");
    // Every base vertex on F = 0, every face facing outwards (along grad F).
    for (const Vertex v : base.live_vertices()) {
      Vec3 g;
      const double f = F.value_gradient(base.position(v), g);
      EXPECT_LT(std::abs(f) / g.norm(), 1e-8) << s.name;
    }
    for (const Face f : base.live_faces()) {
      const auto v = base.vertices(f);
      const Vec3 &a = base.position(v[0]), &b = base.position(v[1]), &c = base.position(v[2]);
      Vec3 g;
      F.value_gradient((a + b + c) / 3, g);
      EXPECT_GT((b - a).cross(c - a).dot(g), 0) << s.name << ": a base face faces inwards";
    }

    // Through the scene (no base mesh given) and the adapter.
    AdaptOptions o;
    o.threshold = 0.008;
    o.epsilon = 0.002;
    Adapter adapter(*surface, o, default_criteria("expr", 0.0, o, 0.0));
    adapter.initialize();
    expect_closed_manifold(adapter.mesh(), s, "adapted");
    const auto dense = test::dense_error(adapter.mesh(), *surface, 20 * o.density, 7);
    EXPECT_LE(dense.max_error, (o.threshold + o.epsilon) * 1.10)
        << s.name << ": dense error at (" << dense.worst.transpose() << ")";
    RecordProperty(s.name + "_base_triangles", static_cast<int>(base.n_faces()));
    RecordProperty(s.name + "_adapted_triangles", static_cast<int>(adapter.mesh().n_faces()));
  }
}

}  // namespace
}  // namespace dynamesh
