// Geometry types shared by every module: Eigen aliases and the frame conventions of docs/architecture.md §3.
// World frame ENU (z up), body FLU, camera optical frame (z forward, x right, y down).
// A pose T_A_B maps points expressed in frame B to frame A.
#pragma once

#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace msb {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Pose = Eigen::Isometry3d;

/// Standard gravity in m/s².
inline constexpr double kGravity = 9.81;
/// Radians per degree (std::numbers::pi / 180, the same double as M_PI / 180).
inline constexpr double kDeg = std::numbers::pi / 180.0;

/// Wraps an angle to (-pi, pi].
double wrapAngle(double a);

/// Yaw (rotation about world z) of a rotation matrix, ZYX convention.
inline double yawOf(const Mat3& R) { return std::atan2(R(1, 0), R(0, 0)); }

/// Pose from position and yaw (roll = pitch = 0).
inline Pose poseFromXyzYaw(const Vec3& p, double yaw) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  T.translation() = p;
  return T;
}

}  // namespace msb
