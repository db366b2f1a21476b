// The viewer's settings between runs (where they live, what is saved, how the command line
// combines with them) and its frame-timing summary.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "app/viewer/frame_timing.h"
#include "app/viewer/viewer_args.h"
#include "app/viewer/viewer_state.h"
#include "test_render_scratch.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

// Sets (or unsets, with nullopt) an environment variable for the scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      ::setenv(name, value->c_str(), 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(ViewerSettings, LiveInXdgConfigHomeElseDotConfig) {
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "/somewhere/config");
    ScopedEnv home("HOME", "/home/person");
    EXPECT_EQ(settings_path(), "/somewhere/config/dynamesh/viewer.conf");
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "relative/is/ignored");
    ScopedEnv home("HOME", "/home/person");
    EXPECT_EQ(settings_path(), "/home/person/.config/dynamesh/viewer.conf");
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", std::nullopt);
    ScopedEnv home("HOME", std::nullopt);
    EXPECT_EQ(settings_path(), "");
  }
}

TEST(ViewerSettings, SaveCreatesTheDirectoryAndLoadRestoresEverything) {
  const fs::path file = test::render_scratch("viewer_settings") / "new" / "dir" / "viewer.conf";
  ViewerState s;
  s.controls.scene = "mri";
  s.controls.scene_parameters = {{"depth_max", 12.5}, {"threshold", 40}};
  s.controls.scene_text = {{"volume", "/data/brain with space.nii.gz"}};
  s.controls.threshold = 0.5;
  s.controls.epsilon = 0.1;
  s.controls.max_triangles = 123456;
  s.steps = 42;
  s.time = 0.25;
  s.style.mode = ColorMode::kIntensity;
  s.style.wireframe = false;
  s.camera.distance = 7.5f;
  s.show_panel = false;
  s.window_x = 15;
  s.window_y = 30;
  s.window_width = 1500;
  s.window_height = 900;
  save_viewer_state(s, file.string());

  ViewerState r;
  ASSERT_TRUE(load_viewer_state(r, file.string()));
  EXPECT_EQ(r.controls, s.controls);
  EXPECT_EQ(r.steps, 42);
  EXPECT_DOUBLE_EQ(r.time, 0.25);
  EXPECT_EQ(r.style.mode, ColorMode::kIntensity);
  EXPECT_FALSE(r.style.wireframe);
  EXPECT_FLOAT_EQ(r.camera.distance, 7.5f);
  EXPECT_FALSE(r.show_panel);
  EXPECT_EQ(r.window_x, 15);
  EXPECT_EQ(r.window_y, 30);
  EXPECT_EQ(r.window_width, 1500);
  EXPECT_EQ(r.window_height, 900);

  ViewerState untouched;
  EXPECT_FALSE(load_viewer_state(untouched, (file.parent_path() / "missing.conf").string()));
}

TEST(ViewerSettings, CommandLineWinsOverSavedSettings) {
  ViewerState saved;
  saved.controls.scene = "capsule-bend";
  saved.controls.scene_parameters = {{"r", 0.3}};
  saved.controls.threshold = 0.004;
  saved.controls.epsilon = 0.001;
  saved.steps = 250;
  saved.window_width = 1600;

  // Nothing given: what was saved.
  ViewerArgs a = parse_viewer_args({}, saved);
  EXPECT_EQ(a.state.controls, saved.controls);
  EXPECT_EQ(a.state.steps, 250);
  EXPECT_EQ(a.state.window_width, 1600);

  // The same scene keeps its saved parameters; given options replace saved ones, and a
  // threshold without epsilon brings epsilon = T/4 as in dynamesh-cli run.
  a = parse_viewer_args({"--scene", "capsule-bend", "--threshold", "0.01", "--width", "900"},
                        saved);
  EXPECT_EQ(a.state.controls.scene_parameters, saved.controls.scene_parameters);
  EXPECT_DOUBLE_EQ(a.state.controls.threshold, 0.01);
  EXPECT_DOUBLE_EQ(a.state.controls.epsilon, 0.0025);
  EXPECT_EQ(a.state.window_width, 900);
  EXPECT_DOUBLE_EQ(a.state.style.colors.threshold, 0.01);

  // Another scene drops the saved scene's parameters.
  a = parse_viewer_args({"--scene", "sinc", "--param", "beta=3"}, saved);
  EXPECT_EQ(a.state.controls.scene, "sinc");
  ASSERT_EQ(a.state.controls.scene_parameters.size(), 1u);
  EXPECT_EQ(a.state.controls.scene_parameters[0].first, "beta");

  a = parse_viewer_args({"--volume", "/x/brain.nii"}, saved);
  ASSERT_EQ(a.state.controls.scene_text.size(), 1u);
  EXPECT_EQ(a.state.controls.scene_text[0].second, "/x/brain.nii");
}

