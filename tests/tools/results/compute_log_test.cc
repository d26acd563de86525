// A replay's latency log is bad input when it is missing, truncated or another build's: the
// error names the scenario, the key and the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tools/results/compute_log.h"
#include "tools/results/input_files.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/provenance.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// The message of loadComputeReplay for a spec naming `file` (seed 3, scenario settings
// 00000000000000aa unless given), or "" if it loads.
std::string replayError(const std::string& file, uint64_t seed = 3, const std::string& scenario = "00000000000000aa") {
  ScenarioSpec spec;
  spec.flight.seed = seed;
  spec.replay_settings_hash = scenario;
  spec.timing.compute = ComputeMode::kCharged;
  spec.timing.replay = file;
  try {
    loadComputeReplay(spec, "s.yaml");
    return "";
  } catch (const InputFileError& e) {
    return e.what();
  }
}

TEST(ComputeLog, AReplayLogThatIsMissingTruncatedOrAnotherBuildsIsBadInput) {
  const fs::path dir = fs::path(::testing::TempDir()) / "msb_compute_log";
  fs::create_directories(dir);
  const std::vector<ComputeCall> calls = {{ComputeCall::Stage::kMap, 0, 0, 10, 1}};
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  const ComputeLogHeader header{msbGitRevision(), "charged", 1.0, 3, "00000000000000aa"};
  const std::string ours = computeLogText(calls, header);
  EXPECT_EQ(replayError(write("ok.csv", ours)), "");
  for (const auto& [name, text, says] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"cut.csv", ours.substr(0, ours.rfind("# end")), "truncated"},
           {"other.csv", computeLogText(calls, {"0123456789ab", "charged", 1.0, 3, "00000000000000aa"}),
            "build 0123456789ab"},
           {"modelled.csv", computeLogText(calls, {msbGitRevision(), "modelled", 1.0, 3, "00000000000000aa"}),
            "compute modelled"},
           {"long.csv", computeLogText({{ComputeCall::Stage::kMap, 0, 0, 10, int64_t(1) << 40}}, header),
            "outside 0...1800000"}}) {
    const std::string e = replayError(write(name, text));
    EXPECT_NE(e.find("s.yaml: key 'timing.replay'"), std::string::npos) << e;
    EXPECT_NE(e.find(name), std::string::npos) << e;
    EXPECT_NE(e.find(says), std::string::npos) << e;
  }
  // Measured in another run: another seed (`--seed 2` over seed 3's config.yaml) or scenario.
  const std::string seeded = replayError((dir / "ok.csv").string(), 2);
  EXPECT_NE(seeded.find("seed 3, this run's seed is 2"), std::string::npos) << seeded;
  const std::string other = replayError((dir / "ok.csv").string(), 3, "00000000000000bb");
  EXPECT_NE(other.find("scenario settings 00000000000000aa"), std::string::npos) << other;
  const std::string missing = replayError((dir / "none.csv").string());
  EXPECT_NE(missing.find("timing.replay"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.csv"), std::string::npos) << missing;
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A collision forfeits a positive score and keeps a negative one: crashing never pays.
TEST(Score, ACrashNeverRaisesAScore) {
  ScenarioSpec spec;
  spec.flight.world_name = "urban";
  MissionResult r;
  r.box_free_m3 = 1000;
  for (const double earned : {-6971.0, 250.0})
    for (const bool crashed : {false, true}) {
      r.earned = EarnedTally{std::max(earned, 0.0), std::max(-earned, 0.0), 0.0};
      r.flight.collision.reset();
      if (crashed) {
        CollisionEvent hit;
        hit.vehicle_position_m = hit.contact_position_m = Vec3::Zero();
        r.flight.collision = hit;
      }
      const nlohmann::json m = missionMetrics(spec, r, nullptr);
      const double expect = crashed ? std::min(earned, 0.0) : earned;
      EXPECT_DOUBLE_EQ(m["score"]["earned"].get<double>(), expect) << earned << (crashed ? " crashed" : "");
      EXPECT_DOUBLE_EQ(m["score"]["before_forfeit"].get<double>(), earned);
    }
}

}  // namespace
}  // namespace msb
