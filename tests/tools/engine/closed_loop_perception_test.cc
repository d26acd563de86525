// Perception in closed-loop flights on rendered images: tracks, SLAM-point accuracy against the
// urban town's ground truth, textureless surfaces, tracking loss, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/common/rng.h"
#include "core/eval/slam_point_truth.h"
#include "tools/config/world_registry.h"
#include "tools/engine/closed_loop.h"

namespace msb {
namespace {

// A 3 m-radius circle centred on the urban town's start at 2.5 m, always facing west (the town):
// inside the world's guaranteed 6 m start clearance, with parallax for the tracked points.
FlightSpec urbanCircle(BuiltWorld* world) {
  WorldSpec ws = loadWorldSpec(std::string(MSB_SOURCE_DIR) + "/worlds/urban_town/spec.yaml");
  *world = buildWorld(ws, (std::string(::testing::TempDir()) + "/msb_perception_cache"));
  FlightSpec s;
  s.world_path = world->world_xml;
  const Vec3 c = world->generated.start.translation();
  s.start_position_m = c + Vec3(0, 0, 0.05);
  s.start_yaw_rad = M_PI;
  s.duration_s = 16.0;
  s.hold_after_s = 0.5;
  s.waypoints.push_back({c + Vec3(0, 0, 2.5), M_PI});
  for (int k = 0; k <= 16; ++k) {
    const double a = 2 * M_PI * k / 16;
    s.waypoints.push_back({c + Vec3(3 * std::cos(a), 3 * std::sin(a), 2.5), M_PI});
  }
  s.camera_stream.save_every_n = 0;
  s.perception.enabled = true;
  return s;
}

struct Evaluation {
  FlightResult result;
  double mean_tracks = 0, mean_points = 0;
  std::vector<double> errors[3];      // by true depth: < 8 m, 8–20 m, > 20 m
  long samples = 0, textureless = 0;  // textureless: interior points (see PointTruth)
  uint64_t points_hash = 0;
};

Evaluation evaluate(const FlightSpec& spec, const BuiltWorld& world) {
  Evaluation ev;
  const WorldTruth truth(world.generated.shapes);
  const FisheyeCamera camera(spec.camera);
  std::map<int64_t, Pose> gt_camera;
  int frames = 0;
  ClosedLoop loop(spec, LoopSetup{});
  while (loop.running()) {
    const TickRecord& s = loop.step();
    if (!s.points) continue;
    gt_camera[s.perceived->tick] = s.perceived->T_W_C;
    ++frames;
    ev.mean_tracks += s.tracks->tracks.size();
    ev.mean_points += s.points->points.size();
    for (const auto& p : s.points->points) {
      ev.points_hash = fnv1a64(p.p_W.data(), sizeof(double) * 3, ev.points_hash ^ p.track_id);
      const PointTruth t = evaluatePoint(p, gt_camera.at(p.anchor_tick), truth, camera);
      if (!t.has_surface) continue;
      ++ev.samples;
      ev.textureless += t.textureless_interior;
      if (!t.interior) continue;  // silhouette corners have no single true surface
      ev.errors[t.true_depth_m < 8 ? 0 : t.true_depth_m < 20 ? 1 : 2].push_back(t.error_m);
    }
  }
  ev.result = loop.finish();
  ev.mean_tracks /= std::max(1, frames);
  ev.mean_points /= std::max(1, frames);
  return ev;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

TEST(PerceptionFlight, UrbanTracksPointAccuracyTexturelessShareAndDeterminism) {
  BuiltWorld world;
  const FlightSpec spec = urbanCircle(&world);
  const Evaluation a = evaluate(spec, world);
  ASSERT_EQ(a.result.status, RunStatus::kCompleted);
  EXPECT_GE(a.mean_tracks, 100.0);
  EXPECT_GE(a.mean_points, 50.0);
  // Error grows with distance, as inverse-depth uncertainty predicts (roughly with depth²).
  for (const auto& e : a.errors) ASSERT_GT(e.size(), 100u);
  const double near = median(a.errors[0]), mid = median(a.errors[1]), far = median(a.errors[2]);
  std::printf("median point error: <8 m %.3f, 8-20 m %.3f, >20 m %.3f; textureless %.2f %% of %ld\n", near, mid, far,
              100.0 * a.textureless / a.samples, a.samples);
  EXPECT_LT(near, 0.15);
  EXPECT_GT(mid, near);
  EXPECT_GT(far, 1.5 * mid);
  EXPECT_LT(double(a.textureless) / a.samples, 0.02);
  // Same spec and seed: identical trajectory and SLAM points.
  const Evaluation b = evaluate(spec, world);
  EXPECT_EQ(a.result.trajectory_hash, b.result.trajectory_hash);
  EXPECT_EQ(a.points_hash, b.points_hash);
}

TEST(PerceptionFlight, RenderedFramesTrackedOnASecondThreadGiveTheSameFlight) {
  // The pipelined loop on rendered images: tracking on a second thread while the next frame
  // renders changes nothing against one thread (same latency, same trajectory and points).
  BuiltWorld world;
  FlightSpec spec = urbanCircle(&world);
  spec.duration_s = 8.0;
  spec.perception.latency_frames = 1;
  const Evaluation one = evaluate(spec, world);
  spec.perception.threads = 2;
  const Evaluation two = evaluate(spec, world);
  ASSERT_EQ(one.result.status, RunStatus::kCompleted);
  EXPECT_GE(one.mean_tracks, 100.0);
  EXPECT_EQ(one.result.trajectory_hash, two.result.trajectory_hash);
  EXPECT_EQ(one.points_hash, two.points_hash);
}

TEST(PerceptionFlight, FacingATexturelessWallEndsInVioLost) {
  FlightSpec s;
  s.world_path = std::string(MSB_SOURCE_DIR) + "/tests/data/worlds/blank_room.xml";
  s.duration_s = 10.0;
  s.waypoints = {{Vec3(0, 0, 1.5), 0.0}, {Vec3(0, 4, 1.5), 0.0}};
  s.camera_stream.save_every_n = 0;
  s.perception.enabled = true;
  ClosedLoop loop(s, LoopSetup{});
  loop.run();
  const FlightResult r = loop.finish();
  EXPECT_EQ(r.status, RunStatus::kVioLost);
  EXPECT_NEAR(r.vio_lost_at_s, s.perception.lost_after_s, 0.1);
}

}  // namespace
}  // namespace msb
