#include "core/io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace dynamesh {

AtomicFile::AtomicFile(std::string path, std::ios::openmode mode)
    : path_(std::move(path)), partial_(path_ + ".partial") {
  out_.open(partial_, mode | std::ios::out | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::remove(partial_.c_str());
}

void AtomicFile::commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || std::rename(partial_.c_str(), path_.c_str()) != 0) {
    const std::string reason = written ? std::strerror(errno) : "write failed";
    std::remove(partial_.c_str());
    throw std::runtime_error("cannot write " + path_ + ": " + reason);
  }
  committed_ = true;
}

}  // namespace dynamesh
