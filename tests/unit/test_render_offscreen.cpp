// Offscreen rendering (OSMesa): what the pictures contain, measured in pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/offscreen/offscreen_render.h"
#include "test_render_shapes.h"

namespace dynamesh {
namespace {

struct Hsv {
  double h, s, v;  // hue in degrees
};

Hsv hsv(const std::uint8_t* p) {
  const double r = p[0] / 255.0, g = p[1] / 255.0, b = p[2] / 255.0;
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), d = mx - mn;
  double h = 0.0;
  if (d > 0.0) {
    if (mx == r)
      h = 60.0 * std::fmod((g - b) / d + 6.0, 6.0);
    else if (mx == g)
      h = 60.0 * ((b - r) / d + 2.0);
    else
      h = 60.0 * ((r - g) / d + 4.0);
  }
  return {h, mx > 0.0 ? d / mx : 0.0, mx};
}

bool is_background(const Image& img, int x, int y, const RenderStyle& style) {
  const std::uint8_t* p = img.pixel(x, y);
  for (int k = 0; k < 3; ++k) {
    if (std::abs(p[k] - style.background[k] * 255.0f) > 1.5f) return false;
  }
  return true;
}

double covered_fraction(const Image& img, const RenderStyle& style) {
  int covered = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) covered += is_background(img, x, y, style) ? 0 : 1;
  }
  return static_cast<double>(covered) / (img.width * img.height);
}

OffscreenOptions small_options(ColorMode mode) {
  OffscreenOptions o;
  o.width = 320;
  o.height = 240;
  o.style.mode = mode;
  o.style.wireframe = false;
  o.colorbar = false;
  o.refit_each_frame = true;  // the suite shares one renderer across shapes
  return o;
}

class OffscreenRenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { renderer_ = new OffscreenRenderer(); }
  static void TearDownTestSuite() {
    delete renderer_;
    renderer_ = nullptr;
  }
  static OffscreenRenderer* renderer_;
};
OffscreenRenderer* OffscreenRenderTest::renderer_ = nullptr;

TEST_F(OffscreenRenderTest, SphereCoversCentreAndLeavesCornersToBackground) {
  const OffscreenOptions o = small_options(ColorMode::kShaded);
  const Image img = renderer_->render(test::sphere_snapshot(), o);
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 240);
  // A fitted sphere fills most of the height: a disc of radius ~0.9 * 120 pixels.
  const double fraction = covered_fraction(img, o.style);
  EXPECT_GT(fraction, 0.35);
  EXPECT_LT(fraction, 0.62);
  for (auto [x, y] : {std::pair{0, 0}, {319, 0}, {0, 239}, {319, 239}}) {
    EXPECT_TRUE(is_background(img, x, y, o.style)) << "corner " << x << "," << y;
  }
  EXPECT_FALSE(is_background(img, 160, 120, o.style));
  // Shaded: the surface tint is a pale grey-blue, not a colour-map colour.
  EXPECT_LT(hsv(img.pixel(160, 120)).s, 0.3);
}

TEST_F(OffscreenRenderTest, SphereOffCentreIsFittedToo) {
  const OffscreenOptions o = small_options(ColorMode::kShaded);
  const Image img = renderer_->render(test::sphere_snapshot(5.0, Vec3(10, -3, 2)), o);
  EXPECT_GT(covered_fraction(img, o.style), 0.35);
  EXPECT_FALSE(is_background(img, 160, 120, o.style));
}

TEST_F(OffscreenRenderTest, ErrorZeroIsYellowAndAtThresholdIsRed) {
  OffscreenOptions o = small_options(ColorMode::kError);
  o.style.colors.threshold = 0.01;
  const Image none = renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.0f), o);
  const Hsv yellow = hsv(none.pixel(160, 120));
  EXPECT_GT(yellow.h, 40.0);
  EXPECT_LT(yellow.h, 70.0);
  EXPECT_GT(yellow.s, 0.6);

  const Image at = renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.01f), o);
  const Image beyond = renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.5f), o);
  for (const Image* img : {&at, &beyond}) {
    const Hsv red = hsv(img->pixel(160, 120));
    EXPECT_TRUE(red.h < 15.0 || red.h > 345.0) << "hue " << red.h;
    EXPECT_GT(red.s, 0.6);
  }
  const Hsv half =
      hsv(renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.005f), o).pixel(160, 120));
  EXPECT_GT(half.h, 80.0) << "half the threshold is green";
  EXPECT_LT(half.h, 160.0);
}

TEST_F(OffscreenRenderTest, ViridisErrorEndsArePurpleAndYellow) {
  OffscreenOptions o = small_options(ColorMode::kError);
  o.style.colors.error_viridis = true;
  const Hsv low =
      hsv(renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.0f), o).pixel(160, 120));
  EXPECT_GT(low.h, 260.0);
  EXPECT_LT(low.h, 320.0);
}

