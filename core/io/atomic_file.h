// AtomicFile: an output file that appears under its name only once it is complete.
// Writes go to "<path>.partial"; commit() flushes and renames it; destruction without
// commit() removes the partial file.
#pragma once

#include <fstream>
#include <string>

namespace dynamesh {

class AtomicFile {
 public:
  // Throws std::runtime_error naming the path when it cannot be opened.
  explicit AtomicFile(std::string path, std::ios::openmode mode = std::ios::out);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  // Throws std::runtime_error when writing or renaming failed.
  void commit();

 private:
  std::string path_, partial_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace dynamesh
