// The real viewer under a virtual display (xvfb-run): a scripted run writes a screenshot that
// shows the ImGui panel and the mesh. Fails, never skips, when it cannot run: xvfb is in
// scripts/debian-packages.txt, so a machine built by ./dev has it.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "test_render_scratch.h"
#include "xvfb_run.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

struct Rgb {
  int r, g, b;
};

TEST(ViewerUnderXvfb, ScriptedRunWritesScreenshotWithPanelAndMesh) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = fs::path(DYNAMESH_BINARY_DIR) / "test_output" / "viewer_xvfb";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path shot = dir / "viewer.png";
  const test::XvfbRun run = test::run_under_xvfb(
      test::viewer_command("--scene sphere --frames 5 --width 1000 --height 640 --screenshot '" +
                           shot.string() + "'"),
      dir / "log.txt");
  ASSERT_EQ(run.status, 0) << run.output;

  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load(shot.c_str(), &w, &h, &n, 3);
  ASSERT_NE(pixels, nullptr);
  EXPECT_EQ(w, 1000);
  EXPECT_EQ(h, 640);
  const auto at = [&](int x, int y) {
    const stbi_uc* p = pixels + 3 * (y * w + x);
    return Rgb{p[0], p[1], p[2]};
  };
  // The panel: ImGui's dark theme fills the left strip (sampled below its title bar).
  int dark = 0, samples = 0;
  for (int y = 40; y < h; y += 7) {
    for (int x = 5; x < 300; x += 7) {
      const Rgb c = at(x, y);
      dark += (c.r + c.g + c.b) < 3 * 90 ? 1 : 0;
      ++samples;
    }
  }
  EXPECT_GT(dark, samples / 2) << "no dark ImGui panel on the left";
  // The mesh: the 3D view's centre is not the light background, and its corner is.
  const int cx = 330 + (w - 330) / 2, cy = h / 2;
  const Rgb centre = at(cx, cy), corner = at(w - 3, h - 3);
  EXPECT_GT(corner.r, 220);
  EXPECT_GT(corner.g, 220);
  EXPECT_GT(
      std::abs(centre.r - corner.r) + std::abs(centre.g - corner.g) + std::abs(centre.b - corner.b),
      60)
      << "the centre of the view shows background, not the mesh";
  stbi_image_free(pixels);
}

using Outcome = test::XvfbRun;

// The viewer under a fresh virtual display, with `options` (after `env`, e.g. "env PATH=...").
Outcome run_viewer(const std::string& options, const fs::path& log, const std::string& env = "") {
  return test::run_under_xvfb(env + " " + test::viewer_command(options), log);
}

TEST(ViewerUnderXvfb, RecordsOneVideoFramePerStepThroughFfmpeg) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  ASSERT_TRUE(test::on_path("ffprobe")) << "ffprobe not found: install the Debian package ffmpeg";
  const fs::path dir = test::render_scratch("viewer_record");
  const fs::path video = dir / "run.mp4";
  const Outcome r = run_viewer(
      "--scene sinc --frames 7 --width 640 --height 480 --record '" + video.string() + "'",
      dir / "log.txt");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("recorded 7 frames"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(video)) << r.output;
  EXPECT_FALSE(fs::exists(video.string() + ".partial"));
  // An independent reader: ffprobe decodes the file and counts.
  const Outcome probe = test::run_logged(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=width,height,nb_read_frames -of csv=p=0 '" +
          video.string() + "'",
      dir / "probe.txt");
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_EQ(probe.output.substr(0, probe.output.find_last_not_of("\n") + 1), "640,480,7");
}

