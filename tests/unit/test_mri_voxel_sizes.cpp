// The mri scene through dynamesh-cli on real scans (Colin27 from mricron-data; skipped when
// it is not installed):
// - Any sane voxel size: Colin27's ch2bet with its header rewritten (pixdim and sform, or a
//   rotated sform) gives a closed, embedded layer (the exact judge, mesh_validity.h) whose
//   area is the 1 mm layer's times the squared voxel-size ratio, within 10%. The default
//   suite runs 2 mm (which refined without end until the closing was sized to the brain,
//   SegmentationOptions::closing_reference_ml) and a 35-degree oblique sform at 1.1 mm
//   (which refined without end before the cuberille and opening fixes); the other variants
//   of the issue are measured in /work/notes/issue-14-core.md.
// - Header flips (a negative sform axis, negative pixdims under an sform, a qform-only
//   header with qfac -1) over voxels stored in the matching reversed order give the same
//   brain in the same place; anisotropic 1 x 1 x 3 mm voxels give the layer of the brain
//   stretched 3x along z (T = 1 mm in these two tests, to keep them short).
// - A head with its skull (ch2) gives the skull-stripped brain's (ch2bet) layer through the
//   built-in brain extraction.
// - A scan that is not a brain fails fast: a random volume and a head whose brain was
//   removed exit 2 within seconds with one line naming --mask.
// - --mask: a mask made from ch2bet, used with the head ch2, gives ch2bet's layer.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "child_cpu_time.h"
#include "cli_runner.h"
#include "ply_reader.h"
#include "test_nifti_files.h"
#include "tests/support/mesh_validity.h"

namespace dynamesh {
namespace {

const std::filesystem::path kTemplates = "/usr/share/mricron/templates";
const std::filesystem::path kBrain = kTemplates / "ch2bet.nii.gz";
const std::filesystem::path kHead = kTemplates / "ch2.nii.gz";

struct Nifti {
  nifti_1_header header;
  std::vector<char> data;
};

Nifti read_whole(const std::filesystem::path& path) {
  znzFile f = znzopen(path.c_str(), "rb", 1);
  Nifti n;
  EXPECT_EQ(znzread(&n.header, 1, sizeof n.header, f), sizeof n.header);
  char extension[4];
  znzread(extension, 1, 4, f);
  std::size_t bytes = std::size_t(n.header.bitpix / 8);
  for (int i = 1; i <= 3; ++i) bytes *= std::size_t(n.header.dim[i]);
  n.data.resize(bytes);
  EXPECT_EQ(znzread(n.data.data(), 1, bytes, f), bytes);
  znzclose(f);
  return n;
}

// Colin27's brain with voxels of `spacing` mm along its axes, turned by `degrees` about x
// then z, its centre kept in place; pixdim agrees with the sform. Written uncompressed.
std::filesystem::path rescaled_brain(const std::filesystem::path& dir, const Vec3& spacing,
                                     double degrees) {
  Nifti n = read_whole(kBrain);
  const Vec3 centre_index(0.5 * (n.header.dim[1] - 1), 0.5 * (n.header.dim[2] - 1),
                          0.5 * (n.header.dim[3] - 1));
  Mat3 old_linear;
  Vec3 old_offset;
  const float* rows[3] = {n.header.srow_x, n.header.srow_y, n.header.srow_z};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) old_linear(r, c) = rows[r][c];
    old_offset[r] = rows[r][3];
  }
  const Vec3 centre = old_linear * centre_index + old_offset;
  const double a = degrees * std::numbers::pi / 180.0;
  const Mat3 turn = (Eigen::AngleAxisd(a, Vec3::UnitZ()) * Eigen::AngleAxisd(a, Vec3::UnitX()))
                        .toRotationMatrix();
  const Mat3 linear = turn * Mat3(spacing.asDiagonal());
  test::set_sform(n.header, linear, centre - linear * centre_index);
  n.header.qform_code = 0;
  for (int i = 0; i < 3; ++i) n.header.pixdim[i + 1] = static_cast<float>(spacing[i]);
  n.header.vox_offset = 352.0f;
  const auto path = dir / ("brain_" + std::to_string(spacing[0]) + "_" +
                           std::to_string(spacing[2]) + "_" + std::to_string(degrees) + ".nii");
  test::write_nifti(path, n.header, n.data.data(), n.data.size());
  return path;
}

