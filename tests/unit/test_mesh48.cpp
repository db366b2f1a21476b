// Tests of the 4-8 mesh: construction, uniform refinement counts, split/weld inverse,
// long random operation sequences, and carrying points through bisections — checked
// against closed forms and measurements from the plain triangle list.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "core/mesh/base_meshes.h"
#include "core/mesh/bisection_map.h"
#include "core/mesh/mesh48.h"
#include "mesh_measure.h"
#include "tests/support/random_renumbering.h"

namespace dynamesh {
namespace {

using test::topology;

Mesh48 icosahedron() {
  const double p = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                         {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> t = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return make_48_mesh(v, {}, t);
}

// An irregular open disk: a jittered hexagonal patch of the plane y = 0.
Mesh48 irregular_disk() {
  std::vector<Vec3> v = {{0, 0, 0}};
  std::vector<std::array<std::uint32_t, 3>> t;
  for (int i = 0; i < 7; ++i) {
    const double a = 2 * M_PI * i / 7;
    v.emplace_back(std::cos(a) * (1 + 0.2 * (i % 3)), 0, std::sin(a));
  }
  for (int i = 0; i < 7; ++i)
    t.push_back(
        {0, static_cast<std::uint32_t>(1 + (i + 1) % 7), static_cast<std::uint32_t>(1 + i)});
  return make_48_mesh(v, {}, t);
}

// Splits every face of the current (uniform) depth once: doubles the face count.
void refine_uniformly(Mesh48& mesh) {
  const int depth = mesh.depth(mesh.live_faces().front());
  for (Face f : mesh.live_faces())
    if (mesh.is_alive(f) && mesh.depth(f) == depth) mesh.split(f);
}

TEST(Mesh48, GridHasExpectedCountsAndBoundary) {
  const Mesh48 mesh = make_grid_mesh(4, 3, Vec2(-1, -1), Vec2(1, 2));
  ASSERT_TRUE(mesh.check().ok()) << mesh.check().summary();
  const auto t = topology(mesh);
  EXPECT_EQ(t.vertices, 5 * 4);
  EXPECT_EQ(t.faces, 4 * 3 * 2);
  EXPECT_EQ(t.boundary_edges, 2 * (4 + 3));
  EXPECT_EQ(t.euler(), 1);
  EXPECT_NEAR(test::boundary_length(mesh), 2 * (2 + 3), 1e-12);
  EXPECT_NEAR(test::total_area(mesh), 2 * 3, 1e-12);
  for (Face f : mesh.live_faces())  // counter-clockwise in (u, v) = (x, z): normal along -y
    EXPECT_LT(test::face_area_vector(
                  mesh, {mesh.vertex(f, 0).idx, mesh.vertex(f, 1).idx, mesh.vertex(f, 2).idx})
                  .y(),
              0);
}

TEST(Mesh48, BoxIsClosedOutwardAndExact) {
  Box3 box;
  box.extend(Vec3(-1, -0.5, -0.25));
  box.extend(Vec3(2, 0.5, 0.75));
  const Mesh48 mesh = make_box_mesh(box, {3, 2, 1});
  ASSERT_TRUE(mesh.check().ok()) << mesh.check().summary();
  const auto t = topology(mesh);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.euler(), 2);
  EXPECT_EQ(t.faces, 2 * 2 * (3 * 2 + 2 * 1 + 3 * 1));
  EXPECT_NEAR(test::enclosed_volume(mesh), 3.0 * 1.0 * 1.0, 1e-12);
  EXPECT_NEAR(test::total_area(mesh), 2 * (3 * 1 + 3 * 1 + 1 * 1), 1e-12);
}

TEST(Mesh48, VelhoConstructionMakesAnyTriangleMesh48) {
  const Mesh48 ico = icosahedron();
  ASSERT_TRUE(ico.check().ok()) << ico.check().summary();
  EXPECT_EQ(topology(ico).euler(), 2);
  EXPECT_EQ(topology(ico).boundary_edges, 0);
  const double edge = 2.0, ico_area = 20 * std::sqrt(3.0) / 4 * edge * edge;
  EXPECT_NEAR(test::total_area(ico), ico_area, 1e-9);  // new vertices lie in old faces
  // 20 faces: a pair of faces becomes 4, an unpaired face 3, so F = 60 - 2 * pairs, and the
  // greedy pairing of an icosahedron (a perfect matching has 10 pairs) finds most pairs.
  const long n = topology(ico).faces;
  EXPECT_EQ(n % 2, 0);
  EXPECT_GE(n, 40);
  EXPECT_LE(n, 46);

  const Mesh48 disk = irregular_disk();
  ASSERT_TRUE(disk.check().ok()) << disk.check().summary();
  EXPECT_EQ(topology(disk).euler(), 1);
  EXPECT_EQ(topology(disk).boundary_edges, 7);
}

TEST(Mesh48, RejectsBrokenBaseMeshes) {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  // Three triangles on one edge: non-manifold.
  EXPECT_THROW(make_48_mesh(p, {}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), std::invalid_argument);
  // Two triangles with opposite orientation across their shared edge.
  EXPECT_THROW(make_48_mesh(p, {}, {{0, 1, 2}, {0, 1, 3}}), std::invalid_argument);
  // Index out of range.
  EXPECT_THROW(make_48_mesh(p, {}, {{0, 1, 7}}), std::invalid_argument);
  // Not a triangulated quadrangulation: the refinement edges (1,2) and (0,3) are not shared.
  EXPECT_THROW(Mesh48::from_base_triangles(p, {}, {{0, 1, 2}, {1, 0, 3}}), std::invalid_argument);
  // A vertex nobody uses.
  EXPECT_THROW(Mesh48::from_base_triangles(p, {}, {{0, 1, 2}}), std::invalid_argument);
}

// Closed forms for L uniform rounds: F = F0 2^L. Closed: V = 2 + F / 2 (Euler, E = 3F/2).
// Open grid: boundary edges double every second round (the first round splits only quad
// diagonals), B = B0 2^floor(L/2), and V = 1 + (F + B) / 2.
TEST(Mesh48, UniformRefinementMatchesClosedForms) {
  Box3 cube;
  cube.extend(Vec3(-1, -1, -1));
  cube.extend(Vec3(1, 1, 1));
  Mesh48 box = make_box_mesh(cube, {2, 2, 2});
  Mesh48 grid = make_grid_mesh(3, 2, Vec2(0, 0), Vec2(3, 2));
  const long box_f0 = topology(box).faces, grid_f0 = topology(grid).faces;
  const long grid_b0 = topology(grid).boundary_edges;
  for (int level = 1; level <= 8; ++level) {
    refine_uniformly(box);
    refine_uniformly(grid);
    const long f_box = box_f0 << level, f_grid = grid_f0 << level;
    const long b_grid = grid_b0 << (level / 2);
    const auto tb = topology(box), tg = topology(grid);
    EXPECT_EQ(tb.faces, f_box);
    EXPECT_EQ(tb.vertices, 2 + f_box / 2);
    EXPECT_EQ(tg.faces, f_grid);
    EXPECT_EQ(tg.boundary_edges, b_grid);
    EXPECT_EQ(tg.vertices, 1 + (f_grid + b_grid) / 2);
    EXPECT_EQ(static_cast<long>(box.n_faces()), f_box);
    EXPECT_EQ(static_cast<long>(grid.n_vertices()), tg.vertices);
  }
  ASSERT_TRUE(box.check().ok()) << box.check().summary();
  ASSERT_TRUE(grid.check().ok()) << grid.check().summary();
  EXPECT_NEAR(test::enclosed_volume(box), 8.0, 1e-9);
  EXPECT_NEAR(test::total_area(grid), 6.0, 1e-9);
  // After an even number of rounds the interior is the regular 4-8 pattern.
  for (Vertex v : grid.live_vertices())
    if (!grid.is_boundary(v)) {
      EXPECT_TRUE(grid.valence(v) == 4 || grid.valence(v) == 8);
    }
}

TEST(Mesh48, SplitThenWeldRestoresConnectivityExactly) {
  Mesh48 mesh = make_grid_mesh(4, 4, Vec2(0, 0), Vec2(1, 1));
  std::mt19937 rng(7);
  // Grow an irregular adaptive mesh first.
  for (int i = 0; i < 400; ++i) {
    const auto faces = mesh.live_faces();
    mesh.split(faces[rng() % faces.size()]);
  }
  ASSERT_TRUE(mesh.check().ok());
  int cascades = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto before = test::face_set(mesh);
    std::set<std::uint32_t> existed;
    for (const auto& t : before) existed.insert(t.begin(), t.end());
    const std::size_t n_vertices = mesh.n_vertices();
    const auto faces = mesh.live_faces();
    const Vertex m = mesh.split(faces[rng() % faces.size()]);
    cascades += mesh.n_vertices() - n_vertices > 1;
    ASSERT_TRUE(mesh.weld(m)) << "a freshly split vertex must be weldable";
    // Vertices of forced splits weld back, finest first.
    for (std::size_t guard = 0; mesh.n_vertices() > n_vertices; ++guard) {
      ASSERT_LT(guard, 64u) << "forced split vertices cannot be welded back";
      for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (!existed.count(v) && mesh.is_alive(Vertex(v)) && mesh.weld(Vertex(v))) break;
    }
    EXPECT_EQ(test::face_set(mesh), before) << "trial " << trial;
    ASSERT_TRUE(mesh.check().ok()) << mesh.check().summary();
  }
  EXPECT_GT(cascades, 0) << "the trials never exercised a forced (recursive) split";
}

// Random interleavings of splits and welds. `check_every_op` is the debug variant.
void random_operations(Mesh48 mesh, int operations, std::size_t face_cap, bool check_every_op,
                       unsigned seed) {
  const auto t0 = topology(mesh);
  const double length0 = test::boundary_length(mesh);
  const double area0 = test::total_area(mesh);
  std::mt19937 rng(seed);
  int splits = 0, welds = 0;
  for (int op = 0; op < operations; ++op) {
    const bool want_split = mesh.n_faces() < face_cap && (rng() % 100) < 55;
    if (want_split) {
      Face f;
      do f = Face(static_cast<std::uint32_t>(rng() % mesh.face_capacity()));
      while (!mesh.is_alive(f));
      mesh.split(f);
      ++splits;
    } else {
      for (int attempt = 0; attempt < 64; ++attempt) {
        const Vertex v(static_cast<std::uint32_t>(rng() % mesh.vertex_capacity()));
        if (mesh.is_alive(v) && mesh.weld(v)) {
          ++welds;
          break;
        }
      }
    }
    if (check_every_op) {
      const CheckReport report = mesh.check();
      ASSERT_TRUE(report.ok()) << "after operation " << op << ": " << report.summary();
    }
  }
  const CheckReport report = mesh.check();
  ASSERT_TRUE(report.ok()) << report.summary();
  const auto t = topology(mesh);
  EXPECT_EQ(t.euler(), t0.euler());
  EXPECT_NEAR(test::boundary_length(mesh), length0, 1e-9 * (1 + length0));
  EXPECT_NEAR(test::total_area(mesh), area0, 1e-9 * area0);
  EXPECT_EQ(static_cast<long>(mesh.n_faces()), t.faces);
  EXPECT_EQ(static_cast<long>(mesh.n_vertices()), t.vertices);
  EXPECT_GT(splits, operations / 4);
  EXPECT_GT(welds, operations / 8);
}

Mesh48 unit_box() {
  Box3 cube;
  cube.extend(Vec3(-1, -1, -1));
  cube.extend(Vec3(1, 1, 1));
  return make_box_mesh(cube, {2, 2, 2});
}

TEST(Mesh48RandomOps, GridCheckedAfterEveryOperation) {
  random_operations(make_grid_mesh(3, 3, Vec2(0, 0), Vec2(1, 1)), 100000, 400, true, 1);
}
TEST(Mesh48RandomOps, BoxCheckedAfterEveryOperation) {
  random_operations(unit_box(), 100000, 400, true, 2);
}
TEST(Mesh48RandomOps, IrregularCheckedAfterEveryOperation) {
  random_operations(icosahedron(), 100000, 400, true, 3);
}
TEST(Mesh48RandomOps, GridLargeCheckedAtEnd) {
  random_operations(make_grid_mesh(8, 8, Vec2(0, 0), Vec2(1, 1)), 100000, 20000, false, 4);
}
TEST(Mesh48RandomOps, BoxLargeCheckedAtEnd) {
  random_operations(unit_box(), 100000, 20000, false, 5);
}
TEST(Mesh48RandomOps, IrregularLargeCheckedAtEnd) {
  random_operations(irregular_disk(), 100000, 20000, false, 6);
}

// A listener that carries points (face, barycentric) through every split and weld using
// the records' documented layout. On a flat grid split vertices sit exactly at midpoints,
// so a carried point must keep its position.
class PointCarrier : public MeshListener {
 public:
  struct Point {
    Face face;
    Vec3 bary;
  };
  std::vector<Point> points;

