// Opening scans in the viewer (issue 14), driven under Xvfb as a person would:
//   - the path field: xdotool clicks the mri scene's `volume` field, selects its text, types
//     a .nii path and presses Enter;
//   - drag and drop: tests/support/xdnd_drop drops a file or a folder on the window by the
//     XDND protocol, as a file manager does (xdotool cannot be a drag source); GLFW's own
//     X11 drop handling and the viewer's drop callback take it from there;
//   - a DICOM series folder (tests/support/make_dicom_series.py) dropped on the window is
//     converted with dcm2niix (core/io/dicom_series.h, as `--volume DIR`);
//   - a file that is no scan gives the red message and the previous scene stays;
//   - while a scan loads (on the worker), the window keeps drawing frames, with the loading
//     stage in the panel.
// What the viewer shows is read from its widget report (DYNAMESH_WIDGET_REPORT): the scene's
// volume, the mesh's bounds, the error message, the loading progress and the frames drawn.
// Each ball's layer at t = 0 is the ball's surface: its bounds say which scan is on screen.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_mri_ball.h"
#include "test_render_scratch.h"
#include "xvfb_run.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

std::string reported(const std::string& report, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(report, m, std::regex("(^|\n)" + key + " ([^\n]+)"))) return "";
  return m[2];
}

std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

// The mesh on screen is the surface of the ball of `radius` around `centre` (mm): its
// bounding box, to the voxel staircase and the blurs (1.5 mm).
void expect_ball(const std::string& report, const Vec3& centre, double radius, const char* what) {
  SCOPED_TRACE(what);
  const std::vector<double> b = numbers(reported(report, "bounds"));
  ASSERT_EQ(b.size(), 6u) << report;
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(0.5 * (b[a] + b[a + 3]), centre[a], 1.0) << report;
    EXPECT_NEAR(0.5 * (b[a + 3] - b[a]), radius, 1.5) << report;
  }
}

