// Sweeps: expansion of a sweep file (ids, order, variants, seeds, include/exclude, errors), and
// the runner on short test-world runs: parallel runs, a failing run recorded while the others
// complete, resume (complete runs skipped, missing ones redone), a killed sweep resumed to the
// same results, a changed sweep file named.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/sweep_plan.h"
#include "tools/config/yaml_reader.h"

namespace msb {
namespace {

namespace fs = std::filesystem;
using msb_test::readText;
using msb_test::run;

const std::string kScenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/test_world_short.yaml";

fs::path writeSweep(const fs::path& dir, const std::string& body) {
  const fs::path f = dir / "sweep.yaml";
  std::ofstream(f) << "scenario: " << kScenario << "\n" << body;
  return f;
}

TEST(SweepPlan, ExpandsAxesVariantsSeedsAndFilters) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "plan");
  const fs::path f = writeSweep(d, R"(set: {duration_s: 30}
axes:
  - {name: world, key: world, values: [a, b]}
  - name: variant
    variants:
      full: {}
      no_ovde: {method.switches.ovde: false, method.map.r_max_m: 8}
      other: {scenario: other.yaml}
seeds: 2
exclude: [{world: b, variant: other}, {world: a, variant: full, seed: 2}]
)");
  const SweepPlan p = loadSweepPlan(f.string());
  std::vector<std::string> ids;
  for (const auto& r : p.runs) ids.push_back(r.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"a-full-s1", "a-no_ovde-s1", "a-no_ovde-s2", "a-other-s1", "a-other-s2",
                                           "b-full-s1", "b-full-s2", "b-no_ovde-s1", "b-no_ovde-s2"}));
  const SweepRun& r = p.runs[2];
  EXPECT_EQ(r.seed, 2u);
  EXPECT_EQ(r.scenario, kScenario);
  const std::vector<std::pair<std::string, std::string>> sets = {
      {"duration_s", "30"}, {"world", "a"}, {"method.switches.ovde", "false"}, {"method.map.r_max_m", "8"}};
  EXPECT_EQ(r.sets, sets);
  EXPECT_EQ(p.runs[3].scenario, (d / "other.yaml").string());
  EXPECT_EQ(p.axes, (std::vector<std::string>{"world", "variant"}));
  // The same file expands the same way; include keeps only what it names.
  EXPECT_EQ(loadSweepPlan(f.string()).file_hash, p.file_hash);
  const fs::path g = writeSweep(d, "axes: [{name: w, key: world, values: [a, b]}]\nseeds: [3, 7]\ninclude: [{w: b}]\n");
  const SweepPlan q = loadSweepPlan(g.string());
  ASSERT_EQ(q.runs.size(), 2u);
  EXPECT_EQ(q.runs[0].id, "b-s3");
  EXPECT_EQ(q.runs[1].id, "b-s7");
  // An entry's seed may be a list: one entry per row instead of one per seed (table1.yaml).
  const fs::path h =
      writeSweep(d, "axes: [{name: w, key: world, values: [a, b]}]\nseeds: 4\nexclude: [{w: b, seed: [2, 4]}]\n");
  std::vector<std::string> kept;
  for (const auto& run : loadSweepPlan(h.string()).runs) kept.push_back(run.id);
  EXPECT_EQ(kept, (std::vector<std::string>{"a-s1", "a-s2", "a-s3", "a-s4", "b-s1", "b-s3"}));
}

// A value the sweep file gives is the value the run gets: names with quotes, Markdown or a '#'
// reach `--set` quoted, and read back unchanged.
TEST(SweepPlan, SetValuesReachTheRunAsTheyWereWritten) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "quoted");
  const std::string name = "a \"quoted\" [x](y) # not a comment: {z}";
  const fs::path f = writeSweep(
      d, "set: {name: '" + std::string("a \"quoted\" [x](y) # not a comment: {z}") + "', duration_s: 30}\nseeds: 1\n");
  const SweepPlan p = loadSweepPlan(f.string());
  ASSERT_EQ(p.runs.size(), 1u);
  std::vector<std::string> sets;
  for (const auto& [k, v] : p.runs[0].sets) sets.push_back(k + "=" + v);
  const ScenarioSpec spec = loadScenario(p.runs[0].scenario, sets);
  EXPECT_EQ(spec.name, name);
  EXPECT_DOUBLE_EQ(spec.flight.duration_s, 30.0);
}