using Layer = test::PlyMeasure;
using test::measure_ply;

// The layer at depth 0 of `volume` (plus `extra` options), judged closed and embedded;
// `threshold` is the T the run uses (the scene's 0.5 mm unless `extra` sets another).
Layer layer_of(const std::filesystem::path& volume, const std::string& name,
               const test::Args& extra = {}, double* preparation_seconds = nullptr,
               double threshold = 0.5) {
  using test::operator+;
  const auto dir = test::cli_scratch("mri_voxel_sizes");
  const std::string mesh = (dir / (name + ".ply")).string();
  const test::CliRun run =
      test::run_cli(test::Args{"--scene", "mri", "--volume", volume.string(), "--steps", "0",
                               "--max-triangles", "60000", "--export-final", mesh, "--quiet"} +
                    extra);
  EXPECT_EQ(run.status, 0) << name << ": " << run.err;
  if (run.status != 0) return {};
  EXPECT_EQ(run.json["budget_hit"], false) << name << ": refinement ran away";
  EXPECT_LE(run["max_sample_error"], threshold * 1.25 * 1.1) << name;  // T + eps, 10% slack
  if (preparation_seconds) *preparation_seconds = run["preparation_seconds"];
  const test::MeshValidity v = test::check_mesh_validity_of_file(mesh);
  EXPECT_TRUE(v.embedded_closed_manifold()) << name << ": " << v.describe();
  return measure_ply(test::read_ply(mesh));
}

struct VoxelVariant {
  Vec3 spacing;
  double degrees;
};

// Each of the voxel sizes: ch2bet's voxels rescaled to `spacing` (and turned by
// `degrees`), judged closed and embedded (layer_of), with an area within 10% of the 1 mm
// layer stretched by the same spacing along the scan's axes (ch2bet's sform is the
// identity, so its axes are the world's; a turn does not change area). For isotropic
// voxels that is the 1 mm area times the square of the voxel-size ratio.
void expect_layers_scaled(const std::vector<VoxelVariant>& variants, const std::string& tag) {
  const auto dir = test::scratch_dir("mri_voxel_sizes_" + tag);
  const Layer reference = layer_of(kBrain, "ch2bet_" + tag);
  ASSERT_GT(reference.area, 0.0);
  const test::PlyData mesh =
      test::read_ply((test::cli_scratch("mri_voxel_sizes") / ("ch2bet_" + tag + ".ply")).string());
  for (const VoxelVariant& v : variants) {
    const double expected = measure_ply(mesh, v.spacing).area;
    const std::string name = "voxels_" + std::to_string(v.spacing[0]) + "x" +
                             std::to_string(v.spacing[2]) + "_turned_" +
                             std::to_string(int(v.degrees));
    const Layer layer = layer_of(rescaled_brain(dir, v.spacing, v.degrees), name);
    EXPECT_NEAR(layer.area / expected, 1.0, 0.10) << name << ": area " << layer.area;
    ::testing::Test::RecordProperty(name + "_area_ratio", std::to_string(layer.area / expected));
  }
}

// Split in two so that CTest runs the halves side by side.
TEST(MriVoxelSizes, Colin27AtFinerVoxelsGivesTheSameLayerScaled) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  expect_layers_scaled({{Vec3::Constant(0.8), 0.0},
                        {Vec3::Constant(0.95), 0.0},
                        {Vec3::Constant(1.05), 0.0},
                        {Vec3(1.0, 1.0, 1.2), 0.0}},
                       "finer");
}

TEST(MriVoxelSizes, Colin27AtCoarserOrTurnedVoxelsGivesTheSameLayerScaled) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  expect_layers_scaled(
      {{Vec3::Constant(1.1), 35.0}, {Vec3::Constant(1.5), 0.0}, {Vec3::Constant(2.0), 0.0}},
      "coarser");
}

// ch2bet with its sform's linear part replaced by `linear` (pixdim left as it was: the sform
// takes precedence), written uncompressed.
std::filesystem::path resformed_brain(const std::filesystem::path& dir, const std::string& name,
                                      const Mat3& linear) {
  Nifti n = read_whole(kBrain);
  const Vec3 offset(n.header.srow_x[3], n.header.srow_y[3], n.header.srow_z[3]);
  test::set_sform(n.header, linear, offset);
  n.header.vox_offset = 352.0f;
  const auto path = dir / (name + ".nii");
  test::write_nifti(path, n.header, n.data.data(), n.data.size());
  return path;
}

