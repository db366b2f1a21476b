// Hostile input through the real dynamesh-cli (issue 15): every reproduction of the campaign
// ends in exit status 2 with one line on stderr within 10 s, or succeeds within its budget.
// Each run is under `timeout`, so a hang fails the test instead of stalling CI. Hostile
// NIfTI files are made from a small synthetic volume (test_nifti_files.h).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "child_cpu_time.h"
#include "cli_runner.h"
#include "test_nifti_files.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

const std::string kCli = std::string(DYNAMESH_BINARY_DIR) + "/dynamesh-cli";
// The bar, on the CPU time the run takes (user + system, the child's threads
// included): on this shared 2-core machine the wall time of a 0.8 s CPU refusal reached 17.9 s
// under load. A hang still fails: it burns CPU past the bar, or is killed at kKillSeconds.
constexpr int kLimitSeconds = 10;
constexpr int kKillSeconds = 60;

struct Outcome {
  int status = -1;  // exit status; -1 when killed (a hang or a crash)
  std::string out, err;
  double seconds = 0;      // wall
  double cpu_seconds = 0;  // user + system
};

Outcome run(const std::vector<std::string>& args, int limit = kKillSeconds) {
  static const fs::path dir = test::scratch_dir("cli_hostile");
  const fs::path err = dir / "stderr.txt";
  std::ostringstream command;
  command << "timeout -s KILL " << limit << " " << kCli;
  for (const std::string& a : args) command << " " << test::shell_quoted(a);
  command << " 2>" << err.string();
  Outcome r;
  const double cpu_before = test::children_cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = ::popen(command.str().c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int raw = ::pclose(pipe);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpu_seconds =
      test::children_cpu_seconds() - cpu_before;  // pclose reaped the shell and its tree
  r.status = WIFEXITED(raw) && WEXITSTATUS(raw) != 137 ? WEXITSTATUS(raw) : -1;
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  r.err = s.str();
  return r;
}

// Exit 2, one line on stderr that contains `fragment`, nothing on stdout, within the limit.
void expect_refused(const std::vector<std::string>& args, const std::string& fragment) {
  std::string shown;
  for (const auto& a : args) shown += " " + (a.size() > 60 ? a.substr(0, 60) + "..." : a);
  const Outcome r = run(args);
  EXPECT_EQ(r.status, 2) << shown << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << shown << "\n" << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << shown << "\nstderr: " << r.err;
  EXPECT_TRUE(r.out.empty()) << shown << "\n" << r.out;
  EXPECT_LT(r.cpu_seconds, kLimitSeconds) << shown << " (" << r.seconds << " s wall)";
}

// The synthetic volume: a ball of radius 6 voxels in 16^3, int16, 1 mm voxels.
std::vector<std::int16_t> ball_values(int n = 16) {
  std::vector<std::int16_t> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double d = std::hypot(i - 7.5, j - 7.5, k - 7.5);
        v.push_back(static_cast<std::int16_t>(d < 6 ? 100 : 0));
      }
  return v;
}

nifti_1_header ball_header() {
  return test::make_header({16, 16, 16}, DT_INT16, 16);
}

std::string write_volume(const std::string& name, const nifti_1_header& h,
                         const std::vector<std::int16_t>& values = ball_values()) {
  static const fs::path dir = test::scratch_dir("cli_hostile_nifti");
  test::write_nifti(dir / name, h, values);
  return (dir / name).string();
}

std::vector<std::string> mri(const std::string& volume) {
  return {"run", "--scene", "mri", "--volume", volume, "--steps", "1", "--quiet"};
}

