// Viewpoint value (field of view, range, facing) and visited-viewpoint blocking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/methods/monospheres/map/sphere_map_test_seam.h"
#include "core/methods/monospheres/planner/viewpoint_set.h"

namespace msb {
namespace {

// One sphere at the origin with frontiers on a patch in its shell towards +x (normals −x).
struct Scene {
  SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
  uint64_t sphere;
  int frontiers = 0;
  Scene() {
    sphere = SphereMapTestSeam::addSphere(map, {0, 0, 2}, 3.0);
    for (double y = -4; y <= 4; y += 1.6)
      for (double z = -1; z <= 5; z += 1.6) frontiers += bool(SphereMapTestSeam::tryAddFrontier(map, {4.5, y, z}));
  }
};

TEST(ViewpointSet, ValueCountsVisibleFacingFrontiers) {
  Scene s;
  ASSERT_GE(s.frontiers, 10);
  ViewpointSet vs(ViewpointConfig{}, 1);
  const Vec3 c(0, 0, 2);
  const int ahead = vs.value(s.map, c, 0.0);
  EXPECT_GE(ahead, 7);
  EXPECT_LE(ahead, s.frontiers);
  EXPECT_EQ(vs.value(s.map, c, M_PI), 0);            // looking away
  EXPECT_EQ(vs.value(s.map, c, M_PI / 2), 0);        // 90° off: outside ±60°
  EXPECT_EQ(vs.value(s.map, {9.0, 0, 2}, M_PI), 0);  // from the unknown side: not facing
  EXPECT_EQ(vs.value(s.map, {-20, 0, 2}, 0.0), 0);   // beyond 10 m
}

TEST(ViewpointSet, PassingAViewpointBlocksItsNeighbourhood) {
  // Plain (pose) VPB, the paper's rule: frontier_view_limit 0.
  Scene s;
  auto all = [](const Vec3&) { return true; };
  ViewpointConfig plain;
  plain.frontier_view_limit = 0;
  ViewpointSet vs(plain, 3);
  const Vec3 far(100, 100, 2);
  vs.update(s.map, {s.sphere}, far, 0.0, 0.0, 0, all);
  ASSERT_FALSE(vs.viewpoints().empty());
  for (const auto& [id, v] : vs.viewpoints()) {
    EXPECT_GE(v.value, 7);
    EXPECT_LE(std::abs(v.yaw_rad), M_PI / 2);  // only poses facing the frontiers are valuable
  }
  // The vehicle passes the first viewpoint with its heading: removed, a marker left.
  const Viewpoint first = vs.viewpoints().begin()->second;
  vs.update(s.map, {s.sphere}, first.position, first.yaw_rad, 1.0, 0, all);
  EXPECT_FALSE(vs.viewpoints().count(first.id));
  EXPECT_GE(vs.passedCount(), 1);
  ASSERT_GE(vs.markers().size(), 1u);
  // New candidates within 7 m / 60° of a marker are blocked, however often we sample.
  for (int k = 0; k < 5; ++k) vs.update(s.map, {s.sphere}, far, 0.0, 2.0 + k, 0, all);
  for (const auto& [id, v] : vs.viewpoints())
    for (const auto& m : vs.markers())
      EXPECT_FALSE(posesClose(v.position, v.yaw_rad, m.position, m.yaw_rad, 7.0, M_PI / 3));
}

TEST(ViewpointSet, WithNewFrontierBlockingMarkersLetNewerFrontiersThrough) {
  // Frontiers on the lower half of the patch; the vehicle passes a viewpoint (a marker). Then
  // frontiers appear on the upper half. Plain VPB keeps the marker's neighbourhood closed; with
  // vpb_new_frontiers candidates there are valued on the newer frontiers only, so they return
  // once enough new ones appear, and not before.
  for (bool new_frontiers : {false, true}) {
    SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
    const uint64_t sphere = SphereMapTestSeam::addSphere(map, {0, 0, 2}, 3.0);
    int old_count = 0, new_count = 0;
    for (double y : {-2.4, -0.8})
      for (double z : {0.4, 2.0, 3.6}) old_count += bool(SphereMapTestSeam::tryAddFrontier(map, {4.2, y, z}));
    ViewpointConfig cfg;
    cfg.min_value = 4;
    ASSERT_GE(old_count, cfg.min_value);
    cfg.frontier_view_limit = 0;  // plain VPB, with or without the newer-frontier rule
    cfg.vpb_new_frontiers = new_frontiers;
    ViewpointSet vs(cfg, 3);
    auto all = [](const Vec3&) { return true; };
    vs.update(map, {sphere}, {100, 100, 2}, 0.0, 0.0, 0, all);
    ASSERT_FALSE(vs.viewpoints().empty());
    const Viewpoint first = vs.viewpoints().begin()->second;
    vs.update(map, {sphere}, first.position, first.yaw_rad, 1.0, 0, all);
    ASSERT_EQ(vs.markers().size(), 1u);
    const VisitedMarker marker = vs.markers().front();
    auto nearMarker = [&] {
      int n = 0;
      for (const auto& [id, v] : vs.viewpoints())
        n += posesClose(v.position, v.yaw_rad, marker.position, marker.yaw_rad, 7.0, M_PI / 3);
      return n;
    };
    // The only sphere is at the marker: nothing new near it either way.
    for (int k = 0; k < 3; ++k) vs.update(map, {sphere}, {100, 100, 2}, 0.0, 2.0 + k, 0, all);
    EXPECT_EQ(nearMarker(), 0) << new_frontiers;
    for (double y : {0.8, 2.4})
      for (double z : {0.4, 2.0, 3.6}) new_count += bool(SphereMapTestSeam::tryAddFrontier(map, {4.2, y, z}));
    ASSERT_GE(new_count, cfg.min_value);
    for (int k = 0; k < 3; ++k) vs.update(map, {sphere}, {100, 100, 2}, 0.0, 5.0 + k, 0, all);
    EXPECT_EQ(nearMarker() > 0, new_frontiers) << new_frontiers;
    for (const auto& [id, v] : vs.viewpoints()) EXPECT_LE(v.value, old_count + new_count);
  }
}

TEST(ViewpointSet, WithAFrontierViewLimitFrontiersRetireAfterThatManyLooks) {
  // frontier_view_limit = 2: near a marker only the frontiers it does not see count; a frontier
  // seen from two markers counts nowhere. Passing viewpoint after viewpoint therefore ends: the
  // frontiers that survive being looked at retire. Frontiers that appear elsewhere afterwards
  // are worth viewpoints again.
  Scene s;
  auto all = [](const Vec3&) { return true; };
  ViewpointConfig cfg;
  cfg.frontier_view_limit = 2;
  ViewpointSet vs(cfg, 3);
  const Vec3 far(100, 100, 2);
  const double block = cfg.block_angle_deg * M_PI / 180.0;
  // The value rule written out: visible, seen from fewer than two markers, from no close one.
  auto sees = [&](const Vec3& p, double yaw, const Frontier& f) {
    const Vec3 ray = f.position - p;
    const Vec3 axis(std::cos(yaw), std::sin(yaw), 0);
    return ray.norm() <= cfg.frontier_range_m && ray.dot(axis) >= 0.5 * ray.norm() && f.normal.dot(ray) < 0;
  };
  auto expectedValue = [&](const Viewpoint& v) {
    int n = 0;
    for (const auto& [fid, f] : s.map.frontiers()) {
      if (!sees(v.position, v.yaw_rad, f)) continue;
      int views = 0;
      bool seen_close = false;
      for (const auto& m : vs.markers()) {
        views += sees(m.position, m.yaw_rad, f);
        seen_close |= posesClose(v.position, v.yaw_rad, m.position, m.yaw_rad, cfg.block_distance_m, block) &&
                      sees(m.position, m.yaw_rad, f);
      }
      EXPECT_EQ(vs.views(s.map, fid), views);
      n += views < 2 && !seen_close;
    }
    return n;
  };
  vs.update(s.map, {s.sphere}, far, 0.0, 0.0, 0, all);
  ASSERT_FALSE(vs.viewpoints().empty());
  int passes = 0;
  bool retired_after_two = false;
  while (!vs.viewpoints().empty() && passes < 20) {
    for (const auto& [id, v] : vs.viewpoints()) {
      EXPECT_EQ(v.value, expectedValue(v)) << "pass " << passes;
      EXPECT_GE(v.value, cfg.min_value);
    }
    const Viewpoint v = vs.viewpoints().begin()->second;
    vs.update(s.map, {s.sphere}, v.position, v.yaw_rad, 1.0 + passes, 0, all);  // pass it: a marker
    ++passes;
    EXPECT_FALSE(vs.viewpoints().count(v.id));
    ASSERT_EQ(vs.markers().size(), size_t(passes));
    if (passes == 1) {
      EXPECT_EQ(vs.retiredFrontiers(s.map), 0);  // one look retires nothing
    }
    if (passes == 2) retired_after_two = vs.retiredFrontiers(s.map) > 0;
    for (int k = 0; k < 3; ++k) vs.update(s.map, {s.sphere}, far, 0.0, 1.5 + passes + 0.1 * k, 0, all);
  }
  EXPECT_TRUE(vs.viewpoints().empty()) << "still viewpoints after " << passes << " passes";
  EXPECT_GE(passes, 2);
  EXPECT_TRUE(retired_after_two || passes > 2);
  EXPECT_GE(vs.retiredFrontiers(s.map), 1);
  EXPECT_GT(vs.rejections().visited, 0);  // refused for frontiers already looked at
  // Frontier ids churn as the map changes: a retired frontier dropped (an obstacle point comes
  // close) and sampled again at the same place has a new id and is still retired.
  uint64_t old_id = 0;
  for (const auto& [id, f] : s.map.frontiers())
    if (vs.views(s.map, id) >= 2) old_id = id;
  ASSERT_NE(old_id, 0u);
  const Vec3 at = s.map.frontiers().at(old_id).position;
  const uint64_t rock = SphereMapTestSeam::addObstacle(s.map, at + Vec3(0.5, 0, 0), 5.0);
  SphereMapTestSeam::revalidateChangedFrontiers(s.map);
  ASSERT_FALSE(s.map.frontiers().count(old_id));
  SphereMapTestSeam::eraseObstacle(s.map, rock);
  SphereMapTestSeam::revalidateChangedFrontiers(s.map);
  const auto new_id = SphereMapTestSeam::tryAddFrontier(s.map, at);
  ASSERT_TRUE(new_id.has_value());
  EXPECT_GT(*new_id, old_id);
  EXPECT_GE(vs.views(s.map, *new_id), 2);
  // New frontiers behind the sphere (normals +x): viewpoints facing them appear.
  int behind = 0;
  for (double y = -4; y <= 4; y += 1.6)
    for (double z = -1; z <= 5; z += 1.6) behind += bool(SphereMapTestSeam::tryAddFrontier(s.map, {-4.5, y, z}));
  ASSERT_GE(behind, 7);
  bool facing_back = false;
  for (int k = 0; k < 5; ++k) vs.update(s.map, {s.sphere}, far, 0.0, 30.0 + k, 0, all);
  for (const auto& [id, v] : vs.viewpoints()) {
    facing_back |= std::abs(v.yaw_rad) > M_PI / 2;
    EXPECT_EQ(v.value, expectedValue(v));
  }
  EXPECT_TRUE(facing_back);
}

TEST(ViewpointSet, FrontierViewLimitIsValidated) {
  ViewpointConfig cfg;
  cfg.frontier_view_limit = -1;
  EXPECT_THROW(ViewpointSet(cfg, 1), ConfigError);
  cfg.frontier_view_limit = 1;
  cfg.vpb_new_frontiers = true;
  EXPECT_THROW(ViewpointSet(cfg, 1), ConfigError);
}

TEST(ViewpointSet, WithoutVpbViewpointsSurvivePassing) {
  Scene s;
  auto all = [](const Vec3&) { return true; };
  ViewpointConfig cfg;
  cfg.vpb = false;
  ViewpointSet vs(cfg, 3);
  vs.update(s.map, {s.sphere}, {100, 100, 2}, 0.0, 0.0, 0, all);
  ASSERT_FALSE(vs.viewpoints().empty());
  const Viewpoint first = vs.viewpoints().begin()->second;
  vs.update(s.map, {s.sphere}, first.position, first.yaw_rad, 1.0, 0, all);
  EXPECT_EQ(vs.passedCount(), 0);
  EXPECT_TRUE(vs.markers().empty());
  bool near_again = false;  // the neighbourhood still holds a viewpoint
  for (const auto& [id, v] : vs.viewpoints())
    near_again |= posesClose(v.position, v.yaw_rad, first.position, first.yaw_rad, 7.0, M_PI / 3);
  EXPECT_TRUE(near_again);
  // Reached goals are removed either way; failed goals are blacklisted.
  const uint64_t id = vs.viewpoints().begin()->first;
  vs.markReached(id, s.map, first.position, first.yaw_rad);
  EXPECT_FALSE(vs.viewpoints().count(id));
  EXPECT_TRUE(vs.markers().empty());
}

TEST(ViewpointSet, UnreachableOrOutsideCandidatesAreNotSampled) {
  Scene s;
  ViewpointSet vs(ViewpointConfig{}, 3);
  EXPECT_EQ(vs.update(s.map, {}, {100, 100, 2}, 0.0, 0.0, 0, nullptr), 0);
  EXPECT_EQ(vs.update(s.map, {s.sphere}, {100, 100, 2}, 0.0, 0.0, 0, [](const Vec3& p) { return p.z() > 5; }), 0);
  EXPECT_TRUE(vs.viewpoints().empty());
}

TEST(ViewpointSet, RelaxedValueAcceptsFewFrontiers) {
  // Three frontiers only: below min_value 7, above relaxed_min_value 2.
  SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
  const uint64_t sphere = SphereMapTestSeam::addSphere(map, {0, 0, 2}, 3.0);
  int n = 0;
  for (double y : {-1.6, 0.0, 1.6}) n += bool(SphereMapTestSeam::tryAddFrontier(map, {4.5, y, 2.0}));
  ASSERT_EQ(n, 3);
  ViewpointSet vs(ViewpointConfig{}, 5);
  EXPECT_EQ(vs.update(map, {sphere}, {100, 100, 2}, 0.0, 0.0, 0, nullptr), 0);
  EXPECT_GT(vs.update(map, {sphere}, {100, 100, 2}, 0.0, 1.0, 0, nullptr, true), 0);
  for (const auto& [id, v] : vs.viewpoints()) EXPECT_GE(v.value, 2);
}

TEST(ViewpointSet, ThePublishedSamplingDrawsOverEverySphereReachableOrNot) {
  // method.reference_code.viewpoints_anywhere (LNM tryAddingGoalsNearby 1815-1823: an index
  // drawn below the length of getReachableNodes' mask, which covers every sphere of the map):
  // with one reachable sphere far from the frontiers, the published samples still land on the
  // newest sphere, the only one that sees them. Neither the intended draw (the reachable sphere
  // only) nor a draw below the count of reachable spheres (the oldest sphere only) finds a view.
  SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
  const uint64_t oldest = SphereMapTestSeam::addSphere(map, {-40, 0, 2}, 3.0);
  const uint64_t reachable = SphereMapTestSeam::addSphere(map, {-80, 0, 2}, 3.0);
  const uint64_t newest = SphereMapTestSeam::addSphere(map, {0, 0, 2}, 3.0);
  ASSERT_LT(oldest, reachable);
  ASSERT_LT(reachable, newest);
  int frontiers = 0;
  for (double y = -4; y <= 4; y += 1.6)
    for (double z = -1; z <= 5; z += 1.6) frontiers += bool(SphereMapTestSeam::tryAddFrontier(map, {4.5, y, z}));
  ASSERT_GE(frontiers, 10);
  for (const bool anywhere : {false, true}) {
    ViewpointConfig c;
    c.sample_anywhere = anywhere;
    ViewpointSet vs(c, 3);
    vs.update(map, {reachable}, {100, 100, 2}, 0.0, 0.0, 0, nullptr);
    EXPECT_EQ(vs.viewpoints().empty(), !anywhere) << "anywhere " << anywhere;
    for (const auto& [id, v] : vs.viewpoints()) EXPECT_EQ(v.sphere, newest);
  }
}

TEST(ViewpointSet, ThePublishedPinholeVisibilityCountsOnlyFrontiersInsideTheImage) {
  // method.reference_code.pinhole_rays (LNM getViewpointFrontierValue, CS getVisiblePoints):
  // frontiers project through the pinhole K (fx 227.4, 752 × 480) and count only inside the
  // image, ±58.8° horizontally and ±46.5° vertically; the intended cone is ±60° all round.
  SphereMap map{SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1};
  const Vec3 c(0, 0, 2);
  SphereMapTestSeam::addSphere(map, c, 3.0);
  const auto dir = [](double az_deg, double el_deg) {
    const double az = az_deg * kDeg, el = el_deg * kDeg;
    return Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  };
  // Inside both: straight ahead, 55° to the left. Inside the cone only: 59.5° to the right,
  // 50° below.
  for (const Vec3& d : {dir(0, 0), dir(55, 0), dir(-59.5, 0), dir(0, -50)})
    ASSERT_TRUE(SphereMapTestSeam::tryAddFrontier(map, c + 4.5 * d)) << d.transpose();
  const FisheyeCamera cam(FisheyeCameraConfig{});
  ViewpointConfig pinhole;
  pinhole.pinhole_view = {true, cam.cx() / cam.fx(), (cam.width() - cam.cx()) / cam.fx(), cam.cy() / cam.fy(),
                          (cam.height() - cam.cy()) / cam.fy()};
  ASSERT_NEAR(std::atan(pinhole.pinhole_view.right) / kDeg, 58.8, 0.05);
  ASSERT_NEAR(std::atan(pinhole.pinhole_view.down) / kDeg, 46.5, 0.05);
  EXPECT_EQ(ViewpointSet(ViewpointConfig{}, 1).value(map, c, 0.0), 4);
  EXPECT_EQ(ViewpointSet(pinhole, 1).value(map, c, 0.0), 2);
  // Turned 90° to the left, the frontier 55° left lies 35° right of the axis: inside both.
  EXPECT_EQ(ViewpointSet(pinhole, 1).value(map, c, M_PI / 2), 1);
  EXPECT_EQ(ViewpointSet(ViewpointConfig{}, 1).value(map, c, M_PI / 2), 1);
}

}  // namespace
}  // namespace msb
