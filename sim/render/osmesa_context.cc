#include <GL/osmesa.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/render/gl_context.h"

namespace msb {
namespace {

// llvmpipe rasterises in the thread that calls GL: no worker threads (LP_NUM_THREADS=0), whatever
// the environment says. Mesa 22.3's llvmpipe (Debian 12) has a use-after-free between its
// rasteriser threads and the GL thread: a worker signals a fence (pthread_cond_broadcast on the
// fence's condition variable) after the GL thread has dropped the last reference and freed it.
// The broadcast then writes into freed heap memory, which corrupts malloc's lists and crashes a
// mission much later inside malloc or free (docs/robustness.md, "The heap corruption"). Without
// workers there is no second thread to race, and the frames are the same (llvmpipe's output
// does not depend on its thread count); it costs nothing measurable (docs/performance.md).
// llvmpipe reads the variable when OSMesa creates its screen, at the first context.
void rasteriseInTheCallingThread() {
  static const bool once = [] {
    const char* given = std::getenv("LP_NUM_THREADS");
    if (given && std::string(given) != "0")
      std::fprintf(stderr,
                   "msbench: LP_NUM_THREADS=%s ignored: llvmpipe rasterises in the rendering thread "
                   "(worker threads race in Mesa 22.3; docs/robustness.md)\n",
                   given);
    return ::setenv("LP_NUM_THREADS", "0", 1) == 0;
  }();
  (void)once;
}

// OSMesa context rendering into a client-memory RGBA buffer (MuJoCo renders off-screen into
// its own framebuffer object; this buffer only backs the default framebuffer).
class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height)
      : width_(width), height_(height), buffer_(static_cast<size_t>(width) * height * 4) {
    rasteriseInTheCallingThread();
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
