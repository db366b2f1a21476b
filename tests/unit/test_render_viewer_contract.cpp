// The viewer's side of the user's contract (issue 12), through the real `dynamesh` under
// Xvfb: scripted runs that cannot show what they were asked exit 2; --threshold refines;
// each scene opens at its own settings (mri in millimetres) or the ones last used with it;
// --frames N shows N frames, steps 0 .. N-1; Esc quits and saves; --version; the sliders
// (driven with xdotool) and every adaptation and view option move the result the documented
// way.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "test_render_scratch.h"
#include "xvfb_run.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
  long triangles = -1;
  long frames = -1, last_step = -1;
};

Outcome viewer(const std::string& options, const fs::path& dir, const std::string& name,
               const std::string& environment = "") {
  const test::XvfbRun run =
      test::run_under_xvfb((environment.empty() ? "" : "env " + environment) +
                               test::viewer_command("--width 900 --height 600 " + options),
                           dir / (name + ".txt"));
  Outcome r;
  r.status = run.status;
  r.output = run.output;
  std::smatch m;
  if (std::regex_search(r.output, m, std::regex("(\\d+) frames in [0-9.]+ s \\((\\d+) triangles")))
    r.frames = std::stol(m[1]), r.triangles = std::stol(m[2]);
  if (std::regex_search(r.output, m, std::regex("last step shown (\\d+)")))
    r.last_step = std::stol(m[1]);
  return r;
}

// A number of a saved state file ("key = value" lines); NaN when absent.
double saved_number(const std::string& saved, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(saved, m, std::regex("(^|\n)" + key + " = ([^\n]+)"))) return std::nan("");
  return std::stod(m[2]);
}

TEST(ViewerContract, ScriptedRunsWithBadInputExitTwo) {
  const fs::path dir = test::render_scratch("viewer_bad");
  const fs::path shot = dir / "x.png";
  const Outcome scene =
      viewer("--scene nosuch --frames 3 --screenshot '" + shot.string() + "'", dir, "scene");
  EXPECT_EQ(scene.status, 2) << scene.output;
  EXPECT_NE(scene.output.find("unknown scene 'nosuch'"), std::string::npos) << scene.output;
  // A formula that does not build: the run cannot show it (the screenshot shows the panel's
  // red message).
  const Outcome formula = viewer(
      "--fresh --scene expr --implicit 'x^2+y^2+z^2+1' --bounds "
      "-1,-1,-1,1,1,1 --frames 2 --screenshot '" +
          shot.string() + "'",
      dir, "formula");
  EXPECT_EQ(formula.status, 2) << formula.output;
  EXPECT_NE(formula.output.find("error shown: "), std::string::npos) << formula.output;
  EXPECT_NE(formula.output.find("no zero crossing"), std::string::npos) << formula.output;
}

TEST(ViewerContract, FramesCountAddsUp) {
  const fs::path dir = test::render_scratch("viewer_frames");
  const Outcome r = viewer("--fresh --scene sinc --frames 5", dir, "frames");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.frames, 5) << r.output;
  EXPECT_EQ(r.last_step, 4) << r.output;
}

TEST(ViewerContract, ThresholdRefines) {
  const fs::path dir = test::render_scratch("viewer_threshold");
  const Outcome fine =
      viewer("--fresh --scene sinc --t0 0.25 --frames 2 --threshold 0.004", dir, "fine");
  const Outcome coarse =
      viewer("--fresh --scene sinc --t0 0.25 --frames 2 --threshold 0.016", dir, "coarse");
  ASSERT_EQ(fine.status, 0) << fine.output;
  ASSERT_EQ(coarse.status, 0) << coarse.output;
  EXPECT_GT(fine.triangles, 2.5 * coarse.triangles) << fine.output << coarse.output;
}

TEST(ViewerContract, KeyframesSweepThereAndBack) {
  const fs::path dir = test::render_scratch("viewer_keyframes");
  // sinc at its peak (t = 0.25), flat at t = 0.5: 3 frames arrive at the flat keyframe,
  // 5 frames are back at the peak.
  const std::string run = "--fresh --scene sinc --keyframes 0.25,0.5,0.25 --steps 2 --frames ";
  const Outcome there = viewer(run + "3", dir, "there");
  const Outcome back = viewer(run + "5", dir, "back");
  ASSERT_EQ(there.status, 0) << there.output;
  ASSERT_EQ(back.status, 0) << back.output;
  EXPECT_EQ(back.last_step, 4);
  EXPECT_GT(back.triangles, 2 * there.triangles) << there.output << back.output;
}

