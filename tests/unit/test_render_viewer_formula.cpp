// The viewer's formula panel without its window: the draft of the fields and its conversion
// to the expr scene's text options, the checks shown while typing, the example library, the
// command line's expr options, and what the simulation does with a formula that only fails
// when the surface is built.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "app/viewer/formula_draft.h"
#include "app/viewer/formula_examples.h"
#include "app/viewer/simulation.h"
#include "app/viewer/simulation_driver.h"
#include "app/viewer/viewer_args.h"
#include "core/surface/expression/expr_options.h"
#include "core/surface/expression/expression.h"
#include "core/surface/scene_registry.h"
#include "test_render_scratch.h"
#include "test_render_step_request.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

const char* kSphere = "x^2 + y^2 + z^2 - 1";

FormulaDraft implicit_draft(const std::string& formula) {
  FormulaDraft d = formula_draft_from_text({{"implicit", formula}, {"bounds", "-2,-2,-2,2,2,2"}});
  return d;
}

// --- the draft ------------------------------------------------------------------------------

TEST(FormulaDraft, DefaultsAreWhatTheSceneRunsWithoutOptions) {
  FormulaDraft filled = formula_draft_from_text({});
  EXPECT_EQ(filled.source, TextOptions{});
  EXPECT_FALSE(FormulaDraft{}.source);  // never shown yet: the panel fills it on first sight
  filled.source.reset();
  EXPECT_EQ(filled, FormulaDraft{});
  const ExprOptions plain = parse_expr_options({});
  const ExprOptions drafted = parse_expr_options(formula_draft_text(FormulaDraft{}));
  EXPECT_EQ(drafted.kind, ExprKind::kImplicit);
  EXPECT_EQ(drafted.formula, plain.formula);
  ASSERT_TRUE(drafted.bounds && plain.bounds);
  EXPECT_EQ(drafted.bounds->min, plain.bounds->min);
  EXPECT_EQ(drafted.bounds->max, plain.bounds->max);
  // Every kind's defaults check and build.
  for (ExprKind kind : {ExprKind::kImplicit, ExprKind::kHeight, ExprKind::kParametric}) {
    FormulaDraft d;
    d.kind = kind;
    EXPECT_TRUE(check_formula_draft(d).ok()) << formula_kind_key(kind);
    EXPECT_NO_THROW(make_scene("expr", {}, formula_draft_text(d))) << formula_kind_key(kind);
  }
}

TEST(FormulaDraft, TextRoundTripsThroughTheFieldsOfEachKind) {
  const std::vector<TextOptions> texts = {
      {{"implicit", kSphere}, {"bounds", "-2,-2,-2,2,2,2"}, {"base-mesh", "/m/torus.obj"}},
      {{"height", "sin(x)*z"}, {"domain", "0,1,0,2"}},
      {{"height", "sin(x)*z"}},  // the scene's default square, left to the scene
      {{"parametric", "cos(u); v; sin(u)"}, {"domain", "0,2*pi,-1,1"}, {"periodic", "uv"}},
      {{"parametric", "cos(u); v; sin(u)"}, {"domain", "0,1,0,1"}},
  };
  for (const TextOptions& text : texts) {
    const FormulaDraft d = formula_draft_from_text(text);
    EXPECT_EQ(formula_draft_text(d), text) << text[0].second;
    EXPECT_FALSE(formula_draft_edited(d));
  }
  // The domain comes before the formula on some command lines: it is still the kind's.
  const FormulaDraft late =
      formula_draft_from_text({{"domain", "0,3,0,1"}, {"parametric", "u; v; 0"}});
  EXPECT_EQ(late.parametric_domain, "0,3,0,1");
  EXPECT_EQ(late.parametric[2], "0");
  EXPECT_FALSE(late.periodic_u);  // not given: not periodic, whatever the panel's default
}

