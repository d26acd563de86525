// Reports under the evaluator's key (docs/integrity.md, tools/sweep/suite.h applySealRules): which
// records rank, which are listed, which count as failed; and the key end to end through a sweep.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"
#include "tests/tools/sweep/report_fixtures.h"
#include "tools/results/record_seal.h"
#include "tools/results/run_record.h"
#include "tools/sweep/suite.h"
#include "tools/sweep/sweep_report.h"

namespace msb {
namespace {

using msb_test::run;

// Under the evaluator's key (`report --key`, docs/integrity.md): only records sealed under it
// are ranked; self-sealed, pre-seal and other keys' records are listed; a forged re-seal (the
// public digest recomputed) counts as a failed run; a key that sealed nothing here is refused.
TEST(SweepReport, UnderTheEvaluatorsKeyOnlyItsSealedRecordsAreRanked) {
  const fs::path d = msb_test::tempDir("msb_report_", "keyed");
  std::ofstream(d / "evaluator.key") << "the evaluator's key: 32 bytes ok";
  std::ofstream(d / "submitter.key") << "a submitter's own key, 32 bytes.";
  const EvaluatorKey key = readEvaluatorKey(d / "evaluator.key");
  const EvaluatorKey theirs = readEvaluatorKey(d / "submitter.key");
  SweepResults s;
  s.dir = d / "sweep";
  s.axes = {"world", "method"};
  const std::string csv = "t_s,area_m2\n0,0\n";
  auto made = [&](const std::string& id, double area, const EvaluatorKey* with) {
    ReportRun r = madeRun(id, "urban", id.substr(6, id.size() - 9), area, "completed");
    r.metrics["versions"] = {{"msbench", "0.2.0"}};
    r.metrics["record_format"] = kRecordFormat;
    r.metrics["record_seal"] = with ? recordSeal(*with, r.metrics, csv) : std::string(kSelfSealedValue);
    fs::create_directories(s.dir / "runs" / id);
    std::ofstream(s.dir / "runs" / id / "coverage.csv") << csv;
    return r;
  };
  s.runs = {made("urban-ms-s1", 500, &key), made("urban-self-s1", 900, nullptr), made("urban-theirs-s1", 900, &theirs),
            made("urban-forged-s1", 500, &key), madeRun("urban-old-s1", "urban", "old", 400, "completed")};
  s.runs[3].metrics["coverage"]["area_m2"] = 9000.0;  // raised after sealing
  SweepResults wrong = s;
  const SealSummary sum = applySealRules(s, key);
  EXPECT_EQ(sum.evaluated, 1);
  EXPECT_EQ(sum.not_evaluated, 3);
  EXPECT_EQ(sum.tampered, 1);
  EXPECT_EQ(s.runs[0].status, "complete");
  EXPECT_NE(s.runs[1].unranked.find("self-sealed"), std::string::npos) << s.runs[1].unranked;
  EXPECT_NE(s.runs[2].unranked.find("another evaluator key (" + theirs.id + ")"), std::string::npos);
  EXPECT_EQ(s.runs[3].status, "failed");
  EXPECT_NE(s.runs[3].failure->problem.find("tampered or re-sealed"), std::string::npos);
  EXPECT_NE(s.runs[4].unranked.find("pre-seal"), std::string::npos) << s.runs[4].unranked;
  const std::vector<ReportRow> rows = reportRows(s);
  for (const ReportRow& r : rows) EXPECT_LT(r.area_m2.mean, 1000.0) << rowName(r);
  const std::string md = reportMarkdown(s, rows);
  EXPECT_NE(md.find("verified under evaluator key " + key.id), std::string::npos) << md;
  // The submitter's key on the evaluator's runs: nothing sealed under it but keyed seals here.
  wrong.runs = {wrong.runs[0]};
  try {
    applySealRules(wrong, theirs);
    ADD_FAILURE() << "a key that sealed nothing was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((d / "submitter.key").string()), std::string::npos) << e.what();
  }
}

// The evaluator's key end to end (docs/integrity.md): a sweep run with $MSBENCH_EVALUATOR_KEY_FILE
// seals its records under it; `report --key` ranks them, counts a forged re-seal as failed and
// refuses another key or a missing key file (exit 2, the file named); a key file that cannot be
// read leaves the run self-sealed and says so (exit 0); a suite a run names for itself is not
// adopted by the report (before: the report set the honest runs aside against it).
TEST(SweepReport, TheEvaluatorsKeySealsASweepAndTheReportVerifiesIt) {
  const fs::path d = msb_test::tempDir("msb_report_", "evaluator_key");
  std::ofstream(d / "evaluator.key") << "the evaluator's key: 32 bytes ok\n";
  std::ofstream(d / "other.key") << "somebody else's key, 32 bytes ok\n";
  const std::string scenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/test_world_short.yaml";
  std::ofstream(d / "sweep.yaml") << "scenario: " << scenario
                                  << "\nset: {duration_s: 2, suite: " << (d / "mine").string() << "}\nseeds: 2\n";
  const fs::path out = d / "out";
  setenv(kEvaluatorKeyFileVariable, (d / "evaluator.key").c_str(), 1);
  const int swept = run("sweep '" + (d / "sweep.yaml").string() + "' --out '" + out.string() + "' --jobs 2", d / "log");
  unsetenv(kEvaluatorKeyFileVariable);
  ASSERT_EQ(swept, 0) << readText(d / "log");
  const std::string id = readEvaluatorKey(d / "evaluator.key").id;
  const auto m = nlohmann::json::parse(readText(out / "runs" / "s1" / "metrics.json"));
  EXPECT_EQ(m["record_format"], kRecordFormat);
  EXPECT_EQ(m["record_seal"].get<std::string>().rfind("hmac-sha256:" + id + ":", 0), 0u) << m.dump();
  EXPECT_EQ(readText(out / "runs" / "s1" / "metrics.json").find("32 bytes ok"), std::string::npos);
  // Verified: both ranked; the run-named suite (a directory that does not exist) is not adopted.
  ASSERT_EQ(
      run("report '" + out.string() + "' --no-figures --key '" + (d / "evaluator.key").string() + "'", d / "log_key"),
      0)
      << readText(d / "log_key");
  EXPECT_NE(readText(d / "log_key").find("2 runs sealed under it, 0 not"), std::string::npos)
      << readText(d / "log_key");
  EXPECT_NE(readText(out / "report" / "report.md").find("2 runs: 2 complete"), std::string::npos);
  // Another key, a missing key file: exit 2, the file named.
  EXPECT_EQ(run("report '" + out.string() + "' --no-figures --key '" + (d / "other.key").string() + "'", d / "log_o"),
            2);
  EXPECT_NE(readText(d / "log_o").find((d / "other.key").string()), std::string::npos) << readText(d / "log_o");
  EXPECT_NE(readText(d / "log_o").find("sealed none of these runs"), std::string::npos) << readText(d / "log_o");
  EXPECT_EQ(run("report '" + out.string() + "' --no-figures --key '" + (d / "none.key").string() + "'", d / "log_n"),
            2);
  EXPECT_NE(readText(d / "log_n").find((d / "none.key").string() + ": file not found"), std::string::npos)
      << readText(d / "log_n");
  // A forger raises a score and recomputes the public digest: the report without a key takes it,
  // the evaluator's report counts the run as failed.
  editMetrics(out / "runs" / "s2", [](nlohmann::json& j) { j["coverage"]["area_m2"] = 5000.0; });
  ASSERT_EQ(run("report '" + out.string() + "' --no-figures", d / "log_plain"), 0) << readText(d / "log_plain");
  EXPECT_NE(readText(out / "report" / "report.md").find("not verified under an evaluator key"), std::string::npos);
  ASSERT_EQ(run("report '" + out.string() + "' --no-figures --key '" + (d / "evaluator.key").string() + "'",
                d / "log_forged"),
            0);
  EXPECT_NE(readText(d / "log_forged").find("1 tampered"), std::string::npos) << readText(d / "log_forged");
  EXPECT_NE(readText(out / "report" / "report.md").find("tampered or re-sealed"), std::string::npos);
  // An unreadable key file at run time: the run goes on self-sealed and says so.
  setenv(kEvaluatorKeyFileVariable, (d / "none.key").c_str(), 1);
  const int self =
      run("run '" + scenario + "' --duration 1 --quiet --out '" + (d / "self").string() + "'", d / "log_s");
  unsetenv(kEvaluatorKeyFileVariable);
  EXPECT_EQ(self, 0) << readText(d / "log_s");
  EXPECT_NE(readText(d / "log_s").find("self-sealed"), std::string::npos) << readText(d / "log_s");
  EXPECT_EQ(nlohmann::json::parse(readText(d / "self" / "metrics.json"))["record_seal"], kSelfSealedValue);
}

}  // namespace
}  // namespace msb
