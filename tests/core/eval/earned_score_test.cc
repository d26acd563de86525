// The earned score on hand-built worlds: sight from inside the box, truth, volume, blanket claims.
#include "core/eval/earned_score.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/eval/verified_coverage.h"

namespace msb {
namespace {

Shape ground() {
  Shape s;
  s.type = ShapeType::kHalfSpace;
  return s;
}

Shape block(const Vec3& centre, const Vec3& half) {
  Shape s;
  s.type = ShapeType::kBox;
  s.pose = poseFromXyzYaw(centre, 0.0);
  s.size = half;
  return s;
}

PlacedElement disk(const Vec3& c, double r) {
  PlacedElement e;
  e.centre = c, e.radius = r;
  return e;
}

// The box of these tests: 40 × 40 m, 0–7 m high.
Aabb box() { return {Vec3(-20, -20, 0), Vec3(20, 20, 7)}; }

// The camera at `p` looking along +x (optical z = world x).
Pose cameraAt(const Vec3& p) {
  Pose T = Pose::Identity();
  Mat3 R;
  R.col(0) = Vec3(0, -1, 0), R.col(1) = Vec3(0, 0, -1), R.col(2) = Vec3(1, 0, 0);
  T.linear() = R;
  T.translation() = p;
  return T;
}

// What the camera sees from `T`, handed to the score as the mission does.
void look(EarnedScore& s, VerifiedCoverage& v, const Pose& T) {
  VerifiedCoverage::Sight sight;
  v.look(T, &sight);
  s.see(T.translation(), sight);
}

VerifiedCoverageConfig heights() {
  VerifiedCoverageConfig c;
  c.z_lo_m = 0.0, c.z_hi_m = 7.0;
  return c;
}

TEST(EarnedScore, DeclaringNothingEarnsNothing) {
  const WorldTruth truth({ground()});
  EarnedScore s(truth, box());
  EXPECT_EQ(s.tally().earnedM3(), 0.0);
  EXPECT_EQ(s.samplesPerColumn(), 5 * 5 * 14);
}

TEST(EarnedScore, AFreeBallSeenFromInsideIsCreditedByTheVolumeItHolds) {
  // A 2 m ball 6 m ahead in open space, seen: credited about its volume (4/3 π 8 ≈ 33.5 m³, on
  // a 0.5 m lattice), nothing charged.
  const WorldTruth truth({ground()});
  const FisheyeCamera camera;
  EarnedScore s(truth, box());
  VerifiedCoverage v(truth, camera, heights());
  look(s, v, cameraAt({0, 0, 2}));
  s.declare(disk({6, 0, 3}, 2.0));
  const EarnedTally t = s.tally();
  EXPECT_NEAR(t.credited_m3, 4.0 / 3.0 * M_PI * 8.0, 4.0);
  EXPECT_EQ(t.falsely_free_m3, 0.0);
  EXPECT_EQ(t.unseen_m3, 0.0);
  EXPECT_EQ(t.earnedM3(), t.credited_m3);
}

TEST(EarnedScore, OnlyWhatTheCameraCameWithinTheCreditRangeOfIsCredited) {
  // The same ball 15 m ahead: its columns are seen (no charge), but no ray crossed it within
  // 10 m of the camera, so nothing is credited until the camera comes closer.
  const WorldTruth truth({ground()});
  const FisheyeCamera camera;
  EarnedScore s(truth, box());
  VerifiedCoverage v(truth, camera, heights());
  look(s, v, cameraAt({0, 0, 2}));
  s.declare(disk({15, 0, 3}, 2.0));
  EXPECT_EQ(s.tally().credited_m3, 0.0);
  EXPECT_EQ(s.tally().unseen_m3, 0.0);
  look(s, v, cameraAt({8, 0, 2}));
  EXPECT_NEAR(s.tally().credited_m3, 4.0 / 3.0 * M_PI * 8.0, 4.0);
}

TEST(EarnedScore, TheSameBallUnseenOrSeenFromOutsideTheBoxCostsWhatItWouldHaveBought) {
  const WorldTruth truth({ground()});
  const FisheyeCamera camera;
  // Never seen: charged as unseen.
  EarnedScore unseen(truth, box());
  unseen.declare(disk({6, 0, 3}, 2.0));
  EXPECT_EQ(unseen.tally().credited_m3, 0.0);
  EXPECT_NEAR(unseen.tally().earnedM3(), -4.0 / 3.0 * M_PI * 8.0, 4.0);
  // Seen from 25 m up (the box's top is 7 m, the margin 1 m): nothing it saw earns.
  EarnedScore high(truth, box());
  VerifiedCoverage v(truth, camera, heights());
  EXPECT_FALSE(high.inside(Vec3(0, 0, 25)));
  EXPECT_TRUE(high.inside(Vec3(0, 0, 7.9)));
  look(high, v, cameraAt({-15, 0, 25}));
  EXPECT_GT(v.seen().size(), 0u);
  high.declare(disk({6, 0, 3}, 2.0));
  EXPECT_LT(high.tally().earnedM3(), 0.0);
}

TEST(EarnedScore, DeclaredFreeSpaceInsideAnObstacleIsCharged) {
  // A 3 m cube of solid 6 m ahead; a ball of 2 m about its centre is all inside it, deeper than
  // 0.5 m for most of it: charged, never credited.
  const WorldTruth truth({ground(), block({6, 0, 3}, {3, 3, 3})});
  const FisheyeCamera camera;
  EarnedScore s(truth, box());
  VerifiedCoverage v(truth, camera, heights());
  look(s, v, cameraAt({0, 0, 2}));
  s.declare(disk({6, 0, 3}, 2.0));
  const EarnedTally t = s.tally();
  EXPECT_EQ(t.credited_m3, 0.0);
  EXPECT_GT(t.falsely_free_m3, 10.0);
  EXPECT_LT(t.earnedM3(), -10.0);
}

TEST(EarnedScore, AThinElementBuysOnlyTheSamplesItHolds) {
  // A 0.3 m ball at the box's ceiling over a node: at most one sample, not a 2.5 m column.
  const WorldTruth truth({ground()});
  const FisheyeCamera camera;
  EarnedScore s(truth, box());
  VerifiedCoverage v(truth, camera, heights());
  look(s, v, cameraAt({0, 0, 2}));
  s.declare(disk({5, 0, 6.75}, 0.3));
  EXPECT_LE(s.tally().credited_m3, 0.125);
}

TEST(EarnedScore, ABlanketClaimOverATownScoresBelowAnHonestBall) {
  // A town of blocks in the box, the camera inside it looking along a street: a disk of 30 m
  // declared at once earns less than nothing; an honest ball in the street earns its volume.
  std::vector<Shape> town = {ground()};
  for (int i = -2; i <= 2; ++i)
    for (int j : {-1, 1}) town.push_back(block({8.0 * i, 8.0 * j, 5}, {3, 3, 5}));
  const WorldTruth truth(town);
  const FisheyeCamera camera;
  EarnedScore blanket(truth, box()), honest(truth, box());
  VerifiedCoverage v1(truth, camera, heights()), v2(truth, camera, heights());
  look(blanket, v1, cameraAt({-16, 0, 2}));
  look(honest, v2, cameraAt({-16, 0, 2}));
  blanket.declare(disk({0, 0, 3}, 30.0));
  honest.declare(disk({-10, 0, 2.5}, 2.0));
  EXPECT_LT(blanket.tally().earnedM3(), 0.0);
  EXPECT_GT(honest.tally().earnedM3(), 20.0);
  EXPECT_GT(blanket.tally().credited_m3, honest.tally().credited_m3);  // it did buy the street
}

TEST(EarnedScore, TheBoxFreeVolumeLeavesOutObstacles) {
  const WorldTruth empty({ground()});
  EarnedScore open(empty, box());
  // 17 × 17 nodes in [−20, 20]², each 2.5 × 2.5 × 7 m.
  EXPECT_NEAR(open.boxFreeM3(), 17.0 * 17.0 * 43.75, 1e-9);
  const WorldTruth with_block({ground(), block({0, 0, 5}, {5, 5, 5})});
  EarnedScore blocked(with_block, box());
  EXPECT_LT(blocked.boxFreeM3(), open.boxFreeM3() - 500.0);
}

}  // namespace
}  // namespace msb
