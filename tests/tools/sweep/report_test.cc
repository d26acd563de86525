// Reports and regression: the table rows of hand-built results (grouping, the paper's rows,
// time to a box share, collisions by kind); `msbench report` on a real tiny sweep (table, CSV,
// figures); `msbench regress` passing on identical results, failing on a changed A or hash on
// the same machine, and the band mode for results from another machine.
#include <gtest/gtest.h>

#include <tuple>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"
#include "tests/tools/sweep/report_fixtures.h"
#include "tools/config/scenario_yaml.h"
#include "tools/results/run_record.h"
#include "tools/sweep/findings.h"
#include "tools/sweep/regression.h"
#include "tools/sweep/suite.h"
#include "tools/sweep/sweep_report.h"

namespace msb {
namespace {

namespace fs = std::filesystem;
using msb_test::readText;
using msb_test::run;

// A suite's published runs fix each world's settings: a run whose fixed settings differ is set
// aside (no row, named with both hashes), one that matches is counted.
TEST(SweepReport, ASuiteSetsAsideRunsWithOtherSettings) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_report_suite";
  fs::remove_all(d);
  fs::create_directories(d / "suite/runs/urban-s1");
  const std::string scenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/urban.yaml";
  std::ofstream(d / "suite/runs/urban-s1/config.yaml") << effectiveScenarioYaml(loadScenario(scenario));
  const std::string suite_hash = loadScenario(scenario).fixed_settings_hash;
  SweepResults s;
  s.dir = d / "sweep";
  s.axes = {"world", "method"};
  s.runs = {madeRun("urban-mine-s1", "urban", "mine", 800, "completed"),
            madeRun("urban-fast-s1", "urban", "fast", 900, "completed"),
            madeRun("cave-mine-s1", "cave", "mine", 500, "completed")};
  s.runs[0].metrics["fixed_settings_hash"] = suite_hash;
  s.runs[1].metrics["fixed_settings_hash"] = loadScenario(scenario, {"trajectory.limits=fast"}).fixed_settings_hash;
  s.runs[2].metrics["fixed_settings_hash"] = suite_hash;
  applySuite(s, d / "suite");
  EXPECT_EQ(s.runs[0].status, "complete");
  EXPECT_EQ(s.runs[1].status, "off-suite");
  EXPECT_NE(s.runs[1].off_suite.find(suite_hash), std::string::npos) << s.runs[1].off_suite;
  EXPECT_EQ(s.runs[2].status, "off-suite");
  EXPECT_NE(s.runs[2].off_suite.find("not in the suite"), std::string::npos) << s.runs[2].off_suite;
  const auto rows = reportRows(s);
  int complete = 0;
  for (const auto& r : rows) complete += r.complete;
  EXPECT_EQ(complete, 1);
  const std::string md = reportMarkdown(s, rows);
  EXPECT_NE(md.find("## Off the suite"), std::string::npos);
  EXPECT_NE(md.find("2 off the suite"), std::string::npos);
  EXPECT_THROW(applySuite(s, d / "nothing"), std::runtime_error);
}

// Held-out worlds (docs/worlds.md): a suite is ranked on one salt; runs drawn with different
// salts (or some with none) are refused, naming the commitments.
TEST(SweepReport, ASuiteRefusesRunsDrawnWithDifferentWorldSalts) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_report_salts";
  fs::remove_all(d);
  fs::create_directories(d / "suite/runs/urban-s1");
  const std::string scenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/urban.yaml";
  std::ofstream(d / "suite/runs/urban-s1/config.yaml") << effectiveScenarioYaml(loadScenario(scenario));
  SweepResults s;
  s.dir = d / "sweep";
  s.axes = {"world", "method"};
  s.runs = {madeRun("urban-a-s1", "urban", "a", 800, "completed"),
            madeRun("urban-b-s1", "urban", "b", 900, "completed")};
  s.runs[0].metrics["world_salt_commitment"] = "fnv1a64:0000000000000001";
  s.runs[1].metrics["world_salt_commitment"] = "fnv1a64:0000000000000001";
  SweepResults same = s;
  EXPECT_NO_THROW(applySuite(same, d / "suite"));
  s.runs[1].metrics["world_salt_commitment"] = "fnv1a64:0000000000000002";
  try {
    applySuite(s, d / "suite");
    ADD_FAILURE() << "two salts were ranked together";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("2 different world salts"), std::string::npos) << e.what();
  }
  s.runs[1].metrics.erase("world_salt_commitment");
  EXPECT_THROW(applySuite(s, d / "suite"), std::runtime_error);  // one salted, one not
}