// Issue 15's placement family: a sheared sform (x += 0.5 y, a 27-degree slant) is a valid
// placement and gives a closed, embedded layer (the volume is resampled onto perpendicular
// axes before the distance transform, orthogonal_resampling.h; before, the first step ran
// for 400 s); a 100x scaled sform (a 17 m brain) is refused in one line within 10 s.
TEST(MriVoxelSizes, ShearedSformWorksAndScaledOneIsRefusedFast) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_sforms");
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.5;
  const Layer sheared = layer_of(resformed_brain(dir, "sheared", shear), "sheared");
  EXPECT_GT(sheared.area, 0.0);
  // Shear keeps volume: the enclosed volume stays that of the unsheared layer (1.72 L
  // measured for ch2bet's depth-0 layer), within 10%.
  EXPECT_NEAR(sheared.volume / 1.716e6, 1.0, 0.10) << sheared.volume;
  using test::operator+;
  const auto scaled = resformed_brain(dir, "scaled100", 100.0 * Mat3::Identity());
  const auto start = std::chrono::steady_clock::now();
  const test::CliRun run =
      test::run_cli({"--scene", "mri", "--volume", scaled.string(), "--steps", "0", "--quiet"});
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("would span fewer than"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_LT(elapsed, 10.0);
}

// Area-weighted centroid of a mesh's triangles (world mm).
Vec3 centroid_of(const test::PlyData& ply) {
  const std::vector<Vec3> p = [&] {
    std::vector<Vec3> q;
    for (const auto& v : ply.vertices) q.emplace_back(v[0], v[1], v[2]);
    return q;
  }();
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (const auto& f : ply.faces) {
    const double a = 0.5 * (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).norm();
    sum += a * (p[f[0]] + p[f[1]] + p[f[2]]) / 3.0;
    area += a;
  }
  return sum / area;
}

// ch2bet's voxels stored in the reverse order along index axis `axis` (0, 1, 2).
Nifti flipped_data(Nifti n, int axis) {
  const std::size_t bytes = std::size_t(n.header.bitpix / 8);
  const std::size_t d[3] = {std::size_t(n.header.dim[1]), std::size_t(n.header.dim[2]),
                            std::size_t(n.header.dim[3])};
  std::vector<char> out(n.data.size());
  for (std::size_t k = 0; k < d[2]; ++k)
    for (std::size_t j = 0; j < d[1]; ++j)
      for (std::size_t i = 0; i < d[0]; ++i) {
        std::size_t ijk[3] = {i, j, k};
        ijk[axis] = d[axis] - 1 - ijk[axis];
        const std::size_t from = ((k * d[1] + j) * d[0] + i) * bytes;
        const std::size_t to = ((ijk[2] * d[1] + ijk[1]) * d[0] + ijk[0]) * bytes;
        std::copy_n(n.data.data() + from, bytes, out.data() + to);
      }
  n.data = std::move(out);
  return n;
}

// The mri layer through the CLI at T = 1 mm (quicker; the same T for every variant compared),
// with its mesh read back.
struct LayerMesh {
  Layer layer;
  test::PlyData ply;
};

LayerMesh coarse_layer_of(const std::filesystem::path& volume, const std::string& name) {
  LayerMesh m;
  m.layer = layer_of(volume, name, {"--threshold", "1"}, nullptr, 1.0);
  m.ply = test::read_ply((test::cli_scratch("mri_voxel_sizes") / (name + ".ply")).string());
  return m;
}

