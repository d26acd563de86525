#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "sim/render/gl_context.h"

namespace msb {
namespace {

// OSMesa context rendering into a client-memory RGBA buffer (MuJoCo renders off-screen into
// its own framebuffer object; this buffer only backs the default framebuffer).
class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height)
      : width_(width), height_(height), buffer_(static_cast<size_t>(width) * height * 4) {
    ctx_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: could not create a context");
    makeCurrent();
  }
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }

  void makeCurrent() override {
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw std::runtime_error("OSMesa: could not make the context current");
  }

  std::string description() const override {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return std::string(renderer ? renderer : "?") + " / " + (version ? version : "?");
  }

 private:
  OSMesaContext ctx_ = nullptr;
  int width_, height_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> makeOsMesaContext(int width, int height) {
  return std::make_unique<OsMesaContext>(width, height);
}

}  // namespace msb
