// The renderer seam of the loop: anything that turns the simulation state and a camera pose
// into a grey-scale image. The fisheye cube-map renderer (OSMesa) is the benchmark's renderer;
// the null renderer below draws nothing and serves loop tests that need no images (with the
// oracle feature source, or with perception off).
#pragma once

#include <mujoco/mujoco.h>

#include <string>

#include "core/camera/fisheye_camera.h"
#include "core/common/messages.h"

namespace msb {

/// Wall time of the parts of one rendered frame (recorded, never used for decisions).
struct RenderTiming {
  double scene_ms = 0.0;     ///< mjv_updateScene
  double render_ms = 0.0;    ///< mjr_render of all faces + glFinish
  double readback_ms = 0.0;  ///< glReadPixels of the atlas
  double remap_ms = 0.0;     ///< grey conversion + lookup-table remap
  double totalMs() const { return scene_ms + render_ms + readback_ms + remap_ms; }
};

/// Renders camera frames of a MuJoCo simulation.
class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;
  /// Renders the image seen from the camera pose T_W_C (optical frame) for the state in
  /// `data` into `frame` (pixels, size; tick/time/pose are left to the caller).
  virtual void render(const mjData* data, const Pose& T_W_C, CameraFrame* frame, RenderTiming* timing = nullptr) = 0;
  /// What renders (GL renderer and version, or "null").
  virtual std::string description() const = 0;
};

/// A renderer that draws nothing: every frame is a uniform mid-grey image of the camera's size
/// (no GL context). Named for what it is; never the default of a benchmark run.
class NullRenderer final : public FrameRenderer {
 public:
  /// Frames get the camera's image size.
  explicit NullRenderer(const FisheyeCamera& camera) : width_(camera.width()), height_(camera.height()) {}
  void render(const mjData*, const Pose&, CameraFrame* frame, RenderTiming* timing) override {
    frame->width = width_;
    frame->height = height_;
    frame->pixels.assign(size_t(width_) * size_t(height_), 128);
    if (timing) *timing = RenderTiming{};
  }
  std::string description() const override { return "null renderer (no images)"; }

 private:
  int width_, height_;
};

}  // namespace msb
