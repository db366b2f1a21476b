// Every documented option of `dynamesh-cli run` changes the result in the documented
// direction, through the real binary (issue 12): the threshold on every scene, eps, density,
// edge length, budget, seed, k, smoothing, keyframes; a default given explicitly changes
// nothing. Runs are short and coarse where the direction still shows clearly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "ply_reader.h"
#include "stats_table.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using test::Args;
using test::CliRun;
using test::run_cli;
using test::operator+;

CliRun ok(const Args& args) {
  CliRun r = run_cli(args + Args{"--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(r.json.is_discarded() || r.json.is_null()) << r.out;
  return r;
}

// A short stretch of each scene's motion: a few steps, enough to move.
Args scene(const std::string& name) {
  Args a{"--scene", name, "--steps", "2", "--t0", "0.2", "--t1", "0.3"};
  if (name == "expr")
    a = a +
        Args{"--implicit", "x^2 + y^2/(1+0.5*sin(6.28*t)) + z^2 - 1", "--bounds", "-2,-2,-2,2,2,2"};
  return a;
}

TEST(CliOptions, ThresholdRefinesEveryScene) {
  for (const std::string name : {"sphere", "capsule-bend", "sinc", "twist", "expr"}) {
    SCOPED_TRACE(name);
    const CliRun fine = ok(scene(name) + Args{"--threshold", "0.002"});
    const CliRun coarse = ok(scene(name) + Args{"--threshold", "0.008"});
    // Error ~ curvature * edge^2: a quarter of T needs about four times the triangles.
    EXPECT_GT(fine["triangles"], 2.5 * coarse["triangles"]);
    EXPECT_GT(fine["peak_triangles"], 2.5 * coarse["peak_triangles"]);
    // sphere: its x >= 0 half follows an edge length, not the error (checked below).
    if (name != "sphere") {
      EXPECT_LE(fine["worst_max_sample_error"], 0.002 * 1.25 + 1e-12);
      EXPECT_LE(coarse["worst_max_sample_error"], 0.008 * 1.25 + 1e-12);
    }
  }
}

TEST(CliOptions, ThresholdOnMriInMillimetres) {
  // mri is in millimetres: its own T is 0.5 mm, eps T/4; stated, they change nothing.
  const Args mri{"--scene", "mri", "--steps", "1", "--t1", "0.1"};
  const CliRun fine = ok(mri + Args{"--threshold", "0.5", "--epsilon", "0.125"});
  const CliRun bare = ok(mri);
  const CliRun coarse = ok(mri + Args{"--threshold", "1.0"});
  EXPECT_GT(fine["triangles"], 1.5 * coarse["triangles"]);
  EXPECT_LE(fine["worst_max_sample_error"], 0.5 * 1.25 + 1e-9);
  EXPECT_LE(coarse["worst_max_sample_error"], 1.0 * 1.25 + 1e-9);
  EXPECT_EQ(bare["triangles"], fine["triangles"]);
  EXPECT_EQ(bare["mean_sample_error"], fine["mean_sample_error"]);
}

TEST(CliOptions, EpsilonWidensTheBandSoFewerOperations) {
  // There and back over the sinc's rise: a narrow band welds what it split and splits again.
  const Args run{"--scene", "sinc", "--keyframes", "0.2,0.3,0.2",
                 "--steps", "8",    "--threshold", "0.008"};
  const CliRun narrow = ok(run + Args{"--epsilon", "0.0002"});
  const CliRun wide = ok(run + Args{"--epsilon", "0.006"});
  EXPECT_GT(narrow["welds"], 2 * wide["welds"]);
  EXPECT_GT(narrow["splits"] + narrow["welds"], 1.2 * (wide["splits"] + wide["welds"]));
  // Splits wait until T + eps: the wide band keeps fewer triangles, and its errors reach
  // further (but never past T + eps).
  EXPECT_LT(wide["triangles"], narrow["triangles"]);
  EXPECT_LE(narrow["worst_max_sample_error"], 0.0082 + 1e-12);
  EXPECT_LE(wide["worst_max_sample_error"], 0.014 + 1e-12);
  EXPECT_GT(wide["worst_max_sample_error"], 0.0082);
}

TEST(CliOptions, DensityScalesTheSampleCount) {
  const Args run = scene("sinc");
  const CliRun sparse = ok(run + Args{"--density", "20000"});
  const CliRun dense = ok(run + Args{"--density", "80000"});
  EXPECT_GT(dense["samples"], 3.0 * sparse["samples"]);
}

TEST(CliOptions, EdgeLengthRefinesTheSpheresRightHalf) {
  const Args run = scene("sphere");
  const CliRun long_edges = ok(run + Args{"--edge-length", "0.4"});
  const CliRun short_edges = ok(run + Args{"--edge-length", "0.1"});
  EXPECT_GT(short_edges["triangles"], 2.0 * long_edges["triangles"]);
}

TEST(CliOptions, MaxTrianglesIsHeldAndReported) {
  const Args run = scene("sinc") + Args{"--threshold", "0.002"};
  const CliRun free = ok(run);
  ASSERT_GT(free["peak_triangles"], 3000);
  EXPECT_FALSE(free.json["budget_hit"].get<bool>());
  const CliRun held = ok(run + Args{"--max-triangles", "3000"});
  EXPECT_TRUE(held.json["budget_hit"].get<bool>());
  EXPECT_LE(held["peak_triangles"], 3000);
  EXPECT_LE(free["worst_max_sample_error"], 0.0025 + 1e-12);
}

TEST(CliOptions, SeedChangesTheSamplesOnlyWhenItChanges) {
  const Args run = scene("sinc");
  const CliRun a = ok(run + Args{"--seed", "7"});
  const CliRun again = ok(run + Args{"--seed", "7"});
  const CliRun b = ok(run + Args{"--seed", "8"});
  EXPECT_EQ(a["mean_sample_error"], again["mean_sample_error"]);
  EXPECT_EQ(a["triangles"], again["triangles"]);
  EXPECT_NE(a["mean_sample_error"], b["mean_sample_error"]);
}

TEST(CliOptions, SmoothingShapesTheTriangles) {
  const Args run = scene("capsule-bend") + Args{"--steps", "4"};
  const CliRun none = ok(run + Args{"--no-smooth"});
  const CliRun zero = ok(run + Args{"--smooth-iters", "0"});
  const CliRun some = ok(run + Args{"--smooth-iters", "3"});
  // --no-smooth and zero iterations are the same run.
  EXPECT_EQ(none["mean_aspect_ratio"], zero["mean_aspect_ratio"]);
  EXPECT_EQ(none["triangles"], zero["triangles"]);
  // Smoothing moves vertices towards their neighbours' centroid: rounder triangles.
  EXPECT_LT(some["mean_aspect_ratio"], none["mean_aspect_ratio"]);
}

TEST(CliOptions, CurvatureSensitivityHoldsVerticesInCurvedRegions) {
  const Args run = scene("capsule-bend") + Args{"--steps", "4", "--smooth-iters", "3"};
  const CliRun plain = ok(run + Args{"--k", "0"});
  const CliRun sensitive = ok(run + Args{"--k", "8"});
  // k = 0 is plain tangential Laplacian smoothing, the roundest triangles; a large k holds
  // vertices where the surface curves (Equation 1: exp(-k l) scales their move).
  EXPECT_LT(plain["mean_aspect_ratio"], sensitive["mean_aspect_ratio"]);
  EXPECT_NE(plain["survivor_displacement_mean"], sensitive["survivor_displacement_mean"]);
}

// Smoothing moves summed over the steps after the initial adaptation (stats column).
double moves_after_start(const fs::path& csv) {
  const test::StatsTable table(csv);
  double moved = 0;
  for (std::size_t row = 1; row < table.rows(); ++row)
    moved += table.number(row, "smoothing_moved");
  return moved;
}

TEST(CliOptions, SettledVerticesAreLeftInPlace) {
  // Small steps of a capsule: vertices that stay within 1% of an edge of their ring's centroid
  // are left where they are by --smooth-settled 0.01, and more by 0.1; 0 (the default) moves
  // every vertex every step, as the paper does.
  const fs::path dir = test::cli_scratch("settled");
  // `name` names the stats file; `option` is added to the run (empty: the default).
  auto moves = [&](const std::string& name, const Args& option) {
    const fs::path csv = dir / (name + ".csv");
    ok(Args{"--scene", "capsule-bend", "--threshold", "0.002", "--epsilon", "0.0005", "--t0", "0.5",
            "--t1", "0.51", "--steps", "10", "--stats", csv.string()} +
       option);
    return moves_after_start(csv);
  };
  const double paper = moves("s0", {"--smooth-settled", "0"}),
               settled = moves("s0.01", {"--smooth-settled", "0.01"}),
               coarse = moves("s0.1", {"--smooth-settled", "0.1"});
  EXPECT_EQ(moves("bare", {}), paper);  // without the option: the paper's
  std::printf("smoothing moves over 10 steps: %.0f (0), %.0f (0.01), %.0f (0.1)\n", paper, settled,
              coarse);
  EXPECT_LT(settled, 0.95 * paper);  // measured 0.86: a coarse mesh, many level transitions
  EXPECT_LT(coarse, 0.5 * settled);
}

TEST(CliOptions, RawCurvatureHoldsMoreOnAStronglyCurvedScene) {
  // Equation 1's exp(-k l): l is the curvature normalised to [0, 1] over the mesh by default;
  // raw, it is the curvature itself, up to ~18 per unit on the sinc's crest, so crest
  // vertices hardly move and the triangles there stay as split (rounder without).
  const Args run = scene("sinc") + Args{"--steps", "4", "--smooth-iters", "3"};
  const CliRun normalised = ok(run);
  const CliRun raw = ok(run + Args{"--smooth-raw-curvature"});
  EXPECT_GT(raw["mean_aspect_ratio"], normalised["mean_aspect_ratio"] + 0.05);
  EXPECT_LT(raw["survivor_displacement_mean"], normalised["survivor_displacement_mean"]);
}

TEST(CliOptions, NoStructuralOnlyMovesTheMesh) {
  const Args run = scene("sinc");
  const CliRun adapted = ok(run);
  const CliRun moved = ok(run + Args{"--no-structural"});
  EXPECT_GT(adapted["splits"], 100);
  EXPECT_EQ(moved["splits"], 0);
  EXPECT_EQ(moved["welds"], 0);
  // The base mesh, every step: as many triangles at the start as at the end, far fewer than
  // the adapted mesh, and its vertices follow the surface.
  EXPECT_EQ(moved.json["keyframe_triangles"][0].get<double>(), moved["triangles"]);
  EXPECT_LT(moved["triangles"], adapted["triangles"] / 4);
  EXPECT_GT(moved["survivor_displacement_mean"], 0);
  EXPECT_GT(moved["max_sample_error"], 0.01);  // nothing refines it within T + eps
}

TEST(CliOptions, QuietDropsTheProgressLinesOnly) {
  const Args run = scene("sinc");
  CliRun loud = run_cli(run);
  CliRun quiet = run_cli(run + Args{"--quiet"});
  ASSERT_EQ(loud.status, 0) << loud.err;
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  // One progress line per step (0, 1, 2) without it; none with it; the same JSON.
  const auto progress_lines = [](const std::string& err) {
    std::istringstream lines(err);
    int n = 0;
    for (std::string line; std::getline(lines, line);) n += line.rfind("step ", 0) == 0 ? 1 : 0;
    return n;
  };
  EXPECT_EQ(progress_lines(loud.err), 3) << loud.err;
  EXPECT_EQ(progress_lines(quiet.err), 0) << quiet.err;
  // All but the timings and the process's memory readings: the same JSON.
  for (const char* measured :
       {"seconds_per_step", "preparation_seconds", "resident_mb", "peak_resident_mb"}) {
    loud.json.erase(measured);
    quiet.json.erase(measured);
  }
  EXPECT_EQ(loud.json, quiet.json);
}

TEST(CliOptions, CheckVerifiesWithoutChangingTheRun) {
  // --check verifies the 4-8 invariants after every step: on a healthy run it finds nothing
  // and changes nothing (a broken mesh cannot be made through the binary; the check itself
  // is Mesh48::check, tested in test_mesh48).
  const Args run = scene("capsule-bend");
  const CliRun plain = ok(run);
  const CliRun checked = ok(run + Args{"--check"});
  for (const char* key : {"triangles", "vertices", "max_sample_error", "splits", "welds"})
    EXPECT_EQ(plain[key], checked[key]) << key;
}

TEST(CliOptions, PeriodicClosesTheSeam) {
  // The wobbling tube (assets/examples): u runs around it. --periodic u glues u = 0 to
  // u = 2 pi; without it the tube is a sheet rolled up with an open seam along its length.
  const fs::path dir = test::cli_scratch("periodic");
  const Args tube{"--scene",
                  "expr",
                  "--parametric",
                  "sin(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v)); v; cos(u)*(1 + 0.3*sin(2*pi*t)*cos(3*v))",
                  "--domain",
                  "0,2*pi,-1,1",
                  "--steps",
                  "2",
                  "--t1",
                  "0.2"};
  const auto boundary_edges = [&](const Args& extra, const std::string& name) {
    const std::string ply = (dir / (name + ".ply")).string();
    const CliRun r = ok(tube + extra + Args{"--export-final", ply});
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const auto& f : test::read_ply(ply).faces)
      for (std::size_t i = 0; i < f.size(); ++i) ++uses[std::minmax(f[i], f[(i + 1) % f.size()])];
    return std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; });
  };
  const long closed = boundary_edges({"--periodic", "u"}, "closed");
  const long open = boundary_edges({}, "open");
  // Closed: the two rims (v = -1, 1) alone; open: the seam's two sides too.
  EXPECT_GT(closed, 0);
  EXPECT_GT(open, closed + 8) << open << " vs " << closed;
}

