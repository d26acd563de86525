// Seeded mutation fuzzing of the JSON readers (tests/tools/fuzz_helpers.h): a run's metrics.json,
// a golden file and a sweep index. Every mutation is read or refused with an error naming the file;
// nothing else (a raw JSON exception, a crash) may escape.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/tools/fuzz_helpers.h"
#include "tools/results/run_record.h"
#include "tools/sweep/regression.h"
#include "tools/sweep/sweep_report.h"

namespace msb {
namespace {

using namespace fuzz_test;

// A documented refusal: the reader's error, rethrown as the file error it is (it names the file).
[[noreturn]] void refuse(const std::string& file, const std::string& message) {
  if (message.rfind(file, 0) != 0) ADD_FAILURE() << "the error does not name the file: " << message;
  throw FileConfigError(message);
}

const char* const kMetrics =
    R"({"status": "collided", "world": "urban", "method": "monospheres", "seed": 3, "sim_time_s": 120.5,)"
    R"( "determinism_hash": "0123456789abcdef", "machine": {"id": "1261a40036056aeb"},)"
    R"( "coverage": {"area_m2": 1862.5, "box_share": 0.42, "longest_no_gain_s": 30},)"
    R"( "collision": {"object": "bus_0", "kind": "textureless", "t_s": 120.5}})";

TEST(JsonFuzz, MetricsFiles) {
  const fs::path d = dir("metrics");
  fuzz(kMetrics, d / "metrics.json", 2000, "fuzz_metrics", [](const std::string& p) {
    const MissionRecordRead read = readMissionRecord(p);
    if (!read.record) refuse(p, read.problem);
  });
}

TEST(JsonFuzz, GoldenFiles) {
  const fs::path d = dir("golden");
  const std::string golden =
      R"({"kind": "msbench-golden", "machine": {"id": "m"}, "tolerance": {"relative": 0.25, "absolute_m2": 100},)"
      R"( "runs": [{"id": "urban-grid-s1", "status": "completed", "area_m2": 856.25, "sim_time_s": 60,)"
      R"( "determinism_hash": "a7eab0cdee45814a", "machine_id": "m"}]})";
  fuzz(golden, d / "golden.json", 1000, "fuzz_golden", [](const std::string& p) { readGolden(p); });
}

TEST(JsonFuzz, SweepIndexes) {
  const fs::path d = dir("sweep");
  fs::create_directories(d / "runs" / "a-s1");
  std::ofstream(d / "runs" / "a-s1" / "metrics.json") << kMetrics;
  const std::string index =
      R"({"axes": ["a"], "sweep_file_hash": "x", "build": "b", "runs": [{"id": "a-s1", "seed": 1,)"
      R"( "status": "complete", "labels": {"a": "a"}}, {"id": "a-s2", "seed": 2, "status": "failed",)"
      R"( "labels": {"a": "a"}, "failure": {"exit_code": 1}}]})";
  fuzz(index, d / "sweep.json", 1000, "fuzz_sweep_index", [&d](const std::string& p) {
    try {
      const SweepResults r = loadSweepResults(d);
      (void)reportMarkdown(r, reportRows(r));  // the report of whatever was read
    } catch (const std::runtime_error& e) {
      refuse(p, e.what());
    }
  });
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

// The message a golden file's reader refuses `text` with.
std::string goldenRefusal(const std::string& text) {
  const fs::path p = fuzz_test::dir("golden_ranges") / "golden.json";
  std::ofstream(p) << text;
  try {
    readGolden(p);
  } catch (const FileConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonRanges, AGoldensToleranceAreaAndHashAreRangeChecked) {
  // Before: a tolerance of 1e300 hid a 10x change, a negative one was accepted, and so was a
  // 15-digit hash.
  auto golden = [](const std::string& tolerance, const std::string& area, const std::string& hash) {
    return R"({"kind": "msbench-golden", "machine": {"id": "m"}, "tolerance": )" + tolerance +
           R"(, "runs": [{"id": "r", "status": "completed", "area_m2": )" + area +
           R"(, "sim_time_s": 60, "determinism_hash": ")" + hash + R"(", "machine_id": "m"}]})";
  };
  const std::string ok_tol = R"({"relative": 0.25, "absolute_m2": 100})";
  EXPECT_EQ(goldenRefusal(golden(ok_tol, "856", "a7eab0cdee45814a")), "");
  EXPECT_NE(goldenRefusal(golden(R"({"relative": 1e300})", "856", "a7eab0cdee45814a")).find("'tolerance.relative'"),
            std::string::npos);
  EXPECT_NE(goldenRefusal(golden(R"({"absolute_m2": -1})", "856", "a7eab0cdee45814a")).find("'tolerance.absolute_m2'"),
            std::string::npos);
  EXPECT_NE(goldenRefusal(golden(ok_tol, "1e300", "a7eab0cdee45814a")).find("'runs[0].area_m2'"), std::string::npos);
  EXPECT_NE(goldenRefusal(golden(ok_tol, "856", "a7eab0cdee45814")).find("16 hexadecimal digits"), std::string::npos);
}

TEST(JsonRanges, AMetricsFileClaimingAnAbsurdAreaOrAKeyTwiceIsRefused) {
  const fs::path p = fuzz_test::dir("metrics_ranges") / "metrics.json";
  std::string text = kMetrics;
  std::ofstream(p) << std::string(text).replace(text.find("1862.5"), 6, "1e300");
  EXPECT_NE(readMissionRecord(p).problem.find("'coverage.area_m2'"), std::string::npos);
  std::ofstream(p) << text.substr(0, text.size() - 1) + R"(, "coverage": {"area_m2": 99999}})";
  EXPECT_NE(readMissionRecord(p).problem.find("key 'coverage' appears twice"), std::string::npos);
  // Every other area and share a report reads is range-checked too (before: a verified area of
  // -5 or 1e300 was averaged as is).
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{{"verified_area_m2", "-5"},
                                                                                   {"verified_area_m2", "1e300"},
                                                                                   {"area_box_m2", "-1"},
                                                                                   {"area_published_rule_m2", "2e7"},
                                                                                   {"verified_box_share", "1.5"},
                                                                                   {"box_share_true_frame", "-0.1"}}) {
    std::string bad = text;
    bad.replace(bad.find("\"longest_no_gain_s\""), 0, "\"" + key + "\": " + value + ", ");
    std::ofstream(p) << bad;
    EXPECT_NE(readMissionRecord(p).problem.find("'coverage." + key + "'"), std::string::npos) << key << " " << value;
  }
  std::string ok = text;
  ok.replace(ok.find("\"longest_no_gain_s\""), 0, R"("verified_area_m2": 1500, "seen_area_m2": null, )");
  std::ofstream(p) << ok;
  EXPECT_TRUE(readMissionRecord(p).record) << readMissionRecord(p).problem;
}

}  // namespace
}  // namespace msb