TEST(ViewerContract, KeyframesLeaveTheSavedIntervalAlone) {
  const fs::path dir = test::render_scratch("viewer_keyframes_saved");
  const fs::path state = dir / "viewer.conf";
  const std::string file = "--state '" + state.string() + "' ";
  ASSERT_EQ(viewer(file + "--fresh --scene sinc --t0 0.1 --t1 0.9 --frames 1", dir, "a").status, 0);
  // A sweep for this session: the person's t0 .. t1 is what the next session opens with.
  ASSERT_EQ(viewer(file + "--keyframes 0.25,0.5,0.25 --steps 2 --frames 3", dir, "b").status, 0);
  const std::string saved = test::slurp_text(state);
  EXPECT_NEAR(saved_number(saved, "t0"), 0.1, 1e-12) << saved;
  EXPECT_NEAR(saved_number(saved, "t1"), 0.9, 1e-12) << saved;
}

TEST(ViewerContract, EachSceneOpensAtItsOwnSettings) {
  const fs::path dir = test::render_scratch("viewer_scenes");
  const fs::path state = dir / "viewer.conf";
  // The person set T = 0.03 on sinc (saved at exit).
  const Outcome sinc = viewer("--state '" + state.string() +
                                  "' --fresh --scene sinc "
                                  "--t0 0.25 --threshold 0.03 --frames 1",
                              dir, "sinc");
  ASSERT_EQ(sinc.status, 0) << sinc.output;
  // Switching to sphere: the sphere's own settings, as a fresh start there.
  const Outcome sphere =
      viewer("--state '" + state.string() + "' --scene sphere --t0 0.25 --frames 1", dir, "sphere");
  const Outcome sphere_fresh =
      viewer("--fresh --scene sphere --t0 0.25 --frames 1", dir, "sphere_fresh");
  ASSERT_EQ(sphere.status, 0) << sphere.output;
  EXPECT_EQ(sphere.triangles, sphere_fresh.triangles);
  // Back to sinc: its T = 0.03 again.
  const Outcome back =
      viewer("--state '" + state.string() + "' --scene sinc --t0 0.25 --frames 1", dir, "back");
  const Outcome sinc_fresh = viewer("--fresh --scene sinc --t0 0.25 --frames 1", dir, "fresh");
  EXPECT_EQ(back.triangles, sinc.triangles);
  EXPECT_LT(back.triangles, sinc_fresh.triangles / 2);
  // mri opens at 0.5 mm, as dynamesh-cli run's default (thousands of triangles, not 450,000).
  const Outcome mri = viewer("--fresh --scene mri --frames 1", dir, "mri");
  ASSERT_EQ(mri.status, 0) << mri.output;
  EXPECT_GT(mri.triangles, 1000);
  EXPECT_LT(mri.triangles, 30000) << mri.output;
}

TEST(ViewerContract, EscapeQuitsAndSaves) {
  const fs::path dir = test::render_scratch("viewer_escape");
  const fs::path state = dir / "viewer.conf";
  // An interactive session (no --frames): a key press is the only way out here. The script
  // starts the viewer, waits for its window and presses Esc every half second (a press that
  // arrives before the first frame is drawn is not seen) for at most 30 s.
  const fs::path script = dir / "escape.sh";
  std::ofstream(script) << "'" << DYNAMESH_VIEWER << "' --state '" << state.string()
                        << "' --fresh --scene sinc --width 640 --height 480 &\n"
                        << "pid=$!\n"
                        << "w=$(xdotool search --sync --name dynamesh | head -1)\n"
                        << "for i in $(seq 60); do\n"
                        << "  kill -0 $pid 2>/dev/null || break\n"
                        << "  xdotool windowfocus $w 2>/dev/null\n"
                        << "  xdotool key --window $w Escape 2>/dev/null\n"
                        << "  sleep 0.5\n"
                        << "done\n"
                        << "if kill -0 $pid 2>/dev/null; then kill $pid; exit 9; fi\n"
                        << "wait $pid\n";
  const test::XvfbRun run = test::run_script_under_xvfb(script, dir / "log.txt");
  EXPECT_EQ(run.status, 0) << run.output;
  const std::string saved = test::slurp_text(state);
  EXPECT_NE(saved.find("scene = sinc"), std::string::npos) << saved;
}

