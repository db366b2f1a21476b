// What `dynamesh-cli run --render` draws (issue 12), read back from its PNG files: an open
// surface shows its colour bar's colours from above and from below; --color, --camera,
// --no-wireframe, --color-range change the picture in the documented direction; categorical
// fields (valence) are flat per vertex region, not blended across faces; the shaded sinc
// shows its front from above.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/render/colormap.h"
#include "app/render/render_style.h"
#include "cli_runner.h"
#include "test_render_scratch.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using test::Args;
using test::operator+;

struct Rgb {
  int r = 0, g = 0, b = 0;
};

// Hue in degrees and saturation in [0, 1] (HSV): lighting scales a colour and specular
// highlights add white, neither of which moves its hue.
double hue(const Rgb& c) {
  const double r = c.r / 255.0, g = c.g / 255.0, b = c.b / 255.0;
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), d = mx - mn;
  if (d <= 0) return 0.0;
  double h = mx == r ? std::fmod((g - b) / d, 6.0) : mx == g ? (b - r) / d + 2 : (r - g) / d + 4;
  h *= 60.0;
  return h < 0 ? h + 360.0 : h;
}
double saturation(const Rgb& c) {
  const int mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  return mx == 0 ? 0.0 : double(mx - mn) / mx;
}
double hue_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 360.0 - d);
}

struct Picture {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;
  Rgb at(int x, int y) const { return pixels[std::size_t(y) * width + x]; }
  // Pixels of the 3D view (left of the colour bar strip) that are not background.
  std::vector<Rgb> mesh_pixels(int view_width) const {
    std::vector<Rgb> out;
    const Rgb bg = at(1, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < view_width; ++x) {
        const Rgb c = at(x, y);
        if (std::abs(c.r - bg.r) + std::abs(c.g - bg.g) + std::abs(c.b - bg.b) > 12)
          out.push_back(c);
      }
    return out;
  }
};

