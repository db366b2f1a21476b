// The mri scene's inputs and parameters through dynamesh-cli:
// - A DICOM series folder (--volume DIR, converted with dcm2niix): a ball written slice by
//   slice by tests/support/make_dicom_series.py (pydicom) in DICOM's LPS patient space gives
//   a layer centred where the ball is in NIfTI's RAS space, with the ball's radius; folders
//   with no series or with two are refused in one line; no temporary file stays behind.
// - The `closing` parameter: a smaller closing keeps more of the sulci, so the layer of
//   Colin27 with closing=2 has more area and encloses less than with the default 5 mm
//   (T = 1 mm, to keep the test short).
//   A closing below 2 mm (0 included), whose layer self-intersects or runs into the
//   triangle budget, is refused in one line before the volume is loaded.
// - The memory and time budgets hold while the volume is preprocessed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>

#include "cli_runner.h"
#include "ply_reader.h"
#include "test_nifti_files.h"

namespace dynamesh {
namespace {

const std::filesystem::path kBrain = "/usr/share/mricron/templates/ch2bet.nii.gz";

void make_series(const std::filesystem::path& dir, const std::string& extra = "") {
  const std::string command = "/usr/bin/python3 " + std::string(DYNAMESH_SOURCE_DIR) +
                              "/tests/support/make_dicom_series.py " +
                              test::shell_quoted(dir.string()) + " " + extra;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// The CLI converts a DICOM folder in its temporary directory (TMPDIR). Each test that checks
// that no conversion stays behind gives the CLI a private one: /tmp is shared with the tests
// that ctest -j runs side by side, whose own conversions come and go while this one runs.
class PrivateTemporaryDirectory {
 public:
  explicit PrivateTemporaryDirectory(const std::filesystem::path& dir) : dir_(dir) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    if (const char* old = std::getenv("TMPDIR")) previous_ = old;
    setenv("TMPDIR", dir_.c_str(), 1);
  }
  ~PrivateTemporaryDirectory() {
    if (previous_)
      setenv("TMPDIR", previous_->c_str(), 1);
    else
      unsetenv("TMPDIR");
  }
  PrivateTemporaryDirectory(const PrivateTemporaryDirectory&) = delete;
  PrivateTemporaryDirectory& operator=(const PrivateTemporaryDirectory&) = delete;

  // DICOM conversions left in it.
  std::size_t conversions() const {
    std::size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir_))
      n += e.path().filename().string().rfind("dynamesh-dicom-", 0) == 0;
    return n;
  }

 private:
  std::filesystem::path dir_;
  std::optional<std::string> previous_;
};

std::size_t lines(const std::string& s) {
  return std::count(s.begin(), s.end(), '\n');
}

