// The mri entry of the scene catalogue: listed without loading, built from a --volume file
// with the numeric overrides used directly (one segmentation), clear one-line errors for bad
// input, the intensity as a point quantity, and the suggested settings per scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "core/surface/scene_registry.h"
#include "core/surface/volume/mri_scene.h"
#include "core/surface/volume/mri_surface.h"
#include "test_mri_ball.h"

namespace dynamesh {
namespace {

template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

SceneInfo info_of(const std::string& name) {
  for (const SceneInfo& s : list_scenes())
    if (s.name == name) return s;
  ADD_FAILURE() << name << " is not listed";
  return {};
}

TEST(MriScene, IsListedWithNominalParametersAndMillimetreSuggestions) {
  const SceneInfo mri = info_of("mri");
  EXPECT_TRUE(mri.parameters_depend_on_input);
  ASSERT_EQ(mri.parameters.size(), 3u);
  EXPECT_EQ(mri.parameters[0].name, "depth_max");
  EXPECT_EQ(mri.parameters[0].value, 15.0);  // SCENES.md: d(t) = 15 t mm
  EXPECT_EQ(mri.parameters[1].name, "threshold");
  EXPECT_EQ(mri.parameters[1].value, 0.0);  // Otsu
  EXPECT_EQ(mri.parameters[2].name, "closing");
  EXPECT_EQ(mri.parameters[2].value, 5.0);  // mm, for a brain up to 1.7 L
  EXPECT_EQ(mri.suggested_threshold, 0.5);
  EXPECT_GT(mri.suggested_density, 0.0);
  for (const char* name : {"sphere", "capsule-bend", "sinc", "twist"}) {
    const SceneInfo s = info_of(name);
    EXPECT_EQ(s.suggested_threshold, 0.008) << name;
    EXPECT_EQ(s.suggested_density, 2000.0) << name;
    EXPECT_FALSE(s.parameters_depend_on_input) << name;
  }
  const std::string help = scene_help();
  EXPECT_TRUE(contains(help, "mri"));
  EXPECT_TRUE(contains(help, "--volume"));
  EXPECT_TRUE(contains(help, "threshold 0.5"));
}

TEST(MriScene, BuildsFromTheVolumeOptionWithOverridesInOneSegmentation) {
  std::vector<std::string> stages;
  const ProgressCallback progress = [&](std::string_view stage, double) {
    if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
  };
  auto surface = make_scene("mri", {{"threshold", 30.0}, {"depth_max", 8.0}},
                            {{"volume", test::write_ball_file("mri_scene")}}, progress);
  EXPECT_EQ(stages, (std::vector<std::string>{"reading", "segmenting", "distance transform",
                                              "critical points"}));
  auto& mri = dynamic_cast<MriSurface&>(*surface);
  EXPECT_EQ(mri.time(), 0.0);
  EXPECT_EQ(mri.depth_max(), 8.0);
  EXPECT_EQ(mri.layers().segmentation().threshold, 30.0);
  EXPECT_FALSE(mri.layers().segmentation().otsu);
  // The ball's surface is the layer at t = 0.
  EXPECT_NEAR(mri.value(test::kBallCentre + Vec3(test::kBallRadius, 0, 0)), 0.0,
              0.5 * test::kBallSpacing.norm());

  // The reporter belonged to make_scene's caller: later re-segmentations stay silent.
  stages.clear();
  mri.set_parameter("threshold", 40.0);
  EXPECT_EQ(mri.layers().segmentation().threshold, 40.0);
  EXPECT_TRUE(stages.empty());
}

TEST(MriScene, BadInputGivesOneLineErrors) {
  const auto one_line = [](const std::string& e) {
    EXPECT_FALSE(e.empty());
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  std::string e = error_of([] { make_scene("mri", {}, {{"volume", "/nonexistent/brain.nii"}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "/nonexistent/brain.nii")) << e;

  e = error_of([] { make_scene("mri", {}, {{"colour", "red"}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "'colour'")) << e;
  EXPECT_TRUE(contains(e, "--volume")) << e;

  const auto junk = test::scratch_dir("mri_scene_junk") / "junk.nii";
  std::ofstream(junk) << "not a NIfTI file";
  e = error_of([&] { make_scene("mri", {}, {{"volume", junk.string()}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "junk.nii")) << e;

  const auto ball = test::write_ball_file("mri_scene_bad");
  e = error_of([&] { make_scene("mri", {{"depth_max", 50.0}}, {{"volume", ball.string()}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "depth_max")) << e;  // deeper than the ball's centre
  e = error_of([&] { make_scene("mri", {{"depth_max", -1.0}}, {{"volume", ball.string()}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "depth_max")) << e;
  e = error_of([&] { make_scene("mri", {{"depth", 1.0}}, {{"volume", ball.string()}}); });
  one_line(e);
  EXPECT_TRUE(contains(e, "'depth'")) << e;
}

TEST(MriScene, MissingDefaultVolumeSaysWhatToInstall) {
  if (std::filesystem::exists(kDefaultMriVolume)) GTEST_SKIP() << "mricron-data is installed";
  const std::string e = error_of([] { make_scene("mri"); });
  EXPECT_TRUE(contains(e, "mricron-data")) << e;
  EXPECT_TRUE(contains(e, "--volume")) << e;
}

TEST(MriScene, IntensityIsAPointQuantity) {
  auto surface = make_scene("mri", {}, {{"volume", test::write_ball_file("mri_scene_q")}});
  EXPECT_EQ(surface->point_quantities(), std::vector<std::string>{"intensity"});
  // Inside the ball the volume holds round(80 + z); trilinear reproduces the linear function.
  EXPECT_NEAR(surface->point_quantity("intensity", test::kBallCentre + Vec3(1, 2, 5)), 85.0, 0.5);
  EXPECT_NEAR(surface->point_quantity("intensity", test::kBallCentre - Vec3(0, 0, 7)), 73.0, 0.5);
  EXPECT_TRUE(std::isnan(surface->point_quantity("curvature", test::kBallCentre)));
}

}  // namespace
}  // namespace dynamesh
