// Text and simple shapes drawn into an RGBA frame (rows top to bottom) after
// rendering, with FreeType and a Debian font (fonts-dejavu-core).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pronk::render {

class TextOverlay {
 public:
  // Throws pronk::Error naming the font file when FreeType cannot load it.
  explicit TextOverlay(int pixel_height, bool bold = false);
  ~TextOverlay();
  TextOverlay(const TextOverlay&) = delete;
  TextOverlay& operator=(const TextOverlay&) = delete;

  // Width in pixels of `text`.
  int measure(const std::string& text);
  // Draws `text` with its top-left corner at (x, y), blended with `rgb`.
  void draw(std::vector<uint8_t>& rgba, int width, int height, int x, int y, const std::string& text,
            const Eigen::Vector3d& rgb);
  int lineHeight() const { return pixel_height_; }

 private:
  int pixel_height_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A filled rectangle blended with `alpha` (0..1).
void fillRect(std::vector<uint8_t>& rgba, int width, int height, int x, int y, int w, int h,
              const Eigen::Vector3d& rgb, double alpha = 1.0);

}  // namespace pronk::render
