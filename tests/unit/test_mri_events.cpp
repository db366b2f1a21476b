// mri topology events from the distance field's fixed critical points (issue 16): checked
// against flood fills of the layers on a grid (an independent count of their pieces), on a
// synthetic dumbbell whose deep layer splits in two, and on Colin27 with its sulci open.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "core/adapt/adapter.h"
#include "core/adapt/criteria.h"
#include "core/geometry/fold_repair.h"
#include "core/surface/expression/triangle_mesh_file.h"
#include "core/surface/volume/mri_base_mesh.h"
#include "core/surface/volume/mri_surface.h"
#include "core/topology/topology_events.h"
#include "dense_error.h"
#include "mri_dumbbell.h"
#include "test_nifti_files.h"
#include "test_volume_fixtures.h"
#include "tests/support/mesh_validity.h"
#include "topology_measure.h"

namespace dynamesh {
namespace {

// Pieces of {D < -depth} among the samples `distance` on a grid of dims (i fastest), 6-connected,
// counting only those of at least `min_cells` cells.
int count_pieces(const std::vector<float>& distance, const std::array<int, 3>& dims, double depth,
                 int min_cells) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<char> seen(distance.size(), 0);
  std::vector<std::size_t> stack;
  int pieces = 0;
  for (std::size_t start = 0; start < distance.size(); ++start) {
    if (seen[start] || !(distance[start] < -depth)) continue;
    seen[start] = 1;
    stack.assign(1, start);
    int cells = 0;
    while (!stack.empty()) {
      const std::size_t q = stack.back();
      stack.pop_back();
      ++cells;
      const int i = static_cast<int>(q % nx), j = static_cast<int>(q / nx % ny),
                k = static_cast<int>(q / (static_cast<std::size_t>(nx) * ny));
      const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (const auto& s : step) {
        const int a = i + s[0], b = j + s[1], c = k + s[2];
        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
        const std::size_t r = (static_cast<std::size_t>(c) * ny + b) * nx + a;
        if (seen[r] || !(distance[r] < -depth)) continue;
        seen[r] = 1;
        stack.push_back(r);
      }
    }
    pieces += cells >= min_cells;
  }
  return pieces;
}

// The surface's D sampled on a box grid of spacing h over its bounds.
struct SampledDistance {
  std::vector<float> values;
  std::array<int, 3> dims{0, 0, 0};
};
SampledDistance sample_distance(const MriSurface& surface, double h) {
  const Box3 box = surface.bounds();
  SampledDistance s;
  for (int a = 0; a < 3; ++a) s.dims[a] = static_cast<int>(std::ceil(box.size()[a] / h)) + 1;
  s.values.reserve(static_cast<std::size_t>(s.dims[0]) * s.dims[1] * s.dims[2]);
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i)
        s.values.push_back(
            static_cast<float>(surface.layers().distance(box.min + h * Vec3(i, j, k))));
  return s;
}

// The depth at which the dumbbell's layer splits, by bisection on a flood fill's piece count.
double flood_fill_split_depth(const MriSurface& surface) {
  const SampledDistance d = sample_distance(surface, 0.25);
  double one = 1.0, two = kDepthMax;
  EXPECT_EQ(count_pieces(d.values, d.dims, one, 1), 1);
  EXPECT_EQ(count_pieces(d.values, d.dims, two, 1), 2);
  while (two - one > 0.01) {
    const double mid = 0.5 * (one + two);
    (count_pieces(d.values, d.dims, mid, 1) >= 2 ? two : one) = mid;
  }
  return 0.5 * (one + two);
}

TEST(MriEvents, DumbbellSplitsWhereTheFloodFillSplits) {
  const auto surface = make_dumbbell(kDepthMax);
  const double reference = flood_fill_split_depth(*surface);
  RecordProperty("flood_fill_split_depth", std::to_string(reference));
  // The closed form: the distance is blurred (sigma 1.5 mm, and the B-spline's 1/3 voxel^2 per
  // axis), which across the neck's axis averages the cone |rho| - r into r less sigma sqrt(pi/2)
  // (the mean of |rho| under a 2-D Gaussian): 5 - 2.01 mm.
  const double sigma = std::sqrt(1.5 * 1.5 + 1.0 / 3.0);
  EXPECT_NEAR(reference, kNeckRadius - sigma * std::sqrt(M_PI / 2), 0.5);

  const FixedCriticalPoints& p = surface->fixed_critical_points(0.5);
  RecordProperty("candidates", std::to_string(p.candidates));
  RecordProperty("kept", std::to_string(p.points.size()));
  // In [0, 8] mm: the neck's saddle, and nothing else (the balls' centres lie deeper).
  ASSERT_EQ(p.points.size(), 1u);
  const CriticalPoint& saddle = p.points.front();
  EXPECT_EQ(saddle.index, 1);
  EXPECT_LT(saddle.position.norm(), 1.0);
  EXPECT_NEAR(-saddle.value, reference, 0.05);
}

