// Compute in the loop (tools/engine/compute_clock.h): the method's computer serves the calls in the
// order they were asked for, a call's latency delays the next and the output of a planning step;
// a charged run replays bit for bit from its latency log; `modelled` is deterministic on one
// thread or two; `free` is the loop as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "core/geometry/world_truth.h"
#include "tools/config/world_registry.h"
#include "tools/engine/compute_clock.h"
#include "tools/engine/mission.h"

namespace msb {
namespace {

using Stage = ComputeCall::Stage;

TEST(ComputeClock, ACallThatTakesLongerThanThePeriodHalvesTheRate) {
  // Map updates asked every 100 ticks (5 Hz at 500 Hz), each 200 ticks (0.4 s) long; frames
  // every 33 ticks: the map runs every 200 ticks (2.5 Hz), each start when the last ends.
  ComputeClock clock(33);
  std::vector<int64_t> starts;
  for (int64_t tick = 0; tick <= 2000; tick += 1) {
    if (tick % 100 == 0) clock.ask(Stage::kMap, tick);
    if (tick % 33 != 0 && tick % 100 != 0) continue;  // camera ticks (and the ask ticks)
    while (auto call = clock.next(tick)) {
      starts.push_back(call->start_tick);
      clock.charge(*call, 200);
    }
  }
  ASSERT_GE(starts.size(), 10u);
  for (size_t i = 1; i < starts.size(); ++i) EXPECT_EQ(starts[i] - starts[i - 1], 200) << i;
}

TEST(ComputeClock, OldestAskFirstMapBeforePlanOnATieAndChainsWithinAFrame) {
  ComputeClock clock(33);
  clock.ask(Stage::kMap, 0);
  clock.ask(Stage::kPlan, 0);
  auto a = clock.next(0);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->stage, Stage::kMap);
  clock.charge(*a, 10);  // ends before the next frame: the plan starts when it ends
  auto b = clock.next(0);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->stage, Stage::kPlan);
  EXPECT_EQ(b->start_tick, 10);
  clock.charge(*b, 100);
  EXPECT_FALSE(clock.next(0));
  // Busy until 110: a map asked at 33 waits; the plan asked at 20 (earlier) goes first at 99.
  clock.ask(Stage::kPlan, 20);
  clock.ask(Stage::kMap, 33);
  clock.ask(Stage::kPlan, 66);  // already waiting: keeps its first ask
  EXPECT_FALSE(clock.next(33));
  EXPECT_FALSE(clock.next(66));
  auto c = clock.next(99);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->stage, Stage::kPlan);
  EXPECT_EQ(c->asked_tick, 20);
  EXPECT_EQ(c->start_tick, 110);
}

TEST(ComputeTiming, TheCostModelAddsItsTermsAndRefusesBadCoefficients) {
  StageCostModel m{0.1, {{"a", 0.5}, {"a*b", 0.25}}};
  EXPECT_DOUBLE_EQ(m.seconds({{"a", 2}, {"b", 4}}), 0.1 + 1.0 + 2.0);
  EXPECT_THROW(m.seconds({{"a", 2}}), std::runtime_error);
  ComputeTiming t;
  t.compute = ComputeMode::kModelled;
  t.map.per["spheres"] = -1e-6;
  EXPECT_THROW(checkValid(t), ConfigError);
  t.map.per["spheres"] = std::nan("");
  EXPECT_THROW(checkValid(t), ConfigError);
  t.map.per = {{"a**b", 1.0}};
  EXPECT_THROW(checkValid(t), ConfigError);
  // A cost model's words only mean something when the model is used.
  ComputeTiming charged;
  charged.compute = ComputeMode::kCharged;
  charged.compute_model = ComputeModel::kReferencePython;
  EXPECT_THROW(checkValid(charged), ConfigError);
}