// Header flips that place the same brain in the same world spot through reversed voxel
// order: a negative sform axis (data reversed along j, the front-back axis, where Colin27
// is not symmetric), the same with negative pixdims (the sform governs; NIfTI takes no
// sign from pixdim[1..3]), and a qform-only header (sform_code 0) whose qfac = pixdim[0] =
// -1 reverses k (data reversed along k). Each gives a closed, embedded layer with the 1 mm
// layer's area and volume (within 10%: the voxel size is unchanged) at the same place
// (centroid within 1 mm; ignoring a flip would move it by centimetres).
TEST(MriVoxelSizes, HeaderFlipsGiveTheSameBrainInTheSamePlace) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_flips");
  const LayerMesh reference = coarse_layer_of(kBrain, "flips_reference");
  ASSERT_GT(reference.layer.area, 0.0);
  const Vec3 centre = centroid_of(reference.ply);
  const Nifti original = read_whole(kBrain);
  const Mat3 linear = Mat3::Identity();  // ch2bet: sform diag(1, 1, 1), offset below
  const Vec3 offset(original.header.srow_x[3], original.header.srow_y[3],
                    original.header.srow_z[3]);
  ASSERT_EQ(original.header.sform_code, 4);
  ASSERT_EQ(original.header.srow_x[0], 1.0f);

  std::vector<std::pair<std::string, std::filesystem::path>> variants;
  {  // sform with a negative j axis; the first voxel is the old last one along j
    Nifti n = flipped_data(original, 1);
    Mat3 l = linear;
    l(1, 1) = -1.0;
    test::set_sform(n.header, l, offset + Vec3(0.0, n.header.dim[2] - 1.0, 0.0));
    n.header.qform_code = 0;
    n.header.vox_offset = 352.0f;
    test::write_nifti(dir / "sform_flip_j.nii", n.header, n.data.data(), n.data.size());
    variants.emplace_back("sform_flip_j", dir / "sform_flip_j.nii");
    for (int i = 1; i <= 3; ++i) n.header.pixdim[i] = -1.0f;
    test::write_nifti(dir / "sform_flip_j_negative_pixdim.nii", n.header, n.data.data(),
                      n.data.size());
    variants.emplace_back("sform_flip_j_negative_pixdim", dir / "sform_flip_j_negative_pixdim.nii");
  }
  {  // qform only: identity quaternion, qfac -1 reverses k
    Nifti n = flipped_data(original, 2);
    n.header.sform_code = 0;
    n.header.qform_code = 1;
    n.header.quatern_b = n.header.quatern_c = n.header.quatern_d = 0.0f;
    n.header.pixdim[0] = -1.0f;
    n.header.qoffset_x = static_cast<float>(offset[0]);
    n.header.qoffset_y = static_cast<float>(offset[1]);
    n.header.qoffset_z = static_cast<float>(offset[2] + (n.header.dim[3] - 1.0));
    n.header.vox_offset = 352.0f;
    test::write_nifti(dir / "qform_flip_k.nii", n.header, n.data.data(), n.data.size());
    variants.emplace_back("qform_flip_k", dir / "qform_flip_k.nii");
  }
  for (const auto& [name, path] : variants) {
    const LayerMesh m = coarse_layer_of(path, name);
    EXPECT_NEAR(m.layer.area / reference.layer.area, 1.0, 0.10) << name << ": " << m.layer.area;
    EXPECT_NEAR(m.layer.volume / reference.layer.volume, 1.0, 0.10) << name;
    const Vec3 c = centroid_of(m.ply);
    EXPECT_LT((c - centre).norm(), 1.0)
        << name << ": centroid " << c.transpose() << " vs " << centre.transpose();
    ::testing::Test::RecordProperty(name + "_area_ratio",
                                    std::to_string(m.layer.area / reference.layer.area));
  }
}

// Anisotropic voxels: ch2bet with its sform's z column tripled (1 x 1 x 3 mm voxels, a brain
// stretched 3x along z). The layer is closed and embedded; its enclosed volume is 3x the
// 1 mm layer's and its area that of the 1 mm layer stretched 3x along z (computed from that
// mesh), both within 10%. (The closing, sized to the brain, and the blurs are isotropic in
// mm, so the stretched brain's layer is not exactly the stretched layer.)
TEST(MriVoxelSizes, AnisotropicVoxelsGiveTheStretchedLayer) {
  if (!std::filesystem::exists(kBrain)) GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_anisotropic");
  const LayerMesh reference = coarse_layer_of(kBrain, "anisotropic_reference");
  ASSERT_GT(reference.layer.area, 0.0);
  const double stretched_area = measure_ply(reference.ply, Vec3(1.0, 1.0, 3.0)).area;
  const LayerMesh z3 = coarse_layer_of(
      resformed_brain(dir, "z3", Vec3(1.0, 1.0, 3.0).asDiagonal().toDenseMatrix()), "z3");
  EXPECT_NEAR(z3.layer.volume / (3.0 * reference.layer.volume), 1.0, 0.10) << z3.layer.volume;
  EXPECT_NEAR(z3.layer.area / stretched_area, 1.0, 0.10)
      << z3.layer.area << " vs stretched " << stretched_area;
  RecordProperty("volume_ratio", std::to_string(z3.layer.volume / reference.layer.volume));
  RecordProperty("area_over_stretched", std::to_string(z3.layer.area / stretched_area));
  RecordProperty("area_over_iso_scaled",
                 std::to_string(z3.layer.area / (reference.layer.area * std::cbrt(9.0))));
}

