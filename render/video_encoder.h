// H.264 MP4 through libavcodec/libavformat. Frames are encoded as they come, so
// memory stays bounded however long the video.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pronk::render {

class VideoEncoder {
 public:
  // Opens `path` for writing. Throws pronk::Error naming the path for an
  // unwritable file, odd or non-positive sizes, a non-positive fps, or a
  // missing H.264 encoder.
  VideoEncoder(const std::string& path, int width, int height, double fps);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // One RGBA frame, rows top to bottom.
  void addFrame(const std::vector<uint8_t>& rgba);
  // Flushes the encoder and writes the trailer; called by the destructor too.
  void finish();
  int frames() const { return frames_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int frames_ = 0;
};

// Writes one RGBA frame (rows top to bottom) as a PNG, through libavcodec's
// PNG encoder. Throws Error naming the path when it cannot.
void writePng(const std::string& path, const std::vector<uint8_t>& rgba, int width, int height);

// What a video file holds, read back with libavformat (for tests and reports).
struct VideoInfo {
  std::string codec;
  int width = 0, height = 0;
  long frames = 0;
  double duration_s = 0;
};
VideoInfo probeVideo(const std::string& path);

}  // namespace pronk::render
