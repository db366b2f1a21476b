// The scene catalogue: names, descriptions, parameters by name with ranges, and one-line
// errors that say what is valid.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/surface/scene_registry.h"
#include "core/surface/scenes/capsule_bend_scene.h"
#include "core/surface/scenes/sphere_scene.h"

namespace dynamesh {
namespace {

// The message of the std::invalid_argument that fn throws ("" if none).
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

TEST(SceneRegistry, ListsTheFourBuiltInScenesWithDescriptionsAndParameters) {
  const std::vector<SceneInfo> scenes = list_scenes();
  ASSERT_GE(scenes.size(), 4u);
  const std::vector<std::string> names{"sphere", "capsule-bend", "sinc", "twist"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(scenes[i].name, names[i]);
    EXPECT_FALSE(scenes[i].description.empty());
    EXPECT_EQ(scenes[i].description.find('\n'), std::string::npos);
    EXPECT_FALSE(scenes[i].parameters.empty());
    for (const SurfaceParameter& p : scenes[i].parameters) {
      EXPECT_LE(p.min, p.value) << names[i] << " " << p.name;
      EXPECT_LE(p.value, p.max) << names[i] << " " << p.name;
      EXPECT_FALSE(p.description.empty());
    }
  }
}

TEST(SceneRegistry, DefaultsAreThoseOfScenesMd) {
  const auto value = [](const std::string& scene, const std::string& key) {
    for (const SurfaceParameter& p : make_scene(scene)->parameters()) {
      if (p.name == key) return p.value;
    }
    ADD_FAILURE() << scene << " has no " << key;
    return 0.0;
  };
  EXPECT_EQ(value("sphere", "R0"), 0.6);
  EXPECT_EQ(value("sphere", "R1"), 9.0);
  EXPECT_EQ(value("sphere", "L"), 0.25);
  EXPECT_EQ(value("capsule-bend", "h"), 1.5);
  EXPECT_EQ(value("capsule-bend", "r"), 0.4);
  EXPECT_DOUBLE_EQ(value("capsule-bend", "bend"), 3.14159265358979323846);
  EXPECT_EQ(value("sinc", "alpha"), 0.6);
  EXPECT_DOUBLE_EQ(value("sinc", "beta"), 4 * 3.14159265358979323846);
  EXPECT_EQ(value("sinc", "kappa"), -0.5);
  EXPECT_EQ(value("twist", "p"), 4.0);
  EXPECT_EQ(value("twist", "s"), 8.0);
  EXPECT_EQ(value("twist", "h"), 1.5);
  EXPECT_EQ(value("twist", "r"), 0.4);
  EXPECT_EQ(value("twist", "turns"), 1.5);
}

TEST(SceneRegistry, MakesScenesOfTheRightKindAtTimeZero) {
  EXPECT_EQ(make_scene("sphere")->kind(), SurfaceKind::kImplicit);
  EXPECT_EQ(make_scene("capsule-bend")->kind(), SurfaceKind::kImplicit);
  EXPECT_EQ(make_scene("sinc")->kind(), SurfaceKind::kParametric);
  EXPECT_EQ(make_scene("twist")->kind(), SurfaceKind::kImplicit);
  // Scenes with an input (mri: a volume of seconds to load) are tested in their own files.
  for (const SceneInfo& s : list_scenes())
    if (!s.parameters_depend_on_input) {
      EXPECT_EQ(make_scene(s.name)->time(), 0.0);
    }
}

TEST(SceneRegistry, OverridesChangeTheSurface) {
  auto s = make_scene("sphere", {{"R0", 2.0}, {"R1", 4.0}});
  auto& sphere = dynamic_cast<ImplicitSurface&>(*s);
  EXPECT_NEAR(sphere.value(Vec3(2, 0, 0)), 0.0, 1e-15);
  sphere.set_time(1.0);
  EXPECT_NEAR(sphere.value(Vec3(0, 4, 0)), 0.0, 1e-15);
}

TEST(SceneRegistry, UnknownSceneListsTheValidNames) {
  const std::string e = error_of([] { make_scene("cube"); });
  EXPECT_TRUE(contains(e, "'cube'")) << e;
  for (const char* name : {"sphere", "capsule-bend", "sinc", "twist"}) {
    EXPECT_TRUE(contains(e, name)) << e;
  }
  EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(SceneRegistry, UnknownParameterListsTheValidOnes) {
  const std::string e = error_of([] { make_scene("sphere", {{"R2", 1.0}}); });
  EXPECT_TRUE(contains(e, "sphere")) << e;
  EXPECT_TRUE(contains(e, "'R2'")) << e;
  EXPECT_TRUE(contains(e, "R0, R1, L")) << e;
}

TEST(SceneRegistry, OutOfRangeValueGivesTheRange) {
  const std::string e = error_of([] { make_scene("twist", {{"p", 1.0}}); });
  EXPECT_TRUE(contains(e, "p = 1")) << e;
  EXPECT_TRUE(contains(e, "[2, 16]")) << e;
  EXPECT_FALSE(error_of([] { make_scene("sinc", {{"beta", -1.0}}); }).empty());
  EXPECT_FALSE(error_of([] { make_scene("sinc", {{"beta", std::nan("")}}); }).empty());
}

TEST(SceneRegistry, SetParameterChecksTooAndLeavesTheSceneUnchanged) {
  SphereScene s;
  EXPECT_THROW(s.set_parameter("R0", -1.0), std::invalid_argument);
  EXPECT_THROW(s.set_parameter("radius", 1.0), std::invalid_argument);
  EXPECT_NEAR(s.value(Vec3(0.6, 0, 0)), 0.0, 1e-15);
}

// bend < 2h/r keeps the inner side off the bending axis; the check depends on three values,
// so overrides are accepted in any order that ends in a valid combination.
TEST(SceneRegistry, CoupledConstraintsAreCheckedInAnyOrder) {
  const std::string e = error_of([] { make_scene("capsule-bend", {{"r", 1.2}}); });
  EXPECT_TRUE(contains(e, "bend")) << e;
  EXPECT_TRUE(contains(e, "lower bend or r")) << e;
  EXPECT_TRUE(error_of([] { make_scene("capsule-bend", {{"r", 1.2}, {"bend", 1.0}}); }).empty());
  EXPECT_TRUE(error_of([] { make_scene("capsule-bend", {{"bend", 1.0}, {"r", 1.2}}); }).empty());
  CapsuleBendScene s;
  EXPECT_THROW(s.set_parameter("r", 1.2), std::invalid_argument);
  EXPECT_EQ(s.rest_shape().radius, 0.4);
}

TEST(SceneRegistry, LastValueOfARepeatedKeyWins) {
  auto s = make_scene("sphere", {{"R0", 1.0}, {"R0", 2.0}});
  EXPECT_EQ(s->parameters()[0].value, 2.0);
}

TEST(SceneRegistry, BuiltInScenesTakeNoTextOptions) {
  EXPECT_FALSE(error_of([] { make_scene("sphere", {}, {{"volume", "x.nii"}}); }).empty());
}

TEST(SceneRegistry, RegisteredScenesAreMadeAndListed) {
  register_scene("test-sphere", "a sphere registered by a test", [](const TextOptions& o) {
    auto s = std::make_unique<SphereScene>();
    if (!o.empty()) s->set_parameter("R0", std::stod(o.front().second));
    return std::unique_ptr<Surface>(std::move(s));
  });
  const auto scenes = list_scenes();
  EXPECT_TRUE(std::any_of(scenes.begin(), scenes.end(),
                          [](const SceneInfo& s) { return s.name == "test-sphere"; }));
  EXPECT_EQ(make_scene("test-sphere", {}, {{"radius", "2"}})->parameters()[0].value, 2.0);
  EXPECT_THROW(register_scene("sphere", "again", nullptr), std::invalid_argument);
}

TEST(SceneRegistry, ParsesKeyValueOverrides) {
  EXPECT_EQ(parse_parameter_override("R0=0.8"), std::make_pair(std::string("R0"), 0.8));
  EXPECT_EQ(parse_parameter_override("kappa=-1e-1"), std::make_pair(std::string("kappa"), -0.1));
  for (const char* bad : {"R0", "=1", "R0=", "R0=abc", "R0=1x", "R0=inf"}) {
    EXPECT_THROW(parse_parameter_override(bad), std::invalid_argument) << bad;
  }
}

TEST(SceneRegistry, HelpNamesEveryParameter) {
  const std::string help = scene_help();
  for (const SceneInfo& s : list_scenes()) {
    EXPECT_TRUE(contains(help, s.name));
    for (const SurfaceParameter& p : s.parameters) EXPECT_TRUE(contains(help, p.description));
  }
}

}  // namespace
}  // namespace dynamesh