TEST(MriEvents, DumbbellRunReportsTheSplitAndFollowsIt) {
  const auto surface = make_dumbbell(kDepthMax);
  const double reference = flood_fill_split_depth(*surface);
  AdaptOptions options;
  options.threshold = 0.5;
  options.epsilon = 0.125;
  options.density = 2.0;  // mri's suggested T and density (mri_scene.h)
  Adapter adapter(*surface, options, default_criteria(MriSurface::kName, 0.0, options, 0.0));
  adapter.initialize();
  EXPECT_EQ(summarize_topology(adapter.mesh()), (MeshTopologySummary{2, 1}));
  const int steps = 16;
  std::vector<TopologyEvent> events;
  for (int s = 1; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const StepStats& stats = adapter.step(t);
    events.insert(events.end(), stats.topology_events.begin(), stats.topology_events.end());
    const double depth = kDepthMax * t;
    const MeshTopologySummary topology = summarize_topology(adapter.mesh());
    // Away from the event (a step's depth), one piece before and two after.
    if (std::abs(depth - reference) > kDepthMax / steps) {
      const bool before = depth < reference;
      EXPECT_EQ(topology, (MeshTopologySummary{before ? 2 : 4, before ? 1 : 2}))
          << "at depth " << depth;
    }
    const test::MeshValidity v = test::check_mesh_validity(adapter.mesh());
    EXPECT_TRUE(v.embedded_closed_manifold()) << "at depth " << depth << ": " << v.describe();
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, TopologyEventKind::kSplit);
  // Within one step of the flood fill's depth.
  EXPECT_NEAR(kDepthMax * events[0].time, reference, kDepthMax / steps);
  EXPECT_LT(events[0].position.norm(), 1.0);
}

// The dumbbell's layers over 8 mm in `steps` steps with the local repair off: what a run does
// with an event it cannot repair locally. A budget of 5,000 triangles stops a runaway refinement
// (the unrepaired split refined without end: >13 minutes and 1.5 GB in step 3).
struct UnrepairedRun {
  std::vector<StepStats> steps;
  MeshTopologySummary topology;
};
// `last`: the last step taken (the whole schedule when 0); `seed`: the sample seed.
UnrepairedRun run_dumbbell_unrepaired(bool rebase, int steps, bool watched = true,
                                      std::uint64_t seed = 1, int last = 0) {
  const auto surface = make_dumbbell(kDepthMax);
  AdaptOptions options;
  options.threshold = 0.5;
  options.epsilon = 0.125;
  options.density = 2.0;
  options.seed = seed;
  options.topology_events = watched;
  options.local_topology_repair = false;
  options.topology_rebase = rebase;
  options.max_triangles = 5'000;
  Adapter adapter(*surface, options, default_criteria(MriSurface::kName, 0.0, options, 0.0));
  adapter.initialize();
  UnrepairedRun run;
  for (int s = 1; s <= (last > 0 ? last : steps); ++s)
    run.steps.push_back(adapter.step(static_cast<double>(s) / steps));
  run.topology = summarize_topology(adapter.mesh());
  return run;
}