// A sweep kept in a method's folder names missions by name, as a scenario's `base:` does; a
// file of that name beside the sweep wins.
TEST(SweepPlan, ScenariosAreNamedByAMissionsNameOrAFileBeside) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "by_name");
  std::ofstream(d / "mine") << "base: base\n";
  std::ofstream(d / "sweep.yaml")
      << "scenario: monospheres\naxes: [{name: m, variants: {a: {}, b: {scenario: grid_random}, "
         "c: {scenario: mine}}}]\nseeds: 1\n";
  const SweepPlan p = loadSweepPlan((d / "sweep.yaml").string());
  ASSERT_EQ(p.runs.size(), 3u);
  const std::string missions = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/";
  EXPECT_EQ(p.runs[0].scenario, missions + "monospheres.yaml");
  EXPECT_EQ(p.runs[1].scenario, missions + "grid_random.yaml");
  EXPECT_EQ(p.runs[2].scenario, (d / "mine").string());
  EXPECT_EQ(loadScenario(p.runs[1].scenario, {"world=urban"}).method.type, "grid_random");
}

TEST(SweepPlan, BadSweepFilesNameTheFileAndKey) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "bad");
  auto expectError = [&](const std::string& body, const std::string& fragment) {
    const fs::path f = writeSweep(d, body);
    try {
      loadSweepPlan(f.string());
      ADD_FAILURE() << "accepted: " << body;
    } catch (const FileConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(f.string()), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  expectError("axes: [{name: w, key: world, values: [a]}]\ncolour: red\n", "colour");
  expectError("axes: [{name: w, values: [a]}]\n", "axes[0].key");
  expectError("axes: [{name: w, key: world, values: [a/b]}]\n", "label 'a/b'");
  expectError("axes: [{name: w, key: world, values: [a]}]\nseeds: 0\n", "seeds");
  expectError("axes: [{name: w, key: world, values: [a]}]\nexclude: [{v: x}]\n", "exclude[0].v");
  expectError("axes: [{name: w, key: world, values: [a]}]\ninclude: [{w: z}]\n", "include[0]': matches no combination");
  // An exclude entry that matches nothing (a misspelt value) is refused, not ignored.
  expectError("axes: [{name: w, key: world, values: [a, b]}]\nexclude: [{w: a}, {w: c}]\n",
              "exclude[1]': matches no combination");
  expectError("axes: [{name: w, key: world, values: [a]}]\nexclude: [{w: a, seed: []}]\n", "exclude[0].seed");
  expectError("axes: [{name: w, key: world, values: [a]}]\nexclude: [{w: a, seed: [1, x]}]\n", "exclude[0].seed[1]");
  expectError("axes: [{name: w, key: world, values: [a]}]\nseeds: 2\nexclude: [{seed: [7, 8]}]\n",
              "exclude[0]': matches no combination");
}

// Starts `msbench sweep FILE --out OUT` in the background as the leader of its own process group
// (setsid), output to `log`; returns its pid (0 if it could not be started).
int startSweepInItsOwnGroup(const fs::path& file, const fs::path& out, const fs::path& log) {
  const std::string cmd = "setsid '" + msb_test::kExe + "' sweep '" + file.string() + "' --out '" + out.string() +
                          "' > '" + log.string() + "' 2>&1 & echo $!";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return 0;
  int pid = 0;
  if (fscanf(p, "%d", &pid) != 1) pid = 0;
  pclose(p);
  return pid;
}

// A sweep directory's runs.csv as id → row fields.
std::map<std::string, std::vector<std::string>> rows(const fs::path& dir) {
  std::map<std::string, std::vector<std::string>> out;
  std::istringstream in(readText(dir / "runs.csv"));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string x;
    while (std::getline(ss, x, ',')) f.push_back(x);
    out[f[0]] = f;
  }
  return out;
}