// One "key value" line of the viewer's widget report (app/viewer/widget_report.h); NaN when
// absent.
double reported(const std::string& report, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(report, m, std::regex("(^|\n)" + key + " ([^\n]+)"))) return std::nan("");
  return std::stod(m[2]);
}

TEST(ViewerContract, SlidersTakeEffect) {
  const fs::path dir = test::render_scratch("viewer_sliders");
  const fs::path state = dir / "viewer.conf", report = dir / "report.txt";
  // An interactive session driven with a real mouse and keyboard (xdotool): the viewer
  // reports where its sliders are and what it shows (DYNAMESH_WIDGET_REPORT). Each slider is
  // Ctrl-clicked, a value typed and Enter pressed (a log slider applies on release/Enter);
  // then Restart and three steps (">") measure the run with the new value, so each
  // measurement differs from the one before it in that one control alone.
  const fs::path script = dir / "sliders.sh";
  std::ofstream(script)
      << "report='" << report.string() << "'\n"
      << "DYNAMESH_WIDGET_REPORT=\"$report\" '" << DYNAMESH_VIEWER << "' --state '"
      << state.string()
      << "' --fresh --scene capsule-bend --t0 0.2 --t1 0.3 --steps 4 --smooth-iters 3 "
         "--width 1000 --height 760 &\n"
      << "pid=$!\n"
      << "val() { awk -v k=\"$1\" '$1==k {print $2}' \"$report\" 2>/dev/null; }\n"
      // Waits (at most 60 s) until the viewer took more than $1 results and is idle.
      << "settle() {\n"
      << "  for i in $(seq 240); do\n"
      << "    kill -0 $pid 2>/dev/null || return 1\n"
      << "    r=$(val results); b=$(val busy)\n"
      << "    [ -n \"$r\" ] && [ \"$r\" -gt \"$1\" ] && [ \"$b\" = 0 ] &&\n"
      << "      [ -n \"$(val triangles)\" ] && return 0\n"
      << "    sleep 0.25\n"
      << "  done\n"
      << "  return 1\n"
      << "}\n"
      << "centre() { awk -v k=\"$1\" '$1==\"widget\" && $2==k {print int(($3+$5)/2), "
         "int(($4+$6)/2)}' \"$report\"; }\n"
      << "click() { set -- $(centre \"$1\"); [ -n \"$2\" ] || exit 3; r=$(val results)\n"
      << "  xdotool mousemove --window $w $1 $2 click 1; settle $r || exit 4; }\n"
      // Keys are held as a person holds them (ImGui 1.86 reads the keys that are down when a
      // frame starts: a press and release within one frame is lost), and repeated until the
      // report shows their effect: Ctrl-click until the slider takes typing, Enter until it
      // lets go.
      << "active() { [ \"$(awk '$1==\"active\" {print $2}' \"$report\")\" = \"$1\" ]; }\n"
      << "hold() { xdotool keydown $1; sleep 0.3; xdotool keyup $1; }\n"
      << "slider() { set -- $(centre \"$1\") \"$1\" \"$2\"; [ -n \"$4\" ] || exit 5\n"
      << "  for i in 1 2 3 4 5 6; do\n"
      << "    xdotool mousemove --window $w $1 $2 keydown ctrl; sleep 0.3; xdotool click 1\n"
      << "    sleep 0.3; xdotool keyup ctrl; sleep 0.5; active $3 && break\n"
      << "  done\n"
      << "  active $3 || exit 6; r=$(val results); xdotool type --delay 50 \"$4\"\n"
      << "  for i in $(seq 20); do hold Return; sleep 0.2; active $3 || break; done\n"
      << "  settle $r || exit 7; }\n"
      << "measure() { click Restart; for s in 1 2 3; do click step_forward; done\n"
      << "  cp \"$report\" \"$report.$1\"; }\n"
      << "settle 0 || exit 2\n"
      << "w=$(xdotool search --sync --name dynamesh | head -1)\n"
      << "xdotool windowfocus $w 2>/dev/null\n"
      << "measure base\n"
      << "slider k 8; measure k8\n"
      << "slider k 0; measure k0\n"
      << "slider density 8000; measure dense\n"
      << "slider epsilon 0.0075; measure wide\n"
      << "slider threshold_T 0.002; measure fine\n"
      << "for i in $(seq 60); do kill -0 $pid 2>/dev/null || break; hold Escape; sleep 0.2; done\n"
      << "if kill -0 $pid 2>/dev/null; then kill $pid; exit 9; fi\n"
      << "wait $pid\n";
  const test::XvfbRun run =
      test::run_script_under_xvfb(script, dir / "log.txt", {.screen = "1280x900x24"});
  ASSERT_EQ(run.status, 0) << run.output;
  const auto read = [&](const char* name) {
    return test::slurp_text(report.string() + "." + name);
  };
  const std::string base = read("base"), k8 = read("k8"), k0 = read("k0"), dense = read("dense"),
                    wide = read("wide"), fine = read("fine");
  // Each slider holds the typed value (eps follows T: 0.0075 * 0.002 / 0.008).
  EXPECT_EQ(reported(k8, "k"), 8);
  EXPECT_EQ(reported(k0, "k"), 0);
  EXPECT_EQ(reported(dense, "density"), 8000);
  EXPECT_EQ(reported(wide, "epsilon"), 0.0075);
  EXPECT_EQ(reported(fine, "threshold"), 0.002);
  // Typing "0.002" passes through 0: the band must keep its width relative to T.
  EXPECT_NEAR(reported(fine, "epsilon"), 0.001875, 1e-9);
  for (const std::string* r : {&base, &k8, &k0, &dense, &wide, &fine})
    EXPECT_EQ(reported(*r, "step"), 3) << *r;
  // k = 0 is plain tangential smoothing: rounder triangles than k = 8, which holds the
  // vertices where the surface curves (as dynamesh-cli run --k).
  EXPECT_LT(reported(k0, "mean_aspect"), reported(k8, "mean_aspect")) << k0 << k8;
  // Four times the density: more than three times the samples.
  EXPECT_GT(reported(dense, "samples"), 3 * reported(k0, "samples")) << dense << k0;
  // A wide band splits only above T + eps: fewer triangles.
  EXPECT_LT(reported(wide, "triangles"), reported(dense, "triangles")) << wide << dense;
  // A quarter of T: well over twice the triangles.
  EXPECT_GT(reported(fine, "triangles"), 2.5 * reported(wide, "triangles")) << fine << wide;
  // Esc saved what the sliders hold.
  const std::string saved = test::slurp_text(state);
  EXPECT_NEAR(saved_number(saved, "threshold"), 0.002, 1e-15) << saved;
  EXPECT_NEAR(saved_number(saved, "epsilon"), 0.001875, 1e-9) << saved;
  EXPECT_EQ(saved_number(saved, "k"), 0) << saved;
  EXPECT_EQ(saved_number(saved, "density"), 8000) << saved;
}