TEST(FormulaDraft, EditsLineBreaksAndKindsAreSeenForWhatTheyAre) {
  FormulaDraft d = implicit_draft(kSphere);
  d.implicit = "x^2 + y^2\n + z^2 - 1";  // a line broken by Ctrl+Enter
  EXPECT_EQ(formula_draft_text(d)[0].second, "x^2 + y^2  + z^2 - 1");
  d.implicit = "x^2 + y^2 + z^2 - 0.5";
  EXPECT_TRUE(formula_draft_edited(d));
  d = implicit_draft(kSphere);
  d.kind = ExprKind::kHeight;
  EXPECT_TRUE(formula_draft_edited(d));
  d.kind = ExprKind::kImplicit;
  EXPECT_FALSE(formula_draft_edited(d));  // the implicit fields were kept meanwhile
  // Wrapping a long formula for the field is no edit.
  const TextOptions blob = {{"implicit", kDefaultImplicitFormula}, {"bounds", "-2,-2,-2,2,2,2"}};
  const FormulaDraft wrapped = formula_draft_from_text(blob, 24);
  EXPECT_NE(wrapped.implicit.find('\n'), std::string::npos);
  EXPECT_FALSE(formula_draft_edited(wrapped));
}

// --- the checks shown while typing ----------------------------------------------------------

TEST(FormulaCheck, EachMistakeIsReportedUnderItsOwnField) {
  EXPECT_TRUE(check_formula_draft(implicit_draft(kSphere)).ok());

  FormulaCheck c = check_formula_draft(implicit_draft("x^2 + (y^2"));
  EXPECT_FALSE(c.ok());
  EXPECT_FALSE(c.formula[0].empty());
  EXPECT_EQ(c.formula[0].find("x^2 + (y^2"), std::string::npos)
      << "the field shows the formula already: " << c.formula[0];
  EXPECT_TRUE(c.extent.empty());

  c = check_formula_draft(implicit_draft("x^2 + w^2 - 1"));
  EXPECT_NE(c.formula[0].find("unknown name 'w'"), std::string::npos) << c.formula[0];
  EXPECT_NE(c.formula[0].find("x, y, z, t"), std::string::npos) << c.formula[0];

  c = check_formula_draft(implicit_draft(" \n "));
  EXPECT_NE(c.formula[0].find("empty"), std::string::npos) << c.formula[0];

  FormulaDraft d = implicit_draft(kSphere);
  d.bounds = "-2,-2,-2,2,2";
  c = check_formula_draft(d);
  EXPECT_TRUE(c.formula[0].empty());
  EXPECT_NE(c.extent.find("6 numbers"), std::string::npos) << c.extent;
  d.bounds = "";
  EXPECT_FALSE(check_formula_draft(d).extent.empty());
  d.bounds = "-2,-2,-2,2,2,2";
  d.base_mesh = "/no/such/mesh.obj";
  c = check_formula_draft(d);
  EXPECT_NE(c.base_mesh.find("/no/such/mesh.obj"), std::string::npos) << c.base_mesh;

  d = FormulaDraft{};
  d.kind = ExprKind::kParametric;
  d.parametric[1] = "v +";
  c = check_formula_draft(d);
  EXPECT_TRUE(c.formula[0].empty());
  EXPECT_FALSE(c.formula[1].empty());
  EXPECT_TRUE(c.formula[2].empty());
  d.parametric[1] = "v; 0";  // would shift Z
  EXPECT_NE(check_formula_draft(d).formula[1].find(';'), std::string::npos);
  d.parametric[1] = "v";
  d.parametric[2] = "sin(x)";  // x is no variable of a parametric surface
  EXPECT_NE(check_formula_draft(d).formula[2].find("unknown name 'x'"), std::string::npos);
  d.parametric[2] = "0";
  d.parametric_domain = "";
  EXPECT_FALSE(check_formula_draft(d).extent.empty());

  d = FormulaDraft{};
  d.kind = ExprKind::kHeight;
  d.height_domain = "1,0,-1,1";
  EXPECT_NE(check_formula_draft(d).extent.find("empty"), std::string::npos);
  d.height_domain = "";  // the scene's default square
  EXPECT_TRUE(check_formula_draft(d).ok());
}

TEST(FormulaCheck, WhatChecksParsesAndOnlyBuildingFindsTheRest) {
  // The panel sends a draft only when it checks: then the options always parse.
  const FormulaDraft no_crossing = implicit_draft("x^2 + y^2 + z^2 + 1");
  ASSERT_TRUE(check_formula_draft(no_crossing).ok());
  EXPECT_NO_THROW(parse_expr_options(formula_draft_text(no_crossing)));
  // ...and what the formula does over the bounds is the worker thread's to find.
  EXPECT_THROW(make_scene("expr", {}, formula_draft_text(no_crossing)), std::invalid_argument);
}

// --- wrapping a formula for a narrow field ---------------------------------------------------