TEST(ViewerUnderXvfb, WithoutFfmpegRecordsAPngSequence) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_record_png");
  // A PATH with no ffmpeg on it (the viewer needs nothing else from PATH).
  const Outcome r = run_viewer("--scene sinc --frames 4 --width 320 --height 240 --record '" +
                                   (dir / "run.mp4").string() + "'",
                               dir / "log.txt", "env PATH=/nonexistent");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "run.mp4"));
  const fs::path frames = dir / "run_frames";
  ASSERT_TRUE(fs::is_directory(frames)) << r.output;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(frames)) {
    int w = 0, h = 0, n = 0;
    ASSERT_EQ(stbi_info(entry.path().c_str(), &w, &h, &n), 1) << entry.path();
    EXPECT_EQ(w, 320);
    EXPECT_EQ(h, 240);
    ++count;
  }
  EXPECT_EQ(count, 4);
  EXPECT_TRUE(fs::exists(frames / "frame_000000.png"));
  EXPECT_TRUE(fs::exists(frames / "frame_000003.png"));
}

TEST(ViewerUnderXvfb, SettingsPersistBetweenRuns) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_settings_runs");
  const fs::path state = dir / "config" / "viewer.conf";
  const std::string shot = " --screenshot '" + (dir / "shot.png").string() + "'";
  const Outcome first = run_viewer("--state '" + state.string() +
                                       "' --scene sinc --param beta=10 --threshold 0.03 --frames 1 "
                                       "--width 700 --height 500" +
                                       shot,
                                   dir / "first.txt");
  ASSERT_EQ(first.status, 0) << first.output;
  std::ifstream in(state);
  const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(saved.find("scene = sinc"), std::string::npos) << saved;
  EXPECT_NE(saved.find("param.beta = 10"), std::string::npos) << saved;
  EXPECT_NE(saved.find("window_width = 700"), std::string::npos) << saved;

  // The second run names no scene: it continues with the saved one and its window size.
  const Outcome second =
      run_viewer("--state '" + state.string() + "' --frames 1" + shot, dir / "second.txt");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_NE(second.output.find("scene sinc"), std::string::npos) << second.output;
  int w = 0, h = 0, n = 0;
  ASSERT_EQ(stbi_info((dir / "shot.png").c_str(), &w, &h, &n), 1);
  EXPECT_EQ(w, 700);
  EXPECT_EQ(h, 500);
}

TEST(ViewerUnderXvfb, BadParameterShowsAnErrorInsteadOfCrashing) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_bad_parameter");
  const Outcome r = run_viewer("--scene sinc --param no_such=1 --frames 2 --screenshot '" +
                                   (dir / "shot.png").string() + "'",
                               dir / "log.txt");
  EXPECT_EQ(r.status, 2) << r.output;  // scripted: could not show what was asked
  EXPECT_NE(r.output.find("error shown: sinc: no parameter 'no_such'"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir / "shot.png"));
}

// Pixels of the panel's error red (antialiased text) in the panel's top part, where the
// scene section and its formula fields are.
int red_text_pixels(const fs::path& png) {
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load(png.c_str(), &w, &h, &n, 3);
  if (pixels == nullptr) return -1;
  int red = 0;
  for (int y = 0; y < std::min(h, 320); ++y) {
    for (int x = 0; x < std::min(w, 330); ++x) {
      const stbi_uc* p = pixels + 3 * (y * w + x);
      red += p[0] > 180 && p[1] > 60 && p[1] < 140 && p[2] > 40 && p[2] < 120 && p[0] > p[1] + 80;
    }
  }
  stbi_image_free(pixels);
  return red;
}

