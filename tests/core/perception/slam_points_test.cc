// SLAM points as OpenVINS makes them: the feature initialiser (linear triangulation with its
// condition-number and depth checks, Gauss–Newton, the baseline ratio) and the rules of which
// tracks become SLAM features (max tracks spanning the clone window, the start-up delay, the
// per-update and state caps, marginalisation of lost tracks).
#include "core/perception/slam_points.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/rng.h"

namespace msb {
namespace {

constexpr double kFrameHz = 15.0;

// Camera poses along a sideways/forward path looking roughly along +x (optical z = world x).
std::vector<Pose> cameraPath(int n, double step_m) {
  const FisheyeCamera cam;
  std::vector<Pose> poses;
  for (int i = 0; i < n; ++i)
    poses.push_back(poseFromXyzYaw(Vec3(0.5 * i * step_m, i * step_m, 1.5), 0.02 * i) * cam.T_B_C());
  return poses;
}

// Observations of p from the poses (anchor = the first pose), or none if it leaves the view.
std::vector<std::pair<Vec2, Pose>> observe(const FisheyeCamera& cam, const std::vector<Pose>& poses, const Vec3& p,
                                           RngStream* noise = nullptr) {
  std::vector<std::pair<Vec2, Pose>> obs;
  for (const auto& T : poses) {
    const Vec3 pc = T.inverse() * p;
    if (!cam.inFieldOfView(pc)) return {};
    obs.emplace_back(cam.project(pc) + (noise ? Vec2(noise->normal(), noise->normal()) : Vec2::Zero()), T);
  }
  return obs;
}

TEST(SlamPoints, TheInitialiserRecoversExactPointsWithoutNoise) {
  const FisheyeCamera cam;
  const SlamPointEstimator est(SlamPointsConfig{}, cam, kFrameHz);
  RngStream rng(1, "tri_exact");
  const auto poses = cameraPath(9, 0.3);
  int tested = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 p(rng.uniform(3, 30), rng.uniform(-15, 15), rng.uniform(-2, 8));
    const auto obs = observe(cam, poses, p);
    if (obs.empty()) continue;
    SlamPoint out;
    if (!est.initialise(obs, &out)) continue;  // the baseline ratio refuses far points
    EXPECT_LT((out.p_W - p).norm(), 1e-3) << p.transpose();
    EXPECT_LT(out.reprojection_rms_px, 1e-6);
    ++tested;
  }
  EXPECT_GT(tested, 150);
}

TEST(SlamPoints, NormalisedErrorIsConsistentWithTheCovarianceAt1pxNoise) {
  const FisheyeCamera cam;
  SlamPointsConfig cfg;
  cfg.max_reprojection_rms_px = 10.0;  // keep every estimate: the test is about consistency
  const SlamPointEstimator est(cfg, cam, kFrameHz);
  RngStream rng(2, "tri_nees");
  const auto poses = cameraPath(15, 0.4);
  double nees_sum = 0;
  int n = 0;
  for (int k = 0; k < 3000 && n < 1500; ++k) {
    const Vec3 p(rng.uniform(3, 15), rng.uniform(-8, 14), rng.uniform(-1, 5));
    const auto obs = observe(cam, poses, p, &rng);
    if (obs.empty()) continue;
    SlamPoint out;
    if (!est.refine(obs, (p - poses.front().translation()).norm(), &out)) continue;
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

TEST(SlamPoints, ALowParallaxTriangulationIsRefusedByTheConditionNumber) {
  const FisheyeCamera cam;
  // A point 20 m ahead seen from centres 1 mm apart: the rays are parallel to 5e-5 rad.
  std::vector<Pose> poses;
  for (int i = 0; i < 9; ++i) poses.push_back(poseFromXyzYaw(Vec3(0, 0.000125 * i, 1.5), 0) * cam.T_B_C());
  const auto obs = observe(cam, poses, Vec3(20, 0.5, 2.0));
  ASSERT_FALSE(obs.empty());
  SlamPointsConfig only_cond;  // every other check out of the way
  only_cond.max_baseline = 1e9;
  only_cond.max_dist_m = 1e6;
  SlamPoint out;
  EXPECT_FALSE(SlamPointEstimator(only_cond, cam, kFrameHz).initialise(obs, &out));
  only_cond.max_cond_number = 1e15;
  EXPECT_TRUE(SlamPointEstimator(only_cond, cam, kFrameHz).initialise(obs, &out));
  EXPECT_LT((out.p_W - Vec3(20, 0.5, 2.0)).norm(), 0.01);
}

TEST(SlamPoints, FlyingForwardOnlyNearGroundPointsPassTheBaselineRatio) {
  // 0.53 s of forward flight at 2 m/s, 2.5 m above the ground (the window at 15 Hz: 9 frames).
  const FisheyeCamera cam;
  const SlamPointEstimator est(SlamPointsConfig{}, cam, kFrameHz);
  ASSERT_EQ(est.windowClones(), 8);  // round(11 · 15 / 21)
  std::vector<Pose> poses;
  for (int i = 8; i >= 0; --i) poses.push_back(poseFromXyzYaw(Vec3(2.0 * i / kFrameHz, 0, 2.5), 0) * cam.T_B_C());
  SlamPoint out;
  const Vec3 near_ground(1.07 + 5.0, 0.5, 0.0), far_ground(1.07 + 25.0, 0.5, 0.0);
  EXPECT_TRUE(est.initialise(observe(cam, poses, near_ground), &out));
  EXPECT_LT((out.p_W - near_ground).norm(), 1e-3);
  EXPECT_FALSE(est.initialise(observe(cam, poses, far_ground), &out));  // |p| / b ≈ 240
  // Beside the path the same distance keeps a transverse baseline of the whole flight.
  const Vec3 side(6.0, 20.0, 2.5);  // ahead of the anchor: OpenVINS refuses depth < 0.1 m along the axis)
  EXPECT_TRUE(est.initialise(observe(cam, poses, side), &out));
}

// One frame's tracks of the points `ids`→`points`, seen from T.
TrackFrame frameOf(int i, const Pose& T, const std::map<uint64_t, Vec3>& points) {
  const FisheyeCamera cam;
  TrackFrame tf;
  tf.tick = i;
  tf.t_s = i / kFrameHz;
  for (const auto& [id, p] : points) tf.tracks.push_back({id, cam.project(T.inverse() * p), i});
  return tf;
}

Pose sidewaysPose(int i) { return poseFromXyzYaw(Vec3(0, 1.0 * i / kFrameHz, 1.5), 0) * FisheyeCamera().T_B_C(); }

TEST(SlamPoints, TracksBecomeSlamPointsOnlyAfterTheDelayAndOnceTheySpanTheWindow) {
  const FisheyeCamera cam;
  SlamPointEstimator est(SlamPointsConfig{}, cam, kFrameHz);
  const Vec3 a(8, 1, 1), b(9, -1, 2);
  for (int i = 0; i <= 18; ++i) {
    std::map<uint64_t, Vec3> pts = {{7, a}};
    if (i >= 10) pts[9] = b;  // a younger track
    const SlamPointsFrame out = est.update(frameOf(i, sidewaysPose(i), pts), sidewaysPose(i));
    if (i < 17) {
      // Frames 0–8 filled a window before the 1 s delay: that window was used up (OpenVINS
      // spends it on an MSCKF update); the next one is full at frame 17.
      EXPECT_TRUE(out.points.empty()) << "frame " << i;
    } else if (i == 17) {
      ASSERT_EQ(out.points.size(), 1u);
      EXPECT_EQ(out.points[0].track_id, 7u);
      EXPECT_LT((out.points[0].p_W - a).norm(), 1e-3);
      EXPECT_EQ(out.points[0].anchor_tick, 17);  // anchored at the newest observation
    } else {
      ASSERT_EQ(out.points.size(), 2u);  // track 9 spans its window at frame 18 (frames 10–18)
      EXPECT_EQ(out.points[1].track_id, 9u);
    }
  }
  // A lost track is marginalised.
  EXPECT_TRUE(est.update(frameOf(19, sidewaysPose(19), {{9, b}}), sidewaysPose(19)).points.size() == 1);
  EXPECT_TRUE(est.update(TrackFrame{}, sidewaysPose(20)).points.empty());
}

// A frame in which track `id`'s pixel is `offset` off where the point projects.
TrackFrame frameWithOffset(int i, const Pose& T, uint64_t id, const Vec3& p, const Vec2& offset) {
  TrackFrame tf = frameOf(i, T, {{id, p}});
  tf.tracks[0].pixel += offset;
  return tf;
}

TEST(SlamPoints, TheSecondFailedUpdateInAFeaturesLifeMarginalisesItAsOpenVinsChi2Rule) {
  // OpenVINS counts χ²-gate failures over a feature's whole life (update_fail_count is never
  // reset) and marginalises at the second; a rejected observation is not used.
  SlamPointsConfig cfg;
  cfg.dt_slam_delay_s = 0.0;
  SlamPointEstimator est(cfg, FisheyeCamera(), kFrameHz);
  const Vec3 a(8, 1, 1);
  int i = 0;
  for (; i <= 8; ++i) est.update(frameOf(i, sidewaysPose(i), {{7, a}}), sidewaysPose(i));
  auto pointsAt = [&](const TrackFrame& f) { return est.update(f, sidewaysPose(f.tick)).points; };
  ASSERT_EQ(pointsAt(frameOf(i, sidewaysPose(i), {{7, a}})).size(), 1u);  // in the state
  ++i;
  // First failure: a 40-px jump is rejected; the feature keeps its estimate.
  auto out = pointsAt(frameWithOffset(i, sidewaysPose(i), 7, a, Vec2(40, 0)));
  ++i;
  ASSERT_EQ(out.size(), 1u);
  EXPECT_LT((out[0].p_W - a).norm(), 1e-3);
  // Clean updates succeed (the rejected observation is not in them) ...
  for (int k = 0; k < 5; ++k, ++i) {
    out = pointsAt(frameOf(i, sidewaysPose(i), {{7, a}}));
    ASSERT_EQ(out.size(), 1u);
    EXPECT_LT(out[0].reprojection_rms_px, 1e-3);
  }
  // ... and do not reset the count: the second failure marginalises the feature.
  EXPECT_TRUE(pointsAt(frameWithOffset(i, sidewaysPose(i), 7, a, Vec2(40, 0))).empty());
}

TEST(SlamPoints, AtMostMaxSlamInUpdateNewFeaturesPerFrameAndMaxSlamInTheState) {
  const FisheyeCamera cam;
  std::map<uint64_t, Vec3> pts;
  RngStream rng(3, "slam_caps");
  for (uint64_t id = 1; id <= 40; ++id) pts[id] = Vec3(rng.uniform(5, 10), rng.uniform(-3, 3), rng.uniform(0, 3));
  SlamPointsConfig cfg;
  cfg.dt_slam_delay_s = 0.0;
  SlamPointEstimator est(cfg, cam, kFrameHz);
  size_t first = 0, second = 0;
  for (int i = 0; i <= 17; ++i) {
    const auto out = est.update(frameOf(i, sidewaysPose(i), pts), sidewaysPose(i));
    if (i < 8) {
      EXPECT_TRUE(out.points.empty());
    }
    if (i == 8) first = out.points.size();
    if (i == 17) second = out.points.size();
  }
  EXPECT_EQ(first, 25u);   // 40 max tracks, 25 taken; the other 15 start new windows
  EXPECT_EQ(second, 40u);  // ... and join nine frames later
  cfg.max_slam = 10;
  SlamPointEstimator capped(cfg, cam, kFrameHz);
  size_t last = 0;
  for (int i = 0; i <= 17; ++i) last = capped.update(frameOf(i, sidewaysPose(i), pts), sidewaysPose(i)).points.size();
  EXPECT_EQ(last, 10u);
}

}  // namespace
}  // namespace msb
