// Topology change through the real dynamesh-cli on variants of the issue's two examples (issue
// 16: "hidden variants will be checked"): other directions and centres of the blobs, bounds
// from tight to wide, other step counts, the torus pinched elsewhere and at another time. Every
// exported frame is judged, not the end state: a closed embedded manifold (exact CGAL test)
// whose dense error (its own sampling, the Newton distance to F) is within (T + eps) * 1.10 but
// at the event's instant, and farther than 0.04 from an event the closed-form number of
// components and Euler characteristic, which a flood-filled fine voxel grid of F < 0 confirms;
// the run finishes (status 0) and reports each true event, of its kind, within one step, once.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "core/surface/scene_registry.h"
#include "dense_error.h"
#include "ply_reader.h"
#include "stats_table.h"
#include "tests/support/mesh_validity.h"
#include "topology_measure.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

const std::string kCli = std::string(DYNAMESH_BINARY_DIR) + "/dynamesh-cli";

struct Variant {
  std::string name, formula, bounds;
  int steps = 40;
  int max_rebuilds = -1;  // global re-bases allowed (-1: not judged)
  bool bubble = false;    // outside within the solid: the voxel reference counts solid components
  std::vector<std::pair<double, std::string>> events;  // true time, kind
  // Components and Euler characteristic at t, away from the events.
  std::pair<long, long> (*topology)(double t, const std::vector<double>& times) = nullptr;
  std::string cli_args;  // more CLI options (a sample seed: a hidden variant is another draw)
};

// A sweep over sampling luck runs every variant with more CLI options from the environment
// (e.g. DYNAMESH_VARIANT_CLI_ARGS="--seed 3"): the suite itself runs with none.
std::string cli_args_from_environment() {
  const char* args = std::getenv("DYNAMESH_VARIANT_CLI_ARGS");
  return args ? std::string(" ") + args : std::string();
}

// Two Gaussian blobs exp(-|p - c|^2 / s2) at c = o +- a(t) d, a(t) = a0 + a1 (2t - 1)^2, in
// 0.5 - blob - blob: they touch at the midpoint when 2 exp(-a^2 / s2) = 0.5, a = sqrt(s2 ln 4).
Variant blobs(const std::string& name, const Vec3& d, const Vec3& o, double s2, double a0,
              double a1, const std::string& bounds, int steps) {
  const Vec3 u = d.normalized();
  const std::string at = "(" + std::to_string(a0) + "+" + std::to_string(a1) + "*(2*t-1)^2)";
  const auto blob = [&](const std::string& sign) {
    std::string e = "exp(-(";
    const char* axis[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
      e += std::string(i ? "+" : "") + "(" + axis[i] + "-" + std::to_string(o[i]) + sign +
           std::to_string(u[i]) + "*" + at + ")^2";
    return e + ")/" + std::to_string(s2) + ")";
  };
  const double a = std::sqrt(s2 * std::log(4.0));
  const double w = std::sqrt((a - a0) / a1);
  Variant v;
  v.name = name;
  v.formula = "0.5 - " + blob("-") + " - " + blob("+");
  v.bounds = bounds;
  v.steps = steps;
  v.events = {{0.5 - 0.5 * w, "merge"}, {0.5 + 0.5 * w, "split"}};
  v.topology = [](double t, const std::vector<double>& times) {
    return t > times[0] && t < times[1] ? std::pair<long, long>{1, 2} : std::pair<long, long>{2, 4};
  };
  return v;
}

// A torus of radii R and r with a bump of strength c t and width^2 w2 at angle phi on its core
// circle: there F = -r^2 + c t, so the tube pinches through at t = r^2 / c (the bump's centre
// is a saddle of F while w2 > c t, across the tube F curves up by 2 (1 - c t / w2)). The
// issue's torus: R = 1, r = 0.3, w2 = 0.16. The event time is taken from the numbers as printed.
struct TorusShape {
  double R = 1, r = 0.3, w2 = 0.16;
  std::string bounds = "-1.5,-1.5,-0.5,1.5,1.5,0.5";
};

Variant torus_pinch(const std::string& name, double phi, double c, int steps,
                    const TorusShape& shape = {}) {
  const std::string r2 = std::to_string(shape.r * shape.r), cs = std::to_string(c);
  Variant v;
  v.name = name;
  v.formula = "(sqrt(x^2+y^2)-" + std::to_string(shape.R) + ")^2 + z^2 - " + r2 + " + " + cs +
              "*t*exp(-((x-" + std::to_string(shape.R * std::cos(phi)) + ")^2+(y-" +
              std::to_string(shape.R * std::sin(phi)) + ")^2+z^2)/" + std::to_string(shape.w2) +
              ")";
  v.bounds = shape.bounds;
  v.steps = steps;
  v.events = {{std::stod(r2) / std::stod(cs), "split"}};
  v.topology = [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{1, 0} : std::pair<long, long>{1, 2};
  };
  return v;
}

// The issue's torus with bumps of strengths c1 t and c2 t at angles phi1 and phi2 on its core
// circle: it pinches through at t = 0.09 / c1 and 0.09 / c2, first into a bent tube (1
// component, Euler characteristic 2), then into two (2, 4); equal strengths pinch both at once.
Variant torus_pinched_twice(const std::string& name, double phi1, double c1, double phi2, double c2,
                            int steps) {
  const auto bump = [](double phi, double c) {
    return " + " + std::to_string(c) + "*t*exp(-((x-" + std::to_string(std::cos(phi)) + ")^2+(y-" +
           std::to_string(std::sin(phi)) + ")^2+z^2)/0.16)";
  };
  Variant v;
  v.name = name;
  v.formula = "(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09" + bump(phi1, c1) + bump(phi2, c2);
  v.bounds = "-1.5,-1.5,-0.5,1.5,1.5,0.5";
  v.steps = steps;
  v.events = {{0.09 / c1, "split"}, {0.09 / c2, "split"}};
  v.topology = [](double t, const std::vector<double>& times) {
    const int pinched = (t > times[0]) + (t > times[1]);
    return pinched == 0 ? std::pair<long, long>{1, 0} : std::pair<long, long>{pinched, 2 * pinched};
  };
  return v;
}

// Three Gaussian blobs in a row, spaced a(t) = 0.6 + 0.9 (2t - 1)^2 along x, in 0.5 - blobs:
// both necks open at once where the smallest sum along the axis between two neighbours is 0.5,
// found here by bisection on the spacing (1.1774; the third blob adds little to the two-blob
// 2 sqrt(0.25 ln 4) = 1.1774), so three components merge into one and split again.
Variant three_blobs_in_a_row(int steps) {
  const auto sum = [](double x, double a) {
    double f = 0;
    for (const double c : {-a, 0.0, a}) f += std::exp(-(x - c) * (x - c) / 0.25);
    return f;
  };
  const auto smallest_between = [&](double a) {
    double m = HUGE_VAL;
    for (int i = 0; i <= 20000; ++i) m = std::min(m, sum(a * i / 20000.0, a));
    return m;
  };
  double lo = 0.6, hi = 1.5;  // merged at lo, apart at hi
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (smallest_between(mid) > 0.5 ? lo : hi) = mid;
  }
  const double w = std::sqrt((lo - 0.6) / 0.9);
  const std::string a = "(0.6+0.9*(2*t-1)^2)";
  Variant v;
  v.name = "three-in-a-row";
  v.formula = "0.5 - exp(-((x+" + a + ")^2+y^2+z^2)/0.25) - exp(-(x^2+y^2+z^2)/0.25) - " +
              "exp(-((x-" + a + ")^2+y^2+z^2)/0.25)";
  v.bounds = "-2.5,-0.8,-0.8,2.5,0.8,0.8";
  v.steps = steps;
  const double merge = 0.5 - 0.5 * w, split = 0.5 + 0.5 * w;
  v.events = {{merge, "merge"}, {merge, "merge"}, {split, "split"}, {split, "split"}};
  v.topology = [](double t, const std::vector<double>& times) {
    return t > times[0] && t < times[2] ? std::pair<long, long>{1, 2} : std::pair<long, long>{3, 6};
  };
  return v;
}

