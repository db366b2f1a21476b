// SampleStore (core/adapt/sample_store.h): samples are points of the surface that follow
// splits and welds. On a flat mesh whose split vertices stay at edge midpoints, carrying a
// sample into a child or back into the parent must leave its position in space unchanged,
// however the store lays its ranges out (in place, appended, compacted).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "core/adapt/criteria.h"
#include "core/adapt/sample_store.h"
#include "core/mesh/spatial_order.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

std::vector<Vec3> world_points(const Mesh48& mesh, const SampleStore& store) {
  std::vector<Vec3> points;
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    store.for_each_sample(f, [&](const Vec3& b, double) {
      points.push_back(b[0] * mesh.position(v[0]) + b[1] * mesh.position(v[1]) +
                       b[2] * mesh.position(v[2]));
    });
  }
  std::sort(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

TEST(SampleStore, SamplesKeepTheirPlaceThroughSplitsWeldsAndCompaction) {
  // sinc at t = 0 is the flat square y = 0: split vertices at midpoints stay on it.
  const std::unique_ptr<Surface> surface = make_scene("sinc");
  surface->set_time(0.0);
  const SurfaceProbe probe(*surface);
  Mesh48 mesh = surface->base_mesh();
  // Dense enough that no child falls below the minimum (which would draw a fresh pattern).
  SampleStore store(40000.0, 5);
  mesh.add_listener(&store);
  store.reset(mesh);
  const std::vector<Vec3> before = world_points(mesh, store);
  ASSERT_GT(before.size(), 1000u);

  std::mt19937 rng(3);
  int splits = 0, welds = 0;
  for (int op = 0; op < 3000; ++op) {
    if (rng() % 2 == 0) {
      const std::vector<Face> faces = mesh.live_faces();
      const Face f = faces[rng() % faces.size()];
      // Only faces whose children will still hold enough samples.
      if (store.count(f) >= 4 * SampleStore::kMinSamplesPerFace && mesh.split(f).is_valid())
        ++splits;
    } else {
      const std::vector<Vertex> vertices = mesh.live_vertices();
      const Vertex v = vertices[rng() % vertices.size()];
      if (mesh.can_weld(v) && mesh.weld(v)) ++welds;
    }
    // Compacted, sibling ranges are no longer adjacent: a weld must then move them.
    if (op % 100 == 0) store.compact();
    if (op % 250 == 0) store.evaluate_all(mesh, probe);
  }
  store.evaluate_all(mesh, probe);
  EXPECT_GT(splits, 300);
  EXPECT_GT(welds, 100);

  std::size_t counted = 0;
  for (Face f : mesh.live_faces()) {
    counted += store.count(f);
    EXPECT_LT(store.face_error(f), 1e-9);  // flat: the samples lie on the surface
  }
  EXPECT_EQ(counted, store.n_samples());
  const std::vector<Vec3> after = world_points(mesh, store);
  ASSERT_EQ(after.size(), before.size());
  // Every sample is where one was at the start (barycentric coordinates are floats: a few
  // float ulps of the unit square). Sorted by x, the match lies within a narrow window.
  constexpr double kTolerance = 1e-5;
  std::size_t unmatched = 0;
  for (const Vec3& p : after) {
    auto it = std::lower_bound(before.begin(), before.end(), p.x() - kTolerance,
                               [](const Vec3& a, double x) { return a.x() < x; });
    bool found = false;
    for (; it != before.end() && it->x() <= p.x() + kTolerance && !found; ++it)
      found = (*it - p).norm() < kTolerance;
    unmatched += !found;
  }
  EXPECT_EQ(unmatched, 0u);
}

// The mean sampled error the step reports (summary()) keeps each face's sum of its samples'
// errors instead of reading every sample: it must still be the mean over the samples, however
// they were measured (some faces, all, again after densifying), split, welded, redrawn,
// compacted and renumbered. Counted here afresh from the samples themselves.
TEST(SampleStore, SummaryIsTheMeanOverEverySample) {
  const std::unique_ptr<Surface> surface = make_scene("sinc");
  surface->set_time(0.37);  // rippled: the samples' errors differ from face to face
  const SurfaceProbe probe(*surface);
  Mesh48 mesh = surface->base_mesh();
  SampleStore store(20000.0, 11);
  mesh.add_listener(&store);
  store.reset(mesh);
  // The interior peak search on, as the adapter sets it, with T + eps the median face's
  // reading: measuring then keeps samples at faces' interior peaks (append_sample).
  for (int level = 0; level < 3; ++level)
    for (Face f : mesh.live_faces())
      if (mesh.is_alive(f)) mesh.split(f);
  store.evaluate_all(mesh, probe);
  std::vector<double> readings;
  for (Face f : mesh.live_faces()) readings.push_back(store.face_error(f));
  std::nth_element(readings.begin(), readings.begin() + readings.size() / 2, readings.end());
  const double limit = readings[readings.size() / 2];
  ASSERT_GT(limit, 0.0);
  store.set_peak_search(0.7 * limit, 1.0 / 0.7 - 1.0, limit);
  auto check = [&](int op) {
    double sum = 0.0;
    std::size_t count = 0;
    for (Face f : mesh.live_faces())
      store.for_each_sample(f, [&](const Vec3&, double error) {
        sum += error;
        ++count;
      });
    const SampleStore::Summary s = store.summary(mesh);
    ASSERT_EQ(s.samples, count) << "after operation " << op;
    const double mean = count ? sum / static_cast<double>(count) : 0.0;
    // The same positive terms added in another order: within a few ulps per term.
    ASSERT_NEAR(s.mean_error, mean, 1e-12 * mean + 1e-300) << "after operation " << op;
  };
  std::mt19937 rng(5);
  std::size_t checked_nonzero = 0;
  for (int op = 0; op < 1500; ++op) {
    const std::vector<Face> faces = mesh.live_faces();
    switch (rng() % 8) {
      case 0:
      case 1:
      case 2: {
        const Face f = faces[rng() % faces.size()];
        if (mesh.depth(f) < 14) mesh.split(f);
        break;
      }
      case 3:
      case 4: {
        const std::vector<Vertex> vertices = mesh.live_vertices();
        const Vertex v = vertices[rng() % vertices.size()];
        if (mesh.can_weld(v)) mesh.weld(v);
        break;
      }
      case 5: {  // some faces measured (densifying where unresolved, keeping interior peaks)
        std::vector<Face> some;
        for (Face f : faces)
          if (rng() % 3 == 0) some.push_back(f);
        store.evaluate_faces(mesh, probe, some);
        break;
      }
      case 6:
        if (rng() % 4 == 0)
          store.evaluate_all(mesh, probe);
        else
          store.compact();
        break;
      default:
        if (rng() % 2) {
          mesh.renumber(spatial_renumbering(mesh));
        } else {  // patterns redrawn for another density
          store.set_density(rng() % 2 ? 5000.0 : 40000.0);
          store.refresh_patterns(mesh);
        }
    }
    check(op);
    checked_nonzero += store.summary(mesh).mean_error > 0.0;
  }
  EXPECT_GT(checked_nonzero, 1000u);  // the check compared real errors, not zeros
}

// refresh_patterns decides most faces on their squared area against the count's limits
// squared (SampleStore::pattern_outdated, a 1e-12 margin) and only the rest on the rounded
// area: its verdicts must be the rule's, count == 0 or 2 count < target or (count > 2 target
// and not densified), target = clamp(round(D * area), 9, 1e6), also for densities that put a
// face's D * area right at a limit (on either side of the rounding's half). A redrawn face
// reads unmeasured, the others keep their measurement.
TEST(SampleStore, PatternRefreshFollowsTheTargetRule) {
  const std::unique_ptr<Surface> surface = make_scene("sinc");
  surface->set_time(0.37);
  const SurfaceProbe probe(*surface);
  Mesh48 mesh = surface->base_mesh();
  std::mt19937 rng(9);
  for (int op = 0; op < 400; ++op) {  // faces of many sizes and shapes
    const std::vector<Face> faces = mesh.live_faces();
    const Face f = faces[rng() % faces.size()];
    if (mesh.depth(f) < 12) mesh.split(f);
  }
  SampleStore store(3000.0, 13);
  mesh.add_listener(&store);
  store.reset(mesh);
  auto area = [&](Face f) {
    const auto v = mesh.vertices(f);
    const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    return 0.5 * (b - a).cross(c - a).norm();
  };
  std::size_t redrawn = 0, kept = 0, at_limit = 0;
  store.evaluate_all(mesh, probe);  // every face measured (some densified)
  for (int trial = 0; trial < 60; ++trial) {
    const std::vector<Face> faces = mesh.live_faces();
    // A density that puts one face's D * area at a limit of its count: 2 count + 0.5 (the
    // target rounds to 2 count + 1, or stays at 2 count just below), or count / 2 - 0.5.
    // Not a density that would draw millions of samples.
    Face pick;
    double limit = 0.0;
    do {
      pick = faces[rng() % faces.size()];
      const double n = store.count(pick);
      limit = trial % 2 ? 2.0 * n + 0.5 : std::max(n / 2.0 - 0.5, 1.0);
    } while (limit / area(pick) > 10000.0 || limit / area(pick) < 250.0);
    const double nudge = std::ldexp(1.0, -50) * static_cast<double>(int(rng() % 5) - 2);
    store.set_density(limit / area(pick) * (1.0 + nudge));
    std::vector<std::uint8_t> expected;
    std::vector<std::uint32_t> count_before;
    for (Face f : faces) {
      count_before.push_back(store.count(f));
      const double target = std::clamp(std::round(store.density() * area(f)),
                                       double{SampleStore::kMinSamplesPerFace}, 1e6);
      const double count = store.count(f);
      expected.push_back(count == 0 || 2 * count < target ||
                         (count > 2 * target && !store.densified(f)));
      const double x = store.density() * area(f);
      at_limit +=
          std::abs(x - (2 * count + 0.5)) < 1e-9 * x || std::abs(2 * x + 1 - count) < 1e-9 * x;
    }
    store.refresh_patterns(mesh);
    for (std::size_t i = 0; i < faces.size(); ++i) {
      ASSERT_EQ(!store.measured(faces[i]), expected[i] != 0)
          << "trial " << trial << ", face " << faces[i].idx << ": " << count_before[i]
          << " samples, D * area " << store.density() * area(faces[i]);
      redrawn += expected[i];
      kept += !expected[i];
    }
    std::vector<Face> unmeasured;  // measured again, so that every face starts measured
    for (Face f : faces)
      if (!store.measured(f)) unmeasured.push_back(f);
    store.evaluate_faces(mesh, probe, unmeasured);
  }
  EXPECT_GT(redrawn, 100u);
  EXPECT_GT(kept, 1000u);
  EXPECT_GE(at_limit, 30u);  // the densities did put faces at the limits
}

// A mesh that needed many samples and then few (the sphere growing to R = 9 and back) does
// not keep the peak's buffers: after compaction each holds at most kReleaseFactor times the
// live samples (the default sphere kept 115 MB of them at R = 0.6, where it needs 0.2 MB).
TEST(SampleStore, BuffersShrinkWithTheSamples) {
  const std::unique_ptr<Surface> surface = make_scene("sinc");
  surface->set_time(0.0);
  const SurfaceProbe probe(*surface);
  Mesh48 mesh = surface->base_mesh();
  for (int level = 0; level < 4; ++level)
    for (Face f : mesh.live_faces())
      if (mesh.is_alive(f)) mesh.split(f);
  SampleStore store(400000.0, 7);  // ~1.6M samples on the 2 x 2 square
  mesh.add_listener(&store);
  store.reset(mesh);
  store.evaluate_all(mesh, probe);
  const std::size_t peak = store.n_samples();
  ASSERT_GT(peak, 1000000u);
  EXPECT_GE(store.held_samples(), peak);
  // Far fewer samples: every pattern is redrawn sparser, the old ranges become garbage.
  store.set_density(2000.0);
  EXPECT_EQ(store.refresh_patterns(mesh), mesh.n_faces());
  store.compact();
  const std::size_t live = store.n_samples();
  EXPECT_LT(live, peak / 10);  // 9 samples per face at least
  EXPECT_LE(store.held_samples(),
            2 * SampleStore::kReleaseFactor * std::max(live, SampleStore::kReleaseFloor));
  // The samples are intact: every face holds its pattern, and measuring still works.
  std::size_t counted = 0;
  for (Face f : mesh.live_faces()) counted += store.count(f);
  EXPECT_EQ(counted, live);
  store.evaluate_all(mesh, probe);
  for (Face f : mesh.live_faces()) EXPECT_LT(store.face_error(f), 1e-9);  // flat at t = 0
  // And the pool grows again when the samples do.
  store.set_density(400000.0);
  store.refresh_patterns(mesh);
  store.compact();
  EXPECT_GT(store.n_samples(), 1000000u);
}

TEST(GeometricErrorCriterion, WeldCeilingBoundsEveryAllowedWeld) {
  const GeometricErrorCriterion c(1e-3, 2.5e-4);
  const Mesh48 mesh;
  const DiamondChange plan;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 2e-3);
  int allowed = 0;
  for (int i = 0; i < 20000; ++i) {
    const double error = u(rng), current = u(rng);
    const WeldQuery q{mesh, plan, error, current};
    if (!c.allows_weld(q)) continue;
    ++allowed;
    EXPECT_LE(error, c.weld_error_ceiling(current)) << error << " " << current;
  }
  EXPECT_GT(allowed, 1000);
  // And the bound is tight: just above it, never allowed.
  for (double current : {0.0, 5e-4, 9e-4, 1.1e-3, 2e-3}) {
    const double ceiling = c.weld_error_ceiling(current);
    EXPECT_FALSE(c.allows_weld({mesh, plan, ceiling * (1 + 1e-9) + 1e-15, current}));
  }
}

