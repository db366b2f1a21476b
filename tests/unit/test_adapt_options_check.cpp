// The adaptation options' limits (core/adapt/adapt_options_check.h), at each side of each
// boundary; both programs refuse through this one check (test_render_viewer_hostile.cpp
// compares their lines).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/adapt/adapt_options_check.h"

namespace dynamesh {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The problem with the defaults changed by `change`, or "" when none.
template <class Change>
std::string problem(Change change) {
  AdaptOptions o;
  change(o);
  return adapt_option_problem(o);
}

TEST(AdaptOptionsCheck, DefaultsPass) {
  EXPECT_EQ(adapt_option_problem(AdaptOptions{}), "");
}

TEST(AdaptOptionsCheck, EachOptionIsRefusedJustOutsideItsRangeAndNamed) {
  struct Case {
    const char* option;
    void (*outside)(AdaptOptions&);
    void (*inside)(AdaptOptions&);
  };
  const Case cases[] = {
      {"--threshold", [](AdaptOptions& o) { o.threshold = 0.0; },
       [](AdaptOptions& o) { o.threshold = 1e-12, o.epsilon = 0.0; }},
      {"--threshold", [](AdaptOptions& o) { o.threshold = kInf; },
       [](AdaptOptions& o) { o.threshold = 1e6; }},
      {"--epsilon", [](AdaptOptions& o) { o.epsilon = -1e-300; },
       [](AdaptOptions& o) { o.epsilon = 0.0; }},
      {"--density", [](AdaptOptions& o) { o.density = 0.0; },
       [](AdaptOptions& o) { o.density = 1e-6; }},
      {"--density", [](AdaptOptions& o) { o.density = kNaN; },
       [](AdaptOptions& o) { o.density = 1e9; }},
      {"--max-triangles", [](AdaptOptions& o) { o.max_triangles = kMinTriangleBudget - 1; },
       [](AdaptOptions& o) { o.max_triangles = kMinTriangleBudget; }},
      {"--k", [](AdaptOptions& o) { o.smoothing.k = -1e-9; },
       [](AdaptOptions& o) { o.smoothing.k = 0.0; }},
      {"--smooth-iters", [](AdaptOptions& o) { o.smoothing.iterations = -1; },
       [](AdaptOptions& o) { o.smoothing.iterations = 0; }},
      {"--smooth-iters", [](AdaptOptions& o) { o.smoothing.iterations = kMaxSmoothIterations + 1; },
       [](AdaptOptions& o) { o.smoothing.iterations = kMaxSmoothIterations; }},
      {"--smooth-settled", [](AdaptOptions& o) { o.smoothing.settled_offset = 1.0; },
       [](AdaptOptions& o) { o.smoothing.settled_offset = 0.999; }},
      {"--smooth-settled", [](AdaptOptions& o) { o.smoothing.settled_offset = kNaN; },
       [](AdaptOptions& o) { o.smoothing.settled_offset = 0.0; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.option);
    const std::string refused = problem(c.outside);
    EXPECT_EQ(refused.rfind(std::string(c.option) + " must", 0), 0u) << refused;
    EXPECT_EQ(refused.find('\n'), std::string::npos) << refused;
    EXPECT_EQ(problem(c.inside), "");
  }
}

TEST(AdaptOptionsCheck, HysteresisAgainstTheThresholdIsLeftToTheCaller) {
  // The CLI takes a scene's suggested threshold after loading the scene (apply_scene_defaults).
  EXPECT_EQ(problem([](AdaptOptions& o) { o.threshold = 0.001, o.epsilon = 0.5; }), "");
}

}  // namespace
}  // namespace dynamesh
