#include "sim/physics/mrs_trajectory_generator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/physics/trajectory_tracker.h"

namespace msb {
namespace {

constexpr double kPi = std::numbers::pi;

MrsGeneratorConfig withSet(const std::string& name) {
  MrsGeneratorConfig c;
  c.constraints = *MrsConstraints::preset(name);
  return c;
}

MrsInitialState atRest(const Vec3& p, double yaw) {
  MrsInitialState s;
  s.reference.position_m = p;
  s.reference.yaw_rad = yaw;
  return s;
}

double duration(const MrsTrajectory& t) { return double(t.samples.size() - 1) * t.dt_s; }

TEST(MrsTrajectoryGenerator, ConstraintSetsAreTheConstraintManagers) {
  const auto f = *MrsConstraints::preset("fast"), m = *MrsConstraints::preset("medium");
  EXPECT_EQ(f.horizontal_speed_mps, 8.0);
  EXPECT_EQ(f.vertical_speed_mps, 4.0);  // vertical half the horizontal
  EXPECT_EQ(f.heading_accel_radps2, 2.0);
  EXPECT_EQ(m.horizontal_speed_mps, 4.0);
  EXPECT_EQ(m.vertical_accel_mps2, 1.0);
  EXPECT_EQ(m.heading_accel_radps2, 1.0);
  EXPECT_FALSE(MrsConstraints::preset("ludicrous"));
}

TEST(MrsTrajectoryGenerator, ANinetyDegreeHeadingStepTakesTheHeadingTermsSegmentTime) {
  // 1.5·(Δψ/ω − ω²/α over ω, else Δψ/ω) + 1.5·2ω/α for Δψ > 45°, whatever the distance.
  const MrsTrajectoryGenerator medium(withSet("medium")), fast(withSet("fast"));
  const Eigen::Vector4d a(0, 0, 2, 0), b(1, 0, 2, kPi / 2), c(1, 0, 2, kPi / 6);
  EXPECT_NEAR(medium.euclideanSegmentTime(a, b), 1.5 * ((kPi / 2 - 1.0) + 2.0), 1e-12);  // 3.86 s
  EXPECT_NEAR(fast.euclideanSegmentTime(a, b), 1.5 * (kPi / 4 + 2.0), 1e-12);            // 4.18 s
  EXPECT_NEAR(medium.euclideanSegmentTime(a, c), 1.5 * (kPi / 6), 1e-12);                // 30°: no acceleration term
  // The generated trajectory takes at least that long for one metre.
  const auto t = fast.generate(atRest(Vec3(0, 0, 2), 0.0), {{Vec3(1, 0, 2), kPi / 2}});
  EXPECT_GE(duration(t), 1.5 * (kPi / 4 + 2.0) - 0.2);
  EXPECT_NEAR(t.samples.back().heading_rad, kPi / 2, 0.02);
  const auto t0 = fast.generate(atRest(Vec3(0, 0, 2), 0.0), {{Vec3(1, 0, 2), 0.0}});
  EXPECT_LT(duration(t0), 2.0);
}

TEST(MrsTrajectoryGenerator, ACornerIsFlownWithinTheDeviationLimit) {
  // 12 m east, then 12 m north: samples leave the path by at most max_deviation once the
  // corner's segments are split; with a loose limit the corner is cut.
  const std::vector<Waypoint> l = {{Vec3(12, 0, 2), {}}, {Vec3(12, 12, 2), {}}};
  const MrsTrajectoryGenerator tight(withSet("fast"));
  MrsGeneratorConfig loose_cfg = withSet("fast");
  loose_cfg.max_deviation_m = 10.0;
  const MrsTrajectoryGenerator loose(loose_cfg);
  const auto t = tight.generate(atRest(Vec3(0, 0, 2), 0.0), l);
  const auto u = loose.generate(atRest(Vec3(0, 0, 2), 0.0), l);
  EXPECT_FALSE(t.fallback);
  EXPECT_GT(t.deviation_splits, 0);
  EXPECT_EQ(u.deviation_splits, 0);
  auto worst = [](const MrsTrajectory& tr) {
    double w = 0;  // distance from the L
    for (const auto& s : tr.samples) {
      const Vec3& p = s.position_m;
      const double d1 = std::hypot(p.y(), std::max(0.0, p.x() - 12.0)),
                   d2 = std::hypot(p.x() - 12.0, std::max(0.0, -p.y()));
      w = std::max(w, std::min(d1, d2));
    }
    return w;
  };
  EXPECT_LT(worst(t), 0.1);
  EXPECT_GT(worst(u), 0.1);
  // At the corner the tight trajectory slows down.
  double corner_speed = 1e9;
  for (const auto& s : t.samples)
    if ((s.position_m - Vec3(12, 0, 2)).norm() < 0.5) corner_speed = std::min(corner_speed, s.velocity_mps.norm());
  EXPECT_LT(corner_speed, 2.0);
  EXPECT_LT((t.samples.back().position_m - Vec3(12, 12, 2)).norm(), 0.05);
}

TEST(MrsTrajectoryGenerator, AClimbIsFlownAtTheVerticalLimit) {
  // Straight up 30 m at `fast`: the vertical limit (4 m/s) binds, not the horizontal (8 m/s).
  const MrsTrajectoryGenerator g(withSet("fast"));
  const auto up = g.generate(atRest(Vec3(0, 0, 2), 0.0), {{Vec3(0, 0, 32), 0.0}});
  const auto along = g.generate(atRest(Vec3(0, 0, 2), 0.0), {{Vec3(30, 0, 2), 0.0}});
  double vz = 0, vx = 0;
  for (const auto& s : up.samples) vz = std::max(vz, std::abs(s.velocity_mps.z()));
  for (const auto& s : along.samples) vx = std::max(vx, std::abs(s.velocity_mps.x()));
  EXPECT_LE(vz, 4.0 * 1.05);
  EXPECT_GT(vz, 3.0);
  EXPECT_GT(vx, 5.0);
  EXPECT_LE(vx, 8.0 * 1.05);
  EXPECT_GT(duration(up), duration(along));
}

TEST(MrsTrajectoryGenerator, StartsFromTheTrackersStateAndIsDeterministic) {
  MrsInitialState s = atRest(Vec3(1, 2, 3), 0.3);
  s.reference.velocity_mps = Vec3(2, 0, 0);
  s.reference.accel_mps2 = Vec3(0, 0.5, 0);
  s.moving = true;
  const MrsTrajectoryGenerator g(withSet("medium"));
  const std::vector<Waypoint> path = {{Vec3(8, 2, 3), {}}, {Vec3(8, 9, 4), {}}, {Vec3(1, 9, 3), {}}};
  const auto a = g.generate(s, path), b = g.generate(s, path);
  ASSERT_FALSE(a.samples.empty());
  EXPECT_NEAR((a.samples[0].position_m - Vec3(1, 2, 3)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((a.samples[0].velocity_mps - Vec3(2, 0, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(a.samples[0].heading_rad, 0.3, 1e-9);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) EXPECT_EQ(a.samples[i].position_m, b.samples[i].position_m);
  // The front-flight headings: the last leg faces west.
  EXPECT_NEAR(std::abs(wrapAngle(a.samples.back().heading_rad)), kPi, 0.05);
}

TEST(MrsTrajectoryGenerator, TheTrackerFollowsTheSamplesToTheEnd) {
  TrajectoryTrackerConfig c;
  c.generator = "mrs";
  TrajectoryTracker tr(c, Vec3(0, 0, 2), 0.0);
  tr.setPath({{Vec3(6, 0, 2), {}}, {Vec3(6, 6, 2), 1.0}});
  ASSERT_FALSE(tr.finished());
  const double expected = double(tr.generated().samples.size() - 1) * tr.generated().dt_s;
  double t = 0;
  while (!tr.finished() && t < 60) tr.update(0.002), t += 0.002;
  ASSERT_TRUE(tr.finished());
  EXPECT_NEAR(t, expected, 0.01);
  EXPECT_LT((tr.reference().position_m - Vec3(6, 6, 2)).norm(), 0.05);
  EXPECT_NEAR(tr.reference().yaw_rad, 1.0, 0.02);
  // A new path mid-flight starts where the reference is, at its velocity.
  TrajectoryTracker tr2(c, Vec3(0, 0, 2), 0.0);
  tr2.setPath({{Vec3(20, 0, 2), {}}});
  for (int i = 0; i < 1000; ++i) tr2.update(0.002);
  const TrajectoryReference before = tr2.reference();
  tr2.setPath({{Vec3(20, 10, 2), {}}});
  EXPECT_NEAR((tr2.generated().samples[0].position_m - before.position_m).norm(), 0.0, 1e-9);
  EXPECT_NEAR((tr2.generated().samples[0].velocity_mps - before.velocity_mps).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace msb