// A ball of `radius` mm around `centre` on an axis-aligned grid of 1 mm voxels, n^3, as an
// uncompressed .nii (large enough that loading it takes a visible moment).
fs::path write_big_ball(const fs::path& path, int n, const Vec3& centre, double radius) {
  VoxelGrid grid;
  grid.dims = {n, n, n};
  grid.linear = Mat3::Identity();
  grid.offset = centre - Vec3::Constant(0.5 * (n - 1));
  std::vector<std::int16_t> values;
  values.reserve(std::size_t(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        values.push_back((grid.to_world(Vec3(i, j, k)) - centre).norm() <= radius ? 90 : 0);
  nifti_1_header h = test::make_header({n, n, n}, DT_INT16, 16);
  test::set_sform(h, grid.linear, grid.offset);
  test::write_nifti(path, h, values);
  return path;
}

TEST(ViewerOpenScan, PathFieldDropAndDicomFolderLoadOnTheWorker) {
  const fs::path dir = test::render_scratch("viewer_open_scan");
  const fs::path report = dir / "report.txt";
  for (const char* old : {"series", "config"}) fs::remove_all(dir / old);
  fs::remove(report);
  // Ball A (the mri tests' oblique, anisotropic ball, .nii.gz): radius 20 at (4, -3, 10).
  const fs::path ball_a = test::write_ball_file("viewer_open_scan_a");
  // Ball B: radius 25 at (30, 20, -10), 1 mm voxels, 200^3 (at 120^3 a quiet machine loaded it
  // between two of the script's looks at the panel, and no frame was seen drawn while busy).
  const Vec3 centre_b(30, 20, -10);
  const fs::path ball_b = write_big_ball(dir / "ball_b.nii", 200, centre_b, 25.0);
  // The DICOM series: radius 30 at LPS (10, 20, 30) = RAS (-10, -20, 30).
  const std::string make_series = "/usr/bin/python3 '" + std::string(DYNAMESH_SOURCE_DIR) +
                                  "/tests/support/make_dicom_series.py' '" +
                                  (dir / "series").string() + "'";
  ASSERT_EQ(std::system(make_series.c_str()), 0) << make_series;
  {
    std::ofstream garbage(dir / "garbage.nii", std::ios::binary);
    for (int i = 0; i < 4000; ++i) garbage.put(static_cast<char>((i * 7919) % 251));
  }

  const fs::path script = dir / "open.sh";
  std::ofstream(script)
      << "cd '" << dir.string() << "'\n"
      << "report='" << report.string() << "'\n"
      << "export XDG_CONFIG_HOME='" << (dir / "config").string() << "'\n"
      << "DYNAMESH_WIDGET_REPORT=\"$report\" '" << DYNAMESH_VIEWER
      << "' --fresh --scene mri --volume '" << ball_a.string() << "' --width 1100 --height 760 &\n"
      << "pid=$!\n"
      << "val() { awk -v k=\"$1\" '$1==k {print $2}' \"$report\" 2>/dev/null; }\n"
      << "volume() { awk '$1==\"scene_text\" && $2==\"volume\" {print $3}' \"$report\"; }\n"
      // Waits (at most 120 s) until the report shows volume $1, more than $2 results, and an
      // idle worker; meanwhile copies each report to $3.N and moves the mouse over the 3D
      // view (input the window must answer while the scan loads).
      << "settle() {\n"
      << "  for i in $(seq 1200); do\n"
      << "    kill -0 $pid 2>/dev/null || return 1\n"
      << "    cp \"$report\" \"$3.$i\" 2>/dev/null\n"
      << "    xdotool mousemove --window $w $((600 + i % 40)) 400 2>/dev/null\n"
      << "    r=$(val results)\n"
      << "    [ \"$(volume)\" = \"$1\" ] && [ -n \"$r\" ] && [ \"$r\" -gt \"$2\" ] &&\n"
      << "      [ \"$(val busy)\" = 0 ] && [ -n \"$(val triangles)\" ] && return 0\n"
      << "    sleep 0.1\n"
      << "  done\n"
      << "  return 1\n"
      << "}\n"
      << "hold() { xdotool keydown $1; sleep 0.3; xdotool keyup $1; }\n"
      << "active() { [ \"$(awk '$1==\"active\" {print $2}' \"$report\")\" = volume ]; }\n"
      << "w=''\n"
      << "for i in $(seq 600); do [ -n \"$(val triangles)\" ] && [ \"$(val busy)\" = 0 ] && "
         "break; sleep 0.2; done\n"
      << "w=$(xdotool search --sync --name dynamesh | head -1)\n"
      << "xdotool windowfocus $w 2>/dev/null\n"
      << "cp \"$report\" \"$report.start\"\n"
      // The path field: click it until it takes typing, select all, type, Enter.
      << "set -- $(awk '$1==\"widget\" && $2==\"volume\" {print int(($3+$5)/2), "
         "int(($4+$6)/2)}' \"$report\")\n"
      << "[ -n \"$2\" ] || exit 3\n"
      << "for i in 1 2 3 4 5 6; do xdotool mousemove --window $w $1 $2 click 1; sleep 0.5; "
         "active && break; done\n"
      << "active || exit 4\n"
      << "xdotool keydown ctrl keydown a; sleep 0.3; xdotool keyup a keyup ctrl; sleep 0.3\n"
      << "r=$(val results)\n"
      << "xdotool type --delay 20 '" << ball_b.string() << "'\n"
      << "for i in $(seq 20); do hold Return; sleep 0.2; active || break; done\n"
      << "settle '" << ball_b.string() << "' $r \"$report.typing\" || exit 5\n"
      << "cp \"$report\" \"$report.typed\"\n"
      // A file that is no scan, dropped on the 3D view: the message, and ball B stays.
      << "r=$(val results)\n"
      << "'" << DYNAMESH_XDND_DROP << "' $w 700 380 '" << (dir / "garbage.nii").string()
      << "' || exit 6\n"
      << "for i in $(seq 600); do [ -n \"$(val open_error)\" ] && [ \"$(val busy)\" = 0 ] && "
         "[ \"$(val results)\" -gt $((r + 1)) ] && break; sleep 0.1; done\n"
      << "cp \"$report\" \"$report.bad\"\n"
      // The scene on screen still works: one step forward.
      << "set -- $(awk '$1==\"widget\" && $2==\"step_forward\" {print int(($3+$5)/2), "
         "int(($4+$6)/2)}' \"$report\")\n"
      << "[ -n \"$2\" ] || exit 11\n"
      << "r=$(val results)\n"
      << "for i in 1 2 3 4 5; do xdotool mousemove --window $w $1 $2 click 1; sleep 0.5; "
         "[ \"$(val results)\" -gt $r ] && break; done\n"
      << "for i in $(seq 600); do [ \"$(val busy)\" = 0 ] && [ \"$(val results)\" -gt $r ] && "
         "break; sleep 0.1; done\n"
      << "cp \"$report\" \"$report.stepped\"\n"
      // The DICOM series folder, dropped.
      << "r=$(val results)\n"
      << "'" << DYNAMESH_XDND_DROP << "' $w 700 380 '" << (dir / "series").string()
      << "' || exit 7\n"
      << "settle '" << (dir / "series").string() << "' $r \"$report.dicoming\" || exit 8\n"
      << "cp \"$report\" \"$report.dicom\"\n"
      // Ball A's .nii.gz, dropped.
      << "r=$(val results)\n"
      << "'" << DYNAMESH_XDND_DROP << "' $w 700 380 '" << ball_a.string() << "' || exit 9\n"
      << "settle '" << ball_a.string() << "' $r \"$report.gzing\" || exit 10\n"
      << "cp \"$report\" \"$report.gz\"\n"
      << "for i in $(seq 40); do kill -0 $pid 2>/dev/null || break; hold Escape; sleep 0.2; "
         "done\n"
      << "kill $pid 2>/dev/null; wait $pid\n";
  const test::XvfbRun run =
      test::run_script_under_xvfb(script, dir / "log.txt", {.screen = "1280x900x24"});
  ASSERT_EQ(run.status, 0) << run.output;
  const auto read = [&](const std::string& name) {
    return test::slurp_text(report.string() + "." + name);
  };
  const std::string start = read("start"), typed = read("typed"), bad = read("bad"),
                    stepped = read("stepped"), dicom = read("dicom"), gz = read("gz");
  expect_ball(start, test::kBallCentre, test::kBallRadius, "ball A from the command line");
  // Typed into the path field.
  EXPECT_EQ(reported(typed, "scene_text volume"), ball_b.string()) << typed;
  expect_ball(typed, centre_b, 25.0, "ball B typed into the path field");
  EXPECT_EQ(reported(typed, "error"), "") << typed;
  // The garbage file: a message naming it, and ball B's scene on screen, adapted again.
  const std::string error = reported(bad, "open_error");
  EXPECT_NE(error.find("cannot open " + (dir / "garbage.nii").string()), std::string::npos) << bad;
  EXPECT_NE(error.find("NIfTI"), std::string::npos) << bad;
  EXPECT_EQ(reported(bad, "scene_text volume"), ball_b.string()) << bad;
  EXPECT_EQ(reported(bad, "busy"), "0") << bad;
  expect_ball(bad, centre_b, 25.0, "ball B after the garbage file");
  EXPECT_EQ(reported(bad, "triangles"), reported(typed, "triangles")) << bad << typed;
  EXPECT_EQ(reported(bad, "error"), "") << bad;
  // ... and it still adapts: a step forward takes it deeper, with no error.
  EXPECT_EQ(reported(stepped, "step"), "1") << stepped;
  EXPECT_EQ(reported(stepped, "error"), "") << stepped;
  EXPECT_EQ(reported(stepped, "scene_text volume"), ball_b.string()) << stepped;
  // The DICOM folder, converted: the ball where the series puts it in RAS.
  EXPECT_EQ(reported(dicom, "scene_text volume"), (dir / "series").string()) << dicom;
  expect_ball(dicom, Vec3(-10, -20, 30), 30.0, "the DICOM series dropped");
  EXPECT_EQ(reported(dicom, "error"), "") << dicom;
  EXPECT_EQ(reported(dicom, "open_error"), "") << dicom;
  // The .nii.gz dropped.
  expect_ball(gz, test::kBallCentre, test::kBallRadius, "ball A's .nii.gz dropped");
  EXPECT_EQ(reported(gz, "error"), "") << gz;
  EXPECT_EQ(reported(gz, "open_error"), "") << gz;

  // While each scan loaded: the panel showed its stage, and frames went on being drawn.
  for (const char* loading : {"typing", "dicoming"}) {
    SCOPED_TRACE(loading);
    std::set<std::string> stages;
    std::set<double> busy_frames;
    for (int i = 1; i <= 1200; ++i) {
      const fs::path sample = report.string() + "." + loading + "." + std::to_string(i);
      if (!fs::exists(sample)) continue;
      const std::string r = test::slurp_text(sample);
      if (reported(r, "busy") != "1") continue;
      if (const std::string p = reported(r, "progress"); !p.empty())
        stages.insert(p.substr(0, p.rfind(' ')));
      busy_frames.insert(std::stod(reported(r, "frames")));
    }
    EXPECT_FALSE(stages.empty()) << "no loading stage seen while busy";
    EXPECT_GE(busy_frames.size(), 2u) << "no frame drawn while the scan loaded";
    std::string seen;
    for (const std::string& s : stages) seen += s + "; ";
    std::printf("%s: %zu distinct frame counts while loading; stages shown: %s\n", loading,
                busy_frames.size(), seen.c_str());
  }
}

}  // namespace
}  // namespace dynamesh
