// Issue 14: the mri layers are coloured per fragment from the scan (a 3-D texture sampled at
// each fragment's world position through the inverse of the volume's placement), so the
// picture follows the scan, not the mesh. Driven through the real dynamesh-cli:
//   - the same layer at T = 0.5 and 0.1 mm, same camera, correlates >= 0.9 in grey value
//     over the brain's pixels (Colin27, and a synthetic checkered ball);
//   - the same world pattern stored on an axis-aligned grid and on an oblique, anisotropic
//     one gives the same picture (the sform is honoured per fragment);
//   - --color region paints each atlas region flat, and needs an atlas.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "test_nifti_files.h"
#include "test_render_scratch.h"
#include "test_volume_fixtures.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using test::Args;
using test::operator+;

constexpr const char* kColin27 = "/usr/share/mricron/templates/ch2bet.nii.gz";
constexpr int kWidth = 480, kHeight = 360;
// The 3D view lies left of the colour bar's strip (about a quarter of 480 pixels).
constexpr int kViewWidth = 320;

struct Picture {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const { return &rgb[3 * (std::size_t(y) * width + x)]; }
  double grey(int x, int y) const {
    const unsigned char* c = at(x, y);
    return 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
  }
  bool background(int x, int y) const {
    const unsigned char *c = at(x, y), *bg = at(1, 1);
    return std::abs(c[0] - bg[0]) + std::abs(c[1] - bg[1]) + std::abs(c[2] - bg[2]) <= 6;
  }
};

