// The checks beside the loop (collision audit, front-end profile, verified coverage's "seen",
// map accuracy, the SLAM points' truth pose) under the mission defaults: the urban mission of
// scenarios/missions/ with the real renderer and tracker, perception used 3 frames after its
// frame, on two threads — and the same at latency 0. A method hovers facing a building, mapping
// every SLAM point it is given, then flies into it (docs/architecture.md, "Which tick a record
// carries"). Each check is compared with the same check fed in the test from the frames the
// loop rendered, paired by their own ticks.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "core/eval/collision_audit.h"
#include "core/eval/frontend_profile.h"
#include "core/eval/slam_point_truth.h"
#include "core/eval/verified_coverage.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/engine/mission.h"

namespace msb {
namespace {

const std::string kUrban = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/urban.yaml";

// Hovers at `hover` facing `yaw` until `hover_s`, then flies to `through` (beyond a wall). Its
// map is every SLAM point it observed and a 1 m ball of free space about the hover point (for
// the earned score); its counters say which frame it saw last.
class KamikazeExplorer final : public Explorer {
 public:
  KamikazeExplorer(const Vec3& hover, double yaw, const Vec3& through, double hover_s)
      : hover_(hover), through_(through), yaw_(yaw), hover_s_(hover_s) {}
  void observe(const SlamPointsFrame& f) override {
    for (const SlamPoint& p : f.points) points_.push_back(p.p_W);
    last_tick_ = f.tick;
  }
  std::optional<PathCommand> plan(const VehicleState& s) override {
    if (phase_ == 0) return ++phase_, PathCommand{s.tick, {{hover_, yaw_}}};
    if (phase_ == 1 && s.t_s >= hover_s_ && s.path_finished) return ++phase_, PathCommand{s.tick, {{through_, yaw_}}};
    return std::nullopt;
  }
  ExplorerSnapshot snapshot() const override {
    ExplorerSnapshot s;
    s.obstacles = points_;
    FreeSpaceElement ball;
    ball.id = 1, ball.centre = hover_, ball.radius = 1.0;
    s.free_space.push_back(ball);
    return s;
  }
  std::map<std::string, double> counters() const override {
    return {{"last_frame_tick", double(last_tick_)}, {"points", double(points_.size())}};
  }

