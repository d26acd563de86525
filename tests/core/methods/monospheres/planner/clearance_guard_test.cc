// The clearance rules on a hand-built map: too close, moving away, blocked paths, the escape.
#include "core/methods/monospheres/planner/clearance_guard.h"
#include "core/methods/monospheres/map/sphere_map_test_seam.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

struct Scene {
  Scene() : map(SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1) {}
  SphereMap map;
};

TEST(ClearanceGuard, TooCloseUnlessMovingAway) {
  Scene s;
  SphereMapTestSeam::addObstacle(s.map, Vec3(0, 0, 2), 1.0);
  ClearanceConfig c;  // clearance 1 m, moving away allowed
  const ClearanceGuard g(s.map, PathCheckConfig{}, c);
  // The vehicle 0.8 m from the point: a sample closer to it is too close, one farther is not.
  const Vec3 here(0.8, 0, 2);
  EXPECT_TRUE(g.tooClose(Vec3(0.5, 0, 2), here));
  EXPECT_FALSE(g.tooClose(Vec3(0.9, 0, 2), here));
  EXPECT_FALSE(g.tooClose(Vec3(3, 0, 2), here));  // outside every clearance
  // Without moving away, any sample inside the clearance is too close.
  c.allow_moving_away = false;
  const ClearanceGuard strict(s.map, PathCheckConfig{}, c);
  EXPECT_TRUE(strict.tooClose(Vec3(0.9, 0, 2), here));
}

TEST(ClearanceGuard, SegmentsAndPathsAheadAreCheckedBySamples) {
  Scene s;
  SphereMapTestSeam::addObstacle(s.map, Vec3(3, 0, 2), 1.0);
  const ClearanceGuard g(s.map, PathCheckConfig{}, ClearanceConfig{});
  const Vec3 here(0, 0, 2);
  EXPECT_FALSE(g.segmentClear(here, Vec3(6, 0, 2), here));  // passes through the point
  EXPECT_TRUE(g.segmentClear(here, Vec3(0, 6, 2), here));   // stays 3 m away
  EXPECT_TRUE(g.pathBlocked({here, Vec3(6, 0, 2)}));
  // Only the first check_ahead_m (5 m) counts: a point 8 m along the path does not block it.
  Scene far;
  SphereMapTestSeam::addObstacle(far.map, Vec3(8, 0, 2), 1.0);
  const ClearanceGuard g2(far.map, PathCheckConfig{}, ClearanceConfig{});
  EXPECT_FALSE(g2.pathBlocked({here, Vec3(10, 0, 2)}));
  EXPECT_FALSE(g2.pathBlocked({}));
}

TEST(ClearanceGuard, EscapeBacksOutBeyondTheClearance) {
  Scene s;
  const Vec3 o(0, 0, 2);
  SphereMapTestSeam::addObstacle(s.map, o, 1.0);
  const ClearanceConfig c;
  const PathCheckConfig check;
  const ClearanceGuard g(s.map, check, c);
  EXPECT_FALSE(g.escape(Vec3(3, 0, 2)));  // not inside a clearance
  const auto target = g.escape(Vec3(0.6, 0, 2));
  ASSERT_TRUE(target);
  EXPECT_NEAR((*target - o).norm(), check.check_clearance_m + c.escape_margin_m, 1e-9);
  EXPECT_GT(target->x(), 0.6);  // straight away from the point
}

}  // namespace
}  // namespace msb
