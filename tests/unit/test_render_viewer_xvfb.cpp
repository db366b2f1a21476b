// The real viewer under a virtual display (xvfb-run): a scripted run writes a screenshot that
// shows the ImGui panel and the mesh. Fails, never skips, when it cannot run: xvfb is in
// scripts/debian-packages.txt, so a machine built by ./dev has it.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

struct Rgb {
  int r, g, b;
};

TEST(ViewerUnderXvfb, ScriptedRunWritesScreenshotWithPanelAndMesh) {
  ASSERT_TRUE(on_path("xvfb-run")) << "xvfb-run not found: install the Debian package xvfb";
  const fs::path dir = fs::path(DYNAMESH_BINARY_DIR) / "test_output" / "viewer_xvfb";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path shot = dir / "viewer.png";
  const std::string command = "xvfb-run -a -s '-screen 0 1280x800x24' '" +
                              std::string(DYNAMESH_VIEWER) +
                              "' --scene sphere --frames 5 --width 1000 --height 640 "
                              "--screenshot '" +
                              shot.string() + "' > '" + (dir / "log.txt").string() + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "log.txt");

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

TEST(ViewerUnderXvfb, WithoutDisplayExitsTwoNamingTheBatchCommand) {
  const fs::path log = fs::path(DYNAMESH_BINARY_DIR) / "test_output" / "viewer_nodisplay.txt";
  fs::create_directories(log.parent_path());
  const std::string command = "env -u DISPLAY -u WAYLAND_DISPLAY '" + std::string(DYNAMESH_VIEWER) +
                              "' > '" + log.string() + "' 2>&1";
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
  const int status = std::system(
      ("'" + std::string(DYNAMESH_VIEWER) + "' --no-such-option >/dev/null 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
}

}  // namespace
}  // namespace dynamesh
