#include "sim/sensors/imu_model.h"

#include <cmath>

namespace msb {

void ImuConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

ImuModel::ImuModel(const ImuConfig& config, uint64_t seed) : config_(checkValid(config)), rng_(seed, "imu") {}

ImuSample ImuModel::sample(int64_t tick, double t_s, double dt, const Vec3& f, const Vec3& w) {
  // Bias random walk first, then white noise, in a fixed draw order (acc xyz, gyro xyz, ...).
  const double sq = std::sqrt(dt);
  accel_bias_ += config_.accel_random_walk * sq * rng_.normal3();
  gyro_bias_ += config_.gyro_random_walk * sq * rng_.normal3();
  ImuSample s;
  s.tick = tick;
  s.t_s = t_s;
  s.accel_mps2 = f + accel_bias_ + config_.accel_noise_density / sq * rng_.normal3();
  s.gyro_radps = w + gyro_bias_ + config_.gyro_noise_density / sq * rng_.normal3();
  return s;
}

}  // namespace msb
