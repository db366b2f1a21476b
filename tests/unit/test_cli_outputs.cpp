// What dynamesh-cli leaves on disk (issue 12): `--stats -` and /dev/stdout are written in
// place (the device node stays), a FIFO stays a FIFO, a run whose formula turns bad part way
// removes every file it wrote, Ctrl-C / SIGTERM leaves no partial file, and --export writes
// a ParaView collection naming its frames with their times, which VTK itself reads.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <thread>

#include "cli_runner.h"
#include "ply_reader.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::run_cli;

int count_lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  std::size_t at = 0;
  while (at < text.size()) {
    if (text.compare(at, prefix.size(), prefix) == 0) ++n;
    at = text.find('\n', at);
    if (at == std::string::npos) break;
    ++at;
  }
  return n;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> found;
  if (fs::exists(dir))
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (!e.is_directory()) found.push_back(e.path());
  return found;
}

TEST(CliOutputs, StatsDashWritesTheCsvToStdout) {
  const CliRun r = run_cli({"--scene", "sinc", "--steps", "3", "--quiet", "--stats", "-"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("step,time,triangles", 0), 0u) << r.out;
  EXPECT_EQ(count_lines_starting(r.out, "step,"), 1);
  // Rows 0..3, then the JSON summary as the last line.
  for (const char* row : {"0,", "1,", "2,", "3,"}) EXPECT_EQ(count_lines_starting(r.out, row), 1);
  EXPECT_EQ(r.json["steps"].get<int>(), 3);
  EXPECT_FALSE(fs::exists("-"));
}

TEST(CliOutputs, DevStdoutStaysWhatItIs) {
  const auto before = fs::symlink_status("/dev/stdout").type();
  ASSERT_TRUE(before == fs::file_type::symlink || before == fs::file_type::character);
  const CliRun r =
      run_cli({"--scene", "sinc", "--steps", "2", "--quiet", "--stats", "/dev/stdout"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(fs::symlink_status("/dev/stdout").type(), before);
  EXPECT_FALSE(fs::exists("/dev/stdout.partial"));
  // The CSV went through the shell's redirection of stdout, before the JSON line.
  EXPECT_EQ(r.out.rfind("step,time,triangles", 0), 0u) << r.out;
  EXPECT_EQ(count_lines_starting(r.out, "2,"), 1) << r.out;
  EXPECT_FALSE(r.json.is_null());
}

TEST(CliOutputs, FifoStaysAFifoAndRegularFilesAreAtomic) {
  const fs::path dir = test::cli_scratch("fifo");
  const fs::path fifo = dir / "stats.fifo", copy = dir / "copy.csv";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A reader on the other end, as a user's `tail -f` or pipeline would be.
  std::thread reader([&] {
    // (timeout: a run that failed before opening the FIFO must not hang the test)
    std::system(("timeout 120 cat " + test::shell_quoted(fifo.string()) + " > " +
                 test::shell_quoted(copy.string()))
                    .c_str());
  });
  const CliRun r =
      run_cli({"--scene", "sinc", "--steps", "2", "--quiet", "--stats", fifo.string()});
  reader.join();
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(test::slurp_file(copy).rfind("step,time,triangles", 0), 0u);
  // A regular file: complete under its name, nothing beside it.
  const fs::path csv = dir / "stats.csv";
  ASSERT_EQ(run_cli({"--scene", "sinc", "--steps", "2", "--quiet", "--stats", csv.string()}).status,
            0);
  EXPECT_EQ(count_lines_starting(test::slurp_file(csv), "2,"), 1);
  EXPECT_FALSE(fs::exists(csv.string() + ".partial"));
  // A symbolic link to a regular file stays a link; its target gets the rows.
  const fs::path target = dir / "target.csv", link = dir / "link.csv";
  fs::remove(link);
  { std::ofstream(target) << "old\n"; }
  fs::create_symlink(target, link);
  ASSERT_EQ(
      run_cli({"--scene", "sinc", "--steps", "1", "--quiet", "--stats", link.string()}).status, 0);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(test::slurp_file(target).rfind("step,", 0), 0u);
}

TEST(CliOutputs, AFormulaThatTurnsBadLeavesNoFileBehind) {
  const fs::path dir = test::cli_scratch("turns_bad");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path frames = dir / "frames", meshes = dir / "meshes", csv = dir / "s.csv";
  // NaN only for t in (0.29, 0.31), which building the surface does not sample: steps 0..2
  // (t = 0, 0.1, 0.2) are written before step 3 (t = 0.3) fails.
  const CliRun r = run_cli({"--scene",        "expr",
                            "--implicit",     "x^2+y^2+z^2-1+0*sqrt(abs(t-0.3)-0.01)",
                            "--bounds",       "-2,-2,-2,2,2,2",
                            "--threshold",    "0.05",
                            "--steps",        "10",
                            "--render",       frames.string(),
                            "--width",        "64",
                            "--height",       "64",
                            "--export",       meshes.string(),
                            "--stats",        csv.string(),
                            "--export-final", (dir / "final.ply").string(),
                            "--quiet"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is NaN at (-2, -2, -2), t = 0.3"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in(dir).empty())
      << files_in(dir).size() << " files, e.g. " << files_in(dir).front();
}

TEST(CliOutputs, ExportWritesAParaViewCollection) {
  const fs::path dir = test::cli_scratch("pvd") / "meshes";
  fs::remove_all(dir);
  const CliRun r = run_cli({"--scene", "sinc", "--steps", "4", "--t0", "0.1", "--t1", "0.3",
                            "--export", dir.string(), "--export-every", "2", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string pvd = test::slurp_file(dir / "frames.pvd");
  // One DataSet per exported step (0, 2, 4), in order, with its time and an existing file.
  const std::regex dataset("<DataSet timestep=\"([0-9.e-]+)\"[^>]*file=\"([^\"]+)\"");
  std::vector<std::pair<double, std::string>> sets;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it)
    sets.emplace_back(std::stod((*it)[1]), (*it)[2]);
  ASSERT_EQ(sets.size(), 3u) << pvd;
  const double times[] = {0.1, 0.2, 0.3};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(sets[i].first, times[i], 1e-9);
    const std::string vtp = test::slurp_file(dir / sets[i].second);
    EXPECT_NE(vtp.find("<VTKFile type=\"PolyData\""), std::string::npos) << sets[i].second;
    EXPECT_NE(vtp.find("Name=\"error\""), std::string::npos);
  }
  // The last frame holds the mesh the JSON describes.
  const std::string last = test::slurp_file(dir / sets[2].second);
  EXPECT_NE(last.find("NumberOfPolys=\"" + std::to_string(r.json["triangles"].get<long>())),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "frame_00004.ply"));
}

TEST(CliOutputs, ExportCollectionReadsInVtk) {
  // An independent reader: VTK's own vtkXMLPolyDataReader (python3-vtk9) reads every frame the
  // .pvd names (tests/support/read_paraview_collection.py; VTK has no .pvd reader, ParaView's
  // is not part of it, so the collection is parsed with Python's XML parser). What it reads
  // must be the run: the PLY twin of each frame (read by this test's own PLY reader) and the
  // JSON's counts.
  const fs::path dir = test::cli_scratch("pvd_vtk") / "meshes";
  fs::remove_all(dir);
  const CliRun r =
      run_cli({"--scene", "sinc", "--steps", "4", "--t0", "0.1", "--t1", "0.3", "--export",
               dir.string(), "--export-every", "2", "--color", "error", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const fs::path out = dir.parent_path() / "vtk.json", err = dir.parent_path() / "vtk.err";
  const std::string command = "/usr/bin/python3 " +
                              test::shell_quoted(std::string(DYNAMESH_SOURCE_DIR) +
                                                 "/tests/support/read_paraview_collection.py") +
                              " " + test::shell_quoted((dir / "frames.pvd").string()) + " > " +
                              test::shell_quoted(out.string()) + " 2> " +
                              test::shell_quoted(err.string());
  ASSERT_EQ(std::system(command.c_str()), 0) << test::slurp_file(err);
  const nlohmann::json vtk = nlohmann::json::parse(test::slurp_file(out));
  const nlohmann::json& frames = vtk["frames"];
  ASSERT_EQ(frames.size(), 3u) << vtk;
  const double times[] = {0.1, 0.2, 0.3};
  const char* plys[] = {"frame_00000.ply", "frame_00002.ply", "frame_00004.ply"};
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(plys[i]);
    const nlohmann::json& f = frames[i];
    EXPECT_NEAR(f["time"].get<double>(), times[i], 1e-9);
    EXPECT_TRUE(f["triangles_only"].get<bool>());
    const test::PlyData ply = test::read_ply((dir / plys[i]).string());
    EXPECT_EQ(f["points"].get<std::size_t>(), ply.vertices.size());
    EXPECT_EQ(f["polys"].get<std::size_t>(), ply.faces.size());
    // The same points: the bounding boxes agree (both are float32 copies of one mesh).
    for (int axis = 0; axis < 3; ++axis) {
      const int c = test::ply_column(ply, std::string(1, char('x' + axis)));
      ASSERT_GE(c, 0);
      double lo = 1e300, hi = -1e300;
      for (const auto& v : ply.vertices) lo = std::min(lo, v[c]), hi = std::max(hi, v[c]);
      EXPECT_NEAR(f["bounds"][2 * axis].get<double>(), lo, 1e-6);
      EXPECT_NEAR(f["bounds"][2 * axis + 1].get<double>(), hi, 1e-6);
    }
    // The error field: the PLY's per-vertex error, within the hysteresis band's top (sinc:
    // T + eps = 0.01), not all zero; unit normals.
    const int e = test::ply_column(ply, "error");
    ASSERT_GE(e, 0);
    double lo = 1e300, hi = -1e300;
    for (const auto& v : ply.vertices) lo = std::min(lo, v[e]), hi = std::max(hi, v[e]);
    const nlohmann::json& error = f["arrays"]["error"];
    EXPECT_EQ(error[0].get<int>(), 1);
    EXPECT_NEAR(error[1].get<double>(), lo, 1e-7);
    EXPECT_NEAR(error[2].get<double>(), hi, 1e-7);
    EXPECT_GE(error[1].get<double>(), 0.0);
    EXPECT_LE(error[2].get<double>(), 0.01 + 1e-6);
    EXPECT_GT(error[2].get<double>(), 0.002);
    const nlohmann::json& normals = f["arrays"]["normals"];
    EXPECT_EQ(normals[0].get<int>(), 3);
    EXPECT_NEAR(normals[1].get<double>(), 1.0, 1e-5);
    EXPECT_NEAR(normals[2].get<double>(), 1.0, 1e-5);
  }
  // The last frame is the mesh the JSON describes.
  EXPECT_EQ(frames[2]["polys"].get<double>(), r["triangles"]);
  EXPECT_EQ(frames[2]["points"].get<double>(), r["vertices"]);
}

}  // namespace
}  // namespace dynamesh
