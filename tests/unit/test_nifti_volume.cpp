// Reading NIfTI-1 volumes: every supported datatype, plain and gzip, scaling, placement
// (sform, qform, pixdim), 4-D files, byte-swapped files, and a clear error for each kind of
// bad input. Files are written byte by byte by test_nifti_files.h.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "core/io/nifti_volume.h"
#include "test_nifti_files.h"

namespace dynamesh {
namespace {

using test::make_header;
using test::scratch_dir;
using test::write_nifti;

// A small volume whose voxel (i, j, k) holds a distinct value that fits in every type.
constexpr int kNx = 5, kNy = 4, kNz = 3;
double pattern(int i, int j, int k) {
  return i + 7 * j + 31 * k;
}  // 0..108

template <class T>
std::vector<T> pattern_values() {
  std::vector<T> v;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) v.push_back(static_cast<T>(pattern(i, j, k)));
  return v;
}

void expect_pattern(const NiftiVolume& nv, double slope = 1.0, double inter = 0.0) {
  ASSERT_EQ(nv.volume.grid.dims, (std::array<int, 3>{kNx, kNy, kNz}));
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i)
        EXPECT_FLOAT_EQ(nv.volume.at(i, j, k), slope * pattern(i, j, k) + inter);
}

template <class T>
void check_type(int datatype, const std::string& name) {
  const auto dir = scratch_dir("nifti_types");
  for (const char* file : {"v.nii", "v.nii.gz"}) {
    const auto path = dir / (name + file);
    write_nifti(path, make_header({kNx, kNy, kNz}, datatype, 8 * sizeof(T)), pattern_values<T>());
    const NiftiVolume nv = read_nifti_volume(path);
    EXPECT_EQ(nv.datatype, datatype);
    EXPECT_EQ(nv.datatype_name, name);
    expect_pattern(nv);
  }
}

TEST(NiftiVolume, ReadsEveryIntegerAndFloatTypePlainAndGzip) {
  check_type<std::uint8_t>(DT_UINT8, "uint8");
  check_type<std::int8_t>(DT_INT8, "int8");
  check_type<std::int16_t>(DT_INT16, "int16");
  check_type<std::uint16_t>(DT_UINT16, "uint16");
  check_type<std::int32_t>(DT_INT32, "int32");
  check_type<std::uint32_t>(DT_UINT32, "uint32");
  check_type<std::int64_t>(DT_INT64, "int64");
  check_type<std::uint64_t>(DT_UINT64, "uint64");
  check_type<float>(DT_FLOAT32, "float32");
  check_type<double>(DT_FLOAT64, "float64");
}

TEST(NiftiVolume, AppliesSlopeAndIntercept) {
  const auto path = scratch_dir("nifti_scale") / "s.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_INT16, 16);
  h.scl_slope = 0.5f;
  h.scl_inter = -3.0f;
  write_nifti(path, h, pattern_values<std::int16_t>());
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_DOUBLE_EQ(nv.scl_slope, 0.5);
  expect_pattern(nv, 0.5, -3.0);
}

TEST(NiftiVolume, ZeroSlopeMeansUnscaled) {
  const auto path = scratch_dir("nifti_scale0") / "s.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  h.scl_slope = 0.0f;
  h.scl_inter = 100.0f;  // ignored: NIfTI-1 says slope 0 means no scaling
  write_nifti(path, h, pattern_values<std::uint8_t>());
  expect_pattern(read_nifti_volume(path));
}

TEST(NiftiVolume, UsesObliqueSformFirst) {
  const auto path = scratch_dir("nifti_sform") / "s.nii.gz";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_FLOAT32, 32);
  const Mat3 rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3 linear = rotation * Vec3(0.9, 1.2, 2.0).asDiagonal();
  const Vec3 offset(-10.5, 20.25, 3.0);
  test::set_sform(h, linear, offset);
  h.qform_code = 1;  // present but must lose to the sform
  write_nifti(path, h, pattern_values<float>());
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_EQ(nv.placement, VoxelPlacement::kSform);
  EXPECT_LT((nv.volume.grid.linear - linear).norm(), 1e-6);
  EXPECT_LT((nv.volume.grid.offset - offset).norm(), 1e-5);
  EXPECT_NEAR(nv.volume.grid.spacing()[2], 2.0, 1e-6);
  // Voxel (1, 2, 1) lands where the affine says.
  EXPECT_LT((nv.volume.grid.to_world(Vec3(1, 2, 1)) - (linear * Vec3(1, 2, 1) + offset)).norm(),
            1e-5);
}