TEST(Sweep, RunsInParallelRecordsAFailureAndResumes) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "run");
  // Two good variants x 2 seeds, and one that fails at run time (the oracle feature source
  // needs a generated world; the test world is plain MJCF): exit 2 of that run only.
  const fs::path f = writeSweep(d, R"(set: {duration_s: 3}
axes:
  - name: variant
    variants:
      a: {}
      b: {mission.metric_rate_hz: 2}
      broken: {perception.source: oracle}
seeds: 2
exclude: [{variant: broken, seed: 2}]
)");
  const fs::path out = d / "out";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --jobs 2", d / "log1"), 1)
      << readText(d / "log1");
  auto r = rows(out);
  ASSERT_EQ(r.size(), 5u);
  for (const auto& id : {"a-s1", "a-s2", "b-s1", "b-s2"}) EXPECT_EQ(r[id][3], "complete") << id;
  EXPECT_EQ(r["broken-s1"][3], "failed");
  EXPECT_EQ(r["broken-s1"][10], "2");  // exit code
  const auto index = nlohmann::json::parse(readText(out / "sweep.json"));
  EXPECT_NE(index["runs"][4]["failure"]["log_tail"].get<std::string>().find("oracle"), std::string::npos);
  // Resume: complete runs skipped (their files untouched), a removed one redone, the failed one
  // tried again; the results are the same.
  const auto stamp = fs::last_write_time(out / "runs" / "a-s1" / "metrics.json");
  const std::string b2_hash = r["b-s2"][9];
  fs::remove_all(out / "runs" / "b-s2");
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --jobs 2", d / "log2"), 1);
  // b-s2 was removed and broken-s1 failed: 3 complete, 2 to run.
  EXPECT_NE(readText(d / "log2").find("3 complete, 2 to run"), std::string::npos) << readText(d / "log2");
  const auto r2 = rows(out);
  EXPECT_EQ(r2.at("b-s2")[3], "complete");
  EXPECT_EQ(r2.at("b-s2")[9], b2_hash);
  EXPECT_EQ(fs::last_write_time(out / "runs" / "a-s1" / "metrics.json"), stamp);
  // A changed sweep file is named and refused.
  std::ofstream(f, std::ios::app) << "# changed\n";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log3"), 2);
  EXPECT_NE(readText(d / "log3").find("the sweep file changed"), std::string::npos) << readText(d / "log3");
}

// A run's log path that is a FIFO (or device) is never opened for writing: the run fails at
// once, its record names the log, the sweep goes on (before: the run blocked until its limit).
TEST(Sweep, ARunWhoseLogIsAFifoFailsAtOnceNamingIt) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "fifo_log");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 2\n");
  const fs::path out = d / "out";
  ASSERT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --jobs 1", d / "log0"), 0)
      << readText(d / "log0");
  // Resumed with run s1 to redo and a FIFO where its log goes.
  fs::remove_all(out / "runs" / "s1");
  fs::remove(out / "logs" / "s1.log");
  ASSERT_EQ(mkfifo((out / "logs" / "s1.log").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --jobs 1", d / "log"), 1)
      << readText(d / "log");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120));
  auto r = rows(out);
  EXPECT_EQ(r["s1"][2], "failed");  // id, seed, status (no axes)
  EXPECT_EQ(r["s2"][2], "complete");
  const auto index = nlohmann::json::parse(readText(out / "sweep.json"));
  EXPECT_NE(index["runs"][0]["failure"]["log_tail"].get<std::string>().find("s1.log: is a FIFO"), std::string::npos)
      << index["runs"][0]["failure"].dump();
}

