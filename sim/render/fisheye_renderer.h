// Fisheye rendering with MuJoCo's mjr_* renderer in an off-screen context.
//
// MuJoCo renders pinhole views only, so the fisheye image is assembled from the faces of a cube
// map around the camera (front, right, left, down, up in the optical frame). Each face is a
// 90° pinhole view with focal length f_face = face_focal_ratio · fx (pixels per unit tangent),
// but only the part of the face the fisheye actually sees is rendered: its rectangle is taken
// from the lookup table itself, plus a 2-pixel margin for bilinear sampling. Each face is drawn
// into a framebuffer of its own (render.framebuffer_per_face, the default: a whole-buffer clear
// instead of MuJoCo's scissored clear of a shared buffer) and read back into its rectangle of one
// atlas image; a lookup table built once maps every fisheye pixel to atlas coordinates (the
// fixed-point bilinear remap of cv::remap). With framebuffer_per_face off, all rectangles are
// drawn into MuJoCo's one off-screen buffer and read back at once (bench-sim compares the two).
// The renderer draws from its own copy of the model: its visual settings never reach physics.
// Each fisheye pixel samples exactly one face, so there are no blending seams; with
// ambient-only lighting, shading does not depend on the face either.
//
// Far clip: each face's frustum ends at the camera's clip_far_m (40 m, the reference's Gazebo
// camera, which clips its cube faces the same way); the pixels nothing was drawn into are then
// painted with the backdrop colour (the sky's, the fog's in fog, black without a sky) by one
// quad at the far plane that passes the depth test only where the cleared depth remains.
//
// Resolution: at the image centre the fisheye needs fx pixels per radian; a face gives f_face at
// its centre and 2·f_face at its edges. face_focal_ratio = 1 matches the front and up/down faces
// to the fisheye (within 5 %); near θ = 90° the fisheye's tangential resolution is 1.65·fx, so
// the side faces are up to 1.65× coarser there (docs/performance.md). Smaller ratios trade
// sharpness for speed (see bench-sim).
//
// Per-face culling: the cost of a face is dominated by the geoms submitted, not by its pixels
// (docs/performance.md), so each face draws only the geoms whose bounding sphere (the model's
// rbound) meets its frustum, and the finite planes (ground, sky) whose rectangle does. Nothing
// casts shadows or reflects, and the order of the remaining geoms is kept, so the pixels are the
// same.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "sim/render/fixed_point_remap.h"
#include "sim/render/frame_renderer.h"
#include "sim/render/gl_context.h"
#include "sim/render/render_conditions.h"

namespace msb {

/// Geom group of sky planes (sim/world's geom_groups::kSky; sim/render does not include it).
inline constexpr int kSkyGeomGroup = 5;

/// Benchmark render settings (docs/architecture.md §5).
struct FisheyeRendererConfig {
  double face_focal_ratio = 1.0;           ///< cube-face focal length / fisheye fx
  double ambient = 0.9;                    ///< headlight ambient intensity (no diffuse/specular)
  int tessellation_slices = 12;            ///< MuJoCo quality.numslices (coarse)
  int tessellation_stacks = 8;             ///< MuJoCo quality.numstacks (coarse)
  double plane_grid_m = 20.0;              ///< minimum rendering grid spacing of planes
  double near_clip_m = 0.03;               ///< near clipping distance
  bool read_red_channel_only = false;      ///< read one channel (exact for grey-scale worlds)
  int max_visible_geom_group = 2;          ///< groups above are not drawn (3: vehicle, 4: collision-only)
  bool sky = true;                         ///< draw the world's sky planes (outdoor worlds; else black)
  bool sun = true;                         ///< use the world's directional lights (outdoor worlds' sun)
  double sun_ambient = 0.55;               ///< headlight ambient when the sun is on
  RenderConditions conditions;             ///< light and visibility (docs/conditions.md)
  bool cull_per_face = true;               ///< draw in each face only geoms whose bounding sphere meets
                                           ///< its frustum (same pixels, fewer draw calls)
  bool trilinear_textures = false;         ///< true: blend two mip levels per texture sample (MuJoCo's
                                           ///< own setting); false: the nearest mip level, bilinear in
                                           ///< it (≈ 0.8× the frame, same sharpness and tracking)
  bool single_channel_textures = true;     ///< keep grey textures as one byte per texel instead of
                                           ///< MuJoCo's RGB (same texel values and pixels)
  bool framebuffer_per_face = true;        ///< render each face into its own framebuffer, so that
                                           ///< MuJoCo's clear covers a whole buffer (fast in llvmpipe)
  bool single_channel_framebuffer = true;  ///< with framebuffer_per_face, a one-channel colour
                                           ///< buffer when the model renders grey (same pixels)