Picture render(const Args& args, const std::string& name) {
  const fs::path dir = test::render_scratch("mri_intensity_" + name);
  const test::CliRun r =
      test::run_cli(args + Args{"--render", dir.string(), "--size",
                                std::to_string(kWidth) + "x" + std::to_string(kHeight),
                                "--no-wireframe", "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  Picture p;
  int n = 0;
  stbi_uc* data = stbi_load((dir / "frame_00000.png").c_str(), &p.width, &p.height, &n, 3);
  if (data == nullptr) {
    ADD_FAILURE() << "no frame in " << dir << ": " << r.err;
    return p;
  }
  p.rgb.assign(data, data + 3 * p.width * p.height);
  stbi_image_free(data);
  return p;
}

// Pearson correlation of the grey values over the pixels that show the surface in both.
double grey_correlation(const Picture& a, const Picture& b, std::size_t* pixels = nullptr) {
  if (a.rgb.empty() || b.rgb.empty()) return 0.0;
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  std::size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < kViewWidth; ++x) {
      if (a.background(x, y) || b.background(x, y)) continue;
      const double u = a.grey(x, y), v = b.grey(x, y);
      sa += u, sb += v, saa += u * u, sbb += v * v, sab += u * v;
      ++n;
    }
  if (pixels) *pixels = n;
  if (n < 2) return 0.0;
  const double cov = sab / n - (sa / n) * (sb / n);
  const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
  return cov / std::sqrt(va * vb);
}

// A layer 3 mm below the brain's surface (t = 0.2 of depth_max 15 mm), seen from the left.
const Args kLayer{"--scene", "mri",     "--steps",   "0",        "--t0",
                  "0.2",     "--color", "intensity", "--camera", "90,10"};

TEST(MriIntensity, Colin27LayerLooksTheSameAtCoarseAndFineThreshold) {
  if (!fs::exists(kColin27)) GTEST_SKIP() << "mricron-data not installed";
  const Picture coarse = render(kLayer + Args{"--threshold", "0.5"}, "colin_05");
  const Picture fine = render(kLayer + Args{"--threshold", "0.1"}, "colin_01");
  std::size_t pixels = 0;
  const double r = grey_correlation(coarse, fine, &pixels);
  RecordProperty("correlation", std::to_string(r));
  std::printf("Colin27 T=0.5 vs T=0.1: grey correlation %.4f over %zu pixels\n", r, pixels);
  EXPECT_GT(pixels, 20000u);  // the brain fills a good part of the view
  EXPECT_GE(r, 0.9);
}

// A checkered ball (10 mm cells of 120 and 180 on a background of 0), radius 40 mm, the
// pattern a function of the world position, stored on `grid`.
fs::path write_checkered_ball(const fs::path& dir, const std::string& name, const VoxelGrid& grid) {
  std::vector<std::int16_t> values;
  for (int k = 0; k < grid.dims[2]; ++k)
    for (int j = 0; j < grid.dims[1]; ++j)
      for (int i = 0; i < grid.dims[0]; ++i) {
        const Vec3 p = grid.to_world(Vec3(i, j, k));
        const int cell = static_cast<int>(std::floor(p.x() / 10) + std::floor(p.y() / 10) +
                                          std::floor(p.z() / 10));
        values.push_back(p.norm() > 40.0 ? 0 : (cell & 1) ? 180 : 120);
      }
  nifti_1_header h = test::make_header({grid.dims[0], grid.dims[1], grid.dims[2]}, DT_INT16, 16);
  test::set_sform(h, grid.linear, grid.offset);
  const fs::path path = dir / (name + ".nii.gz");
  test::write_nifti(path, h, values);
  return path;
}

const VoxelGrid kAligned =
    test::oblique_grid({96, 96, 96}, Vec3(1, 1, 1), 0.0, Vec3(0, 0, 1), Vec3(0.3, -0.2, 0.1));
const VoxelGrid kOblique = test::oblique_grid({110, 100, 84}, Vec3(0.9, 1.0, 1.15), 0.5,
                                              Vec3(1, 2, 0), Vec3(0.3, -0.2, 0.1));

Args ball_layer(const fs::path& volume) {
  return {"--scene", "mri",  "--volume", volume.string(), "--param",   "threshold=60", "--steps",
          "0",       "--t0", "0.3",      "--color",       "intensity", "--camera",     "30,20"};
}

TEST(MriIntensity, CheckeredBallLooksTheSameAtCoarseAndFineThreshold) {
  const fs::path dir = test::render_scratch("mri_intensity_ball");
  const fs::path ball = write_checkered_ball(dir, "oblique", kOblique);
  const Picture coarse = render(ball_layer(ball) + Args{"--threshold", "0.5"}, "ball_05");
  const Picture fine = render(ball_layer(ball) + Args{"--threshold", "0.1"}, "ball_01");
  std::size_t pixels = 0;
  const double r = grey_correlation(coarse, fine, &pixels);
  std::printf("checkered ball T=0.5 vs T=0.1: grey correlation %.4f over %zu pixels\n", r, pixels);
  EXPECT_GT(pixels, 20000u);
  EXPECT_GE(r, 0.9);
}

TEST(MriIntensity, ObliquePlacementIsHonouredPerFragment) {
  // The same world pattern on two grids: the pictures agree only if each fragment goes
  // through its own volume's inverse sform (a shader ignoring the rotation or the spacing
  // would show the oblique grid's checkers turned and stretched).
  const fs::path dir = test::render_scratch("mri_intensity_grids");
  const Picture aligned =
      render(ball_layer(write_checkered_ball(dir, "aligned", kAligned)), "grid_aligned");
  const Picture oblique =
      render(ball_layer(write_checkered_ball(dir, "oblique", kOblique)), "grid_oblique");
  const double r = grey_correlation(aligned, oblique);
  std::printf("checkered ball aligned vs oblique grid: grey correlation %.4f\n", r);
  EXPECT_GE(r, 0.9);
}

// A label volume on its own (coarser) grid: region 1 where x < 0, region 2 where x >= 0.
fs::path write_halves_atlas(const fs::path& dir) {
  const VoxelGrid grid =
      test::oblique_grid({50, 50, 50}, Vec3(2, 2, 2), 0.0, Vec3(0, 0, 1), Vec3(0.5, 0.0, 0.0));
  std::vector<std::int16_t> values;
  for (int k = 0; k < 50; ++k)
    for (int j = 0; j < 50; ++j)
      for (int i = 0; i < 50; ++i) values.push_back(grid.to_world(Vec3(i, j, k)).x() < 0 ? 1 : 2);
  nifti_1_header h = test::make_header({50, 50, 50}, DT_INT16, 16);
  test::set_sform(h, grid.linear, grid.offset);
  const fs::path path = dir / "halves.nii.gz";
  test::write_nifti(path, h, values);
  test::write_text(dir / "halves.nii.txt", "1 Left_half 11\n2 Right_half 12\n");
  return path;
}

TEST(MriIntensity, RegionColoursAreFlatPerAtlasRegion) {
  const fs::path dir = test::render_scratch("mri_region");
  const fs::path ball = write_checkered_ball(dir, "ball", kOblique);
  const Args layer{"--scene", "mri", "--volume", ball.string(), "--param",  "threshold=60",
                   "--steps", "0",   "--t0",     "0.3",         "--camera", "0,90"};
  // Without an atlas there are no regions to show: bad input.
  const test::CliRun refused = test::run_cli(layer + Args{"--color", "region", "--quiet"});
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("--atlas"), std::string::npos) << refused.err;

  // Seen from above (+y up the screen is -z... any way round): x < 0 is one side of the
  // picture, x >= 0 the other. Each side is one flat colour (up to shading), the two differ.
  const Picture p =
      render(layer + Args{"--color", "region", "--atlas", write_halves_atlas(dir).string()},
             "region_halves");
  ASSERT_FALSE(p.rgb.empty());
  int left = kWidth, right = -1;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (!p.background(x, y)) left = std::min(left, x), right = std::max(right, x);
  ASSERT_GT(right - left, 100);
  // Chromaticity (r, g) / (r + g + b): lighting scales a colour without changing it.
  const auto chroma = [&](int x, int y) {
    const unsigned char* c = p.at(x, y);
    const double s = std::max(1, c[0] + c[1] + c[2]);
    return std::pair<double, double>(c[0] / s, c[1] / s);
  };
  const int y = p.height / 2;
  const auto a = chroma(left + (right - left) / 5, y), a2 = chroma(left + (right - left) / 3, y);
  const auto b = chroma(right - (right - left) / 5, y), b2 = chroma(right - (right - left) / 3, y);
  EXPECT_NEAR(a.first, a2.first, 0.02);
  EXPECT_NEAR(a.second, a2.second, 0.02);
  EXPECT_NEAR(b.first, b2.first, 0.02);
  EXPECT_NEAR(b.second, b2.second, 0.02);
  EXPECT_GT(std::abs(a.first - b.first) + std::abs(a.second - b.second), 0.05);
}

