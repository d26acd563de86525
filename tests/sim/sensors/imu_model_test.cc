#include "sim/sensors/imu_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/physics/quadrotor_sim.h"

namespace msb {
namespace {

TEST(ImuModel, WhiteNoiseMatchesTheDensity) {
  ImuConfig cfg;
  cfg.accel_random_walk = 0.0;
  cfg.gyro_random_walk = 0.0;
  ImuModel imu(cfg, 1);
  const double dt = 1.0 / cfg.rate_hz;
  const int n = 100000;
  double sa = 0, sg = 0;
  for (int i = 0; i < n; ++i) {
    const ImuSample s = imu.sample(i, i * dt, dt, Vec3(0, 0, 9.81), Vec3::Zero());
    sa += (s.accel_mps2 - Vec3(0, 0, 9.81)).squaredNorm();
    sg += s.gyro_radps.squaredNorm();
  }
  // Per-axis standard deviation σ/√Δt.
  EXPECT_NEAR(std::sqrt(sa / (3 * n)), cfg.accel_noise_density / std::sqrt(dt),
              0.02 * cfg.accel_noise_density / std::sqrt(dt));
  EXPECT_NEAR(std::sqrt(sg / (3 * n)), cfg.gyro_noise_density / std::sqrt(dt),
              0.02 * cfg.gyro_noise_density / std::sqrt(dt));
}

TEST(ImuModel, BiasRandomWalkGrowsWithTheSquareRootOfTime) {
  // Over T seconds the bias spread is σ_b √T; check across many independent seeds.
  ImuConfig cfg;
  const double dt = 1.0 / cfg.rate_hz, T = 100.0;
  double sum_sq = 0;
  const int runs = 200;
  for (int r = 0; r < runs; ++r) {
    ImuModel imu(cfg, 1000 + r);
    for (int i = 0; i < T / dt; ++i) imu.sample(i, i * dt, dt, Vec3::Zero(), Vec3::Zero());
    sum_sq += imu.accelBias().squaredNorm();
  }
  const double spread = std::sqrt(sum_sq / (3 * runs));
  EXPECT_NEAR(spread, cfg.accel_random_walk * std::sqrt(T), 0.15 * cfg.accel_random_walk * std::sqrt(T));
}

TEST(ImuModel, SameSeedSameSamples) {
  ImuModel a(ImuConfig{}, 5), b(ImuConfig{}, 5), c(ImuConfig{}, 6);
  const ImuSample sa = a.sample(0, 0, 0.005, Vec3(1, 2, 3), Vec3(0.1, 0, 0));
  const ImuSample sb = b.sample(0, 0, 0.005, Vec3(1, 2, 3), Vec3(0.1, 0, 0));
  const ImuSample sc = c.sample(0, 0, 0.005, Vec3(1, 2, 3), Vec3(0.1, 0, 0));
  EXPECT_EQ(sa.accel_mps2, sb.accel_mps2);
  EXPECT_EQ(sa.gyro_radps, sb.gyro_radps);
  EXPECT_NE(sa.accel_mps2, sc.accel_mps2);
}

TEST(ImuTruth, RestingVehicleMeasuresGravityReactionAndNoRotation) {
  QuadrotorSim sim(PhysicsConfig{}, std::string(MSB_SOURCE_DIR) + "/tests/data/worlds/open_field.xml",
                   poseFromXyzYaw(Vec3(0, 0, 0.05), 0.7));
  for (int i = 0; i < 500; ++i) {
    sim.beginTick();
    sim.endTick(Vec4::Zero());
  }
  EXPECT_NEAR((sim.imuTruth().specific_force_mps2 - Vec3(0, 0, 9.81)).norm(), 0.0, 0.02);
  EXPECT_NEAR(sim.imuTruth().angular_rate_radps.norm(), 0.0, 1e-3);
}

TEST(ImuTruth, FreeFallMeasuresZeroSpecificForce) {
  QuadrotorSim sim(PhysicsConfig{}, std::string(MSB_SOURCE_DIR) + "/tests/data/worlds/open_field.xml",
                   poseFromXyzYaw(Vec3(0, 0, 20), 0.0));
  for (int i = 0; i < 100; ++i) {
    sim.beginTick();
    sim.endTick(Vec4::Zero());
  }
  EXPECT_LT(sim.imuTruth().specific_force_mps2.norm(), 1e-6);
}

}  // namespace
}  // namespace msb
