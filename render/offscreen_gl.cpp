#include "render/offscreen_gl.h"

#include <GL/osmesa.h>

#include <cstring>

#include "pronk/error.h"

namespace pronk::render {

struct OffscreenGl::Impl {
  OSMesaContext context = nullptr;
  std::vector<uint8_t> buffer;
};

OffscreenGl::OffscreenGl(int width, int height) : width_(width), height_(height), impl_(std::make_unique<Impl>()) {
  impl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!impl_->context) throw Error("OSMesa: cannot create an off-screen OpenGL context");
  impl_->buffer.resize(size_t(width) * height * 4);
  makeCurrent();
}

OffscreenGl::~OffscreenGl() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

void OffscreenGl::makeCurrent() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    throw Error("OSMesa: cannot make the context current");
  }
}

void OffscreenGl::readPixels(std::vector<uint8_t>& out) {
  glFinish();
  out.resize(impl_->buffer.size());
  const size_t row = size_t(width_) * 4;
  for (int y = 0; y < height_; ++y) {
    std::memcpy(out.data() + size_t(y) * row, impl_->buffer.data() + size_t(height_ - 1 - y) * row, row);
  }
}

}  // namespace pronk::render