// A scripted run's last frame as the viewer reports it (widget_report.h): the controls it
// ran with and the mesh on screen.
std::string shown(const std::string& options, const fs::path& dir, const std::string& name) {
  const fs::path report = dir / (name + ".report");
  const Outcome r =
      viewer("--fresh " + options, dir, name, "DYNAMESH_WIDGET_REPORT='" + report.string() + "' ");
  EXPECT_EQ(r.status, 0) << r.output;
  return test::slurp_text(report);
}

TEST(ViewerOptions, AdaptationOptionsMoveTheResultTheDocumentedWay) {
  const fs::path dir = test::render_scratch("viewer_options");
  // capsule-bend over a short stretch of its motion, 4 frames (steps 0 .. 3).
  const std::string run = "--scene capsule-bend --t0 0.2 --t1 0.3 --steps 4 --frames 4 ";
  const auto at = [&](const std::string& options, const std::string& name) {
    const std::string r = shown(run + options, dir, name);
    EXPECT_EQ(reported(r, "step"), 3) << name << ": " << r;
    return r;
  };
  // --epsilon: a wide band splits only above T + eps, fewer triangles.
  const std::string narrow = at("--epsilon 0.0002", "narrow"),
                    wide = at("--epsilon 0.0075", "wide");
  EXPECT_EQ(reported(wide, "epsilon"), 0.0075);
  EXPECT_LT(reported(wide, "triangles"), reported(narrow, "triangles")) << wide << narrow;
  // --density: four times the samples per unit area, more than three times the samples.
  const std::string sparse = at("--density 2000", "sparse"), dense = at("--density 8000", "dense");
  EXPECT_GT(reported(dense, "samples"), 3 * reported(sparse, "samples"));
  // --k: plain smoothing (0) gives rounder triangles than a curvature-held one (8).
  const std::string k0 = at("--smooth-iters 3 --k 0", "k0"),
                    k8 = at("--smooth-iters 3 --k 8", "k8");
  EXPECT_LT(reported(k0, "mean_aspect"), reported(k8, "mean_aspect")) << k0 << k8;
  // --smooth-iters: smoothing rounds the triangles; none leaves them as split.
  const std::string none = at("--smooth-iters 0", "none"), three = at("--smooth-iters 3", "three");
  EXPECT_LT(reported(three, "mean_aspect"), reported(none, "mean_aspect")) << three << none;
  // --smooth-settled: vertices nearer their ring's centroid than this fraction of an edge stay
  // where they are: at 0.05 many do, and the triangles keep more of their split shape than with
  // every vertex smoothed, less than with none (measured 1.487 against 1.455 and 1.650).
  const std::string settled = at("--smooth-iters 3 --smooth-settled 0.05", "settled");
  EXPECT_EQ(reported(settled, "smooth_settled"), 0.05);
  EXPECT_EQ(reported(three, "smooth_settled"), 0.0);
  EXPECT_GT(reported(settled, "mean_aspect"), reported(three, "mean_aspect")) << settled << three;
  EXPECT_LT(reported(settled, "mean_aspect"), reported(none, "mean_aspect")) << settled << none;
  // --seed: the same seed, the same run; another, other samples.
  const std::string seed7 = at("--seed 7", "seed7"), again = at("--seed 7", "again"),
                    seed8 = at("--seed 8", "seed8");
  EXPECT_EQ(reported(seed7, "mean_error"), reported(again, "mean_error"));
  EXPECT_EQ(reported(seed7, "triangles"), reported(again, "triangles"));
  EXPECT_NE(reported(seed7, "mean_error"), reported(seed8, "mean_error"));
}