TEST(NiftiVolume, UsesQuaternionQformWithoutSform) {
  const auto path = scratch_dir("nifti_qform") / "q.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  // 90 degrees about z: quaternion (a, b, c, d) = (cos 45, 0, 0, sin 45); qfac -1 flips k.
  h.qform_code = 1;
  h.quatern_d = static_cast<float>(std::sin(std::numbers::pi / 4));
  h.qoffset_x = 5.0f;
  h.qoffset_y = 6.0f;
  h.qoffset_z = 7.0f;
  h.pixdim[0] = -1.0f;
  h.pixdim[1] = 2.0f;
  h.pixdim[2] = 3.0f;
  h.pixdim[3] = 4.0f;
  write_nifti(path, h, pattern_values<std::uint8_t>());
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_EQ(nv.placement, VoxelPlacement::kQform);
  Mat3 expected;
  expected << 0, -3, 0,  //
      2, 0, 0,           //
      0, 0, -4;
  EXPECT_LT((nv.volume.grid.linear - expected).norm(), 1e-5);
  EXPECT_LT((nv.volume.grid.offset - Vec3(5, 6, 7)).norm(), 1e-6);
}

TEST(NiftiVolume, FallsBackToPixdim) {
  const auto path = scratch_dir("nifti_pixdim") / "p.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  h.pixdim[1] = 1.5f;
  h.pixdim[2] = 2.5f;
  h.pixdim[3] = 3.5f;
  write_nifti(path, h, pattern_values<std::uint8_t>());
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_EQ(nv.placement, VoxelPlacement::kPixdim);
  EXPECT_LT((nv.volume.grid.linear - Vec3(1.5, 2.5, 3.5).asDiagonal().toDenseMatrix()).norm(),
            1e-6);
  EXPECT_EQ(nv.volume.grid.offset, Vec3::Zero());
}

TEST(NiftiVolume, FourDimensionalFileGivesItsFirstVolume) {
  const auto path = scratch_dir("nifti_4d") / "t.nii.gz";
  std::vector<std::int16_t> values = pattern_values<std::int16_t>();
  const std::size_t n = values.size();
  for (int t = 1; t < 3; ++t)
    for (std::size_t i = 0; i < n; ++i) values.push_back(static_cast<std::int16_t>(1000 * t));
  write_nifti(path, make_header({kNx, kNy, kNz, 3}, DT_INT16, 16), values);
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_EQ(nv.volumes_in_file, 3);
  expect_pattern(nv);
}

TEST(NiftiVolume, ReadsByteSwappedFile) {
  const auto path = scratch_dir("nifti_swapped") / "b.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_INT16, 16);
  h.pixdim[1] = 2.0f;
  std::vector<std::int16_t> values = pattern_values<std::int16_t>();
  for (auto& v : values) test::swap16(&v);
  test::swap32(&h.sizeof_hdr);
  for (auto& d : h.dim) test::swap16(&d);
  for (auto& p : h.pixdim) test::swap32(&p);
  test::swap16(&h.datatype);
  test::swap16(&h.bitpix);
  test::swap32(&h.vox_offset);
  write_nifti(path, h, values);
  const NiftiVolume nv = read_nifti_volume(path);
  expect_pattern(nv);
  EXPECT_NEAR(nv.volume.grid.spacing()[0], 2.0, 1e-9);
}

TEST(NiftiVolume, NonFiniteVoxelsBecomeZeroAndAreCounted) {
  const auto path = scratch_dir("nifti_nan") / "n.nii";
  std::vector<float> values = pattern_values<float>();
  values[3] = std::numeric_limits<float>::quiet_NaN();
  values[4] = std::numeric_limits<float>::infinity();
  write_nifti(path, make_header({kNx, kNy, kNz}, DT_FLOAT32, 32), values);
  const NiftiVolume nv = read_nifti_volume(path);
  EXPECT_EQ(nv.non_finite, 2u);
  EXPECT_EQ(nv.volume.values[3], 0.0f);
}