TEST(MriInputs, DicomSeriesFolderGivesTheBallWhereItIs) {
  const auto dir = test::scratch_dir("mri_dicom");
  std::filesystem::remove_all(dir / "series");
  // Ball of radius 30 mm at LPS (10, 20, 30) = RAS (-10, -20, 30); voxels 2 x 2 x 2.5 mm.
  make_series(dir / "series");
  const PrivateTemporaryDirectory tmp(dir / "tmp");
  const std::string mesh = (dir / "ball.ply").string();
  const test::CliRun run = test::run_cli({"--scene", "mri", "--volume", (dir / "series").string(),
                                          "--steps", "0", "--export-final", mesh, "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(tmp.conversions(), 0u);
  const test::PlyData ply = test::read_ply(mesh);
  ASSERT_GT(ply.vertices.size(), 100u);
  Vec3 centre = Vec3::Zero();
  for (const auto& v : ply.vertices) centre += Vec3(v[0], v[1], v[2]);
  centre /= static_cast<double>(ply.vertices.size());
  EXPECT_LT((centre - Vec3(-10.0, -20.0, 30.0)).norm(), 1.0) << centre.transpose();
  double min_r = 1e300, max_r = 0.0;
  for (const auto& v : ply.vertices) {
    const double r = (Vec3(v[0], v[1], v[2]) - Vec3(-10.0, -20.0, 30.0)).norm();
    min_r = std::min(min_r, r);
    max_r = std::max(max_r, r);
  }
  // The voxel staircase (2.5 mm slices) and the blurs keep the layer within ~1.5 mm of the
  // sphere; a series read in the wrong order or space would be off by centimetres.
  EXPECT_GT(min_r, 28.5);
  EXPECT_LT(max_r, 31.5);
}

TEST(MriInputs, DicomFolderWithoutOrWithTwoSeriesIsRefusedInOneLine) {
  const auto dir = test::scratch_dir("mri_dicom_bad");
  std::filesystem::remove_all(dir / "empty");
  std::filesystem::remove_all(dir / "two");
  std::filesystem::create_directories(dir / "empty");
  const PrivateTemporaryDirectory tmp(dir / "tmp");
  const test::CliRun none =
      test::run_cli({"--scene", "mri", "--volume", (dir / "empty").string(), "--quiet"});
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("no DICOM series"), std::string::npos) << none.err;
  EXPECT_EQ(lines(none.err), 1u) << none.err;
  make_series(dir / "two", "--prefix A");
  make_series(dir / "two", "--prefix B --radius 25");
  const test::CliRun two =
      test::run_cli({"--scene", "mri", "--volume", (dir / "two").string(), "--quiet"});
  EXPECT_EQ(two.status, 2);
  EXPECT_NE(two.err.find("holds 2 DICOM series"), std::string::npos) << two.err;
  EXPECT_EQ(lines(two.err), 1u) << two.err;
  EXPECT_EQ(tmp.conversions(), 0u);
}

test::PlyMeasure layer(const std::string& name, const test::Args& extra) {
  using test::operator+;
  const auto dir = test::cli_scratch("mri_inputs");
  const std::string mesh = (dir / (name + ".ply")).string();
  const test::CliRun run =
      test::run_cli(test::Args{"--scene", "mri", "--steps", "0", "--threshold", "1",
                               "--max-triangles", "200000", "--export-final", mesh, "--quiet"} +
                    extra);
  EXPECT_EQ(run.status, 0) << name << ": " << run.err;
  if (run.status != 0) return {};
  EXPECT_EQ(run.json["budget_hit"], false) << name;
  EXPECT_LE(run["max_sample_error"], 1.0 * 1.25 * 1.1) << name;  // T + eps (T = 1 mm, eps T/4)
  return test::measure_ply(test::read_ply(mesh));
}

TEST(MriInputs, SmallerClosingKeepsMoreOfTheSulci) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  const test::PlyMeasure closed = layer("closing_default", {});
  const test::PlyMeasure open = layer("closing_2", {"--param", "closing=2"});
  // Following the sulci: more area, less volume (the sulci are no longer filled).
  // (Measured: +3.3% area, -1.4% volume.)
  EXPECT_GT(open.area, 1.02 * closed.area) << open.area << " vs " << closed.area;
  EXPECT_LT(open.volume, closed.volume) << open.volume << " vs " << closed.volume;
  RecordProperty("area_ratio", std::to_string(open.area / closed.area));
  RecordProperty("volume_ratio", std::to_string(open.volume / closed.volume));
  // Out of range: one line with the range.
  const test::CliRun bad = test::run_cli({"--scene", "mri", "--param", "closing=-1", "--quiet"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("closing"), std::string::npos) << bad.err;
  EXPECT_EQ(lines(bad.err), 1u) << bad.err;
}

// A closing below 2 mm leaves slits the refinement cannot follow (kMinClosingMm: 1 mm gave a
// self-intersecting layer, 0.5 mm and 0 ran into the triangle budget): such a value exits 2
// with one line giving the range and why, before the volume is loaded (within seconds).
TEST(MriInputs, ClosingBelowTwoMillimetresIsRefusedBeforeLoading) {
  for (const std::string value : {"0", "1", "1.99"}) {
    const auto start = std::chrono::steady_clock::now();
    const test::CliRun bad =
        test::run_cli({"--scene", "mri", "--param", "closing=" + value, "--steps", "0", "--quiet"});
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(bad.status, 2) << value;
    EXPECT_NE(bad.err.find("closing = " + value + " is outside its range [2, 20]"),
              std::string::npos)
        << bad.err;
    EXPECT_NE(bad.err.find("refinement cannot follow"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("give 2 to keep the most sulci"), std::string::npos) << bad.err;
    EXPECT_EQ(lines(bad.err), 1u) << bad.err;
    EXPECT_LT(elapsed, 5.0) << value << ": the volume was loaded before refusing";
  }
}

// --max-memory and --max-seconds bound the preprocessing: refused in one line, before the
// work (memory) or at the first progress report past the deadline (time).
TEST(MriInputs, BudgetsBoundThePreprocessing) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  const test::CliRun memory =
      test::run_cli({"--scene", "mri", "--max-memory", "100", "--steps", "0", "--quiet"});
  EXPECT_EQ(memory.status, 2);
  EXPECT_NE(memory.err.find("--max-memory 100"), std::string::npos) << memory.err;
  EXPECT_NE(memory.err.find("181x217x181 voxels needs about"), std::string::npos) << memory.err;
  EXPECT_EQ(lines(memory.err), 1u) << memory.err;
  const auto start = std::chrono::steady_clock::now();
  const test::CliRun time =
      test::run_cli({"--scene", "mri", "--max-seconds", "0.5", "--steps", "0", "--quiet"});
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(time.status, 2);
  EXPECT_NE(time.err.find("--max-seconds 0.5) ran out while loading"), std::string::npos)
      << time.err;
  EXPECT_EQ(lines(time.err), 1u) << time.err;
  EXPECT_LT(elapsed, 10.0);
  // Within budget the same run succeeds and reports its preparation time.
  const test::CliRun ok = test::run_cli({"--scene", "mri", "--max-memory", "1000",
                                         "--max-triangles", "100000", "--steps", "0", "--quiet"});
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_GT(ok["preparation_seconds"], 0.0);
}

}  // namespace
}  // namespace dynamesh
