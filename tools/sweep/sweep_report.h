// The report of a sweep directory (docs/sweeps.md, "Reports"): runs grouped by their axis labels
// (all but the seed) into rows of the paper's Table I layout — runs, mean and max A, crashes,
// the paper's figures where the row exists — plus box share, time to 50 % and 90 % of the box,
// A per 100 m flown, the longest time without coverage gain, collisions by object kind and the
// mean real-time factor. Markdown and CSV are written here; the figures by a Python script.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/eval/coverage_sample.h"

namespace msb {

/// One run of a sweep as the report sees it.
struct ReportRun {
  std::string id;
  std::map<std::string, std::string> labels;  ///< axis name -> label
  uint64_t seed = 0;
  std::string status;                         ///< the sweep's: complete | failed | pending
  nlohmann::json metrics;                     ///< metrics.json (complete runs)
  nlohmann::json failure;                     ///< sweep.json's failure record (failed runs)
  std::vector<CoverageSample> coverage;       ///< coverage.csv (complete runs)
};

/// A sweep directory read back: its axes and runs in run order.
struct SweepResults {
  std::filesystem::path dir;
  std::vector<std::string> axes;
  std::vector<ReportRun> runs;
};

/// A mean over the runs where a quantity exists, and how many runs that is.
struct MeanOf {
  double mean = 0.0;
  int count = 0;  ///< runs that contributed (0: no value)
};

/// One row of the table: the runs sharing all axis labels.
struct ReportRow {
  std::vector<std::string> labels;  ///< one per axis, in axis order
  std::string world, method;        ///< from the runs' metrics (method incl. switched-off switches)
  int runs = 0, complete = 0, failed = 0, crashes = 0;  ///< crashes: runs that collided
  MeanOf area_m2, box_share, t50_s, t90_s, area_per_100m, longest_no_gain_s, rtf;
  double max_area_m2 = 0.0;
  std::map<std::string, int> collisions_by_kind;  ///< textured / textureless / thin / ground / unknown
  std::optional<double> paper_mean_m2, paper_max_m2;
};

/// The paper's Table I mean and max A for a world and a method with its switches (monospheres
/// with one of ovde/dbof/fff/vpb off = the ablation rows; grid_random = Grid-Based).
std::optional<std::pair<double, double>> paperTableOne(const std::string& world, const std::string& method,
                                                       const nlohmann::json& switches);

/// The method as the report names it: the type, plus the switches that are off
/// ("monospheres -ovde").
std::string reportMethodName(const nlohmann::json& metrics);

/// Reads DIR/sweep.json and every complete run's metrics.json and coverage.csv. Throws
/// std::runtime_error naming the file when the directory is not a sweep directory.
SweepResults loadSweepResults(const std::filesystem::path& dir);

/// First time the box share reached `share` (nullopt: never).
std::optional<double> timeToBoxShare(const std::vector<CoverageSample>& coverage, double share);

/// The table rows, in the order their first run appears.
std::vector<ReportRow> reportRows(const SweepResults& results);

/// report.md text: the table and one line per failed run.
std::string reportMarkdown(const SweepResults& results, const std::vector<ReportRow>& rows);

/// table.csv text: one line per row, plain numbers (empty = no value).
std::string reportTableCsv(const SweepResults& results, const std::vector<ReportRow>& rows);

/// runs.csv-like text for the figure script: run id, row key, status, run directory.
std::string reportRunsCsv(const SweepResults& results);

}  // namespace msb
