// The grid explorer's decisions: goals stay in the square around the vehicle and in the box,
// take-off first, then a goal and a path that avoids mapped obstacles; the predicted-path
// check stops the vehicle when an obstacle appears on its path; a goal chooser's goals, paths
// and "no goal" replace the draw.
#include <gtest/gtest.h>

#include <cmath>

#include "core/methods/grid_random/grid_explorer.h"
#include "core/methods/grid_random/grid_test_seam.h"

namespace msb {
namespace {

// The explorer's mechanics on hand-built maps where most space is unknown: unknown space
// traversable (the default blocks it, tested in the planner tests).
GridExplorerConfig traversableUnknown() {
  GridExplorerConfig c;
  c.planner.unknown_is_occupied = false;
  return c;
}

ExplorerContext context() {
  ExplorerContext ctx;
  ctx.exploration_box = {Vec3(-50, -45, 0), Vec3(12, 20, 7)};
  ctx.start = poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0);
  ctx.seed = 5;
  return ctx;
}

VehicleState at(const Vec3& p, double t, bool finished) {
  VehicleState s;
  s.t_s = t;
  s.T_W_B = poseFromXyzYaw(p, 0.0);
  s.reference.position_m = p;
  s.path_finished = finished;
  return s;
}

TEST(GridExplorer, GoalsStayInTheSquareAndTheBox) {
  GridExplorer e(GridExplorerConfig{}, context());
  const Aabb box = context().exploration_box;
  for (const Vec3& p : {Vec3(0, 0, 2), Vec3(10, 18, 2), Vec3(-49, -44, 6), Vec3(-20, -10, 3)}) {
    Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
    for (int k = 0; k < 2000; ++k) {
      const Vec3 g = e.drawGoal(p);
      ASSERT_TRUE(box.contains(g)) << g.transpose();
      ASSERT_LE(std::abs(g.x() - p.x()), 20.0 + 1e-9);
      ASSERT_LE(std::abs(g.y() - p.y()), 20.0 + 1e-9);
      ASSERT_GE(g.z(), 1.0);
      ASSERT_LE(g.z(), 6.5);
      lo = lo.cwiseMin(g.head<2>());
      hi = hi.cwiseMax(g.head<2>());
    }
    // Uniform over the whole intersection: its corners are approached.
    const Vec2 want_lo = (p.head<2>() - Vec2(20, 20)).cwiseMax(box.min.head<2>());
    const Vec2 want_hi = (p.head<2>() + Vec2(20, 20)).cwiseMin(box.max.head<2>());
    EXPECT_LT((lo - want_lo).norm(), 1.0);
    EXPECT_LT((hi - want_hi).norm(), 1.0);
  }
}

TEST(GridExplorer, ThePublishedGoalsSpanTheBoxsWholeHeightBand) {
  // random_octomap_explorer.py sample_free_point: z uniform over [z_min, z_max] of the safety
  // area (urban 0…7 m). The intended band keeps 1 m above the floor and 0.5 m below the top.
  for (const bool published : {false, true}) {
    GridExplorerConfig c;
    if (published) c.applyPublishedSettings();
    GridExplorer e(c, context());
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 4000; ++k) {
      const double z = e.drawGoal(Vec3(0, 0, 2)).z();
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
    EXPECT_NEAR(lo, published ? 0.0 : 1.0, 0.02) << "published " << published;
    EXPECT_NEAR(hi, published ? 7.0 : 6.5, 0.02) << "published " << published;
    EXPECT_GE(lo, published ? 0.0 : 1.0);
    EXPECT_LE(hi, published ? 7.0 : 6.5);
  }
}

TEST(GridExplorer, TakesOffThenPlansAroundMappedObstacles) {
  GridExplorer e(traversableUnknown(), context());
  // A wall west of the start (the explorer's goals will be all around).
  GridMap& map = GridExplorerTestSeam::map(e);
  for (double x = -20.25; x < 10; x += 0.5)
    for (double z = 0.25; z < 7; z += 0.5)
      GridMapTestSeam::tree(map).updateNode(octomap::point3d(float(x), 6.25f, float(z)), true);
  GridMapTestSeam::tree(map).updateInnerOccupancy();
  const auto wall = map.leaves(true);
  // Take-off: climb, then forward.
  ASSERT_TRUE(e.plan(at(Vec3(0, 0, 0.05), 0.0, true)));
  EXPECT_FALSE(e.plan(at(Vec3(0, 0, 2), 0.2, true)));
  ASSERT_TRUE(e.plan(at(Vec3(0, 0, 2), 0.4, false)));
  EXPECT_FALSE(e.plan(at(Vec3(4, 0, 2), 0.6, true)));
  // Exploring: a goal, a path to it that never comes within 1.5 m of the wall's cells.
  for (int k = 0; k < 20; ++k) {
    const double t = 1.0 + 1.0 * k;
    const auto cmd = e.plan(at(Vec3(4, 0, 2.05), t, true));
    ASSERT_TRUE(e.goal());
    if (!cmd) continue;
    Vec3 a(4, 0, 2.05);
    for (const auto& w : cmd->waypoints) {
      EXPECT_FALSE(w.heading_rad) << "the camera faces the direction of travel";
      for (double s = 0; s <= 1.0; s += 0.002) {
        // The cell the path passes through keeps the clearance from every wall cell (points on
        // a cell boundary belong to either cell: skipped).
        const Vec3 x = a + s * (w.position_m - a);
        const Vec3 frac = (x / 0.5) - (x / 0.5).array().round().matrix();
        if (frac.cwiseAbs().minCoeff() < 1e-6) continue;
        const Vec3 cell = ((x / 0.5).array().floor() + 0.5).matrix() * 0.5;
        for (const auto& o : wall) EXPECT_GT((cell - o.centre).norm(), 1.5) << x.transpose();
      }
      a = w.position_m;
    }
  }
  EXPECT_GE(e.counters().at("goals_chosen"), 2.0);
}

TEST(GridExplorer, AnObstacleOnThePathAheadStopsTheVehicle) {
  GridExplorer e(traversableUnknown(), context());
  for (int k = 0; k < 4; ++k) e.plan(at(Vec3(0, 0, 2), 0.2 * k, true));  // take-off done
  const auto cmd = e.plan(at(Vec3(4, 0, 2), 1.0, true));
  ASSERT_TRUE(cmd);
  ASSERT_FALSE(cmd->waypoints.empty());
  // An obstacle point appears 2 m ahead on the path: the next step stops.
  const Vec3 dir = (cmd->waypoints.front().position_m - Vec3(4, 0, 2)).normalized();
  const Vec3 obstacle = Vec3(4, 0, 2) + 2.0 * dir;
  GridMapTestSeam::tree(GridExplorerTestSeam::map(e))
      .updateNode(octomap::point3d(float(obstacle.x()), float(obstacle.y()), float(obstacle.z())), true);
  GridMapTestSeam::tree(GridExplorerTestSeam::map(e)).updateInnerOccupancy();
  const auto stop = e.plan(at(Vec3(4, 0, 2), 1.2, false));
  ASSERT_TRUE(stop);
  ASSERT_EQ(stop->waypoints.size(), 1u);
  EXPECT_TRUE(stop->waypoints[0].position_m.isApprox(Vec3(4, 0, 2)));
  EXPECT_EQ(e.counters().at("blocked_stops"), 1.0);
}

// Take-off done for an explorer at (4, 0, 2) (its two legs, as in the test above).
void takeOff(GridExplorer& e) {
  ASSERT_TRUE(e.plan(at(Vec3(0, 0, 0.05), 0.0, true)));
  EXPECT_FALSE(e.plan(at(Vec3(0, 0, 2), 0.2, true)));
  ASSERT_TRUE(e.plan(at(Vec3(0, 0, 2), 0.4, false)));
  EXPECT_FALSE(e.plan(at(Vec3(4, 0, 2), 0.6, true)));
}

// mrs_octomap_planner's failure rule (timerMain): a failed plan sends nothing and is tried again
// at once; after two in a row the planner is idle until the explorer's next goal. msbench's
// rule stops the vehicle and asks for a new goal at the next goal check. Here every plan fails
// (nothing is known: the published grid plans through known cells only).
TEST(GridExplorer, ThePublishedPlannerTriesTwiceSendingNothingThenWaitsForANewGoal) {
  GridExplorerConfig published;
  published.applyPublishedSettings();
  published.planner.planning_tree_resolution_m = 0.0;
  ASSERT_TRUE(published.reference_failures);
  GridExplorer ref(published, context());
  takeOff(ref);
  EXPECT_FALSE(ref.plan(at(Vec3(4, 0, 2), 1.0, true)));  // a goal; the plan fails: nothing sent
  EXPECT_EQ(ref.counters().at("paths_failed"), 1.0);
  EXPECT_FALSE(ref.plan(at(Vec3(4, 0, 2), 1.2, true)));  // tried again at once: fails, idle
  EXPECT_FALSE(ref.plan(at(Vec3(4, 0, 2), 1.4, true)));  // idle: no plan
  EXPECT_EQ(ref.counters().at("paths_failed"), 2.0);
  EXPECT_EQ(ref.counters().at("goals_idle"), 0.0);
  EXPECT_FALSE(ref.plan(at(Vec3(4, 0, 2), 2.0, true)));  // the next goal check: a new goal
  EXPECT_EQ(ref.counters().at("goals_idle"), 1.0);
  EXPECT_EQ(ref.counters().at("paths_failed"), 3.0);

  published.reference_failures = false;
  GridExplorer ours(published, context());
  takeOff(ours);
  const auto stop = ours.plan(at(Vec3(4, 0, 2), 1.0, true));  // fails: the vehicle is stopped
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->waypoints.size(), 1u);
  EXPECT_FALSE(ours.plan(at(Vec3(4, 0, 2), 1.2, true)));
  EXPECT_FALSE(ours.plan(at(Vec3(4, 0, 2), 1.4, true)));
  EXPECT_EQ(ours.counters().at("paths_failed"), 1.0);
}