TEST(ComputeLog, RoundTripsAndRefusesTruncatedLogs) {
  std::vector<ComputeCall> calls = {{Stage::kMap, 0, 0, 1234, 2}, {Stage::kPlan, 0, 2, 99, 7}};
  const std::string text = computeLogText(calls, {"abc123", "charged", 1.25, 7, "00ff00ff00ff00ff"});
  const ComputeLog log = parseComputeLog(text);
  EXPECT_EQ(log.header.build, "abc123");
  EXPECT_DOUBLE_EQ(log.header.machine_factor, 1.25);
  EXPECT_EQ(log.header.seed, 7u);
  EXPECT_EQ(log.header.scenario, "00ff00ff00ff00ff");
  ASSERT_EQ(log.calls.size(), 2u);
  EXPECT_EQ(log.calls[1].stage, Stage::kPlan);
  EXPECT_EQ(log.calls[1].start_tick, 2);
  EXPECT_EQ(log.calls[1].latency_ticks, 7);
  EXPECT_EQ(log.calls[0].cpu_ns, 1234);
  // Without its closing line, with a row cut, or a count that disagrees: refused.
  EXPECT_THROW(parseComputeLog(text.substr(0, text.rfind("# end"))), std::runtime_error);
  EXPECT_THROW(parseComputeLog(text.substr(0, text.rfind("99,7"))), std::runtime_error);
  std::string miscounted = text;
  miscounted.replace(miscounted.rfind("calls 2"), 7, "calls 3");
  EXPECT_THROW(parseComputeLog(miscounted), std::runtime_error);
  EXPECT_THROW(parseComputeLog("hello\n"), std::runtime_error);
}

// A replay log is checked whole before a run starts: each bad header value or row is refused,
// naming the line and the reason (docs/compute.md, "Replays").
TEST(ComputeLog, EveryBadHeaderValueOrRowIsRefusedNamingTheLine) {
  const std::vector<ComputeCall> calls = {{Stage::kMap, 0, 0, 1234, 2}, {Stage::kPlan, 0, 2, 99, 7}};
  const std::string good = computeLogText(calls, {"abc123", "charged", 1.25, 7, "00ff00ff00ff00ff"});
  ASSERT_NO_THROW(parseComputeLog(good, 100));
  auto errorOf = [](const std::string& text) -> std::string {
    try {
      parseComputeLog(text, 100);
      return "";
    } catch (const std::runtime_error& e) {
      return e.what();
    }
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    const size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return t.replace(at, from.size(), to);
  };
  // Machine factors that are not a finite number above 0, or not all of the field.
  for (const char* f : {"nan", "inf", "-1", "0", "12abc", "0x10", ""}) {
    const std::string e = errorOf(replaced("machine_factor 1.25", std::string("machine_factor ") + f));
    EXPECT_NE(e.find("line 1"), std::string::npos) << f << ": " << e;
    EXPECT_NE(e.find("machine_factor"), std::string::npos) << f << ": " << e;
  }
  EXPECT_NE(errorOf(replaced("; seed 7", "")).find("no seed"), std::string::npos);
  EXPECT_NE(errorOf(replaced("; seed 7", "; seed -0")).find("seed"), std::string::npos);
  EXPECT_NE(errorOf(replaced("; scenario", "; extra 1; scenario")).find("line 1"), std::string::npos);
  // Rows: half-numbers, signs, a latency past the limit or of int64's size, order broken.
  for (const auto& [from, to, says] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"1,plan,0,2,99,7", "1,plan,0,2,99,0abc", "line 4"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,+0", "line 4"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,9223372036854775807", "outside 0...100"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,101", "outside 0...100"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,-1", "outside"},
           {"1,plan,0,2,99,7", "1,plan,0,1,99,7", "before the call above it ended"},
           {"1,plan,0,2,99,7", "1,plan,3,2,99,7", "before it was asked for"},
           {"0,map,0,0,1234,2", "0,map,5,5,1234,2", "asked for before"},
           {"1,plan,0,2,99,7", "1,plan,0,2,-5,7", "negative CPU"},
           {"1,plan,0,2,99,7", "2,plan,0,2,99,7", "index"},
           {"1,plan,0,2,99,7", "1,fly,0,2,99,7", "stage"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,7,8", "6 comma-separated"},
           {"1,plan,0,2,99,7", "1,plan,0,2,99,7,", "6 comma-separated"},
           {"# end; calls 2\n", "# end; calls 2\nmore\n", "after the closing line"}}) {
    const std::string e = errorOf(replaced(from, to));
    EXPECT_NE(e.find(says), std::string::npos) << to << ": " << e;
  }
}

// The urban town on the null renderer and oracle features (as closed_loop_test.cc).
const BuiltWorld& urban() {
  static const BuiltWorld world =
      buildWorld(loadWorldSpec(std::string(MSB_SOURCE_DIR) + "/worlds/urban_town/spec.yaml"),
                 std::string(::testing::TempDir()) + "/msb_compute_cache");
  return world;
}