 private:
  Vec3 hover_, through_;
  double yaw_, hover_s_;
  int phase_ = 0;
  int64_t last_tick_ = -1;
  std::vector<Vec3> points_;
};

// The nearest textured wall part seen level from `hover`, 8-20 m away, that a 0.8 m wide, 0.8 m
// high bundle of rays meets at the same part: the heading to it and the ray's hit.
struct Target {
  double yaw = 0;
  RayHit hit;
};
std::optional<Target> nearestWall(const WorldTruth& truth, const Vec3& hover) {
  std::optional<Target> best;
  for (int k = 0; k < 72; ++k) {
    const double yaw = k * M_PI / 36.0;
    const Vec3 d(std::cos(yaw), std::sin(yaw), 0), side(-d.y(), d.x(), 0);
    const auto hit = truth.raycast(hover, d, 20.0);
    if (!hit || hit->distance_m < 8.0 || (best && hit->distance_m >= best->hit.distance_m)) continue;
    const Shape& s = truth.shapes()[hit->shape];
    if (s.kind != ObstacleKind::kTextured || std::string(surfaceClass(s)) != "walls") continue;
    bool same = true;
    for (const Vec3& o : {Vec3(0.4 * side), Vec3(-0.4 * side), Vec3(0, 0, 0.4), Vec3(0, 0, -0.4)}) {
      const auto h = truth.raycast(hover + o, d, 20.0);
      same = same && h && h->shape == hit->shape && std::abs(h->distance_m - hit->distance_m) < 1.0;
    }
    if (same) best = Target{yaw, *hit};
  }
  return best;
}

// What one kamikaze mission gave, with the truth-side checks recomputed in the test.
struct Flown {
  MissionResult result;
  std::string target_part;
  int records_with_points = 0, records_paired_right = 0;
  FrontEndProfile profile_own_frame, profile_latest_frame;
  int audit_points_own_frame = 0, audit_points_latest_frame = 0;
  size_t seen_latest_frame = 0, seen_perceived_frame = 0;
  int64_t last_map_frame_tick = -1;
  int latency = 0, threads = 0;
};

// Flies the kamikaze mission of the urban scenario with `sets` over the scenario's defaults.
Flown flyIntoWall(const std::vector<std::string>& sets) {
  ScenarioSpec spec = loadScenario(kUrban, sets);
  spec.mission.progress = false;
  MissionWorld world = prepareMissionWorld(kUrban, spec);
  const WorldTruth& truth = *world.truth;
  Flown out;
  out.latency = spec.flight.perception.latency_frames, out.threads = spec.flight.perception.threads;
  const Vec3 hover = spec.flight.start_position_m + Vec3(0, 0, 2.5);
  const std::optional<Target> target = nearestWall(truth, hover);
  if (!target) throw std::runtime_error("no wall in reach of the urban start");
  out.target_part = truth.shapes()[target->hit.shape].name;
  const Vec3 d(std::cos(target->yaw), std::sin(target->yaw), 0);
  // In the estimate frame, which starts at the true start pose: the wall's drift is small at 30 s.
  Mission mission(
      spec, world.box, &truth,
      std::make_unique<KamikazeExplorer>(hover, target->yaw, hover + (target->hit.distance_m + 3) * d, 25.0));

  // The same checks fed here: with each frame's points paired with the pose of their own frame,
  // and (to show the checks can tell) with the latest rendered frame's.
  const FisheyeCamera camera(spec.flight.camera);
  FrontEndProfiler own(truth), latest(truth);
  CollisionAuditRecorder audit_own(truth, camera), audit_latest(truth, camera);
  VerifiedCoverageConfig vc;
  vc.z_lo_m = world.box.min.z(), vc.z_hi_m = world.box.max.z();
  VerifiedCoverage seen_latest(truth, camera, vc), seen_perceived(truth, camera, vc);
  std::map<int64_t, CameraFrame> rendered;  // tick → frame (pose and tick; pixels dropped)
  std::optional<CameraFrame> newest, perceived;
  const int64_t metric_ticks = int64_t(mission.physicsHz() / spec.mission.metric_rate_hz);
  const int64_t map_ticks = int64_t(mission.physicsHz() / spec.mission.map_rate_hz);
  double last_sample_s = -1;
  while (mission.running()) {
    const TickRecord& t = mission.step();
    if (t.frame) {
      CameraFrame f{t.frame->tick, t.frame->t_s, 0, 0, {}, t.frame->T_W_C};
      rendered[f.tick] = f, newest = f;
      if (f.tick % map_ticks == 0) out.last_map_frame_tick = f.tick;
    }
    if (t.points) {
      ++out.records_with_points;
      const CameraFrame& own_frame = rendered.at(t.points->tick);
      out.records_paired_right +=
          t.perceived->tick == t.points->tick && t.perceived->T_W_C.matrix() == own_frame.T_W_C.matrix();
      own.addFrame(*t.points, own_frame.T_W_C, own_frame.tick);
      audit_own.addFrame(*t.points, own_frame.T_W_C, own_frame.tick);
      SlamPointsFrame as_latest = *t.points;  // relabelled: what a reader of the wrong frame sees
      as_latest.tick = newest->tick;
      latest.addFrame(as_latest, newest->T_W_C, newest->tick);
      audit_latest.addFrame(as_latest, newest->T_W_C, newest->tick);
      perceived = own_frame;
    }
    if (t.completed && t.tick % metric_ticks == 0) {
      seen_latest.look(newest->T_W_C);
      if (perceived) seen_perceived.look(perceived->T_W_C);
      last_sample_s = t.t_s;
    }
  }
  out.result = mission.finish();
  if (last_sample_s < out.result.flight.sim_time_s) {  // the final sample at the end
    seen_latest.look(newest->T_W_C);
    if (perceived) seen_perceived.look(perceived->T_W_C);
  }
  out.profile_own_frame = own.result(), out.profile_latest_frame = latest.result();
  out.audit_points_own_frame = audit_own.input(out.target_part).slam_points_on_part;
  out.audit_points_latest_frame = audit_latest.input(out.target_part).slam_points_on_part;
  out.seen_latest_frame = seen_latest.seen().size(), out.seen_perceived_frame = seen_perceived.seen().size();
  return out;
}

// The mission defaults, flown once (and the same at latency 0) for all tests below.
const Flown& underDefaults() {
  static const Flown f = flyIntoWall({"duration_s=60"});
  return f;
}
const Flown& atLatency0() {
  static const Flown f = flyIntoWall({"duration_s=60", "perception.latency_frames=0", "perception.threads=1"});
  return f;
}

void expectAuditedAsSeen(const Flown& f) {
  const MissionResult& r = f.result;
  ASSERT_EQ(r.flight.status, RunStatus::kCollided) << "latency " << f.latency;
  ASSERT_TRUE(r.flight.collision && r.collision_audit);
  EXPECT_EQ(r.flight.collision->world_geom, f.target_part);
  // The method mapped the wall for 25 s: the part gave points, the map held them at contact.
  EXPECT_GE(r.collision_audit->slam_points_on_part, 20);
  EXPECT_NE(r.collision_audit->cause, "unseen");
  EXPECT_EQ(r.collision_audit->cause, "planner");
  EXPECT_GE(r.collision_audit->map_points_on_object, 20);
  EXPECT_LT(r.collision_audit->nearest_map_point_m, 0.6);
}

TEST(MissionChecks, TheMissionDefaultsArePipelinedOnTwoThreads) {
  // The tests below are about this setting: if the defaults change, so must they.
  EXPECT_EQ(underDefaults().latency, 3);
  EXPECT_EQ(underDefaults().threads, 2);
}

TEST(MissionChecks, FlyingIntoAMappedWallIsAuditedWithItsPointsUnderTheDefaults) {
  expectAuditedAsSeen(underDefaults());
}

TEST(MissionChecks, FlyingIntoAMappedWallIsAuditedWithItsPointsAtLatency0) { expectAuditedAsSeen(atLatency0()); }

TEST(MissionChecks, TheAuditCountsEachFramesPointsFromItsOwnFrame) {
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    ASSERT_TRUE(f->result.collision_audit);
    EXPECT_EQ(f->result.collision_audit->slam_points_on_part, f->audit_points_own_frame) << "latency " << f->latency;
  }
  // Paired with the latest rendered frame, the pipelined loop's points are counted elsewhere.
  EXPECT_NE(underDefaults().audit_points_latest_frame, underDefaults().audit_points_own_frame);
}

TEST(MissionChecks, EveryPerceptionRecordCarriesTheFrameItWasComputedFrom) {
  // What the perception log, the SLAM points' truth and the Python binding read.
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    EXPECT_GT(f->records_with_points, 300) << "latency " << f->latency;
    EXPECT_EQ(f->records_paired_right, f->records_with_points) << "latency " << f->latency;
  }
}

