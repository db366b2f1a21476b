// Mesh48::renumber and the spatial order (core/mesh/renumbering.h, spatial_order.h): the
// geometry and connectivity after a renumbering are those before, mapped through it, element
// for element; bad renumberings are refused; the spatial order makes faces' corners close.
#include <gtest/gtest.h>

#include <random>

#include "core/mesh/base_meshes.h"
#include "core/mesh/mesh48.h"
#include "core/mesh/spatial_order.h"
#include "tests/support/random_renumbering.h"

namespace dynamesh {
namespace {

// A graded 4-8 mesh with scattered ids: random splits and welds of a flat grid (the grid's
// vertices lifted onto a bump, so positions are not all in one plane).
Mesh48 scattered_mesh(std::size_t faces, std::uint32_t seed) {
  Mesh48 mesh = make_grid_mesh(16, 16, Vec2(0, 0), Vec2(1, 1));
  std::mt19937 rng(seed);
  while (mesh.n_faces() < faces) {
    Face f;
    do f = Face(static_cast<std::uint32_t>(rng() % mesh.face_capacity()));
    while (!mesh.is_alive(f));
    mesh.split(f);
  }
  // Welds free slots in the middle of the arrays (a renumbering compacts them away).
  for (std::size_t i = 0; i < faces / 4; ++i)
    mesh.weld(Vertex(static_cast<std::uint32_t>(rng() % mesh.vertex_capacity())));
  for (Vertex v : mesh.live_vertices()) {
    Vec3& p = mesh.position(v);
    p.z() = std::sin(3 * p.x()) * std::cos(2 * p.y());
  }
  return mesh;
}

// Every element of `after` is the element of `before` that `r` sends to it, with its
// references mapped: vertices, twins, depth, positions and uvs bit for bit, lineage.
void expect_mapped(const Mesh48& before, const Mesh48& after, const Renumbering& r,
                   bool compacted = true) {
  ASSERT_EQ(after.n_faces(), before.n_faces());
  ASSERT_EQ(after.n_vertices(), before.n_vertices());
  if (compacted) {  // no free slot left
    EXPECT_EQ(after.face_capacity(), after.n_faces());
    EXPECT_EQ(after.vertex_capacity(), after.n_vertices());
  }
  for (const Face f : before.live_faces()) {
    const Face g(r.face[f.idx]);
    ASSERT_TRUE(after.is_alive(g));
    EXPECT_EQ(after.depth(g), before.depth(f));
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(after.vertex(g, i).idx, r.vertex[before.vertex(f, i).idx]);
      const Halfedge t = before.twin(Halfedge(f, i));
      const Halfedge u = after.twin(Halfedge(g, i));
      if (!t.is_valid()) {
        EXPECT_FALSE(u.is_valid());
      } else {
        EXPECT_EQ(u.face().idx, r.face[t.face().idx]);
        EXPECT_EQ(u.local(), t.local());
      }
    }
  }
  for (const Vertex v : before.live_vertices()) {
    const Vertex w(r.vertex[v.idx]);
    ASSERT_TRUE(after.is_alive(w));
    EXPECT_EQ(after.position(w), before.position(v));
    EXPECT_EQ(after.uv(w), before.uv(v));
    EXPECT_EQ(after.level(w), before.level(v));
    EXPECT_EQ(after.is_base(w), before.is_base(v));
    if (!before.is_base(v)) {
      EXPECT_EQ(after.parents(w)[0].idx, r.vertex[before.parents(v)[0].idx]);
      EXPECT_EQ(after.parents(w)[1].idx, r.vertex[before.parents(v)[1].idx]);
    }
    EXPECT_EQ(after.valence(w), before.valence(v));
    EXPECT_EQ(after.can_weld(w), before.can_weld(v));
  }
  EXPECT_TRUE(after.check().ok()) << after.check().summary();
}

TEST(Renumbering, SpatialOrderKeepsGeometryAndConnectivityExactly) {
  const Mesh48 before = scattered_mesh(30000, 3);
  ASSERT_TRUE(before.check().ok());
  ASSERT_GT(before.face_capacity(), before.n_faces());  // has free slots to compact
  Mesh48 after = before;
  const Renumbering r = spatial_renumbering(after);
  after.renumber(r);
  expect_mapped(before, after, r);
}

TEST(Renumbering, RandomOrderKeepsGeometryAndConnectivityExactly) {
  const Mesh48 before = scattered_mesh(8000, 5);
  Mesh48 after = before;
  std::mt19937 rng(7);
  const Renumbering r = random_renumbering(after, rng);
  after.renumber(r);
  expect_mapped(before, after, r);
  // The renumbered mesh goes on splitting and welding like any other.
  for (int i = 0; i < 2000; ++i) {
    const Face f(static_cast<std::uint32_t>(rng() % after.face_capacity()));
    if (after.is_alive(f)) after.split(f);
    after.weld(Vertex(static_cast<std::uint32_t>(rng() % after.vertex_capacity())));
  }
  EXPECT_TRUE(after.check().ok()) << after.check().summary();
}

TEST(Renumbering, RefusesWhatIsNotABijectionOfTheLiveElements) {
  const Mesh48 before = scattered_mesh(2000, 9);
  ASSERT_GT(before.face_capacity(), before.n_faces());
  Mesh48 mesh = before;
  std::mt19937 rng(1);
  const Renumbering good = random_renumbering(mesh, rng);
  Renumbering twice = good;  // two faces sent to one id
  const std::vector<Face> live = mesh.live_faces();
  twice.face[live[1].idx] = twice.face[live[0].idx];
  Renumbering dead = good;  // a dead slot given an id
  for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f)
    if (!mesh.is_alive(Face(f))) {
      dead.face[f] = 0;
      break;
    }
  Renumbering short_list = good;
  short_list.vertex.pop_back();
  Renumbering out_of_range = good;
  out_of_range.vertex[mesh.live_vertices()[0].idx] = static_cast<std::uint32_t>(mesh.n_vertices());
  for (const Renumbering* bad : {&twice, &dead, &short_list, &out_of_range}) {
    EXPECT_THROW(mesh.renumber(*bad), std::invalid_argument);
    expect_mapped(
        before, mesh,
        [&] {  // unchanged: the identity on the live elements
          Renumbering id;
          id.vertex.assign(before.vertex_capacity(), kInvalidIndex);
          id.face.assign(before.face_capacity(), kInvalidIndex);
          for (Vertex v : before.live_vertices()) id.vertex[v.idx] = v.idx;
          for (Face f : before.live_faces()) id.face[f.idx] = f.idx;
          return id;
        }(),
        false);
  }
}

