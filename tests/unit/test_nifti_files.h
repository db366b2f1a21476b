// Test helper: writes NIfTI-1 files byte by byte (the 348-byte header of nifti1.h, 4 bytes
// of extension flags, then the voxels), independently of the reader under test. znzlib is
// used only as a gzip stream for .nii.gz.
#pragma once

#include <unistd.h>

#include <nifti1.h>
#include <znzlib.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh::test {

// A scratch directory under the build tree, emptied at construction.
// Per process: CTest runs tests in parallel processes, and two writing the same file race.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(DYNAMESH_BINARY_DIR) / "test_scratch" /
                                    (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline nifti_1_header make_header(const std::vector<int>& dims, int datatype, int bitpix) {
  nifti_1_header h;
  std::memset(&h, 0, sizeof h);
  h.sizeof_hdr = 348;
  h.dim[0] = static_cast<short>(dims.size());
  for (std::size_t i = 0; i < 7; ++i) {
    h.dim[i + 1] = static_cast<short>(i < dims.size() ? dims[i] : 1);
    h.pixdim[i + 1] = 1.0f;
  }
  h.pixdim[0] = 1.0f;  // qfac
  h.datatype = static_cast<short>(datatype);
  h.bitpix = static_cast<short>(bitpix);
  h.vox_offset = 352.0f;
  std::memcpy(h.magic, "n+1", 4);
  return h;
}

// Sets the sform (code 2, "aligned anat") to p = linear * ijk + offset.
inline void set_sform(nifti_1_header& h, const Mat3& linear, const Vec3& offset) {
  h.sform_code = 2;
  float* rows[3] = {h.srow_x, h.srow_y, h.srow_z};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rows[r][c] = static_cast<float>(linear(r, c));
    rows[r][3] = static_cast<float>(offset[r]);
  }
}

// Writes header + 4 zero extension bytes + data, gzip-compressed when the name ends in .gz.
// `header_bytes` < 348 writes a truncated header, `data_bytes` may cut the data short.
inline void write_nifti(const std::filesystem::path& path, const nifti_1_header& h,
                        const void* data, std::size_t data_bytes,
                        std::size_t header_bytes = sizeof(nifti_1_header)) {
  const bool gz = path.extension() == ".gz";
  znzFile f = znzopen(path.c_str(), "wb", gz ? 1 : 0);
  if (znz_isnull(f)) throw std::runtime_error("cannot write " + path.string());
  znzwrite(&h, 1, header_bytes, f);
  if (header_bytes == sizeof(nifti_1_header)) {
    const char extension[4] = {0, 0, 0, 0};
    znzwrite(extension, 1, 4, f);
    if (data_bytes > 0) znzwrite(data, 1, data_bytes, f);
  }
  znzclose(f);
}

template <class T>
void write_nifti(const std::filesystem::path& path, const nifti_1_header& h,
                 const std::vector<T>& values) {
  write_nifti(path, h, values.data(), values.size() * sizeof(T));
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Reverses the byte order of the header's multi-byte fields that the reader uses (a
// big-endian file as written on another machine).
inline void swap16(void* p) {
  auto* b = static_cast<unsigned char*>(p);
  std::swap(b[0], b[1]);
}
inline void swap32(void* p) {
  auto* b = static_cast<unsigned char*>(p);
  std::swap(b[0], b[3]);
  std::swap(b[1], b[2]);
}

}  // namespace dynamesh::test
