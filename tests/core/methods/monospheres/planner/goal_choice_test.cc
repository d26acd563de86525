// MonoSpheres' goal choice on hand-built maps: the cheapest reachable viewpoint, local before
// global, FFF's feasibility, how a goal ends, and an outside chooser.
#include "core/methods/monospheres/planner/goal_choice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/methods/monospheres/map/sphere_map_test_seam.h"

namespace msb {
namespace {

// A chain of overlapping spheres along +y (radius 3, 2 m apart) with frontiers on a wall at
// x = 4.5 facing it; viewpoints sampled at the reachable centres; costs from the first sphere.
struct Scene {
  SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
  ViewpointSet viewpoints{ViewpointConfig{}, 5};
  std::vector<uint64_t> spheres;
  SphereCostField field;

  Scene() {
    for (double y = 0; y <= 8; y += 2) spheres.push_back(SphereMapTestSeam::addSphere(map, {0, y, 2}, 3.0));
    for (double y = -4; y <= 12; y += 1.6)
      for (double z = -1; z <= 5; z += 1.6) SphereMapTestSeam::tryAddFrontier(map, {4.5, y, z});
    field = sphereCostsFrom(map, spheres.front(), SafetyCostConfig{});
    viewpoints.update(map, spheres, {100, 100, 2}, 0.0, 0.0, 0, [](const Vec3&) { return true; });
  }
  // The viewpoint the rule should take: least path cost, ties by id.
  uint64_t cheapest() const {
    std::pair<double, uint64_t> best{1e18, 0};
    for (const auto& [id, v] : viewpoints.viewpoints()) best = std::min(best, {field.cost.at(v.sphere), id});
    return best.second;
  }
};

// A straight route: FFF's check sees the travel direction from `from` to the goal.
std::vector<Vec3> straight(const Vec3& from, const SpherePath&, const Vec3& goal) { return {from, goal}; }

// The rule without FFF's feasibility check (most tests are about the rest).
GoalChoiceConfig withoutFff() {
  GoalChoiceConfig c;
  ReferenceCodeConfig rc;  // the intended method
  c.fff = false;
  return c;
}

VehicleState at(const Vec3& p, double yaw, double t) {
  VehicleState s;
  s.t_s = t;
  s.T_W_B = poseFromXyzYaw(p, yaw);
  s.reference.position_m = p;
  s.reference.yaw_rad = yaw;
  return s;
}

TEST(GoalChoice, TakesTheCheapestReachableViewpoint) {
  Scene s;
  ASSERT_GE(s.viewpoints.viewpoints().size(), 2u);
  GoalChoiceConfig c = withoutFff();
  ReferenceCodeConfig rc;  // the intended method
  GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
  EXPECT_EQ(goals.goal(), 0u);
  bool global = true;
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 1.0), s.field, &global));
  EXPECT_FALSE(global);
  EXPECT_EQ(goals.goal(), s.cheapest());
  EXPECT_DOUBLE_EQ(goals.lastProgress(), 1.0);
}

TEST(GoalChoice, SearchesBeyondTheLocalRadiusOnlyAfterEnoughMisses) {
  Scene s;
  GoalChoiceConfig c = withoutFff();
  ReferenceCodeConfig rc;  // the intended method
  c.local_misses_before_global = 3;
  GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
  const VehicleState far = at({0, 40, 2}, 0.0, 1.0);  // every viewpoint beyond 15 m
  bool global = false;
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(goals.takeNew(far, s.field, &global)) << "miss " << k;
  ASSERT_TRUE(goals.takeNew(far, s.field, &global));
  EXPECT_TRUE(global);
  EXPECT_EQ(goals.goal(), s.cheapest());
}

