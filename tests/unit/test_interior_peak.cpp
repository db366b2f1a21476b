// SampleStore's interior peak (sample_store.h, evaluate_faces): where the residual is not
// quadratic over a face, the model fitted to its 3 x 3 stratified samples can peak inside the
// face well below the residual there; the store measures where the model peaks and keeps that
// point as a sample. Judged against an independent dense lattice of the surface's positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/adapt/error_model.h"
#include "core/adapt/sample_store.h"
#include "core/mesh/base_meshes.h"

namespace dynamesh {
namespace {

// z = A (3 (u v + v w + w u))^2 over the unit right triangle, w = 1 - u - v: a dome that
// vanishes at the triangle's corners and peaks at its centroid (A), quartic in the barycentric
// coordinates, so the flat triangle's residual is not quadratic over it. Its edges read at
// most 0.5625 A (their midpoints): only the interior holds the peak.
class QuarticDome final : public ParametricSurface {
 public:
  static constexpr double kAmplitude = 0.01;
  std::string name() const override { return "quartic-dome"; }
  ParameterDomain domain() const override { return ParameterDomain{}; }
  Vec3 position(const Vec2& uv) const override {
    const double u = uv.x(), v = uv.y(), w = 1.0 - u - v;
    const double q = 3.0 * (u * v + v * w + w * u);
    return {u, v, kAmplitude * q * q};
  }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3(0.0, 0.0, 0.0));
    box.extend(Vec3(1.0, 1.0, kAmplitude));
    return box;
  }
  Mesh48 base_mesh() const override { return make_grid_mesh(1, 1, Vec2(0, 0), Vec2(1, 1)); }
};

// The largest |x(b) - S(uv(b))| over a barycentric lattice of order n, from positions only.
double lattice_error(const QuarticDome& s, const Vec2 (&uv)[3], int n, bool edges_only) {
  double worst = 0.0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      if (edges_only && i != 0 && j != 0 && i + j != n) continue;
      const double b1 = static_cast<double>(i) / n, b2 = static_cast<double>(j) / n;
      const double b0 = 1.0 - b1 - b2;
      const Vec3 x = b0 * s.position(uv[0]) + b1 * s.position(uv[1]) + b2 * s.position(uv[2]);
      worst = std::max(worst, (x - s.position(b0 * uv[0] + b1 * uv[1] + b2 * uv[2])).norm());
    }
  return worst;
}

// The dome's one face: the unit right triangle in (u, v), its corners on the surface.
struct DomeFace {
  Vec2 uv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  Vec3 p[3];
  Mesh48 mesh;
  explicit DomeFace(const QuarticDome& s)
      : p{s.position(uv[0]), s.position(uv[1]), s.position(uv[2])},
        mesh(Mesh48::from_base_triangles({p[0], p[1], p[2]}, {uv[0], uv[1], uv[2]},
                                         {{{0, 1, 2}}})) {}
};

TEST(InteriorPeak, FaceWhoseModelUnderReadsItsInteriorIsMeasuredWhereTheModelPeaks) {
  const QuarticDome surface;
  const SurfaceProbe probe(surface);
  const DomeFace face(surface);
  const auto& uv = face.uv;
  const Mesh48& mesh = face.mesh;
  const double dense = lattice_error(surface, uv, 300, false);
  const double edges = lattice_error(surface, uv, 300, true);
  ASSERT_NEAR(dense, QuarticDome::kAmplitude, 1e-6);
  int under_read = 0, caught = 0;
  double worst = 1.0;
  for (std::uint64_t seed = 1; seed <= 32; ++seed) {
    // 9 samples (3 x 3) on the face, and the adapter's peak search for a face whose true
    // error is T + eps (kPeakSearchBand = 0.7 of it, adapter.cpp).
    SampleStore store(9.0 / 0.5, seed);
    store.set_peak_search(0.7 * dense, 1.0 / 0.7 - 1.0);
    store.reset(mesh);
    ASSERT_EQ(store.count(Face(0)), 9u);
    store.evaluate_all(mesh, probe);
    // What the stratified pattern alone can read: its samples' quadratic model, or the
    // edges' true maximum (an upper bound of their peaks' reading). The kept sample, if any,
    // is the tenth.
    QuadraticErrorModel pattern;
    int k = 0;
    store.for_each_sample(Face(0), [&](const Vec3& b, double) {
      if (k++ < 9) pattern.add(b, probe.residual_at(face.p, uv, b));
    });
    const QuadraticErrorModel::Result fit = pattern.evaluate();
    ASSERT_TRUE(fit.resolved) << "seed " << seed;
    const bool under = std::max(fit.error, edges) < 0.9 * dense;
    under_read += under;
    const double reading = store.face_error(Face(0)) / dense;
    worst = std::min(worst, reading);
    caught += under && reading >= 0.9;
    EXPECT_GE(reading, 0.9) << "seed " << seed << ": 3 x 3 alone "
                            << std::max(fit.error, edges) / dense;
  }
  // Not vacuous: the 3 x 3 pattern alone under-reads the peak by more than 10% for several
  // seeds (7 of 32 when written; 10 with patterns keyed on the face's position).
  EXPECT_GE(under_read, 4);
  std::printf(
      "under-read by > 10%% without the interior peak: %d of 32 seeds, caught %d; worst "
      "reading %.3f of the dense maximum\n",
      under_read, caught, worst);
}

// The peak is looked for only at measurements both sampling modes make (sample_store.h,
// on_turn): the face's first after its samples changed, or one on its turn in the rotation. A
// face that comes to read in the search band between its turns keeps its samples until its turn,
// and then looks once. (With the peak looked for at the first measurement in the band, as
// before, predictive sampling had to measure every face that could cross into it.)
TEST(InteriorPeak, LookedForOnlyAtTheFirstMeasurementOrOnTheFacesTurn) {
  const QuarticDome surface;
  const DomeFace face(surface);
  const double dense = lattice_error(surface, face.uv, 300, false);
  const SurfaceProbe probe(surface);
  int kept = 0;
  for (std::uint64_t seed = 1; seed <= 32; ++seed) {
    SampleStore store(9.0 / 0.5, seed);
    store.reset(face.mesh);
    store.set_step(1);  // face 0's turn is step 0 (mod kRotation)
    store.evaluate_all(face.mesh,
                       probe);  // its first measurement, with no search: nothing looked for
    store.set_peak_search(0.7 * dense, 1.0 / 0.7 - 1.0);  // now it reads in the search band
    for (std::uint64_t step = 1; step < SampleStore::kRotation; ++step) {
      store.set_step(step);
      store.evaluate_all(face.mesh, probe);
      ASSERT_EQ(store.count(Face(0)), 9u) << "seed " << seed << ", step " << step;
    }
    store.set_step(SampleStore::kRotation);  // its turn
    store.evaluate_all(face.mesh, probe);
    const std::uint32_t after_turn = store.count(Face(0));
    kept += after_turn == 10;
    store.set_step(2 * SampleStore::kRotation);  // its next turn: looked for once only
    store.evaluate_all(face.mesh, probe);
    EXPECT_EQ(store.count(Face(0)), after_turn) << "seed " << seed;
  }
  // Not vacuous: on its turn the face kept a peak for several seeds (those whose 3 x 3 pattern
  // under-reads it, InteriorPeak above).
  EXPECT_GE(kept, 4);
  std::printf("a peak kept on the face's turn for %d of 32 seeds, none before it\n", kept);
}

}  // namespace
}  // namespace dynamesh