// The largest Newton distance to F over a frame read back from its PLY, sampled densely
// (dense_error.h's points: random ones at `density` per unit area, the corners, the midpoints).
double dense_error_of(const test::PlyData& ply, const Surface& surface, double density) {
  std::mt19937_64 rng(7);
  double worst = 0;
  const Vec2 uv[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  for (const auto& f : ply.faces) {
    Vec3 p[3];
    for (int i = 0; i < 3; ++i) {
      const auto& row = ply.vertices[f[i]];
      p[i] = Vec3(row[0], row[1], row[2]);
    }
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const auto n = static_cast<int>(std::max(3.0, std::ceil(density * area)));
    worst = std::max(worst, test::dense_triangle_error(surface, p, uv, n, rng));
  }
  return worst;
}

void run_and_judge(const Variant& v) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
  const fs::path dir = fs::path(DYNAMESH_BINARY_DIR) / "test_scratch" /
                       ("topology_variants_" + v.name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string command = test::shell_quoted(kCli) + " run --scene expr --quiet --implicit " +
                        test::shell_quoted(v.formula) + " --bounds " + v.bounds + " --steps " +
                        std::to_string(v.steps) + " " + v.cli_args + cli_args_from_environment() +
                        " --stats " + test::shell_quoted((dir / "stats.csv").string()) +
                        " --export " + test::shell_quoted((dir / "frames").string()) + " > " +
                        test::shell_quoted((dir / "out").string()) + " 2> " +
                        test::shell_quoted((dir / "err").string());
  const int raw = std::system(command.c_str());
  std::stringstream out, err;
  out << std::ifstream(dir / "out").rdbuf();
  err << std::ifstream(dir / "err").rdbuf();
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << v.name << ": " << err.str();
  std::string last, line;
  while (std::getline(out, line))
    if (!line.empty()) last = line;
  const nlohmann::json json = nlohmann::json::parse(last);
  const double step = 1.0 / v.steps;
  std::vector<double> times;
  for (const auto& [time, kind] : v.events) {
    times.push_back(time);
    int found = 0, expected = 0;  // events of one kind at one instant (two pinches) are several
    for (const auto& e : json["topology_events"])
      found += e["kind"] == kind && std::abs(e["time"].get<double>() - time) <= step;
    for (const auto& [other_time, other_kind] : v.events)
      expected += other_kind == kind && std::abs(other_time - time) <= step;
    EXPECT_EQ(found, expected) << v.name << ": " << kind << "s reported near t=" << time << "\n"
                               << err.str();
  }
  for (const auto& e : json["topology_events"]) {
    bool expected = false;
    for (const double time : times)
      expected = expected || std::abs(e["time"].get<double>() - time) <= step;
    EXPECT_TRUE(expected) << v.name << ": unexpected " << e.dump() << "\n" << err.str();
  }
  // The CLI's defaults: T = 0.008, eps = T / 4, density 2000 (dense: 5 times that).
  constexpr double kT = 0.008, kEps = 0.002, kDenseDensity = 5 * 2000.0, kSlack = 1.10;
  std::unique_ptr<Surface> surface =
      make_scene("expr", {}, {{"implicit", v.formula}, {"bounds", v.bounds}});
  const auto& F = dynamic_cast<const ImplicitSurface&>(*surface);
  double worst_ratio = 0;
  for (int i = 0; i <= v.steps; ++i) {
    char file[32];
    std::snprintf(file, sizeof file, "frame_%05d.ply", i);
    const double t = static_cast<double>(i) / v.steps;
    const std::string frame = v.name + " frame " + std::to_string(i) + " t=" + std::to_string(t);
    const test::MeshValidity m =
        test::check_mesh_validity_of_file((dir / "frames" / file).string());
    EXPECT_TRUE(m.embedded_closed_manifold()) << frame << ": " << m.describe();
    double nearest = HUGE_VAL;
    for (const double time : times) nearest = std::min(nearest, std::abs(t - time));
    surface->set_time(t);
    // At an event's instant F has a double cone, where the Newton path is not a distance
    // (test_topology_events.cpp): that one frame's error is not judged.
    if (nearest > 1e-9) {
      const double ratio = dense_error_of(test::read_ply((dir / "frames" / file).string()),
                                          *surface, kDenseDensity) /
                           (kT + kEps);
      worst_ratio = std::max(worst_ratio, ratio);
      EXPECT_LE(ratio, kSlack) << frame << ": dense error / (T + eps)";
    }
    if (nearest <= 0.04) continue;
    const auto [components, euler] = v.topology(t, times);
    EXPECT_EQ(m.components, components) << frame;
    EXPECT_EQ(m.euler(), euler) << frame;
    const test::SolidTopology ref =
        test::solid_topology([&](const Vec3& p) { return F.value(p); }, F.bounds(), 96);
    if (!v.bubble) {  // a bubble's solid is one shell bounded by two surfaces
      EXPECT_EQ(ref.components, components) << frame << " (voxel reference)";
    }
    EXPECT_EQ(ref.surface_euler, euler) << frame << " (voxel reference)";
  }
  // Coherence: the mean over the steps of the fraction of vertices kept (the CSV's column).
  const test::StatsTable stats(dir / "stats.csv");
  ASSERT_EQ(stats.rows(), static_cast<std::size_t>(v.steps + 1)) << v.name;
  double survival = 0;
  for (std::size_t k = 1; k < stats.rows(); ++k)  // row 0: the initial adaptation
    survival += stats.number(k, "kept_fraction");
  survival /= v.steps;
  EXPECT_GE(survival, 0.9) << v.name << ": mean vertex survival";
  if (v.max_rebuilds >= 0) {
    EXPECT_LE(json["rebuilds"].get<int>(), v.max_rebuilds) << v.name << "\n" << err.str();
  }
  std::printf("%s: rebuilds %d, local repairs %d, survival %.4f, worst dense error %.3f (T+eps)\n",
              v.name.c_str(), json["rebuilds"].get<int>(), json["local_repairs"].get<int>(),
              survival, worst_ratio);
  if (!std::getenv("DYNAMESH_VARIANT_KEEP_FRAMES")) fs::remove_all(dir);
}

const Vec3 kDiagonal(0.6, 0.48, 0.64);

TEST(TopologyVariantsCli, DiagonalBlobsWithWideBoundsFinishWithEveryFrameRight) {
  // Stopped at the merge (step 7) with "the contoured base mesh folds over" before the fix.
  run_and_judge(blobs("diagonal-wide", kDiagonal, Vec3::Zero(), 0.2, 0.15, 0.9,
                      "-1.2,-1.1,-1.2,1.2,1.1,1.2", 40));
}

TEST(TopologyVariantsCli, OffCentreBlobsAlongYInWideBounds) {
  run_and_judge(blobs("y-off-centre", Vec3::UnitY(), Vec3(0.13, 0.07, -0.11), 0.25, 0.2, 0.8,
                      "-2,-2,-2,2,2,2", 20));
}

TEST(TopologyVariantsCli, TorusPinchedElsewhereAndEarlier) {
  run_and_judge(torus_pinch("torus-135deg", 2.356, 0.3, 20));
}

// The variant sweep's failures (session 5). Wide blobs along (1, 1, 0): the fold net re-based
// the mesh just before the split, the split's local repair was refused, and the re-base's
// contour on the grid still joined the two tips (closer than a cell): the split queue refined
// that bridge up to the triangle budget (no end in 300 s).
TEST(TopologyVariantsCli, WideBlobsSplitAfterARebaseFinish) {
  run_and_judge(
      blobs("wide-110", Vec3(1, 1, 0), Vec3::Zero(), 0.35, 0.3, 0.8, "-2,-2,-1.5,2,2,1.5", 40));
}

// The same in 20 steps (session 7's sweep): the neck thinning towards the split folded at
// t = 0.85 and the fold net re-based; the split's local repair was then refused (the cut,
// levelled around coarse faces, enclosed a diamond: 4 border loops against the contour's 2),
// and the mesh was re-based again: survival 0.896. Now the folds are re-meshed locally, the
// frame at t = 0.85 is checked for faces crossing the mesh (a re-mesh across the thinning
// neck left 111 crossing pairs), re-based once, and the split repaired locally.
TEST(TopologyVariantsCli, WideBlobsIn20StepsSplitLocally) {
  Variant v =
      blobs("wide-110-20", Vec3(1, 1, 0), Vec3::Zero(), 0.35, 0.3, 0.8, "-2,-2,-1.5,2,2,1.5", 20);
  v.max_rebuilds = 1;
  run_and_judge(v);
}

// The issue's blobs as a formula in 20 steps: the merge's local repair was followed by folds
// (17 faces: the split pass across the new neck, thinner than the edges, and equal sub-steps
// giving the first one most of its widening), and the fold net rebuilt the whole mesh.
TEST(TopologyVariantsCli, IssueBlobsIn20StepsMergeWithoutARebuild) {
  Variant v =
      blobs("x-20", Vec3::UnitX(), Vec3::Zero(), 0.25, 0.2, 0.8, "-1.8,-0.8,-0.8,1.8,0.8,0.8", 20);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The torus pinched at 40 degrees at t = 0.75, a step time: the event falls on a frame, where
// the surface is a double cone. The mesh was rebuilt twice (a re-base on the instant that
// already had the new topology, then the crossing counted again at the next step).
TEST(TopologyVariantsCli, TorusPinchOnAStepTimeIsReportedOnce) {
  Variant v = torus_pinch("torus-40deg", 0.7, 0.12, 20);
  v.max_rebuilds = 0;  // the event's instant is repaired locally
  run_and_judge(v);
}

// Two pinches at the same instant, a step time (t = 0.5): the run was refused before its
// first step ("needs at least about 4e+09 triangles"), as the workload estimate read a
// curvature of ~1e10 at a grid crossing a rounding error from one pinch's apex.
TEST(TopologyVariantsCli, TorusPinchedTwiceAtOnceFallsInTwo) {
  run_and_judge(torus_pinched_twice("torus-twice-at-once", 0.0, 0.18, 3.14159265, 0.18, 20));
}

TEST(TopologyVariantsCli, TorusPinchedTwiceInTurnFallsInTwo) {
  run_and_judge(torus_pinched_twice("torus-twice-in-turn", 0.0, 0.3, 2.0, 0.18, 20));
}

// The issue's torus pinch in 10 steps: the step after the pinch (t = 0.6, 23 sub-steps) left
// one face folded at each retracting tip, two patches' width apart, and the mesh was rebuilt
// from F's contour (survival 0.895): one patch per cluster of folds now.
TEST(TopologyVariantsCli, TorusPinchIn10StepsKeepsItsVertices) {
  Variant v = torus_pinch("torus-10", 0.0, 0.18, 10);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The torus pinched at 135 degrees with the pinch on a frame (t = 0.09 / 0.3 = 0.3) in 10 steps.
// The repair at that instant contoured F = 0 on a grid with a point on the double cone's tip,
// whose neighbours along x and y lie within the grid's resolution of zero, inside; the grid's
// face diagonals between them run along the tube past the tip and kept the two sheets joined
// through flat triangles. Every attempt was refused ("a new triangle would be turned over"),
// the mesh rebuilt: survival 0.897. Now the patch is contoured at a clear level there.
TEST(TopologyVariantsCli, TorusPinchedOnAFrameAt135Degrees) {
  Variant v = torus_pinch("torus-135deg-10", 3 * M_PI / 4, 0.3, 10);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The same pinch 0.00005 before that frame (c = 0.30005): repaired locally, but the frame just
// after it read 1.17 (T + eps) densely at the new tips until the error there was taken as
// Newton's distance (SurfaceProbe::set_singular_points); main rebuilt the mesh (survival 0.897).
TEST(TopologyVariantsCli, TorusPinchedJustBeforeAFrameAt135Degrees) {
  Variant v = torus_pinch("torus-135deg-10-early", 3 * M_PI / 4, 0.30005, 10);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// One event of `kind` at `time`, with `before` and `after` it as (components, Euler
// characteristic), on an F of one's own, 20 steps.
template <long C0, long E0, long C1, long E1>
Variant one_event(const std::string& name, const std::string& formula, const std::string& bounds,
                  double time, const std::string& kind) {
  Variant v;
  v.name = name;
  v.formula = formula;
  v.bounds = bounds;
  v.steps = 20;
  v.events = {{time, kind}};
  v.topology = [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{C0, E0} : std::pair<long, long>{C1, E1};
  };
  return v;
}

// The torus pinch run backwards: a bent tube whose ends meet at t = 0.5 and close into a torus
// (a merge that makes a handle: Euler characteristic 2 -> 0, one component throughout).
TEST(TopologyVariantsCli, BentTubeClosesIntoATorus) {
  run_and_judge(one_event<1, 2, 1, 0>(
      "tube-closes", "(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09 + 0.18*(1-t)*exp(-((x-1)^2+y^2+z^2)/0.16)",
      "-1.5,-1.5,-0.5,1.5,1.5,0.5", 0.5, "merge"));
}

// A quartic F, not a sum of Gaussians: the Cassini surface |p - f|^2 |p + f|^2 = b^4 about the
// foci f = (+-0.8, 0, 0), with b = 0.93 - 0.26 t, is one peanut for b > 0.8 and two eggs below;
// at b = 0.8 (t = 0.5, a step time) it is a lemniscate's surface of revolution, pinched at 0.
TEST(TopologyVariantsCli, CassiniPeanutFallsInTwo) {
  run_and_judge(one_event<1, 2, 2, 4>(
      "cassini", "(x^2+y^2+z^2)^2 - 2*0.64*(x^2-y^2-z^2) + 0.4096 - (0.93-0.26*t)^4",
      "-1.6,-1,-1,1.6,1,1", 0.5, "split"));
}

// Two necks open and close at once, both found and repaired in the same step, 0.0005 before a
// frame (the merge) and 0.0005 after one (the split). Before the fix: the frame at t = 0.1
// had 27 split vertices 0.006-0.024 off F, left on their edges by the fold guard in the last
// sub-step (dense error 3.06 (T + eps)); the frame at t = 0.9, re-based for faces left folded
// by the neck's thinning, had 26 crossing pairs; survival 0.848 (two re-bases).
TEST(TopologyVariantsCli, ThreeBlobsInARowMergeAndSplitAtOnce) {
  Variant v = three_blobs_in_a_row(20);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The same in 40 steps (the frames at t = 0.1 and 0.9 as in 20 steps, before the fix).
TEST(TopologyVariantsCli, ThreeBlobsInARowIn40Steps) {
  Variant v = three_blobs_in_a_row(40);
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The same with another sample draw (--seed 2; a hidden variant is another draw): the frame
// 0.0005 before the double split had 7 faces left folded by the correction, and their patches
// made folds of their own (a stitch's strip triangle, a patch centred off the neck) that no
// relaxation was tried on: 2 faces still folded after 4 patches, the mesh re-based (84
// crossing pairs in that frame), the split's repair refused, re-based again: survival 0.861.
TEST(TopologyVariantsCli, ThreeBlobsInARowWithOtherSamplesMergeAndSplitAtOnce) {
  Variant v = three_blobs_in_a_row(20);
  v.cli_args = "--seed 2";
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// Components born and dying (session 15). A blob grows at (0.8, 0, 0) with weight w(t) beside
// one at (-0.8, 0, 0): its minimum, 0.5 - w - exp(-1.6^2 / 0.25) = 0.5 - w - 3.6e-5, crosses zero
// at w = 0.49996 (the other blob's tail moves it by less than 1e-4 in t). A bubble of outside
// at the centre of the unit sphere, |p|^2 - 1 + w(t) exp(-|p|^2 / 0.1): the maximum at the
// origin, w - 1, crosses zero at w = 1 exactly; the solid is then one shell with two surfaces,
// so the voxel reference counts one solid component where the mesh has two. Before
// component_repair.h every birth and death was refused by the local repair ("nothing to cut
// near the event") and the whole mesh re-based (no vertex survived it): a birth in 5 steps
// kept 0.80 of the vertices on average.
Variant blob_weighted(const std::string& name, const std::string& weight, double time, bool born,
                      int steps) {
  Variant v;
  v.name = name;
  v.formula =
      "0.5 - exp(-((x+0.8)^2+y^2+z^2)/0.25) - " + weight + "*exp(-((x-0.8)^2+y^2+z^2)/0.25)";
  v.bounds = "-1.8,-0.8,-0.8,1.8,0.8,0.8";
  v.steps = steps;
  v.max_rebuilds = 0;
  v.events = {{time, born ? "birth" : "death"}};
  v.topology = born ? [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{1, 2} : std::pair<long, long>{2, 4};
  } : [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{2, 4} : std::pair<long, long>{1, 2};
  };
  return v;
}

TEST(TopologyVariantsCli, BlobBornBesideAnotherKeepsTheOthersVertices) {
  run_and_judge(blob_weighted("born", "(0.3+0.6*t)", 0.33327, true, 20));
}

TEST(TopologyVariantsCli, BlobBornIn5Steps) {
  run_and_judge(blob_weighted("born-5", "(0.3+1.2*t)", 0.16664, true, 5));
}

TEST(TopologyVariantsCli, BlobDiesBesideAnother) {
  run_and_judge(blob_weighted("dies", "(0.9-0.6*t)", 0.66673, false, 20));
}

Variant bubble(const std::string& name, const std::string& weight, double time, bool born) {
  Variant v = one_event<1, 2, 2, 4>("bubble-" + name,
                                    "x^2+y^2+z^2-1+" + weight + "*exp(-(x^2+y^2+z^2)/0.1)",
                                    "-1.3,-1.3,-1.3,1.3,1.3,1.3", time, born ? "birth" : "death");
  if (!born)
    v.topology = [](double t, const std::vector<double>& times) {
      return t < times[0] ? std::pair<long, long>{2, 4} : std::pair<long, long>{1, 2};
    };
  v.max_rebuilds = 0;
  v.bubble = true;
  return v;
}

TEST(TopologyVariantsCli, BubbleBornInsideASphere) {
  run_and_judge(bubble("born", "(0.5+1.2*t)", 5.0 / 12.0, true));
}

TEST(TopologyVariantsCli, BubbleInsideASphereDies) {
  run_and_judge(bubble("dies", "(1.7-1.2*t)", 7.0 / 12.0, false));
}

// A hole opening through a membrane (the event kind no other variant has): the quartic torus
// (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2), R = 1, r = 0.3, minus w(t) exp(-|p|^2 / 0.5) fills
// its middle while w > (R^2 - r^2)^2 = 0.8281, the value at the origin, a saddle of index 2;
// w = 1.1 - 0.6 t opens it at t = 0.45317: a sphere becomes a torus.
TEST(TopologyVariantsCli, HoleOpensThroughAMembrane) {
  Variant v = one_event<1, 2, 1, 0>(
      "hole-opens", "((x^2+y^2+z^2+0.91)^2 - 4*(x^2+y^2)) - (1.1-0.6*t)*exp(-(x^2+y^2+z^2)/0.5)",
      "-1.6,-1.6,-0.6,1.6,1.6,0.6", (1.1 - 0.8281) / 0.6, "hole-opens");
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// The same with another sample draw (--seed 2): 2 faces were left folded by the correction in
// the step of the event (t = 0.5) and the mesh was re-based.
TEST(TopologyVariantsCli, HoleOpensThroughAMembraneWithOtherSamples) {
  Variant v = one_event<1, 2, 1, 0>(
      "hole-opens-seed-2",
      "((x^2+y^2+z^2+0.91)^2 - 4*(x^2+y^2)) - (1.1-0.6*t)*exp(-(x^2+y^2+z^2)/0.5)",
      "-1.6,-1.6,-0.6,1.6,1.6,0.6", (1.1 - 0.8281) / 0.6, "hole-opens");
  v.cli_args = "--seed 2";
  v.max_rebuilds = 0;
  run_and_judge(v);
}

// Frames within 0.001 of an event (session 16's sweep of 24 random variants in 40 steps: 4
// failed). Next to the critical point the first-order distance |F| / |grad F| read the error
// 0.9985 (T + eps) where the Newton distance is 1.155 (the tip of a blob 0.0007 before it
// merged), so the faces there were left too coarse; the probe now takes Newton's distance near
// F's critical points close to F = 0 (SurfaceProbe::set_singular_points).
TEST(TopologyVariantsCli, BlobsFramedJustBeforeTheyMerge) {
  run_and_judge(blobs("merge-near-frame", Vec3(-0.708621, 0.645387, -0.285188),
                      Vec3(0.003062, 0.080908, -0.043990), 0.158259, 0.350713, 0.584894,
                      "-1.591133,-1.454126,-1.242018,1.597257,1.615941,1.154039", 40));
}

// A thinner torus (R = 1.044, r = 0.261) pinched by a narrower bump (width^2 0.104) at 134
// degrees, 0.0009 after a frame: that frame read 1.115 (T + eps) densely, and the step before
// it had left 11 faces folded and the mesh was rebuilt, twice (survival 0.950).
TEST(TopologyVariantsCli, ThinTorusPinchedJustAfterAFrame) {
  Variant v;
  v.name = "thin-torus-near-frame";
  v.formula =
      "(sqrt(x^2+y^2)-1.044114)^2 + z^2 - 0.067920 + "
      "0.180698*t*exp(-((x+0.721968)^2+(y-0.754279)^2+z^2)/0.103735)";
  v.bounds = "-1.604729,-1.604729,-0.460615,1.604729,1.604729,0.460615";
  v.steps = 40;
  v.max_rebuilds = 0;
  v.events = {{0.067920 / 0.180698, "split"}};
  v.topology = [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{1, 0} : std::pair<long, long>{1, 2};
  };
  run_and_judge(v);
}

// The random-variant sweep (issue 16: "hidden variants will be checked"). A seed draws one
// variant of a kind: 1 or 3 mod 4, a torus pinch; 2 mod 4, two blobs merging and splitting
// again; 0 mod 4, a blob born or dying beside another. The torus and the blobs are drawn as
// session 16's throw-away sweep drew them (seeds 1-24: 3, 13, 15 and 18 failed on main f90b776).
// Uniform draws by hand from std::mt19937_64 (fully specified), computed as libstdc++'s
// uniform_real_distribution computes them, so a seed is the same variant with any library.
class Draws {
 public:
  explicit Draws(unsigned seed) : rng_(seed) {}
  double operator()(double a, double b) {
    double u = static_cast<double>(rng_()) / 18446744073709551616.0;  // 2^64
    if (u >= 1) u = std::nextafter(1.0, 0.0);
    return u * (b - a) + a;
  }
  // Normalized from the cube, drawn z first (session 16 drew Vec3(U, U, U), built right to left).
  Vec3 direction() {
    const double z = (*this)(-1, 1), y = (*this)(-1, 1), x = (*this)(-1, 1);
    return Vec3(x, y, z).normalized();
  }
  Vec3 offset(double half) {
    const double z = (*this)(-half, half), y = (*this)(-half, half), x = (*this)(-half, half);
    return Vec3(x, y, z);
  }

 private:
  std::mt19937_64 rng_;
};

std::string csv(const Vec3& p) {
  return std::to_string(p[0]) + "," + std::to_string(p[1]) + "," + std::to_string(p[2]);
}

// The bounds: the box of the given points, widened by `margin`.
std::string bounds_around(const std::vector<Vec3>& points, double margin) {
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return csv(lo - Vec3::Constant(margin)) + "," + csv(hi + Vec3::Constant(margin));
}

// A torus R in (0.8, 1.2), r in (0.2, 0.35) pinched at a random angle at tp in (0.2, 0.8): the
// bump's strength c = r^2 / tp, its width^2 w2 at least 1.5 r^2 > c tp, so its centre is still
// a saddle at tp (TorusShape) and the tube pinches through there.
Variant sweep_torus(const std::string& name, Draws& draw, int steps, std::string& args) {
  TorusShape shape;
  shape.R = draw(0.8, 1.2);
  shape.r = draw(0.2, 0.35);
  shape.w2 = std::max(0.1, 1.5 * shape.r * shape.r) + draw(0, 0.1);
  const double phi = draw(0, 2 * M_PI), tp = draw(0.2, 0.8);
  const double xy = shape.R + shape.r + 0.3, z = shape.r + 0.2;
  shape.bounds = bounds_around({Vec3(-xy, -xy, -z), Vec3(xy, xy, z)}, 0);
  args = "torus R " + std::to_string(shape.R) + " r " + std::to_string(shape.r) + " w2 " +
         std::to_string(shape.w2) + " phi " + std::to_string(phi) + " tp " + std::to_string(tp);
  return torus_pinch(name, phi, shape.r * shape.r / tp, steps, shape);
}

// Two blobs of width^2 s2 in (0.15, 0.35) along a random direction about a random centre:
// touching at a = sqrt(s2 ln 4) (blobs()), closest at a0 = a (0.3 to 0.8), farthest at
// a0 + a1 = a + (0.3 to 1): they merge at 0.5 - 0.5 w and split at 0.5 + 0.5 w, with
// w = sqrt((a - a0) / a1) in (0.29, 0.79): events within (0.10, 0.36) and (0.64, 0.90). The
// bounds: 0.15 (or, one time in 0.3, 0.6) beyond the blobs' radius at their farthest.
Variant sweep_blobs(const std::string& name, Draws& draw, int steps, std::string& args) {
  const Vec3 d = draw.direction(), o = draw.offset(0.15);
  const double s2 = draw(0.15, 0.35), touch = std::sqrt(s2 * std::log(4.0));
  const double a0 = touch * draw(0.3, 0.8), a1 = touch - a0 + draw(0.3, 1.0);
  const double margin = std::sqrt(s2 * std::log(2.0)) + (draw(0, 1) < 0.3 ? 0.6 : 0.15);
  const std::string bounds = bounds_around({o - (a0 + a1) * d, o + (a0 + a1) * d}, margin);
  args = "blobs d " + csv(d) + " o " + csv(o) + " s2 " + std::to_string(s2) + " a0 " +
         std::to_string(a0) + " a1 " + std::to_string(a1);
  return blobs(name, d, o, s2, a0, a1, bounds, steps);
}

double as_printed(double x) {
  return std::stod(std::to_string(x));
}

// A blob at c2 of weight w(t) = w0 +- k t beside one of weight 1 at c1, both of width^2 s2 in
// (0.15, 0.3), L = |c1 - c2| = (1.25 to 1.6) times where two blobs of weight 1 touch, so they
// never merge (w <= 1): 0.5 - exp(-|p - c1|^2 / s2) - w exp(-|p - c2|^2 / s2). The minimum near
// c2 lies on the axis (across it both terms curve up); the blob is born (or dies) where that
// minimum is zero, at weight w* (a bisection on w of a golden-section search along the axis,
// on the numbers as printed), at te in (0.2, 0.8), with k in (0.45, 0.6): w within (0.02, 0.98).
Variant sweep_born_or_dying(const std::string& name, Draws& draw, int steps, std::string& args) {
  const Vec3 d = draw.direction(), o = draw.offset(0.15);
  const double s2 = as_printed(draw(0.15, 0.3));
  const double L = 2 * std::sqrt(s2 * std::log(4.0)) * draw(1.25, 1.6);
  const double te = draw(0.2, 0.8), k = as_printed(draw(0.45, 0.6));
  const bool born = draw(0, 1) < 0.5;
  Vec3 c1 = o - 0.5 * L * d, c2 = o + 0.5 * L * d;
  for (int i = 0; i < 3; ++i) {
    c1[i] = as_printed(c1[i]);
    c2[i] = as_printed(c2[i]);
  }
  const Vec3 axis = (c1 - c2).normalized();
  const auto F = [&](double x, double w) {  // at c2 + x axis
    const Vec3 p = c2 + x * axis;
    return 0.5 - std::exp(-(p - c1).squaredNorm() / s2) - w * std::exp(-x * x / s2);
  };
  const auto smallest = [&](double w) {
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double lo = -0.5 * std::sqrt(s2), hi = 0.5 * std::sqrt(s2);
    for (int i = 0; i < 200; ++i) {
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      if (F(a, w) < F(b, w))
        hi = b;
      else
        lo = a;
    }
    return F(0.5 * (lo + hi), w);
  };
  double wlo = 0.3, whi = 0.7;  // smallest > 0 at wlo, < 0 at whi
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (wlo + whi);
    (smallest(mid) > 0 ? wlo : whi) = mid;
  }
  const double w_event = 0.5 * (wlo + whi);
  const double w0 = as_printed(born ? w_event - k * te : w_event + k * te);
  const auto blob = [&](const Vec3& c) {
    return "exp(-((x-" + std::to_string(c[0]) + ")^2+(y-" + std::to_string(c[1]) + ")^2+(z-" +
           std::to_string(c[2]) + ")^2)/" + std::to_string(s2) + ")";
  };
  Variant v;
  v.name = name;
  v.formula = "0.5 - " + blob(c1) + " - (" + std::to_string(w0) + (born ? "+" : "-") +
              std::to_string(k) + "*t)*" + blob(c2);
  v.bounds = bounds_around({c1, c2}, std::sqrt(s2 * std::log(2.0)) + 0.5);
  v.steps = steps;
  v.events = {{std::abs(w_event - w0) / k, born ? "birth" : "death"}};
  v.topology = born ? [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{1, 2} : std::pair<long, long>{2, 4};
  } : [](double t, const std::vector<double>& times) {
    return t < times[0] ? std::pair<long, long>{2, 4} : std::pair<long, long>{1, 2};
  };
  args = std::string(born ? "born" : "dying") + " s2 " + std::to_string(s2) + " L " +
         std::to_string(L) + " k " + std::to_string(k) + " w* " + std::to_string(w_event) + " te " +
         std::to_string(v.events[0].first);
  return v;
}

Variant sweep_variant(unsigned seed, int steps) {
  Draws draw(seed);
  const std::string name = "sweep" + std::to_string(seed);
  std::string args;
  Variant v = seed % 2   ? sweep_torus(name, draw, steps, args)
              : seed % 4 ? sweep_blobs(name, draw, steps, args)
                         : sweep_born_or_dying(name, draw, steps, args);
  std::string events;
  for (const auto& [time, kind] : v.events) events += " " + kind + " " + std::to_string(time);
  std::printf(
      "%s: %s;%s\n  dynamesh-cli run --scene expr --implicit '%s' --bounds %s --steps %d%s\n",
      name.c_str(), args.c_str(), events.c_str(), v.formula.c_str(), v.bounds.c_str(), v.steps,
      cli_args_from_environment().c_str());
  std::fflush(stdout);
  return v;
}

// In CI three seeds, one of each kind but the blobs (about 22 s; the blobs have tests of their
// own above); DYNAMESH_SWEEP_SEEDS=a-b (or one seed) and DYNAMESH_SWEEP_STEPS=N run others.
// Seed 15 (a torus pinched at t = 0.6796) failed on main f90b776: dense error 1.132 (T + eps)
// in the frame at t = 0.675. Seed 4: a blob dying at t = 0.6539; 28: one born.
TEST(TopologySweep, RandomVariants) {
  std::vector<unsigned> seeds = {15, 4, 28};
  if (const char* env = std::getenv("DYNAMESH_SWEEP_SEEDS")) {
    char* end = nullptr;
    const unsigned long first = std::strtoul(env, &end, 10);
    unsigned long last = first;
    bool ok = end != env;
    if (ok && *end == '-') {
      const char* second = end + 1;
      last = std::strtoul(second, &end, 10);
      ok = end != second;
    }
    ASSERT_TRUE(ok && *end == 0 && first <= last)
        << "DYNAMESH_SWEEP_SEEDS=" << env << ": expected a seed or a range a-b";
    seeds.clear();
    for (unsigned long s = first; s <= last; ++s) seeds.push_back(static_cast<unsigned>(s));
  }
  int steps = 40;
  if (const char* env = std::getenv("DYNAMESH_SWEEP_STEPS")) {
    steps = std::atoi(env);
    ASSERT_GT(steps, 0) << "DYNAMESH_SWEEP_STEPS=" << env;
  }
  for (const unsigned seed : seeds) {
    SCOPED_TRACE("sweep seed " + std::to_string(seed));
    run_and_judge(sweep_variant(seed, steps));
  }
}

}  // namespace
}  // namespace dynamesh
