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
  // Opens PATH.partial for writing; finish() renames it over `path`. Throws
  // pronk::Error naming the path for an unwritable file, something other than
  // a regular file at `path`, odd or non-positive sizes, a non-positive fps, or
  // a missing H.264 encoder.
  VideoEncoder(const std::string& path, int width, int height, double fps);
  // Without finish(): PATH.partial is removed and `path` left as it was.
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // One RGBA frame, rows top to bottom.
  void addFrame(const std::vector<uint8_t>& rgba);
  // Flushes the encoder, writes the trailer and renames the whole video into
  // place. Throws Error when any write failed (a full disk, a file-size limit):
  // then no video is left, the partial file removed.
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
