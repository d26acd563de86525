// The one fisheye camera model of msbench, shared by renderer, tracker, mapper and planner.
//
// Equidistant / Kannala–Brandt model in OpenCV's cv::fisheye convention (no skew). For a point
// X = (x, y, z) in the camera optical frame (z forward, x right, y down):
//
//   r  = sqrt(x² + y²),   θ = atan2(r, z)                       (angle from the optical axis)
//   θd = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸)                   (distorted angle)
//   u  = fx · θd · x / r + cx,   v = fy · θd · y / r + cy        (pixel; r → 0 gives (cx, cy))
//
// Unprojection inverts θd(θ) by Newton's method and returns the unit bearing
//   (sin θ · mx / |m|, sin θ · my / |m|, cos θ),  m = ((u − cx)/fx, (v − cy)/fy), θd = |m|.
// Unlike OpenCV (θ = atan(r/z)), θ = atan2(r, z) stays valid behind the image plane, so the
// model covers the whole 180° (and wider) field of view. A direction is in the field of view
// when θ ≤ fov/2 and its pixel lies inside the image.
#pragma once

#include <array>
#include <optional>

#include "core/common/config_fields.h"
#include "core/common/types.h"

namespace msb {

/// Intrinsics, image size and mounting of the fisheye camera (docs/architecture.md §5 defaults).
struct FisheyeCameraConfig {
  int width_px = 752;                                                    ///< image width at full resolution
  int height_px = 480;                                                   ///< image height at full resolution
  double fx_px = 227.4;                                                  ///< focal length x, full resolution
  double fy_px = 227.4;                                                  ///< focal length y, full resolution
  double cx_px = 376.0;                                                  ///< principal point x, full resolution
  double cy_px = 240.0;                                                  ///< principal point y, full resolution
  std::array<double, 4> k = {0.019266, 0.001143, -0.000381, 0.0000634};  ///< KB coefficients
  double fov_deg = 180.0;                            ///< full field of view (cone around the optical axis)
  double scale = 1.0;                                ///< resolution scale: 1 = full, 0.5 = half (376×240)
  Vec3 mount_position_B_m = Vec3(0.085, 0.0, 0.13);  ///< camera centre in the body frame
  double mount_pitch_down_deg = 0.0;                 ///< downward tilt of the forward-looking camera
  /// Far clip of the simulated camera: nothing farther (along each cube face's axis, as the
  /// reference's Gazebo wide-angle camera clips its faces) is drawn; the sky colour shows
  /// instead. The reference's camera clips at 40 m (docs/perception.md).
  double clip_far_m = 40.0;

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("width_px", s.width_px, Limits::range(16, 4096));
    v.key("height_px", s.height_px, Limits::range(16, 4096));
    v.key("fx_px", s.fx_px, Limits::positive());
    v.key("fy_px", s.fy_px, Limits::positive());
    v.key("cx_px", s.cx_px, Limits::nonNegative());
    v.key("cy_px", s.cy_px, Limits::nonNegative());
    v.key("k", s.k, Limits::any());
    v.key("fov_deg", s.fov_deg, Limits::range(10.0, 200.0));
    v.key("scale", s.scale, Limits{0.25, 1.0, false, false});
    v.key("mount_position_B_m", s.mount_position_B_m, Limits::range(-1.0, 1.0));
    v.key("mount_pitch_down_deg", s.mount_pitch_down_deg, Limits::range(-90.0, 90.0));
    v.key("clip_far_m", s.clip_far_m, Limits::range(1.0, 100000.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Kannala–Brandt fisheye camera (see file comment for the maths).
class FisheyeCamera {
 public:
  /// Builds the model; applies `scale` to size and intrinsics. Throws ConfigError if invalid.
  explicit FisheyeCamera(const FisheyeCameraConfig& config = {});

  /// Image width in pixels (after scaling).
  int width() const { return width_; }
  /// Image height in pixels (after scaling).
  int height() const { return height_; }
  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  const std::array<double, 4>& k() const { return config_.k; }
  /// Half of the field of view in radians.
  double halfFovRad() const { return half_fov_rad_; }
  /// The configuration the model was built from.
  const FisheyeCameraConfig& config() const { return config_; }
  /// Camera optical frame in the body frame (forward-looking mount).
  const Pose& T_B_C() const { return T_B_C_; }

  /// Distorted angle θd for an incidence angle θ.
  double distort(double theta) const;
  /// Incidence angle θ for a distorted angle θd (Newton; exact to ~1e-12 rad).
  double undistort(double theta_d) const;

  /// Projects a point in the camera frame to a pixel (any direction except the origin).
  Vec2 project(const Vec3& p_C) const;
  /// Projection and its 2×3 Jacobian with respect to the point.
  Vec2 project(const Vec3& p_C, Eigen::Matrix<double, 2, 3>* J) const;
  /// Unit bearing vector of a pixel (valid for θd up to the model's monotonic range).
  Vec3 unproject(const Vec2& px) const;

  /// True if the direction is within the FoV cone and projects inside the image.
  bool inFieldOfView(const Vec3& p_C) const;
  /// True if the pixel lies inside the image (continuous coordinates, centres at integers).
  bool inImage(const Vec2& px) const;
  /// True if the pixel's ray lies within the FoV cone (pixels outside it are black).
  bool pixelInFov(const Vec2& px) const;

 private:
  FisheyeCameraConfig config_;
  int width_, height_;
  double fx_, fy_, cx_, cy_;
  double half_fov_rad_;
  Pose T_B_C_;
};

}  // namespace msb