// Exit status 2, within `seconds`, one line on stderr naming --mask, and no output file.
void expect_refused_fast(const test::Args& args, const std::filesystem::path& mesh,
                         double seconds) {
  using test::operator+;
  const auto start = std::chrono::steady_clock::now();
  const test::CliRun run = test::run_cli(args + test::Args{"--export-final", mesh.string()});
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_LT(elapsed, seconds);
  EXPECT_NE(run.err.find("--mask"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(std::filesystem::exists(mesh));
  // Peak memory of any child so far (this process runs only this test under CTest).
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  EXPECT_LT(usage.ru_maxrss, 2L * 1024 * 1024) << "KiB";
}

TEST(MriVoxelSizes, RandomVolumeFailsFastNamingMask) {
  const auto dir = test::scratch_dir("mri_random");
  nifti_1_header h = test::make_header({128, 128, 128}, NIFTI_TYPE_UINT8, 8);
  std::vector<std::uint8_t> noise(128 * 128 * 128);
  std::mt19937 random(7);
  for (auto& v : noise) v = static_cast<std::uint8_t>(random() & 0xff);
  test::write_nifti(dir / "random.nii.gz", h, noise);
  expect_refused_fast({"--scene", "mri", "--volume", (dir / "random.nii.gz").string(), "--quiet"},
                      dir / "random.ply", 30.0);
}

// Distance from p to the triangle (a, b, c) (C. Ericson, "Real-Time Collision Detection",
// 2005, 5.1.5: the closest point by Voronoi regions).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

std::vector<Vec3> positions_of(const test::PlyData& ply) {
  std::vector<Vec3> p;
  for (const auto& v : ply.vertices) p.emplace_back(v[0], v[1], v[2]);
  return p;
}

// Mean distance from the vertices of `from` to the surface `to` (brute force over all
// triangles: a few thousand of each).
double mean_distance(const test::PlyData& from, const test::PlyData& to) {
  const std::vector<Vec3> p = positions_of(from), q = positions_of(to);
  double sum = 0.0;
  for (const Vec3& x : p) {
    double best = 1e300;
    for (const auto& f : to.faces)
      best = std::min(best, point_triangle_distance(x, q[f[0]], q[f[1]], q[f[2]]));
    sum += best;
  }
  return sum / static_cast<double>(p.size());
}

// Built-in brain extraction (brain_extraction.h): the head with its skull (ch2) gives the
// layer 3 mm deep of the skull-stripped brain (ch2bet): enclosed volume and area within 10%
// and a mean symmetric surface distance of at most 2 mm. The issue's "preprocessing under
// 30 s" is a speed goal, measured by BM_MriPrepWhole/head (tests/bench); here the head's
// whole run is held to 30 s of CPU time (all threads; 6-7 s measured), which a loaded
// machine does not inflate the way it inflates the wall clock (preparation_seconds: 35 s
// wall at load 25 for ~3.4 s of CPU).
TEST(MriVoxelSizes, HeadWithSkullGivesTheStrippedBrainsLayer) {
  if (!std::filesystem::exists(kHead) || !std::filesystem::exists(kBrain))
    GTEST_SKIP() << "mricron-data not installed";
  const test::Args deep{"--param", "depth_max=3", "--t0", "1"};
  double preparation = 0.0;
  const Layer brain = layer_of(kBrain, "ch2bet_3mm", deep);
  const double cpu_before = test::children_cpu_seconds();
  const Layer head = layer_of(kHead, "ch2_3mm", deep, &preparation);
  const double cpu = test::children_cpu_seconds() - cpu_before;
  ASSERT_GT(brain.area, 0.0);
  ASSERT_GT(head.area, 0.0);
  EXPECT_NEAR(head.area / brain.area, 1.0, 0.10) << head.area << " vs " << brain.area;
  EXPECT_NEAR(head.volume / brain.volume, 1.0, 0.10) << head.volume << " vs " << brain.volume;
  const test::PlyData a =
      test::read_ply((test::cli_scratch("mri_voxel_sizes") / "ch2bet_3mm.ply").string());
  const test::PlyData b =
      test::read_ply((test::cli_scratch("mri_voxel_sizes") / "ch2_3mm.ply").string());
  const double symmetric = 0.5 * (mean_distance(a, b) + mean_distance(b, a));
  EXPECT_LE(symmetric, 2.0) << "mm";
  EXPECT_LT(cpu, 30.0) << "s of CPU for the whole run";
  RecordProperty("run_cpu_seconds", std::to_string(cpu));
  RecordProperty("symmetric_surface_distance_mm", std::to_string(symmetric));
  RecordProperty("area_ratio", std::to_string(head.area / brain.area));
  RecordProperty("volume_ratio", std::to_string(head.volume / brain.volume));
  RecordProperty("preparation_seconds", std::to_string(preparation));
}

// A head without a brain (ch2 with every voxel of ch2bet's brain set to 0: scalp, skull,
// eyes and neck) has no brain-like piece: exit 2 within 30 s and 2 GB, naming --mask.
TEST(MriVoxelSizes, HeadWithoutBrainFailsFastNamingMask) {
  if (!std::filesystem::exists(kHead) || !std::filesystem::exists(kBrain))
    GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_no_brain");
  Nifti head = read_whole(kHead);
  const Nifti brain = read_whole(kBrain);
  ASSERT_EQ(head.header.bitpix, 8);
  ASSERT_EQ(brain.data.size(), head.data.size());
  for (std::size_t v = 0; v < head.data.size(); ++v)
    if (brain.data[v] != 0) head.data[v] = 0;
  head.header.vox_offset = 352.0f;
  test::write_nifti(dir / "no_brain.nii", head.header, head.data.data(), head.data.size());
  expect_refused_fast({"--scene", "mri", "--volume", (dir / "no_brain.nii").string(), "--quiet"},
                      dir / "no_brain.ply", 30.0);
}

TEST(MriVoxelSizes, MaskFromAnotherToolGivesThatBrainsLayer) {
  if (!std::filesystem::exists(kHead) || !std::filesystem::exists(kBrain))
    GTEST_SKIP() << "mricron-data not installed";
  const auto dir = test::scratch_dir("mri_mask");
  // The brain mask: ch2bet's nonzero voxels (what BET left), on ch2's grid.
  Nifti brain = read_whole(kBrain);
  std::vector<std::uint8_t> mask(brain.data.size() / std::size_t(brain.header.bitpix / 8));
  ASSERT_EQ(brain.header.bitpix, 8);
  for (std::size_t v = 0; v < mask.size(); ++v) mask[v] = brain.data[v] != 0 ? 1 : 0;
  nifti_1_header h = brain.header;
  h.datatype = NIFTI_TYPE_UINT8;
  h.scl_slope = 1.0f;
  h.scl_inter = 0.0f;
  h.vox_offset = 352.0f;
  test::write_nifti(dir / "mask.nii.gz", h, mask);

  const Layer reference = layer_of(kBrain, "ch2bet");
  const Layer masked = layer_of(kHead, "ch2_masked", {"--mask", (dir / "mask.nii.gz").string()});
  EXPECT_NEAR(masked.area / reference.area, 1.0, 0.10) << masked.area;
  EXPECT_NEAR(masked.volume / reference.volume, 1.0, 0.10) << masked.volume;

  // A mask on another grid is refused in one line.
  h.dim[1] = 100;
  test::write_nifti(dir / "small.nii.gz", h,
                    std::vector<std::uint8_t>(std::size_t(100) * h.dim[2] * h.dim[3], 1));
  const test::CliRun bad = test::run_cli({"--scene", "mri", "--volume", kHead.string(), "--mask",
                                          (dir / "small.nii.gz").string(), "--quiet"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("grid"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

}  // namespace
}  // namespace dynamesh