TEST_F(OffscreenRenderTest, ValenceCategoriesDiffer) {
  const OffscreenOptions o = small_options(ColorMode::kValence);
  const Image four = renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 4.0f), o);
  const Image eight = renderer_->render(test::sphere_snapshot(1.0, Vec3::Zero(), 8.0f), o);
  EXPECT_GT(std::abs(hsv(four.pixel(160, 120)).h - hsv(eight.pixel(160, 120)).h), 60.0);
}

// Pixels the wireframe darkened: compared with the same picture without it.
Image wire_mask(const Image& plain, const Image& wired) {
  Image mask(plain.width, plain.height);
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      mask.pixel(x, y)[0] = hsv(wired.pixel(x, y)).v < hsv(plain.pixel(x, y)).v - 0.25 ? 1 : 0;
    }
  }
  return mask;
}

// Median length of the runs of wire pixels along the rows and columns of the centre area.
int median_wire_run(const Image& mask) {
  std::vector<int> runs;
  const auto scan = [&](int n, auto at) {
    int run = 0;
    for (int i = 0; i < n; ++i) {
      if (at(i)) {
        ++run;
      } else if (run > 0) {
        runs.push_back(run);
        run = 0;
      }
    }
  };
  for (int y = mask.height / 3; y < 2 * mask.height / 3; ++y) {
    scan(mask.width, [&](int x) { return mask.pixel(x, y)[0] != 0; });
  }
  for (int x = mask.width / 3; x < 2 * mask.width / 3; ++x) {
    scan(mask.height, [&](int y) { return mask.pixel(x, y)[0] != 0; });
  }
  if (runs.empty()) return 0;
  std::nth_element(runs.begin(), runs.begin() + runs.size() / 2, runs.end());
  return runs[runs.size() / 2];
}

int count(const Image& mask) {
  int n = 0;
  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) n += mask.pixel(x, y)[0];
  }
  return n;
}

TEST_F(OffscreenRenderTest, WireframeStaysThinAtAnyZoom) {
  OffscreenOptions o = small_options(ColorMode::kShaded);
  const MeshSnapshot sphere = test::sphere_snapshot();
  for (float zoom : {1.0f, 4.0f, 16.0f}) {
    o.style.wireframe = false;
    o.camera.reset();
    const Image fitted = renderer_->render(sphere, o);
    (void)fitted;
    o.camera = renderer_->camera();
    o.camera->distance /= zoom;
    const Image plain = renderer_->render(sphere, o);
    o.style.wireframe = true;
    const Image mask = wire_mask(plain, renderer_->render(sphere, o));
    EXPECT_GT(count(mask), 200) << "zoom " << zoom;
    // One-pixel lines: runs across them are 1-3 pixels whatever the zoom, where a world-space
    // width would grow with it.
    EXPECT_GE(median_wire_run(mask), 1) << "zoom " << zoom;
    EXPECT_LE(median_wire_run(mask), 3) << "zoom " << zoom;
  }
}

TEST_F(OffscreenRenderTest, BackFacesHaveTheirOwnTint) {
  OffscreenOptions o = small_options(ColorMode::kShaded);
  o.camera = Camera();
  o.camera->target = glm::vec3(0.0f);
  o.camera->distance = 0.2f;  // inside the unit sphere: only back faces are seen
  const Hsv inside = hsv(renderer_->render(test::sphere_snapshot(), o).pixel(160, 120));
  EXPECT_TRUE(inside.h < 30.0 || inside.h > 340.0) << "reddish tint, hue " << inside.h;
  EXPECT_GT(inside.s, 0.25);
}

TEST_F(OffscreenRenderTest, ColorBarShowsTheMapOnTheRight) {
  OffscreenOptions o = small_options(ColorMode::kError);
  o.colorbar = true;
  const Image img = renderer_->render(test::sphere_snapshot(), o);
  bool red = false, yellow = false;
  for (int y = 0; y < img.height; ++y) {
    for (int x = img.width - 30; x < img.width; ++x) {
      const Hsv c = hsv(img.pixel(x, y));
      if (c.s > 0.7 && c.v > 0.6 && (c.h < 10 || c.h > 350)) red = true;
      if (c.s > 0.7 && c.v > 0.8 && c.h > 45 && c.h < 65) yellow = true;
    }
  }
  EXPECT_TRUE(red);
  EXPECT_TRUE(yellow);
}

TEST(OffscreenRenderer, SameConnectivityUploadsPositionsOnly) {
  OffscreenRenderer renderer;
  const OffscreenOptions o = small_options(ColorMode::kShaded);
  MeshSnapshot s = test::sphere_snapshot();
  renderer.render(s, o);
  EXPECT_EQ(renderer.uploads().full, 1);
  for (float& x : s.positions) x *= 1.1f;  // deformed, same triangles
  renderer.render(s, o);
  EXPECT_EQ(renderer.uploads().full, 1);
  EXPECT_EQ(renderer.uploads().geometry, 1);
  renderer.render(test::sphere_snapshot(1.0, Vec3::Zero(), 0.0f, 8, 16), o);
  EXPECT_EQ(renderer.uploads().full, 2);
}

}  // namespace
}  // namespace dynamesh