// A run that cannot follow the split: every step ends below the budget, and well below it (by
// count: 4,000 triangles, not a timeout: without a hold each step ran into the budget), with
// splits held, and the error the mesh cannot meet reported (above T + eps, where the kept neck
// spans the gap between the lobes); the mesh keeps the neck F no longer has.
void expect_held_and_bounded(const UnrepairedRun& run) {
  ASSERT_EQ(run.steps.size(), 8u);
  std::size_t held = 0, most = 0;
  double worst = 0;
  for (const StepStats& s : run.steps) {
    EXPECT_FALSE(s.budget_hit) << "step " << s.step << ": " << s.triangles << " triangles";
    EXPECT_FALSE(s.sample_budget_hit) << "step " << s.step;
    EXPECT_LT(s.triangles, 4'000u) << "step " << s.step;
    held += s.splits_held;
    most = std::max(most, s.triangles);
    worst = std::max(worst, s.max_error);
  }
  ::testing::Test::RecordProperty("peak_triangles", std::to_string(most));
  ::testing::Test::RecordProperty("worst_error", std::to_string(worst));
  EXPECT_GT(held, 0u);
  EXPECT_GE(run.steps.back().held_depth, 0);
  EXPECT_GT(worst, 0.5 + 0.125);
  EXPECT_EQ(run.topology, (MeshTopologySummary{2, 1}));
}

// The global re-base is the fallback of a layer's event, as of the analytic scenes': the
// dumbbell ends in two pieces (Euler characteristic 4), counted on the mesh.
TEST(MriEvents, DumbbellSplitNotRepairedLocallyIsRebuiltFromTheContour) {
  const UnrepairedRun run = run_dumbbell_unrepaired(/*rebase=*/true, 8);
  std::size_t rebuilds = 0;
  for (const StepStats& s : run.steps) {
    rebuilds += s.rebuilt;
    EXPECT_FALSE(s.budget_hit) << "step " << s.step;
  }
  EXPECT_EQ(rebuilds, 1u);
  EXPECT_EQ(run.topology, (MeshTopologySummary{4, 2}));
}

// Neither repaired nor rebuilt: the run still ends, every step under the triangle budget, the
// splits held from the event on, and the error the mesh cannot meet there is reported, not
// hidden (above T + eps, where the kept neck spans the gap between the lobes).
TEST(MriEvents, DumbbellSplitNeitherRepairedNorRebuiltEndsBounded) {
  const UnrepairedRun run = run_dumbbell_unrepaired(/*rebase=*/false, 8);
  for (const StepStats& s : run.steps) EXPECT_EQ(s.rebuilt, false);
  expect_held_and_bounded(run);
}

// No monitor (events off): nothing says the layer split, and the mesh keeps the neck F no longer
// has. The faces spanning the gap keep their error however often they are split; they are held
// without an event (AdaptOptions::hold_stalled_splits), and the run ends with that error
// reported (2026-11-24: at most 1,820 triangles, max error 13.9 mm). With the faces held only
// within each split pass, the refinement ran into the 5,000-triangle budget in step 3.
TEST(MriEvents, DumbbellSplitUnwatchedEndsBounded) {
  const UnrepairedRun run = run_dumbbell_unrepaired(/*rebase=*/false, 8, /*watched=*/false);
  for (const StepStats& s : run.steps) EXPECT_TRUE(s.topology_events.empty());
  expect_held_and_bounded(run);
}

// The hold must not hang on the sample draw. The faces spanning the dumbbell's gap read about
// the gap's half-width at every depth, a little more or less with each face's samples; when
// any new maximum restarted the count (adapter.cpp, split_pass), seed 1 held at depth 10 and
// 1,426 triangles but seed 3 at depth 13 and 3,566, and seed 4 at depth 16 in the
// 5,000-triangle budget. The step past the split (3 of 8, 3 mm deep) for seeds 1-6:
// every one held, under the budget, at most four levels apart.
TEST(MriEvents, DumbbellUnwatchedHoldsForEverySeed) {
  int shallowest = 1000, deepest = -1;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const UnrepairedRun run =
        run_dumbbell_unrepaired(/*rebase=*/false, 8, /*watched=*/false, seed, /*last=*/3);
    const StepStats& split = run.steps.back();
    std::printf("seed %d: held at depth %d, %zu triangles, %zu splits held\n",
                static_cast<int>(seed), split.held_depth, split.triangles, split.splits_held);
    EXPECT_FALSE(split.budget_hit) << "seed " << seed;
    EXPECT_LT(split.triangles, 2'500u) << "seed " << seed;
    EXPECT_GT(split.splits_held, 0u) << "seed " << seed;
    ASSERT_GE(split.held_depth, 0) << "seed " << seed;
    shallowest = std::min(shallowest, split.held_depth);
    deepest = std::max(deepest, split.held_depth);
  }
  EXPECT_LE(deepest - shallowest, 4);
}

// Through the binary: the dumbbell as a NIfTI file, closing 2 mm (the neck, 10 mm across, stays
// open). The run says how many critical points it watches and reports the split on stderr and
// in the JSON, within one step of the closed form (5 mm less the blur's 2.0 mm, within 0.5 mm
// as in DumbbellSplitsWhereTheFloodFillSplits).
std::filesystem::path write_dumbbell_nifti() {
  const ScalarVolume v = dumbbell_volume();
  std::vector<std::int16_t> values(v.values.begin(), v.values.end());
  const auto path = test::scratch_dir("mri_dumbbell") / "dumbbell.nii.gz";
  nifti_1_header h = test::make_header({72, 36, 36}, DT_INT16, 16);
  test::set_sform(h, v.grid.linear, v.grid.offset);
  test::write_nifti(path, h, values);
  return path;
}

TEST(MriEvents, CliReportsTheDumbbellsSplit) {
  const auto path = write_dumbbell_nifti();
  const int steps = 8;
  const test::CliRun run = test::run_cli(
      {"--scene", "mri", "--volume", path.string(), "--param", "closing=2", "--param",
       "depth_max=" + std::to_string(kDepthMax), "--steps", std::to_string(steps), "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("topology: 1 critical point(s) of F can change the layer's topology"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("topology: split at t="), std::string::npos) << run.err;
  const nlohmann::json& summary = run.json;
  ASSERT_TRUE(summary.is_object()) << run.out;
  ASSERT_EQ(summary["topology_events"].size(), 1u) << run.err;
  const auto& e = summary["topology_events"][0];
  EXPECT_EQ(e["kind"], "split");
  const double sigma = std::sqrt(1.5 * 1.5 + 1.0 / 3.0);
  EXPECT_NEAR(kDepthMax * e["time"].get<double>(), kNeckRadius - sigma * std::sqrt(M_PI / 2),
              0.5 + kDepthMax / steps);
}

// --topology-events off: the same run past the dumbbell's split watches no critical point,
// reports no event and repairs nothing (the split is followed with it on, locally or by a
// re-base); a value other than on or off is one line and status 2; --help names it. Off, the mesh
// keeps the neck F no longer has, and the budget bounds the run (at 4,994 triangles, max error 7.6
// mm, 2026-11-24).
TEST(MriEvents, CliTopologyEventsOffWatchesNothing) {
  const auto path = write_dumbbell_nifti();
  const auto run = [&](const std::string& events) {
    return test::run_cli({"--scene", "mri", "--volume", path.string(), "--param", "closing=2",
                          "--param", "depth_max=" + std::to_string(kDepthMax), "--t1", "0.5",
                          "--steps", "2", "--max-triangles", "5000", "--topology-events", events,
                          "--quiet"});
  };
  const test::CliRun on = run("on"), off = run("off");
  ASSERT_EQ(on.status, 0) << on.err;
  ASSERT_EQ(off.status, 0) << off.err;
  ASSERT_TRUE(on.json.is_object()) << on.out;
  ASSERT_TRUE(off.json.is_object()) << off.out;
  EXPECT_NE(on.err.find("critical point(s) of F can change"), std::string::npos) << on.err;
  EXPECT_NE(on.err.find("topology: split at t="), std::string::npos) << on.err;
  EXPECT_EQ(on.json["topology_events"].size(), 1u) << on.err;
  EXPECT_GE(on.json["local_repairs"].get<int>() + on.json["rebuilds"].get<int>(), 1) << on.err;
  EXPECT_EQ(off.err.find("critical point"), std::string::npos) << off.err;
  EXPECT_EQ(off.err.find(" at t="), std::string::npos) << off.err;
  EXPECT_TRUE(off.json["topology_events"].empty()) << off.err;
  EXPECT_EQ(off.json["local_repairs"], 0) << off.err;
  EXPECT_EQ(off.json["rebuilds"], 0) << off.err;
  const test::CliRun bad = run("maybe");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err, "dynamesh-cli: --topology-events must be on or off, got 'maybe'\n");
  const test::CliRun help = test::run_cli({"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--topology-events on|off"), std::string::npos) << help.out;
}

// mri's suggested T, eps and density (mri_scene.h).
AdaptOptions mri_suggested_options() {
  AdaptOptions options;
  options.threshold = 0.5;
  options.epsilon = 0.125;
  options.density = 2.0;
  return options;
}

// An adapter on `surface` adapted to it at time t0.
std::unique_ptr<Adapter> started_adapter(Surface& surface, const AdaptOptions& options, double t0) {
  surface.set_time(t0);
  auto adapter = std::make_unique<Adapter>(surface, options,
                                           default_criteria(MriSurface::kName, t0, options, 0.0));
  adapter->initialize();
  return adapter;
}

// Is `mesh` an embedded closed manifold with no folded face and no sliver (the fold screen's
// verdicts, fold_repair.h), within the dense error bound, with `expected` pieces and Euler
// characteristic? Judged independently of the adapter's bookkeeping: CGAL's exact test, a dense
// measurement of the distance to F, the topology counted on the triangles.
void expect_embedded_within_bound(const Mesh48& mesh, const Surface& surface,
                                  const AdaptOptions& options, MeshTopologySummary expected,
                                  const std::string& where) {
  const test::MeshValidity v = test::check_mesh_validity(mesh);
  EXPECT_TRUE(v.embedded_closed_manifold()) << where << ": " << v.describe();
  EXPECT_EQ(summarize_topology(mesh), expected) << where;
  std::vector<Face> folded, slivers;
  find_bad_faces(mesh, surface, FoldRepairOptions{}.min_angle_deg, folded, slivers);
  EXPECT_EQ(folded.size(), 0u) << where;
  EXPECT_EQ(slivers.size(), 0u) << where;
  // Every 4th face, as MriAdaptColin27 does (every 8th) to stay fast on a whole brain.
  const auto dense =
      test::dense_error(mesh, surface, 1.0, 29, [](Face f) { return f.idx % 4 == 0; });
  EXPECT_LE(dense.max_error, 1.10 * (options.threshold + options.epsilon))
      << where << ": dense error at (" << dense.worst.transpose() << ")";
  ::testing::Test::RecordProperty(where + "_triangles", std::to_string(mesh.n_faces()));
  ::testing::Test::RecordProperty(where + "_dense_error", std::to_string(dense.max_error));
}

// The dumbbell started 2 mm deep (t0 = 0.25 of 8 mm), before its split at 2.8 mm: its neck
// is thinner than the cuberille's 8 mm cells, and the cuberille, largest piece only, kept one
// lobe and ended in the neck; the first refinement then split there to the mesh's depth limit
// (852 folded faces, max error 1.88 mm), and the split was rebuilt globally (2,504 triangles
// after). The base is now F's contour (it covers both lobes), the first mesh is embedded and
// within the bound, and the split is repaired locally (2026-11-24: 434 triangles at first, 374
// at the end, 0.25 s CPU).
TEST(MriEvents, DumbbellStartedBeforeItsSplitHasBothLobes) {
  const auto surface = make_dumbbell(kDepthMax);
  const AdaptOptions options = mri_suggested_options();
  const auto run = started_adapter(*surface, options, 0.25);
  const Adapter& adapter = *run;
  double low = 0, high = 0;
  for (const Vertex v : adapter.mesh().live_vertices()) {
    low = std::min(low, adapter.mesh().position(v).x());
    high = std::max(high, adapter.mesh().position(v).x());
  }
  // The lobes' far ends lie 28 mm - 2 mm from the centre.
  EXPECT_LT(low, -24.0);
  EXPECT_GT(high, 24.0);
  expect_embedded_within_bound(adapter.mesh(), *surface, options, {2, 1}, "dumbbell_first_mesh");
}

TEST(MriEvents, CliDumbbellStartedBeforeItsSplitIsRepairedLocally) {
  const auto path = write_dumbbell_nifti();
  const auto final_mesh = test::scratch_dir("mri_dumbbell_t0") / "final.ply";
  const test::CliRun run =
      test::run_cli({"--scene", "mri", "--volume", path.string(), "--param", "closing=2", "--param",
                     "depth_max=" + std::to_string(kDepthMax), "--t0", "0.25", "--steps", "8",
                     "--export-final", final_mesh.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(run.json.is_object()) << run.out;
  EXPECT_EQ(run.json["topology_events"].size(), 1u) << run.err;
  EXPECT_EQ(run["local_repairs"], 1) << run.err;
  EXPECT_EQ(run["rebuilds"], 0) << run.err;
  EXPECT_LE(run["worst_max_sample_error"], 0.5 + 0.125) << run.err;
  EXPECT_LT(run["peak_triangles"], 1000) << run.err;
  const test::MeshValidity v = test::check_mesh_validity_of_file(final_mesh.string());
  EXPECT_TRUE(v.embedded_closed_manifold()) << v.describe();
  EXPECT_EQ(v.components, 2);
  EXPECT_EQ(v.euler(), 4);
}

// Colin27's layers from 0 to `depth_max` mm deep, its mask closed by a ball of `closing` mm.
std::unique_ptr<MriSurface> colin27_layers(double closing, double depth_max = 20.0) {
  MriOptions o;
  o.closing_radius_mm = closing;
  o.closing_given = true;
  o.depth_max = depth_max;
  return make_mri_surface(o);
}

// Colin27 with its sulci open (closing 0): every time a flood fill of the layers on a 1 mm grid
// finds more pieces at the next millimetre of depth, a split was reported within that
// millimetre. Layers only shrink with depth, so a piece (of at least 27 cells: smaller ones are
// a lobe's last millimetre) can only become two by a split, never by growing.
TEST(MriEvents, Colin27SplitsAreReportedWhereTheFloodFillSplits) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto surface = colin27_layers(0.0);
  const FixedCriticalPoints& p = surface->fixed_critical_points(0.5);
  RecordProperty("candidates", std::to_string(p.candidates));
  RecordProperty("kept", std::to_string(p.points.size()));
  RecordProperty("seconds_search", std::to_string(surface->layers().timings().critical_points));
  const SampledDistance d = sample_distance(*surface, 1.0);
  int increases = 0;
  int previous = count_pieces(d.values, d.dims, 0.0, 27);
  for (int depth = 1; depth <= 20; ++depth) {
    const int pieces = count_pieces(d.values, d.dims, depth, 27);
    int splits = 0;
    for (const CriticalPoint& cp : p.points)
      splits += cp.index == 1 && -cp.value > depth - 1 && -cp.value <= depth;
    if (pieces > previous) {
      ++increases;
      EXPECT_GE(splits, pieces - previous) << "between " << depth - 1 << " and " << depth << " mm";
    }
    previous = pieces;
  }
  RecordProperty("flood_fill_increases", std::to_string(increases));
  EXPECT_GT(increases, 0);  // the layers do split into lobes
}

// Colin27 with closing 2: its layers enclose a cavity of 1.5 cm^3 on the midline down to 0.81
// mm, where a hole opens into it. The first mesh has the cavity's surface (mri_base_mesh.h:
// the cuberille, largest piece only and its cavities filled, had only the outer one), so the
// mesh is embedded with F's two pieces, and the hole is repaired locally in the step that
// crosses it (until 2026-11-24 the repair found one sheet where the contour had two, failed,
// and the splits were held: 13.8 mm of error 4 mm deep).
TEST(MriEvents, Colin27HoleIntoTheCavityIsRepairedLocally) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto surface = colin27_layers(2.0, 4.0);
  const AdaptOptions options = mri_suggested_options();
  const auto run = started_adapter(*surface, options, 0.0);
  Adapter& adapter = *run;
  expect_embedded_within_bound(adapter.mesh(), *surface, options, {4, 2}, "first_mesh");
  const StepStats& stats = adapter.step(0.25);  // 0 to 1 mm deep
  ASSERT_EQ(stats.topology_events.size(), 1u);
  EXPECT_EQ(stats.topology_events[0].kind, TopologyEventKind::kHoleOpens);
  EXPECT_NEAR(4.0 * stats.topology_events[0].time, 0.81, 0.01);
  EXPECT_EQ(stats.local_repairs, 1u);
  EXPECT_FALSE(stats.rebuilt);
  EXPECT_EQ(stats.splits_held, 0u);
  expect_embedded_within_bound(adapter.mesh(), *surface, options, {2, 1}, "at_1mm");
}

// Where a layer's first mesh starts (mri_start_depth): Colin27's critical points with closing 2
// (0.809, 10.600 and 11.942 mm deep) and 8 mm cells, so nothing within 4 mm of one.
TEST(MriEvents, StartDepthIsClearOfCriticalPointsByHalfACell) {
  std::vector<CriticalPoint> points(3);
  points[0].value = -0.809, points[1].value = -10.6, points[2].value = -11.942;
  EXPECT_EQ(mri_start_depth(points, 0.0), 0.0);
  EXPECT_EQ(mri_start_depth(points, 1.0), 0.0);  // past the hole: from before it
  EXPECT_EQ(mri_start_depth(points, 2.0), 0.0);
  EXPECT_EQ(mri_start_depth(points, 5.0), 5.0);                 // clear: no detour
  EXPECT_DOUBLE_EQ(mri_start_depth(points, 10.0), 10.6 - 4.0);  // a thin wall ahead
  EXPECT_DOUBLE_EQ(mri_start_depth(points, 20.0), 20.0);
  EXPECT_DOUBLE_EQ(mri_start_depth(points, 15.0), 10.6 - 4.0);  // clear of 10.6 and 11.942
  EXPECT_EQ(mri_start_depth({}, 3.0), 3.0);
}

// Colin27 with closing 2 started 1 mm deep, past the hole that opens into the cavity 0.81 mm
// deep (a hole about 1 mm wide, narrower than the base's 8 mm cells). The base covered the
// cavity over, and split vertices next to the hole projected through it onto the cavity's
// wall: the first refinement ran into the triangle budget (main 2a84c07 through the CLI,
// 60,000 triangles, 28 mm of error, 4,310 degenerate triangles). The first mesh is now made
// before the hole opens and carried to 1 mm (MriSurface::mild_time), the hole repaired
// locally on the way: embedded, the flood fill's topology, within the bound.
TEST(MriEvents, Colin27StartedPastTheHoleIsEmbeddedWithItsTopology) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto surface = colin27_layers(2.0, 4.0);
  AdaptOptions options = mri_suggested_options();
  options.max_triangles = 60000;  // main's code refined without end
  surface->set_time(0.25);
  const test::SolidTopology solid = test::solid_topology(
      [&](const Vec3& p) { return surface->value(p); }, surface->bounds(), 180);
  EXPECT_EQ(solid.components, 1);
  EXPECT_EQ(solid.surface_euler, 2);
  const auto run = started_adapter(*surface, options, 0.25);
  EXPECT_EQ(surface->time(), 0.25);
  EXPECT_FALSE(run->stats().budget_hit);
  expect_embedded_within_bound(run->mesh(), *surface, options, {solid.surface_euler, 1},
                               "first_mesh_1mm");
}

// Colin27 with closing 2 started 10 mm deep, 0.6 mm before a hole opens through a wall at 10.6
// mm and 1.9 mm before a split at 11.9 mm: main 2a84c07 (CLI, 60,000-triangle budget) ran into
// the budget with 6.5 mm of error and 740 degenerate triangles, refining next to the thin wall.
// Now made 6.6 mm deep, clear of both, and carried to 10 mm (2026-11-24: 8,752 triangles, dense
// error 0.617 mm). Carried from 6 mm instead it ended with 1,484 self-intersecting pairs: this
// guards the rule's start, not every start.
TEST(MriEvents, Colin27Started10MmDeepBeforeAThinWallIsEmbedded) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto surface = colin27_layers(2.0, 15.0);
  AdaptOptions options = mri_suggested_options();
  options.max_triangles = 60000;  // main's code refined without end
  const auto run = started_adapter(*surface, options, 10.0 / 15.0);
  EXPECT_NEAR(15.0 * surface->mild_time(), 6.6, 0.01);
  EXPECT_FALSE(run->stats().budget_hit);
  expect_embedded_within_bound(run->mesh(), *surface, options, {2, 1}, "first_mesh_10mm");
}

