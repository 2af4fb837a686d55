#include "render/text_overlay.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>

#include "pronk/error.h"

namespace pronk::render {

struct TextOverlay::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
};

TextOverlay::TextOverlay(int pixel_height, bool bold) : pixel_height_(pixel_height), impl_(std::make_unique<Impl>()) {
  const char* font = bold ? PRONK_BOLD_FONT_FILE : PRONK_FONT_FILE;
  if (FT_Init_FreeType(&impl_->library)) throw Error("FreeType: cannot initialise the library");
  if (FT_New_Face(impl_->library, font, 0, &impl_->face)) {
    FT_Done_FreeType(impl_->library);
    throw Error(std::string(font) + ": cannot load the font (Debian package fonts-dejavu-core)");
  }
  FT_Set_Pixel_Sizes(impl_->face, 0, FT_UInt(pixel_height));
}

TextOverlay::~TextOverlay() {
  if (impl_->face) FT_Done_Face(impl_->face);
  if (impl_->library) FT_Done_FreeType(impl_->library);
}

int TextOverlay::measure(const std::string& text) {
  int x = 0;
  for (unsigned char c : text) {
    if (FT_Load_Char(impl_->face, c, FT_LOAD_DEFAULT)) continue;
    x += int(impl_->face->glyph->advance.x >> 6);
  }
  return x;
}

void TextOverlay::draw(std::vector<uint8_t>& rgba, int width, int height, int x, int y, const std::string& text,
                       const Eigen::Vector3d& rgb) {
  const int baseline = y + int(impl_->face->size->metrics.ascender >> 6);
  int pen = x;
  for (unsigned char c : text) {
    if (FT_Load_Char(impl_->face, c, FT_LOAD_RENDER)) continue;
    const FT_GlyphSlot g = impl_->face->glyph;
    for (unsigned row = 0; row < g->bitmap.rows; ++row) {
      for (unsigned col = 0; col < g->bitmap.width; ++col) {
        const int px = pen + g->bitmap_left + int(col), py = baseline - g->bitmap_top + int(row);
        if (px < 0 || py < 0 || px >= width || py >= height) continue;
        const double a = g->bitmap.buffer[row * unsigned(g->bitmap.pitch) + col] / 255.0;
        uint8_t* p = &rgba[(size_t(py) * width + px) * 4];
        for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::clamp((1 - a) * p[k] + a * 255.0 * rgb(k), 0.0, 255.0));
      }
    }
    pen += int(g->advance.x >> 6);
  }
}

void fillRect(std::vector<uint8_t>& rgba, int width, int height, int x, int y, int w, int h,
              const Eigen::Vector3d& rgb, double alpha) {
  for (int py = std::max(0, y); py < std::min(height, y + h); ++py)
    for (int px = std::max(0, x); px < std::min(width, x + w); ++px) {
      uint8_t* p = &rgba[(size_t(py) * width + px) * 4];
      for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::clamp((1 - alpha) * p[k] + alpha * 255.0 * rgb(k), 0.0, 255.0));
    }
}

}  // namespace pronk::render