// Abstention does not pay (issue 93): a method that exits when a seed goes badly keeps the run in
// its row at A = 0 and score 0; before, the failed run left the mean and raised the row.
TEST(SweepReport, AFailedRunCountsInItsRowAsNothingExploredAndNothingEarned) {
  SweepResults s;
  s.axes = {"world", "method"};
  s.runs = {madeRun("urban-honest-s1", "urban", "honest", 500, "completed"),
            madeRun("urban-honest-s2", "urban", "honest", 500, "completed"),
            madeRun("urban-honest-s3", "urban", "honest", 300, "completed"),
            madeRun("urban-quitter-s1", "urban", "quitter", 500, "completed"),
            madeRun("urban-quitter-s2", "urban", "quitter", 500, "completed"),
            madeRun("urban-quitter-s3", "urban", "quitter", 300, "completed")};
  for (ReportRun& r : s.runs) r.metrics["score"] = {{"earned", 10 * r.record->area_m2}};
  for (ReportRun& r : s.runs) r.record = missionRecordOf(r.metrics, r.id).record;
  // The quitter's bad seed: its method exited, so the run failed.
  s.runs[5].status = "failed";
  s.runs[5].record.reset();
  s.runs[5].failure.emplace();
  s.runs[5].seed = 3;
  const std::vector<ReportRow> rows = reportRows(s);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].area_m2.count, 3);
  EXPECT_NEAR(rows[1].area_m2.mean, 1000.0 / 3, 1e-9);
  EXPECT_LT(rows[1].area_m2.mean, rows[0].area_m2.mean);
  EXPECT_NEAR(rows[1].earned_m3.mean, 10000.0 / 3, 1e-9);
  EXPECT_EQ(rows[1].failed, 1);
  EXPECT_NE(reportMarkdown(s, rows).find("counts in its row with A = 0 and score 0"), std::string::npos);
}

TEST(SweepReport, RowsGroupRunsAndCarryThePapersFigures) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  s.runs = {madeRun("urban-full-s1", "urban", "full", 800, "completed"),
            madeRun("urban-full-s2", "urban", "full", 600, "collided", "textureless"),
            madeRun("urban-no_ovde-s1", "urban", "no_ovde", 400, "collided", "thin")};
  ReportRun failed;
  failed.id = "urban-full-s3";
  failed.labels = {{"world", "urban"}, {"method", "full"}};
  failed.status = "failed";
  s.runs.push_back(failed);
  ASSERT_TRUE(isTableOneSweep(s));
  const auto rows = reportRows(s);
  ASSERT_EQ(rows.size(), 2u);
  const ReportRow& full = rows[0];
  EXPECT_EQ(full.labels, (std::vector<std::string>{"urban", "full"}));
  EXPECT_EQ(full.runs, 3);
  EXPECT_EQ(full.complete, 2);
  EXPECT_EQ(full.failed, 1);
  // The failed run counts with A = 0 (issue 93: abstention must not raise a row).
  EXPECT_EQ(full.area_m2.count, 3);
  EXPECT_DOUBLE_EQ(full.area_m2.mean, 1400.0 / 3);
  EXPECT_DOUBLE_EQ(full.max_area_m2, 800.0);
  EXPECT_EQ(full.crashes, 1);
  EXPECT_EQ(full.collisions_by_kind.at("textureless"), 1);
  ASSERT_TRUE(full.paper_mean_m2.has_value());
  EXPECT_DOUBLE_EQ(*full.paper_mean_m2, 4919.0);
  // Box share 0.8 and 0.6 at the end, linear in time: 50 % at 70 s (0.56 at 70 s) and at 90 s.
  EXPECT_EQ(full.t50_s.count, 2);
  EXPECT_DOUBLE_EQ(full.t50_s.mean, (70.0 + 90.0) / 2);
  EXPECT_EQ(full.t90_s.count, 0);
  EXPECT_DOUBLE_EQ(full.area_per_100m.mean, 350.0);
  // The ablation row maps to the paper's No OVDE row.
  EXPECT_EQ(rows[1].method, "monospheres -ovde");
  EXPECT_DOUBLE_EQ(*rows[1].paper_mean_m2, 747.0);
  EXPECT_EQ(rows[1].collisions_by_kind.at("thin"), 1);
  // The Markdown names every row and the failed run; the CSV has a line per row.
  const std::string md = reportMarkdown(s, rows);
  // (No earned column: these runs recorded no earned score.)
  // The failed run's A = 0 is in the mean and its interval.
  EXPECT_NE(md.find("| urban | full | monospheres | 2 of 3 | 467 [0, 800] | 800 | 4919 | 6081 | 1/2 [0.09, 0.91] | "
                    "2/6 (p = 1.00) |"),
            std::string::npos)
      << md;
  EXPECT_EQ(full.paper_runs, 6);
  EXPECT_EQ(full.paper_collisions, 2);
  EXPECT_FALSE(isSaturated(full));
  EXPECT_NE(md.find("| urban-full-s3 | failed |"), std::string::npos) << md;
  const std::string csv = reportTableCsv(s, rows);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_EQ(paperRow("cave", "grid_random", nlohmann::json::object())->mean_area_m2, 3171.0);
  EXPECT_EQ(paperRowNamed("urban", "monospheres -ovde")->mean_area_m2, 747.0);
  EXPECT_EQ(paperRowNamed("urban", "monospheres -ovde -dbof"), nullptr);
}

// A run in one of the authors' worlds (suburb3, recorded with paper_world rooftops) answers to
// the paper's rooftops row; without paper_world, suburb3 is no Table I world.
TEST(SweepReport, TheAuthorsWorldsAnswerToThePapersRowsByTheirPaperWorld) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  s.runs = {madeRun("rooftops-full-s1", "suburb3", "full", 900, "completed")};
  ASSERT_TRUE(s.runs[0].record.has_value());
  EXPECT_FALSE(isTableOneSweep(s));
  s.runs[0].metrics["paper_world"] = "rooftops";
  s.runs[0].record = missionRecordOf(s.runs[0].metrics, "rooftops-full-s1/metrics.json").record;
  ASSERT_TRUE(isTableOneSweep(s));
  const auto rows = reportRows(s);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].world, "rooftops");
  ASSERT_TRUE(rows[0].paper_mean_m2.has_value());
  EXPECT_DOUBLE_EQ(*rows[0].paper_mean_m2, 3760.0);
}

