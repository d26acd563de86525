// The VIO drift model: growth with distance, response to the tracked-feature count (position
// and yaw in rotation), determinism.
#include "sim/sensors/vio_drift.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

// Flies `n` steps of `step_m` along +x (turning by `turn_rad` per step) with `tracked` features;
// returns the final position error and the absolute yaw error.
std::pair<double, double> fly(uint64_t seed, int tracked, int n, double step_m, double turn_rad = 0.0) {
  VioDriftModel vio(VioDriftConfig{}, seed);
  vio.setTrackedFeatures(tracked);
  Odometry gt;
  Odometry est;
  double yaw = 0;
  for (int i = 0; i <= n; ++i) {
    gt.T_W_B = poseFromXyzYaw(Vec3(step_m * i, 0, 2), yaw);
    est = vio.update(gt);
    yaw += turn_rad;
  }
  const Mat3 dR = est.T_W_B.linear() * gt.T_W_B.linear().transpose();
  return {(est.T_W_B.translation() - gt.T_W_B.translation()).norm(), std::abs(std::atan2(dR(1, 0), dR(0, 0)))};
}

TEST(VioDrift, GrowsWithDistanceAtAboutOnePercentWithNominalFeatures) {
  // Mean over seeds: ≈ 1 % of distance at 100 m; over 400 m the yaw random walk's lever arm
  // adds to it (measured 2.2 %), growing with distance.
  double e100 = 0, e400 = 0;
  for (uint64_t s = 1; s <= 20; ++s) {
    e100 += fly(s, 200, 1000, 0.1).first / 20;
    e400 += fly(s, 200, 4000, 0.1).first / 20;
  }
  EXPECT_GT(e400, 2.5 * e100);
  EXPECT_NEAR(e100 / 100, 0.01, 0.004);
  EXPECT_GT(e400 / 400, 0.01);
  EXPECT_LT(e400 / 400, 0.03);
}

TEST(VioDrift, FewTrackedFeaturesMakeItDriftFaster) {
  // Same seeds, same path: the error grows as the tracked count falls below nominal.
  double nominal = 0, half = 0, none = 0;
  for (uint64_t s = 1; s <= 20; ++s) {
    nominal += fly(s, 100, 1000, 0.1).first;
    half += fly(s, 50, 1000, 0.1).first;
    none += fly(s, 0, 1000, 0.1).first;
  }
  EXPECT_NEAR(half / nominal, 2.0, 0.2);  // 1 + 4 · 0.5²
  EXPECT_NEAR(none / nominal, 5.0, 0.5);  // 1 + 4
  // Above nominal nothing changes.
  EXPECT_EQ(fly(3, 100, 500, 0.1), fly(3, 400, 500, 0.1));
}

TEST(VioDrift, TurningWithFewFeaturesAddsYawError) {
  // Turning in place (no distance): no yaw error with nominal features; with none, about
  // 2° per radian turned (σ), here 2π rad in 100 steps.
  EXPECT_EQ(fly(4, 150, 100, 0.0, 2 * M_PI / 100).second, 0.0);
  double rms = 0;
  for (uint64_t s = 1; s <= 40; ++s) {
    const double e = fly(s, 0, 100, 0.0, 2 * M_PI / 100).second;
    rms += e * e / 40;
  }
  // Each step adds N(0, (2° · 0.0628)²); 100 steps: σ = 2° · 0.0628 · 10 = 1.26°.
  EXPECT_NEAR(std::sqrt(rms) * 180 / M_PI, 1.26, 0.4);
}

TEST(VioDrift, SameSeedSameDriftDifferentSeedDifferentDrift) {
  EXPECT_EQ(fly(7, 30, 300, 0.1, 0.01), fly(7, 30, 300, 0.1, 0.01));
  EXPECT_NE(fly(7, 30, 300, 0.1, 0.01), fly(8, 30, 300, 0.1, 0.01));
}

}  // namespace
}  // namespace msb