TEST(Sweep, ARunKilledByASignalIsRecordedFailedAndTheSweepGoesOn) {
  // Three runs one at a time; the second gets SIGSEGV once it has printed its first progress
  // line (as a memory error would end it): recorded failed with the signal, the crash handler's
  // line and the last progress line; the others complete.
  const fs::path d = msb_test::tempDir("msb_sweep_", "signal");
  const fs::path f = writeSweep(d, "set: {duration_s: 12}\nseeds: 3\n");
  const fs::path out = d / "out";
  ASSERT_NE(startSweepInItsOwnGroup(f, out, d / "log"), 0);
  // Wait for run s2's first progress line, then kill it (its command line names its output
  // directory).
  const std::string pattern = (out / "runs" / "s2").string();
  bool killed = false;
  for (int i = 0; i < 1200 && !killed; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (readText(out / "logs" / "s2.log").find(": t = 10 / 12 s") == std::string::npos) continue;
    // "[-]-out": the regular expression matches the run's "--out" but not this shell's own
    // command line, which holds the pattern too.
    killed = std::system(("pkill -SEGV -f -- '[-]-out " + pattern + " ' > /dev/null 2>&1").c_str()) == 0;
  }
  ASSERT_TRUE(killed) << readText(d / "log");
  // The sweep (a background shell job) is not our child: wait for its last line.
  for (int i = 0; i < 1200 && readText(d / "log").find("runs complete") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto r = rows(out);
  ASSERT_EQ(r.size(), 3u) << readText(d / "log");
  EXPECT_EQ(r.at("s1")[2], "complete");
  EXPECT_EQ(r.at("s2")[2], "failed");
  EXPECT_EQ(r.at("s2")[10], "11");  // signal
  EXPECT_EQ(r.at("s3")[2], "complete");
  EXPECT_NE(readText(d / "log").find("2 of 3 runs complete, 1 failed"), std::string::npos) << readText(d / "log");
  EXPECT_FALSE(fs::exists(out / "runs" / "s2" / "metrics.json"));
  const auto failure = nlohmann::json::parse(readText(out / "sweep.json"))["runs"][1]["failure"];
  EXPECT_EQ(failure["signal_name"], "SIGSEGV") << failure.dump(2);
  EXPECT_NE(failure.value("last_progress", "").find("t = 10 / 12 s"), std::string::npos) << failure.dump(2);
  EXPECT_NE(failure.value("fatal", "").find("msbench run: fatal signal 11 (SIGSEGV) after tick "), std::string::npos)
      << failure.dump(2);
  // The report lists the failed run before the table.
  ASSERT_EQ(run("report '" + out.string() + "' --no-figures", d / "log_report"), 0) << readText(d / "log_report");
  const std::string report = readText(out / "report" / "report.md");
  const size_t failed_at = report.find("## Failed runs"), table_at = report.find("## Table I layout");
  ASSERT_NE(failed_at, std::string::npos) << report;
  EXPECT_LT(failed_at, table_at);
  EXPECT_NE(report.find("| s2 | signal 11 (SIGSEGV) |", failed_at), std::string::npos) << report;
}

TEST(Sweep, ARunPastItsWallClockLimitIsStoppedAndRecordedFailed) {
  // A run that never ends by itself (a hung method, a deadlock) costs at most its limit: the
  // sweep sends SIGTERM, records the run failed with the limit named, and goes on.
  const fs::path d = msb_test::tempDir("msb_sweep_", "limit");
  const fs::path f = writeSweep(d, "set: {duration_s: 60}\nseeds: 1\n");
  const fs::path out = d / "out";
  run("sweep '" + f.string() + "' --out '" + out.string() + "' --run-time-limit 2", d / "log");
  EXPECT_EQ(rows(out).at("s1")[2], "failed") << readText(d / "log");
  const auto failure = nlohmann::json::parse(readText(out / "sweep.json"))["runs"][0]["failure"];
  EXPECT_EQ(failure.value("limit", ""), "stopped by the sweep: its wall-clock limit of 2 s passed") << failure.dump(2);
  EXPECT_EQ(failure.value("signal", -1) == 0 ? failure.value("exit_code", 0) : 128 + failure.value("signal", 0),
            128 + SIGTERM)
      << failure.dump(2);
  EXPECT_NE(readText(d / "log").find("passed its wall-clock limit of 2 s"), std::string::npos) << readText(d / "log");
}

TEST(Sweep, ARecordChangedAfterMsbenchWroteItIsNotCounted) {
  // metrics.json carries record_digest over itself and coverage.csv: a figure changed afterwards
  // (by hand, by a script, by a method's hook) makes the run a failed one in report and regress.
  const fs::path d = msb_test::tempDir("msb_sweep_", "sealed");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 3\n");
  const fs::path out = d / "out";
  ASSERT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log"), 0) << readText(d / "log");
  // runs.csv carries the verified figures beside the paper's A.
  const std::string csv = readText(out / "runs.csv");
  EXPECT_NE(csv.find(",exit_code,signal,verified_area_m2,verified_box_share,score_earned_m3\n"), std::string::npos)
      << csv;
  auto m = nlohmann::json::parse(readText(out / "runs" / "s1" / "metrics.json"));
  ASSERT_TRUE(m.contains("record_digest"));
  m["coverage"]["area_m2"] = 7777.0;
  std::ofstream(out / "runs" / "s1" / "metrics.json") << m.dump(2) << "\n";
  std::ofstream(out / "runs" / "s2" / "coverage.csv", std::ios::app) << "2.0,9999,9999,9999,9999,9999,9999\n";
  ASSERT_EQ(run("report '" + out.string() + "' --no-figures", d / "log_report"), 0) << readText(d / "log_report");
  const std::string report = readText(out / "report" / "report.md");
  const size_t failed_at = report.find("## Failed runs");
  ASSERT_NE(failed_at, std::string::npos) << report;
  for (const char* id : {"| s1 |", "| s2 |"}) EXPECT_NE(report.find(id, failed_at), std::string::npos) << report;
  EXPECT_NE(report.find("changed after msbench wrote them"), std::string::npos) << report;
  EXPECT_EQ(report.find("7777"), std::string::npos) << report;
}

TEST(Sweep, ASecondSweepIntoTheSameDirectoryIsRefusedNamingTheFirst) {
  // Two sweeps writing one index would mark each other's runs failed: the second is refused
  // (exit 2, the holder's pid) and the first completes as if alone.
  const fs::path d = msb_test::tempDir("msb_sweep_", "two");
  const fs::path f = writeSweep(d, "set: {duration_s: 6}\nseeds: 1\n");
  const fs::path out = d / "out";
  const int first = startSweepInItsOwnGroup(f, out, d / "log1");
  ASSERT_NE(first, 0);
  for (int i = 0; i < 600 && !fs::exists(out / "logs" / "s1.log"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log2"), 2) << readText(d / "log2");
  EXPECT_NE(readText(d / "log2").find("another msbench process (pid " + std::to_string(first) + ")"), std::string::npos)
      << readText(d / "log2");
  for (int i = 0; i < 1200 && readText(d / "log1").find("runs complete") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(rows(out).at("s1")[2], "complete") << readText(d / "log1");
  EXPECT_FALSE(fs::exists(d / "out.lock"));
}

TEST(Sweep, ARunThatRecordedAnErrorIsRedoneOnResume) {
  // msbench run writes metrics.json with status "error" when a run fails with a caught error
  // (and exits 1); a resumed sweep must redo that run, not count it complete.
  const fs::path d = msb_test::tempDir("msb_sweep_", "error");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 2\n");
  const fs::path out = d / "out";
  ASSERT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log1"), 0) << readText(d / "log1");
  const std::string hash = rows(out).at("s2")[8];
  std::ofstream(out / "runs" / "s2" / "metrics.json") << R"({"status": "error", "error": "as a failed run writes it"})";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log2"), 0) << readText(d / "log2");
  EXPECT_NE(readText(d / "log2").find("1 complete, 1 to run"), std::string::npos) << readText(d / "log2");
  EXPECT_EQ(rows(out).at("s2")[8], hash);
}

TEST(Sweep, UnknownKeysInAVariantRefuseTheWholeSweepBeforeAnyRun) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "unknown");
  const fs::path f = writeSweep(d, "axes: [{name: v, variants: {x: {method.switches.warp: true}}}]\n");
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + (d / "out").string() + "'", d / "log"), 2);
  const std::string log = readText(d / "log");
  EXPECT_NE(log.find(f.string()), std::string::npos) << log;
  EXPECT_NE(log.find("warp"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(d / "out"));
}

TEST(Sweep, AKilledSweepResumesToTheSameResults) {
  const fs::path d = msb_test::tempDir("msb_sweep_", "kill");
  const fs::path f = writeSweep(d, "set: {duration_s: 3}\nseeds: 3\n");
  // Uninterrupted reference.
  ASSERT_EQ(run("sweep '" + f.string() + "' --out '" + (d / "ref").string() + "'", d / "log_ref"), 0);
  // Killed (SIGKILL to the sweep and its run) once the first run is complete, then resumed.
  const fs::path out = d / "out";
  const int pid = startSweepInItsOwnGroup(f, out, d / "log_kill");
  ASSERT_GT(pid, 0);
  for (int i = 0; i < 600 && !fs::exists(out / "runs" / "s1" / "metrics.json"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_TRUE(fs::exists(out / "runs" / "s1" / "metrics.json"));
  kill(-pid, SIGKILL);  // the whole process group: the sweep and its running run
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log_resume"), 0)
      << readText(d / "log_resume");
  const auto a = rows(d / "ref"), b = rows(out);
  ASSERT_EQ(a.size(), 3u);
  for (const auto& [id, row] : a) EXPECT_EQ(b.at(id)[8], row[8]) << id;  // determinism hash
}

TEST(Sweep, TaskIndexRunsOneRunAndAPlainCallWritesTheIndex) {
  // As Slurm array tasks would: each task runs its own run into the shared layout, without an
  // index; a plain call afterwards skips them all and writes sweep.json and runs.csv.
  const fs::path d = msb_test::tempDir("msb_sweep_", "task");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 2\n");
  const fs::path out = d / "out";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --task-index 1", d / "log1"), 0)
      << readText(d / "log1");
  EXPECT_TRUE(fs::exists(out / "runs" / "s2" / "metrics.json"));
  EXPECT_FALSE(fs::exists(out / "runs" / "s1"));
  EXPECT_FALSE(fs::exists(out / "sweep.json"));
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --task-index 2", d / "log2"), 2);
  EXPECT_EQ(std::system(("SLURM_ARRAY_TASK_ID=0 '" + msb_test::kExe + "' sweep '" + f.string() + "' --out '" +
                         out.string() + "' > '" + (d / "log3").string() + "' 2>&1")
                            .c_str()),
            0);
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "'", d / "log4"), 0);
  EXPECT_NE(readText(d / "log4").find("2 complete, 0 to run"), std::string::npos) << readText(d / "log4");
  const auto r = rows(out);
  EXPECT_EQ(r.at("s1")[2], "complete");
  EXPECT_EQ(r.at("s2")[2], "complete");
  // The job-array script names the array size and the task index.
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --emit-slurm", d / "log5"), 0);
  EXPECT_NE(readText(d / "log5").find("#SBATCH --array=0-1"), std::string::npos) << readText(d / "log5");
  EXPECT_NE(readText(d / "log5").find("--task-index \"$SLURM_ARRAY_TASK_ID\""), std::string::npos);
}

TEST(Sweep, EmitSlurmPreparesTheDirectoryTheTasksWriteInto) {
  // Slurm writes each task's log into --out/slurm before the task starts: the directory is marked
  // as this sweep's when the script is made, so the first task finds a sweep directory.
  const fs::path d = msb_test::tempDir("msb_sweep_", "slurmdir");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 1\n");
  const fs::path out = d / "out";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --emit-slurm", d / "script"), 0);
  EXPECT_NE(readText(d / "script").find("#SBATCH --output=" + out.string() + "/slurm/slurm-%A_%a.out"),
            std::string::npos)
      << readText(d / "script");
  ASSERT_TRUE(fs::is_directory(out / "slurm"));
  std::ofstream(out / "slurm" / "slurm-7_0.out") << "task log\n";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + out.string() + "' --task-index 0", d / "log"), 0)
      << readText(d / "log");
  // A user's directory is refused by --emit-slurm as by the sweep itself, and left as it was.
  const fs::path user = d / "mine";
  fs::create_directories(user);
  std::ofstream(user / "notes.txt") << "mine\n";
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + user.string() + "' --emit-slurm", d / "log2"), 2);
  EXPECT_FALSE(fs::exists(user / "slurm"));
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

