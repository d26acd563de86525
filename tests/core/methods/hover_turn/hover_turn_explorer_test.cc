// hover_turn, the example method: its phases and its one free-space sphere.
#include "core/methods/hover_turn/hover_turn_explorer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

VehicleState at(int64_t tick, bool finished) {
  VehicleState v;
  v.tick = tick;
  v.path_finished = finished;
  return v;
}

SlamPointsFrame pointAt(const Vec3& p) {
  SlamPointsFrame f;
  SlamPoint s;
  s.p_W = p;
  f.points.push_back(s);
  return f;
}

TEST(HoverTurn, ClimbsTurnsOnceDescendsAndHolds) {
  HoverTurnConfig c;
  c.turn_step_deg = 90.0;
  ExplorerContext ctx;
  ctx.start = poseFromXyzYaw(Vec3(0, 0, 0), 0.0);
  HoverTurnExplorer ex(c, ctx);
  // Climb to 2 m.
  auto cmd = ex.plan(at(1, true));
  ASSERT_TRUE(cmd);
  EXPECT_TRUE(cmd->waypoints.front().position_m.isApprox(Vec3(0, 0, 2)));
  EXPECT_FALSE(ex.plan(at(2, false)));  // waits for the tracker
  // Four 90° steps, each its own path.
  for (int k = 1; k <= 4; ++k) {
    cmd = ex.plan(at(10 + k, true));
    ASSERT_TRUE(cmd) << k;
    EXPECT_NEAR(std::cos(*cmd->waypoints.front().heading_rad), std::cos(k * M_PI / 2), 1e-9) << k;
  }
  // Then the descent to 0.3 m, then nothing more.
  cmd = ex.plan(at(20, true));
  ASSERT_TRUE(cmd);
  EXPECT_NEAR(cmd->waypoints.front().position_m.z(), 0.3, 1e-12);
  EXPECT_FALSE(ex.plan(at(21, true)));
  EXPECT_FALSE(ex.plan(at(22, true)));
  EXPECT_EQ(ex.counters().at("turn_steps"), 4.0);
}

TEST(HoverTurn, TheSphereHoldsNoPointSeenDuringTheTurn) {
  HoverTurnConfig c;
  ExplorerContext ctx;
  HoverTurnExplorer ex(c, ctx);
  ex.observe(pointAt(Vec3(1, 0, 2)));  // before the turn: ignored
  EXPECT_TRUE(ex.snapshot().free_space.empty());
  ex.plan(at(1, true));                // climb sent
  ex.plan(at(2, true));                // climb done: the turn starts
  ex.observe(pointAt(Vec3(3, 0, 2)));  // 3 m from the hover point (0, 0, 2)
  ex.plan(at(3, true));                // one turn step done
  const auto fs = ex.snapshot().free_space;
  ASSERT_EQ(fs.size(), 1u);
  EXPECT_NEAR(fs.front().radius, 3.0 - c.margin_m, 1e-12);
  EXPECT_TRUE(fs.front().centre.isApprox(Vec3(0, 0, 2)));
  EXPECT_EQ(ex.counters().at("points_seen"), 1.0);
}

}  // namespace
}  // namespace msb