// Renders frame 0 (or `frame`) of a run and reads it back.
Picture render(const Args& args, const std::string& name, const std::string& frame = "00000",
               const std::string& size = "320x240") {
  const fs::path dir = test::render_scratch("cli_pictures_" + name);
  const test::CliRun r =
      test::run_cli(args + Args{"--render", dir.string(), "--size", size, "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  Picture p;
  int n = 0;
  stbi_uc* data =
      stbi_load((dir / ("frame_" + frame + ".png")).c_str(), &p.width, &p.height, &n, 3);
  if (data == nullptr) {
    ADD_FAILURE() << "no frame " << frame << " in " << dir;
    return p;
  }
  for (int i = 0; i < p.width * p.height; ++i)
    p.pixels.push_back({data[3 * i], data[3 * i + 1], data[3 * i + 2]});
  stbi_image_free(data);
  return p;
}

// The sinc at t = 0 is flat (amplitude alpha sin 0): its error is zero everywhere.
const Args kFlatSinc{"--scene", "sinc",  "--steps",       "0", "--t0", "0",
                     "--color", "error", "--no-wireframe"};

TEST(CliPictures, OpenSurfaceShowsTheBarsColoursFromAboveAndBelow) {
  const glm::vec3 zero = colormap(ColormapId::kErrorYellowGreenRed).sample(0.0f);
  const Rgb bar{int(255 * zero.r), int(255 * zero.g), int(255 * zero.b)};
  const Picture above = render(kFlatSinc + Args{"--camera", "0,90"}, "above");
  const Picture below = render(kFlatSinc + Args{"--camera", "0,-90"}, "below");
  ASSERT_FALSE(above.pixels.empty());
  ASSERT_FALSE(below.pixels.empty());
  for (const Picture* p : {&above, &below}) {
    // The middle of the view (the colour bar takes the right edge).
    const Rgb c = p->at(p->width * 2 / 5, p->height / 2);
    SCOPED_TRACE(p == &above ? "above" : "below");
    EXPECT_LT(hue_distance(hue(c), hue(bar)), 6.0)
        << "pixel " << c.r << "," << c.g << "," << c.b << " against the bar's " << bar.r << ","
        << bar.g << "," << bar.b;
    EXPECT_GT(saturation(c), 0.5) << c.r << "," << c.g << "," << c.b;
  }
  const Rgb a = above.at(above.width * 2 / 5, above.height / 2);
  const Rgb b = below.at(below.width * 2 / 5, below.height / 2);
  EXPECT_LE(std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b), 30);
  // Shaded: the flat grey-blue tint, no colour map.
  const Picture shaded = render(Args{"--scene", "sinc", "--steps", "0", "--t0", "0", "--color",
                                     "shaded", "--camera", "0,90", "--no-wireframe"},
                                "shaded");
  EXPECT_LT(saturation(shaded.at(shaded.width / 2, shaded.height / 2)), 0.35);
}

// The sinc is a height field whose upper side is its front (sinc_scene.h): shaded from above
// it shows the surface tint, from below the back-face tint blended in (mesh.frag.glsl). Hues,
// since lighting scales a colour and highlights add white.
TEST(CliPictures, ShadedSincShowsItsFrontFromAbove) {
  const RenderStyle style;
  const glm::vec3 back = glm::mix(style.surface_color, style.backface_tint, 0.65f);
  const auto rgb = [](const glm::vec3& c) {
    return Rgb{int(255 * c.r), int(255 * c.g), int(255 * c.b)};
  };
  const double front_hue = hue(rgb(style.surface_color)), back_hue = hue(rgb(back));
  ASSERT_GT(hue_distance(front_hue, back_hue), 90.0);  // the two are told apart by hue
  const Args flat{"--scene", "sinc",    "--param", "alpha=0",       "--steps",
                  "0",       "--color", "shaded",  "--no-wireframe"};
  for (const char* side : {"above", "below"}) {
    SCOPED_TRACE(side);
    const bool above = std::string(side) == "above";
    const Picture p =
        render(flat + Args{"--camera", above ? "0,90" : "0,-90"}, std::string("shaded_") + side);
    ASSERT_FALSE(p.pixels.empty());
    // A 5 x 5 block of the view's middle, every pixel nearer the expected side's hue.
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const Rgb c = p.at(p.width * 2 / 5 + 10 * dx, p.height / 2 + 10 * dy);
        const double to_front = hue_distance(hue(c), front_hue),
                     to_back = hue_distance(hue(c), back_hue);
        EXPECT_LT(above ? to_front : to_back, 15.0)
            << "pixel " << c.r << "," << c.g << "," << c.b << " (front " << front_hue
            << " deg, back " << back_hue << " deg)";
      }
  }
}

TEST(CliPictures, CameraDistanceAndElevation) {
  const Args flat{"--scene", "sinc", "--steps", "0", "--t0", "0", "--color", "shaded"};
  const std::size_t near =
      render(flat + Args{"--camera", "0,90,3"}, "near").mesh_pixels(320).size();
  const std::size_t far = render(flat + Args{"--camera", "0,90,6"}, "far").mesh_pixels(320).size();
  const std::size_t edge_on =
      render(flat + Args{"--camera", "0,0"}, "edge_on").mesh_pixels(320).size();
  // Twice as far, a quarter of the pixels; a flat square seen edge on is a line.
  EXPECT_GT(near, 3 * far);
  EXPECT_GT(far, 10 * edge_on);
  // Bad views: exit 2.
  for (const char* bad : {"90", "0,91", "a,b", "0,0,-1", "0,0,1,2"})
    EXPECT_EQ(test::run_cli({"--scene", "sinc", "--camera", bad}).status, 2) << bad;
}

TEST(CliPictures, WireframeCanBeTurnedOff) {
  const Args curved{"--scene", "sinc", "--steps", "0", "--t0", "0.25", "--color", "shaded"};
  const auto dark = [](const Picture& p) {
    std::size_t n = 0;
    for (const Rgb& c : p.mesh_pixels(320)) n += c.r + c.g + c.b < 3 * 70;
    return n;
  };
  const Picture wired = render(curved + Args{"--wireframe"}, "wired");
  const Picture bare = render(curved + Args{"--no-wireframe"}, "bare");
  const std::size_t mesh = bare.mesh_pixels(320).size();
  EXPECT_GT(dark(wired), mesh / 20);
  EXPECT_GT(dark(wired), 10 * dark(bare));
}