// The same 2 mm deep through the binary, for two steps to 3 mm: the first and the last frames
// embedded, one piece of Euler characteristic 2 (a flood fill of F on a 1 mm grid says so at 1
// and 2 mm: Colin27StartedPastTheHoleIsEmbeddedWithItsTopology), every step within T + eps.
// main 2a84c07: the first frame ran into the budget (60,000 triangles, 24 mm, 7,655 degenerate).
TEST(MriEvents, CliColin27StartedPastTheHoleHasEmbeddedFrames) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_colin27_t0_2mm");
  const test::CliRun run = test::run_cli(
      {"--scene", "mri", "--param", "closing=2", "--param", "depth_max=4", "--t0", "0.5", "--t1",
       "0.75", "--steps", "2", "--max-triangles", "60000", "--export", dir.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(run.json.is_object()) << run.out;
  EXPECT_EQ(run.json["budget_hit"], false) << run.err;
  EXPECT_EQ(run["rebuilds"], 0) << run.err;
  EXPECT_LE(run["worst_max_sample_error"], 0.5 + 0.125) << run.err;
  EXPECT_LT(run["peak_triangles"], 20000) << run.err;
  for (const char* frame : {"frame_00000.ply", "frame_00002.ply"}) {
    const test::MeshValidity v = test::check_mesh_validity_of_file((dir / frame).string());
    EXPECT_TRUE(v.embedded_closed_manifold()) << frame << ": " << v.describe();
    EXPECT_EQ(v.components, 1) << frame;
    EXPECT_EQ(v.euler(), 2) << frame;
  }
}

// Colin27 with closing 2, 10 mm deep: F's 8 mm contour has a second piece, a small lobe that
// the cuberille's cells join to the largest piece (some cuberille vertices are nearest to it).
// It is not added: added, it lay on the cuberille's sheet (38 self-intersecting pairs).
TEST(MriEvents, Colin27BaseAt10MmDoesNotAddALobeTheCuberilleHas) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const auto surface = colin27_layers(2.0);
  surface->set_time(0.5);
  const test::MeshValidity v = test::check_mesh_validity(surface->base_mesh());
  EXPECT_TRUE(v.embedded_closed_manifold()) << v.describe();
}

