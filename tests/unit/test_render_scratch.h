// A scratch directory for the rendering and viewer tests, under the build tree.
#pragma once

#include <unistd.h>

#include <filesystem>
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

}  // namespace dynamesh::test