// The adapter asks no criterion about a face reading at or below the criteria's split floor
// (Adapter::split_error_floor): that is sound only if no error there asks for a split.
TEST(GeometricErrorCriterion, SplitFloorBoundsEveryRequestedSplit) {
  const GeometricErrorCriterion c(1e-3, 2.5e-4);
  const Mesh48 mesh;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 2e-3);
  for (const bool initial : {false, true}) {
    const double floor = c.split_error_floor(initial);
    auto urgency = [&](double error) { return c.split_urgency({mesh, Face(), error, initial}); };
    int asked = 0;
    for (int i = 0; i < 20000; ++i) {
      const double error = u(rng);
      if (urgency(error) <= 1.0) continue;
      ++asked;
      EXPECT_GT(error, floor) << error << " initial " << initial;
    }
    EXPECT_GT(asked, 1000);
    // At the floor no split, and the next double up asks for one: the floor is the bound itself.
    EXPECT_LE(urgency(floor), 1.0);
    EXPECT_GT(urgency(std::nextafter(floor, 1.0)), 1.0);
  }
  EXPECT_EQ(c.split_error_floor(false), 1e-3 + 2.5e-4);
  EXPECT_EQ(c.split_error_floor(true), 1e-3);
  // A criterion restricted to a half-space asks for nothing outside it: its inner floor holds.
  const HalfSpaceCriterion half(std::make_unique<GeometricErrorCriterion>(1e-3, 2.5e-4),
                                Vec3::UnitX(), 0.0);
  EXPECT_EQ(half.split_error_floor(false), c.split_error_floor(false));
  // An edge length asks for splits whatever the error.
  EXPECT_EQ(EdgeLengthCriterion(0.1).split_error_floor(false),
            -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace dynamesh