TEST(FormulaWrap, BreaksOnlyWhereTheMeaningCannotChange) {
  const std::vector<std::string> formulas = {
      kDefaultImplicitFormula, "sqrt((sqrt(x^2+y^2)-1)^2+z^2) - 0.4 - 0.1*sin(2*pi*t)",
      "(x/(1+0.3*sin(2*pi*t)))^2 + (y/0.7)^2 + (z/(0.5-0.2*sin(2*pi*t)))^2 - 1",
      "1e-3*x + 2.5e+2*y*z - 1e-1*(x-y)/(1+z^2)", "x^2+y^2+z^2-1"};
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (const std::string& safe : formulas) {
    for (std::size_t columns : {8u, 12u, 20u, 33u, 45u, 200u}) {
      const std::string wrapped = wrap_formula(safe, columns);
      // Lines fit unless nothing could be broken.
      std::size_t start = 0;
      for (;;) {
        const std::size_t end = wrapped.find('\n', start);
        const std::string line = wrapped.substr(start, end - start);
        EXPECT_FALSE(line.empty()) << wrapped;
        if (line.size() > columns) {
          EXPECT_EQ(line.find(' ', 1), std::string::npos) << "could break at a space: " << line;
        }
        if (end == std::string::npos) break;
        start = end + 1;
      }
      if (safe.size() <= columns) {
        EXPECT_EQ(wrapped, safe);
      }
      // As sent (line breaks become spaces) it is the same function.
      FormulaDraft d;
      d.implicit = wrapped;
      const std::string sent = formula_draft_text(d)[0].second;
      const Expression original({safe}, {"x", "y", "z", "t"}, "original");
      const Expression rewrapped({sent}, {"x", "y", "z", "t"}, "wrapped");
      for (int i = 0; i < 20; ++i) {
        const double p[4] = {coordinate(random), coordinate(random), coordinate(random),
                             0.5 * (1 + coordinate(random))};
        EXPECT_DOUBLE_EQ(rewrapped.value(p), original.value(p)) << wrapped;
      }
    }
  }
  // A line the person broke stays broken; a name is never split.
  EXPECT_EQ(wrap_formula("a\nb", 40), "a\nb");
  EXPECT_EQ(wrap_formula("longname_without_breaks", 5), "longname_without_breaks");
}

// --- the example library -------------------------------------------------------------------

TEST(FormulaExamples, TheShippedExamplesLoadAndBuild) {
  const std::vector<FormulaExample> examples =
      load_formula_examples(std::string(DYNAMESH_SOURCE_DIR) + "/assets/examples");
  ASSERT_GE(examples.size(), 4u);
  std::vector<std::string> names;
  for (const FormulaExample& e : examples) {
    names.push_back(e.name);
    ASSERT_TRUE(e.error.empty()) << e.path << ": " << e.error;
    // What the panel would send for it builds the surface.
    const FormulaDraft d = formula_draft_from_text(e.text, 40);
    ASSERT_TRUE(check_formula_draft(d).ok()) << e.name;
    EXPECT_NO_THROW(make_scene("expr", {}, formula_draft_text(d))) << e.name;
  }
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const char* wanted :
       {"pulsing-blob", "breathing-torus", "breathing-ellipsoid", "travelling-wave"})
    EXPECT_NE(std::find(names.begin(), names.end(), wanted), names.end()) << wanted;
  // The torus's base mesh, written relative to the repository root, is found from anywhere.
  const auto torus = std::find_if(examples.begin(), examples.end(), [](const FormulaExample& e) {
    return e.name == "breathing-torus";
  });
  ASSERT_NE(torus, examples.end());
  const auto mesh = std::find_if(torus->text.begin(), torus->text.end(),
                                 [](const auto& kv) { return kv.first == "base-mesh"; });
  ASSERT_NE(mesh, torus->text.end());
  EXPECT_TRUE(fs::path(mesh->second).is_absolute()) << mesh->second;
  EXPECT_TRUE(fs::is_regular_file(mesh->second)) << mesh->second;
}

