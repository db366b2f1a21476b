// The viewer against hostile input (issue 15): every value from its command line, viewer.conf
// or a --state file is validated as dynamesh-cli validates it; a broken saved state is
// reported (stderr and the panel's status line) and the viewer starts from the defaults,
// never crashes or hangs. The real viewer runs under xvfb-run with `timeout`.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <csignal>
#include <thread>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/viewer/simulation.h"
#include "app/viewer/viewer_args.h"
#include "app/viewer/viewer_state.h"
#include "cli_runner.h"
#include "test_render_scratch.h"
#include "test_render_step_request.h"
#include "xvfb_run.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

std::string refusal(const std::vector<std::string>& args, const ViewerState& base = {}) {
  try {
    parse_viewer_args(args, base);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ViewerHostile, CommandLineValuesAreCheckedAsTheCliChecksThem) {
  EXPECT_NE(refusal({"--density", "inf"}).find("--density expects a number"), std::string::npos);
  EXPECT_NE(refusal({"--k", "nan"}).find("--k expects a number"), std::string::npos);
  EXPECT_NE(refusal({"--edge-length", "nan"}).find("--edge-length expects a number"),
            std::string::npos);
  EXPECT_NE(refusal({"--threshold", "1e400"}).find("expects a number"), std::string::npos);
  EXPECT_NE(refusal({"--steps", "4294967297"}).find("--steps expects a whole number in [1,"),
            std::string::npos);
  EXPECT_NE(refusal({"--max-triangles", "1e10"}).find("--max-triangles expects"),
            std::string::npos);
  EXPECT_NE(refusal({"--smooth-iters", "2147483647"}).find("--smooth-iters expects"),
            std::string::npos);
  EXPECT_NE(refusal({"--volume", ""}).find("--volume needs a value, got an empty string"),
            std::string::npos);
  EXPECT_NE(refusal({"--camera", "0,0,1e38"}).find("the distance must be in [1e-4, 1e5]"),
            std::string::npos);
  const std::string long_scene(20000, 'x');
  const std::string m = refusal({"--scene", long_scene});
  EXPECT_NE(m.find("unknown scene"), std::string::npos);
  EXPECT_LT(m.size(), 200u);  // the name is not echoed whole
  EXPECT_EQ(refusal({"--scene", "sinc", "--density", "500"}), "(accepted)");
}

// The adaptation's limits are one check (core/adapt/adapt_options_check.h) and its values are
// read by one reader (core/io/number_text.h): a bad value gets the same line from the viewer
// as from dynamesh-cli run, whose binary exits 2 with it.
TEST(ViewerHostile, AdaptationLimitsGiveTheCliLineWordForWord) {
  const std::vector<std::vector<std::string>> cases = {
      {"--threshold", "0"},       {"--epsilon", "-0.001"},
      {"--density", "0"},         {"--k", "-1"},
      {"--smooth-settled", "1"},  {"--smooth-settled", "-0.5"},
      {"--smooth-iters", "1001"}, {"--smooth-iters", "2.5"},
      {"--density", "12abc"},     {"--threshold", "1e400"}};
  for (const std::vector<std::string>& args : cases) {
    SCOPED_TRACE(args[0] + " " + args[1]);
    const std::string viewer = refusal(args);
    EXPECT_EQ(viewer.rfind(args[0] + " ", 0), 0u) << viewer;
    const test::CliRun cli = test::run_cli(args);
    EXPECT_EQ(cli.status, 2) << cli.err;
    EXPECT_EQ(std::count(cli.err.begin(), cli.err.end(), '\n'), 1) << cli.err;
    EXPECT_NE(cli.err.find(viewer + "\n"), std::string::npos) << cli.err << " vs " << viewer;
  }
  // The triangle budget's floor, once the viewer's (8) and the CLI's (2): now 2 in both.
  EXPECT_EQ(refusal({"--max-triangles", "2"}), "(accepted)");
  EXPECT_NE(refusal({"--max-triangles", "1"}).find("[2,"), std::string::npos);
  EXPECT_EQ(test::run_cli({"--max-triangles", "1"}).status, 2);
}

// A saved state with one bad value: parse_viewer_args over it refuses it (main then starts
// from the defaults with a notice).
TEST(ViewerHostile, SavedValuesAreCheckedLikeCommandLineValues) {
  const fs::path dir = test::render_scratch("viewer_hostile_state");
  const std::vector<std::pair<std::string, std::string>> bad = {{"smooth_iterations", "2147483647"},
                                                                {"camera.distance", "-5"},
                                                                {"camera.distance", "1e38"},
                                                                {"camera.fov_y_degrees", "0"},
                                                                {"camera.fov_y_degrees", "180"},
                                                                {"wire_width", "1e30"},
                                                                {"scene", std::string(20000, 'x')},
                                                                {"density", "0"},
                                                                {"steps", "0"},
                                                                {"camera.rotation", "0 0 0 0"},
                                                                {"record_fps", "0"},
                                                                {"threshold", "-1"},
                                                                {"smooth_settled", "-0.1"}};
  for (const auto& [key, value] : bad) {
    const fs::path file = dir / "viewer.conf";
    std::ofstream(file) << "scene = sinc\n" << key << " = " << value << "\n";
    ViewerState saved;
    ASSERT_TRUE(load_viewer_state(saved, file.string()));
    EXPECT_NE(refusal({}, saved), "(accepted)") << key << " = " << value.substr(0, 40);
  }
  std::ofstream(dir / "good.conf") << "scene = sinc\ncamera.distance = 4\nwire_width = 2\n";
  ViewerState saved;
  ASSERT_TRUE(load_viewer_state(saved, (dir / "good.conf").string()));
  EXPECT_EQ(refusal({}, saved), "(accepted)");
  // Values that do not read as numbers are skipped (the default stays) and reported.
  std::ofstream(dir / "malformed.conf")
      << "scene = sinc\ndensity = 1e400\nk = nan\nsteps = 4294967297\nthreshold = 0.01\n";
  ViewerState fresh;
  std::vector<std::string> rejected;
  ASSERT_TRUE(load_viewer_state(fresh, (dir / "malformed.conf").string(), &rejected));
  EXPECT_EQ(rejected, (std::vector<std::string>{"density", "k", "steps"}));
  EXPECT_EQ(fresh.controls.density, ViewerState{}.controls.density);
  EXPECT_EQ(fresh.steps, ViewerState{}.steps);
  EXPECT_EQ(fresh.controls.threshold, 0.01);
}

using ViewerRun = test::XvfbRun;

ViewerRun run_viewer(const std::string& options, const fs::path& log) {
  return test::run_under_xvfb(test::viewer_command(options), log, {.kill_after_seconds = 60});
}

TEST(ViewerHostile, StartsWhateverItsSavedStateHolds) {
  const fs::path dir = test::render_scratch("viewer_hostile_start");
  const fs::path state = dir / "viewer.conf";
  // The 20,000-character scene name that aborted ImGui at every start.
  std::ofstream(state) << "scene = " << std::string(20000, 'x') << "\nsmooth_iterations = 2\n";
  const fs::path shot = dir / "shot.png";
  const ViewerRun r =
      run_viewer("--state '" + state.string() + "' --frames 2 --screenshot '" + shot.string() + "'",
                 dir / "log.txt");
  ASSERT_EQ(r.status, 0) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("ignoring the saved settings in"), std::string::npos)
      << r.output.substr(0, 2000);
  EXPECT_TRUE(fs::exists(shot));
  EXPECT_LT(r.output.size(), 4000u);  // the name is not echoed whole
}

