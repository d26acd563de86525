// Verified coverage on hand-built worlds: what the camera saw, what is truly free, squares turned.
#include "core/eval/verified_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/eval/mission_coverage.h"
#include "tests/core/eval/truth_shapes.h"

namespace msb {
namespace {

using test::ground;
Shape wall(const Vec3& centre, const Vec3& half) { return test::block(centre, half); }

// The camera at (0, 0, 2) looking along +x (optical z = world x, optical x = world −y, optical y
// = world −z).
Pose cameraLookingAlongX() {
  Pose T = Pose::Identity();
  Mat3 R;
  R.col(0) = Vec3(0, -1, 0);
  R.col(1) = Vec3(0, 0, -1);
  R.col(2) = Vec3(1, 0, 0);
  T.linear() = R;
  T.translation() = Vec3(0, 0, 2);
  return T;
}

VerifiedCoverageConfig heights() {
  VerifiedCoverageConfig c;
  c.z_lo_m = 0.0, c.z_hi_m = 7.0;
  return c;
}

PlacedElement disk(uint64_t key, const Vec3& c, double r) {
  PlacedElement e;
  e.key = key, e.centre = c, e.radius = r;
  return e;
}

TEST(VerifiedCoverage, TheCameraSeesUpToAWallAndNotBehindIt) {
  // A wall 10 m ahead, 30 m wide, 10 m high: the columns before it are seen, behind it not,
  // and nothing behind the camera (a 180° field of view).
  const WorldTruth truth({ground(), wall({10, 0, 5}, {0.5, 15, 5})});
  const FisheyeCamera camera;
  VerifiedCoverage v(truth, camera, heights());
  EXPECT_GT(v.look(cameraLookingAlongX()), 20);
  EXPECT_TRUE(v.seen().count({2, 0}));    // 5 m ahead
  EXPECT_FALSE(v.seen().count({6, 0}));   // 15 m ahead: behind the wall
  EXPECT_FALSE(v.seen().count({-3, 0}));  // 7.5 m behind the camera
  // Within the wall's width nothing beyond it is seen (rays past its ends see farther).
  for (const ColumnIndex& c : v.seen()) {
    if (std::abs(c.second) <= 4) {
      EXPECT_LE(c.first, 4) << c.first << "," << c.second;
    }
  }
}

TEST(VerifiedCoverage, FreeSpaceBehindAWallItNeverSawEarnsNothing) {
  // A method declares a truly free disk behind the wall: covered and free, never seen.
  const WorldTruth truth({ground(), wall({10, 0, 5}, {0.5, 15, 5})});
  VerifiedCoverage v(truth, FisheyeCamera(), heights());
  v.look(cameraLookingAlongX());
  const PlacedElement behind = disk(1, {20, 0, 3}, 4.0);
  EXPECT_TRUE(v.partIsFree(behind, {8, 0}));
  EXPECT_EQ(v.mark({behind}), 0);
  // The same disk before the wall is seen and verified, column by column.
  EXPECT_GT(v.mark({disk(2, {4, 0, 3}, 3.0)}), 0);
}

TEST(VerifiedCoverage, AnElementThatCutsIntoAnObstacleIsNotFreeThere) {
  // A pillar 2 m wide at column (2, 0): a disk over it is not free in that column (deeper than
  // the tolerance), free in the columns around it.
  const WorldTruth truth({ground(), wall({5, 0, 5}, {1.0, 1.0, 5})});
  VerifiedCoverage v(truth, FisheyeCamera(), heights());
  const PlacedElement e = disk(1, {5, 0, 3}, 3.0);
  EXPECT_FALSE(v.partIsFree(e, {2, 0}));
  EXPECT_TRUE(v.partIsFree(e, {1, 0}));
  // An element touching the pillar's face (within the tolerance) is free.
  EXPECT_TRUE(v.partIsFree(disk(2, {3.2, 0, 3}, 1.2), {2, 0}));   // 0.4 m into its face
  EXPECT_FALSE(v.partIsFree(disk(2, {3.2, 0, 3}, 2.0), {2, 0}));  // 1.2 m into it
  // An element above the flight heights has no part to verify.
  EXPECT_FALSE(v.partIsFree(disk(3, {0, 0, 20}, 2.0), {0, 0}));
}

TEST(VerifiedCoverage, OnlySeenFreeCoveredColumnsCount) {
  const WorldTruth truth({ground()});
  VerifiedCoverage v(truth, FisheyeCamera(), heights());
  v.markSeenForTest({0, 0});
  EXPECT_EQ(v.mark({disk(1, {0, 0, 2}, 3.0)}), 1);  // 5 columns covered, one seen
  EXPECT_EQ(v.verified().count(), 1u);
  v.markSeenForTest({1, 0});
  EXPECT_EQ(v.mark({disk(1, {0, 0, 2}, 3.0)}), 1);  // seen later: verified then
}

TEST(ColumnCoverage, SquaresTurnWithoutShrinking) {
  // A 4 m square turned by 45° covers the nodes within its diamond: (0, 0) and the four axis
  // neighbours at 2.5 m (inside the diamond's 2.83 m reach), not the diagonals at 3.54 m.
  PlacedElement sq;
  sq.footprint = FreeSpaceElement::Footprint::kSquare;
  sq.radius = 2.0;
  sq.yaw_rad = M_PI / 4;
  const auto turned = columnsUnder(sq, 2.5);
  EXPECT_EQ(turned.size(), 5u);
  // Unturned, it covers the same nodes as the VIO-frame square.
  sq.yaw_rad = 0.0;
  ColumnCoverage aligned;
  aligned.markSquare({0, 0}, 2.0);
  EXPECT_EQ(columnsUnder(sq, 2.5).size(), aligned.count());
  // A 1 m square is counted as a square in the true frame, not as its inscribed disk: a node
  // at 0.6 m from the centre along a diagonal lies in the square (corner 0.707 m), not in the disk.
  PlacedElement small;
  small.footprint = FreeSpaceElement::Footprint::kSquare;
  small.radius = 0.5;
  small.centre = Vec3(0.42, 0.42, 0);
  EXPECT_EQ(columnsUnder(small, 2.5).size(), 1u);
}

TEST(MissionCoverage, TrueFrameSquaresTurnWithTheCorrection) {
  // The estimate is turned 30° from truth: a 1 m square whose corner region covers a node keeps
  // its area in the true frame (the turned square), where an inscribed disk would miss the node.
  const Aabb box{Vec3(-5, -5, 0), Vec3(5, 5, 5)};
  MissionCoverage cov(box, {});
  cov.setTrueFromEstimate(poseFromXyzYaw(Vec3::Zero(), M_PI / 6));
  FreeSpaceElement e;
  e.id = 1;
  e.footprint = FreeSpaceElement::Footprint::kSquare;
  e.radius = 0.5;
  // In the true frame the centre is at distance 0.6 m from the node (0, 0) along the square's
  // diagonal: the estimate-frame centre is the true one turned back by 30°.
  const Vec3 true_centre = poseFromXyzYaw(Vec3::Zero(), M_PI / 6).linear() * Vec3(0.42, 0.42, 1.0);
  e.centre = poseFromXyzYaw(Vec3::Zero(), M_PI / 6).linear().transpose() * true_centre;
  cov.sample(1.0, 0.0, {e});
  EXPECT_EQ(cov.trueFrameColumns().count(), 1u);
}

}  // namespace
}  // namespace msb
