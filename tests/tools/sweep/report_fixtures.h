// Hand-built report inputs shared by the report tests: a complete run with the fields the report
// reads, and a run's metrics.json rewritten with its digest recomputed.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"
#include "tools/results/run_record.h"
#include "tools/sweep/sweep_report.h"

namespace msb {

namespace fs = std::filesystem;
using msb_test::readText;

// A complete run with the fields the report reads.
inline ReportRun madeRun(const std::string& id, const std::string& world, const std::string& variant, double area,
                         const std::string& status, const std::string& kind = "") {
  ReportRun r;
  r.id = id;
  r.labels = {{"world", world}, {"method", variant}};
  r.status = "complete";
  r.metrics = {{"world", world},
               {"method", "monospheres"},
               {"switches", {{"ovde", variant != "no_ovde"}, {"fff", true}}},
               {"status", status},
               {"distance_flown_m", 200.0},
               {"real_time_factor", 2.0},
               {"sim_time_s", 100.0},
               {"duration_s", 1200.0},
               {"determinism_hash", "0123456789abcdef"},
               {"coverage", {{"area_m2", area}, {"box_share", area / 1000.0}, {"longest_no_gain_s", 30.0}}}};
  if (!kind.empty()) r.metrics["collision"] = {{"world_geom", "g"}, {"object", "bus_0"}, {"kind", kind}};
  r.record = missionRecordOf(r.metrics, id + "/metrics.json").record;
  for (int t = 0; t <= 10; ++t) {
    CoverageSample c;
    c.t_s = 10.0 * t;
    c.area_m2 = area * t / 10.0;
    c.box_share = area / 1000.0 * t / 10.0;
    r.coverage.push_back(c);
  }
  return r;
}

// Rewrites one run's metrics.json with a change, sealed again as msbench would have written it
// (these tests are about what regress and report do with such a record, not about the seal:
// Sweep.ARecordChangedAfterMsbenchWroteItIsNotCounted).
inline void editMetrics(const fs::path& run_dir, const std::function<void(nlohmann::json&)>& edit) {
  auto m = nlohmann::json::parse(readText(run_dir / "metrics.json"));
  edit(m);
  if (m.contains("record_digest")) m["record_digest"] = recordDigest(m, readText(run_dir / "coverage.csv"));
  std::ofstream(run_dir / "metrics.json") << m.dump(2);
}

}  // namespace msb
