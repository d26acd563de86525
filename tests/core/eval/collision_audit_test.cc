// The collision audit's cause classes on hand-built cases: a wall (box 1 m thick, 10 m wide,
// 4 m high at x = 5) hit at (4.5, 0, 2) by a vehicle whose map is built by hand.
#include "core/eval/collision_audit.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

WorldTruth wallWorld() {
  Shape wall;
  wall.type = ShapeType::kBox;
  wall.pose = Pose::Identity();
  wall.pose.translation() = Vec3(5, 0, 2);
  wall.size = Vec3(0.5, 5, 2);  // half extents
  wall.name = "wall_0_burned";
  wall.object = "wall_0";
  return WorldTruth({wall});
}

CollisionAuditInput contactAt(const ExplorerSnapshot& map, int points_on_part) {
  CollisionAuditInput in;
  in.object = "wall_0";
  in.contact_W = Vec3(4.5, 0, 2);
  in.slam_points_on_object = points_on_part + 10;
  in.slam_points_on_part = points_on_part;
  in.map = &map;
  return in;
}

TEST(CollisionAudit, APartThatNeverGaveAPointIsUnseen) {
  const WorldTruth truth = wallWorld();
  ExplorerSnapshot map;
  map.obstacles = {Vec3(4.5, 3, 2)};  // the object's other points, not the part's
  const CollisionAudit a = auditCollision(contactAt(map, 0), truth);
  EXPECT_EQ(a.cause, "unseen");
  EXPECT_EQ(a.slam_points_on_part, 0);
  EXPECT_EQ(a.map_points_on_object, 1);
}

TEST(CollisionAudit, KnownPointsAtTheContactMeanThePlannerFlewIntoThem) {
  const WorldTruth truth = wallWorld();
  ExplorerSnapshot map;
  map.obstacles = {Vec3(4.5, 0.3, 2.1), Vec3(4.5, 2, 2)};
  const CollisionAudit a = auditCollision(contactAt(map, 20), truth);
  EXPECT_EQ(a.cause, "planner");
  EXPECT_NEAR(a.nearest_map_point_m, std::hypot(0.3, 0.1), 1e-9);
  EXPECT_EQ(a.map_points_on_object, 2);
}

TEST(CollisionAudit, SeenPointsThatTheMapDroppedOrFreeSpaceOverlappingTheContactAreSeenButFreed) {
  const WorldTruth truth = wallWorld();
  // No point of the wall in the map (deleted or never inserted).
  ExplorerSnapshot empty;
  EXPECT_EQ(auditCollision(contactAt(empty, 20), truth).cause, "seen-but-freed");
  // The wall's points are in the map, away from the contact, but a sphere covers the contact.
  ExplorerSnapshot map;
  map.obstacles = {Vec3(4.5, 4, 2)};
  map.free_space = {{7, Vec3(3.5, 0, 2), 1.5, FreeSpaceElement::Footprint::kDisk}};
  const std::map<uint64_t, double> first_seen = {{7, 42.0}};
  CollisionAuditInput in = contactAt(map, 20);
  in.free_space_first_seen_s = &first_seen;
  const CollisionAudit a = auditCollision(in, truth);
  EXPECT_EQ(a.cause, "seen-but-freed");
  EXPECT_TRUE(a.inside_free_space);
  ASSERT_TRUE(a.free_space_since_s);
  EXPECT_DOUBLE_EQ(*a.free_space_since_s, 42.0);
}

TEST(CollisionAudit, TheObjectMappedButTheEstimateDriftedIsDrift) {
  const WorldTruth truth = wallWorld();
  // The estimate frame is 1.5 m off along y: the wall's map points sit on the wall once the
  // drift is undone, away from the contact as the drifted vehicle sees it; no free space there.
  Pose true_from_est = Pose::Identity();
  true_from_est.translation() = Vec3(0, 1.5, 0);
  ExplorerSnapshot map;
  map.obstacles = {Vec3(4.5, -4.0, 2), Vec3(4.5, -3.5, 1)};  // (4.5, -2.5, 2) and (4.5, -2, 1) in truth
  CollisionAuditInput in = contactAt(map, 20);
  in.T_true_from_est = true_from_est;
  in.vio_drift_m = 1.5;
  const CollisionAudit a = auditCollision(in, truth);
  EXPECT_EQ(a.map_points_on_object, 2);
  EXPECT_FALSE(a.inside_free_space);
  EXPECT_EQ(a.cause, "drift");
  // The same without drift is none of the classes.
  in.vio_drift_m = 0.1;
  EXPECT_EQ(auditCollision(in, truth).cause, "other");
}

