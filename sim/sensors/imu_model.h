// IMU model: accelerometer and gyroscope readings from the simulator's noise-free specific force
// and angular rate, with white noise and a bias random walk per axis (continuous-time densities
// as in Kalibr/OpenVINS). For a sample interval Δt:
//   white noise  n ~ N(0, σ² / Δt)          σ  = noise density      (unit/√Hz)
//   bias         b ← b + N(0, σ_b² Δt)      σ_b = random-walk density (unit·√Hz)
//   reading      = truth + b + n
// Noise comes from the component's own RNG stream ("imu"); MuJoCo's sensor noise is not used.
#pragma once

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/common/rng.h"

namespace msb {

/// IMU rate and noise densities (defaults of the reference setup, docs/architecture.md §4).
struct ImuConfig {
  double rate_hz = 200.0;                 ///< sample rate
  double accel_noise_density = 2.0e-3;    ///< m/s²/√Hz
  double accel_random_walk = 3.0e-3;      ///< m/s³/√Hz
  double gyro_noise_density = 1.6968e-4;  ///< rad/s/√Hz
  double gyro_random_walk = 1.9393e-5;    ///< rad/s²/√Hz

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("rate_hz", s.rate_hz, Limits::range(1.0, 2000.0));
    v.key("accel_noise_density", s.accel_noise_density, Limits::nonNegative());
    v.key("accel_random_walk", s.accel_random_walk, Limits::nonNegative());
    v.key("gyro_noise_density", s.gyro_noise_density, Limits::nonNegative());
    v.key("gyro_random_walk", s.gyro_random_walk, Limits::nonNegative());
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Turns truth into noisy IMU samples; owns its bias state and RNG stream.
class ImuModel {
 public:
  /// Seeds the "imu" stream from the scenario seed. Throws ConfigError if invalid.
  ImuModel(const ImuConfig& config, uint64_t seed);

  /// A noisy sample for truth at (tick, t); `dt_s` is the time since the previous sample.
  ImuSample sample(int64_t tick, double t_s, double dt_s, const Vec3& specific_force_mps2,
                   const Vec3& angular_rate_radps);
  /// Current accelerometer bias.
  const Vec3& accelBias() const { return accel_bias_; }
  /// Current gyroscope bias.
  const Vec3& gyroBias() const { return gyro_bias_; }

 private:
  ImuConfig config_;
  RngStream rng_;
  Vec3 accel_bias_ = Vec3::Zero();
  Vec3 gyro_bias_ = Vec3::Zero();
};

}  // namespace msb