TEST(CliHostile, NiftiHeadersWithAbsurdPlacementsAreRefused) {
  nifti_1_header h = ball_header();
  h.pixdim[1] = 1e30f;
  expect_refused(mri(write_volume("pixdim1_1e+30.nii", h)), "outside [0.01, 100] mm");
  for (const short qform : {0, 1}) {
    h = ball_header();
    h.qform_code = qform;
    h.pixdim[1] = h.pixdim[2] = h.pixdim[3] = 1e30f;
    expect_refused(mri(write_volume(std::to_string(qform) + "_pixdim_all_.nii", h)),
                   "outside [0.01, 100] mm");
  }
  for (const int row : {0, 1, 2}) {
    h = ball_header();
    test::set_sform(h, Mat3::Identity(), Vec3::Zero());
    float* rows[3] = {h.srow_x, h.srow_y, h.srow_z};
    rows[row][row] = 1e30f;
    expect_refused(mri(write_volume(std::to_string(row) + "_srow_1e30_.nii", h)),
                   "outside [0.01, 100] mm");
  }
  for (const float size : {1e-5f, 1e6f}) {
    h = ball_header();
    h.pixdim[1] = h.pixdim[2] = h.pixdim[3] = size;
    expect_refused(mri(write_volume(std::to_string(size) + "_pixdim_.nii", h)),
                   "outside [0.01, 100] mm");
  }
  h = ball_header();
  Mat3 sliver = Mat3::Identity();
  sliver.col(2) = Vec3(1, 0, 1e-4);  // the third axis almost along the first: near singular
  test::set_sform(h, sliver, Vec3::Zero());
  expect_refused(mri(write_volume("singular.nii", h)), "singular or nearly so");
}