TEST(SweepReport, ThePublishedCodesSwitchesNameTheRowAndKeepThePapersRow) {
  // "+published" when every switch is on, "+name" for each one on, nothing for the intended
  // method; the paper's row is the same (the switches model how its runs were made).
  nlohmann::json m = {{"method", "monospheres"},
                      {"switches", {{"ovde", true}, {"dbof", false}}},
                      {"reference_code", {{"path_resend_8s", true}, {"safety_cost_inverted", true}}}};
  EXPECT_EQ(reportMethodName(m), "monospheres -dbof +published");
  m["reference_code"]["safety_cost_inverted"] = false;
  EXPECT_EQ(reportMethodName(m), "monospheres -dbof +path_resend_8s");
  m["reference_code"]["path_resend_8s"] = false;
  EXPECT_EQ(reportMethodName(m), "monospheres -dbof");
  EXPECT_EQ(paperRowNamed("urban", "monospheres -dbof +published")->mean_area_m2, 2308.0);
}

TEST(SweepReport, ACustomSweepRanksByTheEarnedScoreBeforeVerifiedA) {
  // A blanket claim that verified A would put first (880 m² against 450: it paid for sight) pays
  // for what it never looked at: the earned score puts it last.
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  for (int seed = 1; seed <= 3; ++seed) {
    ReportRun blanket = madeRun("urban-blanket-s" + std::to_string(seed), "urban", "blanket", 900, "completed");
    blanket.metrics["method"] = "python";
    blanket.metrics["duration_s"] = 60.0;
    blanket.metrics["coverage"]["verified_area_m2"] = 880.0;
    blanket.metrics["score"] = {{"earned", -7000.0 - seed}, {"unit", "m3"}};
    blanket.record = missionRecordOf(blanket.metrics, blanket.id + "/metrics.json").record;
    ReportRun ms = madeRun("urban-ms-s" + std::to_string(seed), "urban", "ms", 500, "completed");
    ms.metrics["duration_s"] = 60.0;
    ms.metrics["coverage"]["verified_area_m2"] = 450.0;
    ms.metrics["score"] = {{"earned", 2900.0 + seed}, {"unit", "m3"}};
    ms.record = missionRecordOf(ms.metrics, ms.id + "/metrics.json").record;
    s.runs.push_back(blanket);
    s.runs.push_back(ms);
  }
  const std::string md = reportMarkdown(s, reportRows(s));
  const size_t results_at = md.find("## Results");
  ASSERT_NE(results_at, std::string::npos) << md;
  EXPECT_NE(md.find("Ranked by the earned score"), std::string::npos) << md;
  const size_t ms_at = md.find("| urban | ms |", results_at), blanket_at = md.find("| urban | blanket |", results_at);
  ASSERT_NE(ms_at, std::string::npos) << md;
  ASSERT_NE(blanket_at, std::string::npos) << md;
  EXPECT_LT(ms_at, blanket_at) << md;
  EXPECT_NE(md.find("| 3 | 2902 [", ms_at), std::string::npos) << md;
}

