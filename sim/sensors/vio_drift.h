// The simulated VIO pose estimate: ground truth composed with a slowly drifting world-frame
// transform T_drift = [Rz(δψ), δt] (roll and pitch stay gravity-aligned, as in real VIO):
//   T_W_B_est = T_drift · T_W_B_gt.
// Drift grows with distance travelled s (metres along the ground-truth path):
//   position: δt' = b · ds + σ_w √ds · n, with a drift-rate vector b whose size is about
//             `position_drift_fraction` (default 1 % of distance) and whose direction wanders
//             (b ← b + σ_b √ds · n);
//   yaw:      δψ' = σ_ψ √ds · n  (random walk; σ_ψ = yaw_random_walk_deg_per_sqrt_m).
// The drift follows the image: with fewer features tracked from the previous frame than
// `nominal_tracks` (shortfall q = 1 − n/nominal ∈ [0, 1]) the position drift rate, both random
// walks and the yaw random walk grow by the factor 1 + few_tracks_gain · q², and every yaw
// change of the vehicle adds a yaw error of σ = yaw_error_per_turn_deg_per_rad · q per radian
// turned (rotation with few features is what VIO gets wrong). At or above the nominal count the
// model is the distance-only one above (≈ 1 % of distance). The loop reports the count once
// per camera frame (setTrackedFeatures); it applies from the next physics step on.
// A yaw increment rotates the drift frame about the vehicle's current position, so the
// estimated trajectory stays continuous. The estimate starts equal to ground truth (VIO world
// frame = world frame at t = 0). Per camera frame a small white noise is added to the pose
// handed to perception (not to the controller's state).
#pragma once

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/common/rng.h"

namespace msb {

/// Drift process parameters (docs/architecture.md §6 defaults).
struct VioDriftConfig {
  bool enabled = true;                               ///< false: estimate = ground truth
  double position_drift_fraction = 0.01;             ///< drift-rate size, metres per metre travelled
  double drift_rate_wander_per_sqrt_m = 0.001;       ///< how fast the drift direction changes
  double position_random_walk_m_per_sqrt_m = 0.002;  ///< extra random walk of the position
  double yaw_random_walk_deg_per_sqrt_m = 0.1;       ///< yaw random walk
  double frame_position_noise_m = 0.005;             ///< white noise per camera-frame pose
  double frame_yaw_noise_deg = 0.02;                 ///< white noise per camera-frame yaw
  int nominal_tracks = 100;                          ///< tracked features at (and above) which drift is nominal
  double few_tracks_gain = 4.0;                      ///< drift growth at zero tracked features: × (1 + gain)
  double yaw_error_per_turn_deg_per_rad = 2.0;       ///< yaw error σ per radian turned, at zero tracked features

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("enabled", s.enabled);
    v.key("position_drift_fraction", s.position_drift_fraction, Limits::range(0.0, 0.5));
    v.key("drift_rate_wander_per_sqrt_m", s.drift_rate_wander_per_sqrt_m, Limits::nonNegative());
    v.key("position_random_walk_m_per_sqrt_m", s.position_random_walk_m_per_sqrt_m, Limits::nonNegative());
    v.key("yaw_random_walk_deg_per_sqrt_m", s.yaw_random_walk_deg_per_sqrt_m, Limits::range(0.0, 10.0));
    v.key("frame_position_noise_m", s.frame_position_noise_m, Limits::nonNegative());
    v.key("frame_yaw_noise_deg", s.frame_yaw_noise_deg, Limits::nonNegative());
    v.key("nominal_tracks", s.nominal_tracks, Limits::range(1, 10000));
    v.key("few_tracks_gain", s.few_tracks_gain, Limits::range(0.0, 100.0));
    v.key("yaw_error_per_turn_deg_per_rad", s.yaw_error_per_turn_deg_per_rad, Limits::range(0.0, 90.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The drift model with every drift rate and noise multiplied by `scale` (the front end's
/// drift_scale axis); the feature-count coupling (nominal_tracks, few_tracks_gain) is kept.
VioDriftConfig scaledDrift(const VioDriftConfig& config, double scale);

/// Drifting pose estimate; owns the "vio_drift" RNG stream.
class VioDriftModel {
 public:
  /// Seeds the stream from the scenario seed. Throws ConfigError.
  VioDriftModel(const VioDriftConfig& config, uint64_t seed);

  /// Advances the drift by the ground-truth motion since the last call and returns the
  /// estimate of `gt` (pose, world velocity; body rates unchanged).
  Odometry update(const Odometry& gt);
  /// A camera-frame pose estimate: the estimate of T_W_C with per-frame white noise.
  Pose noisyCameraPose(const Pose& T_W_C_gt);
  /// Features tracked from the previous frame in the latest camera frame (drives the growth).
  void setTrackedFeatures(int tracked);
  /// The current shortfall q = 1 − min(tracked / nominal_tracks, 1).
  double shortfall() const { return shortfall_; }
  /// The current drift transform (estimate frame ← world frame).
  const Pose& drift() const { return T_drift_; }
  /// Distance travelled so far (m).
  double distance() const { return distance_; }

 private:
  VioDriftConfig config_;
  RngStream rng_;
  Pose T_drift_ = Pose::Identity();
  double yaw_ = 0.0;
  Vec3 rate_ = Vec3::Zero();
  Vec3 last_position_ = Vec3::Zero();
  bool started_ = false;
  double shortfall_ = 0.0;
  double last_gt_yaw_ = 0.0;
  double distance_ = 0.0;
};

}  // namespace msb
