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
  int64_t tick = 0;           ///< simulation tick of the reading
  double t_s = 0.0;           ///< simulated time in seconds
  Vec3 accel_mps2 = Vec3::Zero();  ///< specific force (gravity reaction included), m/s²
  Vec3 gyro_radps = Vec3::Zero();  ///< angular rate, rad/s
};

/// One grey-scale fisheye image.
struct CameraFrame {
  int64_t tick = 0;              ///< simulation tick at which the image was rendered
  double t_s = 0.0;              ///< simulated time in seconds
  int width = 0;                 ///< pixels
  int height = 0;                ///< pixels
  std::vector<uint8_t> pixels;   ///< row-major, top row first, width*height bytes
  Pose T_W_C = Pose::Identity(); ///< ground-truth camera pose at render time (for evaluation)
};

/// A vehicle state estimate (or ground truth) in the world frame.
struct Odometry {
  int64_t tick = 0;                 ///< simulation tick
  double t_s = 0.0;                 ///< simulated time in seconds
  Pose T_W_B = Pose::Identity();    ///< body pose in world
  Vec3 v_W_mps = Vec3::Zero();      ///< linear velocity, world frame
  Vec3 omega_B_radps = Vec3::Zero();///< angular velocity, body frame
};

/// A waypoint of a path command: position and an optional goal heading.
struct Waypoint {
  Vec3 position_m = Vec3::Zero();     ///< world frame
  std::optional<double> heading_rad;  ///< yaw to hold when reaching it; none = face travel
};

/// A path for the trajectory tracker to follow (replaces the previous one).
struct PathCommand {
  int64_t tick = 0;                ///< tick at which the command was issued
  std::vector<Waypoint> waypoints; ///< in order; the tracker starts from its current state
};

/// The smooth reference the controller tracks, produced by the trajectory tracker.
struct TrajectoryReference {
  Vec3 position_m = Vec3::Zero();     ///< world frame
  Vec3 velocity_mps = Vec3::Zero();   ///< world frame
  Vec3 accel_mps2 = Vec3::Zero();     ///< world frame, feed-forward
  double yaw_rad = 0.0;               ///< heading
  double yaw_rate_radps = 0.0;        ///< heading rate
};

}  // namespace msb
