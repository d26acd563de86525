// The shared take-off and sendPath: what every method flies first, and how a sent path is recorded.
#include "core/explorer/takeoff.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/explorer/counters.h"
#include "core/explorer/explorer.h"

namespace msb {
namespace {

TEST(Takeoff, ClimbsThenFliesAheadOncePerLegAndWaitsForEach) {
  // Start at (1, 2, 0) facing +y: climb 3 m, then 4 m ahead along +y.
  TakeoffSequence t(poseFromXyzYaw(Vec3(1, 2, 0), M_PI / 2), 3.0, 4.0);
  const auto climb = t.step(true);
  ASSERT_TRUE(climb && climb->size() == 1u);
  EXPECT_TRUE(climb->front().position_m.isApprox(Vec3(1, 2, 3)));
  EXPECT_NEAR(*climb->front().heading_rad, M_PI / 2, 1e-12);
  EXPECT_FALSE(t.step(false));  // the climb is not finished: nothing new
  EXPECT_FALSE(t.step(true));   // finished: the next step sends the forward leg
  const auto ahead = t.step(false);
  ASSERT_TRUE(ahead);
  EXPECT_TRUE(ahead->front().position_m.isApprox(Vec3(1, 6, 3), 1e-12));
  EXPECT_FALSE(t.done());
  EXPECT_FALSE(t.step(true));
  EXPECT_TRUE(t.done());
  EXPECT_FALSE(t.step(true));  // done: never sends again
}

TEST(Takeoff, ConfigValidationNamesEachBadKey) {
  TakeoffConfig c;
  ConfigChecker ok("takeoff");
  checkFields(c, ok);
  EXPECT_TRUE(ok.issues().empty());
  c.takeoff_altitude_m = 0.1;  // below the 0.3 m floor
  c.start_forward_m = -1.0;
  ConfigChecker bad("takeoff");
  checkFields(c, bad);
  EXPECT_EQ(bad.issues().size(), 2u);
}

TEST(SendPath, RecordsThePathFromTheReferenceAndCountsIt) {
  VehicleState v;
  v.tick = 42;
  v.reference.position_m = Vec3(1, 1, 1);
  std::vector<Vec3> last;
  double paths_sent = 0;
  const PathCommand cmd = sendPath(v, {{Vec3(2, 2, 2), std::nullopt}, {Vec3(3, 3, 3), 0.5}}, last, paths_sent);
  EXPECT_EQ(cmd.tick, 42);
  ASSERT_EQ(cmd.waypoints.size(), 2u);
  ASSERT_EQ(last.size(), 3u);
  EXPECT_TRUE(last.front().isApprox(Vec3(1, 1, 1)));
  EXPECT_TRUE(last.back().isApprox(Vec3(3, 3, 3)));
  EXPECT_EQ(paths_sent, 1.0);
  sendPath(v, {{Vec3(0, 0, 1), std::nullopt}}, last, paths_sent);
  EXPECT_EQ(paths_sent, 2.0);
  EXPECT_EQ(last.size(), 2u);
}

enum class DemoCounter { kGoalsReached, kPathsSent, kCount };

TEST(Counters, AreIndexedByTheEnumAndWrittenByName) {
  Counters<DemoCounter> c({"goals_reached", "paths_sent"});
  ++c[DemoCounter::kPathsSent];
  c[DemoCounter::kPathsSent] += 2;
  const auto m = c.toMap();
  ASSERT_EQ(m.size(), 2u);  // zeros included: every counter is always written
  EXPECT_EQ(m.at("goals_reached"), 0.0);
  EXPECT_EQ(m.at("paths_sent"), 3.0);
}

}  // namespace
}  // namespace msb