// Session 4: a state file with 200,000 `param.` lines ran for minutes (make_scene kept the
// last value per key by comparing every pair; killed at 60 s): now read in seconds, and the
// first unknown parameter is the message.
TEST(ViewerHostile, AStateWithManyParametersIsReadInSeconds) {
  const fs::path dir = test::render_scratch("viewer_hostile_many");
  const fs::path state = dir / "viewer.conf";
  {
    std::ofstream out(state);
    out << "scene = sinc\n";
    for (int i = 1; i <= 200000; ++i) out << "param.p" << i << " = 1\n";
  }
  const auto start = std::chrono::steady_clock::now();
  const ViewerRun r = run_viewer("--state '" + state.string() + "' --frames 2 --screenshot '" +
                                     (dir / "shot.png").string() + "'",
                                 dir / "log.txt");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.status, 2) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("error shown: sinc: no parameter 'p1'"), std::string::npos)
      << r.output.substr(0, 2000);
  EXPECT_LT(seconds, 40.0);  // xvfb-run's start included
}

// A scripted run ended by a signal (session 4) exited 0 with no word, its movie looking like
// a finished recording: now it says it was stopped and what stays, and ends with 128 + the
// signal as dynamesh-cli does. The screenshot and frame log of an unfinished run are not
// written.
TEST(ViewerHostile, ASignalEndsAScriptedRunWithItsStatus) {
  for (const int signal : {SIGTERM, SIGINT}) {
    const fs::path dir = test::render_scratch("viewer_hostile_signal_" + std::to_string(signal));
    const fs::path pid_file = dir / "pid", movie = dir / "movie.mp4";
    // sh records its pid, then becomes the viewer: the signal goes to the viewer itself.
    const std::string command =
        "sh -c 'echo $$ > \"" + pid_file.string() + "\"; exec \"" + DYNAMESH_VIEWER +
        "\" --fresh --width 400 --height 300 --scene sinc --play --run-for 50 --record \"" +
        movie.string() + "\" --screenshot \"" + (dir / "shot.png").string() + "\" --frame-log \"" +
        (dir / "frames.csv").string() + "\"'";
    std::thread viewer([&] {
      const test::XvfbRun run =
          test::run_under_xvfb(command, dir / "log.txt", {.kill_after_seconds = 60});
      std::ofstream(dir / "status") << run.status;
    });
    // Signalled once frames are being recorded (into movie.mp4.partial until it is done).
    const fs::path partial = movie.string() + ".partial";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(40);
    std::error_code ec;
    while (!(fs::exists(partial) && fs::file_size(partial, ec) > 0) &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::seconds(1));
    pid_t pid = 0;
    std::ifstream(pid_file) >> pid;
    ASSERT_GT(pid, 0);
    ::kill(pid, signal);
    viewer.join();
    int status = -1;
    std::ifstream(dir / "status") >> status;
    std::ifstream in(dir / "log.txt");
    const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(status, 128 + signal) << log;
    EXPECT_NE(log.find("stopped by signal " + std::to_string(signal) +
                       " before the scripted run was done; recorded "),
              std::string::npos)
        << log;
    EXPECT_TRUE(fs::exists(movie)) << log;  // a whole file of the frames so far, as said
    EXPECT_FALSE(fs::exists(dir / "shot.png"));
    EXPECT_FALSE(fs::exists(dir / "frames.csv"));
  }
}