// Only a complete path resets the reference's failure count: failure, a path short of the goal,
// failure, and the planner is idle (with every path resetting it, it would try a third time).
TEST(GridExplorer, APathShortOfTheGoalDoesNotResetThePublishedFailureCount) {
  GridExplorerConfig published;
  published.applyPublishedSettings();
  published.planner.planning_tree_resolution_m = 0.0;
  GridExplorer e(published, context());
  GridMap& map = GridExplorerTestSeam::map(e);
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(-8.25, y, z), {Vec3(6.9, y, z)});
  bool given = false;  // one goal, in unknown space beyond the known slab
  e.setGoalChooser([&](const GoalRequest&) -> std::optional<std::vector<Vec3>> {
    if (given) return std::nullopt;
    given = true;
    return std::vector<Vec3>{Vec3(4, 15, 2)};
  });
  takeOff(e);
  const Vec3 unknown(4, 0, 6), known(4, 0, 2);
  EXPECT_FALSE(e.plan(at(unknown, 1.0, true)));  // failure 1: tried again at once
  const auto partial = e.plan(at(known, 1.2, true));
  ASSERT_TRUE(partial);  // a path to the known cell closest to the goal
  EXPECT_EQ(e.counters().at("paths_to_closest_cell"), 1.0);
  EXPECT_FALSE(e.plan(at(unknown, 2.2, false)));  // failure 2: idle
  EXPECT_FALSE(e.plan(at(unknown, 2.4, false)));  // idle: no third try
  EXPECT_EQ(e.counters().at("paths_failed"), 2.0);
}

