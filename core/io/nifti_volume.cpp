#include "core/io/nifti_volume.h"

#include <nifti1_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace dynamesh {
namespace {

constexpr int kNifti1HeaderSize = 348;
constexpr int kNifti2HeaderSize = 540;
// Guards against headers that claim absurd sizes before anything is allocated (2^31 voxels
// of float is 8 GiB, far beyond any brain image).
constexpr std::size_t kMaxVoxels = std::size_t{1} << 31;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw std::runtime_error("NIfTI file '" + path.string() + "': " + problem);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::int32_t byte_swapped(std::int32_t v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  u = (u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) | (u << 24);
  std::memcpy(&v, &u, 4);
  return v;
}

// Reads the raw 348-byte header (through znzlib, so .nii.gz works) and puts it in native
// byte order.
nifti_1_header read_header(const std::filesystem::path& path, bool gzipped, bool& swapped) {
  znzFile file = znzopen(path.c_str(), "rb", gzipped ? 1 : 0);
  if (znz_isnull(file)) fail(path, "cannot open for reading");
  nifti_1_header header;
  std::memset(&header, 0, sizeof header);
  const std::size_t got = znzread(&header, 1, sizeof header, file);
  znzclose(file);
  if (got < static_cast<std::size_t>(kNifti1HeaderSize)) {
    fail(path, "truncated header: " + std::to_string(got) + " of " +
                   std::to_string(kNifti1HeaderSize) + " bytes");
  }
  swapped = false;
  if (header.sizeof_hdr == kNifti1HeaderSize) return header;
  const std::int32_t reversed = byte_swapped(header.sizeof_hdr);
  if (reversed == kNifti1HeaderSize) {
    swap_nifti_header(&header, 1);
    swapped = true;
    return header;
  }
  if (header.sizeof_hdr == kNifti2HeaderSize || reversed == kNifti2HeaderSize) {
    fail(path, "NIfTI-2 files are not supported (only NIfTI-1)");
  }
  fail(path, "not a NIfTI-1 file (header size field is " + std::to_string(header.sizeof_hdr) +
                 ", expected 348)");
}

void check_magic(const std::filesystem::path& path, const nifti_1_header& h) {
  if (std::memcmp(h.magic, "n+1", 4) == 0) return;
  if (std::memcmp(h.magic, "ni1", 4) == 0) {
    fail(path, "header of a two-file .hdr/.img pair; only single-file .nii is supported");
  }
  fail(path, "bad magic string (expected \"n+1\"): not a NIfTI-1 single file");
}

struct DatatypeInfo {
  int code;
  int bytes;
  const char* name;
};

constexpr DatatypeInfo kSupported[] = {{DT_UINT8, 1, "uint8"},     {DT_INT8, 1, "int8"},
                                       {DT_INT16, 2, "int16"},     {DT_UINT16, 2, "uint16"},
                                       {DT_INT32, 4, "int32"},     {DT_UINT32, 4, "uint32"},
                                       {DT_INT64, 8, "int64"},     {DT_UINT64, 8, "uint64"},
                                       {DT_FLOAT32, 4, "float32"}, {DT_FLOAT64, 8, "float64"}};

const DatatypeInfo& datatype_info(const std::filesystem::path& path, int code) {
  for (const DatatypeInfo& info : kSupported) {
    if (info.code == code) return info;
  }
  std::ostringstream msg;
  msg << "unsupported datatype " << code << " (" << nifti_datatype_string(code)
      << "); supported: integers of 8 to 64 bits, float32, float64";
  fail(path, msg.str());
}

// Spatial size (dims 1..3, missing ones are 1) and number of volumes (dims 4..7).
std::array<int, 3> check_dimensions(const std::filesystem::path& path, const nifti_1_header& h,
                                    int& volumes) {
  const int ndim = h.dim[0];
  if (ndim < 1 || ndim > 7) {
    fail(path, "invalid number of dimensions dim[0] = " + std::to_string(ndim) + " (1..7)");
  }
  for (int i = 1; i <= ndim; ++i) {
    if (h.dim[i] <= 0) {
      fail(path, "dimension dim[" + std::to_string(i) + "] = " + std::to_string(h.dim[i]) +
                     " is zero or negative");
    }
  }
  std::array<int, 3> dims{1, 1, 1};
  for (int i = 1; i <= std::min(ndim, 3); ++i) dims[i - 1] = h.dim[i];
  volumes = 1;
  for (int i = 4; i <= ndim; ++i) volumes *= h.dim[i];
  const std::size_t voxels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  if (voxels > kMaxVoxels) fail(path, "volume too large (" + std::to_string(voxels) + " voxels)");
  return dims;
}

Mat3 to_mat3(const mat44& m) {
  Mat3 a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = m.m[r][c];
  return a;
}

// NIfTI-1 placement rules: sform first (method 3), then the quaternion qform (method 2, the
// matrix built by nifticlib with qfac = pixdim[0]), then pixdim alone (method 1).
VoxelGrid placement(const std::filesystem::path& path, const nifti_1_header& h,
                    VoxelPlacement& used) {
  VoxelGrid grid;
  if (h.sform_code > 0) {
    const float* rows[3] = {h.srow_x, h.srow_y, h.srow_z};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) grid.linear(r, c) = rows[r][c];
      grid.offset[r] = rows[r][3];
    }
    used = VoxelPlacement::kSform;
  } else if (h.qform_code > 0) {
    const float qfac = h.pixdim[0] < 0.0f ? -1.0f : 1.0f;
    const mat44 m =
        nifti_quatern_to_mat44(h.quatern_b, h.quatern_c, h.quatern_d, h.qoffset_x, h.qoffset_y,
                               h.qoffset_z, h.pixdim[1], h.pixdim[2], h.pixdim[3], qfac);
    grid.linear = to_mat3(m);
    grid.offset = Vec3(m.m[0][3], m.m[1][3], m.m[2][3]);
    used = VoxelPlacement::kQform;
  } else {
    Vec3 d;
    for (int i = 0; i < 3; ++i) d[i] = std::abs(h.pixdim[i + 1]);
    grid.linear = d.asDiagonal();
    used = VoxelPlacement::kPixdim;
  }
  if (!grid.linear.allFinite() || !grid.offset.allFinite()) {
    fail(path, "voxel-to-world transform has non-finite entries");
  }
  if (std::abs(grid.linear.determinant()) < 1e-12) {
    fail(path, "voxel-to-world transform is singular (zero voxel size?)");
  }
  return grid;
}