TEST(ViewerSettings, ScriptedRunsUseNoSettingsFileUnlessGivenOne) {
  ScopedEnv xdg("XDG_CONFIG_HOME", "/cfg");
  EXPECT_EQ(state_file_for(parse_viewer_args({})), "/cfg/dynamesh/viewer.conf");
  EXPECT_EQ(state_file_for(parse_viewer_args({"--frames", "3", "--screenshot", "a.png"})), "");
  EXPECT_EQ(state_file_for(parse_viewer_args({"--run-for", "1", "--state", "s.conf"})), "s.conf");
}

TEST(ViewerSettings, BadOptionsSayWhatIsWrong) {
  const auto message = [](std::vector<std::string> args) {
    try {
      parse_viewer_args(args);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(message({"--threshold", "abc"}).find("--threshold"), std::string::npos);
  EXPECT_NE(message({"--epsilon", "0.1", "--threshold", "0.05"}).find("epsilon"),
            std::string::npos);
  EXPECT_NE(message({"--t0", "0.8", "--t1", "0.2"}).find("t0"), std::string::npos);
  EXPECT_NE(message({"--screenshot", "x.png"}).find("--frames"), std::string::npos);
  EXPECT_NE(message({"--frames", "2", "--run-for", "1"}).find("exclude"), std::string::npos);
  EXPECT_NE(message({"--color", "purple"}).find("--color"), std::string::npos);
  EXPECT_NE(message({"--bogus"}).find("unknown option"), std::string::npos);
  EXPECT_EQ(message({"--frames", "2", "--record", "a.mp4"}), "(accepted)");
}

TEST(ViewerFrameTiming, SummaryCountsFramesStepsAndWorstTimes) {
  std::vector<FrameSample> frames;
  for (int i = 0; i < 100; ++i) {
    FrameSample f;
    f.work_ms = i < 99 ? 10.0 + i % 5 : 80.0;  // one slow frame, with a new step
    f.draw_ms = f.work_ms - 1.0;
    f.handoff_ms = i < 99 ? 0.5 : 6.0;
    f.new_step = i % 10 == 9;
    frames.push_back(f);
  }
  const FrameSummary s = summarize(frames, 2.0);
  EXPECT_EQ(s.frames, 100u);
  EXPECT_EQ(s.new_steps, 10u);
  EXPECT_DOUBLE_EQ(s.fps, 50.0);
  EXPECT_DOUBLE_EQ(s.work_max_ms, 80.0);
  EXPECT_DOUBLE_EQ(s.quiet_work_max_ms, 14.0);
  EXPECT_DOUBLE_EQ(s.handoff_max_ms, 6.0);
  EXPECT_DOUBLE_EQ(s.work_median_ms, 12.0);
  EXPECT_DOUBLE_EQ(s.work_p95_ms, 14.0);

  const fs::path log = test::render_scratch("frame_log") / "frames.csv";
  write_frame_log(frames, log.string());
  std::ifstream in(log);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "frame,at_ms,work_ms,handoff_ms,draw_ms,new_step,triangles");
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 100);
}

}  // namespace
}  // namespace dynamesh