TEST(ViewerUnderXvfb, TypedFormulaRunsWithItsPanel) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_expr");
  const Outcome r = run_viewer(
      "--scene expr --implicit 'x^2 + y^2/(1+0.5*sin(2*pi*t)) + z^2 - 1' "
      "--bounds -2,-2,-2,2,2,2 --threshold 0.02 --frames 4 --width 800 "
      "--height 600 --screenshot '" +
          (dir / "shot.png").string() + "'",
      dir / "log.txt");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("scene expr, last step shown 3"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("error shown"), std::string::npos) << r.output;
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load((dir / "shot.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(pixels, nullptr);
  const stbi_uc* centre = pixels + 3 * ((h / 2) * w + 340 + (w - 340 - 130) / 2);
  EXPECT_LT(centre[0] + centre[1] + centre[2], 3 * 220) << "no mesh in the middle of the view";
  stbi_image_free(pixels);
  EXPECT_EQ(red_text_pixels(dir / "shot.png"), 0) << "an error is shown";
}

TEST(ViewerUnderXvfb, BrokenFormulaShowsItsErrorInRedInsteadOfCrashing) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_expr_broken");
  for (const char* formula : {"sqrt(x^2+y^2+z^2 - 1", "x^2 + y^2 + z^2 + 1"}) {
    const Outcome r =
        run_viewer(std::string("--scene expr --implicit '") + formula +
                       "' --bounds -2,-2,-2,2,2,2 --frames 2 --width 800 --height 600 "
                       "--screenshot '" +
                       (dir / "shot.png").string() + "'",
                   dir / "log.txt");
    EXPECT_EQ(r.status, 2) << r.output;  // scripted: could not show what was asked
    EXPECT_NE(r.output.find("error shown: implicit formula"), std::string::npos) << r.output;
    EXPECT_GT(red_text_pixels(dir / "shot.png"), 100) << formula << ": no red message in the panel";
  }
}

TEST(ViewerUnderXvfb, MeshReachesTheGpuOncePerStepNotPerFrame) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_uploads");
  // Turning the view for a second without playing: many frames, one upload.
  const Outcome still =
      run_viewer("--scene sinc --run-for 1 --orbit --width 400 --height 300", dir / "still.txt");
  ASSERT_EQ(still.status, 0) << still.output;
  EXPECT_NE(still.output.find("uploads: 1 full, 0 positions only, 1 colour"), std::string::npos)
      << still.output;
  unsigned frames = 0;
  const auto at = still.output.find("dynamesh: ", still.output.find("uploads:"));
  ASSERT_EQ(std::sscanf(still.output.c_str() + at, "dynamesh: %u frames", &frames), 1);
  EXPECT_GT(frames, 3u) << still.output;

  // Playing: one geometry upload per step shown.
  const Outcome playing =
      run_viewer("--scene sinc --play --run-for 2 --width 400 --height 300", dir / "playing.txt");
  ASSERT_EQ(playing.status, 0) << playing.output;
  int full = 0, positions = 0, colour = 0;
  unsigned steps = 0;
  const auto up = playing.output.find("uploads:");
  ASSERT_NE(up, std::string::npos) << playing.output;
  ASSERT_EQ(
      std::sscanf(playing.output.c_str() + up, "uploads: %d full, %d positions only, %d colour",
                  &full, &positions, &colour),
      3);
  const auto timing = playing.output.find("new steps");
  ASSERT_NE(timing, std::string::npos);
  const auto comma = playing.output.rfind(", ", timing);
  ASSERT_EQ(std::sscanf(playing.output.c_str() + comma + 2, "%u", &steps), 1);
  EXPECT_GT(steps, 1u) << playing.output;
  EXPECT_EQ(static_cast<unsigned>(full + positions), steps) << playing.output;
  EXPECT_EQ(static_cast<unsigned>(colour), steps) << playing.output;
}

TEST(ViewerUnderXvfb, WithoutDisplayExitsTwoNamingTheBatchCommand) {
  const fs::path log = fs::path(DYNAMESH_BINARY_DIR) / "test_output" / "viewer_nodisplay.txt";
  fs::create_directories(log.parent_path());
  const std::string command =
      "env -u DISPLAY -u WAYLAND_DISPLAY " + test::viewer_command("> '" + log.string() + "' 2>&1");
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::FILE* f = std::fopen(log.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char text[1024] = {};
  const std::size_t size = std::fread(text, 1, sizeof text - 1, f);
  std::fclose(f);
  EXPECT_NE(std::string(text, size).find("dynamesh-cli run"), std::string::npos);
  EXPECT_NE(std::string(text, size).find("--render"), std::string::npos);
}

TEST(ViewerUnderXvfb, BadOptionExitsTwo) {
  const int status = std::system(test::viewer_command("--no-such-option >/dev/null 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
}

}  // namespace
}  // namespace dynamesh