TEST(SweepReport, ACustomSweepShowsNoPaperColumnAndNoVacuousFinding) {
  // A custom sweep: a row that is no Table I row (a method of the user's), and 40-second runs
  // of MonoSpheres beside it — no collision in four runs, which must not "hold" the paper's
  // collision findings.
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  for (int seed = 1; seed <= 2; ++seed) {
    ReportRun mine = madeRun("urban-mine-s" + std::to_string(seed), "urban", "mine", 300, "completed");
    mine.metrics["method"] = "python";
    mine.metrics["duration_s"] = 40.0;
    mine.metrics["coverage"]["verified_area_m2"] = 120.0;
    mine.metrics["score"] = {{"earned", -40.0}, {"unit", "m3"}};
    mine.record = missionRecordOf(mine.metrics, mine.id + "/metrics.json").record;
    ReportRun ms = madeRun("urban-ms-s" + std::to_string(seed), "urban", "ms", 500, "completed");
    ms.metrics["duration_s"] = 40.0;
    ms.metrics["coverage"]["verified_area_m2"] = 450.0;
    ms.metrics["score"] = {{"earned", 1800.0}, {"unit", "m3"}};
    ms.record = missionRecordOf(ms.metrics, ms.id + "/metrics.json").record;
    s.runs.push_back(mine);
    s.runs.push_back(ms);
  }
  EXPECT_FALSE(isTableOneSweep(s));
  const auto rows = reportRows(s);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_FALSE(rows[1].paper_mean_m2.has_value());  // MonoSpheres in urban, but not a Table I run
  const std::string md = reportMarkdown(s, rows);
  EXPECT_EQ(md.find("paper mean A"), std::string::npos) << md;
  EXPECT_EQ(md.find("Table I layout"), std::string::npos) << md;
  EXPECT_NE(md.find("Not a Table I sweep"), std::string::npos) << md;
  // Ranked by verified A (ms earned 450, mine 120 of its 300 claimed: flagged), two runs a row
  // shown as {min, max} ranges, not intervals; paired ratios on verified A.
  const size_t results_at = md.find("## Results");
  ASSERT_NE(results_at, std::string::npos) << md;
  const size_t ms_at = md.find("| urban | ms |", results_at);
  const size_t mine_at = md.find("| urban | mine |", results_at);
  ASSERT_NE(ms_at, std::string::npos) << md;
  ASSERT_NE(mine_at, std::string::npos) << md;
  EXPECT_LT(ms_at, mine_at) << md;
  EXPECT_NE(md.find("| 2 | -40 {-40, -40} | 120 {120, 120} | 300 {300, 300} | 0.40 {0.40, 0.40} ⚠ |", mine_at),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("{min, max}: a range, not an interval"), std::string::npos) << md;
  EXPECT_NE(md.find("Each row's mean verified A over its world's first row's (in a ranked report, the leader's)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| urban | mine / ms |"), std::string::npos) << md;
  EXPECT_NE(md.find("## Verified coverage and map accuracy"), std::string::npos) << md;
  // Every later table in the Results' order (before: sweep order, mine first).
  for (const char* section : {"## Verified coverage", "## Beyond the paper"}) {
    const size_t at = md.find(section);
    ASSERT_NE(at, std::string::npos) << section;
    EXPECT_LT(md.find("| urban | ms |", at), md.find("| urban | mine |", at)) << section;
  }
  // The Runs table says what each run earned and verified.
  EXPECT_NE(md.find("| run | status | A (m²) | earned (m³) | verified A (m²) | box share |"), std::string::npos) << md;
  EXPECT_NE(md.find("| urban-mine-s1 | completed | 300 | -40 | 120 |"), std::string::npos) << md;
  // No table of n/a findings (before: nine rows of "not a Table I sweep").
  const std::string findings_md = findingsMarkdown(evaluateFindings(s, rows));
  EXPECT_EQ(findings_md.find("| – n/a |"), std::string::npos) << findings_md;
  EXPECT_NE(findings_md.find("none applies to this sweep"), std::string::npos) << findings_md;
  // (Verified / claimed 0.40 is below 0.75: flagged.)
  EXPECT_NE(md.find("| urban | mine | 300 {300, 300} | 120 {120, 120} | 0.40 {0.40, 0.40} ⚠ |"), std::string::npos)
      << md;
  // Every finding is n/a: nothing holds, fails or is undecided.
  const FindingCounts c = countFindings(evaluateFindings(s, rows));
  EXPECT_EQ(c.holds + c.fails + c.undecided, 0);
  EXPECT_EQ(c.not_evaluated, int(findingsTable().size()));
  // table.csv: every header once (the axes world/method, then world_name/method_type).
  const std::string csv = reportTableCsv(s, rows);
  std::istringstream head(csv.substr(0, csv.find('\n')));
  std::set<std::string> names;
  for (std::string n; std::getline(head, n, ',');) EXPECT_TRUE(names.insert(n).second) << "duplicate column " << n;
  EXPECT_TRUE(names.count("method_type") && names.count("world_name") && names.count("mean_verified_area_m2"));
  // A Table I run mixed in with an unknown world is no Table I sweep either.
  s.runs.push_back(madeRun("mars-full-s1", "mars", "full", 100, "completed"));
  EXPECT_FALSE(isTableOneSweep(s));
}

