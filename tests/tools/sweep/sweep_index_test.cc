// A sweep run's index entry: written and read back equal; bad keys named.
#include "tools/sweep/sweep_index.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

std::runtime_error bad(const std::string& key, const std::string& why) {
  return std::runtime_error("sweep.json: key '" + key + "': " + why);
}

TEST(SweepIndex, AnEntryReadsBackAsWritten) {
  SweepRunRecord r;
  r.id = "urban-no_dbof-s2";
  r.seed = 2;
  r.scenario = "/x/urban.yaml";
  r.labels = {{"world", "urban"}, {"method", "no_dbof"}};
  r.sets = {"seed=2", "method.switches.dbof=false"};
  r.status = SweepRunStatus::kFailed;
  r.failure = SweepRunFailure{};
  r.failure->exit_code = 0, r.failure->signal = 11, r.failure->signal_name = "SIGSEGV";
  r.failure->log_tail = "tail", r.failure->fatal = "fatal: SIGSEGV at tick 5";
  const nlohmann::json j = sweepRunJson(r);
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failure"]["signal_name"], "SIGSEGV");
  const SweepRunRecord back = readSweepRun(j, "runs[0]", bad);
  EXPECT_EQ(back.id, r.id);
  EXPECT_EQ(back.seed, 2u);
  EXPECT_EQ(back.labels, r.labels);
  EXPECT_EQ(back.sets, r.sets);
  EXPECT_EQ(back.status, SweepRunStatus::kFailed);
  ASSERT_TRUE(back.failure.has_value());
  EXPECT_EQ(back.failure->signal, 11);
  EXPECT_EQ(back.failure->fatal, r.failure->fatal);
  SweepRunRecord done;
  done.id = "a-s1";
  done.status = SweepRunStatus::kComplete;
  done.area_m2 = 1250.5;
  done.run_status = "collided";
  const SweepRunRecord d = readSweepRun(sweepRunJson(done), "runs[1]", bad);
  EXPECT_EQ(d.status, SweepRunStatus::kComplete);
  EXPECT_EQ(d.area_m2, 1250.5);
  EXPECT_EQ(d.run_status, "collided");
  EXPECT_FALSE(d.failure.has_value());
}

TEST(SweepIndex, BadEntriesNameTheKey) {
  auto message = [](const nlohmann::json& j) {
    try {
      readSweepRun(j, "runs[4]", bad);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"seed", 1}}).find("runs[4].id"), std::string::npos);
  EXPECT_NE(message({{"id", "a/b"}}).find("runs[4].id"), std::string::npos);
  EXPECT_NE(message({{"id", "a"}, {"status", "done"}}).find("runs[4].status"), std::string::npos);
  EXPECT_NE(message({{"id", "a"}, {"seed", -1}}).find("runs[4].seed"), std::string::npos);
  EXPECT_NE(message({{"id", "a"}, {"failure", {{"signal", "x"}}}}).find("runs[4].failure.signal"), std::string::npos);
  EXPECT_NE(message({{"id", "a"}, {"labels", {{"world", 3}}}}).find("runs[4].labels.world"), std::string::npos);
}

}  // namespace
}  // namespace msb
