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