TEST(SweepReport, ReportAndRegressOnARealSweep) {
  const fs::path d = msb_test::tempDir("msb_report_", "real");
  const fs::path sweep = d / "sweep.yaml";
  std::ofstream(sweep) << "scenario: " << MSB_SOURCE_DIR << "/scenarios/missions/test_world_short.yaml\n"
                       << "set: {duration_s: 3}\naxes:\n  - name: method\n    variants: {full: {}, no_fff: "
                          "{method.switches.fff: false}}\nseeds: 2\n";
  const fs::path out = d / "out";
  ASSERT_EQ(run("sweep '" + sweep.string() + "' --out '" + out.string() + "' --jobs 2", d / "log_sweep"), 0)
      << readText(d / "log_sweep");
  // Every run records the machine it ran on.
  const auto m = nlohmann::json::parse(readText(out / "runs" / "full-s1" / "metrics.json"));
  ASSERT_TRUE(m.contains("machine"));
  EXPECT_EQ(m["machine"]["id"].get<std::string>().size(), 16u);
  EXPECT_NE(m["machine"]["gl"].get<std::string>().find("llvmpipe"), std::string::npos) << m["machine"].dump();

  // The report: table, CSV, and figures when python3 with matplotlib is there.
  ASSERT_EQ(run("report '" + out.string() + "'", d / "log_report"), 0) << readText(d / "log_report");
  const std::string md = readText(out / "report" / "report.md");
  EXPECT_NE(md.find("| full | monospheres | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| no_fff | monospheres -fff | 2 |"), std::string::npos) << md;
  EXPECT_NE(readText(out / "report" / "table.csv").find("no_fff,"), std::string::npos);
  const bool have_matplotlib = std::system("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0;
  if (have_matplotlib) {
    EXPECT_TRUE(fs::exists(out / "report" / "gallery.png")) << readText(d / "log_report");
    EXPECT_GT(fs::file_size(out / "report" / "coverage_world.xml.png"), 1000u) << readText(d / "log_report");
    EXPECT_GT(fs::file_size(out / "report" / "table1.png"), 1000u) << readText(d / "log_report");
  } else {
    EXPECT_NE(readText(d / "log_report").find("apt-get install python3-matplotlib"), std::string::npos);
  }

  // Regress: a golden from the sweep passes against the same sweep (exact mode).
  const fs::path golden = d / "golden";
  ASSERT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "' --update", d / "log_up"), 0)
      << readText(d / "log_up");
  ASSERT_TRUE(fs::exists(golden / "golden.json"));
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_same"), 0)
      << readText(d / "log_same");
  EXPECT_NE(readText(d / "log_same").find("4 runs compared (4 exactly"), std::string::npos) << readText(d / "log_same");
  // An update that cannot be written (a file size limit, as a full disk) keeps the golden as it
  // was, leaves no temporary and says so (before: a 0-byte golden and exit 0).
  const std::string golden_text = readText(golden / "golden.json");
  const std::string limited = "ulimit -f 1; '" + msb_test::kExe + "' regress '" + out.string() + "' --against '" +
                              golden.string() + "' --update > '" + (d / "log_full").string() + "' 2>&1";
  const int full = std::system(("sh -c \"" + limited + "\"").c_str());
  EXPECT_TRUE(WIFEXITED(full) && WEXITSTATUS(full) != 0) << readText(d / "log_full");
  EXPECT_NE(readText(d / "log_full").find("File too large; the file was not changed"), std::string::npos)
      << readText(d / "log_full");
  EXPECT_EQ(readText(golden / "golden.json"), golden_text);
  for (const auto& e : fs::directory_iterator(golden)) EXPECT_EQ(e.path().filename(), "golden.json") << e.path();
  // A changed A on the same machine is a regression, named.
  const fs::path run_dir = out / "runs" / "no_fff-s2";
  const std::string original = readText(run_dir / "metrics.json");
  editMetrics(run_dir,
              [](nlohmann::json& j) { j["coverage"]["area_m2"] = j["coverage"]["area_m2"].get<double>() + 6.25; });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_changed"), 1);
  EXPECT_NE(readText(d / "log_changed").find("REGRESSION no_fff-s2: A"), std::string::npos)
      << readText(d / "log_changed");
  // The same hash from another machine is the same run: still exact, so the changed A fails.
  editMetrics(run_dir, [](nlohmann::json& j) { j["machine"]["id"] = "0000000000000000"; });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_samehash"), 1);
  EXPECT_NE(readText(d / "log_samehash").find("(exact mode)"), std::string::npos) << readText(d / "log_samehash");
  // From another machine with another hash: compared in a band, so a small change passes and a
  // large one fails.
  editMetrics(run_dir, [](nlohmann::json& j) { j["determinism_hash"] = "ffffffffffffffff"; });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_band"), 0)
      << readText(d / "log_band");
  EXPECT_NE(readText(d / "log_band").find("1 in band mode"), std::string::npos) << readText(d / "log_band");
  editMetrics(run_dir,
              [](nlohmann::json& j) { j["coverage"]["area_m2"] = 5.0 * j["coverage"]["area_m2"].get<double>() + 500; });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_band2"), 1);
  EXPECT_NE(readText(d / "log_band2").find("band mode"), std::string::npos) << readText(d / "log_band2");
  // Without a machine id and a hash the mode is not chosen silently: an error unless --band.
  editMetrics(run_dir, [](nlohmann::json& j) {
    j["machine"].erase("id");
    j["coverage"]["area_m2"] = 1.2 * j["coverage"]["area_m2"].get<double>();
  });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_noid"), 1);
  EXPECT_NE(readText(d / "log_noid").find("no determinism hash or machine id (use --band"), std::string::npos)
      << readText(d / "log_noid");
  // A truncated metrics.json is a failed run, never a complete one.
  const std::string edited = readText(run_dir / "metrics.json");
  std::ofstream(run_dir / "metrics.json") << edited.substr(0, edited.size() / 2);
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "' --band", d / "log_trunc"), 1);
  EXPECT_NE(readText(d / "log_trunc").find("no_fff-s2: did not complete (failed"), std::string::npos)
      << readText(d / "log_trunc");
  EXPECT_NE(readText(d / "log_trunc").find("not valid JSON"), std::string::npos) << readText(d / "log_trunc");
  // A changed status fails in either mode; a missing golden file is bad input.
  std::ofstream(run_dir / "metrics.json") << original;
  editMetrics(run_dir, [](nlohmann::json& j) { j["status"] = "collided"; });
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + golden.string() + "'", d / "log_status"), 1);
  EXPECT_NE(readText(d / "log_status").find("status collided, golden completed"), std::string::npos);
  EXPECT_EQ(run("regress '" + out.string() + "' --against '" + (d / "nothing").string() + "'", d / "log_missing"), 2);
  // A complete run without its coverage.csv counts as failed in the report, the file named
  // (before: read as a run without samples).
  fs::rename(out / "runs" / "full-s1" / "coverage.csv", d / "coverage.csv.away");
  EXPECT_EQ(run("report '" + out.string() + "'", d / "log_nocov"), 0) << readText(d / "log_nocov");
  EXPECT_NE(readText(d / "log_nocov").find("run full-s1 counts as failed"), std::string::npos)
      << readText(d / "log_nocov");
  EXPECT_NE(readText(d / "log_nocov").find("coverage.csv: missing"), std::string::npos) << readText(d / "log_nocov");
  // A coverage.csv with a hexadecimal, a negative area or a share above 1 is corrupt: the run
  // counts as failed, the file, line and column named (before: read and averaged as is).
  fs::rename(d / "coverage.csv.away", out / "runs" / "full-s1" / "coverage.csv");
  const std::string csv = readText(out / "runs" / "full-s1" / "coverage.csv");
  const std::string header = csv.substr(0, csv.find('\n') + 1);
  ASSERT_EQ(header,
            "t_s,area_m2,area_box_m2,area_true_frame_m2,distance_m,box_share,area_verified_m2,score_earned_m3\n");
  for (const auto& [row, column] :
       std::vector<std::pair<std::string, std::string>>{{"0x1p3,0,0,0,0,0,0,0", "t_s"},
                                                        {"1,-5,0,0,0,0,0,0", "area_m2"},
                                                        {"1,5,0,0,0,1.5,0,0", "box_share"},
                                                        {"1,5,0,0,0,0.5,0,-1e300", "score_earned_m3"}}) {
    { std::ofstream(out / "runs" / "full-s1" / "coverage.csv") << header << row << "\n"; }
    editMetrics(out / "runs" / "full-s1", [](nlohmann::json&) {});  // sealed with this coverage.csv
    EXPECT_EQ(run("report '" + out.string() + "'", d / "log_badcov"), 0) << readText(d / "log_badcov");
    const std::string log = readText(d / "log_badcov");
    EXPECT_NE(log.find("run full-s1 counts as failed"), std::string::npos) << row << "\n" << log;
    EXPECT_NE(log.find("coverage.csv: line 2: column '" + column + "'"), std::string::npos) << row << "\n" << log;
  }
  { std::ofstream(out / "runs" / "full-s1" / "coverage.csv") << csv; }
  editMetrics(out / "runs" / "full-s1", [](nlohmann::json&) {});
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

