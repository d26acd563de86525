// The earned score on hand-built worlds: sight from inside the box, truth, volume, blanket claims.
#include "core/eval/earned_score.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/core/eval/truth_shapes.h"

namespace msb {
namespace {

using test::block;
using test::ground;

// A ball's volume (m³).
constexpr double ballVolume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

PlacedElement disk(const Vec3& c, double r) {
  PlacedElement e;
  e.centre = c, e.radius = r;
  return e;
}

// A world, its 40 × 40 × 7 m box, the camera and the score, with the camera's looks handed to
// the score as the mission hands them.
struct Scene {
  explicit Scene(std::vector<Shape> shapes)
      : truth(std::move(shapes)), score(truth, Aabb{Vec3(-20, -20, 0), Vec3(20, 20, 7)}), verified(truth, camera, [] {
          VerifiedCoverageConfig c;
          c.z_lo_m = 0.0, c.z_hi_m = 7.0;
          return c;
        }()) {}
  // The camera at `p` looking along +x (optical z = world x).
  void lookFrom(const Vec3& p) {
    Pose T = Pose::Identity();
    T.linear().col(0) = Vec3(0, -1, 0), T.linear().col(1) = Vec3(0, 0, -1), T.linear().col(2) = Vec3(1, 0, 0);
    T.translation() = p;
    VerifiedCoverage::Sight sight;
    verified.look(T, &sight);
    score.see(p, sight);
  }
  WorldTruth truth;
  FisheyeCamera camera;
  EarnedScore score;
  VerifiedCoverage verified;
};

TEST(EarnedScore, DeclaringNothingEarnsNothing) {
  Scene s({ground()});
  s.lookFrom({0, 0, 2});
  EXPECT_EQ(s.score.tally().earnedM3(), 0.0);
  EXPECT_EQ(s.score.samplesPerColumn(), 5 * 5 * 14);
}

TEST(EarnedScore, AFreeBallSeenFromInsideIsCreditedByTheVolumeItHolds) {
  // A 2 m ball 6 m ahead in open space, seen: credited about its volume (on a 0.5 m lattice),
  // nothing charged.
  Scene s({ground()});
  s.lookFrom({0, 0, 2});
  s.score.declare(disk({6, 0, 3}, 2.0));
  const EarnedTally t = s.score.tally();
  EXPECT_NEAR(t.credited_m3, ballVolume(2.0), 4.0);
  EXPECT_EQ(t.falsely_free_m3, 0.0);
  EXPECT_EQ(t.unseen_m3, 0.0);
  EXPECT_EQ(t.earnedM3(), t.credited_m3);
}

TEST(EarnedScore, OnlyWhatTheCameraCameWithinTheCreditRangeOfIsCredited) {
  // The same ball 15 m ahead: its columns are seen (no charge), but no ray crossed it within
  // 10 m of the camera, so nothing is credited until the camera comes closer.
  Scene s({ground()});
  s.lookFrom({0, 0, 2});
  s.score.declare(disk({15, 0, 3}, 2.0));
  EXPECT_EQ(s.score.tally().credited_m3, 0.0);
  EXPECT_EQ(s.score.tally().unseen_m3, 0.0);
  s.lookFrom({8, 0, 2});
  EXPECT_NEAR(s.score.tally().credited_m3, ballVolume(2.0), 4.0);
}

TEST(EarnedScore, TheSameBallUnseenOrSeenFromOutsideTheBoxCostsWhatItWouldHaveBought) {
  // Never seen: charged as unseen.
  Scene unseen({ground()});
  unseen.score.declare(disk({6, 0, 3}, 2.0));
  EXPECT_EQ(unseen.score.tally().credited_m3, 0.0);
  EXPECT_NEAR(unseen.score.tally().earnedM3(), -ballVolume(2.0), 4.0);
  // Seen from 25 m up (the box's top is 7 m, the margin 1 m): nothing it saw earns.
  Scene high({ground()});
  EXPECT_FALSE(high.score.inside(Vec3(0, 0, 25)));
  EXPECT_TRUE(high.score.inside(Vec3(0, 0, 7.9)));
  high.lookFrom({-15, 0, 25});
  EXPECT_GT(high.verified.seen().size(), 0u);
  high.score.declare(disk({6, 0, 3}, 2.0));
  EXPECT_LT(high.score.tally().earnedM3(), 0.0);
}

TEST(EarnedScore, DeclaredFreeSpaceInsideAnObstacleIsCharged) {
  // A 6 m cube of solid 6 m ahead; a ball of 2 m about its centre lies inside it, deeper than
  // 0.5 m for most of it: charged, never credited.
  Scene s({ground(), block({6, 0, 3}, {3, 3, 3})});
  s.lookFrom({0, 0, 2});
  s.score.declare(disk({6, 0, 3}, 2.0));
  const EarnedTally t = s.score.tally();
  EXPECT_EQ(t.credited_m3, 0.0);
  EXPECT_GT(t.falsely_free_m3, 10.0);
  EXPECT_LT(t.earnedM3(), -10.0);
}

TEST(EarnedScore, AThinElementBuysOnlyTheSamplesItHolds) {
  // A 0.3 m ball at the box's ceiling over a node: at most one sample, not a 2.5 m column.
  Scene s({ground()});
  s.lookFrom({0, 0, 2});
  s.score.declare(disk({5, 0, 6.75}, 0.3));
  EXPECT_LE(s.score.tally().credited_m3, 0.125);
}

TEST(EarnedScore, ABlanketClaimOverATownScoresBelowAnHonestBall) {
  // A town of blocks in the box, the camera inside it looking along a street: a disk of 30 m
  // declared at once earns less than nothing; an honest ball in the street earns its volume.
  std::vector<Shape> town = {ground()};
  for (int i = -2; i <= 2; ++i)
    for (int j : {-1, 1}) town.push_back(block({8.0 * i, 8.0 * j, 5}, {3, 3, 5}));
  Scene blanket(town), honest(town);
  blanket.lookFrom({-16, 0, 2});
  honest.lookFrom({-16, 0, 2});
  blanket.score.declare(disk({0, 0, 3}, 30.0));
  honest.score.declare(disk({-10, 0, 2.5}, 2.0));
  EXPECT_LT(blanket.score.tally().earnedM3(), 0.0);
  EXPECT_GT(honest.score.tally().earnedM3(), 20.0);
  EXPECT_GT(blanket.score.tally().credited_m3, honest.score.tally().credited_m3);  // it did buy the street
}

TEST(EarnedScore, TheBoxFreeVolumeLeavesOutObstacles) {
  // 17 × 17 nodes in [−20, 20]², each 2.5 × 2.5 × 7 m.
  Scene open({ground()});
  EXPECT_NEAR(open.score.boxFreeM3(), 17.0 * 17.0 * 43.75, 1e-9);
  Scene blocked({ground(), block({0, 0, 5}, {5, 5, 5})});
  EXPECT_LT(blocked.score.boxFreeM3(), open.score.boxFreeM3() - 500.0);
}

}  // namespace
}  // namespace msb