// --- errors: one std::runtime_error naming the file and the problem ----------------------

void expect_error(const std::filesystem::path& path, const std::string& fragment) {
  try {
    read_nifti_volume(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(NiftiVolumeErrors, MissingFile) {
  expect_error(scratch_dir("nifti_err_missing") / "none.nii", "no such file");
}

TEST(NiftiVolumeErrors, WrongExtension) {
  const auto path = scratch_dir("nifti_err_ext") / "brain.txt";
  test::write_text(path, "hello");
  expect_error(path, "expected .nii or .nii.gz");
}

TEST(NiftiVolumeErrors, TextFileNamedNii) {
  const auto dir = scratch_dir("nifti_err_text");
  test::write_text(dir / "short.nii", "this is not an image");
  expect_error(dir / "short.nii", "truncated header");
  test::write_text(dir / "long.nii", std::string(1000, 'x'));
  expect_error(dir / "long.nii", "not a NIfTI-1 file");
}

TEST(NiftiVolumeErrors, WrongMagic) {
  const auto dir = scratch_dir("nifti_err_magic");
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  std::memcpy(h.magic, "abc", 4);
  write_nifti(dir / "m.nii", h, pattern_values<std::uint8_t>());
  expect_error(dir / "m.nii", "bad magic");
  std::memcpy(h.magic, "ni1", 4);
  write_nifti(dir / "pair.nii", h, pattern_values<std::uint8_t>());
  expect_error(dir / "pair.nii", ".hdr/.img pair");
}

TEST(NiftiVolumeErrors, Nifti2Header) {
  const auto path = scratch_dir("nifti_err_n2") / "n2.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  h.sizeof_hdr = 540;
  write_nifti(path, h, pattern_values<std::uint8_t>());
  expect_error(path, "NIfTI-2");
}

TEST(NiftiVolumeErrors, ZeroOrNegativeDimension) {
  const auto dir = scratch_dir("nifti_err_dim");
  write_nifti(dir / "z.nii", make_header({kNx, 0, kNz}, DT_UINT8, 8),
              pattern_values<std::uint8_t>());
  expect_error(dir / "z.nii", "dim[2] = 0");
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  h.dim[0] = 0;
  write_nifti(dir / "nd.nii", h, pattern_values<std::uint8_t>());
  expect_error(dir / "nd.nii", "number of dimensions");
}

TEST(NiftiVolumeErrors, UnsupportedDatatype) {
  const auto path = scratch_dir("nifti_err_type") / "c.nii";
  write_nifti(path, make_header({kNx, kNy, kNz}, DT_COMPLEX64, 64),
              std::vector<float>(2 * kNx * kNy * kNz, 0.0f));
  expect_error(path, "unsupported datatype 32");
}

TEST(NiftiVolumeErrors, TruncatedHeaderAndData) {
  const auto dir = scratch_dir("nifti_err_trunc");
  const nifti_1_header h = make_header({kNx, kNy, kNz}, DT_INT16, 16);
  const auto values = pattern_values<std::int16_t>();
  for (const char* name : {"h.nii", "h.nii.gz"}) {
    write_nifti(dir / name, h, values.data(), 0, 200);
    expect_error(dir / name, "truncated header");
  }
  for (const char* name : {"d.nii", "d.nii.gz"}) {
    write_nifti(dir / name, h, values.data(), values.size() * 2 - 10);
    expect_error(dir / name, "truncated");
  }
}

TEST(NiftiVolumeErrors, SingularTransform) {
  const auto path = scratch_dir("nifti_err_singular") / "s.nii";
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  test::set_sform(h, Mat3::Zero(), Vec3::Zero());
  write_nifti(path, h, pattern_values<std::uint8_t>());
  expect_error(path, "singular");
}

TEST(NiftiVolumeErrors, GzipFileThatIsNotGzip) {
  const auto path = scratch_dir("nifti_err_gz") / "x.nii.gz";
  test::write_text(path, std::string(2000, 'z'));
  expect_error(path, "not a NIfTI-1 file");
}

}  // namespace
}  // namespace dynamesh