  /// The keys, each once with the values it accepts (`conditions` is a section of its own in a flight).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("face_focal_ratio", s.face_focal_ratio, Limits::range(0.25, 2.0));
    v.key("ambient", s.ambient, Limits::range(0.05, 1.0));
    v.key("tessellation_slices", s.tessellation_slices, Limits::range(4, 100));
    v.key("tessellation_stacks", s.tessellation_stacks, Limits::range(4, 100));
    v.key("plane_grid_m", s.plane_grid_m, Limits::nonNegative());
    v.key("near_clip_m", s.near_clip_m, Limits::range(1e-4, 1.0));
    v.key("read_red_channel_only", s.read_red_channel_only);
    v.key("max_visible_geom_group", s.max_visible_geom_group, Limits::range(0, mjNGROUP - 1));
    v.key("sky", s.sky);
    v.key("sun", s.sun);
    v.key("sun_ambient", s.sun_ambient, Limits::range(0.0, 1.0));
    v.key("cull_per_face", s.cull_per_face);
    v.key("trilinear_textures", s.trilinear_textures);
    v.key("framebuffer_per_face", s.framebuffer_per_face);
    v.key("single_channel_textures", s.single_channel_textures);
    v.key("single_channel_framebuffer", s.single_channel_framebuffer);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Whether every colour `m` can render is grey (R = G = B): geom, material and skin colours,
/// lights, headlight, fog, haze and every texel. Such a model renders R = G = B in every pixel.
bool modelRendersGrey(const mjModel* m);

/// One cube face as rendered: orientation and its rectangle in face and atlas pixels.
struct CubeFace {
  std::string name;               ///< front, right, left, down, up
  Mat3 R_C_F;                     ///< face frame (z = face normal, x right, y down) in camera frame
  double tan_x0 = 0, tan_y0 = 0;  ///< top-left corner of the rendered rectangle, tangent units
  int width = 0, height = 0;      ///< rendered rectangle in pixels
  int atlas_x = 0, atlas_y = 0;   ///< bottom-left corner in the atlas (GL coordinates)
};

/// Renders grey-scale fisheye images of a MuJoCo model from a camera pose.
class FisheyeRenderer final : public FrameRenderer {
 public:
  /// Creates the GL context and MuJoCo render context for `model`, which it only reads: the
  /// benchmark's visual settings (off-screen size, samples, headlight, tessellation, plane grid,
  /// lights, sky colour, fog) go into the renderer's own copy of the model, so the physics sees
  /// the world as loaded. `render()` takes the physics' mjData of the same model. Throws
  /// ConfigError or std::runtime_error.
  FisheyeRenderer(const FisheyeRendererConfig& config, const FisheyeCamera& camera, const mjModel* model);
  ~FisheyeRenderer() override;
  FisheyeRenderer(const FisheyeRenderer&) = delete;
  FisheyeRenderer& operator=(const FisheyeRenderer&) = delete;