// Colin27 with closing 2 swept 0 to 4 mm deep in steps of 0.25 mm: every frame is an embedded
// closed manifold within T + eps, with no face turned over.
// - From 1.25 mm on a groove opens along a ridge of the distance field on the frontal midline,
//   near (0, 55, -14) mm, and the fold repair's relaxation could not unfold the faces across
//   it. A distance field's layer kept them (no re-base can follow it), and every frame from
//   1.25 mm on crossed itself there (64 to 449 self-intersecting pairs). They are re-meshed
//   locally from F's contour, as next to an event.
// - From 2.75 mm on, the rim of the cavity's hole near (+-6, -42, -52) mm sweeps along a nearly
//   flat ridge of D, and the faces it folds were not re-meshed: the mesh there is coarse (edges
//   up to 10 mm), so the cut of whole faces within 4 mm of the folds reached up to 24 mm away,
//   into the cavity's other side, with two border loops where F's contour near the folds has
//   one. The 4 mm frame had 13 crossing pairs. The faces near the folds are now split finer
//   than the cut before it is made (local_repair.cpp, refine_near).
TEST(MriEvents, Colin27SweptTo4MmIsEmbeddedAtEveryFrame) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const AdaptOptions options = mri_suggested_options();
  const auto surface = colin27_layers(2.0, 4.0);
  const auto adapter = started_adapter(*surface, options, 0.0);
  for (int k = 1; k <= 16; ++k) {
    const StepStats& stats = adapter->step(k / 16.0);
    const std::string where = std::to_string(0.25 * k) + " mm";
    EXPECT_LE(stats.max_error, options.threshold + options.epsilon) << where;
    const test::MeshValidity v = test::check_mesh_validity(adapter->mesh());
    EXPECT_TRUE(v.embedded_closed_manifold()) << where << ": " << v.describe();
    std::vector<Face> folded, slivers;
    find_bad_faces(adapter->mesh(), *surface, FoldRepairOptions{}.min_angle_deg, folded, slivers);
    EXPECT_EQ(folded.size(), 0u) << where;
  }
}

