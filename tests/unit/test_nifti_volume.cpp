// Reading NIfTI-1 volumes: every supported datatype, plain and gzip, scaling, placement
// (sform, qform, pixdim), 4-D files, byte-swapped files, and a clear error for each kind of
// bad input. Files are written byte by byte by test_nifti_files.h.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
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
  expect_error(path, "not gzip-compressed");
}

}  // namespace
}  // namespace dynamesh

namespace dynamesh {
namespace {

// --- hostile headers (issue 15): refused with the reason, before anything is allocated ----

TEST(NiftiVolumeHostile, AbsurdOrNonFiniteVoxelSizesAreRefused) {
  const auto dir = scratch_dir("nifti_hostile_pixdim");
  const auto values = pattern_values<std::uint8_t>();
  int n = 0;
  // pixdim alone (method 1), then the same pixdim through a qform (method 2).
  for (const int qform : {0, 1}) {
    for (const float size : {1e30f, 1e6f, 101.0f, 1e-5f, 0.005f}) {
      for (const int axis : {1, 3}) {
        nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
        h.qform_code = static_cast<short>(qform);
        h.pixdim[axis] = size;
        const auto path = dir / (std::to_string(n++) + "_p.nii");
        write_nifti(path, h, values);
        expect_error(path, "is outside [0.01, 100] mm");
      }
    }
    for (const float bad : {NAN, INFINITY}) {
      nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
      h.qform_code = static_cast<short>(qform);
      h.pixdim[2] = bad;
      const auto path = dir / (std::to_string(n++) + "_nf.nii");
      write_nifti(path, h, values);
      expect_error(path, "non-finite");
    }
  }
  // Sizes at the ends of the range are read.
  for (const float size : {0.01f, 100.0f}) {
    nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
    h.pixdim[1] = h.pixdim[2] = h.pixdim[3] = size;
    const auto path = dir / (std::to_string(n++) + "_ok.nii");
    write_nifti(path, h, values);
    EXPECT_NEAR(read_nifti_volume(path).volume.grid.spacing()[0], size, 1e-6 * size);
  }
}

TEST(NiftiVolumeHostile, AbsurdSformsAreRefused) {
  const auto dir = scratch_dir("nifti_hostile_sform");
  const auto values = pattern_values<std::uint8_t>();
  auto expect_sform_error = [&](const std::string& name, const Mat3& linear, const Vec3& offset,
                                const std::string& fragment) {
    nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
    test::set_sform(h, linear, offset);
    write_nifti(dir / name, h, values);
    expect_error(dir / name, fragment);
  };
  expect_sform_error("big.nii", 1e30 * Mat3::Identity(), Vec3::Zero(), "outside [0.01, 100]");
  Mat3 one_row = Mat3::Identity();
  one_row.row(0) *= 1e30;  // srow_x = 1e30
  expect_sform_error("row.nii", one_row, Vec3::Zero(), "outside [0.01, 100]");
  expect_sform_error("far.nii", Mat3::Identity(), Vec3(1e30, 0, 0), "mm from the origin");
  expect_sform_error("inf.nii", Mat3::Identity(), Vec3(INFINITY, 0, 0), "non-finite");
  // Two voxel axes 0.1 degrees apart: a flattened sliver, nearly singular.
  Mat3 sliver = Mat3::Identity();
  sliver.col(1) =
      Vec3(std::cos(0.1 * std::numbers::pi / 180), std::sin(0.1 * std::numbers::pi / 180), 0);
  expect_sform_error("sliver.nii", sliver, Vec3::Zero(), "nearly so");
  // A strong but honest shear (45 degrees) is still read.
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1.0;
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_UINT8, 8);
  test::set_sform(h, shear, Vec3::Zero());
  write_nifti(dir / "shear.nii", h, values);
  EXPECT_EQ(read_nifti_volume(dir / "shear.nii").placement, VoxelPlacement::kSform);
}

TEST(NiftiVolumeHostile, HeaderClaimingMoreDataThanTheFileIsRefusedBeforeAllocating) {
  const auto dir = scratch_dir("nifti_hostile_size");
  // 1290^3 voxels in a 352-byte file: beyond what the reader ever reads.
  nifti_1_header h = make_header({1290, 1290, 1290}, DT_UINT8, 8);
  for (const char* name : {"huge.nii", "huge.nii.gz"}) {
    write_nifti(dir / name, h, nullptr, 0);
    expect_error(dir / name, "volume too large");
  }
  // 600^3 float64 (1.6 GB) and dim1 = 32767: within the voxel limit, so refused by the file
  // size (plain) or as the data runs out (gzip). Must be quick and small: the reader grows
  // its buffer only as data arrives (gzip) or checks the file size first (plain).
  h = make_header({600, 600, 600}, DT_FLOAT64, 64);
  nifti_1_header wide = make_header({32767, 100, 20}, DT_INT16, 16);
  for (const char* name : {"big.nii", "big.nii.gz", "wide.nii", "wide.nii.gz"}) {
    write_nifti(dir / name, name[0] == 'b' ? h : wide, nullptr, 0);
    const auto start = std::chrono::steady_clock::now();
    expect_error(dir / name, "truncated data");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  }
}

// Writes a valid file, returns its bytes.
std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(NiftiVolumeHostile, DamagedGzipIsRefused) {
  const auto dir = scratch_dir("nifti_hostile_gz");
  const auto values = pattern_values<std::int16_t>();
  write_nifti(dir / "good.nii.gz", make_header({kNx, kNy, kNz}, DT_INT16, 16), values);
  const std::string good = file_bytes(dir / "good.nii.gz");
  ASSERT_NO_THROW(read_nifti_volume(dir / "good.nii.gz"));
  // The trailer is CRC-32 then the length, 4 bytes each, little-endian.
  std::string crc = good;
  crc[crc.size() - 8] ^= 0x55;
  test::write_text(dir / "crc.nii.gz", crc);
  expect_error(dir / "crc.nii.gz", "incorrect data check");
  std::string length = good;
  length[length.size() - 4] ^= 0x01;
  test::write_text(dir / "len.nii.gz", length);
  expect_error(dir / "len.nii.gz", "incorrect length check");
  test::write_text(dir / "garbage.nii.gz", good + "trailing garbage");
  expect_error(dir / "garbage.nii.gz", "trailing data");
  test::write_text(dir / "cut.nii.gz", good.substr(0, good.size() - 6));
  expect_error(dir / "cut.nii.gz", "ends early");
  // Two concatenated members are valid gzip (the second one here is an empty stream's
  // worth of extra voxels, so refused as trailing voxel data, not as garbage).
  test::write_text(dir / "two.nii.gz", good + good);
  expect_error(dir / "two.nii.gz", "bytes of trailing data after the last voxel");
}

TEST(NiftiVolumeHostile, DimensionsThatDoNotMatchTheDataAreRefused) {
  const auto dir = scratch_dir("nifti_hostile_dims");
  const auto values = pattern_values<std::int16_t>();
  for (const char* name : {"small.nii", "small.nii.gz"}) {
    // dim3 smaller than the data: the rest would be silently ignored.
    write_nifti(dir / name, make_header({kNx, kNy, kNz - 1}, DT_INT16, 16), values);
    expect_error(dir / name, "trailing data after the last voxel");
  }
  for (const char* name : {"4d.nii", "4d.nii.gz"}) {
    // Three volumes claimed, one stored.
    write_nifti(dir / name, make_header({kNx, kNy, kNz, 3}, DT_INT16, 16), values);
    expect_error(dir / name, "describes 3 volumes, the file holds 1");
  }
  nifti_1_header h = make_header({kNx, kNy, kNz}, DT_INT16, 16);
  h.vox_offset = 352.5f;
  write_nifti(dir / "frac.nii", h, values);
  expect_error(dir / "frac.nii", "invalid vox_offset");
  h.vox_offset = 1e30f;
  write_nifti(dir / "far.nii", h, values);
  expect_error(dir / "far.nii", "invalid vox_offset");
}

}  // namespace
}  // namespace dynamesh