TEST(ViewerOptions, EdgeLengthAndBudget) {
  const fs::path dir = test::render_scratch("viewer_options_budget");
  // --edge-length: the sphere's x >= 0 half follows it.
  const std::string sphere = "--scene sphere --t0 0.2 --frames 1 ";
  const std::string long_edges = shown(sphere + "--edge-length 0.4", dir, "long"),
                    short_edges = shown(sphere + "--edge-length 0.1", dir, "short");
  EXPECT_GT(reported(short_edges, "triangles"), 2 * reported(long_edges, "triangles"));
  // --max-triangles: held.
  const std::string sinc = "--scene sinc --t0 0.25 --threshold 0.002 --frames 1 ";
  const std::string free = shown(sinc, dir, "free"),
                    held = shown(sinc + "--max-triangles 3000", dir, "held");
  ASSERT_GT(reported(free, "triangles"), 3000) << free;
  EXPECT_LE(reported(held, "triangles"), 3000) << held;
  EXPECT_GT(reported(held, "triangles"), 1000) << held;
}

// The 3D view of a scripted run's screenshot (900x600; the panel is 340 wide, the colour
// bar's card the right 130): pixels that differ from the background, their darkness, hue and
// saturation.
struct View {
  int mesh = 0, dark = 0, coloured = 0;  // coloured: saturation > 0.25
  double saturation = 0;                 // mean over the mesh pixels
  double hue_p5 = 0, hue_p95 = 0;        // of the coloured mesh pixels (saturation > 0.25), degrees
};

