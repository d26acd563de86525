// Shortcutting and heading assignment with and without forced forward flight.
#include <gtest/gtest.h>

#include <cmath>

#include "core/methods/monospheres/planner/path_shaping.h"

namespace msb {
namespace {

TEST(PathShaping, ShortcutKeepsOnlyNeededCorners) {
  const std::vector<Vec3> pts = {{0, 0, 2}, {2, 0, 2}, {4, 0, 2}, {6, 0, 2}, {6, 2, 2}, {6, 4, 2}, {6, 6, 2}};
  // Free space: everything except a pillar at (2, 3): segments passing within 2 m are blocked.
  auto free = [](const Vec3& a, const Vec3& b) {
    const Vec3 c(2, 3, 2);
    const Vec3 d = b - a;
    const double t = std::clamp((c - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - c).norm() > 2.0;
  };
  const auto out = shortcutPath(pts, free);
  ASSERT_GE(out.size(), 3u);
  EXPECT_EQ(out.front(), pts.front());
  EXPECT_EQ(out.back(), pts.back());
  for (size_t i = 1; i < out.size(); ++i) EXPECT_TRUE(free(out[i - 1], out[i]));
  EXPECT_LT(pathLength(out), pathLength(pts));
  // Everything free: a straight line.
  EXPECT_EQ(shortcutPath(pts, [](const Vec3&, const Vec3&) { return true; }).size(), 2u);
  // Nothing free: the original path.
  EXPECT_EQ(shortcutPath(pts, [](const Vec3&, const Vec3&) { return false; }).size(), pts.size());
}

TEST(PathShaping, FffTurnsOnlyInTheFinalStretch) {
  const std::vector<Vec3> pts = {{0, 0, 2}, {10, 0, 2}, {20, 0, 2}};
  const double goal = M_PI / 2, rate = 0.314;
  const HeadingPlan p = assignHeadings(pts, goal, true, rate);
  EXPECT_TRUE(p.feasible);
  EXPECT_NEAR(p.turn_stretch_m, goal / rate, 1e-9);  // 5.0 m for 90°
  double prev_h = 0.0, prev_x = 0.0;
  for (const auto& w : p.waypoints) {
    const double x = w.position_m.x();
    if (x <= 20 - p.turn_stretch_m + 1e-6) {
      EXPECT_FALSE(w.heading_rad) << x;  // face the direction of travel
      continue;
    }
    ASSERT_TRUE(w.heading_rad) << x;
    // Heading grows linearly with distance, never faster than the budget.
    EXPECT_NEAR(*w.heading_rad, goal * (x - (20 - p.turn_stretch_m)) / p.turn_stretch_m, 1e-9);
    if (x > prev_x) {
      EXPECT_LE((*w.heading_rad - prev_h) / (x - prev_x), rate + 1e-9);
    }
    prev_h = *w.heading_rad, prev_x = x;
  }
  EXPECT_DOUBLE_EQ(*p.waypoints.back().heading_rad, goal);
  EXPECT_EQ(p.waypoints.back().position_m, pts.back());
  // A 3 m approach cannot fit a 90° turn at 0.314 rad/m.
  EXPECT_FALSE(assignHeadings({{0, 0, 2}, {3, 0, 2}}, goal, true, rate).feasible);
  // Re-planning inside the stretch: turn from the current heading over what is left.
  const HeadingPlan late = assignHeadings({{0, 0, 2}, {3, 0, 2}}, goal, true, rate, 1.0, 0.8);
  ASSERT_TRUE(late.waypoints.front().heading_rad);
  EXPECT_GT(*late.waypoints.front().heading_rad, 0.8);
  EXPECT_DOUBLE_EQ(*late.waypoints.back().heading_rad, goal);
}

TEST(PathShaping, WithoutFffEveryWaypointTakesTheGoalHeading) {
  const std::vector<Vec3> pts = {{0, 0, 2}, {10, 0, 2}, {10, 10, 2}};
  const HeadingPlan p = assignHeadings(pts, 2.0, false, 0.314);
  ASSERT_EQ(p.waypoints.size(), 2u);
  for (const auto& w : p.waypoints) EXPECT_DOUBLE_EQ(*w.heading_rad, 2.0);
  EXPECT_TRUE(p.feasible);
}

}  // namespace
}  // namespace msb