  void after_split(Mesh48&, const DiamondChange& change) override {
    for (Point& p : points)
      for (int h = 0; h < change.count; ++h)
        if (p.face == change.halves[h].parent) {
          const int child = bisection_child(p.bary);
          p.bary = to_child_coordinates(p.bary, child);
          p.face = change.halves[h].children[child];
          break;
        }
  }
  void after_weld(Mesh48&, const DiamondChange& change) override {
    for (Point& p : points)
      for (int h = 0; h < change.count; ++h)
        for (int child = 0; child < 2; ++child)
          if (p.face == change.halves[h].children[child]) {
            p.bary = to_parent_coordinates(p.bary, child);
            p.face = change.halves[h].parent;
            child = 2;
            h = change.count;
          }
  }
  void after_renumber(Mesh48&, const Renumbering& r) override {
    for (Point& p : points) p.face = Face(r.face[p.face.idx]);
  }
};

Vec3 position_of(const Mesh48& mesh, const PointCarrier::Point& p) {
  const auto v = mesh.vertices(p.face);
  return p.bary[0] * mesh.position(v[0]) + p.bary[1] * mesh.position(v[1]) +
         p.bary[2] * mesh.position(v[2]);
}

TEST(Mesh48, ListenerRecordsCarryPointsExactly) {
  Mesh48 mesh = make_grid_mesh(3, 3, Vec2(0, 0), Vec2(1, 1));
  PointCarrier carrier;
  mesh.add_listener(&carrier);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> original;
  for (Face f : mesh.live_faces())
    for (int k = 0; k < 20; ++k) {
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      carrier.points.push_back({f, Vec3(1 - a - b, a, b)});
      original.push_back(position_of(mesh, carrier.points.back()));
    }
  for (int op = 0; op < 20000; ++op) {
    if (rng() % 2 == 0 && mesh.n_faces() < 3000) {
      Face f;
      do f = Face(static_cast<std::uint32_t>(rng() % mesh.face_capacity()));
      while (!mesh.is_alive(f));
      mesh.split(f);
    } else {
      const Vertex v(static_cast<std::uint32_t>(rng() % mesh.vertex_capacity()));
      if (mesh.is_alive(v)) mesh.weld(v);
    }
    // Renumberings move every face: the points follow through after_renumber.
    if (op % 5000 == 4999) mesh.renumber(random_renumbering(mesh, rng));
  }
  for (std::size_t i = 0; i < carrier.points.size(); ++i) {
    const auto& p = carrier.points[i];
    ASSERT_TRUE(mesh.is_alive(p.face));
    EXPECT_NEAR(p.bary.sum(), 1.0, 1e-12);
    EXPECT_GE(p.bary.minCoeff(), -1e-12);
    EXPECT_LT((position_of(mesh, p) - original[i]).norm(), 1e-12);
  }
  mesh.remove_listener(&carrier);
}

TEST(Mesh48, SplitBornVertexLevelsAndParents) {
  Mesh48 mesh = make_grid_mesh(2, 2, Vec2(0, 0), Vec2(1, 1));
  const Face f = mesh.live_faces()[0];
  const auto [apex, a, b] = mesh.vertices(f);
  const Vertex m = mesh.split(f);
  EXPECT_FALSE(mesh.is_base(m));
  EXPECT_EQ(mesh.parents(m)[0], a);
  EXPECT_EQ(mesh.parents(m)[1], b);
  EXPECT_EQ(mesh.level(m), 1);
  EXPECT_TRUE(mesh.can_weld(m));
  EXPECT_LT((mesh.position(m) - 0.5 * (mesh.position(a) + mesh.position(b))).norm(), 1e-15);
  EXPECT_FALSE(mesh.can_weld(apex));  // base vertices never weld
  EXPECT_FALSE(mesh.weld(apex));
}

}  // namespace
}  // namespace dynamesh

namespace dynamesh {
namespace {

// Repeatedly splitting the newest corner drives one region to the depth limit; there split
// refuses (invalid handle, mesh unchanged) instead of overflowing the face depth.
TEST(Mesh48, SplitStopsAtTheDepthLimit) {
  Mesh48 mesh = make_grid_mesh(1, 1, Vec2(0, 0), Vec2(1, 1));
  Face f = mesh.live_faces().front();
  int refused_at = -1;
  for (int i = 0; i < 400 && refused_at < 0; ++i) {
    const Vertex v = mesh.split(f);
    if (!v.is_valid()) {
      refused_at = mesh.depth(f);
      break;
    }
    f = mesh.corner(v).face;  // a child of the split, one level deeper
  }
  EXPECT_EQ(refused_at, Mesh48::kMaxDepth);
  EXPECT_TRUE(mesh.check().ok()) << mesh.check().summary();
}

}  // namespace
}  // namespace dynamesh