TEST(CliOptions, BadValuesExitTwoWithOneLineNamingTheOption) {
  // Those test_cli.cpp and test_cli_hostile.cpp do not already refuse.
  const std::vector<Args> cases = {
      {"--k", "-1"},
      {"--smooth-iters", "-1"},
      {"--smooth-settled", "-0.01"},
      {"--smooth-settled", "1"},
      {"--edge-length", "-1"},
      {"--seed", "-1"},
      {"--export-every", "0"},
      {"--camera", "1,2,3,4"},
      {"--color-range", "5,1"},
      {"--keyframes", "0,2"},
      {"--scene", "expr", "--parametric", "u;v;0", "--domain", "0,1,0,1", "--periodic", "w"},
      {"--scene", "expr", "--parametric", "u;v;0", "--domain", "0,1"},
      {"--scene", "expr", "--implicit", "x^2+y^2+z^2-1", "--bounds", "1,1,1"}};
  for (const Args& args : cases) {
    const std::string& named = args[args.size() - 2];
    SCOPED_TRACE(named);
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
  }
}

TEST(CliOptions, StatedDefaultsChangeNothing) {
  const Args run = scene("sinc") + Args{"--steps", "3"};
  const CliRun bare = ok(run);
  const CliRun stated =
      ok(run + Args{"--threshold", "0.008", "--epsilon", "0.002", "--density", "2000", "--seed",
                    "1", "--k", "2", "--smooth-iters", "1", "--smooth-settled", "0",
                    "--max-triangles", "2000000", "--export-every", "1"});
  for (const char* key : {"triangles", "vertices", "max_sample_error", "mean_sample_error",
                          "splits", "welds", "samples", "min_angle_deg", "mean_aspect_ratio"})
    EXPECT_EQ(bare[key], stated[key]) << key;
}

