// PNG files: what the project writes is read back by an independent decoder (stb_image's)
// and matches the rendered pixels; failures leave no file behind.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <filesystem>
#include <memory>

#include "app/offscreen/offscreen_render.h"
#include "app/render/png_file.h"
#include "test_render_shapes.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::path(DYNAMESH_BINARY_DIR) / "test_output" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

struct Decoded {
  int width = 0, height = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels{nullptr, stbi_image_free};
};

Decoded decode(const fs::path& path) {
  Decoded d;
  int channels = 0;
  d.pixels.reset(stbi_load(path.c_str(), &d.width, &d.height, &channels, 3));
  return d;
}

TEST(PngFile, RenderedFrameReadsBackIdentically) {
  const fs::path dir = scratch_dir("png_roundtrip");
  OffscreenOptions o;
  o.width = 200;
  o.height = 150;
  o.style.mode = ColorMode::kError;
  MeshSnapshot s = test::sphere_snapshot();
  auto& error = s.fields[0].values;
  for (std::size_t i = 0; i < error.size(); ++i) error[i] = 0.01f * s.positions[3 * i + 1];
  const Image rendered = render_to_image(s, o);
  write_png(rendered, (dir / "frame.png").string());

  const Decoded d = decode(dir / "frame.png");
  ASSERT_NE(d.pixels, nullptr) << stbi_failure_reason();
  ASSERT_EQ(d.width, 200);
  ASSERT_EQ(d.height, 150);
  int differing = 0;
  for (int y = 0; y < d.height; ++y) {
    for (int x = 0; x < d.width; ++x) {
      const stbi_uc* p = d.pixels.get() + 3 * (y * d.width + x);
      for (int k = 0; k < 3; ++k) differing += p[k] != rendered.pixel(x, y)[k] ? 1 : 0;
    }
  }
  EXPECT_EQ(differing, 0);
  // Nothing but the finished file: the temporary was renamed into place.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(PngFile, TopRowIsTheTopOfThePicture) {
  const fs::path dir = scratch_dir("png_orientation");
  Image image(4, 2);
  for (int x = 0; x < 4; ++x) {
    image.pixel(x, 0)[0] = 255;  // top row red
    image.pixel(x, 1)[2] = 255;  // bottom row blue
  }
  write_png(image, (dir / "rows.png").string());
  const Decoded d = decode(dir / "rows.png");
  ASSERT_NE(d.pixels, nullptr);
  EXPECT_EQ(d.pixels.get()[0], 255);
  EXPECT_EQ(d.pixels.get()[3 * 4 + 2], 255);
}

TEST(PngFile, RenderToPngWritesAFile) {
  const fs::path dir = scratch_dir("png_render");
  OffscreenOptions o;
  o.width = 64;
  o.height = 48;
  render_to_png(test::sphere_snapshot(), o, (dir / "sphere.png").string());
  const Decoded d = decode(dir / "sphere.png");
  ASSERT_NE(d.pixels, nullptr);
  EXPECT_EQ(d.width, 64);
}

TEST(PngFile, UnwritablePathThrowsAndLeavesNothing) {
  const fs::path dir = scratch_dir("png_fail");
  const fs::path missing = dir / "no_such_dir" / "x.png";
  EXPECT_THROW(write_png(Image(4, 4), missing.string()), std::runtime_error);
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 0);
}

TEST(PngFile, EmptyImageIsRefused) {
  EXPECT_THROW(write_png(Image(), "/tmp/never_written.png"), std::runtime_error);
}

}  // namespace
}  // namespace dynamesh