TEST(MissionChecks, TheFrontEndProfilePairsPointsWithTheirOwnFrame) {
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    ASSERT_TRUE(f->result.frontend);
    const FrontEndProfile& m = *f->result.frontend;
    ASSERT_EQ(m.bands.size(), f->profile_own_frame.bands.size());
    for (size_t b = 0; b < m.bands.size(); ++b) {
      EXPECT_EQ(m.bands[b].points, f->profile_own_frame.bands[b].points);
      EXPECT_EQ(m.bands[b].median_m, f->profile_own_frame.bands[b].median_m) << "band " << b;
    }
  }
  // The latest frame's pose (200 ms later, the vehicle flying at the wall) gives other errors.
  const FrontEndProfile& own = underDefaults().profile_own_frame;
  const FrontEndProfile& wrong = underDefaults().profile_latest_frame;
  bool differs = false;
  for (size_t b = 0; b < own.bands.size(); ++b) differs = differs || own.bands[b].median_m != wrong.bands[b].median_m;
  EXPECT_TRUE(differs);
}

TEST(MissionChecks, VerifiedCoverageSeesFromTheLatestRenderedFrameAtEachSample) {
  // docs/metrics.md (c): the camera's view at each metric sample is its latest frame's.
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    EXPECT_GT(f->seen_latest_frame, 20u) << "latency " << f->latency;
    EXPECT_EQ(f->result.seen_columns, f->seen_latest_frame) << "latency " << f->latency;
  }
  EXPECT_NE(underDefaults().seen_perceived_frame, underDefaults().seen_latest_frame);
}