  /// Renders the image seen from the camera pose T_W_C (optical frame) for the state in
  /// `data` into `frame` (pixels, size; tick/time/pose are left to the caller).
  void render(const mjData* data, const Pose& T_W_C, CameraFrame* frame, RenderTiming* timing = nullptr) override;
  /// GL renderer description.
  std::string description() const override { return context_->description(); }

  /// The camera model.
  const FisheyeCamera& camera() const { return camera_; }
  /// The rendered cube faces and their atlas placement.
  const std::vector<CubeFace>& faces() const { return faces_; }
  /// Atlas size in pixels.
  cv::Size atlasSize() const { return {atlas_width_, atlas_height_}; }
  /// Total rendered face pixels per frame.
  long renderedPixels() const;
  /// Geoms drawn in the last frame, summed over its cube faces.
  long drawnGeomsLastFrame() const { return drawn_geoms_; }
  /// Textures kept as one-byte luminance (grey textures, `single_channel_textures`).
  int luminanceTextures() const { return luminance_textures_; }
  /// Whether faces render into one-channel colour buffers (`single_channel_framebuffer` and a
  /// grey model).
  bool singleChannelFramebuffer() const { return single_channel_framebuffer_; }

 private:
  // Paints the pixels of the face viewport nothing was drawn into with the backdrop colour.
  void paintBeyondClip(int x, int y, int width, int height);
  void buildFacesAndLut();
  // The benchmark's visual settings and the conditions, written into the renderer's model copy.
  void configureRenderModel();
  // Creates one framebuffer per face, with MuJoCo's off-screen colour and depth formats.
  void makeFaceFramebuffers();
  // Re-stores every grey texture (all levels R = G = B) as one-byte luminance.
  void storeGreyTexturesAsLuminance();
  // Leaves in scene_ only the geoms of scene_geoms_ that may be seen in a face (its frame in the
  // world, the eye, its tangent bounds).
  // The steps of render(): the MuJoCo scene (with the sun's direction, the geoms kept for
  // culling); every cube face drawn; the atlas read back (returns whether one channel was read);
  // grey conversion and the fisheye remap into `frame`.
  void updateScene(const mjData* data);
  void renderFaces(const Pose& T_W_C);
  bool readBackAtlas();
  void remapInto(CameraFrame* frame, bool red_only);
  void cullToFace(const Mat3& R_W_F, const Vec3& eye, double tx0, double tx1, double ty0, double ty1);

  FisheyeRendererConfig config_;
  FisheyeCamera camera_;
  // The renderer's copy of the physics model, with the visual settings.
  std::unique_ptr<mjModel, void (*)(mjModel*)> model_copy_;
  mjModel* model_;
  std::unique_ptr<GlContext> context_;
  mjvScene scene_;
  mjrContext mjr_context_;
  mjvOption options_;
  mjvCamera free_camera_;
  double face_focal_px_ = 0;
  std::vector<CubeFace> faces_;
  int atlas_width_ = 0, atlas_height_ = 0;
  FixedPointRemap remap_;  // atlas pixels to fisheye pixels (bilinear, fixed point)
  cv::Mat atlas_raw_, atlas_grey_, fisheye_;
  std::optional<Vec3> sun_direction_;        // world direction of the sun's light, if conditions set it
  std::vector<mjvGeom> scene_geoms_;         // the full scene of a frame, culled per face into scene_
  long drawn_geoms_ = 0;                     // geoms drawn in the last frame, over all faces
  float backdrop_[3] = {0, 0, 0};            // colour beyond the camera's far clip (sky, fog or black)
  int luminance_textures_ = 0;               // textures re-stored as one-byte luminance
  bool single_channel_framebuffer_ = false;  // face colour buffers hold one channel (grey model)
  // Per-face framebuffers (framebuffer_per_face): framebuffer, colour and depth renderbuffers.
  std::vector<unsigned> face_fbo_, face_colour_rb_, face_depth_rb_;
};

}  // namespace msb
