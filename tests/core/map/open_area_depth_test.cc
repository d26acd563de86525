#include "core/map/open_area_depth.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

// Camera at (x, 0, 2) looking along world direction `yaw` (optical z horizontal).
Pose camera(double x, double yaw) {
  const FisheyeCamera cam;
  return poseFromXyzYaw(Vec3(x, 0, 2), yaw) * cam.T_B_C();
}

TEST(OpenAreaDepth, ActivatesAfterTranslationWithParallax) {
  const FisheyeCamera cam;
  OpenAreaDepth ovde(OpenAreaDepthConfig{}, cam);
  std::vector<Vec3> active;
  // Sideways flight (camera faces +y, moves along +x), 0.4 m between poses, 2.4 m in total.
  for (int k = 0; k <= 6; ++k) active = ovde.update(camera(0.4 * k, M_PI / 2));
  EXPECT_EQ(ovde.poses().size(), 7u);
  EXPECT_GE(active.size(), 18u);
  for (const auto& v : active) EXPECT_NEAR((v - camera(2.4, M_PI / 2).translation()).norm(), 15.0, 1e-9);
  // The first pose alone: no parallax, nothing active.
  OpenAreaDepth fresh(OpenAreaDepthConfig{}, cam);
  EXPECT_TRUE(fresh.update(camera(0, M_PI / 2)).empty());
}

TEST(OpenAreaDepth, PureRotationActivatesNothing) {
  const FisheyeCamera cam;
  OpenAreaDepth ovde(OpenAreaDepthConfig{}, cam);
  for (int k = 0; k < 12; ++k) EXPECT_TRUE(ovde.update(camera(0, k * 50.0 * M_PI / 180)).empty()) << k;
  EXPECT_GT(ovde.poses().size(), 5u);  // rotations did fill the buffer
}

TEST(OpenAreaDepth, ContinuityBreakDeactivates) {
  const FisheyeCamera cam;
  // Straight run: enough parallax at the end.
  OpenAreaDepth straight(OpenAreaDepthConfig{}, cam);
  for (double x : {0.0, 0.4, 0.8, 1.2}) straight.update(camera(x, M_PI / 2));
  EXPECT_FALSE(straight.update(camera(1.3, M_PI / 2)).empty());
  // Same run, but the camera looked away at x = 0.8: continuity back from now ends there.
  OpenAreaDepth broken(OpenAreaDepthConfig{}, cam);
  broken.update(camera(0.0, M_PI / 2));
  broken.update(camera(0.4, M_PI / 2));
  broken.update(camera(0.8, -M_PI / 2));  // looking the opposite way
  broken.update(camera(1.2, M_PI / 2));
  EXPECT_TRUE(broken.update(camera(1.3, M_PI / 2)).empty());
}

}  // namespace
}  // namespace msb