// The values of a per-vertex field in a VTK PolyData file written by --export.
std::vector<double> vtp_field(const fs::path& vtp, const std::string& name) {
  const std::string text = test::slurp_file(vtp);
  std::vector<double> values;
  const auto at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return values;
  std::istringstream in(text.substr(text.find('>', at) + 1));
  for (double v; in >> v;) values.push_back(v);
  return values;
}

TEST(CliPictures, ValenceIsFlatPerVertexRegion) {
  // The flat sinc's base mesh from above: a 4-8 mesh has no vertex of valence 6 inside, but
  // its valence-4 and valence-8 vertices are joined by edges. Blended across faces, every
  // such edge would pass through the colour of 6 (yellow); flat per vertex region, the
  // colour of 6 appears nowhere but in anti-aliased pixels along region borders.
  const fs::path meshes = test::render_scratch("valence_meshes");
  const Picture p =
      render(Args{"--scene", "sinc", "--steps", "0", "--t0", "0", "--color", "valence",
                  "--no-wireframe", "--camera", "0,90", "--export", meshes.string()},
             "valence", "00000", "800x600");
  const std::vector<double> valence = vtp_field(meshes / "frame_00000.vtp", "valence");
  ASSERT_FALSE(valence.empty());
  ASSERT_EQ(std::count(valence.begin(), valence.end(), 6.0), 0);
  ASSERT_GT(std::count(valence.begin(), valence.end(), 4.0), 0);
  ASSERT_GT(std::count(valence.begin(), valence.end(), 8.0), 0);
  const glm::vec3 six = colormap(ColormapId::kCategorical).sample((6.0f - 2.5f) / 8.0f);
  const double six_hue = hue(Rgb{int(255 * six.r), int(255 * six.g), int(255 * six.b)});
  std::size_t mesh = 0, yellow = 0;
  for (const Rgb& c : p.mesh_pixels(650)) {
    ++mesh;
    // Lighting clamps the red channel first, which moves yellow's hue up by a few degrees.
    yellow += saturation(c) > 0.3 && hue(c) > six_hue - 6.0 && hue(c) < six_hue + 12.0;
  }
  ASSERT_GT(mesh, 50000u);
  EXPECT_LT(double(yellow) / mesh, 0.03) << yellow << " of " << mesh << " pixels show valence 6";
}

TEST(CliPictures, ColorRangeHoldsAcrossFrames) {
  // sinc from its peak (t = 0.25) to flat (t = 0.5), coloured by curvature. The colour bar
  // (its numbers) is drawn in the image's right strip: per frame it changes with the field,
  // with a fixed range (first frame, whole run, typed) it is the same in every frame.
  const Args run{"--scene", "sinc", "--steps", "2",         "--t0",          "0.25",
                 "--t1",    "0.5",  "--color", "curvature", "--no-wireframe"};
  const auto bar_changes = [&](const std::string& range) {
    const Picture first = render(run + Args{"--color-range", range}, "range_" + range, "00000");
    const Picture last = render(run + Args{"--color-range", range}, "range_" + range, "00002");
    int differing = 0;
    for (int y = 0; y < first.height; ++y)
      for (int x = 250; x < first.width; ++x) {
        const Rgb a = first.at(x, y), b = last.at(x, y);
        differing += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b) > 30;
      }
    return differing;
  };
  EXPECT_GT(bar_changes("frame"), 50);
  EXPECT_EQ(bar_changes("first"), 0);
  EXPECT_EQ(bar_changes("run"), 0);
  EXPECT_EQ(bar_changes("-2,2"), 0);
  for (const char* bad : {"all", "1,1", "2,1", "a,b"})
    EXPECT_EQ(test::run_cli({"--scene", "sinc", "--color-range", bad}).status, 2) << bad;
}

}  // namespace
}  // namespace dynamesh