TEST(GoalChoice, FffSkipsGoalsWhoseTurnDoesNotFit) {
  // The cheapest viewpoint from 1 m beyond it (a 180° turn in 1 m): skipped with FFF, taken
  // without; from 8 m before it, flying its heading: taken.
  Scene s;
  const Viewpoint& v = s.viewpoints.viewpoints().at(s.cheapest());
  const Vec3 dir(std::cos(v.yaw_rad), std::sin(v.yaw_rad), 0);
  GoalChoiceConfig c;
  ReferenceCodeConfig rc;  // the intended method
  bool global = false;
  GoalChoice beyond(c, rc, s.viewpoints, s.map, straight);
  if (beyond.takeNew(at(v.position + dir, v.yaw_rad, 1.0), s.field, &global)) {
    EXPECT_NE(beyond.goal(), s.cheapest());
  }
  c.fff = false;
  GoalChoice without_fff(c, rc, s.viewpoints, s.map, straight);
  ASSERT_TRUE(without_fff.takeNew(at(v.position + dir, v.yaw_rad, 1.0), s.field, &global));
  EXPECT_EQ(without_fff.goal(), s.cheapest());
  // The published code keeps the turn check without FFF (reference_code.turn_check_without_fff).
  rc.turn_check_without_fff = true;
  GoalChoice published(c, rc, s.viewpoints, s.map, straight);
  if (published.takeNew(at(v.position + dir, v.yaw_rad, 1.0), s.field, &global)) {
    EXPECT_NE(published.goal(), s.cheapest());
  }
  rc.turn_check_without_fff = false;
  c.fff = true;
  GoalChoice before(c, rc, s.viewpoints, s.map, straight);
  ASSERT_TRUE(before.takeNew(at(v.position - 8.0 * dir, v.yaw_rad, 1.0), s.field, &global));
  EXPECT_EQ(before.goal(), s.cheapest());
}

TEST(GoalChoice, AGoalEndsReachedUnreachableOrWithoutProgress) {
  Scene s;
  GoalChoiceConfig c = withoutFff();
  ReferenceCodeConfig rc;  // the intended method
  GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
  bool global = false;
  // Reached: removed from the set (VPB leaves a marker).
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 0.0), s.field, &global));
  uint64_t id = goals.goal();
  Viewpoint v = s.viewpoints.viewpoints().at(id);
  EXPECT_EQ(goals.checkActive(at(v.position, v.yaw_rad + M_PI, 1.0), s.field), GoalEnd::kNone);  // facing away
  EXPECT_EQ(goals.checkActive(at(v.position, v.yaw_rad, 2.0), s.field), GoalEnd::kReached);
  EXPECT_EQ(goals.goal(), 0u);
  EXPECT_FALSE(s.viewpoints.viewpoints().count(id));
  // Unreachable: its sphere has no cost.
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 3.0), s.field, &global));
  id = goals.goal();
  EXPECT_EQ(goals.checkActive(at({0, 0, 2}, 0.0, 4.0), SphereCostField{}), GoalEnd::kUnreachable);
  EXPECT_FALSE(s.viewpoints.viewpoints().count(id));
  // Without progress: 0.5 m shorter counts as progress, less does not.
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 10.0), s.field, &global));
  goals.noteRemaining(8.0, 12.0);
  EXPECT_DOUBLE_EQ(goals.lastProgress(), 12.0);
  goals.noteRemaining(7.6, 15.0);
  EXPECT_DOUBLE_EQ(goals.lastProgress(), 12.0);
  EXPECT_EQ(goals.checkActive(at({0, 0, 2}, 0.0, 22.0), s.field), GoalEnd::kNone);
  EXPECT_EQ(goals.checkActive(at({0, 0, 2}, 0.0, 22.1), s.field), GoalEnd::kNoProgress);
  EXPECT_EQ(goals.goal(), 0u);
}

