// An OSMesa (software OpenGL) context with its own colour buffer: no display,
// no GPU. llvmpipe renders on every core (LP_NUM_THREADS limits it).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace pronk::render {

class OffscreenGl {
 public:
  // Throws pronk::Error when OSMesa cannot create the context.
  OffscreenGl(int width, int height);
  ~OffscreenGl();
  OffscreenGl(const OffscreenGl&) = delete;
  OffscreenGl& operator=(const OffscreenGl&) = delete;

  void makeCurrent();
  // The finished frame, RGBA, rows top to bottom (OpenGL's are bottom-up).
  void readPixels(std::vector<uint8_t>& rgba_top_down);
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pronk::render
