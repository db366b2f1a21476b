// End-to-end tests of dynamesh-cli: every bad input gives exit status 2, one line on stderr
// and no output file; a good run's closing JSON parses and agrees with its CSV and files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "stats_table.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

const std::string kCli = std::string(DYNAMESH_BINARY_DIR) + "/dynamesh-cli";

struct Result {
  int status = -1;
  std::string out, err;
};

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("dynamesh_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Result run_cli(const std::string& args) {
  const fs::path err = scratch() / "stderr.txt";
  Result r;
  FILE* pipe = ::popen((kCli + " " + args + " 2>" + err.string()).c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int raw = ::pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.err = slurp(err);
  return r;
}

long count_lines(const std::string& s) {
  return std::count(s.begin(), s.end(), '\n');
}

TEST(Cli, BinaryIsBuilt) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
}

TEST(Cli, BadInputIsOneLineAndExitTwo) {
  const fs::path dir = scratch();
  const std::string stats = (dir / "bad.csv").string();
  const char* cases[] = {
      "run --scene cube",
      "run --scene sphere --param R9=1",
      "run --scene sphere --param R0=-5",
      "run --scene sphere --param R0",
      "run --threshold 0",
      "run --threshold -1",
      "run --threshold abc",
      "run --epsilon -0.001",
      "run --threshold 0.01 --epsilon 0.01",
      "run --density 0",
      "run --steps -1",
      "run --steps 2.5",
      "run --t0 1.5",
      "run --max-triangles 1",
      "run --color rainbow",
      "run --width 0",
      "run --frobnicate",
      "run --threshold",
      "run --export-final /nonexistent-dir/x.ply",
      "run --export-final out.stl",
      "run --stats /nonexistent-dir/x.csv",
      "run --export /proc/forbidden",
      "run --scene sinc --color intensity",
      "run --sampling sometimes",
      "frobnicate",
  };
  for (const char* c : cases) {
    // Every case also asks for a CSV (unless it names its own), which must not be left behind.
    const bool own_stats = std::string(c).find("--stats") != std::string::npos;
    const Result r = run_cli(own_stats ? std::string(c) : std::string(c) + " --stats " + stats);
    EXPECT_EQ(r.status, 2) << c << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << c << ": stderr was\n" << r.err;
    EXPECT_EQ(r.err.rfind("dynamesh-cli: ", 0), 0u) << c << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << c;
    EXPECT_FALSE(fs::exists(stats)) << c;
    EXPECT_FALSE(fs::exists(stats + ".partial")) << c;
  }
}

TEST(Cli, HelpTeaches) {
  const Result main_help = run_cli("--help");
  EXPECT_EQ(main_help.status, 0);
  EXPECT_NE(main_help.out.find("dynamesh-cli run"), std::string::npos);
  const Result run_help = run_cli("run --help");
  EXPECT_EQ(run_help.status, 0);
  for (const char* option :
       {"--scene", "--param", "--threshold", "--epsilon", "--density", "--steps", "--stats",
        "--export-final", "--render", "--k", "--sampling", "--renumber"})
    EXPECT_NE(run_help.out.find(option), std::string::npos) << option;
  const Result scenes = run_cli("scenes");
  EXPECT_EQ(scenes.status, 0);
  for (const char* scene : {"sphere", "capsule-bend", "sinc", "twist"})
    EXPECT_NE(scenes.out.find(scene), std::string::npos) << scene;
}