// The time budget (the reference's 1 s `timeout_threshold`): a hovering vehicle's plan gets
// timeout + 1.5^failures, a moving one's the timeout alone; the A* expansions it can pay for
// are the budget less the planning tree's work over the cost of one (kGridBudgetCosts).
TEST(GridExplorer, TheTimeBudgetStopsAMovingVehiclesSearchAndNotAHoveringOnes) {
  GridExplorerConfig published;
  published.applyPublishedSettings();
  published.planner.planning_tree_resolution_m = 0.0;
  published.planner.time_budget_s = 2 * kGridBudgetCosts.per_expansion_s;  // two expansions
  GridExplorer e(published, context());
  GridMap& map = GridExplorerTestSeam::map(e);
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -9.75; y < 10.0; y += 0.5) map.insertScan(Vec3(-8.25, y, z), {Vec3(6.9, y, z)});
  takeOff(e);
  ASSERT_TRUE(e.plan(at(Vec3(4, 0, 2), 1.0, true)));  // hovering: 1 s and more
  EXPECT_EQ(e.counters().at("paths_over_budget"), 0.0);
  e.plan(at(Vec3(4, 0, 2), 2.0, false));  // moving: two expansions
  EXPECT_EQ(e.counters().at("paths_over_budget"), 1.0);
}

