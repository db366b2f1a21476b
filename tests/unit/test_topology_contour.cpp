// Initial meshes of any genus from F alone (issue 16, item 1): a torus, a genus-2 double
// torus and two separate spheres typed as formulas, without --base-mesh, come out closed,
// oriented manifolds with the right Euler characteristic and number of components (measured
// from the triangle list and, independently, from a flood-filled voxel grid of F < 0), adapted
// within the error bound measured densely.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "core/adapt/adapter.h"
#include "core/mesh/mesh48.h"
#include "core/surface/expression/implicit_expression_surface.h"
#include "core/surface/scene_registry.h"
#include "core/topology/contour_base_mesh.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/topology_events.h"
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

// A patch's triangles (a disk) need not have a perfect matching: a triangle with an ear on
// each edge leaves two ears single whatever the matching, and two such centres side by side
// leave two ears three triangles apart. pair_triangles_mending pairs them all by flips or
// splits; the patch stays an oriented manifold disk with the same border and area.
TEST(TopologyContour, MendedPairingPairsDisksWithoutAPerfectMatching) {
  using Tri = std::array<std::uint32_t, 3>;
  struct Disk {
    std::string name;
    std::vector<Vec3> positions;
    std::vector<Tri> triangles;
  };
  const auto v = [](double x, double y) { return Vec3(x, y, 0); };
  const std::vector<Disk> disks = {
      {"star",
       {v(0, 0), v(1, 0), v(0.5, 0.87), v(0.5, -0.6), v(1.2, 0.8), v(-0.2, 0.8)},
       {{0, 1, 2}, {1, 0, 3}, {2, 1, 4}, {0, 2, 5}}},
      {"two stars",
       {v(0, 0), v(1, 0), v(1, 1), v(0, 1), v(0.5, -0.5), v(-0.5, 0.5), v(1.5, 0.5), v(0.5, 1.5)},
       {{0, 1, 2}, {0, 2, 3}, {1, 0, 4}, {0, 3, 5}, {2, 1, 6}, {3, 2, 7}}}};
  const auto signed_area = [](const std::vector<Vec3>& p, const Tri& t) {
    return 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).z();
  };
  const auto border = [](const std::vector<Tri>& triangles) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> directed, open;
    for (const Tri& t : triangles)
      for (int i = 0; i < 3; ++i) {
        const bool fresh = directed.emplace(t[i], t[(i + 1) % 3]).second;
        EXPECT_TRUE(fresh) << "an edge used twice in one direction";
      }
    for (const auto& [a, b] : directed)
      if (!directed.count({b, a})) open.emplace(a, b);
    return open;
  };
  for (const Disk& disk : disks) {
    // The plain maximum matching leaves two triangles single.
    const auto plain = pair_triangles(disk.positions, disk.triangles);
    EXPECT_EQ(std::count(plain.begin(), plain.end(), -1), 2) << disk.name;

    std::vector<Vec3> positions = disk.positions;
    std::vector<Tri> triangles = disk.triangles;
    std::vector<char> exempt(triangles.size(), 0);
    PairingMendOptions options;
    options.split_point = [](const Vec3& a, const Vec3& b) { return 0.5 * (a + b); };
    options.acceptable = [&](const std::vector<Vec3>& p, const Tri& t) {
      return signed_area(p, t) > 1e-9;
    };
    const MendedPairing mended = pair_triangles_mending(positions, triangles, exempt, options);
    ASSERT_TRUE(mended.complete) << disk.name;
    EXPECT_GT(mended.flips + mended.splits, 0) << disk.name;
    ASSERT_EQ(mended.partner.size(), triangles.size());
    for (std::size_t f = 0; f < triangles.size(); ++f) {
      ASSERT_GE(mended.partner[f], 0) << disk.name << ": triangle " << f;
      EXPECT_EQ(mended.partner[static_cast<std::size_t>(mended.partner[f])],
                static_cast<std::int64_t>(f));
    }
    EXPECT_NO_THROW(refinement_edge_first(triangles, mended.partner)) << disk.name;
    double area = 0, area_before = 0;
    for (const Tri& t : triangles) {
      EXPECT_GT(signed_area(positions, t), 0) << disk.name << ": a triangle turned over";
      area += signed_area(positions, t);
    }
    for (const Tri& t : disk.triangles) area_before += signed_area(disk.positions, t);
    EXPECT_NEAR(area, area_before, 1e-12) << disk.name;
    // The split vertices lie on interior edges: the border is the same chain of edges.
    EXPECT_EQ(border(triangles), border(disk.triangles)) << disk.name;
  }
}

}  // namespace
}  // namespace dynamesh

namespace dynamesh {
namespace {

// Just after a split the two new tips are closer than the grid's cells, and the contour of
// F = 0 on the grid may still join them (issue 16: wide blobs along (1, 1, 0), s^2 = 0.35,
// split at t = 0.85203; a re-base there was refined without end). The contour of F = level,
// the level from TopologyMonitor::clear_level, has the two components F has.
TEST(TopologyContour, ContourClearOfTheCriticalPointsSeparatesTipsCloserThanACell) {
  const std::string at = "(0.3+0.8*(2*t-1)^2)";
  const auto blob = [&](const std::string& sign) {
    return "exp(-((x" + sign + "0.70710678*" + at + ")^2+(y" + sign + "0.70710678*" + at +
           ")^2+z^2)/0.35)";
  };
  auto surface = make_scene(
      "expr", {},
      {{"implicit", "0.5 - " + blob("-") + " - " + blob("+")}, {"bounds", "-2,-2,-1.5,2,2,1.5"}});
  auto& F = dynamic_cast<ImplicitSurface&>(*surface);
  const double split = 0.5 + 0.5 * std::sqrt((std::sqrt(0.35 * std::log(4.0)) - 0.3) / 0.8);
  F.set_time(split + 3e-4);
  const test::SolidTopology truth =
      test::solid_topology([&](const Vec3& p) { return F.value(p); }, F.bounds(), 400);
  ASSERT_EQ(truth.components, 2);
  TopologyMonitor monitor;
  monitor.reset(F, Mesh48());
  ContourBaseOptions o;  // 24 cells along the longest side, as a re-base's first try
  const MeshTopologySummary plain = summarize_topology(make_contour_base_mesh(F, o));
  EXPECT_EQ(plain.components, 1) << "the plain contour no longer joins the tips: pick a time "
                                    "closer to the split";
  const Box3 box = F.bounds();
  const double diagonal = make_contour_grid(box, box.size().maxCoeff() / 24).spacing().norm();
  const std::optional<double> level = monitor.clear_level(diagonal, 0.25);
  ASSERT_TRUE(level.has_value());
  EXPECT_LT(*level, 0.0);  // the saddle is outside: a smaller inside
  o.level = *level;
  const Mesh48 mesh = make_contour_base_mesh(F, o);
  const MeshTopologySummary cleared = summarize_topology(mesh);
  EXPECT_EQ(cleared.components, 2);
  EXPECT_EQ(cleared.euler, 4);
  const test::MeshValidity v = test::check_mesh_validity(mesh);
  EXPECT_TRUE(v.embedded_closed_manifold()) << v.describe();
}

}  // namespace
}  // namespace dynamesh
