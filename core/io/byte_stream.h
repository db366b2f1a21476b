// A strict sequential reader of a plain or gzip-compressed file (zlib inflate directly, not
// gzread): a gzip stream whose CRC or length check fails, that ends before its trailer, or
// that is followed by bytes that are not another gzip member is an error, not a short read.
// The readers of user files (NIfTI volumes) use it so that a damaged file is refused rather
// than silently read as far as it goes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace dynamesh {

class ByteStream {
 public:
  // Throws std::runtime_error("cannot open ...") when the file cannot be opened.
  ByteStream(const std::filesystem::path& path, bool gzipped);
  ~ByteStream();
  ByteStream(const ByteStream&) = delete;
  ByteStream& operator=(const ByteStream&) = delete;

  // Reads up to n bytes; fewer only at the end of the data. Throws std::runtime_error with
  // the reason (e.g. "gzip data is corrupt (incorrect data check)") when the data is damaged.
  std::size_t read(void* out, std::size_t n);
  // Skips up to n bytes; returns how many were skipped.
  std::uint64_t skip(std::uint64_t n);
  // Reads to the end, checking the compressed stream; returns how many bytes were left.
  std::uint64_t drain();
  // Bytes of (uncompressed) data delivered so far.
  std::uint64_t position() const { return position_; }
  // Size of the file on disk (compressed size for gzip).
  std::uint64_t file_size() const { return file_size_; }

 private:
  struct Inflater;
  std::size_t read_plain(unsigned char* out, std::size_t n);
  std::size_t read_gzip(unsigned char* out, std::size_t n);

  std::FILE* file_ = nullptr;
  std::unique_ptr<Inflater> inflater_;
  std::uint64_t position_ = 0, file_size_ = 0;
};

}  // namespace dynamesh