TEST(GridExplorer, AGoalChoosersGoalsPathsAndNoGoalReplaceTheDraw) {
  GridExplorer e(traversableUnknown(), context());
  std::vector<GoalRequest> asked;
  std::optional<std::vector<Vec3>> answer = std::vector<Vec3>{Vec3(8, 3, 2)};
  e.setGoalChooser([&](const GoalRequest& q) {
    asked.push_back(q);
    return answer;
  });
  takeOff(e);
  // One point: a goal A* plans to.
  auto cmd = e.plan(at(Vec3(4, 0, 2), 1.0, true));
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_TRUE(asked[0].needs_goal);
  EXPECT_EQ(asked[0].position, Vec3(4, 0, 2));
  ASSERT_TRUE(e.goal() && cmd);
  EXPECT_EQ(*e.goal(), Vec3(8, 3, 2));
  EXPECT_LT((cmd->waypoints.back().position_m - Vec3(8, 3, 2)).norm(), 0.5);
  // Nothing: the goal stays, the chooser is asked again at the next check (not needing a goal).
  answer.reset();
  EXPECT_FALSE(e.plan(at(Vec3(5, 1, 2), 1.5, false)));
  e.plan(at(Vec3(5, 1, 2), 2.0, false));
  ASSERT_EQ(asked.size(), 2u);
  EXPECT_FALSE(asked[1].needs_goal);
  EXPECT_EQ(*e.goal(), Vec3(8, 3, 2));
  // Several points: a path flown exactly as given, not re-planned.
  answer = std::vector<Vec3>{Vec3(5, 2, 2), Vec3(6, 4, 3)};
  cmd = e.plan(at(Vec3(5, 1, 2), 3.0, false));
  ASSERT_TRUE(cmd);
  ASSERT_EQ(cmd->waypoints.size(), 2u);
  EXPECT_EQ(cmd->waypoints[1].position_m, Vec3(6, 4, 3));
  answer.reset();
  EXPECT_FALSE(e.plan(at(Vec3(5, 1.5, 2), 4.5, false)));
  // An empty list: no goal, and the moving vehicle stops where its reference is.
  answer = std::vector<Vec3>{};
  cmd = e.plan(at(Vec3(5, 2, 2), 5.5, false));
  EXPECT_FALSE(e.goal());
  ASSERT_TRUE(cmd);
  ASSERT_EQ(cmd->waypoints.size(), 1u);
  EXPECT_EQ(cmd->waypoints[0].position_m, Vec3(5, 2, 2));
}

}  // namespace
}  // namespace msb