TEST(GoalChoice, BlockedStepsRunningFailTheGoal) {
  Scene s;
  GoalChoiceConfig c = withoutFff();
  ReferenceCodeConfig rc;  // the intended method
  c.max_blocked_steps = 3;
  GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
  bool global = false;
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 0.0), s.field, &global));
  const uint64_t id = goals.goal();
  EXPECT_FALSE(goals.noteBlocked(1.0));
  EXPECT_FALSE(goals.noteBlocked(2.0));
  goals.noteUnblocked();  // the count starts again
  EXPECT_FALSE(goals.noteBlocked(3.0));
  EXPECT_FALSE(goals.noteBlocked(4.0));
  EXPECT_TRUE(goals.noteBlocked(5.0));
  EXPECT_EQ(goals.goal(), 0u);
  EXPECT_FALSE(s.viewpoints.viewpoints().count(id));  // blacklisted
}

TEST(GoalChoice, AChooserReplacesTheRule) {
  Scene s;
  GoalChoiceConfig c = withoutFff();
  ReferenceCodeConfig rc;  // the intended method
  GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
  bool global = false;
  // It sees every reachable viewpoint, cheapest first.
  ViewpointRequest seen;
  goals.setChooser([&](const ViewpointRequest& q) {
    seen = q;
    return std::optional<uint64_t>(q.candidates.back().id);
  });
  ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 1.0), s.field, &global));
  ASSERT_EQ(seen.candidates.size(), s.viewpoints.viewpoints().size());
  EXPECT_EQ(seen.candidates.front().id, s.cheapest());
  EXPECT_EQ(goals.goal(), seen.candidates.back().id);
  // Nothing: the rule; 0: no goal; an id that is not a candidate: an error.
  GoalChoice rule(c, rc, s.viewpoints, s.map, straight);
  rule.setChooser([](const ViewpointRequest&) { return std::nullopt; });
  ASSERT_TRUE(rule.takeNew(at({0, 0, 2}, 0.0, 1.0), s.field, &global));
  EXPECT_EQ(rule.goal(), s.cheapest());
  GoalChoice none(c, rc, s.viewpoints, s.map, straight);
  none.setChooser([](const ViewpointRequest&) { return std::optional<uint64_t>(0); });
  EXPECT_FALSE(none.takeNew(at({0, 0, 2}, 0.0, 1.0), s.field, &global));
  GoalChoice wrong(c, rc, s.viewpoints, s.map, straight);
  wrong.setChooser([](const ViewpointRequest&) { return std::optional<uint64_t>(999999); });
  EXPECT_THROW(wrong.takeNew(at({0, 0, 2}, 0.0, 1.0), s.field, &global), std::runtime_error);
}

TEST(GoalChoice, ThePublishedHeadingTestPassesLargeNegativeDifferences) {
  // method.reference_code.heading_check_signed (LNM roadmap_following_iter: hdif(goal −
  // current) > π/2 fails, no abs()): at the goal turned 150° to its left (goal − current =
  // −150°) the goal counts as reached; turned 150° to its right (+150°) it does not.
  for (const bool signed_check : {false, true}) {
    Scene s;
    GoalChoiceConfig c = withoutFff();
    ReferenceCodeConfig rc;  // the intended method
    rc.heading_check_signed = signed_check;
    GoalChoice goals(c, rc, s.viewpoints, s.map, straight);
    bool global = false;
    ASSERT_TRUE(goals.takeNew(at({0, 0, 2}, 0.0, 0.0), s.field, &global));
    const Viewpoint v = s.viewpoints.viewpoints().at(goals.goal());
    const double right = v.yaw_rad - 150.0 * M_PI / 180.0, left = v.yaw_rad + 150.0 * M_PI / 180.0;
    EXPECT_EQ(goals.checkActive(at(v.position, right, 1.0), s.field), GoalEnd::kNone);
    EXPECT_EQ(goals.checkActive(at(v.position, left, 2.0), s.field), signed_check ? GoalEnd::kReached : GoalEnd::kNone)
        << "signed " << signed_check;
  }
}

}  // namespace
}  // namespace msb
