// Plain message structs passed between layers (sim → core → sim). No behaviour, no pointers
// into other components: each message can be copied, logged and compared.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// One IMU reading in the body (FLU) frame.
struct ImuSample {
  int64_t tick = 0;                ///< simulation tick of the reading
  double t_s = 0.0;                ///< simulated time in seconds
  Vec3 accel_mps2 = Vec3::Zero();  ///< specific force (gravity reaction included), m/s²
  Vec3 gyro_radps = Vec3::Zero();  ///< angular rate, rad/s
};

/// One grey-scale fisheye image.
struct CameraFrame {
  int64_t tick = 0;               ///< simulation tick at which the image was rendered
  double t_s = 0.0;               ///< simulated time in seconds
  int width = 0;                  ///< pixels
  int height = 0;                 ///< pixels
  std::vector<uint8_t> pixels;    ///< row-major, top row first, width*height bytes
  Pose T_W_C = Pose::Identity();  ///< ground-truth camera pose at render time (for evaluation)
};

/// A vehicle state estimate (or ground truth) in the world frame.
struct Odometry {
  int64_t tick = 0;                   ///< simulation tick
  double t_s = 0.0;                   ///< simulated time in seconds
  Pose T_W_B = Pose::Identity();      ///< body pose in world
  Vec3 v_W_mps = Vec3::Zero();        ///< linear velocity, world frame
  Vec3 omega_B_radps = Vec3::Zero();  ///< angular velocity, body frame
};

/// A waypoint of a path command: position and an optional goal heading.
struct Waypoint {
  Vec3 position_m = Vec3::Zero();     ///< world frame
  std::optional<double> heading_rad;  ///< yaw to hold when reaching it; none = face travel
};

/// A path for the trajectory tracker to follow (replaces the previous one).
struct PathCommand {
  int64_t tick = 0;                 ///< tick at which the command was issued
  std::vector<Waypoint> waypoints;  ///< in order; the tracker starts from its current state
};

/// The smooth reference the controller tracks, produced by the trajectory tracker.
struct TrajectoryReference {
  Vec3 position_m = Vec3::Zero();    ///< world frame
  Vec3 velocity_mps = Vec3::Zero();  ///< world frame
  Vec3 accel_mps2 = Vec3::Zero();    ///< world frame, feed-forward
  double yaw_rad = 0.0;              ///< heading
  double yaw_rate_radps = 0.0;       ///< heading rate
};

/// A triangulated point of a currently tracked feature (VIO world frame).
struct SlamPoint {
  uint64_t track_id = 0;
  Vec3 p_W = Vec3::Zero();
  Mat3 cov_W = Mat3::Identity();  ///< position covariance, m²
  double depth_m = 0.0;           ///< along the anchor ray
  double depth_std_m = 0.0;       ///< 1σ depth uncertainty
  double reprojection_rms_px = 0.0;
  int observations = 0;
  Pose T_W_anchor = Pose::Identity();  ///< estimated camera pose of the anchor observation
  Vec2 anchor_pixel = Vec2::Zero();
  int64_t anchor_tick = 0;
};

/// The mapper's input for one camera frame.
struct SlamPointsFrame {
  int64_t tick = 0;
  double t_s = 0.0;
  Pose T_W_C = Pose::Identity();  ///< estimated camera pose of this frame
  std::vector<SlamPoint> points;  ///< sorted by track id, at most max_points
  int tracks = 0;                 ///< tracked features in this frame
};

}  // namespace msb