template <class T>
void convert(const void* raw, std::size_t n, double slope, double inter, float* out) {
  const T* in = static_cast<const T*>(raw);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = static_cast<float>(slope * static_cast<double>(in[i]) + inter);
  }
}

void convert_any(int datatype, const void* raw, std::size_t n, double slope, double inter,
                 float* out) {
  switch (datatype) {
    case DT_UINT8:
      return convert<std::uint8_t>(raw, n, slope, inter, out);
    case DT_INT8:
      return convert<std::int8_t>(raw, n, slope, inter, out);
    case DT_INT16:
      return convert<std::int16_t>(raw, n, slope, inter, out);
    case DT_UINT16:
      return convert<std::uint16_t>(raw, n, slope, inter, out);
    case DT_INT32:
      return convert<std::int32_t>(raw, n, slope, inter, out);
    case DT_UINT32:
      return convert<std::uint32_t>(raw, n, slope, inter, out);
    case DT_INT64:
      return convert<std::int64_t>(raw, n, slope, inter, out);
    case DT_UINT64:
      return convert<std::uint64_t>(raw, n, slope, inter, out);
    case DT_FLOAT32:
      return convert<float>(raw, n, slope, inter, out);
    case DT_FLOAT64:
      return convert<double>(raw, n, slope, inter, out);
    default:
      break;
  }
}

// Reads the first volume's bytes at vox_offset in chunks (so progress can be reported) and
// puts them in native byte order.
std::vector<unsigned char> read_voxels(const std::filesystem::path& path, bool gzipped,
                                       const nifti_1_header& h, bool swapped, std::size_t bytes,
                                       int bytes_per_voxel,
                                       const std::function<void(double)>& progress) {
  znzFile file = znzopen(path.c_str(), "rb", gzipped ? 1 : 0);
  if (znz_isnull(file)) fail(path, "cannot open for reading");
  std::vector<unsigned char> raw(bytes);
  std::size_t got = 0;
  // fseek answers 0 on success, gzseek the new offset: both are >= 0.
  if (znzseek(file, static_cast<znz_off_t>(h.vox_offset), SEEK_SET) >= 0) {
    constexpr std::size_t kChunk = std::size_t{4} << 20;
    while (got < bytes) {
      const std::size_t n = znzread(raw.data() + got, 1, std::min(kChunk, bytes - got), file);
      if (n == 0) break;
      got += n;
      if (progress) progress(static_cast<double>(got) / static_cast<double>(bytes));
    }
  }
  znzclose(file);
  if (got < bytes) {
    fail(path, "truncated data: " + std::to_string(bytes) + " bytes expected after offset " +
                   std::to_string(static_cast<long long>(h.vox_offset)) + ", got " +
                   std::to_string(got));
  }
  if (swapped && bytes_per_voxel > 1) {
    nifti_swap_Nbytes(bytes / bytes_per_voxel, bytes_per_voxel, raw.data());
  }
  return raw;
}

}  // namespace

NiftiVolume read_nifti_volume(const std::filesystem::path& path,
                              const std::function<void(double)>& progress) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  const std::string name = path.filename().string();
  const bool gzipped = ends_with(name, ".nii.gz");
  if (!gzipped && !ends_with(name, ".nii")) {
    fail(path, "unsupported file name: expected .nii or .nii.gz");
  }

  bool swapped = false;
  const nifti_1_header header = read_header(path, gzipped, swapped);
  check_magic(path, header);
  NiftiVolume result;
  const std::array<int, 3> dims = check_dimensions(path, header, result.volumes_in_file);
  const DatatypeInfo& type = datatype_info(path, header.datatype);
  if (header.bitpix != 8 * type.bytes) {
    fail(path, "bitpix " + std::to_string(header.bitpix) + " does not match datatype " + type.name);
  }
  if (!std::isfinite(header.vox_offset) || header.vox_offset < kNifti1HeaderSize + 4) {
    fail(path, "invalid vox_offset " + std::to_string(header.vox_offset) + " (at least 352)");
  }
  result.datatype = type.code;
  result.datatype_name = type.name;
  if (header.scl_slope != 0.0f && std::isfinite(header.scl_slope) &&
      std::isfinite(header.scl_inter)) {
    result.scl_slope = header.scl_slope;
    result.scl_inter = header.scl_inter;
  }
  result.volume.grid = placement(path, header, result.placement);
  result.volume.grid.dims = dims;

  const std::size_t voxels = result.volume.grid.count();
  const std::vector<unsigned char> raw =
      read_voxels(path, gzipped, header, swapped, voxels * type.bytes, type.bytes, progress);
  result.volume.values.resize(voxels);
  convert_any(type.code, raw.data(), voxels, result.scl_slope, result.scl_inter,
              result.volume.values.data());
  for (float& v : result.volume.values) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++result.non_finite;
    }
  }
  return result;
}

}  // namespace dynamesh
