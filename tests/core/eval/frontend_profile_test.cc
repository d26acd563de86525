// The truth-side evaluation of a run on synthetic cases with known errors: the front-end error
// profile (points on the ground, a wrong point 3 m off any surface, a track whose estimate moves
// 0.5 m, a VIO error it must take out first) and the final map's accuracy.
#include "core/eval/frontend_profile.h"
#include "core/eval/map_accuracy.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

WorldTruth groundOnly() {
  Shape ground;
  ground.type = ShapeType::kHalfSpace;
  ground.kind = ObstacleKind::kGround;
  ground.name = ground.object = "ground";
  return WorldTruth({ground});
}

SlamPoint point(uint64_t id, const Vec3& p) {
  SlamPoint s;
  s.track_id = id;
  s.p_W = p;
  return s;
}

SlamPointsFrame frame(const Vec3& camera, std::vector<SlamPoint> points) {
  SlamPointsFrame f;
  f.T_W_C = Pose::Identity();
  f.T_W_C.translation() = camera;
  f.points = std::move(points);
  return f;
}

TEST(FrontEndProfile, ErrorsByDepthBandWrongPointsAndMovedTracks) {
  const WorldTruth truth = groundOnly();
  FrontEndProfiler profiler(truth, /*every=*/1);
  Pose camera_true = Pose::Identity();
  camera_true.translation() = Vec3(0, 0, 1.5);
  // The estimate is 1 m off along x: a point published at x + 1 is where the truth has x.
  const Vec3 off(1, 0, 0);
  profiler.addFrame(
      frame(camera_true.translation() + off,
            {point(1, Vec3(2, 0, 0) + off), point(2, Vec3(3, 0, 3) + off), point(3, Vec3(8, 0, 0) + off)}),
      camera_true, 0);
  profiler.addFrame(
      frame(camera_true.translation() + off, {point(1, Vec3(2, 0.5, 0) + off), point(3, Vec3(8, 0, 0) + off)}),
      camera_true, 0);
  const FrontEndProfile p = profiler.result();
  ASSERT_EQ(p.bands.size(), 4u);
  EXPECT_EQ(p.points, 5);
  // 0-5 m: two publications of track 1 on the ground (error 0) and the wrong point (3 m).
  EXPECT_EQ(p.bands[0].points, 3);
  EXPECT_NEAR(p.bands[0].median_m, 0.0, 1e-9);
  EXPECT_NEAR(p.bands[0].p90_m, 3.0, 1e-9);
  EXPECT_NEAR(p.bands[0].share_over_2_m, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(p.bands[0].share_over_half_m, 1.0 / 3.0, 1e-9);
  // 5-10 m: track 3 twice, on the ground.
  EXPECT_EQ(p.bands[1].points, 2);
  EXPECT_NEAR(p.bands[1].share_over_half_m, 0.0, 1e-12);
  EXPECT_EQ(p.bands[2].points + p.bands[3].points, 0);
  // Tracks seen twice: 1 (moved 0.5 m) and 3 (still).
  EXPECT_EQ(p.tracks, 2);
  EXPECT_NEAR(p.moved_share, 0.5, 1e-12);
}

TEST(FrontEndProfile, EvaluatesOneFrameInEvery) {
  const WorldTruth truth = groundOnly();
  FrontEndProfiler profiler(truth, /*every=*/3);
  for (int k = 0; k < 7; ++k) profiler.addFrame(frame(Vec3(0, 0, 1.5), {point(1, Vec3(2, 0, 0))}), Pose::Identity(), 0);
  EXPECT_EQ(profiler.result().points, 3);  // frames 0, 3 and 6
}

TEST(FrontEndProfile, RefusesAPoseOfAnotherFrame) {
  // Points of tick 10 with the true pose of tick 40 (the pipelined loop's current frame): refused.
  const WorldTruth truth = groundOnly();
  FrontEndProfiler profiler(truth, /*every=*/1);
  SlamPointsFrame f = frame(Vec3(0, 0, 1.5), {point(1, Vec3(2, 0, 0))});
  f.tick = 10;
  EXPECT_THROW(profiler.addFrame(f, Pose::Identity(), 40), std::logic_error);
  EXPECT_EQ(profiler.result().points, 0);
  profiler.addFrame(f, Pose::Identity(), 10);
  EXPECT_EQ(profiler.result().points, 1);
}

}  // namespace
}  // namespace msb

// The final map against the truth (core/eval/map_accuracy.h).
namespace msb {
namespace {

TEST(MapAccuracy, ObstaclesNearASurfaceAndFreeElementsOutsideObstacles) {
  const WorldTruth truth = groundOnly();
  ExplorerSnapshot map;
  EXPECT_FALSE(mapAccuracy(map, truth).has_value());   // an empty map
  map.obstacles = {Vec3(1, 0, 0.2), Vec3(2, 0, 3.0)};  // on the ground; 3 m above it (a phantom)
  map.free_space = {{1, Vec3(0, 0, 2), 1.0, FreeSpaceElement::Footprint::kDisk},
                    {2, Vec3(0, 0, -1), 0.5, FreeSpaceElement::Footprint::kDisk}};  // the second underground
  const auto a = mapAccuracy(map, truth);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->obstacles, 2u);
  EXPECT_EQ(a->obstacles_near_surface, 1u);
  EXPECT_DOUBLE_EQ(*a->nearSurfaceShare(), 0.5);
  EXPECT_DOUBLE_EQ(*a->reallyFreeShare(), 0.5);
  EXPECT_FALSE(MapAccuracy{}.reallyFreeShare().has_value());
}

TEST(MapAccuracy, PointPlacementInsideNearOrFloating) {
  const WorldTruth truth = groundOnly();
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, -1.0)), Placement::inside);  // below the ground: behind the surface seen
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, -0.4)), Placement::near_surface);
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, 0.5)), Placement::near_surface);
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, 0.6)), Placement::floating_near);  // in free air: takes free space away
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, 2.5)), Placement::floating_far);   // far from every surface
  EXPECT_EQ(placementOf(truth, Vec3(0, 0, 40.0)), Placement::floating_far);  // beyond the search range: still floating
  PointPlacement c;
  using enum Placement;
  for (Placement k : {inside, near_surface, near_surface, floating_near, floating_near, floating_far})
    countPlacement(c, k);
  EXPECT_EQ(c.inside, 1u);
  EXPECT_EQ(c.near_surface, 2u);
  EXPECT_EQ(c.floating, 3u);
  EXPECT_EQ(c.floating_far, 1u);
  EXPECT_EQ(c.total(), 6u);
}

}  // namespace
}  // namespace msb