ScenarioSpec oracleMission(double duration_s) {
  ScenarioSpec spec;
  spec.flight.world_path = urban().world_xml;
  spec.flight.start_position_m = urban().generated.start.translation() + Vec3(0, 0, 0.05);
  spec.flight.start_yaw_rad = yawOf(urban().generated.start.linear());
  spec.flight.duration_s = duration_s;
  spec.flight.camera_stream.renderer = RendererKind::kBlank;
  spec.flight.perception.source = FeatureSourceKind::kOracle;
  spec.flight.perception.oracle.textureless_landmarks = true;
  spec.mission.progress = false;
  return spec;
}

// A hand-built method: every planning step sends a climb of 0.1 m per step to where it is, and
// records the tick it planned at; its work counter `unit` is 1 (the cost model's handle); `burn`
// spends that much CPU per planning step.
class StepMethod final : public Explorer {
 public:
  explicit StepMethod(std::vector<int64_t>* planned, double burn_s = 0) : planned_(planned), burn_s_(burn_s) {}
  void observe(const SlamPointsFrame&) override { ++observed_; }
  std::optional<PathCommand> plan(const VehicleState& v) override {
    planned_->push_back(v.tick);
    const double t0 = threadCpuSeconds();
    volatile double x = 0;
    while (threadCpuSeconds() - t0 < burn_s_) x = x + 1;
    PathCommand c;
    c.tick = v.tick;
    c.waypoints = {{v.T_W_B.translation() + Vec3(0, 0, 0.1 + 0.001 * double(planned_->size())), std::nullopt}};
    return c;
  }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {{"unit", 1.0}, {"observed", observed_}}; }

 private:
  std::vector<int64_t>* planned_;
  double burn_s_ = 0;
  double observed_ = 0;
};

TEST(ComputeInTheLoop, APlanningStepOf04SRunsAt25HzAndItsPathLands04SLater) {
  const WorldTruth truth(urban().generated.shapes);
  ScenarioSpec spec = oracleMission(6.0);
  spec.flight.perception.latency_frames = 0;  // the path's delay is the compute alone
  spec.flight.perception.threads = 1;
  spec.timing.compute = ComputeMode::kModelled;
  spec.timing.plan.per = {{"unit", 0.4}};  // every planning step: 0.4 s
  std::vector<int64_t> planned;
  Mission m(spec, urban().generated.exploration_box, &truth, std::make_unique<StepMethod>(&planned));
  std::vector<int64_t> landed;
  double last = -1;
  while (m.running()) {
    const TickRecord& t = m.step();
    if (m.loop().lastPathTimeS() != last) last = m.loop().lastPathTimeS(), landed.push_back(t.tick);
  }
  const MissionResult r = m.finish();
  // 6 s at 2.5 Hz: the 0th step and one every 0.4 s (200 ticks).
  ASSERT_GE(planned.size(), 14u);
  ASSERT_LE(planned.size(), 16u);
  for (size_t i = 1; i < planned.size(); ++i) EXPECT_EQ(planned[i] - planned[i - 1], 200) << i;
  ASSERT_GE(landed.size(), planned.size() - 1);
  for (size_t i = 0; i < landed.size(); ++i) EXPECT_EQ(landed[i] - planned[i], 200) << i;
  // The method is one computer: the map updates, free themselves, wait for each planning step
  // and run with it, at 2.5 Hz instead of 5.
  EXPECT_NEAR(double(r.counters.at("observed")), double(planned.size()), 1.0);
}

// A method that sends one path, then records what each later planning step is told about it.
class OnePathMethod final : public Explorer {
 public:
  std::vector<bool> finished;
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState& v) override {
    if (sent_) {
      finished.push_back(v.path_finished);
      return std::nullopt;
    }
    sent_ = true;
    return PathCommand{v.tick, {{v.T_W_B.translation() + Vec3(0, 0, 1.0), std::nullopt}}};
  }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {{"unit", 1.0}}; }

 private:
  bool sent_ = false;
};

