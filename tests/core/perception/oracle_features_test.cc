// The oracle feature source on a hand-built world: what it tracks is visible from the camera
// (never behind an occluder, never on a textureless surface), tracks keep their ids while the
// view holds, and the same seed gives the same tracks.
#include <gtest/gtest.h>

#include "core/perception/oracle_features.h"

namespace msb {
namespace {

// Ground, a textured wall 12 m ahead (+x) and a textureless crate in front of it.
std::vector<Shape> scene() {
  Shape ground;
  ground.type = ShapeType::kHalfSpace;
  ground.kind = ObstacleKind::kGround;
  ground.object = "ground";
  Shape wall;
  wall.pose.translation() = Vec3(12, 0, 3);
  wall.size = Vec3(0.5, 10, 3);
  wall.object = "wall";
  Shape crate;
  crate.pose.translation() = Vec3(6, 0, 2);
  crate.size = Vec3(0.5, 1.5, 1.0);
  crate.kind = ObstacleKind::kTextureless;
  crate.object = "crate";
  return {ground, wall, crate};
}

// The camera 2 m up at the origin, looking along +x (optical z forward, x right, y down).
CameraFrame frameLookingEast(int64_t tick) {
  CameraFrame f;
  f.tick = tick;
  f.t_s = tick / 500.0;
  Mat3 R;
  R.col(0) = Vec3(0, -1, 0);
  R.col(1) = Vec3(0, 0, -1);
  R.col(2) = Vec3(1, 0, 0);
  f.T_W_C.linear() = R;
  f.T_W_C.translation() = Vec3(0, 0, 2);
  return f;
}

TEST(OracleFeatures, TracksAreVisibleLandmarksWithStableIds) {
  const WorldTruth truth(scene());
  const FisheyeCamera camera{FisheyeCameraConfig{}};
  OracleFeatureConfig cfg;
  cfg.pixel_noise_px = 0.0;
  OracleFeatureSource source(cfg, camera, truth, 7);
  EXPECT_GT(source.landmarkCount(), 100u);
  const CameraFrame f0 = frameLookingEast(0);
  const TrackFrame a = source.process(f0);
  ASSERT_GE(a.tracks.size(), 100u);
  EXPECT_EQ(a.new_tracks, int(a.tracks.size()));
  const Vec3 cam = f0.T_W_C.translation();
  for (const Track& t : a.tracks) {
    // The pixel's ray hits a textured or ground surface first, never the crate.
    const Vec3 ray = f0.T_W_C.linear() * camera.unproject(t.pixel);
    const auto hit = truth.raycast(cam, ray, 100.0);
    ASSERT_TRUE(hit) << t.pixel.transpose();
    EXPECT_NE(truth.shapes()[hit->shape].object, "crate") << t.pixel.transpose();
  }
  // Spread like detections: no two tracks closer than min_distance_px.
  for (size_t i = 0; i < a.tracks.size(); ++i)
    for (size_t j = i + 1; j < a.tracks.size(); ++j)
      EXPECT_GE((a.tracks[i].pixel - a.tracks[j].pixel).norm(), cfg.min_distance_px - 1e-9);
  // The same view again: the same tracks, one frame older.
  const TrackFrame b = source.process(frameLookingEast(33));
  ASSERT_EQ(b.tracks.size(), a.tracks.size());
  EXPECT_EQ(b.new_tracks, 0);
  EXPECT_EQ(b.lost_tracks, 0);
  for (size_t k = 0; k < a.tracks.size(); ++k) {
    EXPECT_EQ(b.tracks[k].id, a.tracks[k].id);
    EXPECT_EQ(b.tracks[k].age, a.tracks[k].age + 1);
  }
}

TEST(OracleFeatures, TexturelessLandmarksOnlyWhenAskedAndSameSeedSameTracks) {
  const WorldTruth truth(scene());
  const FisheyeCamera camera{FisheyeCameraConfig{}};
  OracleFeatureConfig perfect;
  perfect.textureless_landmarks = true;
  OracleFeatureSource with(perfect, camera, truth, 7), without(OracleFeatureConfig{}, camera, truth, 7);
  EXPECT_GT(with.landmarkCount(), without.landmarkCount());
  // Same seed, same configuration: identical tracks, noise included.
  OracleFeatureSource again(perfect, camera, truth, 7);
  const TrackFrame x = with.process(frameLookingEast(0)), y = again.process(frameLookingEast(0));
  ASSERT_EQ(x.tracks.size(), y.tracks.size());
  for (size_t k = 0; k < x.tracks.size(); ++k) EXPECT_EQ(x.tracks[k].pixel, y.tracks[k].pixel);
}

}  // namespace
}  // namespace msb
