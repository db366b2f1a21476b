// Records frames of the window: an MP4 through ffmpeg (frames piped as raw RGBA) when ffmpeg
// is installed, otherwise a numbered PNG sequence in a directory. The MP4 is written under a
// temporary name and renamed when recording stops cleanly.
#pragma once

#include <cstdio>
#include <string>

#include "app/render/image.h"

namespace dynamesh {

class VideoRecorder {
 public:
  VideoRecorder() = default;
  ~VideoRecorder() { stop(); }
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  // Starts a recording named `<dir>/<stem>.mp4` (or the directory `<dir>/<stem>_frames/`).
  // Returns a line describing where it goes, or throws std::runtime_error.
  std::string start(const std::string& dir, const std::string& stem, int width, int height,
                    int fps);
  // Frames of another size than the first are skipped (the window was resized).
  void add_frame(const Image& frame);
  // Finishes the file; returns its path (empty when nothing was recording).
  std::string stop();
  // Stops and removes what was recorded (a scripted run that failed keeps no video).
  void cancel();

  bool recording() const { return pipe_ != nullptr || !frames_dir_.empty(); }
  int frames() const { return frames_; }

 private:
  static bool ffmpeg_available();

  std::FILE* pipe_ = nullptr;
  std::string final_path_, temp_path_, frames_dir_;
  int width_ = 0, height_ = 0, frames_ = 0;
  bool failed_ = false;  // ffmpeg stopped taking frames
};

}  // namespace dynamesh