// A path still on its way (its planning step's compute has not ended) is not finished: the next
// planning step must not take the tracker's previous, finished path for the one it sent (the
// race that made hover_turn skip every other turn step under 2 ms of compute).
TEST(ComputeInTheLoop, APathNotYetInEffectIsNotFinished) {
  const WorldTruth truth(urban().generated.shapes);
  ScenarioSpec spec = oracleMission(1.0);
  spec.flight.perception.latency_frames = 3;  // the path lands 3 frames after its plan ...
  spec.flight.perception.threads = 1;
  spec.timing.compute = ComputeMode::kModelled;
  spec.timing.plan.base_s = 0.004;  // ... and 4 ms later: after the next plan's state (3 frames on)
  auto method = std::make_unique<OnePathMethod>();
  OnePathMethod* m = method.get();
  Mission mission(spec, urban().generated.exploration_box, &truth, std::move(method));
  while (mission.running()) mission.step();
  mission.finish();
  ASSERT_GE(m->finished.size(), 2u);
  EXPECT_FALSE(m->finished[0]);  // a 1 m climb: not done 200 ms after it was sent, nor before it landed
}

TEST(ComputeInTheLoop, AChargedRunReplaysBitForBitFromItsLog) {
  const WorldTruth truth(urban().generated.shapes);
  ScenarioSpec spec = oracleMission(4.0);
  spec.timing.compute = ComputeMode::kCharged;
  std::vector<int64_t> planned;
  Mission a(spec, urban().generated.exploration_box, &truth, std::make_unique<StepMethod>(&planned, 0.03));
  while (a.running()) a.step();
  const MissionResult ra = a.finish();
  ASSERT_FALSE(ra.flight.compute_calls.empty());
  int64_t charged = 0;
  for (const ComputeCall& c : ra.flight.compute_calls) charged += c.latency_ticks;
  EXPECT_GT(charged, 0);  // 30 ms of CPU per step: at least 15 ticks each
  // The replay: the log's latencies, not this machine's.
  ScenarioSpec replay = spec;
  replay.timing.replay = "log.csv";
  replay.compute_replay = parseComputeLog(computeLogText(ra.flight.compute_calls, {"b", "charged", 1.0, 0, ""}));
  std::vector<int64_t> planned_again;
  Mission b(replay, urban().generated.exploration_box, &truth, std::make_unique<StepMethod>(&planned_again, 0.0));
  while (b.running()) b.step();
  const MissionResult rb = b.finish();
  EXPECT_EQ(planned_again, planned);
  EXPECT_EQ(rb.run_hash, ra.run_hash);
  ASSERT_EQ(rb.flight.compute_calls.size(), ra.flight.compute_calls.size());
  // A log that ends early is an error of the run, named.
  replay.compute_replay.calls.resize(3);
  std::vector<int64_t> p3;
  Mission c(replay, urban().generated.exploration_box, &truth, std::make_unique<StepMethod>(&p3));
  EXPECT_THROW(
      {
        while (c.running()) c.step();
        c.finish();
      },
      std::runtime_error);
}

TEST(ComputeInTheLoop, ModelledMonoSpheresIsDeterministicOnOneThreadOrTwo) {
  const WorldTruth truth(urban().generated.shapes);
  auto spec = [](int threads) {
    ScenarioSpec s = oracleMission(20.0);
    s.flight.perception.latency_frames = 1;
    s.flight.perception.threads = threads;
    s.timing.compute = ComputeMode::kModelled;
    s.timing.compute_model = ComputeModel::kReferencePython;
    s.timing.applyProfile();
    return s;
  };
  const Aabb box = urban().generated.exploration_box;
  const MissionResult one = runMission(spec(1), box, &truth), two = runMission(spec(2), box, &truth);
  EXPECT_EQ(one.run_hash, two.run_hash);
  EXPECT_EQ(one.flight.compute_calls.size(), two.flight.compute_calls.size());
  // The reference profile's planning steps are never free; and the run differs from a free one.
  int64_t plan_ticks = 0;
  for (const ComputeCall& c : one.flight.compute_calls)
    if (c.stage == Stage::kPlan) plan_ticks += c.latency_ticks;
  EXPECT_GT(plan_ticks, 0);
  ScenarioSpec free = spec(1);
  free.timing = ComputeTiming{};
  EXPECT_NE(runMission(free, box, &truth).run_hash, one.run_hash);
}

TEST(ComputeInTheLoop, AModelTermTheMethodHasNoCounterForIsRefusedBeforeTheRun) {
  const WorldTruth truth(urban().generated.shapes);
  ScenarioSpec spec = oracleMission(1.0);
  spec.timing.compute = ComputeMode::kModelled;
  spec.timing.map.per = {{"frontiers", 1e-3}};
  std::vector<int64_t> planned;
  try {
    Mission m(spec, urban().generated.exploration_box, &truth, std::make_unique<StepMethod>(&planned));
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("timing.map.per.frontiers"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unit"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb
