// The closed loop without images: the null renderer with the oracle feature source runs a
// scripted flight and a short exploration mission in seconds; two loops stepped in lockstep
// stay bit-identical (MuJoCo pipeline_test style); the seams refuse impossible combinations.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "core/geometry/world_truth.h"
#include "tools/config/world_registry.h"
#include "tools/engine/closed_loop.h"
#include "tools/engine/mission.h"

namespace msb {
namespace {

// The urban town (the dense procedural town, the former `urban`), built once into a test cache.
const BuiltWorld& urban() {
  static const BuiltWorld world =
      buildWorld(loadWorldSpec(std::string(MSB_SOURCE_DIR) + "/worlds/urban_town/spec.yaml"),
                 std::string(::testing::TempDir()) + "/msb_engine_cache");
  return world;
}

// A short climb and a 6 m leg west of the town's start, on the null renderer and oracle features.
FlightSpec oracleFlight() {
  FlightSpec s;
  s.world_path = urban().world_xml;
  const Vec3 c = urban().generated.start.translation();
  s.start_position_m = c + Vec3(0, 0, 0.05);
  s.start_yaw_rad = M_PI;
  s.duration_s = 12.0;
  s.hold_after_s = 0.5;
  s.waypoints = {{c + Vec3(0, 0, 2.5), M_PI}, {c + Vec3(-6, 0, 2.5), M_PI}};
  s.camera_stream.renderer = RendererKind::kBlank;
  s.camera_stream.save_every_n = 0;
  s.perception.enabled = true;
  s.perception.source = FeatureSourceKind::kOracle;
  return s;
}

TEST(ClosedLoop, NullRendererWithOracleFeaturesTracksAndTriangulates) {
  const WorldTruth truth(urban().generated.shapes);
  LoopSetup setup;
  setup.truth = &truth;
  ClosedLoop loop(oracleFlight(), setup);
  int frames = 0;
  double tracks = 0, points = 0;
  while (loop.running()) {
    const TickRecord& t = loop.step();
    ASSERT_EQ(bool(t.frame), bool(t.tracks));
    if (!t.tracks) continue;
    ++frames;
    tracks += double(t.tracks->tracks.size());
    points += double(t.points->points.size());
    // Track ids are sorted and pixels lie in the image.
    for (size_t k = 1; k < t.tracks->tracks.size(); ++k) EXPECT_LT(t.tracks->tracks[k - 1].id, t.tracks->tracks[k].id);
    for (const auto& tr : t.tracks->tracks) EXPECT_TRUE(loop.camera().inImage(tr.pixel)) << tr.pixel.transpose();
  }
  const FlightResult& r = loop.finish();
  EXPECT_EQ(r.status, RunStatus::kCompleted);
  EXPECT_TRUE(r.path_finished);
  EXPECT_EQ(r.gl_description, "null renderer (no images)");
  ASSERT_GE(frames, 80);
  EXPECT_GE(tracks / frames, 150.0);
  EXPECT_GE(points / frames, 30.0);
  EXPECT_NEAR(r.distance_flown_m, 2.45 + 6.0, 1.0);
}

TEST(ClosedLoop, TwoLoopsInLockstepStayIdentical) {
  const WorldTruth truth(urban().generated.shapes);
  LoopSetup setup;
  setup.truth = &truth;
  ClosedLoop a(oracleFlight(), setup), b(oracleFlight(), setup);
  int64_t compared = 0;
  while (a.running()) {
    ASSERT_TRUE(b.running());
    const TickRecord& ta = a.step();
    const TickRecord& tb = b.step();
    ASSERT_EQ(ta.tick, tb.tick);
    if (ta.tracks) {
      ASSERT_EQ(ta.tracks->tracks.size(), tb.tracks->tracks.size()) << "tick " << ta.tick;
      for (size_t k = 0; k < ta.tracks->tracks.size(); ++k)
        ASSERT_EQ(ta.tracks->tracks[k].pixel, tb.tracks->tracks[k].pixel) << "tick " << ta.tick;
      ASSERT_EQ(ta.points->points.size(), tb.points->points.size()) << "tick " << ta.tick;
    }
    if (ta.tick % 500 == 0) {
      ASSERT_EQ(a.stateHash(), b.stateHash()) << "tick " << ta.tick;
      ++compared;
    }
  }
  EXPECT_FALSE(b.running());
  EXPECT_EQ(a.finish().trajectory_hash, b.finish().trajectory_hash);
  EXPECT_GE(compared, 5);
}

// A mission of `duration_s` from the town's start on the null renderer and oracle features, with
// a perfect front end (the textureless vehicles near the start carry landmarks too).
ScenarioSpec oracleMission(double duration_s) {
  ScenarioSpec spec;
  spec.flight = oracleFlight();
  spec.flight.waypoints.clear();
  spec.flight.start_yaw_rad = yawOf(urban().generated.start.linear());
  spec.flight.duration_s = duration_s;
  spec.flight.perception.oracle.textureless_landmarks = true;
  spec.mission.progress = false;
  return spec;
}

TEST(ClosedLoop, ShortOracleMissionExploresDeterministically) {
  const WorldTruth truth(urban().generated.shapes);
  const ScenarioSpec spec = oracleMission(25.0);
  const Aabb box = urban().generated.exploration_box;
  const MissionResult a = runMission(spec, box, &truth);
  ASSERT_EQ(a.flight.status, RunStatus::kCompleted)
      << (a.flight.collision ? a.flight.collision->world_geom + " at t = " + std::to_string(a.flight.collision->t_s)
                             : "");
  EXPECT_GT(a.counters.at("spheres"), 5.0);
  EXPECT_GT(a.columns.areaM2(), 200.0);
  EXPECT_GT(a.box_explorable_columns, 100);
  EXPECT_EQ(a.coverage.size(), 26u);
  const MissionResult b = runMission(spec, box, &truth);
  EXPECT_EQ(a.run_hash, b.run_hash);
}

// The oracle mission of the test above, pipelined: what each frame computes is used one frame
// later; `threads` 1 or 2.
ScenarioSpec pipelinedOracleMission(int threads) {
  ScenarioSpec spec = oracleMission(20.0);
  spec.flight.perception.latency_frames = 1;
  spec.flight.perception.threads = threads;
  return spec;
}

TEST(ClosedLoop, ThePipelinedLoopIsTheSameOnOneThreadOnTwoAndUnderLoad) {
  // Two missions in lockstep, one running each frame's perception on a second thread: the same
  // state every simulated second, the same tracks, the same mission hash.
  const WorldTruth truth(urban().generated.shapes);
  const Aabb box = urban().generated.exploration_box;
  Mission one(pipelinedOracleMission(1), box, &truth), two(pipelinedOracleMission(2), box, &truth);
  int64_t compared = 0, used = 0;
  while (one.running()) {
    ASSERT_TRUE(two.running());
    const TickRecord& a = one.step();
    const TickRecord& b = two.step();
    ASSERT_EQ(bool(a.points), bool(b.points)) << "tick " << a.tick;
    if (a.points) {
      ++used;
      // What is used at frame n was perceived at frame n - 1.
      ASSERT_TRUE(a.frame && a.perceived && a.perceived != a.frame) << "tick " << a.tick;
      ASSERT_LT(a.perceived->tick, a.tick);
      ASSERT_EQ(a.points->points.size(), b.points->points.size()) << "tick " << a.tick;
      ASSERT_EQ(a.map_updated, b.map_updated) << "tick " << a.tick;
    }
    if (a.tick % 500 == 0) {
      ASSERT_EQ(one.loop().stateHash(), two.loop().stateHash()) << "tick " << a.tick;
      ++compared;
    }
  }
  EXPECT_FALSE(two.running());
  const MissionResult ra = one.finish(), rb = two.finish();
  ASSERT_EQ(ra.flight.status, RunStatus::kCompleted);
  EXPECT_EQ(ra.run_hash, rb.run_hash);
  EXPECT_GE(compared, 20);
  EXPECT_GE(used, 290);
  EXPECT_GT(ra.columns.areaM2(), 200.0);
  // A busy thread competing for the cores changes when the second thread runs, not the result.
  std::atomic<bool> stop{false};
  std::thread busy([&] {
    volatile double x = 1.0;
    while (!stop) x = x * 1.0000001 + 1e-9;
  });
  const MissionResult loaded = runMission(pipelinedOracleMission(2), box, &truth);
  stop = true;
  busy.join();
  EXPECT_EQ(loaded.run_hash, ra.run_hash);
  // The latency is behaviour: the sequential loop flies otherwise.
  ScenarioSpec sequential = pipelinedOracleMission(1);
  sequential.flight.perception.latency_frames = 0;
  EXPECT_NE(runMission(sequential, box, &truth).run_hash, ra.run_hash);
}

// One rule for every latency (tools/engine/perception_pipeline.h): the results a tick uses are
// those of the frame `latency` frames back (latency 0: its own), the map updates only with
// them, on camera ticks.
TEST(ClosedLoop, EachLatencyUsesTheFrameThatManyFramesBack) {
  const WorldTruth truth(urban().generated.shapes);
  for (int latency : {0, 1, 3}) {
    ScenarioSpec spec = oracleMission(4.0);
    spec.flight.perception.latency_frames = latency;
    spec.flight.perception.threads = 1;
    Mission m(spec, urban().generated.exploration_box, &truth);
    std::vector<int64_t> frame_ticks;
    int used = 0, map_updates = 0;
    while (m.running()) {
      const TickRecord& t = m.step();
      if (t.frame) frame_ticks.push_back(t.frame->tick);
      if (t.map_updated) {
        ++map_updates;
        EXPECT_TRUE(t.frame) << "latency " << latency << ": a map update off a camera tick at " << t.tick;
      }
      if (!t.perceived) continue;
      ++used;
      ASSERT_GE(frame_ticks.size(), size_t(latency) + 1) << "latency " << latency;
      EXPECT_EQ(t.perceived->tick, frame_ticks[frame_ticks.size() - 1 - size_t(latency)])
          << "latency " << latency << " at tick " << t.tick;
    }
    m.finish();
    EXPECT_EQ(used, int(frame_ticks.size()) - latency) << "latency " << latency;
    EXPECT_GE(map_updates, 15) << "latency " << latency;  // 5 Hz for 4 s
  }
}

TEST(ClosedLoop, ThePipelinedLoopRefusesRatesOffTheCameraTicks) {
  // The map update and the plan run with a frame's perception: their rates must divide the
  // camera's, at every latency (latency 0 too: one rule).
  const WorldTruth truth(urban().generated.shapes);
  for (int latency : {0, 1}) {
    ScenarioSpec spec = pipelinedOracleMission(1);
    spec.flight.perception.latency_frames = latency;
    spec.mission.map_rate_hz = 4.0;
    try {
      Mission m(spec, urban().generated.exploration_box, &truth);
      ADD_FAILURE() << "a 4 Hz map on a 15 Hz camera was accepted at latency " << latency;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("mission.map_rate_hz"), std::string::npos) << e.what();
    }
  }
  // Two threads need a latency to overlap.
  FlightSpec f = oracleFlight();
  f.perception.threads = 2;
  EXPECT_THROW(ClosedLoop(f, LoopSetup{}), ConfigError);
}

TEST(ScenarioSpec, ADefaultScenarioIsAValidMissionOnceItNamesAWorld) {
  // The defaults live in the struct (not in a file loader): a C++-built scenario is a mission.
  ScenarioSpec spec;
  EXPECT_THROW(checkValid(spec), ConfigError);  // no world yet
  spec.flight.world_path = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  EXPECT_NO_THROW(checkValid(spec));
  EXPECT_EQ(spec.flight.duration_s, 1200.0);
  EXPECT_TRUE(spec.flight.perception.enabled);
  EXPECT_EQ(spec.method.type, kDefaultMethodType);
}

TEST(ClosedLoop, SeamsRefuseImpossibleCombinations) {
  // The KLT tracker needs images.
  FlightSpec klt_on_null = oracleFlight();
  klt_on_null.perception.source = FeatureSourceKind::kKlt;
  EXPECT_THROW(ClosedLoop(klt_on_null, LoopSetup{}), ConfigError);
  // The oracle needs ground truth.
  EXPECT_THROW(ClosedLoop(oracleFlight(), LoopSetup{}), ConfigError);
  // (A source that is neither is not a value the type holds: the YAML reader refuses its word,
  // KeyReference.EveryKeyRefusesAValueOutsideWhatItAccepts.)
}

}  // namespace
}  // namespace msb
