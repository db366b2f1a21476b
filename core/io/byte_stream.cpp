#include "core/io/byte_stream.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

namespace dynamesh {

struct ByteStream::Inflater {
  z_stream z{};
  std::array<unsigned char, 1 << 16> in{};
  bool started = false;     // inflateInit2 has been called
  bool member_end = false;  // the last member's trailer has been checked
};

ByteStream::ByteStream(const std::filesystem::path& path, bool gzipped) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw std::runtime_error("cannot open for reading");
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path, ec);
  if (ec) file_size_ = 0;
  if (gzipped) {
    inflater_ = std::make_unique<Inflater>();
    // 16 + MAX_WBITS: gzip wrapper only, with its CRC-32 and length checks.
    if (inflateInit2(&inflater_->z, 16 + MAX_WBITS) != Z_OK) {
      std::fclose(file_);
      throw std::runtime_error("cannot start gzip decompression");
    }
    inflater_->started = true;
  }
}

ByteStream::~ByteStream() {
  if (inflater_ && inflater_->started) inflateEnd(&inflater_->z);
  if (file_) std::fclose(file_);
}

std::size_t ByteStream::read(void* out, std::size_t n) {
  auto* bytes = static_cast<unsigned char*>(out);
  const std::size_t got = inflater_ ? read_gzip(bytes, n) : read_plain(bytes, n);
  position_ += got;
  return got;
}

std::size_t ByteStream::read_plain(unsigned char* out, std::size_t n) {
  const std::size_t got = std::fread(out, 1, n, file_);
  if (got < n && std::ferror(file_)) throw std::runtime_error("read error");
  return got;
}

std::size_t ByteStream::read_gzip(unsigned char* out, std::size_t n) {
  Inflater& s = *inflater_;
  if (position_ == 0 && s.z.total_in == 0 && s.z.avail_in == 0) {
    s.z.avail_in = static_cast<uInt>(std::fread(s.in.data(), 1, s.in.size(), file_));
    s.z.next_in = s.in.data();
    if (s.z.avail_in < 2 || s.z.next_in[0] != 0x1f || s.z.next_in[1] != 0x8b)
      throw std::runtime_error("named .gz but not gzip-compressed");
  }
  std::size_t got = 0;
  while (got < n) {
    if (s.member_end) {
      // After a member's trailer: end of file, or another member (gzip allows several
      // concatenated); anything else is trailing garbage.
      if (s.z.avail_in == 0) {
        s.z.avail_in = static_cast<uInt>(std::fread(s.in.data(), 1, s.in.size(), file_));
        s.z.next_in = s.in.data();
        if (s.z.avail_in == 0) return got;
      }
      if (s.z.next_in[0] != 0x1f)
        throw std::runtime_error(
            "the gzip stream is followed by bytes that are not gzip data (trailing data)");
      inflateReset(&s.z);
      s.member_end = false;
    }
    if (s.z.avail_in == 0) {
      s.z.avail_in = static_cast<uInt>(std::fread(s.in.data(), 1, s.in.size(), file_));
      s.z.next_in = s.in.data();
      if (s.z.avail_in == 0) {
        if (std::ferror(file_)) throw std::runtime_error("read error");
        throw std::runtime_error(
            "gzip data ends early (the file is truncated: no end-of-stream trailer)");
      }
    }
    const std::size_t want = std::min<std::size_t>(n - got, 1u << 30);
    s.z.next_out = out + got;
    s.z.avail_out = static_cast<uInt>(want);
    const int rc = inflate(&s.z, Z_NO_FLUSH);
    got += want - s.z.avail_out;
    if (rc == Z_STREAM_END) {
      s.member_end = true;
    } else if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT) {
      throw std::runtime_error(std::string("gzip data is corrupt (") +
                               (s.z.msg ? s.z.msg : "invalid data") + ")");
    } else if (rc == Z_MEM_ERROR) {
      throw std::runtime_error("out of memory while decompressing");
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      throw std::runtime_error("gzip decompression failed (zlib code " + std::to_string(rc) + ")");
    }
  }
  return got;
}

std::uint64_t ByteStream::skip(std::uint64_t n) {
  if (!inflater_) {  // a plain file: seek, within the file
    const long at = std::ftell(file_);
    const std::uint64_t left = at >= 0 && file_size_ > static_cast<std::uint64_t>(at)
                                   ? file_size_ - static_cast<std::uint64_t>(at)
                                   : 0;
    const std::uint64_t k = std::min(n, left);
    if (k > 0 && std::fseek(file_, static_cast<long>(k), SEEK_CUR) != 0)
      throw std::runtime_error("seek error");
    position_ += k;
    return k;
  }
  std::array<unsigned char, 1 << 16> buffer;
  std::uint64_t skipped = 0;
  while (skipped < n) {
    const std::size_t want =
        static_cast<std::size_t>(std::min<std::uint64_t>(n - skipped, buffer.size()));
    const std::size_t got = read(buffer.data(), want);
    skipped += got;
    if (got < want) break;
  }
  return skipped;
}

std::uint64_t ByteStream::drain() {
  return skip(UINT64_MAX);
}

}  // namespace dynamesh