TEST(CollisionAudit, FreeSpaceCarvedWhereItWasFreeAndMovedOntoTheObjectByDriftIsDrift) {
  const WorldTruth truth = wallWorld();
  // A sphere carved at t = 40 s, when the estimate was exact, in front of the wall; by the
  // contact at t = 100 s the estimate has drifted 2 m along +x: the vehicle, flying in that
  // sphere as it believes, is 2 m further than it thinks and touches the wall.
  Pose drifted = Pose::Identity();
  drifted.translation() = Vec3(2, 0, 0);
  ExplorerSnapshot map;
  map.obstacles = {Vec3(2.5, 4, 2)};  // the wall's points, displaced by the drift, away from the contact
  map.free_space = {{7, Vec3(2.5, 0, 2), 1.5, FreeSpaceElement::Footprint::kDisk}};
  const std::map<uint64_t, double> first_seen = {{7, 40.0}};
  const std::vector<std::pair<double, Pose>> history = {
      {0.0, Pose::Identity()}, {40.0, Pose::Identity()}, {100.0, drifted}};
  CollisionAuditInput in = contactAt(map, 20);
  in.T_true_from_est = drifted;
  in.vio_drift_m = 2.0;
  in.free_space_first_seen_s = &first_seen;
  in.true_from_est_history = &history;
  const CollisionAudit a = auditCollision(in, truth);
  EXPECT_TRUE(a.inside_free_space);
  ASSERT_TRUE(a.carved_clearance_m && a.drift_since_carved_m);
  EXPECT_NEAR(*a.drift_since_carved_m, 2.0, 1e-9);
  EXPECT_NEAR(*a.carved_clearance_m, 2.0, 1e-9);  // (2.5, 0, 2) lies 2 m in front of the wall
  EXPECT_EQ(a.cause, "drift");
  // The same drift, but it had already happened when the sphere was carved: the sphere itself
  // reached into the wall, which is the map's doing, not the drift's.
  const std::vector<std::pair<double, Pose>> drifted_before = {{0.0, Pose::Identity()}, {30.0, drifted}};
  in.true_from_est_history = &drifted_before;
  const CollisionAudit b = auditCollision(in, truth);
  EXPECT_NEAR(*b.drift_since_carved_m, 0.0, 1e-9);
  EXPECT_EQ(b.cause, "seen-but-freed");
}

// A camera at (0, 0, 2) looking along +x at the wall, and a SLAM point of its frame whose anchor
// pixel is the image centre (its ray meets the wall's part "wall_0_burned" at x = 4.5).
struct WallView {
  FisheyeCamera camera;
  Pose T_W_C = Pose::Identity();
  SlamPoint point(uint64_t id, int64_t anchor_tick) const {
    SlamPoint p;
    p.track_id = id;
    p.anchor_pixel = Vec2(camera.cx(), camera.cy());
    p.anchor_tick = anchor_tick;
    return p;
  }
  // A frame of tick `tick` with `points`.
  static SlamPointsFrame frame(int64_t tick, std::vector<SlamPoint> points) {
    SlamPointsFrame f;
    f.tick = tick;
    f.points = std::move(points);
    return f;
  }
  WallView() {
    T_W_C.linear() = Eigen::Quaterniond::FromTwoVectors(camera.unproject(Vec2(camera.cx(), camera.cy())), Vec3::UnitX())
                         .toRotationMatrix();
    T_W_C.translation() = Vec3(0, 0, 2);
  }
};

TEST(CollisionAuditRecorder, CountsThePointsNewInAFrameOnThePartTheirAnchorRayMeets) {
  const WorldTruth truth = wallWorld();
  const WallView v;
  CollisionAuditRecorder rec(truth, v.camera);
  // Frame of tick 30: point 1 is new (anchored at 30), point 2 was anchored at tick 10.
  rec.addFrame(WallView::frame(30, {v.point(1, 30), v.point(2, 10)}), v.T_W_C, 30);
  CollisionAuditInput in = rec.input("wall_0_burned");
  EXPECT_EQ(in.object, "wall_0");
  EXPECT_EQ(in.slam_points_on_part, 1);
  EXPECT_EQ(in.slam_points_on_object, 1);
  // The same track again in a later frame is not counted twice.
  rec.addFrame(WallView::frame(33, {v.point(1, 30), v.point(3, 33)}), v.T_W_C, 33);
  EXPECT_EQ(rec.input("wall_0_burned").slam_points_on_part, 2);
}

TEST(CollisionAuditRecorder, RefusesAPoseOfAnotherFrame) {
  // The pipelined loop hands frame 30's points over at tick 130: paired with the pose of tick
  // 130, every new point would be missed (every collision "unseen"). Refused, nothing counted.
  const WorldTruth truth = wallWorld();
  const WallView v;
  CollisionAuditRecorder rec(truth, v.camera);
  EXPECT_THROW(rec.addFrame(WallView::frame(30, {v.point(1, 30)}), v.T_W_C, 130), std::logic_error);
  EXPECT_EQ(rec.input("wall_0_burned").slam_points_on_part, 0);
}

}  // namespace
}  // namespace msb
