#include "sim/physics/trajectory_tracker.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

// Runs the reference alone until finished or timeout; returns max speed/accel seen.
struct RefStats {
  double max_v = 0, max_a = 0, max_yaw_rate = 0, t = 0;
  bool finished = false;
  TrajectoryReference last;
};

RefStats run(TrajectoryTracker& tr, double max_s) {
  RefStats st;
  for (double t = 0; t < max_s; t += 0.002) {
    const auto& r = tr.update(0.002);
    st.max_v = std::max(st.max_v, r.velocity_mps.norm());
    st.max_a = std::max(st.max_a, r.accel_mps2.norm());
    st.max_yaw_rate = std::max(st.max_yaw_rate, std::abs(r.yaw_rate_radps));
    st.t = t;
    st.last = r;
    if (tr.finished()) {
      st.finished = true;
      break;
    }
  }
  return st;
}

TEST(TrajectoryTracker, PresetsMatchTheReferenceCode) {
  const auto m = TrajectoryLimits::preset("medium"), f = TrajectoryLimits::preset("fast");
  EXPECT_EQ(m.max_speed_mps, 4.0);
  EXPECT_EQ(m.max_accel_mps2, 2.0);
  EXPECT_EQ(m.max_yaw_rate_radps, 1.0);
  EXPECT_EQ(f.max_speed_mps, 8.0);
  EXPECT_EQ(f.max_accel_mps2, 4.0);
  EXPECT_EQ(f.max_yaw_rate_radps, 2.0);
  EXPECT_THROW(TrajectoryLimits::preset("ludicrous"), ConfigError);
}

TEST(TrajectoryTracker, RespectsLimitsAndArrivesWithTheGoalHeading) {
  TrajectoryTracker tr(TrajectoryTrackerConfig{}, Vec3(0, 0, 1), 0.0);
  tr.setPath({{Vec3(30, 0, 1), {}}, {Vec3(30, 20, 3), 2.0}});
  const RefStats st = run(tr, 60.0);
  ASSERT_TRUE(st.finished);
  EXPECT_LE(st.max_v, 4.0 + 1e-9);
  EXPECT_LE(st.max_a, 2.0 + 1e-9);
  EXPECT_LE(st.max_yaw_rate, 1.0 + 1e-9);
  EXPECT_GT(st.max_v, 3.95);
  EXPECT_LT((st.last.position_m - Vec3(30, 20, 3)).norm(), 0.05);
  EXPECT_NEAR(st.last.yaw_rad, 2.0, 0.02);
}

TEST(TrajectoryTracker, FinishesPathsWithShortSegmentsAfterARoundedCorner) {
  // Out 3.5 m, then two laps of a 16-gon of radius 3.5 m: every corner is rounded, so the
  // reference never reaches a segment's end; it must still move on (regression: it stalled
  // and oscillated at the first corner).
  TrajectoryTracker tr(TrajectoryTrackerConfig{}, Vec3(0, 0, 0.05), 0.0);
  std::vector<Waypoint> path = {{Vec3(0, 0, 2.5), {}}};
  for (int k = 0; k <= 32; ++k) {
    const double a = 2 * M_PI * k / 16;
    path.push_back({Vec3(3.5 * std::cos(a), 3.5 * std::sin(a), 2.5), {}});
  }
  path.push_back({Vec3(0, 0, 2.5), 0.0});
  tr.setPath(path);
  const RefStats st = run(tr, 120.0);
  EXPECT_TRUE(st.finished);
  EXPECT_LT(st.t, 60.0);
  EXPECT_EQ(tr.waypointsPassed(), path.size() - 1);  // all but the last, which it reached
}

TEST(TrajectoryTracker, OutAndBackPathsAreFlownInFull) {
  // Regression: with the same line flown back, the next segment projected as closely as the
  // current one and the tracker skipped ahead along the whole path.
  TrajectoryTracker tr(TrajectoryTrackerConfig{}, Vec3(0, 0, 3), 0.0);
  std::vector<Waypoint> path;
  for (int k = 0; k < 3; ++k) path.push_back({Vec3(20, 0, 3), {}}), path.push_back({Vec3(0, 0, 3), {}});
  tr.setPath(path);
  double travelled = 0, max_x = 0;
  Vec3 last = Vec3(0, 0, 3);
  for (int i = 0; i < 60000 && !tr.finished(); ++i) {
    const auto& r = tr.update(0.002);
    travelled += (r.position_m - last).norm();
    last = r.position_m;
    max_x = std::max(max_x, r.position_m.x());
  }
  EXPECT_TRUE(tr.finished());
  // Reversals turn within 0.3 m of their vertex: 5 of them shorten the 120 m by < 3 m.
  EXPECT_NEAR(travelled, 120.0, 3.0);
  EXPECT_NEAR(max_x, 20.0, 0.35);
}

TEST(TrajectoryTracker, HeadingFollowsTheDirectionOfTravel) {
  TrajectoryTracker tr(TrajectoryTrackerConfig{}, Vec3(0, 0, 1), 0.0);
  tr.setPath({{Vec3(0, 30, 1), {}}});
  for (int i = 0; i < 5000; ++i) tr.update(0.002);  // 10 s: cruising along +y
  EXPECT_NEAR(tr.reference().yaw_rad, M_PI / 2, 0.02);
}

TEST(TrajectoryTracker, NewPathContinuesSmoothly) {
  TrajectoryTracker tr(TrajectoryTrackerConfig{}, Vec3(0, 0, 1), 0.0);
  tr.setPath({{Vec3(30, 0, 1), {}}});
  for (int i = 0; i < 3000; ++i) tr.update(0.002);
  const Vec3 v_before = tr.reference().velocity_mps;
  tr.setPath({{Vec3(10, 30, 1), {}}});
  tr.update(0.002);
  EXPECT_LT((tr.reference().velocity_mps - v_before).norm(), 0.05);
}

}  // namespace
}  // namespace msb