// The same sweep in 8 steps: the frontal groove's re-meshed patch crossed the mesh by the end of
// the step 3 mm deep, and the layer was re-based from its base mesh, whose refinement ran into
// the triangle budget (60,000 triangles, 21 mm of error; integ15's code: the same in step 8, 19.6
// mm). A layer is not re-based for a crossing: every step stays within T + eps. And every frame
// is embedded: before 2026-11-24 (session 15) frames 5, 6 and 8 crossed themselves (140, 218 and
// 19 pairs) where the re-mesh at the cavity's rim failed or folded again.
TEST(MriEvents, CliColin27SweptIn8StepsIsEmbeddedAndNotReBased) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("dynamesh_colin27_sweep_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const test::CliRun run =
      test::run_cli({"--scene", "mri", "--param", "closing=2", "--param", "depth_max=4", "--steps",
                     "8", "--max-triangles", "60000", "--export", dir.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(run.json.is_object()) << run.out;
  EXPECT_EQ(run["rebuilds"], 0) << run.err;
  EXPECT_LE(run["worst_max_sample_error"], 0.5 + 0.125) << run.err;
  EXPECT_LT(run["peak_triangles"], 20000) << run.err;
  for (int step = 0; step <= 8; ++step) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.ply", step);
    const test::MeshValidity v = test::check_mesh_validity_of_file((dir / name).string());
    EXPECT_TRUE(v.embedded_closed_manifold()) << name << ": " << v.describe();
  }
  fs::remove_all(dir);
}

// The split hold on real data, through the binary: Colin27 with closing 2 swept 0 to 4 mm deep
// in 4 steps with --topology-events off, so that nothing watches the sulci opening and the
// hold alone bounds the refinement where the mesh's topology is no longer F's. When the hold's
// count restarted at every new maximum of the gap faces' readings (before session 29) the
// sweep ended at 36,482, 238,682, 68,618 and 68,140 triangles with seeds 1-4 (30-121 s); with
// the count restarted only where the error doubles, at 21,512, 15,630, 16,276 and 13,416 (14-36
// s). Those peaks were chaotic in the last bits (the projection's tolerance at 0.9e-10 alone:
// 11,940-45,292 over seeds 1-8). Since split vertices go down their diamond's normal line only
// to where their faces face up, not to F's far sheets (SurfaceProbe::project_split_vertex,
// session 32), seeds 1-8 peak at 11,048-11,240 at either tolerance. Seed 4: the peak stays
// below 12,500, and the error the mesh cannot meet is reported, not hidden.
TEST(MriEvents, CliColin27UnwatchedSweepIsBoundedByTheHold) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  const test::CliRun run =
      test::run_cli({"--scene", "mri", "--param", "closing=2", "--param", "depth_max=4", "--steps",
                     "4", "--topology-events", "off", "--seed", "4", "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(run.json.is_object()) << run.out;
  EXPECT_FALSE(run.json["budget_hit"].get<bool>()) << run.err;
  EXPECT_LT(run["peak_triangles"], 12500) << run.err;
  EXPECT_GT(run["worst_max_sample_error"], 0.5 + 0.125) << run.err;
}

// Runs Colin27 with closing 2, 0 to 4 mm deep, through the binary with `args` added, and
// judges every exported frame (times[k] is frame k's): CGAL-embedded, and within 1.10 (T + eps)
// by a dense measurement of every 4th triangle; the run within T + eps sampled, not re-based,
// with no budget hit.
void expect_colin27_frames_embedded(const std::string& name, std::vector<std::string> args,
                                    const std::vector<double>& times) {
  const auto dir = test::scratch_dir(name);
  args.insert(args.begin(), {"--scene", "mri", "--param", "closing=2", "--param", "depth_max=4"});
  args.insert(args.end(), {"--max-triangles", "60000", "--export", dir.string(), "--quiet"});
  const test::CliRun run = test::run_cli(args);
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(run.json.is_object()) << run.out;
  const AdaptOptions options = mri_suggested_options();
  const double bound = options.threshold + options.epsilon;
  EXPECT_EQ(run.json["budget_hit"], false) << run.err;
  EXPECT_EQ(run["rebuilds"], 0) << run.err;
  EXPECT_LE(run["worst_max_sample_error"], bound) << run.err;
  EXPECT_LT(run["peak_triangles"], 20000) << run.err;
  const auto surface = colin27_layers(2.0, 4.0);
  for (std::size_t k = 0; k < times.size(); ++k) {
    char frame_name[32];
    std::snprintf(frame_name, sizeof frame_name, "frame_%05zu.ply", k);
    const TriangleMesh frame = read_triangle_mesh((dir / frame_name).string());
    const test::MeshValidity v = test::check_mesh_validity(frame.positions, frame.triangles);
    EXPECT_TRUE(v.embedded_closed_manifold()) << frame_name << ": " << v.describe();
    if (!v.manifold()) continue;  // a tangle from a runaway refinement: enough said
    surface->set_time(times[k]);
    const auto dense = test::dense_error(frame.positions, frame.triangles, *surface, 1.0, 29,
                                         [](std::size_t t) { return t % 4 == 0; });
    EXPECT_LE(dense.max_error, 1.10 * bound)
        << frame_name << ": dense error at (" << dense.worst.transpose() << ")";
  }
}

// The same sweep in 4 steps of 1 mm. The rim of the cavity's hole sweeps along a ridge of D
// faster than in 8 steps, and the faces there, stretched to 2-7 mm, fold. Session 15's code
// published the last frame with 11 crossing pairs (its re-mesh ladder failed: the cut levelled
// down reached 12-42 mm with 2 to 7 border loops where F's contour has one; levelled up, the
// strip joining the patch to it turned over). On main 0f86ef5 every frame is embedded (which of
// session 16's changes did it was not isolated); with session 15's interior-peak sampling merged
// in (integ17-peak) the folded faces were split without end and the last frame ran into the
// triangle budget (60,002 triangles, 27 mm sampled, 7,986 degenerate triangles). That sampling
// landed in session 18 with the guard against it: under a topology monitor a folded face is not
// split (Adapter::split_pass).
TEST(MriEvents, CliColin27SweptIn4StepsIsEmbeddedAtEveryFrame) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  expect_colin27_frames_embedded("mri_colin27_sweep_4_steps", {"--steps", "4"},
                                 {0.0, 0.25, 0.5, 0.75, 1.0});
}

// The same with the sample seed 3: main 0f86ef5 published frame 3 (3 mm) with 77 crossing pairs
// near (-4..0, -50..-44, -48..-41), the cavity's rim, after every re-mesh attempt failed ("the
// contour near the event has 1 border loops, the cut 2"), 23 s CPU. The patch filling the whole
// cut (HoleFill) takes the first rung's cut: every frame embedded, 10 s CPU.
TEST(MriEvents, CliColin27SweptIn4StepsWithOtherSamplesIsEmbeddedAtEveryFrame) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  expect_colin27_frames_embedded("mri_colin27_sweep_4_steps_seed_3",
                                 {"--steps", "4", "--seed", "3"}, {0.0, 0.25, 0.5, 0.75, 1.0});
}

// Started 4 mm deep: the first mesh is made 0 mm deep, clear of the hole that opens 0.81 mm
// deep, and carried to 4 mm in 8 steps (mri_start_depth), which meet the rim's folds as the
// sweeps do. Session 15's code left 19 crossing pairs; integ17-peak ran into the triangle budget
// (59,998 triangles, 32.5 mm sampled, not a manifold).
TEST(MriEvents, CliColin27Started4MmDeepIsEmbedded) {
  if (!std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data not installed";
  expect_colin27_frames_embedded("mri_colin27_t0_4mm", {"--t0", "1", "--steps", "0"}, {1.0});
}

}  // namespace
}  // namespace dynamesh
