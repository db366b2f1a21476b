// Mesh48::replace_region's rule across the border of the hole (issue 16, local repair): the
// new faces must keep the 4-8 depth relation with the old ones, or a later split breaks it.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/mesh/base_meshes.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {
namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

Mesh48 cube() {
  return make_box_mesh(Box3{Vec3(-1, -1, -1), Vec3(1, 1, 1)}, {2, 2, 2});
}

// Replaces `faces` by the same triangles (newest vertex first, as stored) at `depths`.
void refill(Mesh48& mesh, const std::vector<Face>& faces, const std::vector<int>& depths,
            bool rotate = false) {
  std::vector<Vertex> existing;
  Triangles triangles;
  for (const Face f : faces) {
    std::array<std::uint32_t, 3> t{};
    const auto v = mesh.vertices(f);
    for (int i = 0; i < 3; ++i) {
      const Vertex corner = v[(i + (rotate ? 1 : 0)) % 3];
      std::uint32_t k = 0;
      while (k < existing.size() && existing[k].idx != corner.idx) ++k;
      if (k == existing.size()) existing.push_back(corner);
      t[i] = k;
    }
    triangles.push_back(t);
  }
  mesh.replace_region(faces, existing, {}, triangles, depths);
}

TEST(Mesh48Surgery, LegsAcrossTheBorderJoinFacesAlikeDeep) {
  Mesh48 mesh = cube();
  const Face f = mesh.live_faces().front(), pair = mesh.neighbor(f, 0);
  ASSERT_TRUE(mesh.is_paired(f));
  const std::size_t faces = mesh.n_faces();
  // The diamond's legs border base faces (depth 0): refilled one level deeper, a later split
  // would break the 4-8 rule, so it is refused and the mesh left as it was.
  EXPECT_THROW(refill(mesh, {f, pair}, {1, 1}), std::logic_error);
  EXPECT_EQ(mesh.n_faces(), faces);
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
  refill(mesh, {f, pair}, {0, 0});
  EXPECT_EQ(mesh.n_faces(), faces);
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
}

TEST(Mesh48Surgery, AHalfDiamondSitsOnTheLegOfAFaceOneBisectionCoarser) {
  Mesh48 mesh = cube();
  const Vertex m = mesh.split(mesh.live_faces().front());
  ASSERT_TRUE(m.is_valid());
  // A child of the split: its refinement edge is a base face's leg (depth 0), its legs are
  // shared with other children (depth 1).
  Face child;
  for (const Face f : mesh.live_faces())
    if (mesh.depth(f) == 1 && !mesh.is_paired(f)) child = f;
  ASSERT_TRUE(child.is_valid());
  EXPECT_THROW(refill(mesh, {child}, {0}), std::logic_error);        // too coarse
  EXPECT_THROW(refill(mesh, {child}, {2}), std::logic_error);        // too deep
  EXPECT_THROW(refill(mesh, {child}, {1}, true), std::logic_error);  // refinement edge a leg
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
  refill(mesh, {child}, {1});
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
  // And the 4-8 rule holds through the splits that follow.
  for (int round = 0; round < 3; ++round)
    for (const Face f : mesh.live_faces())
      if (mesh.is_alive(f) && mesh.depth(f) <= round + 1) mesh.split(f);
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
}

}  // namespace
}  // namespace dynamesh