TEST(MriIntensity, IntensityMapAndAtlasOptions) {
  const fs::path dir = test::render_scratch("mri_options");
  const fs::path ball = write_checkered_ball(dir, "ball", kAligned);
  // Grey has no colour; viridis does (its ends are purple and yellow).
  const auto saturated_share = [](const Picture& p) {
    std::size_t n = 0, coloured = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < kViewWidth; ++x) {
        if (p.background(x, y)) continue;
        const unsigned char* c = p.at(x, y);
        const int mx = std::max({c[0], c[1], c[2]}), mn = std::min({c[0], c[1], c[2]});
        ++n;
        coloured += mx > 0 && (mx - mn) > 0.25 * mx;
      }
    return n ? double(coloured) / double(n) : 0.0;
  };
  const Picture grey = render(ball_layer(ball), "map_grey");
  const Picture viridis =
      render(ball_layer(ball) + Args{"--intensity-map", "viridis"}, "map_viridis");
  EXPECT_LT(saturated_share(grey), 0.01);
  EXPECT_GT(saturated_share(viridis), 0.5);
  // Bad values: one line naming the option, exit status 2.
  for (const Args& bad : {ball_layer(ball) + Args{"--intensity-map", "jet"},
                          ball_layer(ball) + Args{"--atlas", (dir / "missing.nii.gz").string()},
                          ball_layer(ball) + Args{"--atlas", ball.string() + ".txt"}}) {
    const test::CliRun r = test::run_cli(bad + Args{"--quiet"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.err.find("--intensity-map") != std::string::npos ||
                r.err.find("--atlas") != std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace dynamesh