TEST(MissionChecks, TheEarnedScoreCreditsWhatTheCameraLookedAtUnderTheMissionDefaults) {
  // docs/metrics.md, "The earned score": the hover ball (4.2 m³) is free and inside the box; the
  // part of it in front of the camera's latest frames (the fisheye sees no farther back than
  // sideways) is credited, at both latencies, and the running figure is coverage.csv's last.
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    ASSERT_TRUE(f->result.earned) << "latency " << f->latency;
    EXPECT_GT(f->result.earned->credited_m3, 0.5) << "latency " << f->latency;
    EXPECT_LT(f->result.earned->credited_m3, 4.5) << "latency " << f->latency;
    EXPECT_EQ(f->result.earned->falsely_free_m3, 0.0) << "latency " << f->latency;
    EXPECT_DOUBLE_EQ(f->result.coverage.back().score_earned_m3, f->result.earned->earnedM3());
  }
}

TEST(MissionChecks, TheFinalMapHoldsThePerceptionStillInFlight) {
  // Map accuracy and the audit read the map after the last frame's perception ran: its last
  // map frame is the last one rendered on a map tick, not one 3 frames earlier.
  for (const Flown* f : {&underDefaults(), &atLatency0()}) {
    const MissionResult& r = f->result;
    EXPECT_EQ(int64_t(r.counters.at("last_frame_tick")), f->last_map_frame_tick) << "latency " << f->latency;
    ASSERT_TRUE(r.map_accuracy);
    EXPECT_EQ(double(r.map_accuracy->obstacles), r.counters.at("points"));
  }
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A method whose plan() (or observe()) throws a plain library error once the run is under way.
class ThrowingExplorer final : public Explorer {
 public:
  explicit ThrowingExplorer(bool in_plan) : in_plan_(in_plan) {}
  void observe(const SlamPointsFrame& f) override {
    if (!in_plan_ && f.tick >= 500) throw std::out_of_range("map index 7 of 3");
  }
  std::optional<PathCommand> plan(const VehicleState& s) override {
    if (in_plan_ && s.t_s >= 1.0) throw std::runtime_error("no route to the goal");
    return std::nullopt;
  }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }

 private:
  bool in_plan_;
};

// Before: the run ended with "error: no route to the goal", naming no call. Under the mission
// defaults (the call runs on the pipeline's second thread) and at latency 0 on one thread.
TEST(MissionChecks, AnErrorThrownInAMethodsCallNamesTheCallAndItsTick) {
  const std::string& file = kUrban;
  for (const bool defaults : {true, false}) {
    for (const bool in_plan : {true, false}) {
      std::vector<std::string> sets = {"camera_stream.renderer=blank", "perception.source=oracle", "duration_s=4"};
      if (!defaults) sets.insert(sets.end(), {"perception.latency_frames=0", "perception.threads=1"});
      ScenarioSpec spec = loadScenario(file, sets);
      spec.mission.progress = false;
      MissionWorld world = prepareMissionWorld(file, spec);
      Mission mission(spec, world.box, world.truth ? &*world.truth : nullptr,
                      std::make_unique<ThrowingExplorer>(in_plan));
      try {
        while (mission.running()) mission.step();
        ADD_FAILURE() << "the mission ended without the method's error";
      } catch (const MethodCallError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(in_plan ? "the method's plan() at t = " : "the method's observe() at t = "),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find(in_plan ? "threw: no route to the goal" : "threw: map index 7 of 3"), std::string::npos)
            << what;
        EXPECT_NE(what.find("(tick "), std::string::npos) << what;
      }
    }
  }
}

}  // namespace
}  // namespace msb