TEST(SweepDirectory, AUserDirectoryIsNeverWrittenIntoAndTheSweepFileIsNeverTheIndex) {
  // Before: a directory that merely had a runs/ folder got its runs.csv and logs replaced, and
  // --task-index wrote logs into any directory.
  const fs::path d = msb_test::tempDir("msb_sweep_", "userdir");
  const fs::path f = writeSweep(d, "set: {duration_s: 2}\nseeds: 1\n");
  const fs::path user = d / "mine";
  fs::create_directories(user / "runs");
  std::ofstream(user / "runs.csv") << "my data\n";
  for (const std::string extra : {"", " --task-index 0"}) {
    EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + user.string() + "'" + extra, d / "log"), 2) << extra;
    EXPECT_NE(readText(d / "log").find("is not a sweep directory msbench wrote"), std::string::npos)
        << readText(d / "log");
    EXPECT_EQ(readText(user / "runs.csv"), "my data\n");
    EXPECT_FALSE(fs::exists(user / "logs"));
  }
  // A sweep file named sweep.json inside --out would be replaced by the index: refused.
  const fs::path own = d / "own";
  fs::create_directories(own);
  fs::copy_file(f, own / "sweep.json");
  for (const std::string extra : {"", " --accept-changes"}) {
    EXPECT_EQ(run("sweep '" + (own / "sweep.json").string() + "' --out '" + own.string() + "'" + extra, d / "log"), 2);
    EXPECT_NE(readText(d / "log").find("overlaps the input SWEEP"), std::string::npos) << readText(d / "log");
    EXPECT_EQ(readText(own / "sweep.json"), readText(f));
  }
  // An empty directory is fine, and a sweep's own directory resumes.
  fs::create_directories(d / "empty");
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + (d / "empty").string() + "'", d / "log"), 0)
      << readText(d / "log");
  EXPECT_TRUE(fs::exists(d / "empty" / ".msbench-sweep"));
  EXPECT_EQ(run("sweep '" + f.string() + "' --out '" + (d / "empty").string() + "'", d / "log"), 0);
  EXPECT_NE(readText(d / "log").find("1 complete, 0 to run"), std::string::npos) << readText(d / "log");
}

