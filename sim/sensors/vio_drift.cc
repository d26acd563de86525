#include "sim/sensors/vio_drift.h"

#include <algorithm>
#include <cmath>

#include "core/common/types.h"

namespace msb {

void VioDriftConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

void VioDriftModel::setTrackedFeatures(int tracked) {
  shortfall_ = 1.0 - std::clamp(double(tracked) / config_.nominal_tracks, 0.0, 1.0);
}

namespace {
double yawOfPose(const Pose& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }
}  // namespace

VioDriftModel::VioDriftModel(const VioDriftConfig& config, uint64_t seed)
    : config_(checkValid(config)), rng_(seed, "vio_drift") {
  // Initial drift-rate vector: random direction, size position_drift_fraction.
  const Vec3 dir = rng_.normal3();
  rate_ = config_.position_drift_fraction * dir / std::max(dir.norm(), 1e-9);
}

Odometry VioDriftModel::update(const Odometry& gt) {
  const Vec3 p = gt.T_W_B.translation();
  const double gt_yaw = yawOfPose(gt.T_W_B);
  if (!started_) last_position_ = p, last_gt_yaw_ = gt_yaw, started_ = true;
  const double ds = (p - last_position_).norm();
  const double turned = std::abs(std::remainder(gt_yaw - last_gt_yaw_, 2 * M_PI));
  last_position_ = p;
  last_gt_yaw_ = gt_yaw;
  const double growth = 1.0 + config_.few_tracks_gain * shortfall_ * shortfall_;
  // Yaw increment, applied about the current position (keeps the estimate continuous): a
  // random walk over distance, plus an error per radian turned while few features are tracked.
  auto addYaw = [&](double dpsi) {
    const Mat3 dR = Eigen::AngleAxisd(dpsi, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 p_est = T_drift_ * p;
    T_drift_.linear() = dR * T_drift_.linear();
    T_drift_.translation() = p_est - T_drift_.linear() * p;
    yaw_ += dpsi;
  };
  if (config_.enabled && turned > 0.0 && shortfall_ > 0.0 && config_.yaw_error_per_turn_deg_per_rad > 0.0)
    addYaw(config_.yaw_error_per_turn_deg_per_rad * kDeg * shortfall_ * turned * rng_.normal());
  if (config_.enabled && ds > 0.0) {
    distance_ += ds;
    const double sq = std::sqrt(ds);
    addYaw(growth * config_.yaw_random_walk_deg_per_sqrt_m * kDeg * sq * rng_.normal());
    // Position: drift rate times distance plus a random walk; the rate's direction wanders.
    T_drift_.translation() += growth * (rate_ * ds + config_.position_random_walk_m_per_sqrt_m * sq * rng_.normal3());
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

VioDriftConfig scaledDrift(const VioDriftConfig& config, double scale) {
  VioDriftConfig c = config;
  c.position_drift_fraction *= scale;
  c.drift_rate_wander_per_sqrt_m *= scale;
  c.position_random_walk_m_per_sqrt_m *= scale;
  c.yaw_random_walk_deg_per_sqrt_m *= scale;
  c.frame_position_noise_m *= scale;
  c.frame_yaw_noise_deg *= scale;
  c.yaw_error_per_turn_deg_per_rad *= scale;
  return c;
}

}  // namespace msb