TEST(FormulaExamples, BaseMeshesResolveBesideTheFileOrAboveItAndMistakesAreReported) {
  const fs::path root = test::render_scratch("formula_examples");
  fs::create_directories(root / "lib" / "examples");
  std::ofstream(root / "lib" / "examples" / "ring.obj") << "# a mesh\n";
  const auto write = [](const fs::path& file, const std::string& text) {
    std::ofstream(file) << text;
  };
  const fs::path dir = root / "lib" / "examples";
  write(dir / "beside.args",
        "--scene\r\nexpr\r\n--implicit\r\nx^2+y^2+z^2-1\r\n--bounds\r\n"
        "-2,-2,-2,2,2,2\r\n--base-mesh\r\nring.obj\r\n");
  write(dir / "from-root.args",
        "--scene\nexpr\n--implicit\nx\n--bounds\n-1,-1,-1,1,1,1\n--base-mesh\nlib/examples/"
        "ring.obj\n");
  write(dir / "missing.args",
        "--scene\nexpr\n--implicit\nx\n--bounds\n-1,-1,-1,1,1,1\n--base-mesh\nnowhere.obj\n");
  write(dir / "broken.args", "--scene\nexpr\n--no-such-option\n");
  write(dir / "other-scene.args", "--scene\nsphere\n");
  write(dir / "notes.txt", "not an example\n");

  const std::vector<FormulaExample> examples = load_formula_examples(dir.string());
  ASSERT_EQ(examples.size(), 5u);  // notes.txt is no example
  const auto by_name = [&](const std::string& name) {
    for (const FormulaExample& e : examples)
      if (e.name == name) return e;
    ADD_FAILURE() << name;
    return FormulaExample{};
  };
  const fs::path ring = fs::canonical(dir / "ring.obj");
  const FormulaExample beside = by_name("beside");
  EXPECT_TRUE(beside.error.empty()) << beside.error;
  ASSERT_EQ(beside.text.size(), 3u);
  EXPECT_EQ(beside.text[0].second, "x^2+y^2+z^2-1");  // no carriage return left
  EXPECT_EQ(fs::canonical(beside.text[2].second), ring);
  const FormulaExample from_root = by_name("from-root");
  ASSERT_EQ(from_root.text.size(), 3u);
  EXPECT_EQ(fs::canonical(from_root.text[2].second), ring);
  EXPECT_EQ(by_name("missing").text[2].second, "nowhere.obj");  // building says so
  EXPECT_NE(by_name("broken").error.find("--no-such-option"), std::string::npos);
  EXPECT_NE(by_name("other-scene").error.find("expr"), std::string::npos);
  EXPECT_TRUE(load_formula_examples((root / "nowhere").string()).empty());
}

TEST(FormulaExamples, FoundFromTheEnvironmentElseBesideTheExecutableOrInTheSourceTree) {
  const fs::path root = test::render_scratch("formula_assets");
  fs::create_directories(root / "examples");
  const char* before = std::getenv("DYNAMESH_ASSETS");
  const std::string saved = before ? before : "";
  ::setenv("DYNAMESH_ASSETS", root.c_str(), 1);
  EXPECT_EQ(fs::path(find_examples_dir()), root / "examples");
  EXPECT_EQ(fs::path(examples_dir_candidates().front()), root / "examples");
  ::unsetenv("DYNAMESH_ASSETS");
  // Next to the executable (and one level up: the viewer sits in <build>, inside the source
  // tree), and last the source tree it was built from.
  const std::vector<std::string> candidates = examples_dir_candidates();
  ASSERT_GE(candidates.size(), 3u);
  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path();
  EXPECT_EQ(fs::path(candidates[0]), exe / "assets" / "examples");
  EXPECT_EQ(fs::path(candidates[1]), exe.parent_path() / "assets" / "examples");
  EXPECT_EQ(fs::path(candidates.back()), fs::path(DYNAMESH_SOURCE_DIR) / "assets" / "examples");
  const std::string found = find_examples_dir();
  EXPECT_TRUE(fs::is_regular_file(fs::path(found) / "pulsing-blob.args")) << found;
  if (before) ::setenv("DYNAMESH_ASSETS", saved.c_str(), 1);
}

// --- the command line ----------------------------------------------------------------------

