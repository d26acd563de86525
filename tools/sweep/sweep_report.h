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
#include "tools/config/method_table.h"
#include "tools/results/run_record.h"
#include "tools/sweep/statistics.h"
#include "tools/sweep/sweep_index.h"

namespace msb {

/// One run of a sweep as the report sees it.
struct ReportRun {
  std::string id;
  std::map<std::string, std::string> labels;  ///< axis name -> label
  uint64_t seed = 0;
  std::string status;                      ///< the sweep's: complete | failed | pending
  std::optional<MissionRecord> record;     ///< metrics.json read strictly (complete runs)
  nlohmann::json metrics;                  ///< metrics.json (complete runs; the record's)
  std::optional<SweepRunFailure> failure;  ///< why it has no result (failed runs)
  std::vector<CoverageSample> coverage;    ///< coverage.csv (complete runs)
  std::string off_suite;                   ///< why a complete run is off the suite (applySuite)
  std::string unranked;                    ///< why a complete run is not ranked (applyRankRules)
};

/// A sweep directory read back: its axes and runs in run order.
struct SweepResults {
  std::filesystem::path dir;
  std::vector<std::string> axes;
  std::vector<ReportRun> runs;
  std::string suite;         ///< the suite the runs were checked against (applySuite), "" for none
  std::string sealed_under;  ///< the evaluator key id the runs were verified under (applySealRules), "" for none
};

/// A mean over the runs where a quantity exists, how many runs that is, and their values (in run
/// order; what the intervals resample).
struct MeanOf {
  double mean = 0.0;
  int count = 0;  ///< runs that contributed (0: no value)
  std::vector<double> values;
};

/// The share of box explored above which a run counts as having filled the box.
inline constexpr double kSaturatedBoxShare = 0.95;

/// One row of the table: the runs sharing all axis labels.
struct ReportRow {
  std::vector<std::string> labels;                      ///< one per axis, in axis order
  std::string world, method;                            ///< from the runs' metrics (method incl. switched-off switches)
  int runs = 0, complete = 0, failed = 0, crashes = 0;  ///< crashes: runs that collided
  int vio_lost = 0;                                     ///< runs ended because the VIO lost track
  int saturated = 0;                                    ///< runs whose box share reached kSaturatedBoxShare
  MeanOf area_m2, box_share, t50_s, t90_s, area_per_100m, longest_no_gain_s, rtf;
  MeanOf fe_median_m[3];                    ///< front-end profile: median SLAM-point error at 0-5, 5-10, 10-20 m
  MeanOf fe_wrong_share, fe_moved_share;    ///< points over 2 m off a surface; tracks that moved > 0.3 m
  MeanOf verified_area_m2, verified_share;  ///< verified A, and verified A / the paper's A (runs that have it)
  MeanOf earned_m3;                         ///< the earned score, score.earned (runs that have it)
  MeanOf falsely_free_volume, falsely_free_elements;  ///< map accuracy over the final map's free elements
  std::vector<uint64_t> area_seeds;                   ///< the seed of each value of area_m2 (pairing across rows)
  double max_area_m2 = 0.0;
  std::map<std::string, int> collisions_by_kind;  ///< textured / textureless / thin / ground / unknown
  std::optional<double> paper_mean_m2, paper_max_m2;
  int paper_runs = 0;         ///< 0: no paper row
  int paper_collisions = -1;  ///< -1: the paper does not say
};

/// Whether most of a row's complete runs filled the exploration box (its area then no longer
/// tells a faster method from a slower one: compare t50 / t90 instead).
bool isSaturated(const ReportRow& row);

/// The paper's Table I row of a world and a method with its switches (monospheres with one of
/// ovde/dbof/fff/vpb off = the ablation rows; grid_random = Grid-Based), or null.
const PaperRow* paperRow(const std::string& world, const std::string& method, const nlohmann::json& switches);

/// The same for a method as the report names it ("monospheres -ovde").
const PaperRow* paperRowNamed(const std::string& world, const std::string& report_method);

/// The paper's mission length: Table I's runs are 20 simulated minutes.
inline constexpr double kPaperDurationS = 1200.0;

/// Whether the sweep is a Table I sweep, recognised exactly (docs/sweeps.md, "Reports"): it has
/// a complete run, every complete run is a run of a Table I row (its world, method type and the
/// one switch it turns off) and flew the paper's 1200 s. Only then does the report print the
/// paper's figures and evaluate the paper's findings.
bool isTableOneSweep(const SweepResults& results);

/// A row's name in comparisons: its labels except the one naming its world (the sweep's variant
/// names), or the method as the report names it when it has no other label.
std::string rowName(const ReportRow& row);

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

/// The mean of `m` with its bootstrap interval over the runs' values (count must be > 0).
stats::Estimate estimateOf(const MeanOf& m);

/// A row's collision rate: Wilson interval of crashes of complete runs.
stats::Interval collisionRate(const ReportRow& row);

/// Two rows' areas on their common seeds, in the first row's run order.
struct PairedAreas {
  std::vector<uint64_t> seeds;
  std::vector<double> a, b;
};

/// The areas of `a` and `b` from runs with the same seed.
PairedAreas pairedAreas(const ReportRow& a, const ReportRow& b);

/// report.md text: the table and one line per failed run.
std::string reportMarkdown(const SweepResults& results, const std::vector<ReportRow>& rows);

/// table.csv text: one line per row, plain numbers (empty = no value).
std::string reportTableCsv(const SweepResults& results, const std::vector<ReportRow>& rows);

/// runs.csv-like text for the figure script: run id, row key, status, run directory.
std::string reportRunsCsv(const SweepResults& results);

}  // namespace msb