TEST(CliOptions, KeyframesSweepThereAndBack) {
  const Args run{"--scene", "sinc", "--steps", "4", "--keyframes", "0.25,0.5,0.25"};
  const CliRun r = ok(run);
  ASSERT_TRUE(r.json["keyframe_triangles"].is_array()) << r.out;
  const auto n = r.json["keyframe_triangles"].get<std::vector<double>>();
  ASSERT_EQ(n.size(), 3u);
  EXPECT_EQ(r["steps"], 8);
  EXPECT_NEAR(r["time"], 0.25, 1e-12);
  EXPECT_EQ(n[2], r["triangles"]);
  // At t = 0.5 the sinc is flat (alpha sin(2 pi t) = 0): far fewer triangles than at its
  // peak amplitude, and back at the peak about as many as the first time.
  EXPECT_LT(n[1], 0.5 * n[0]);
  EXPECT_NEAR(n[2], n[0], 0.15 * n[0]);
  // The peak over the run is at least every keyframe's count.
  EXPECT_GE(r["peak_triangles"], std::max(n[0], n[2]));
  // Without --keyframes: the two ends of [t0, t1].
  const CliRun plain = ok({"--scene", "sinc", "--steps", "2", "--t0", "0.25", "--t1", "0.5"});
  EXPECT_EQ(plain.json["keyframe_triangles"].size(), 2u);
  // Bad keyframes: exit 2.
  for (const Args& bad : {Args{"--keyframes", "0.5"}, Args{"--keyframes", "0,1.5"},
                          Args{"--keyframes", "0,,1"}, Args{"--keyframes", "0,1", "--t1", "1"}}) {
    const CliRun r2 = run_cli(Args{"--scene", "sinc"} + bad);
    EXPECT_EQ(r2.status, 2) << bad[1] << ": " << r2.err;
  }
}

