// Fuzz helper: the readers under test take a file name (their extension picks the format), so
// each input is written to a per-process file in a RAM-backed directory when there is one.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace dynamesh::fuzz {

inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& ext) {
  static const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                               ? "/dev/shm"
                                               : std::filesystem::temp_directory_path();
  const std::string path = (dir / ("dynamesh_fuzz_" + std::to_string(::getpid()) + ext)).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace dynamesh::fuzz