View look(const std::string& options, const fs::path& dir, const std::string& name) {
  const fs::path shot = dir / (name + ".png");
  const Outcome r =
      viewer("--fresh --frames 1 --screenshot '" + shot.string() + "' " + options, dir, name);
  EXPECT_EQ(r.status, 0) << r.output;
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load(shot.c_str(), &w, &h, &n, 3);
  View v;
  if (pixels == nullptr) {
    ADD_FAILURE() << "no screenshot " << shot;
    return v;
  }
  const stbi_uc* background = pixels + 3 * (5 * w + 345);
  std::vector<double> hues;
  for (int y = 5; y < h - 5; ++y)
    for (int x = 345; x < w - 135; ++x) {
      const stbi_uc* p = pixels + 3 * (y * w + x);
      const int diff = std::abs(p[0] - background[0]) + std::abs(p[1] - background[1]) +
                       std::abs(p[2] - background[2]);
      if (diff < 24) continue;
      ++v.mesh;
      v.dark += p[0] + p[1] + p[2] < 150 ? 1 : 0;
      const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
      const double sat = hi > 0 ? double(hi - lo) / hi : 0.0;
      v.saturation += sat;
      if (sat > 0.25 && hi > lo) {
        double hue = hi == p[0]   ? 60.0 * (p[1] - p[2]) / (hi - lo)
                     : hi == p[1] ? 120.0 + 60.0 * (p[2] - p[0]) / (hi - lo)
                                  : 240.0 + 60.0 * (p[0] - p[1]) / (hi - lo);
        hues.push_back(hue < 0 ? hue + 360 : hue);
      }
    }
  stbi_image_free(pixels);
  if (v.mesh > 0) v.saturation /= v.mesh;
  v.coloured = static_cast<int>(hues.size());
  if (!hues.empty()) {
    std::sort(hues.begin(), hues.end());
    v.hue_p5 = hues[hues.size() / 20];
    v.hue_p95 = hues[hues.size() * 19 / 20];
  }
  return v;
}

TEST(ViewerOptions, ViewOptionsChangeThePicture) {
  const fs::path dir = test::render_scratch("viewer_view_options");
  const std::string sinc = "--scene sinc --t0 0.25 ";
  // --camera: from above the sinc fills its square; edge on, a thin band. Closer is bigger.
  const View above = look(sinc + "--color shaded --no-wireframe --camera 0,90", dir, "above");
  const View edge = look(sinc + "--color shaded --no-wireframe --camera 0,0", dir, "edge");
  EXPECT_GT(above.mesh, 3 * edge.mesh) << above.mesh << " " << edge.mesh;
  const View near = look(sinc + "--color shaded --no-wireframe --camera 30,30,3", dir, "near");
  const View far = look(sinc + "--color shaded --no-wireframe --camera 30,30,6", dir, "far");
  EXPECT_GT(near.mesh, 2.5 * far.mesh) << near.mesh << " " << far.mesh;
  // --wireframe / --no-wireframe: the edges are the dark pixels.
  const View wire = look(sinc + "--color shaded --wireframe --camera 0,90", dir, "wire");
  EXPECT_GT(wire.dark, 10 * above.dark + 100) << wire.dark << " " << above.dark;
  // --color: the error map is saturated (yellow to red); shaded is grey-blue.
  const View error = look(sinc + "--color error --no-wireframe --camera 0,90", dir, "error");
  EXPECT_GT(error.saturation, above.saturation + 0.2)
      << error.saturation << " " << above.saturation;
  // --color-range: each frame's own range spans the bar's hues; a range far wider than the
  // curvature's (at most 18 here) puts every vertex at the bottom of the bar: one hue.
  const std::string curvature = sinc + "--color curvature --no-wireframe --camera 0,90 ";
  const View own = look(curvature + "--color-range frame", dir, "own");
  const View wide = look(curvature + "--color-range 0,1000", dir, "wide");
  EXPECT_GT(own.hue_p95 - own.hue_p5, 60) << own.hue_p5 << " " << own.hue_p95;
  EXPECT_LT(wide.hue_p95 - wide.hue_p5, 15) << wide.hue_p5 << " " << wide.hue_p95;
  EXPECT_GT(wide.coloured, wide.mesh / 2) << wide.coloured << " of " << wide.mesh;
}