TEST(CliOptions, PeakAndWorstErrorCoverTheWholeRun) {
  // sinc from its peak amplitude (t = 0.25) to flat (t = 0.5): the last step is coarse.
  const CliRun r = ok({"--scene", "sinc", "--steps", "4", "--t0", "0.25", "--t1", "0.5", "--stats",
                       (test::cli_scratch("peak") / "s.csv").string()});
  EXPECT_GT(r["peak_triangles"], 2.0 * r["triangles"]);
  EXPECT_EQ(r["peak_triangles_step"], 0);
  EXPECT_GE(r["worst_max_sample_error"], r["max_sample_error"]);
}

TEST(CliOptions, EpsilonMessageQuotesTheGivenThreshold) {
  const CliRun r = run_cli({"--scene", "sinc", "--threshold", "0.004", "--epsilon", "0.005"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("0.004"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0.008"), std::string::npos) << r.err;
  // Without --threshold, eps is checked against the scene's own T: mri's is 0.5 mm.
  const CliRun mri = run_cli({"--scene", "mri", "--epsilon", "0.1", "--steps", "0", "--quiet"});
  EXPECT_EQ(mri.status, 0) << mri.err;
}

TEST(CliOptions, NoGeometricStopsWhenTheMeshIsLeftBehind) {
  // A moving sinc: the vertices stay while the surface moves; the run stops at step 1 with
  // the reason instead of refining towards the budget for minutes.
  const CliRun moving = run_cli({"--scene", "sinc", "--no-geometric", "--steps", "50", "--quiet"});
  EXPECT_EQ(moving.status, 2) << moving.err;
  EXPECT_NE(moving.err.find("--no-geometric: at step 1"), std::string::npos) << moving.err;
  EXPECT_EQ(std::count(moving.err.begin(), moving.err.end(), '\n'), 1) << moving.err;
  // A static interval: nothing to follow, the run completes within T + eps.
  const CliRun still =
      ok({"--scene", "sinc", "--no-geometric", "--steps", "3", "--t0", "0.3", "--t1", "0.3"});
  EXPECT_LE(still["worst_max_sample_error"], 0.01 + 1e-12);
}

TEST(CliOptions, SmoothingWeightsAreAChoice) {
  const Args run = scene("capsule-bend") + Args{"--steps", "4", "--smooth-iters", "3"};
  const CliRun uniform = ok(run);
  const CliRun stated = ok(run + Args{"--smooth-weights", "uniform"});
  const CliRun inverse = ok(run + Args{"--smooth-weights", "inverse-length"});
  EXPECT_EQ(uniform["mean_aspect_ratio"], stated["mean_aspect_ratio"]);
  EXPECT_NE(uniform["mean_aspect_ratio"], inverse["mean_aspect_ratio"]);
  EXPECT_EQ(run_cli({"--smooth-weights", "cotan"}).status, 2);
}

TEST(CliOptions, VersionIsPrinted) {
  const CliRun r = run_cli({}, "--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("dynamesh-cli ", 0), 0u) << r.out;
}

// The program a user runs sets libgomp's passive wait policy itself (core/parallel.h: it
// executes itself once more with the variable added), and keeps a policy the user set. Run
// from an environment without the variable (the test binary's own has it, from its own start).
TEST(CliOptions, VersionSaysTheWaitPolicyTheProgramRunsWith) {
  const std::string cli = test::shell_quoted(test::cli_path());
  auto version = [&](const std::string& env) {
    const std::string out = (test::cli_scratch("wait_policy") / "version.txt").string();
    const std::string line =
        "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u DYNAMESH_OMP_WAIT_POLICY " + env + " " + cli +
        " --version > " + test::shell_quoted(out);
    EXPECT_EQ(std::system(line.c_str()), 0) << line;
    return test::slurp_file(out);
  };
  const std::string plain = version("");
  EXPECT_NE(plain.find("wait policy: passive (OMP_WAIT_POLICY=passive)\n"), std::string::npos)
      << plain;
  const std::string active = version("OMP_WAIT_POLICY=active");
  EXPECT_NE(active.find("wait policy: user (OMP_WAIT_POLICY=active)\n"), std::string::npos)
      << active;
  const std::string one = version("OMP_NUM_THREADS=1");
  EXPECT_NE(one.find("OpenMP threads: 1,"), std::string::npos) << one;
}

}  // namespace
}  // namespace dynamesh