// The spatial order puts a face's corners close together; scattered_face_share sees it.
TEST(Renumbering, SpatialOrderGathersCorners) {
  Mesh48 mesh = scattered_mesh(60000, 11);
  const double before = scattered_face_share(mesh);
  std::mt19937 rng(2);
  mesh.renumber(random_renumbering(mesh, rng));
  const double shuffled = scattered_face_share(mesh);
  mesh.renumber(spatial_renumbering(mesh));
  const double spatial = scattered_face_share(mesh);
  // Mean spread of corner ids, over every face (not the sampled estimate).
  double spread = 0;
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    spread += std::max({v[0].idx, v[1].idx, v[2].idx}) - std::min({v[0].idx, v[1].idx, v[2].idx});
  }
  spread /= static_cast<double>(mesh.n_faces());
  EXPECT_GT(before, 0.2);
  EXPECT_GT(shuffled, 0.9);
  EXPECT_LT(spatial, 0.05);
  EXPECT_LT(spread, 500.0);
  RecordProperty("scattered_before", std::to_string(before));
  RecordProperty("scattered_spatial", std::to_string(spatial));
  RecordProperty("mean_spread", std::to_string(spread));
  std::printf("scattered share: split order %.3f, shuffled %.3f, spatial %.4f; spread %.1f\n",
              before, shuffled, spatial, spread);
}

}  // namespace
}  // namespace dynamesh