TEST(ViewerOptions, FrameLogHasARowPerFrame) {
  const fs::path dir = test::render_scratch("viewer_frame_log");
  const fs::path log = dir / "frames.csv";
  const Outcome r =
      viewer("--fresh --scene sinc --frames 4 --frame-log '" + log.string() + "'", dir, "run");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(log);
  std::string line;
  int rows = 0;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) rows += line.empty() ? 0 : 1;
  EXPECT_EQ(rows, r.frames) << test::slurp_text(log);
  EXPECT_EQ(rows, 4);
}

TEST(ViewerContract, BadValuesExitTwoWithOneLineNamingTheOption) {
  // Refused before a window opens: no display needed.
  const fs::path dir = test::render_scratch("viewer_bad_values");
  const std::pair<const char*, const char*> cases[] = {{"--threshold 0", "--threshold"},
                                                       {"--epsilon 1", "--epsilon"},
                                                       {"--density 0", "--density"},
                                                       {"--k -1", "--k"},
                                                       {"--smooth-iters -1", "--smooth-iters"},
                                                       {"--smooth-settled 1", "--smooth-settled"},
                                                       {"--edge-length -1", "--edge-length"},
                                                       {"--max-triangles 1", "--max-triangles"},
                                                       {"--seed -1", "--seed"},
                                                       {"--steps 0", "--steps"},
                                                       {"--t0 0.6 --t1 0.4", "--t0"},
                                                       {"--keyframes 0,2", "--keyframes"},
                                                       {"--color rainbow", "--color"},
                                                       {"--color-range 5,1", "--color-range"},
                                                       {"--camera 1,2,3,4", "--camera"},
                                                       {"--param x", "--param"},
                                                       {"--width 10", "--width"},
                                                       {"--frames 0", "--frames"},
                                                       {"--run-for -1", "--run-for"},
                                                       {"--orbit", "--orbit"},
                                                       {"--screenshot x.png", "--screenshot"},
                                                       {"--scene nosuch", "unknown scene"},
                                                       {"--no-such-option", "--no-such-option"}};
  for (const auto& [options, named] : cases) {
    SCOPED_TRACE(options);
    const fs::path err = dir / "err.txt";
    const int raw = std::system(
        test::viewer_command(std::string(options) + " > /dev/null 2> '" + err.string() + "'")
            .c_str());
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 2) << raw;
    const std::string text = test::slurp_text(err);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_NE(text.find(named), std::string::npos) << text;
  }
}

TEST(ViewerOptions, ParameterAndTimeChooseTheSurface) {
  const fs::path dir = test::render_scratch("viewer_surface_options");
  // sinc at its crest (t = 0.25) needs many triangles; --param alpha=0 flattens it, and
  // t = 0.5 is its flat moment: both need only the base mesh.
  const std::string crest = shown("--scene sinc --t0 0.25 --frames 1", dir, "crest");
  const std::string flat = shown("--scene sinc --t0 0.25 --param alpha=0 --frames 1", dir, "flat");
  const std::string later = shown("--scene sinc --t0 0.5 --t1 1 --frames 1", dir, "later");
  EXPECT_GT(reported(crest, "triangles"), 4 * reported(flat, "triangles")) << crest << flat;
  EXPECT_GT(reported(crest, "triangles"), 4 * reported(later, "triangles")) << crest << later;
  // --help: exit 0, every option on its usage text.
  const fs::path help = dir / "help.txt";
  ASSERT_EQ(std::system(test::viewer_command("--help > '" + help.string() + "'").c_str()), 0);
  const std::string usage = test::slurp_text(help);
  for (const char* option :
       {"--scene",        "--param",       "--volume",        "--t0",      "--keyframes",
        "--steps",        "--threshold",   "--epsilon",       "--density", "--k",
        "--smooth-iters", "--edge-length", "--max-triangles", "--seed",    "--color",
        "--play",         "--color-range", "--no-wireframe",  "--camera",  "--width",
        "--state",        "--fresh",       "--frames",        "--run-for", "--orbit",
        "--screenshot",   "--record",      "--frame-log",     "--version"})
    EXPECT_NE(usage.find(option), std::string::npos) << option;
}

TEST(ViewerContract, VersionIsPrinted) {
  const std::string out = (test::render_scratch("viewer_version") / "v.txt").string();
  ASSERT_EQ(std::system(test::viewer_command("--version > " + out).c_str()), 0);
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("dynamesh ", 0), 0u) << line;
}

}  // namespace
}  // namespace dynamesh
