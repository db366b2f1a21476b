// AtomicFile: an output file that appears under its name only once it is complete.
// Writes to a regular file (or a name not yet taken) go to "<path>.partial"; commit()
// flushes and renames it; destruction without commit() removes the partial file. While it is
// open, the partial name is registered with remove_partial_files_on_signal(), so Ctrl-C or
// SIGTERM does not leave it behind either.
//
// Special targets are written directly, never replaced: "-" is standard output, and an
// existing path that is not a regular file (/dev/stdout, a FIFO, a terminal) is opened and
// written in place. Renaming a temporary file over them would replace the device node (run
// as root) or fail. Such a target shows what was written so far when the run fails.
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

  std::ostream& stream() { return *out_; }
  // Throws std::runtime_error when writing or renaming failed.
  void commit();
  // True when the target is written in place (standard output, a device, a FIFO).
  bool direct() const { return direct_; }

 private:
  std::string path_, target_, partial_;  // target_: path_ after symbolic links
  std::ofstream file_;
  std::ostream* out_ = &file_;
  bool direct_ = false;
  bool committed_ = false;
  int signal_slot_ = -1;  // where the partial name is registered for the signal handler
};

// True for "-", for existing paths that are neither regular files nor directories, and for
// paths that are or lead (through symbolic links) into /dev or /proc (/dev/stdout).
bool is_special_output(const std::string& path);

// Installs SIGINT, SIGTERM, SIGHUP and SIGPIPE handlers that remove every registered partial
// file, then end the process as the signal would have (status 128 + signal); a signal the
// parent set to be ignored stays ignored. Call once, early, from main.
void remove_partial_files_on_signal();

}  // namespace dynamesh
