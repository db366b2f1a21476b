// A mesh re-based from F's contour mid-run (Adapter::rebuild_from_base, issue 16) is tested for
// crossing itself before its frame is published: it used to be published unchecked. When it
// crosses there is nothing left to fall back on, and the step says so (repair_refusals, which
// the CLI prints on stderr) instead of handing out a wrong frame silently.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/adapt/adapter.h"
#include "core/adapt/criteria.h"
#include "core/topology/contour_base_mesh.h"
#include "tests/support/mesh_validity.h"

namespace dynamesh {
namespace {

// The blobs, F = 0.5 - g(p - c1) - g(p - c2), g(q) = exp(-|q|^2 / 0.25), c1,2 = (-+a, 0,
// 0), a(t) = 0.2 + 0.8 (2t - 1)^2 (split at t = 0.849), with (when `left_only`) the left blob
// alone, and a base mesh that after the split is the left blob's contour twice, the second copy
// moved by 0.01 along x: two pieces, the topology the split asks for, crossing each other.
class BlobsWithCrossedBase final : public ImplicitSurface {
 public:
  explicit BlobsWithCrossedBase(bool left_only = false) : left_only_(left_only) {}
  std::string name() const override { return "blobs-crossed-base"; }
  Box3 bounds() const override { return Box3(Vec3(-1.8, -0.8, -0.8), Vec3(1.8, 0.8, 0.8)); }
  bool may_change_topology() const override { return true; }
  double value_gradient(const Vec3& p, Vec3& g) const override {
    const double a = 0.2 + 0.8 * (2 * time() - 1) * (2 * time() - 1);
    double f = 0.5;
    g = Vec3::Zero();
    for (const double side : {-1.0, 1.0}) {
      if (left_only_ && side > 0) continue;
      const Vec3 q = p - Vec3(side * a, 0, 0);
      const double e = std::exp(-q.squaredNorm() / 0.25);
      f -= e;
      g += e * 2.0 * q / 0.25;
    }
    return f;
  }
  double value(const Vec3& p) const override {
    Vec3 g;
    return value_gradient(p, g);
  }
  Mesh48 base_mesh() const override {
    if (left_only_ || time() < 0.8) return make_contour_base_mesh(*this);
    BlobsWithCrossedBase left(true);
    left.set_time(time());
    const Mesh48 one = make_contour_base_mesh(left);
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> id(one.vertex_capacity(), kInvalidIndex);
    for (const Vertex v : one.live_vertices()) {
      id[v.idx] = static_cast<std::uint32_t>(positions.size());
      positions.push_back(one.position(v));
    }
    const std::uint32_t n = static_cast<std::uint32_t>(positions.size());
    for (std::uint32_t i = 0; i < n; ++i) positions.push_back(positions[i] + Vec3(0.01, 0, 0));
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (const std::uint32_t offset : {0u, n})
      for (const Face f : one.live_faces()) {
        const auto c = one.vertices(f);
        triangles.push_back({id[c[0].idx] + offset, id[c[1].idx] + offset, id[c[2].idx] + offset});
      }
    return Mesh48::from_base_triangles(std::move(positions), {}, triangles);
  }

 private:
  bool left_only_;
};

TEST(RebuildCrossings, ARebasedMeshThatCrossesItselfIsReported) {
  BlobsWithCrossedBase surface;
  AdaptOptions options;
  options.local_topology_repair = false;  // the split is re-based
  surface.set_time(0.5);
  Adapter adapter(surface, options, default_criteria("expr", 0.5, options, 0.0));
  adapter.initialize();
  int rebuilt = 0;
  for (int k = 1; k <= 4; ++k) {
    const StepStats& s = adapter.step(0.5 + 0.125 * k);
    if (!s.rebuilt) continue;
    ++rebuilt;
    const test::MeshValidity v = test::check_mesh_validity(adapter.mesh());
    ASSERT_FALSE(v.embedded_closed_manifold()) << "the crossed base was undone: " << v.describe();
    bool said = false;
    for (const std::string& why : s.repair_refusals)
      said = said || why.find("crosses itself") != std::string::npos;
    EXPECT_TRUE(said) << "step " << k << ": " << v.describe();
  }
  EXPECT_EQ(rebuilt, 1);
}

}  // namespace
}  // namespace dynamesh
