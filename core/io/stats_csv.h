// Per-step statistics as CSV, one row per step (the CLI's --stats). A regular file appears
// under its name only when close() succeeds; "-" (stdout), /dev/stdout and FIFOs get the rows
// as they come (AtomicFile).
#pragma once

#include <memory>
#include <string>

#include "core/adapt/step_stats.h"
#include "core/io/atomic_file.h"

namespace dynamesh {

class StatsCsvWriter {
 public:
  // Throws std::runtime_error naming the file when it cannot be created.
  explicit StatsCsvWriter(const std::string& path);
  void write(const StepStats& s, std::size_t total_splits, std::size_t total_welds);
  void close();

  static const char* header();

 private:
  AtomicFile file_;
};

}  // namespace dynamesh
