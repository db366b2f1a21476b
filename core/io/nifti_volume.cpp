#include "core/io/nifti_volume.h"

#include <nifti1_io.h>

#include "core/io/byte_stream.h"
#include "core/io/number_text.h"

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
constexpr std::size_t kMaxVoxels = std::size_t{1} << 28;
// Placements outside these bounds are refused (issue 15): no MR scanner makes voxels below
// 10 micrometres or above 10 cm, and a volume placed a kilometre away is a broken header.
constexpr double kMinVoxelMm = 0.01, kMaxVoxelMm = 100.0;
constexpr double kMinVoxelShape = 1e-2;
constexpr double kMaxWorldMm = 1e6;

// What fail() throws, told apart from the ByteStream's errors (which get the file name added).
struct NiftiError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw NiftiError("NIfTI file '" + path.string() + "': " + problem);
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

// Reads the raw 348-byte header and puts it in native byte order.
nifti_1_header read_header(const std::filesystem::path& path, ByteStream& in, bool& swapped) {
  nifti_1_header header;
  std::memset(&header, 0, sizeof header);
  const std::size_t got = in.read(&header, sizeof header);
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
                                    std::uint64_t& volumes) {
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
  volumes = 1;  // at most 32767^4 < 2^60: no overflow
  for (int i = 4; i <= ndim; ++i) volumes *= static_cast<std::uint64_t>(h.dim[i]);
  const std::size_t voxels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  if (voxels > kMaxVoxels) {
    fail(path, "volume too large: " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                   " x " + std::to_string(dims[2]) + " voxels would need about " +
                   std::to_string((voxels * 12) >> 20) + " MiB; at most " +
                   std::to_string(kMaxVoxels) + " voxels are read");
  }
  return dims;
}

Mat3 to_mat3(const mat44& m) {
  Mat3 a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = m.m[r][c];
  return a;
}

const char* placement_name(VoxelPlacement p) {
  return p == VoxelPlacement::kSform ? "sform" : p == VoxelPlacement::kQform ? "qform" : "pixdim";
}

// A placement the pipeline can work with: finite, each voxel edge between kMinVoxelMm and
// kMaxVoxelMm, and not nearly singular. The volume of a voxel over the product of its edge
// lengths is 1 for a rectangular voxel and sin(angle) for a sheared pair of axes; below
// kMinVoxelShape the voxel is a flattened sliver (axes within ~0.6 degrees of each other).
void check_placement(const std::filesystem::path& path, const VoxelGrid& grid,
                     VoxelPlacement used) {
  const std::string from = std::string(" (from the ") + placement_name(used) + ")";
  if (!grid.linear.allFinite() || !grid.offset.allFinite()) {
    fail(path, "voxel-to-world transform has non-finite entries" + from);
  }
  double edges = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double size = grid.linear.col(a).norm();
    // The header stores float: 0.01f is 0.0099999998.
    if (!(size >= kMinVoxelMm * (1 - 1e-6) && size <= kMaxVoxelMm * (1 + 1e-6))) {
      fail(path, "voxel size " + format_significant(size, 6) + " mm along axis " + "ijk"[a] + from +
                     " is outside [" + format_significant(kMinVoxelMm, 6) + ", " +
                     format_significant(kMaxVoxelMm, 6) + "] mm");
    }
    edges *= size;
  }
  const double shape = std::abs(grid.linear.determinant()) / edges;
  if (!(shape >= kMinVoxelShape)) {
    fail(path, "voxel-to-world transform is singular or nearly so" + from +
                   ": voxel volume / product of edge lengths = " + format_significant(shape, 6) +
                   " (at least " + format_significant(kMinVoxelShape, 6) + ")");
  }
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
    // nifticlib takes a pixdim that is not positive as 1; a non-finite one is a broken header.
    for (int i = 1; i <= 3; ++i)
      if (!std::isfinite(h.pixdim[i]))
        fail(path, "pixdim[" + std::to_string(i) + "] is non-finite (qform)");
    for (const float q :
         {h.quatern_b, h.quatern_c, h.quatern_d, h.qoffset_x, h.qoffset_y, h.qoffset_z})
      if (!std::isfinite(q)) fail(path, "qform quaternion or offset is non-finite");
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
  check_placement(path, grid, used);
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

