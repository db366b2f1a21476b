// A scratch directory for the rendering and viewer tests, under the build tree.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace dynamesh::test {

// Emptied at construction. Per process: CTest runs tests in parallel processes, and two
// writing the same file race.
inline std::filesystem::path render_scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(DYNAMESH_BINARY_DIR) / "test_scratch" /
                                    (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A whole file as text (empty when missing).
inline std::string slurp_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace dynamesh::test
