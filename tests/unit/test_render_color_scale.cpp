// Colour scales taken from a field's values: a nearly constant field must not spread its
// rounding noise over the whole colour map; a field that really varies keeps its range.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "app/render/color_scale.h"

namespace dynamesh {
namespace {

// Where a value lands on the scale, 0..1.
float position(const ColorScale& s, float v) {
  return (v - s.min) / (s.max - s.min);
}

TEST(ColorScale, NearlyConstantCurvatureIsOneColour) {
  // A sphere of radius 0.6: curvature 1/0.6 everywhere, up to rounding in the 6th digit.
  std::vector<float> k;
  for (int i = 0; i < 1000; ++i) k.push_back(1.0f / 0.6f + 1e-5f * static_cast<float>(i % 7 - 3));
  const FieldStats stats = field_stats(k);
  EXPECT_NEAR(stats.mean, 1.0f / 0.6f, 1e-5f);
  const ColorScale s = color_scale(ColorMode::kCurvature, ColorSettings{}, stats);
  EXPECT_GE(s.max - s.min, kMinRelativeRange * stats.mean * 0.999f);
  // Every value sits in the middle of the map, within a hair.
  for (float v : k) EXPECT_NEAR(position(s, v), 0.5f, 1e-3f);
}

TEST(ColorScale, VaryingCurvatureKeepsItsRange) {
  std::vector<float> k;
  for (int i = 0; i <= 100; ++i) k.push_back(2.5f + 0.02f * static_cast<float>(i));  // 2.5..4.5
  const FieldStats stats = field_stats(k);
  const ColorScale s = color_scale(ColorMode::kCurvature, ColorSettings{}, stats);
  EXPECT_FLOAT_EQ(s.min, stats.low);
  EXPECT_FLOAT_EQ(s.max, stats.high);
  EXPECT_LT(position(s, 2.6f), 0.1f);
  EXPECT_GT(position(s, 4.4f), 0.9f);
}

TEST(ColorScale, AutomaticIntensityWindowIsWidenedTooButAManualOneIsNot) {
  std::vector<float> intensity(500, 80.0f);
  intensity[3] = 80.01f;
  const FieldStats stats = field_stats(intensity);
  ColorSettings auto_window;
  const ColorScale a = color_scale(ColorMode::kIntensity, auto_window, stats);
  EXPECT_NEAR(a.max - a.min, kMinRelativeRange * 80.0f, 1e-3f);
  EXPECT_NEAR(position(a, 80.0f), 0.5f, 1e-3f);

  ColorSettings manual;
  manual.intensity_auto = false;
  manual.intensity_window = 2.0;
  manual.intensity_level = 80.0;
  const ColorScale m = color_scale(ColorMode::kIntensity, manual, stats);
  EXPECT_FLOAT_EQ(m.min, 79.0f);
  EXPECT_FLOAT_EQ(m.max, 81.0f);
}

TEST(ColorScale, FieldOfZerosStillGetsANonEmptyRange) {
  const FieldStats stats = field_stats(std::vector<float>(10, 0.0f));
  const ColorScale s = color_scale(ColorMode::kCurvature, ColorSettings{}, stats);
  EXPECT_GT(s.max, s.min);
}

TEST(ColorScale, DiscreteLabelsThinToWhatFits) {
  ColorScale level;
  level.discrete = true;
  level.min = -0.5f;
  level.max = 8.5f;
  // Levels 0 .. 8: each its own label when nine fit, every second when five do.
  EXPECT_EQ(discrete_labels(level, 9), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(discrete_labels(level, 5), (std::vector<int>{0, 2, 4, 6, 8}));
  // A deep mesh: 0 .. 31 in at most 8 labels, multiples of 5.
  level.max = 31.5f;
  EXPECT_EQ(discrete_labels(level, 8), (std::vector<int>{0, 5, 10, 15, 20, 25, 30}));
  // Valence 3 .. 10 (bins from 2.5): all eight when they fit.
  ColorScale valence = color_scale(ColorMode::kValence, ColorSettings{}, FieldStats{});
  EXPECT_EQ(discrete_labels(valence, 8).size(), 8u);
  EXPECT_EQ(discrete_labels(valence, 8).front(), 3);
  // A typed range far from zero, and a huge one: never more than asked for.
  level.min = -1e9f;
  level.max = 1e9f;
  EXPECT_LE(discrete_labels(level, 6).size(), 6u);
  level.min = -7.5f;
  level.max = -0.5f;
  EXPECT_EQ(discrete_labels(level, 4), (std::vector<int>{-6, -4, -2}));
}

}  // namespace
}  // namespace dynamesh