// The formulas and settings that hung the CLI hang the viewer's worker the same way (a window
// that never shows a mesh, a scripted run that never ends): the same up-front workload check
// refuses them with its reason in the panel, and a scripted run exits 2.
TEST(ViewerHostile, SurfacesThatWouldHangAreRefusedWithTheReason) {
  const fs::path dir = test::render_scratch("viewer_hostile_workload");
  struct Case {
    std::string name, options, reason;
  };
  const std::vector<Case> cases = {
      {"overflow", "--scene expr --height-field 'exp(700*x)'", "not finite"},
      {"ripples", "--scene expr --height-field 'sin(1000*x)'", "more than the triangle budget"},
      {"tiny_threshold", "--scene sphere --threshold 1e-6", "more than the triangle budget"},
      // Session 4: the edge-length demand (shared with dynamesh-cli, workload_check.h). Both
      // ran for ever towards 10^8 triangles (killed at 60 s).
      {"tiny_edge_length", "--scene sphere --edge-length 0.001",
       "edges of at most the edge length 0.001 need at least about"},
      {"tiny_scene_L", "--scene sphere --param L=0.001",
       "edges of at most the scene's L 0.001 need at least about"},
      {"tiny_edges_capsule", "--scene capsule-bend --edge-length 0.001",
       "edges of at most the edge length 0.001 need at least about"},
  };
  for (const Case& c : cases) {
    const fs::path shot = dir / (c.name + ".png");
    const auto start = std::chrono::steady_clock::now();
    const ViewerRun r = run_viewer("--fresh --width 900 --height 600 " + c.options +
                                       " --frames 2 --screenshot '" + shot.string() + "'",
                                   dir / (c.name + ".txt"));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.output.substr(0, 2000);
    const std::size_t shown = r.output.find("error shown: ");
    ASSERT_NE(shown, std::string::npos) << c.name << ": " << r.output.substr(0, 2000);
    EXPECT_NE(r.output.find(c.reason, shown), std::string::npos) << c.name << ": " << r.output;
    EXPECT_LT(seconds, 40.0) << c.name;  // xvfb-run's start included
  }
}

// A control changed while the mesh runs (T lowered on its slider) is checked before the
// adapter refines for it: the message comes back at once and the next sensible value works.
TEST(ViewerHostile, AThresholdNoBudgetCanMeetIsRefusedBeforeRefining) {
  Simulation sim;
  SimulationControls c;
  c.scene = "sphere";
  ASSERT_TRUE(sim.step(test::at(0.2, c)).error.empty());
  c.threshold = 1e-6;
  c.epsilon = 2.5e-7;
  const auto start = std::chrono::steady_clock::now();
  const StepResult refused = sim.step(test::at(0.2, c));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  EXPECT_NE(refused.error.find("more than the triangle budget"), std::string::npos)
      << refused.error;
  EXPECT_FALSE(refused.snapshot);
  c.threshold = 0.004;
  c.epsilon = 0.001;
  const StepResult finer = sim.step(test::at(0.2, c));
  EXPECT_TRUE(finer.error.empty()) << finer.error;
  EXPECT_GT(finer.stats.triangles, 0u);
}

// The same for the edge length typed in the panel on a running mesh (a retune): refused before
// refining, and the scene's own L works again after.
TEST(ViewerHostile, AnEdgeLengthNoBudgetCanMeetIsRefusedBeforeRefining) {
  Simulation sim;
  SimulationControls c;
  c.scene = "sphere";
  ASSERT_TRUE(sim.step(test::at(0.2, c)).error.empty());
  c.edge_length = 0.001;
  const auto start = std::chrono::steady_clock::now();
  const StepResult refused = sim.step(test::at(0.2, c));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  EXPECT_NE(refused.error.find("edges of at most the edge length 0.001"), std::string::npos)
      << refused.error;
  EXPECT_FALSE(refused.snapshot);
  c.edge_length = 0.0;
  const StepResult own = sim.step(test::at(0.2, c));
  EXPECT_TRUE(own.error.empty()) << own.error;
  EXPECT_GT(own.stats.triangles, 0u);
}

}  // namespace
}  // namespace dynamesh