TEST(SweepReport, ACollisionsAuditIsOneLineOfTheRunsTable) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  ReportRun r;
  r.id = "urban-full-s1";
  r.labels = {{"world", "urban"}, {"method", "full"}};
  r.status = "complete";
  r.metrics = {{"status", "collided"},
               {"world", "urban"},
               {"method", "monospheres"},
               {"sim_time_s", 100.0},
               {"determinism_hash", "0123456789abcdef"},
               {"coverage", {{"area_m2", 500.0}, {"box_share", 0.4}}},
               {"collision",
                {{"world_geom", "building_1_burned"},
                 {"object", "building_1"},
                 {"kind", "textureless"},
                 {"audit",
                  {{"cause", "seen-but-freed"},
                   {"slam_points_on_part", 41},
                   {"map_points_on_object", 144},
                   {"vio_drift_m", 1.56},
                   {"inside_free_space", true}}}}}};
  r.record = missionRecordOf(r.metrics, "m.json").record;
  ASSERT_TRUE(r.record.has_value());
  s.runs = {r};
  const std::string md = reportMarkdown(s, reportRows(s));
  EXPECT_NE(md.find("building_1 (textureless): seen-but-freed — 41 SLAM points on the part, 144 map points on the "
                    "object, drift 1.6 m, inside free space"),
            std::string::npos)
      << md;
}

// A complete urban run of a Python method, variant `variant` (its axis label), seed 1, with
// `coverage` and, if given, `map_accuracy` in its record.
ReportRun pythonRun(const std::string& variant, const nlohmann::json& coverage,
                    const nlohmann::json& map_accuracy = nullptr) {
  ReportRun r;
  r.id = "urban-" + variant + "-s1";
  r.labels = {{"world", "urban"}, {"method", variant}};
  r.status = "complete";
  r.metrics = {{"status", "completed"},
               {"world", "urban"},
               {"method", "python"},
               {"sim_time_s", 100.0},
               {"determinism_hash", "0123456789abcdef"},
               {"coverage", coverage}};
  if (!map_accuracy.is_null()) r.metrics["map_accuracy"] = map_accuracy;
  r.record = missionRecordOf(r.metrics, "m.json").record;
  return r;
}

TEST(SweepReport, TheSaturationTableNamesEachVariantOfOneMethod) {
  // Two variants of one method (a Python method with two parameter sets) that both fill the
  // box: each row names its variant (before: "python (saturated)" twice).
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  for (const char* variant : {"slow", "fast"}) {
    s.runs.push_back(pythonRun(variant, {{"area_m2", 5000.0}, {"box_share", 0.97}}));
    ASSERT_TRUE(s.runs.back().record.has_value());
  }
  const std::string md = reportMarkdown(s, reportRows(s));
  EXPECT_NE(md.find("| urban | python [slow] (saturated) | 1/1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| urban | python [fast] (saturated) | 1/1 |"), std::string::npos) << md;
}

TEST(SweepReport, TheVerifiedSectionFlagsARowThatClaimsWhatItDidNotEarn) {
  // One honest row and one that claims 12 times what it earned, half of its free space inside
  // obstacles: only the second is flagged, each figure where it stands, with the flag explained.
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  for (const auto& [variant, verified, falsely_free] :
       std::vector<std::tuple<std::string, double, double>>{{"honest", 4900.0, 0.01}, {"cheat", 400.0, 0.5}}) {
    s.runs.push_back(pythonRun(variant, {{"area_m2", 5000.0}, {"box_share", 0.5}, {"verified_area_m2", verified}},
                               {{"falsely_free_volume_share", falsely_free}, {"falsely_free_element_share", 0.1}}));
    ASSERT_TRUE(s.runs.back().record.has_value());
  }
  const std::string md = reportMarkdown(s, reportRows(s));
  const auto line = [&](const std::string& start) {
    const size_t at = md.find(start, md.find("## Verified coverage"));
    return at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at);
  };
  EXPECT_EQ(line("| urban | honest |").find("⚠"), std::string::npos) << md;
  const std::string cheat = line("| urban | cheat |");
  EXPECT_NE(cheat.find("0.08 ⚠"), std::string::npos) << cheat;
  EXPECT_NE(cheat.find("0.500 ⚠"), std::string::npos) << cheat;
  EXPECT_NE(md.find("⚠: verified / claimed below 0.75"), std::string::npos) << md;
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// A complete urban run as the report reads it, with an earned score (m³).
ReportRun earnedRun(double earned) {
  ReportRun r;
  r.id = "urban-monospheres-s1";
  r.status = "complete";
  r.metrics = {{"world", "urban"},
               {"method", "monospheres"},
               {"status", "completed"},
               {"sim_time_s", 60.0},
               {"duration_s", 60.0},
               {"determinism_hash", "0123456789abcdef"},
               {"machine", {{"id", "1111111111111111"}}},
               {"coverage", {{"area_m2", 1000.0}}},
               {"score", {{"earned", earned}, {"unit", "m3"}}}};
  r.record = missionRecordOf(r.metrics, "metrics.json").record;
  return r;
}

