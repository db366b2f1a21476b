// Where a split puts its new vertex on an implicit surface when Newton from the edge's midpoint
// slides sideways (SurfaceProbe::project_split_vertex): down the diamond's normal line to F,
// but only to a place where the new faces face up grad F. Two closed-form shapes, each a diamond
// of edge 2 on z = 0 whose refinement edge runs from (-1, 0, 0) to (1, 0, 0) across a feature
// 0.9 wide and 1.5 deep centred just off its midpoint:
//  - a pit in the ground z <= 0: the midpoint is above the pit, its nearest point on a wall;
//    the normal line meets the pit's floor, facing up: the vertex goes down there (the rule's
//    purpose: an edge bridging a crease gets shorter);
//  - a thin wall edge-on (a gyrus seen from its end), infinitely tall, ending 1.5 below: the
//    midpoint is inside it, its nearest point on a side; the normal line runs inside the wall
//    and leaves it through the wall's far end, F's other sheet, facing down. A vertex put there
//    turned all 4 of its faces over (Colin27 swept in 4 steps with the projection's tolerance
//    at 0.9e-10: such a landing 14.8 mm away, 7.50 mm read against T + eps = 0.625).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/adapt/surface_probe.h"
#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {
namespace {

constexpr double kHalfWidth = 0.45, kDepth = 1.5;
const Vec3 kCentre(0.05, 0.02, 0.0);  // of the feature, off the midpoint (0, 0, 0)

// max(z, min(w - max(|x - cx|, |y - cy|), z + D)) (pit) or max(|x - cx| - w, -z - D) (wall),
// positive outside, with its gradient from whichever piece is active.
class Feature final : public ImplicitSurface {
 public:
  explicit Feature(bool pit) : pit_(pit) {}
  std::string name() const override { return pit_ ? "pit" : "wall"; }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3(-2, -2, -2));
    box.extend(Vec3(2, 2, 2));
    return box;
  }
  Mesh48 base_mesh() const override { return Mesh48(); }
  double value(const Vec3& p) const override {
    Vec3 g;
    return value_gradient(p, g);
  }
  double value_gradient(const Vec3& p, Vec3& g) const override {
    const Vec3 q = p - kCentre;
    const double floor = q.z() + kDepth;
    if (!pit_) {
      const double side = std::abs(q.x()) - kHalfWidth;
      if (side >= -floor) {
        g = Vec3(std::copysign(1.0, q.x()), 0, 0);
        return side;
      }
      g = Vec3(0, 0, -1);
      return -floor;
    }
    const bool along_x = std::abs(q.x()) >= std::abs(q.y());
    const double wall = kHalfWidth - std::max(std::abs(q.x()), std::abs(q.y()));
    const double inner = std::min(wall, floor);
    if (q.z() >= inner) {
      g = Vec3(0, 0, 1);
      return q.z();
    }
    if (floor <= wall) {
      g = Vec3(0, 0, 1);
      return floor;
    }
    g = along_x ? Vec3(-std::copysign(1.0, q.x()), 0, 0) : Vec3(0, -std::copysign(1.0, q.y()), 0);
    return wall;
  }

 private:
  bool pit_;
};

// Puts each split vertex by the adapter's rule, and keeps the split's record.
class Placement final : public MeshListener {
 public:
  explicit Placement(const SurfaceProbe& probe) : probe_(probe) {}
  void after_split(Mesh48& mesh, const DiamondChange& c) override {
    probe_.put_split_vertex(mesh, c);
    change = c;
  }
  void after_weld(Mesh48&, const DiamondChange&) override {}
  void after_renumber(Mesh48&, const Renumbering&) override {}
  DiamondChange change;

 private:
  const SurfaceProbe& probe_;
};

struct Split {
  Vec3 vertex;
  int faces_turned = 0;  // of the 4 new faces, those facing against grad F at a corner
};

Split split_the_diamond(const ImplicitSurface& surface) {
  // Corners a, b (the refinement edge) and the apexes c, d; both faces face +z.
  std::vector<Vec3> positions = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  const std::vector<std::array<std::uint32_t, 3>> triangles = {{2, 1, 0}, {3, 0, 1}};
  Mesh48 mesh = Mesh48::from_base_triangles(positions, {}, triangles);
  const SurfaceProbe probe(surface);
  Placement placement(probe);
  mesh.add_listener(&placement);
  const Vertex v = mesh.split(Face(0));
  EXPECT_TRUE(v.is_valid());
  Split s;
  s.vertex = mesh.position(v);
  EXPECT_EQ(placement.change.count, 2);
  for (int h = 0; h < placement.change.count; ++h)
    for (const Face f : placement.change.halves[h].children) {
      const auto c = mesh.vertices(f);
      const Vec3 &p0 = mesh.position(c[0]), &p1 = mesh.position(c[1]), &p2 = mesh.position(c[2]);
      const Vec3 normal = (p1 - p0).cross(p2 - p0);
      bool turned = false;
      for (const Vec3* p : {&p0, &p1, &p2}) {
        Vec3 g;
        surface.value_gradient(*p, g);
        turned |= !(normal.dot(g) > 0);
      }
      s.faces_turned += turned;
    }
  return s;
}

TEST(SplitVertexPlacement, BridgingAPitGoesDownToItsFloor) {
  const Feature pit(true);
  const Split s = split_the_diamond(pit);
  // The floor's point under the midpoint (x and y as the midpoint's: the line is vertical).
  EXPECT_NEAR(s.vertex.x(), 0.0, 1e-9);
  EXPECT_NEAR(s.vertex.y(), 0.0, 1e-9);
  EXPECT_NEAR(s.vertex.z(), -kDepth, 1e-9);
  EXPECT_EQ(s.faces_turned, 0);
}

TEST(SplitVertexPlacement, StraddlingAWallDoesNotGoToItsFarEnd) {
  const Feature wall(false);
  // The line's crossing the rule refuses: the wall's far end under the midpoint, where the
  // new faces turn over.
  EXPECT_NEAR(wall.value(Vec3(0, 0, -kDepth)), 0.0, 1e-12);
  const Split s = split_the_diamond(wall);
  EXPECT_GT(s.vertex.z(), -0.5 * kDepth) << s.vertex.transpose();
  // Newton's point instead: the wall's nearer side, straight across from the midpoint.
  EXPECT_NEAR(s.vertex.x(), kCentre.x() - kHalfWidth, 1e-9);
  EXPECT_NEAR(s.vertex.y(), 0.0, 1e-9);
  EXPECT_NEAR(s.vertex.z(), 0.0, 1e-9);
}

}  // namespace
}  // namespace dynamesh
