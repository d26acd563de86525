#include "core/perception/slam_points.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/rng.h"

namespace msb {
namespace {

// Camera poses along a sideways/forward path looking roughly along +x (optical z = world x).
std::vector<Pose> cameraPath(int n, double step_m) {
  const FisheyeCamera cam;
  std::vector<Pose> poses;
  for (int i = 0; i < n; ++i)
    poses.push_back(poseFromXyzYaw(Vec3(0.5 * i * step_m, i * step_m, 1.5), 0.02 * i) * cam.T_B_C());
  return poses;
}

TEST(SlamPoints, RecoversExactPointsWithoutNoise) {
  const FisheyeCamera cam;
  const SlamPointEstimator est(SlamPointsConfig{}, cam);
  RngStream rng(1, "tri_exact");
  const auto poses = cameraPath(12, 0.3);
  int tested = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 p(rng.uniform(3, 30), rng.uniform(-15, 15), rng.uniform(-2, 8));
    std::vector<std::pair<Vec2, Pose>> obs;
    for (const auto& T : poses) {
      const Vec3 pc = T.inverse() * p;
      if (!cam.inFieldOfView(pc)) break;
      obs.emplace_back(cam.project(pc), T);
    }
    if (obs.size() < poses.size()) continue;
    SlamPoint out;
    ASSERT_TRUE(est.estimate(obs, 0.0, &out)) << p.transpose();
    EXPECT_LT((out.p_W - p).norm(), 1e-3) << p.transpose();
    EXPECT_LT(out.reprojection_rms_px, 1e-6);
    ++tested;
  }
  EXPECT_GT(tested, 200);
}

TEST(SlamPoints, NormalisedErrorIsConsistentWithTheCovarianceAt1pxNoise) {
  const FisheyeCamera cam;
  SlamPointsConfig cfg;
  cfg.max_relative_depth_std = 10.0;  // keep every estimate: the test is about consistency
  cfg.max_reprojection_rms_px = 10.0;
  const SlamPointEstimator est(cfg, cam);
  RngStream rng(2, "tri_nees");
  const auto poses = cameraPath(15, 0.4);
  double nees_sum = 0;
  int n = 0;
  for (int k = 0; k < 3000 && n < 1500; ++k) {
    const Vec3 p(rng.uniform(3, 15), rng.uniform(-8, 14), rng.uniform(-1, 5));
    std::vector<std::pair<Vec2, Pose>> obs;
    for (const auto& T : poses) {
      const Vec3 pc = T.inverse() * p;
      if (!cam.inFieldOfView(pc)) break;
      obs.emplace_back(cam.project(pc) + Vec2(rng.normal(), rng.normal()), T);
    }
    if (obs.size() < poses.size()) continue;
    SlamPoint out;
    if (!est.estimate(obs, 0.0, &out)) continue;
    const Vec3 e = out.p_W - p;
    nees_sum += e.dot(out.cov_W.ldlt().solve(e));
    ++n;
  }
  ASSERT_GT(n, 1000);
  const double mean_nees = nees_sum / n;
  EXPECT_GT(mean_nees, 0.5 * 3);
  EXPECT_LT(mean_nees, 2.0 * 3);
  std::printf("mean NEES %.3f over %d points (dof 3)\n", mean_nees, n);
}

TEST(SlamPoints, NeedsParallaxAndWithholdsUncertainPoints) {
  const FisheyeCamera cam;
  SlamPointEstimator est(SlamPointsConfig{}, cam);
  // A point 40 m away seen while moving 0.5 m in total: parallax < 4°, no output.
  const Vec3 p(40, 0, 1.5);
  for (int i = 0; i < 6; ++i) {
    const Pose T = poseFromXyzYaw(Vec3(0, 0.1 * i, 1.5), 0) * cam.T_B_C();
    TrackFrame tf;
    tf.tick = i;
    tf.tracks.push_back({7, cam.project(T.inverse() * p), i});
    const auto out = est.update(tf, T);
    EXPECT_TRUE(out.points.empty());
    EXPECT_EQ(out.tracks, 1);
  }
  // Moving far sideways gives parallax: the point appears, id kept.
  SlamPointsFrame last;
  for (int i = 6; i < 20; ++i) {
    const Pose T = poseFromXyzYaw(Vec3(0, 0.5 * i, 1.5), 0) * cam.T_B_C();
    TrackFrame tf;
    tf.tick = i;
    tf.tracks.push_back({7, cam.project(T.inverse() * p), i});
    last = est.update(tf, T);
  }
  ASSERT_EQ(last.points.size(), 1u);
  EXPECT_EQ(last.points[0].track_id, 7u);
  EXPECT_LT((last.points[0].p_W - p).norm(), 0.01);
  // A lost track's history is dropped.
  TrackFrame empty;
  EXPECT_TRUE(est.update(empty, Pose::Identity()).points.empty());
}

}  // namespace
}  // namespace msb