TEST(CliHostile, NiftiDataThatDoesNotMatchTheHeaderIsRefused) {
  // A 352-byte file claiming 1290^3 voxels; one claiming 600^3 float64 (1.7 GB).
  expect_refused(
      mri(write_volume("huge.nii", test::make_header({1290, 1290, 1290}, DT_INT16, 16), {})),
      "volume too large");
  expect_refused(
      mri(write_volume("f64.nii", test::make_header({600, 600, 600}, DT_FLOAT64, 64), {})),
      "truncated data");
  // dim1 = 32767 on a 16^3 volume's data.
  expect_refused(mri(write_volume("wide.nii", test::make_header({32767, 16, 16}, DT_INT16, 16))),
                 "truncated data");
  // A dimension smaller than the data.
  expect_refused(mri(write_volume("short.nii", test::make_header({16, 16, 15}, DT_INT16, 16))),
                 "trailing data");
  // gzip: a bad CRC, trailing garbage.
  const std::string gz = write_volume("ball.nii.gz", ball_header());
  std::string bytes;
  {
    std::ifstream in(gz, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const fs::path dir = fs::path(gz).parent_path();
  std::string crc = bytes;
  crc[crc.size() - 8] ^= 0x5a;
  test::write_text(dir / "crc.nii.gz", crc);
  expect_refused(mri((dir / "crc.nii.gz").string()), "incorrect data check");
  test::write_text(dir / "tail.nii.gz", bytes + "junk after the stream");
  expect_refused(mri((dir / "tail.nii.gz").string()), "trailing data");
}

std::vector<std::string> implicit(const std::string& formula,
                                  const std::string& bounds = "-1.5,-1.5,-1.5,1.5,1.5,1.5") {
  return {"run",      "--scene", "expr",    "--implicit", formula,
          "--bounds", bounds,    "--steps", "3",          "--quiet"};
}

std::vector<std::string> height(const std::string& formula) {
  return {"run", "--scene", "expr", "--height-field", formula, "--steps", "3", "--quiet"};
}

TEST(CliHostile, FormulasNoMeshCanFollowAreRefusedUpFront) {
  expect_refused(implicit("x<0 ? x^2+y^2+z^2-1 : x^2+y^2+z^2-0.5"), "jumps across zero");
  expect_refused(implicit("x^2+y^2+z^2-1+0.9*sin(3*atan2(y,x))"), "scene expr at t = ");
  // Star-shaped at t = 0; from t = 0.25 on it breaks into ripples no mesh placed on its
  // contour can follow (the contour folds over), refused before any work.
  expect_refused(implicit("x^2+y^2+z^2-1+t*sin(40*x)"), "folds over");
  expect_refused(implicit("x^2+y^2+z^2-1e12", "-2e6,-2e6,-2e6,2e6,2e6,2e6"), "triangles");
  for (const char* f : {"1e308*x", "tan(x*pi/2)", "exp(100*x)", "exp(700*x)", "sin(1000*x)"})
    expect_refused(height(f), "scene expr at t = ");
  // Variants (session 3): a pole, a formula 100,000 characters long (the message quoted all
  // of it: one line of 100 kB), a domain of +-1e300 (the message printed 300-digit numbers).
  expect_refused(implicit("x^2+y^2+z^2-1+0.01/x"), "is infinite at (0, -1.5, -1.5)");
  std::string longest = "x^2+y^2+z^2-1";
  for (int i = 0; i < 20000; ++i) longest += "+0*x";
  const Outcome r = run(implicit(longest));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 1000u);
  EXPECT_NE(r.err.find("characters left out"), std::string::npos) << r.err.substr(0, 300);
  expect_refused({"run", "--scene", "expr", "--height-field", "0", "--domain",
                  "-1e300,1e300,-1e300,1e300", "--quiet"},
                 "at (u, v) = (-9.79167e+299, -9.79167e+299)");
  // Found by fuzz_formula (a 10 s timeout allocating samples for a steep height field):
  // 1932 z^4 - 3 over the default domain.
  expect_refused(height("46*+42*+z^4-3"), "more than --max-triangles");
}

std::string write_mesh(const std::string& name, const std::string& text) {
  static const fs::path dir = test::scratch_dir("cli_hostile_mesh");
  test::write_text(dir / name, text);
  return (dir / name).string();
}

std::vector<std::string> with_base(const std::string& mesh) {
  std::vector<std::string> a = implicit("x^2+y^2+z^2-1");
  a.push_back("--base-mesh");
  a.push_back(mesh);
  return a;
}

const char* kTetraHeader =
    "format ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
const char* kTetraData = "-1 -1 -1\n1 1 -1\n1 -1 1\n-1 1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";

TEST(CliHostile, MeshFilesThatHangOrReadPartiallyAreRefused) {
  // An element without properties before `vertex` (hung), and the same with a huge count.
  expect_refused(with_base(write_mesh("noprop.ply", std::string("ply\nelement junk 5\n") +
                                                        kTetraHeader + kTetraData)),
                 "no properties");
  expect_refused(with_base(write_mesh("noprop_huge.ply",
                                      std::string("ply\nelement junk 9000000000000000000\n") +
                                          kTetraHeader + kTetraData)),
                 "no properties");
  // A face count smaller than the data, and one larger than the file can hold.
  std::string fewer = std::string("ply\n") + kTetraHeader + kTetraData;
  fewer.replace(fewer.find("face 4"), 6, "face 2");
  expect_refused(with_base(write_mesh("fewer.ply", fewer)), "data continues after");
  std::string more = std::string("ply\n") + kTetraHeader + kTetraData;
  more.replace(more.find("face 4"), 6, "face 400000");
  expect_refused(with_base(write_mesh("more.ply", more)), "more than the file");
  // OBJ: a truncated vertex line, a face with two corners.
  const std::string tetra_obj = "v -1 -1 -1\nv 1 1 -1\nv 1 -1 1\nv -1 1 1\n";
  expect_refused(with_base(write_mesh("cut.obj", tetra_obj + "f 1 2 3\nf 1 4 2\nv 1 2\n")),
                 "line 7: a vertex needs three numbers");
  expect_refused(with_base(write_mesh("two.obj", tetra_obj + "f 1 2 3\nf 1 4\n")),
                 "a face has 2 corners");
  // An open mesh (the tetrahedron less one face) as the base of a closed surface.
  expect_refused(with_base(write_mesh("open.obj", tetra_obj + "f 1 2 3\nf 1 4 2\nf 1 3 4\n")),
                 "edges are not shared by exactly two triangles");
}

TEST(CliHostile, NumbersThatWrapOrVanishAreRefused) {
  expect_refused({"run", "--steps", "4294967297"},
                 "--steps expects a whole number in [0, 10000000], got '4294967297'");
  expect_refused({"run", "--size", "4294967312x16"}, "--size expects a whole number in [16,");
  expect_refused({"run", "--width", "-4294967295"}, "--width expects a whole number in [16,");
  expect_refused({"run", "--smooth-iters", "2147483648"},
                 "--smooth-iters expects a whole number in [0, 1000]");
  for (const char* option :
       {"--stats", "--export", "--render", "--export-final", "--volume", "--scene", "--threshold"})
    expect_refused({"run", option, ""}, std::string(option) + " needs a value, got an empty");
  for (const char* bad : {"inf", "nan", "-inf", "1e400", "0x10", " 1", "1 "})
    expect_refused({"run", "--density", bad}, "--density expects a number");
  // A camera distance of 1e38 rendered a blank picture with exit 0 (session 4: the viewer's
  // saved state was checked, the shared --camera option was not).
  for (const char* far : {"0,0,1e38", "0,0,-5", "0,0,0"})
    expect_refused({"run", "--camera", far}, "--camera: the distance must be in [1e-4, 1e5]");
  // A newline in a name stays on the one line of the message.
  expect_refused({"run", "--scene", "mri\n"}, "mri\\n");
}

// Session 3's audit of the sphere's range: L = 0.001 (in [0.001, 10]) and --edge-length 0.001
// ran for ever towards 10^8-10^9 triangles (killed at 60-90 s); the edge-length demand is now
// part of the up-front estimate.
TEST(CliHostile, EdgeLengthsNoBudgetCanMeetAreRefused) {
  expect_refused({"run", "--scene", "sphere", "--param", "L=0.001", "--quiet"},
                 "edges of at most --param L 0.001 need at least about");
  expect_refused({"run", "--scene", "capsule-bend", "--edge-length", "0.001", "--quiet"},
                 "edges of at most --edge-length 0.001 need at least about");
}

TEST(CliHostile, HugeDensityIsRefusedByTheSampleBudget) {
  expect_refused({"run", "--scene", "sphere", "--density", "1e12"}, "--max-samples");
  expect_refused({"run", "--scene", "sphere", "--max-triangles", "100000000"}, "--max-memory");
}

TEST(CliHostile, TimeBudgetStopsTheRunAndIsReported) {
  // 2000 steps of the sinc scene take far longer than a second on any machine.
  const Outcome r =
      run({"run", "--scene", "sinc", "--steps", "2000", "--max-seconds", "1", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LT(r.seconds, 8.0);
  const nlohmann::json j = test::summary_json(r.out);
  EXPECT_TRUE(j["time_budget_hit"].get<bool>());
  EXPECT_LT(j["steps_done"].get<int>(), 2000);
  EXPECT_NE(r.err.find("the time budget (--max-seconds 1) stopped the run after"),
            std::string::npos)
      << r.err;
  // Without the budget the same run is not reported as stopped.
  const Outcome full = run({"run", "--scene", "sinc", "--steps", "2", "--quiet"});
  ASSERT_EQ(full.status, 0) << full.err;
  EXPECT_FALSE(test::summary_json(full.out)["time_budget_hit"].get<bool>());
  EXPECT_EQ(test::summary_json(full.out)["steps_done"].get<int>(), 2);
}

TEST(CliHostile, SampleBudgetStopsRefinementAndIsReported) {
  // At a low density every face holds its minimum of 9 samples, more than density * area:
  // the estimate up front passes, the running count reaches the budget.
  const Outcome r = run({"run", "--scene", "sphere", "--steps", "0", "--density", "10",
                         "--max-samples", "2000", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = test::summary_json(r.out);
  EXPECT_TRUE(j["sample_budget_hit"].get<bool>());
  // A split adds at most two faces' worth of samples (256 each) past the check.
  EXPECT_LE(j["samples"].get<double>(), 2000 + 4 * 256);
  EXPECT_NE(r.err.find("the sample budget (--max-samples 2000) stopped refinement"),
            std::string::npos)
      << r.err;
  const Outcome free =
      run({"run", "--scene", "sphere", "--steps", "0", "--density", "10", "--quiet"});
  ASSERT_EQ(free.status, 0) << free.err;
  EXPECT_FALSE(test::summary_json(free.out)["sample_budget_hit"].get<bool>());
  EXPECT_GT(test::summary_json(free.out)["samples"].get<double>(), 2000);
}

// In-range scene parameters that hung or gave garbage (sinc kappa = 10, twist r = 5, h = 0.05,
// turns = 10). The rule: every value in a documented range works, or the range is
// narrowed to what works. The ranges now end where a default run still works (the next test),
// so these values are refused at once with the range.
TEST(CliHostile, SceneParametersThatHungAreOutsideTheirRanges) {
  const auto param = [](const std::string& scene, const std::string& kv) {
    return std::vector<std::string>{"run", "--scene", scene, "--param", kv, "--quiet"};
  };
  expect_refused(param("sinc", "kappa=10"), "kappa = 10 is outside its range [-10, 2]");
  expect_refused(param("twist", "r=5"), "r = 5 is outside its range [0.01, 1]");
  expect_refused(param("twist", "h=0.05"), "h = 0.05 is outside its range [0.5, 5]");
  expect_refused(param("twist", "turns=10"), "turns = 10 is outside its range [-3, 3]");
}

// The hardest ends of the narrowed ranges (the most triangles and CPU when measured: 4-11 s of
// CPU for 50 steps) adapt the whole animation within T + eps, with no budget hit.
TEST(CliHostile, TheHardestEndsOfTheSceneRangesRun) {
  const std::vector<std::pair<std::string, std::string>> ends = {{"sinc", "kappa=2"},
                                                                 {"sinc", "alpha=2"},
                                                                 {"twist", "p=16"},
                                                                 {"twist", "turns=-3"},
                                                                 {"twist", "r=1"}};
  for (const auto& [scene, kv] : ends) {
    const Outcome r = run({"run", "--scene", scene, "--param", kv, "--steps", "5", "--quiet"}, 120);
    ASSERT_EQ(r.status, 0) << scene << " " << kv << "\n" << r.err;
    const nlohmann::json j = test::summary_json(r.out);
    EXPECT_LE(j["worst_max_sample_error"].get<double>(), 0.008 + 0.002) << scene << " " << kv;
    EXPECT_FALSE(j["budget_hit"].get<bool>()) << scene << " " << kv;
    EXPECT_FALSE(j["sample_budget_hit"].get<bool>()) << scene << " " << kv;
    EXPECT_EQ(j["steps_done"].get<int>(), 5) << scene << " " << kv;
  }
}

// Outputs that cannot be written are refused before the run, and a refused run leaves no
// directory behind: an existing directory given as --export-final or --stats (it used to fail
// with exit 1 after the whole run), a frame size the renderer cannot make (exit 1 and an empty
// directory), a workload refusal after --render made its directory.
TEST(CliHostile, OutputsThatCannotBeWrittenAreRefusedAndLeaveNothing) {
  const fs::path dir = test::scratch_dir("cli_hostile_outputs");
  fs::create_directories(dir / "final.ply");
  fs::create_directories(dir / "stats.csv");
  const std::vector<std::string> sphere = {"run", "--scene", "sphere", "--quiet"};
  auto with = [&sphere](std::vector<std::string> more) {
    more.insert(more.begin(), sphere.begin(), sphere.end());
    return more;
  };
  expect_refused(with({"--export-final", (dir / "final.ply").string()}), "Is a directory");
  expect_refused(with({"--stats", (dir / "stats.csv").string()}), "Is a directory");
  fs::remove_all(dir / "frames");
  expect_refused(
      with({"--steps", "1", "--render", (dir / "frames").string(), "--size", "16384x16384"}),
      "--size 16384x16384");
  EXPECT_FALSE(fs::exists(dir / "frames"));
  fs::remove_all(dir / "frames2");
  expect_refused(with({"--density", "1e12", "--render", (dir / "frames2").string()}),
                 "--max-samples");
  EXPECT_FALSE(fs::exists(dir / "frames2"));
}

// The soak's bar (issue 15): memory follows the mesh, so a run that grows and shrinks again
// ends near where it started, not at its peak. The default sphere goes from R = 0.6 to 9
// (39k triangles, 1.6M samples) and back: on the old code its resident memory at the end
// was 97% of the peak (the sample pool kept its largest buffers), here it is about 55%.
TEST(CliHostile, MemoryIsGivenBackWhenTheMeshShrinks) {
  const Outcome r =
      run({"run", "--scene", "sphere", "--keyframes", "0,1,0", "--steps", "20", "--quiet"}, 120);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = test::summary_json(r.out);
  ASSERT_GT(j["peak_triangles"].get<int>(), 20000);
  EXPECT_LT(j["triangles"].get<int>(), 2000);
  const double end = j["resident_mb"].get<double>(), peak = j["peak_resident_mb"].get<double>();
  EXPECT_GT(end, 0.0);
  EXPECT_LT(end, 0.7 * peak) << end << " MiB at the end, " << peak << " MiB at the peak";
}

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  return files;
}

// A run ended by a signal mid-way (`--render` and `--stats` open): no *.partial file stays,
// the frames that stay are whole PNGs and the CSV does not appear. SIGHUP (the terminal
// closed) and SIGPIPE (stdout's reader gone) left `s.csv.partial` and a `.png.partial`
// (session 4); SIGINT and SIGTERM did not. A signal ignored by the parent (nohup) stays
// ignored: the run goes on.
TEST(CliHostile, SignalsLeaveNoPartialFile) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, 0}) {
    const bool ignored = signal == 0;  // SIGHUP under nohup
    const int sent = ignored ? SIGHUP : signal;
    const fs::path dir = test::scratch_dir("cli_hostile_signal_" + std::to_string(signal));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path frames = dir / "frames", csv = dir / "s.csv";
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
        ::_exit(126);
      if (ignored) std::signal(SIGHUP, SIG_IGN);
      ::execl(kCli.c_str(), "dynamesh-cli", "run", "--scene", "sinc", "--threshold", "0.002",
              "--steps", "400", "--render", frames.c_str(), "--width", "160", "--height", "120",
              "--stats", csv.c_str(), nullptr);
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while ((!fs::exists(frames) || files_under(frames).size() < 2) &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(child, sent);
    int status = 0;
    if (ignored) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      EXPECT_EQ(::waitpid(child, &status, WNOHANG), 0) << "SIGHUP ended a run that ignores it";
      ::kill(child, SIGTERM);
    }
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == (ignored ? SIGTERM : sent))
        << "signal " << sent << ": status " << status;
    EXPECT_FALSE(fs::exists(csv)) << "signal " << sent;
    EXPECT_GE(files_under(dir).size(), 1u) << "signal " << sent;
    for (const fs::path& f : files_under(dir)) {
      EXPECT_EQ(f.extension(), ".png") << "signal " << sent << ": " << f;
      std::ifstream in(f, std::ios::binary);
      std::string magic(4, '\0');
      in.read(magic.data(), 4);
      EXPECT_EQ(magic, "\x89PNG") << f;
    }
  }
}

}  // namespace
}  // namespace dynamesh