TEST(Cli, GoodRunJsonMatchesCsvAndFiles) {
  const fs::path dir = scratch();
  const fs::path csv = dir / "stats.csv", ply = dir / "final.ply", frames = dir / "frames";
  const Result r = run_cli(
      "run --scene sinc --steps 6 --t0 0.1 --t1 0.3 --export-every 3 --stats " + csv.string() +
      " --export-final " + ply.string() + " --export " + (dir / "meshes").string() + " --render " +
      frames.string() + " --width 320 --height 240 --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string last_line = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  const auto json = nlohmann::json::parse(r.out.substr(r.out.find('{')));
  for (const char* key :
       {"triangles", "vertices", "max_sample_error", "mean_sample_error", "splits", "welds",
        "seconds_per_step", "valence_min", "valence_max", "min_angle_deg"})
    EXPECT_TRUE(json.contains(key)) << key;

  const test::StatsTable stats(csv);
  ASSERT_EQ(stats.rows(), 7u);  // step 0 (initialisation) and 6 steps
  auto cell = [&](const std::string& name) { return stats.number(6, name); };
  EXPECT_EQ(json["triangles"].get<double>(), cell("triangles"));
  EXPECT_EQ(json["vertices"].get<double>(), cell("vertices"));
  EXPECT_EQ(json["splits"].get<double>(), cell("total_splits"));
  EXPECT_EQ(json["welds"].get<double>(), cell("total_welds"));
  EXPECT_NEAR(json["max_sample_error"].get<double>(), cell("max_error"), 1e-9);
  EXPECT_NEAR(json["mean_sample_error"].get<double>(), cell("mean_error"), 1e-9);
  EXPECT_LE(json["max_sample_error"].get<double>(), 0.008 * 1.25 + 1e-12);  // T + eps

  // The final PLY holds exactly the mesh the JSON describes.
  const std::string head = slurp(ply).substr(0, 400);
  EXPECT_NE(head.find("element vertex " + std::to_string(json["vertices"].get<long>())),
            std::string::npos);
  EXPECT_NE(head.find("element face " + std::to_string(json["triangles"].get<long>())),
            std::string::npos);
  // Steps 0, 3, 6 exported and rendered; each PNG has the requested size.
  for (const char* step : {"00000", "00003", "00006"}) {
    EXPECT_TRUE(fs::exists(dir / "meshes" / (std::string("frame_") + step + ".ply"))) << step;
    const std::string png = slurp(frames / (std::string("frame_") + step + ".png"));
    ASSERT_GT(png.size(), 24u) << step;
    EXPECT_EQ(png.substr(1, 3), "PNG");
    auto be32 = [&](std::size_t at) {
      return (static_cast<unsigned char>(png[at]) << 24) |
             (static_cast<unsigned char>(png[at + 1]) << 16) |
             (static_cast<unsigned char>(png[at + 2]) << 8) |
             static_cast<unsigned char>(png[at + 3]);
    };
    EXPECT_EQ(be32(16), 320u);
    EXPECT_EQ(be32(20), 240u);
  }
  EXPECT_FALSE(last_line.empty());
  fs::remove_all(dir);
}

// --sampling: full measures every face every step; predictive (the default) measures far
// fewer on a smooth animation, within the same error bound.
TEST(Cli, SamplingOptionChoosesWhatIsMeasured) {
  const fs::path dir = scratch();
  auto measured_share = [&](const std::string& mode) {
    const fs::path csv = dir / (mode + ".csv");
    const Result r =
        run_cli("run --scene twist --threshold 0.004 --t0 0.3 --t1 0.34 --steps 8 " +
                (mode.empty() ? "" : "--sampling " + mode) + " --quiet --stats " + csv.string());
    EXPECT_EQ(r.status, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out.substr(r.out.find('{')));
    EXPECT_LE(json["max_sample_error"].get<double>(), 0.005 + 1e-12) << mode;  // T + eps
    // Each step measures the faces of the mesh the previous step left; row 0, the initial
    // adaptation, measures everything.
    const test::StatsTable stats(csv);
    EXPECT_EQ(stats.rows(), 9u) << mode;
    double measured = 0, faces = 0;
    for (std::size_t k = 1; k < stats.rows(); ++k) {
      measured += stats.number(k, "faces_measured");
      faces += stats.number(k - 1, "triangles");
    }
    return measured / faces;
  };
  EXPECT_EQ(measured_share("full"), 1.0);
  const double predictive = measured_share("predictive");
  EXPECT_LT(predictive, 0.5);
  EXPECT_EQ(measured_share(""), predictive);  // the default
  fs::remove_all(dir);
}

// --renumber: on renumbers the mesh along a Morton curve whenever its numbering has
// scattered (the CSV's `renumbered`), off never. The renumbering happens at the end of a
// step, after everything but the step's statistics: up to the first renumbered step both runs
// are the same computation, so that step's survival statistics (vertices kept, their
// displacement since the step's start), which the on run counts through the renumbering,
// must be the off run's exactly (the mean up to the order of its sum). Afterwards the runs
// differ by rounding only (sums over a vertex's faces in another order). And whatever the
// numbering, a step that welded nothing keeps every vertex it started with.
TEST(Cli, RenumberOptionKeepsSurvivalCounted) {
  const fs::path dir = scratch();
  auto run = [&](const std::string& mode) {
    const fs::path csv = dir / ("renumber_" + mode + ".csv");
    // The growing sphere: thousands of splits per step scatter the numbering quickly.
    const Result r = run_cli("run --scene sphere --threshold 0.002 --steps 10 --renumber " + mode +
                             " --quiet --stats " + csv.string());
    EXPECT_EQ(r.status, 0) << r.err;
    return test::StatsTable(csv);
  };
  const test::StatsTable on = run("on"), off = run("off");
  ASSERT_EQ(on.rows(), 11u);
  ASSERT_EQ(off.rows(), 11u);
  std::size_t first = 0;  // the first renumbered step
  int renumbered = 0;
  for (std::size_t k = 0; k < on.rows(); ++k) {
    EXPECT_EQ(off.number(k, "renumbered"), 0) << k;
    renumbered += on.number(k, "renumbered") == 1;
    if (first == 0 && on.number(k, "renumbered") == 1) first = k;
    if (k > 0 && on.number(k, "welds") == 0) {
      EXPECT_EQ(on.number(k, "vertices_kept"), on.number(k - 1, "vertices")) << k;
    }
  }
  ASSERT_GE(first, 1u);
  EXPECT_GE(renumbered, 2);
  for (std::size_t k = 1; k <= first; ++k) {
    for (const char* exact : {"triangles", "vertices", "splits", "welds", "vertices_kept",
                              "kept_fraction", "survivor_displacement_max", "max_error"})
      EXPECT_EQ(on.cell(k, exact), off.cell(k, exact)) << exact << ", step " << k;
    EXPECT_NEAR(on.number(k, "survivor_displacement_mean"),
                off.number(k, "survivor_displacement_mean"),
                1e-9 * off.number(k, "survivor_displacement_mean"))
        << k;
  }
  for (std::size_t k = first + 1; k < on.rows(); ++k) {
    EXPECT_NEAR(on.number(k, "triangles"), off.number(k, "triangles"),
                0.02 * off.number(k, "triangles"));
    EXPECT_NEAR(on.number(k, "kept_fraction"), off.number(k, "kept_fraction"), 0.02);
    EXPECT_NEAR(on.number(k, "survivor_displacement_mean"),
                off.number(k, "survivor_displacement_mean"),
                0.02 * off.number(k, "survivor_displacement_mean"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dynamesh