// Reads the first volume's bytes (the stream stands at vox_offset), growing the buffer only
// as data arrives so that a header claiming more than the file holds costs nothing, then
// reads the rest of the file to check it holds exactly the volumes the header describes (for
// gzip this also checks the CRC and length in its trailer). Puts the voxels in native order.
std::vector<unsigned char> read_voxels(const std::filesystem::path& path, ByteStream& in,
                                       std::size_t bytes, std::uint64_t volumes,
                                       int bytes_per_voxel, bool swapped,
                                       const std::function<void(double)>& progress) {
  std::vector<unsigned char> raw;
  constexpr std::size_t kChunk = std::size_t{4} << 20;
  while (raw.size() < bytes) {
    const std::size_t before = raw.size();
    const std::size_t want = std::min(kChunk, bytes - before);
    raw.resize(before + want);
    const std::size_t n = in.read(raw.data() + before, want);
    raw.resize(before + n);
    if (n == 0) break;
    if (progress) progress(static_cast<double>(raw.size()) / static_cast<double>(bytes));
  }
  const std::uint64_t start = in.position() - raw.size();
  if (raw.size() < bytes) {
    fail(path, "truncated data: the header's dimensions need " + std::to_string(bytes) +
                   " bytes after offset " + std::to_string(start) + ", the file holds " +
                   std::to_string(raw.size()));
  }
  const std::uint64_t rest = in.drain();
  const std::uint64_t expected = (volumes - 1) * static_cast<std::uint64_t>(bytes);
  if (rest < expected) {
    fail(path, "truncated data: the header describes " + std::to_string(volumes) +
                   " volumes, the file holds " + std::to_string(1 + rest / bytes));
  }
  if (rest > expected) {
    fail(path, std::to_string(rest - expected) +
                   " bytes of trailing data after the last voxel (the dimensions do not "
                   "match the file)");
  }
  if (swapped && bytes_per_voxel > 1) {
    nifti_swap_Nbytes(bytes / bytes_per_voxel, bytes_per_voxel, raw.data());
  }
  return raw;
}

NiftiVolume read_checked(const std::filesystem::path& path, bool gzipped,
                         const std::function<void(double)>& progress) {
  ByteStream in(path, gzipped);
  bool swapped = false;
  const nifti_1_header header = read_header(path, in, swapped);
  check_magic(path, header);
  NiftiVolume result;
  std::uint64_t volumes = 1;
  const std::array<int, 3> dims = check_dimensions(path, header, volumes);
  const DatatypeInfo& type = datatype_info(path, header.datatype);
  if (header.bitpix != 8 * type.bytes) {
    fail(path, "bitpix " + std::to_string(header.bitpix) + " does not match datatype " + type.name);
  }
  // vox_offset is a float holding a byte offset: a whole number past the header (and its
  // 4 extension bytes) that fits the file.
  const double offset = header.vox_offset;
  if (!std::isfinite(offset) || offset < kNifti1HeaderSize + 4 || offset != std::floor(offset) ||
      offset > 1e15) {
    fail(path,
         "invalid vox_offset " + format_significant(offset, 6) + " (a whole number, at least 352)");
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
  // Its far corner, not only the origin: a broken offset or a huge volume of big voxels.
  const double reach = result.volume.grid.offset.norm() +
                       result.volume.grid.linear.norm() *
                           static_cast<double>(*std::max_element(dims.begin(), dims.end()));
  if (!(reach < kMaxWorldMm)) {
    fail(path, "voxel-to-world transform places the volume " + format_significant(reach, 6) +
                   " mm from the origin (at most " + format_significant(kMaxWorldMm, 6) + ")");
  }

  const std::size_t voxels = result.volume.grid.count();
  const std::size_t bytes = voxels * static_cast<std::size_t>(type.bytes);
  // A plain file's size is known: a header claiming more data than the file holds is refused
  // before anything is allocated (gzip data is checked as it arrives, read_voxels).
  const auto start = static_cast<std::uint64_t>(offset);
  if (!gzipped && start + bytes > in.file_size()) {
    fail(path, "truncated data: the header's dimensions " + std::to_string(dims[0]) + " x " +
                   std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " of " + type.name +
                   " need " + std::to_string(bytes) + " bytes after offset " +
                   std::to_string(start) + ", the file has " +
                   std::to_string(in.file_size() > start ? in.file_size() - start : 0));
  }
  const std::uint64_t gap = start - in.position();
  if (in.skip(gap) < gap) {
    fail(path, "truncated file: it ends before vox_offset " + std::to_string(start));
  }
  result.volumes_in_file = static_cast<int>(std::min<std::uint64_t>(volumes, INT32_MAX));
  const std::vector<unsigned char> raw =
      read_voxels(path, in, bytes, volumes, type.bytes, swapped, progress);
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
  try {
    return read_checked(path, gzipped, progress);
  } catch (const NiftiError&) {
    throw;
  } catch (const std::runtime_error& e) {  // from ByteStream: damaged or unreadable data
    fail(path, e.what());
  }
}

}  // namespace dynamesh
