#include "core/io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace dynamesh {
namespace {

// Partial files open right now, for the signal handler: fixed slots of plain characters,
// since a handler may not allocate or lock. A slot is claimed with its flag, filled, then
// published; the handler reads only published slots.
constexpr std::size_t kSlots = 64, kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 published
  char path[kPathMax];
};
std::array<Slot, kSlots> g_partials;

int register_partial(const std::string& path) {
  if (path.size() + 1 > kPathMax) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_partials[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_partials[i].path, path.c_str(), path.size() + 1);
    g_partials[i].state.store(2);
    return static_cast<int>(i);
  }
  return -1;  // more than kSlots open at once: this one is only removed by the destructor
}

void unregister_partial(int slot) {
  if (slot >= 0) g_partials[static_cast<std::size_t>(slot)].state.store(0);
}

extern "C" void remove_partials_and_die(int signal) {
  for (Slot& s : g_partials)
    if (s.state.load() == 2) ::unlink(s.path);
  // End as the signal would have: the default action, re-raised.
  std::signal(signal, SIG_DFL);
  ::raise(signal);
}

}  // namespace

namespace {

enum class Special { kNo, kStdout, kStderr, kInPlace };

// What kind of target `path` is: following every symbolic link, a name that is or leads
// through /dev or /proc (/dev/stdout -> /proc/self/fd/1 -> the shell's redirection) stands
// for a file this process may already have open, which must be written, not replaced; its
// standard output or error are written through their streams, which share the file's offset
// (a second opening of a redirected stdout would write over what std::cout writes).
Special special_kind(const std::string& path) {
  namespace fs = std::filesystem;
  if (path == "-") return Special::kStdout;
  fs::path p = path;
  for (int hop = 0; hop < 40; ++hop) {
    const std::string text = fs::absolute(p).lexically_normal().string();
    for (const char* prefix : {"/dev/fd/", "/proc/self/fd/", "/dev/std"}) {
      const std::string rest =
          text.rfind(prefix, 0) == 0 ? text.substr(std::strlen(prefix)) : std::string();
      if (rest == "1" || rest == "out") return Special::kStdout;
      if (rest == "2" || rest == "err") return Special::kStderr;
    }
    const bool shm = text.rfind("/dev/shm/", 0) == 0;  // a file system like any other
    if ((text.rfind("/dev/", 0) == 0 && !shm) || text.rfind("/proc/", 0) == 0)
      return Special::kInPlace;
    std::error_code ec;
    const fs::file_status link = fs::symlink_status(p, ec);
    if (ec || !fs::exists(link)) return Special::kNo;  // a new file
    if (!fs::is_symlink(link))
      return !fs::is_regular_file(link) && !fs::is_directory(link) ? Special::kInPlace
                                                                   : Special::kNo;
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) return Special::kNo;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return Special::kNo;
}

}  // namespace

bool is_special_output(const std::string& path) {
  return special_kind(path) != Special::kNo;
}

AtomicFile::AtomicFile(std::string path, std::ios::openmode mode) : path_(std::move(path)) {
  const Special kind = special_kind(path_);
  if (kind == Special::kStdout || kind == Special::kStderr) {
    out_ = kind == Special::kStdout ? static_cast<std::ostream*>(&std::cout) : &std::cerr;
    direct_ = true;
    return;
  }
  direct_ = kind == Special::kInPlace;
  // A link to a regular file: its target is replaced, so that the link stays a link.
  std::error_code ec;
  if (!direct_ && std::filesystem::is_symlink(std::filesystem::symlink_status(path_, ec)))
    target_ = std::filesystem::canonical(path_, ec).string();
  if (target_.empty()) target_ = path_;
  // A directory would only refuse the rename at the end of the run (issue 15): say so now.
  if (!direct_ && std::filesystem::is_directory(target_, ec))
    throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(EISDIR));
  // A special file is opened without truncation (a FIFO or a device has nothing to cut).
  partial_ = direct_ ? path_ : target_ + ".partial";
  // Registered before it exists: a signal between the file's creation and its registration
  // left it behind (CliHostile.SignalsLeaveNoPartialFile, once, under load: an empty
  // frame_00003.png.partial after SIGTERM). The handler unlinking a name not created yet is
  // harmless, and it ends the process, so the file is not created after it either.
  if (!direct_) signal_slot_ = register_partial(partial_);
  file_.open(partial_, direct_ ? (mode | std::ios::out) : (mode | std::ios::out | std::ios::trunc));
  if (!file_) {
    const int error = errno;
    unregister_partial(signal_slot_);
    throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(error));
  }
}

AtomicFile::~AtomicFile() {
  if (committed_ || direct_) {
    if (direct_) out_->flush();
    return;
  }
  file_.close();
  std::remove(partial_.c_str());
  unregister_partial(signal_slot_);
}

void AtomicFile::commit() {
  out_->flush();
  const bool written = static_cast<bool>(*out_);
  if (direct_) {
    committed_ = true;
    if (!written) throw std::runtime_error("cannot write " + path_ + ": write failed");
    return;
  }
  file_.close();
  const bool renamed = written && std::rename(partial_.c_str(), target_.c_str()) == 0;
  const std::string reason = written ? std::strerror(errno) : "write failed";
  unregister_partial(signal_slot_);
  if (!renamed) {
    std::remove(partial_.c_str());
    throw std::runtime_error("cannot write " + path_ + ": " + reason);
  }
  committed_ = true;
}

void remove_partial_files_on_signal() {
  struct sigaction action {};
  action.sa_handler = remove_partials_and_die;
  sigemptyset(&action.sa_mask);
  // SIGHUP (the terminal closed) and SIGPIPE (stdout's reader went away: `... | head`) end
  // the process too, and left *.partial files behind (issue 15, session 4).
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction current {};
    ::sigaction(signal, nullptr, &current);
    // What the parent chose to ignore stays ignored (nohup, a background job's SIGINT).
    if (current.sa_handler != SIG_IGN) ::sigaction(signal, &action, nullptr);
  }
}

}  // namespace dynamesh
