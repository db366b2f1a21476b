#include "app/viewer/video_recorder.h"

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "app/render/png_file.h"

namespace dynamesh {
namespace fs = std::filesystem;
namespace {

// One word for /bin/sh, whatever the text holds.
std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

bool VideoRecorder::ffmpeg_available() {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "ffmpeg";
    std::error_code ignored;
    if (fs::is_regular_file(candidate, ignored)) return true;
    start = end + 1;
  }
  return false;
}

std::string VideoRecorder::start(const std::string& dir, const std::string& stem, int width,
                                 int height, int fps) {
  stop();
  width_ = width;
  height_ = height;
  frames_ = 0;
  fs::create_directories(dir);
  if (ffmpeg_available()) {
    final_path_ = (fs::path(dir) / (stem + ".mp4")).string();
    temp_path_ = final_path_ + ".partial";
    // Rows arrive top first (Image order). yuv420p needs even sizes: crop one pixel if odd.
    const std::string command =
        "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgba -s " + std::to_string(width) + "x" +
        std::to_string(height) + " -r " + std::to_string(fps) +
        " -i - -vf 'crop=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -f mp4 " +
        shell_quote(temp_path_);
    // An ffmpeg that exits early must not take the viewer with it: writes then fail instead.
    std::signal(SIGPIPE, SIG_IGN);
    pipe_ = ::popen(command.c_str(), "w");
    failed_ = false;
    if (pipe_ != nullptr) return "recording to " + final_path_;
  }
  frames_dir_ = (fs::path(dir) / (stem + "_frames")).string();
  fs::create_directories(frames_dir_);
  return "ffmpeg not found: recording PNG frames into " + frames_dir_;
}

void VideoRecorder::add_frame(const Image& frame) {
  if (!recording() || frame.width != width_ || frame.height != height_) return;
  if (pipe_ != nullptr) {
    failed_ =
        failed_ || std::fwrite(frame.rgba.data(), 1, frame.rgba.size(), pipe_) != frame.rgba.size();
  } else {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", frames_);
    write_png(frame, (fs::path(frames_dir_) / name).string());
  }
  ++frames_;
}

std::string VideoRecorder::stop() {
  std::string result;
  if (pipe_ != nullptr) {
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    std::error_code error;
    if (status == 0 && !failed_ && frames_ > 0) {
      fs::rename(temp_path_, final_path_, error);
      if (!error) result = final_path_;
    }
    if (result.empty()) fs::remove(temp_path_, error);
  } else if (!frames_dir_.empty()) {
    result = frames_dir_;
    frames_dir_.clear();
  }
  return result;
}

void VideoRecorder::cancel() {
  if (!recording()) return;
  failed_ = true;  // stop() then keeps no video
  const std::string frames_dir = frames_dir_;
  stop();
  std::error_code ignored;
  if (!frames_dir.empty()) fs::remove_all(frames_dir, ignored);
}

}  // namespace dynamesh
