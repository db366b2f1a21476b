// The viewer's side of the user's contract (issue 12), through the real `dynamesh` under
// Xvfb: scripted runs that cannot show what they were asked exit 2; --threshold refines;
// each scene opens at its own settings (mri in millimetres) or the ones last used with it;
// --frames N shows N frames, steps 0 .. N-1; Esc quits and saves; --version.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "test_render_scratch.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
  long triangles = -1;
  long frames = -1, last_step = -1;
};

Outcome viewer(const std::string& options, const fs::path& dir, const std::string& name) {
  const fs::path log = dir / (name + ".txt");
  const std::string command = "xvfb-run -a -s '-screen 0 1280x800x24' '" +
                              std::string(DYNAMESH_VIEWER) + "' --width 900 --height 600 " +
                              options + " > '" + log.string() + "' 2>&1";
  Outcome r;
  const int raw = std::system(command.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::smatch m;
  if (std::regex_search(r.output, m, std::regex("(\\d+) frames in [0-9.]+ s \\((\\d+) triangles")))
    r.frames = std::stol(m[1]), r.triangles = std::stol(m[2]);
  if (std::regex_search(r.output, m, std::regex("last step shown (\\d+)")))
    r.last_step = std::stol(m[1]);
  return r;
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
  const std::string command = "xvfb-run -a -s '-screen 0 1280x800x24' sh '" + script.string() +
                              "' > '" + (dir / "log.txt").string() + "' 2>&1";
  const int raw = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0)
      << raw << ": " << test::slurp_text(dir / "log.txt");
  const std::string saved = test::slurp_text(state);
  EXPECT_NE(saved.find("scene = sinc"), std::string::npos) << saved;
}

TEST(ViewerContract, VersionIsPrinted) {
  const std::string out = (test::render_scratch("viewer_version") / "v.txt").string();
  ASSERT_EQ(std::system(("'" + std::string(DYNAMESH_VIEWER) + "' --version > " + out).c_str()), 0);
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("dynamesh ", 0), 0u) << line;
}

}  // namespace
}  // namespace dynamesh