TEST(FormulaCommandLine, TheViewerReadsTheClisExprOptions) {
  ViewerArgs a = parse_viewer_args(
      {"--scene", "expr", "--implicit", kSphere, "--bounds", "-2,-2,-2,2,2,2", "--height", "600"});
  EXPECT_EQ(a.state.controls.scene, "expr");
  EXPECT_EQ(a.state.controls.scene_text,
            (TextOptions{{"implicit", kSphere}, {"bounds", "-2,-2,-2,2,2,2"}}));
  EXPECT_EQ(a.state.window_height, 600);  // a whole number: the window's height

  a = parse_viewer_args({"--height", "sin(x)*z", "--scene", "expr", "--domain", "0,1,0,1"});
  EXPECT_EQ(a.state.controls.scene_text,
            (TextOptions{{"height", "sin(x)*z"}, {"domain", "0,1,0,1"}}));
  a = parse_viewer_args({"--scene", "expr", "--height-field", "2", "--parametric", "u;v;0",
                         "--periodic", "u", "--base-mesh", "m.obj"});
  EXPECT_EQ(
      a.state.controls.scene_text,
      (TextOptions{
          {"height", "2"}, {"parametric", "u;v;0"}, {"periodic", "u"}, {"base-mesh", "m.obj"}}));

  // Over saved settings: a formula given replaces the saved one whole, none given keeps it.
  ViewerState saved;
  saved.controls.scene = "expr";
  saved.controls.scene_text = {{"parametric", "u;v;0"}, {"domain", "0,1,0,1"}};
  a = parse_viewer_args({"--implicit", kSphere, "--bounds", "-2,-2,-2,2,2,2"}, saved);
  EXPECT_EQ(a.state.controls.scene_text.size(), 2u);
  EXPECT_EQ(a.state.controls.scene_text[0].first, "implicit");
  a = parse_viewer_args({"--threshold", "0.01"}, saved);
  EXPECT_EQ(a.state.controls.scene_text, saved.controls.scene_text);
  a = parse_viewer_args({"--scene", "sphere"}, saved);
  EXPECT_TRUE(a.state.controls.scene_text.empty());
}

// --- the simulation behind the panel ---------------------------------------------------------

SimulationControls coarse_expr(const TextOptions& text) {
  SimulationControls c;
  c.scene = "expr";
  c.scene_text = text;
  c.threshold = 0.04;
  c.epsilon = 0.01;
  c.density = 300;
  return c;
}

using test::at;

TEST(FormulaSimulation, AFormulaThatFailsToBuildLeavesTheLastGoodMeshOnScreen) {
  const SimulationControls good =
      coarse_expr({{"implicit", kSphere}, {"bounds", "-2,-2,-2,2,2,2"}});
  const SimulationControls bad =
      coarse_expr({{"implicit", "x^2 + y^2 + z^2 + 1"}, {"bounds", "-2,-2,-2,2,2,2"}});
  SimulationDriver driver;
  driver.request_step(at(0.0, good, true));
  driver.wait_idle();
  const StepResult first = driver.latest_result();
  ASSERT_TRUE(first.error.empty()) << first.error;
  ASSERT_TRUE(first.snapshot);
  EXPECT_EQ(first.scene_text, good.scene_text);  // the formula on screen, for Revert

  driver.request_step(at(0.1, bad));
  driver.wait_idle();
  const StepResult failed = driver.latest_result();
  EXPECT_NE(failed.error.find("zero"), std::string::npos) << failed.error;
  EXPECT_EQ(failed.snapshot, first.snapshot);  // the last good mesh stays
  EXPECT_TRUE(failed.scene_text.empty());      // no new formula runs

  // Back to the good formula (the panel's Revert): it runs on from the current time.
  driver.request_step(at(0.2, good));
  driver.wait_idle();
  const StepResult back = driver.latest_result();
  ASSERT_TRUE(back.error.empty()) << back.error;
  ASSERT_TRUE(back.snapshot);
  EXPECT_NE(back.snapshot, first.snapshot);
  EXPECT_DOUBLE_EQ(back.snapshot->time, 0.2);
}

TEST(FormulaSimulation, AFormulaThatBreaksLaterStopsWithTheMeshOfItsLastGoodTime) {
  // Fine until t = 0.5, then NaN everywhere.
  const SimulationControls c =
      coarse_expr({{"implicit", "x^2 + y^2 + z^2 - 1 + (t > 0.5 ? sqrt(-1) : 0)"},
                   {"bounds", "-2,-2,-2,2,2,2"}});
  SimulationDriver driver;
  driver.request_step(at(0.0, c, true));
  driver.wait_idle();
  const StepResult good = driver.latest_result();
  ASSERT_TRUE(good.error.empty()) << good.error;
  driver.request_step(at(0.75, c));
  driver.wait_idle();
  const StepResult late = driver.latest_result();
  EXPECT_FALSE(late.error.empty());
  EXPECT_EQ(late.snapshot, good.snapshot);
  EXPECT_DOUBLE_EQ(late.snapshot->time, 0.0);
}

}  // namespace
}  // namespace dynamesh
