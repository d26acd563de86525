// A current OpenGL context for MuJoCo's renderer, behind a small interface so that the
// off-screen backend (OSMesa today) can be swapped without touching the renderer.
#pragma once

#include <memory>
#include <string>

namespace msb {

/// An OpenGL context that can be made current on the calling thread.
class GlContext {
 public:
  virtual ~GlContext() = default;
  /// Makes the context current; throws std::runtime_error on failure.
  virtual void makeCurrent() = 0;
  /// Human-readable GL renderer and version strings (for metrics.json).
  virtual std::string description() const = 0;
};

/// Creates an OSMesa (software, llvmpipe) context with a default framebuffer of the given
/// size, made current. Throws std::runtime_error if OSMesa is unavailable.
std::unique_ptr<GlContext> makeOsMesaContext(int width, int height);

}  // namespace msb
