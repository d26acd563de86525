#include "sim/sensors/vio_drift.h"

#include <cmath>

namespace msb {

void VioDriftConfig::validate(ConfigChecker& c) const {
  c.inRange("position_drift_fraction", position_drift_fraction, 0.0, 0.5);
  c.nonNegative("drift_rate_wander_per_sqrt_m", drift_rate_wander_per_sqrt_m);
  c.nonNegative("position_random_walk_m_per_sqrt_m", position_random_walk_m_per_sqrt_m);
  c.inRange("yaw_random_walk_deg_per_sqrt_m", yaw_random_walk_deg_per_sqrt_m, 0.0, 10.0);
  c.nonNegative("frame_position_noise_m", frame_position_noise_m);
  c.nonNegative("frame_yaw_noise_deg", frame_yaw_noise_deg);
}

VioDriftModel::VioDriftModel(const VioDriftConfig& config, uint64_t seed)
    : config_(checkValid(config)), rng_(seed, "vio_drift") {
  // Initial drift-rate vector: random direction, size position_drift_fraction.
  const Vec3 dir = rng_.normal3();
  rate_ = config_.position_drift_fraction * dir / std::max(dir.norm(), 1e-9);
}

Odometry VioDriftModel::update(const Odometry& gt) {
  const Vec3 p = gt.T_W_B.translation();
  if (!started_) last_position_ = p, started_ = true;
  const double ds = (p - last_position_).norm();
  last_position_ = p;
  if (config_.enabled && ds > 0.0) {
    distance_ += ds;
    const double sq = std::sqrt(ds);
    constexpr double kDeg = M_PI / 180.0;
    // Yaw increment, applied about the current position (keeps the estimate continuous).
    const double dpsi = config_.yaw_random_walk_deg_per_sqrt_m * kDeg * sq * rng_.normal();
    const Mat3 dR = Eigen::AngleAxisd(dpsi, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 p_est = T_drift_ * p;
    T_drift_.linear() = dR * T_drift_.linear();
    T_drift_.translation() = p_est - T_drift_.linear() * p;
    yaw_ += dpsi;
    // Position: drift rate times distance plus a random walk; the rate's direction wanders.
    T_drift_.translation() += rate_ * ds + config_.position_random_walk_m_per_sqrt_m * sq * rng_.normal3();
    rate_ += config_.drift_rate_wander_per_sqrt_m * sq * rng_.normal3();
    if (rate_.norm() > 0) rate_ *= config_.position_drift_fraction / rate_.norm();
  } else if (!config_.enabled) {
    distance_ += ds;
  }
  Odometry est = gt;
  est.T_W_B = T_drift_ * gt.T_W_B;
  est.v_W_mps = T_drift_.linear() * gt.v_W_mps;
  return est;
}

Pose VioDriftModel::noisyCameraPose(const Pose& T_W_C_gt) {
  Pose T = T_drift_ * T_W_C_gt;
  if (!config_.enabled) return T;
  const double dpsi = config_.frame_yaw_noise_deg * M_PI / 180.0 * rng_.normal();
  T.linear() = Eigen::AngleAxisd(dpsi, Vec3::UnitZ()).toRotationMatrix() * T.linear();
  T.translation() += config_.frame_position_noise_m * rng_.normal3();
  return T;
}

}  // namespace msb