TEST(Regression, TheEarnedScoreIsKeptInTheGoldenAndComparedExactlyOrInABand) {
  SweepResults same;
  same.runs = {earnedRun(3000.0)};
  const nlohmann::json golden = goldenFromSweep(same, RegressionTolerance{});
  EXPECT_EQ(golden["runs"][0]["score_earned_m3"].get<double>(), 3000.0);
  EXPECT_TRUE(compareWithGolden(same, golden, {}).regressions.empty());
  // Exact mode (the same machine): any change is a regression, named.
  SweepResults moved;
  moved.runs = {earnedRun(3001.0)};
  const auto exact = compareWithGolden(moved, golden, {});
  ASSERT_EQ(exact.regressions.size(), 1u);
  EXPECT_EQ(exact.regressions[0], "urban-monospheres-s1: earned 3001.0 m³, golden 3000.0 m³ (exact mode)");
  // Band mode: within 25 % (at least 250 m³) passes, beyond fails.
  RegressionTolerance band;
  band.band_only = true;
  EXPECT_TRUE(compareWithGolden(moved, golden, band).regressions.empty());
  SweepResults far;
  far.runs = {earnedRun(4000.0)};
  const auto banded = compareWithGolden(far, golden, band);
  ASSERT_EQ(banded.regressions.size(), 1u);
  EXPECT_NE(banded.regressions[0].find("earned 4000.0 m³, golden 3000.0 m³ ± 750.0"), std::string::npos);
  // A golden without the score (taken before it existed) compares A alone.
  nlohmann::json old = golden;
  old["runs"][0].erase("score_earned_m3");
  EXPECT_TRUE(compareWithGolden(far, old, {}).regressions.empty());
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// Names from files reach report.md as text: a sweep directory, a suite, axis names and labels,
// run ids, a failed run's last progress line and a collision's object carrying markup, a link,
// a table break and bidirectional controls leave no tag, no link and no extra cell.
TEST(SweepReport, NamesFromFilesAreInertInReportMd) {
  const std::string payload = "<img src=x onerror=alert(1)></table><h1>x</h1>[a](javascript:alert(1))|\u202Eevil`";
  SweepResults s;
  s.dir = "/tmp/" + payload;
  s.suite = payload;
  s.axes = {"world", payload};
  ReportRun ok = madeRun("urban-" + payload + "-s1", "urban", payload, 500, "collided", "textured");
  ok.labels = {{"world", "urban"}, {payload, payload}};
  ok.metrics["collision"]["object"] = payload;
  ok.record = missionRecordOf(ok.metrics, "m.json").record;
  ReportRun failed;
  failed.id = payload + "-s2";
  failed.labels = {{"world", "urban"}, {payload, payload}};
  failed.status = "failed";
  SweepRunFailure f;
  f.exit_code = 1;
  f.last_progress = payload;
  failed.failure = f;
  s.runs = {ok, failed};
  const std::string md = reportMarkdown(s, reportRows(s));
  for (const char* bad : {"<img", "</table>", "<h1>", "\u202E"})
    EXPECT_EQ(md.find(bad), std::string::npos) << bad << "\n" << md;
  for (size_t at = md.find("](javascript"); at != std::string::npos; at = md.find("](javascript", at + 1))
    EXPECT_EQ(md[at - 1], '\\') << "a link at " << at << "\n" << md;
  EXPECT_NE(md.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos) << md;
  // Every line of the runs table keeps its nine cell separators (escaped pipes are not ones).
  const size_t runs = md.find("## Runs");
  ASSERT_NE(runs, std::string::npos);
  std::istringstream lines(md.substr(runs));
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| ", 0) != 0) continue;
    int pipes = 0;
    for (size_t i = 0; i < line.size(); ++i) pipes += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
    EXPECT_EQ(pipes, 9) << line;
    ++rows;
  }
  EXPECT_GE(rows, 3);
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// An unsealed record whose earned score exceeds its own box's free volume is not read as a
// result (no run of msbench writes one).
TEST(SweepReport, AnEarnedScoreAboveTheBoxsFreeVolumeIsRefused) {
  ReportRun r = madeRun("urban-x-s1", "urban", "x", 500, "completed");
  r.metrics["score"] = {{"earned", 99999.0}, {"box_free_m3", 28887.0}};
  const MissionRecordRead over = missionRecordOf(r.metrics, "m.json");
  EXPECT_FALSE(over.record.has_value());
  EXPECT_NE(over.problem.find("score.earned"), std::string::npos) << over.problem;
  r.metrics["score"]["earned"] = 20000.0;
  EXPECT_TRUE(missionRecordOf(r.metrics, "m.json").record.has_value());
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// Every report ranks only sealed records of confined or compiled methods: an unsealed record
// (its digest removed) and an unconfined run are listed with their reason and in no row.
TEST(SweepReport, OnlySealedConfinedRunsAreRanked) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  ReportRun honest = madeRun("urban-ms-s1", "urban", "ms", 500, "completed");
  honest.metrics["method_confinement"] = "compiled into msbench";
  honest.metrics["record_digest"] = "x";
  ReportRun unsealed = madeRun("urban-forger-s1", "urban", "forger", 9000, "completed");
  unsealed.metrics["method_confinement"] = "own process, Landlock ABI 7";
  ReportRun chooser = madeRun("urban-chooser-s1", "urban", "chooser", 9000, "completed");
  chooser.metrics["method_confinement"] = "in-process goal chooser (unconfined)";
  chooser.metrics["record_digest"] = "x";
  ReportRun old = madeRun("urban-old-s1", "urban", "old", 400, "completed");  // before the seal: as before
  // A record of a build that writes keyed seals, with its record_seal deleted: unsealed, whatever
  // else it lacks (pre-seal is decided by the build's version).
  ReportRun stripped = madeRun("urban-stripped-s1", "urban", "stripped", 9000, "completed");
  stripped.metrics["versions"] = {{"msbench", "0.2.0"}};
  stripped.metrics["record_digest"] = "x";
  s.runs = {honest, unsealed, chooser, old, stripped};
  applyRankRules(s);
  EXPECT_EQ(s.runs[0].status, "complete");
  EXPECT_EQ(s.runs[1].status, "unranked");
  EXPECT_NE(s.runs[1].unranked.find("unsealed"), std::string::npos);
  EXPECT_EQ(s.runs[2].status, "unranked");
  EXPECT_NE(s.runs[2].unranked.find("unconfined"), std::string::npos);
  EXPECT_EQ(s.runs[3].status, "complete");
  EXPECT_EQ(s.runs[4].status, "unranked");
  EXPECT_NE(s.runs[4].unranked.find("no record_seal"), std::string::npos) << s.runs[4].unranked;
  const std::vector<ReportRow> rows = reportRows(s);
  for (const ReportRow& r : rows) EXPECT_LT(r.area_m2.mean, 1000.0) << rowName(r);
  const std::string md = reportMarkdown(s, rows);
  EXPECT_NE(md.find("## Not ranked"), std::string::npos) << md;
  EXPECT_NE(md.find("| urban-forger-s1 | unsealed"), std::string::npos) << md;
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// The default report's suite is msbench's own settings: a sweep variant that changes a fixed
// setting (a longer camera range: it used to outrank MonoSpheres in the default report) is set
// aside as retuned where another run flies msbench's own; a world msbench publishes nothing in,
// or runs all on settings of their own, are left to --suite.
TEST(SweepReport, ARetunedVariantIsNotRankedBesideMsbenchsOwnSettings) {
  const std::string scenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/urban.yaml";
  SettingsByWorld own;
  own["urban"].insert(loadScenario(scenario).fixed_settings_hash);
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  s.runs = {madeRun("urban-ms-s1", "urban", "ms", 500, "completed"),
            madeRun("urban-far-s1", "urban", "far", 9000, "completed"),
            madeRun("cave-far-s1", "cave", "far", 9000, "completed")};
  s.runs[0].metrics["fixed_settings_hash"] = loadScenario(scenario).fixed_settings_hash;
  const std::string far = loadScenario(scenario, {"camera.clip_far_m=150"}).fixed_settings_hash;
  s.runs[1].metrics["fixed_settings_hash"] = far;
  s.runs[2].metrics["fixed_settings_hash"] = far;
  SweepResults alone = s;
  alone.runs.erase(alone.runs.begin());  // no run on msbench's own settings: nothing to compare with
  applyRetunedRule(s, own);
  EXPECT_EQ(s.runs[0].status, "complete");
  EXPECT_EQ(s.runs[1].status, "unranked");
  EXPECT_NE(s.runs[1].unranked.find("retuned"), std::string::npos) << s.runs[1].unranked;
  EXPECT_NE(s.runs[1].unranked.find(far), std::string::npos) << s.runs[1].unranked;
  EXPECT_EQ(s.runs[2].status, "complete");  // cave: no own settings given here
  const std::string md = reportMarkdown(s, reportRows(s));
  EXPECT_NE(md.find("| urban-far-s1 | retuned"), std::string::npos) << md;
  applyRetunedRule(alone, own);
  EXPECT_EQ(alone.runs[0].status, "complete");
  // The reason quotes metrics.json (a stranger's file): a hash written as markup or a table cell
  // is shown as text.
  SweepResults hostile = s;
  hostile.runs[1] = madeRun("urban-far-s1", "urban", "far", 9000, "completed");
  hostile.runs[1].metrics["fixed_settings_hash"] = "x | <script>alert(1)</script>\n## Forged";
  applyRetunedRule(hostile, own);
  ASSERT_EQ(hostile.runs[1].status, "unranked");
  const std::string hmd = reportMarkdown(hostile, reportRows(hostile));
  EXPECT_EQ(hmd.find("<script>"), std::string::npos) << hmd;
  EXPECT_EQ(hmd.find("\n## Forged"), std::string::npos) << hmd;
}

}  // namespace
}  // namespace msb
