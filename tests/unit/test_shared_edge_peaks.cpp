// SampleStore's shared edge peaks (sample_store.h, evaluate_faces): within one pass an edge's
// peak is evaluated once and read by the face across it. The reading must be what that face
// finds measured alone, to the bit, and a slot filled in one pass must not be read in the next
// (after the vertices moved, or a split or weld gave its halfedge id to another edge).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/adapt/adapter.h"
#include "core/adapt/sample_store.h"
#include "core/mesh/base_meshes.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

// Every face whose model reads above this has its edges searched: as many shared edges as
// the mesh has.
constexpr double kSearchAll = 1e-12;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// `shared` and `alone` (which evaluates every face's edges itself) measure every face in one
// pass each (the same patterns: both stores saw the same operations in the same order, and
// densify alike). Returns how many faces read differently.
int faces_reading_otherwise(const Mesh48& mesh, const SurfaceProbe& probe, SampleStore& shared,
                            SampleStore& alone) {
  shared.evaluate_all(mesh, probe);
  alone.evaluate_all(mesh, probe);
  int differ = 0;
  for (Face f : mesh.live_faces())
    if (!same_bits(shared.face_error(f), alone.face_error(f))) ++differ;
  return differ;
}

class SharedEdgePeaks : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedEdgePeaks, EachFaceReadsWhatItFindsAloneInEveryPass) {
  const std::string scene = GetParam();
  std::unique_ptr<Surface> surface = make_scene(scene);
  surface->set_time(scene == "sinc" ? 0.3 : 0.5);
  AdaptOptions o;
  o.threshold = scene == "sinc" ? 6e-4 : 2e-3;
  o.epsilon = o.threshold / 4;
  Adapter adapter(*surface, o, default_criteria(scene, 0.0, o, 0.0));
  adapter.initialize();
  Mesh48 mesh = adapter.mesh();
  mesh.clear_listeners();
  const SurfaceProbe probe(*surface);
  SampleStore shared(o.density, 3), alone(o.density, 3);
  alone.share_edge_peaks(false);
  for (SampleStore* s : {&shared, &alone}) {
    s->set_peak_search(kSearchAll, 0.3);
    s->reset(mesh);
    mesh.add_listener(s);
  }
  ASSERT_GT(mesh.n_faces(), 1000u);
  // Nearly every interior edge is read once from its slot (1.5 edges per face).
  std::uint64_t before = shared.edge_peaks_shared();
  EXPECT_EQ(faces_reading_otherwise(mesh, probe, shared, alone), 0);
  EXPECT_GT(shared.edge_peaks_shared() - before, mesh.n_faces());

  // A new pass after the surface moved: last pass's slots hold other values.
  surface->set_time(0.53);
  for (Vertex v : mesh.live_vertices()) probe.project_vertex(mesh, v);
  before = shared.edge_peaks_shared();
  EXPECT_EQ(faces_reading_otherwise(mesh, probe, shared, alone), 0);
  EXPECT_GT(shared.edge_peaks_shared() - before, mesh.n_faces());

  // Splits and welds: halfedge ids now name other edges (a face slot freed by a weld is
  // taken by the next split).
  std::mt19937 rng(11);
  int splits = 0, welds = 0;
  for (int op = 0; op < 600; ++op) {
    if (op % 3 != 0) {
      const std::vector<Face> faces = mesh.live_faces();
      const Vertex v = mesh.split(faces[rng() % faces.size()]);
      if (v.is_valid()) {
        probe.project_vertex(mesh, v);
        ++splits;
      }
    } else {
      const std::vector<Vertex> vertices = mesh.live_vertices();
      const Vertex v = vertices[rng() % vertices.size()];
      if (mesh.can_weld(v) && mesh.weld(v)) ++welds;
    }
  }
  EXPECT_GT(splits, 300);
  EXPECT_GT(welds, 20);
  before = shared.edge_peaks_shared();
  EXPECT_EQ(faces_reading_otherwise(mesh, probe, shared, alone), 0);
  EXPECT_GT(shared.edge_peaks_shared() - before, mesh.n_faces());
}

INSTANTIATE_TEST_SUITE_P(SampleStore, SharedEdgePeaks,
                         ::testing::Values("twist", "capsule-bend", "sinc"), [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// F = |x|^8 - 1: the first-order distance F / |grad F| overstates the distance inside the
// unit sphere, so SurfaceProbe caps it at a corner's distance (signed_distance_in_triangle),
// and with a corner close to an edge that cap depends on the face.
class OctticSphere final : public ImplicitSurface {
 public:
  std::string name() const override { return "octic-sphere"; }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3::Constant(-1.0));
    box.extend(Vec3::Constant(1.0));
    return box;
  }
  // Large: the probe's first-order limit (0.02 of it) then covers every point here.
  double length_scale() const override { return 100.0; }
  Mesh48 base_mesh() const override { return Mesh48(); }
  double value(const Vec3& p) const override { return std::pow(p.squaredNorm(), 4) - 1.0; }
  double value_gradient(const Vec3& p, Vec3& gradient) const override {
    gradient = 8.0 * std::pow(p.squaredNorm(), 3) * p;
    return value(p);
  }
};

// Two triangles on an edge (a, b) just inside the unit sphere: a wide one, and a thin one
// whose apex is the sphere's point just above the edge's midpoint. Measured alone, the wide
// face reads the edge's first-order distance (0.080 at its midpoint); the thin one reads it
// capped near its apex at the apex's distance (0.063): it must not take the wide face's peak
// for that edge (b is off the sphere so that the edge's readings are not symmetric: a tie in
// the lattice is not shared either).
TEST(SampleStore, SharedEdgePeakNotTakenWhereTheCapDependsOnTheFace) {
  const OctticSphere surface;
  const SurfaceProbe probe(surface);
  // (No coordinate zero at both ends: such an edge is not shared, zero_at_both_ends.)
  const Vec3 a = Vec3(std::sin(-0.3), 0.05, std::cos(-0.3)).normalized(),
             b = 0.998 * Vec3(std::sin(0.415), -0.03, std::cos(0.415)).normalized();
  const Vec3 midpoint = 0.5 * (a + b);
  const std::vector<Vec3> positions = {Vec3(0.0, -0.6, 0.8), a, b, midpoint.normalized()};
  // The wide face first: it fills the edge's slot, the thin one comes to read it.
  Mesh48 mesh = Mesh48::from_base_triangles(positions, std::vector<Vec2>(4, Vec2::Zero()),
                                            {{0, 1, 2}, {3, 2, 1}});
  SampleStore shared(2000.0, 5), alone(2000.0, 5);
  alone.share_edge_peaks(false);
  for (SampleStore* s : {&shared, &alone}) {
    s->set_peak_search(kSearchAll, 0.3);
    s->reset(mesh);
  }
  const Face wide(0), thin(1);
  shared.evaluate_all(mesh, probe);
  alone.evaluate_all(mesh, probe);
  // The test means something: the thin face alone reads less than the edge's midpoint, where
  // the wide face reads at least the first-order distance.
  const double r = midpoint.norm();
  const double first_order = (1.0 - std::pow(r, 8)) / (8.0 * std::pow(r, 7));
  EXPECT_GT(alone.face_error(wide), first_order);
  EXPECT_LT(alone.face_error(thin), first_order);
  EXPECT_TRUE(same_bits(shared.face_error(wide), alone.face_error(wide)));
  EXPECT_TRUE(same_bits(shared.face_error(thin), alone.face_error(thin)));
}

}  // namespace
}  // namespace dynamesh
