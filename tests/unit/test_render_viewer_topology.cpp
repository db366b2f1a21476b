// Topology events in the real viewer (issue 16: "a merge is just another frame"): the blobs
// scene played through its merge and its split under a virtual display, one PNG per step
// (--record without ffmpeg on PATH). Judged from the pixels, independently of the engine's
// bookkeeping: the mesh's silhouette in the 3D view is two pieces before the merge and after
// the split, one piece between; and the viewer reports each event (stderr, as the panel's
// statistics show it) with its step and how the mesh followed.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "test_render_scratch.h"
#include "xvfb_run.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 800, kHeight = 560;
constexpr int kPanel = 345;      // the ImGui panel on the left
constexpr int kColourBar = 140;  // the colour bar on the right

// 4-connected regions of at least `smallest` pixels within the 3D view that are the mesh
// (`mesh` true: not the light background) or the background (`mesh` false). The mesh's pieces
// count its components as seen; the background's count the holes seen through it, plus one.
int regions(const fs::path& png, bool mesh, int smallest = 400) {
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load(png.c_str(), &w, &h, &n, 3);
  if (pixels == nullptr) return -1;
  const int x0 = kPanel, x1 = w - kColourBar;
  const auto wanted = [&](int x, int y) {
    const stbi_uc* p = pixels + 3 * (y * w + x);
    return (p[0] + p[1] + p[2] < 3 * 200) == mesh;
  };
  std::vector<char> seen(static_cast<std::size_t>(w * h), 0);
  int count = 0;
  std::vector<std::pair<int, int>> stack;
  for (int y = 0; y < h; ++y)
    for (int x = x0; x < x1; ++x) {
      if (seen[y * w + x] || !wanted(x, y)) continue;
      int size = 0;
      stack.assign(1, {x, y});
      seen[y * w + x] = 1;
      while (!stack.empty()) {
        const auto [cx, cy] = stack.back();
        stack.pop_back();
        ++size;
        const int next[4][2] = {{cx + 1, cy}, {cx - 1, cy}, {cx, cy + 1}, {cx, cy - 1}};
        for (const auto& [nx, ny] : next) {
          if (nx < x0 || nx >= x1 || ny < 0 || ny >= h || seen[ny * w + nx] || !wanted(nx, ny))
            continue;
          seen[ny * w + nx] = 1;
          stack.emplace_back(nx, ny);
        }
      }
      count += size >= smallest;
    }
  stbi_image_free(pixels);
  return count;
}

int silhouette_pieces(const fs::path& png) {
  return regions(png, true);
}
int holes_seen(const fs::path& png) {
  return regions(png, false) - 1;
}

fs::path frame(const fs::path& frames, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.png", k);
  return frames / name;
}

// Runs the viewer with `options`, one PNG per step in dir/run_frames; returns its output.
std::string record(const fs::path& dir, const std::string& options) {
  const test::XvfbRun run = test::run_under_xvfb(
      "env PATH=/nonexistent " +
          test::viewer_command("--fresh " + options + " --width " + std::to_string(kWidth) +
                               " --height " + std::to_string(kHeight) + " --record '" +
                               (dir / "run.mp4").string() + "'"),
      dir / "log.txt");
  EXPECT_EQ(run.status, 0) << run.output;
  return run.output;
}

int events_reported(const std::string& log) {
  int reported = 0;
  for (auto at = log.find("dynamesh: topology: "); at != std::string::npos;
       at = log.find("dynamesh: topology: ", at + 1))
    ++reported;
  return reported;
}

TEST(ViewerTopology, BlobsMergeAndSplitFramesRenderAndTheEventsAreReported) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_topology");
  // t = 0.1 .. 0.9 in 16 steps of 0.05: the merge (t = 0.1515) falls in step 2, the split
  // (t = 0.8485) in step 15; frame k shows step k. The camera looks down from above (-y), so
  // the blobs, apart along x, never hide each other.
  const std::string log =
      record(dir, "--scene blobs --t0 0.1 --t1 0.9 --steps 16 --frames 17 --camera 0,90");
  // Each event once, in its step, with its kind and how the mesh followed (repaired locally or
  // rebuilt: the engine's tests judge which; here, that the viewer says it).
  for (const char* event :
       {"dynamesh: topology: step 2 t=0.151", "dynamesh: topology: step 15 t=0.848"}) {
    const auto at = log.find(event);
    ASSERT_NE(at, std::string::npos) << event << " not reported:\n" << log;
    EXPECT_EQ(log.find(event, at + 1), std::string::npos) << event << " reported twice";
    const std::string line = log.substr(at, log.find('\n', at) - at);
    EXPECT_TRUE(line.find("repaired locally") != std::string::npos ||
                line.find("mesh rebuilt") != std::string::npos)
        << line;
  }
  EXPECT_NE(log.find("step 2 t=0.1515: merge near ("), std::string::npos) << log;
  EXPECT_NE(log.find("step 15 t=0.8485: split near ("), std::string::npos) << log;
  EXPECT_EQ(events_reported(log), 2) << "events reported that did not happen:\n" << log;

  // Just before, at (the first frame after the event instant) and after each event.
  const fs::path frames = dir / "run_frames";
  for (const int k : {0, 1, 15, 16})
    EXPECT_EQ(silhouette_pieces(frame(frames, k)), 2) << frame(frames, k) << ": two blobs expected";
  for (const int k : {2, 3, 8, 13, 14})
    EXPECT_EQ(silhouette_pieces(frame(frames, k)), 1)
        << frame(frames, k) << ": one merged blob expected";
}

TEST(ViewerTopology, TorusPinchFramesShowTheHoleCloseUpAndTheEventIsReported) {
  ASSERT_TRUE(test::on_path("xvfb-run")) << test::kXvfbMissing;
  const fs::path dir = test::render_scratch("viewer_topology_torus");
  // The torus pinch, t = 0.45, 0.5, 0.55, seen along the torus's axis (z): the hole
  // shows through before the pinch and opens to the outside after it.
  const std::string log =
      record(dir,
             "--scene expr --implicit '(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09 + "
             "0.18*t*exp(-((x-1)^2+y^2+z^2)/0.16)' --bounds -1.5,-1.5,-0.5,1.5,1.5,0.5 "
             "--t0 0.45 --t1 0.55 --steps 2 --frames 3 --camera 0,0");
  EXPECT_NE(log.find("dynamesh: topology: step 1 t=0.5000: split near (1.00, "), std::string::npos)
      << log;
  EXPECT_EQ(events_reported(log), 1) << log;
  const fs::path frames = dir / "run_frames";
  EXPECT_EQ(silhouette_pieces(frame(frames, 0)), 1);
  EXPECT_EQ(holes_seen(frame(frames, 0)), 1) << "the torus's hole, before the pinch";
  // t = 0.5 is the instant of the pinch (the tips touch in F): rendered, its hole not judged.
  EXPECT_EQ(silhouette_pieces(frame(frames, 1)), 1);
  EXPECT_EQ(silhouette_pieces(frame(frames, 2)), 1);
  EXPECT_EQ(holes_seen(frame(frames, 2)), 0) << "the bent tube has no hole";
}

}  // namespace
}  // namespace dynamesh