TEST(SweepDirectory, CtrlCStopsTheSweepRecordsTheRunPendingAndStartsNoOther) {
  // Ctrl-C signals the whole process group. Before, the stopped run was recorded failed and the
  // next run started.
  const fs::path d = msb_test::tempDir("msb_sweep_", "ctrlc");
  const fs::path f = writeSweep(d, "set: {duration_s: 12}\nseeds: 3\n");
  const fs::path out = d / "out";
  const int pid = startSweepInItsOwnGroup(f, out, d / "log");
  ASSERT_GT(pid, 0);
  for (int i = 0; i < 1200 && readText(out / "logs" / "s1.log").find(": t = 10 / 12 s") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  kill(-pid, SIGINT);  // what the terminal sends
  for (int i = 0; i < 600 && kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto r = rows(out);
  ASSERT_EQ(r.size(), 3u) << readText(d / "log");
  EXPECT_EQ(r.at("s1")[2], "pending") << readText(d / "log");
  EXPECT_EQ(r.at("s2")[2], "pending");
  EXPECT_FALSE(fs::exists(out / "logs" / "s2.log"));  // never started
  EXPECT_EQ(readText(d / "log").find("failed ("), std::string::npos) << readText(d / "log");
}

// Every shipped sweep file expands, and every one of its runs' scenarios loads with its --set
// values (the sweep command checks this before it starts; a sweep that cannot start is a defect
// only a run would find: the conditions sweep once could not).
TEST(Sweep, EveryShippedSweepLoadsEveryRun) {
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(MSB_SOURCE_DIR) / "scenarios/sweeps")) {
    if (e.path().extension() != ".yaml") continue;
    ++files;
    const SweepPlan plan = loadSweepPlan(e.path().string());
    EXPECT_FALSE(plan.runs.empty()) << e.path();
    for (const SweepRun& r : plan.runs) {
      std::vector<std::string> sets;
      for (const auto& [k, v] : r.sets) sets.push_back(k + "=" + v);
      EXPECT_NO_THROW(loadScenario(r.scenario, sets)) << e.path() << " run " << r.id;
    }
  }
  EXPECT_GE(files, 8);
}

}  // namespace
}  // namespace msb
