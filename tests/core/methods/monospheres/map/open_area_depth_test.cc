#include "core/methods/monospheres/map/open_area_depth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace msb {
namespace {

// Camera at (x, 0, 2) looking along world direction `yaw` (optical z horizontal).
Pose camera(double x, double yaw) {
  const FisheyeCamera cam;
  return poseFromXyzYaw(Vec3(x, 0, 2), yaw) * cam.T_B_C();
}

// OVDE with a pose buffer of its own, as the sphere map's state holds one.
struct Ovde {
  Ovde(const OpenAreaDepthConfig& c, const FisheyeCamera& cam) : ovde(c, cam) {}
  std::vector<Vec3> update(const Pose& T_W_C) { return ovde.update(T_W_C, poses); }
  OpenAreaDepth ovde;
  OvdePoseBuffer poses;
};

TEST(OpenAreaDepth, ActivatesAfterTranslationWithParallax) {
  const FisheyeCamera cam;
  Ovde ovde(OpenAreaDepthConfig{}, cam);
  std::vector<Vec3> active;
  // Sideways flight (camera faces +y, moves along +x), 0.4 m between poses, 2.4 m in total.
  for (int k = 0; k <= 6; ++k) active = ovde.update(camera(0.4 * k, M_PI / 2));
  EXPECT_EQ(ovde.poses.size(), 7u);
  EXPECT_GE(active.size(), 18u);
  for (const auto& v : active) EXPECT_NEAR((v - camera(2.4, M_PI / 2).translation()).norm(), 15.0, 1e-9);
  // The first pose alone: no parallax, nothing active.
  Ovde fresh(OpenAreaDepthConfig{}, cam);
  EXPECT_TRUE(fresh.update(camera(0, M_PI / 2)).empty());
}

TEST(OpenAreaDepth, PureRotationActivatesNothing) {
  const FisheyeCamera cam;
  Ovde ovde(OpenAreaDepthConfig{}, cam);
  for (int k = 0; k < 12; ++k) EXPECT_TRUE(ovde.update(camera(0, k * 50.0 * M_PI / 180)).empty()) << k;
  EXPECT_GT(ovde.poses.size(), 5u);  // rotations did fill the buffer
}

TEST(OpenAreaDepth, ContinuityBreakDeactivates) {
  const FisheyeCamera cam;
  // Straight run: enough parallax at the end.
  Ovde straight(OpenAreaDepthConfig{}, cam);
  for (double x : {0.0, 0.4, 0.8, 1.2}) straight.update(camera(x, M_PI / 2));
  EXPECT_FALSE(straight.update(camera(1.3, M_PI / 2)).empty());
  // Same run, but the camera looked away at x = 0.8: continuity back from now ends there.
  Ovde broken(OpenAreaDepthConfig{}, cam);
  broken.update(camera(0.0, M_PI / 2));
  broken.update(camera(0.4, M_PI / 2));
  broken.update(camera(0.8, -M_PI / 2));  // looking the opposite way
  broken.update(camera(1.2, M_PI / 2));
  EXPECT_TRUE(broken.update(camera(1.3, M_PI / 2)).empty());
}

TEST(OpenAreaDepth, WholeBufferNeedsEveryBufferedPoseToHaveSeenThePoint) {
  const FisheyeCamera cam;
  OpenAreaDepthConfig paper;  // the default
  OpenAreaDepthConfig recent_cfg;
  recent_cfg.visibility = "recent_run";
  // Looked the other way first, then turned and flew sideways 1.6 m: the recent run back from
  // now has the parallax, but the buffered poses from before the turn never saw these points.
  auto fly = [&](Ovde& ovde) {
    ovde.update(camera(-0.8, -M_PI / 2));
    ovde.update(camera(-0.4, -M_PI / 2));
    std::vector<Vec3> active;
    for (double x : {0.0, 0.4, 0.8, 1.2, 1.6}) active = ovde.update(camera(x, M_PI / 2));
    return active;
  };
  Ovde recent(recent_cfg, cam), whole(paper, cam);
  EXPECT_FALSE(fly(recent).empty());
  EXPECT_TRUE(fly(whole).empty());
  // Once the buffer holds only poses that saw them (max_poses 4 here), they activate again.
  paper.max_poses = 4;
  Ovde short_buffer(paper, cam);
  EXPECT_FALSE(fly(short_buffer).empty());
  // And on a straight run from the start both rules agree.
  Ovde a(recent_cfg, cam), b(OpenAreaDepthConfig{}, cam);
  std::vector<Vec3> ra, rb;
  for (int k = 0; k <= 6; ++k) ra = a.update(camera(0.4 * k, M_PI / 2)), rb = b.update(camera(0.4 * k, M_PI / 2));
  EXPECT_EQ(ra.size(), rb.size());
  EXPECT_GE(rb.size(), 18u);
}

// method.reference_code.ovde_parallax_frames (SBM ofs_freespace_update): the published points
// are the pinhole K's rays through the central 60 % of the image, edges included (the corner
// ray 51.5° off the axis under K, where the fisheye's central cells reach 57°); after sideways
// flight they activate; a frame that adds no pose (it neither moved 0.3 m nor turned its axis
// 45°) keeps the flags, even turned 30° away, where the paper's rule (every buffered pose must
// see the point) recomputes them and keeps fewer.
TEST(OpenAreaDepth, ThePublishedActivationUsesPinholeRaysAndKeepsItsFlagsBetweenPoses) {
  const FisheyeCamera cam;
  const OpenAreaDepth ovde(OpenAreaDepthConfig{}, cam);
  OvdePoseBuffer poses;
  std::vector<bool> flags;
  std::vector<Vec3> active;
  for (int k = 0; k <= 6; ++k) active = ovde.updatePublished(camera(0.4 * k, M_PI / 2), poses, flags);
  ASSERT_EQ(flags.size(), 36u);
  EXPECT_GE(active.size(), 12u);
  const Pose now = camera(2.4, M_PI / 2);
  const double corner = std::atan(std::hypot(0.3 * cam.width() / cam.fx(), 0.3 * cam.height() / cam.fy()));
  double widest = 0.0;
  for (const Vec3& v : active) {
    const Vec3 c = now.inverse() * v;
    EXPECT_NEAR(c.norm(), 15.0, 1e-9);
    widest = std::max(widest, std::atan2(c.head<2>().norm(), c.z()));
  }
  EXPECT_LE(widest, corner + 1e-9);
  // Turned 30° at the same place: no pose is added, the same points stay active.
  const Pose turned = camera(2.4, M_PI / 2 + 30 * M_PI / 180);
  const std::vector<Vec3> kept = ovde.updatePublished(turned, poses, flags);
  EXPECT_EQ(kept.size(), active.size());
  EXPECT_EQ(poses.size(), 7u);
  Ovde paper(OpenAreaDepthConfig{}, cam);
  for (int k = 0; k <= 6; ++k) paper.update(camera(0.4 * k, M_PI / 2));
  EXPECT_LT(paper.update(turned).size(), kept.size());
}

TEST(OpenAreaDepth, UnknownVisibilityRuleIsAConfigError) {
  OpenAreaDepthConfig c;
  c.visibility = "sometimes";
  EXPECT_THROW(OpenAreaDepth(c, FisheyeCamera{}), ConfigError);
}

}  // namespace
}  // namespace msb
