// Ablations across levels of a condition (docs/sweeps.md, "Ablations across levels"): a sweep
// with a `method` axis and one more axis (the level: a front-end degradation preset, a drift
// scale, a conditions preset ...) compares, in every world and at every level, each method's
// mean area with the first method's (the full method) on the same seeds, and states for each
// the lowest level at which the ratio's 95 % interval lies below 1 — or that none does.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tools/sweep/statistics.h"
#include "tools/sweep/sweep_report.h"

namespace msb {

/// One method against the full method at one level of one world.
struct LevelCell {
  std::string world, level, method;  ///< method as the report names it
  int level_index = 0;               ///< position of the level on its axis
  stats::Estimate ratio;             ///< mean A / the full method's mean A
  int pairs = 0;                     ///< common seeds (0: compared independently)
};

/// The comparisons of a level sweep.
struct LevelSweep {
  std::string axis;                 ///< the level axis' name
  std::vector<std::string> levels;  ///< its labels in sweep order
  std::string reference_method;     ///< the full method (first method label)
  std::vector<LevelCell> cells;     ///< world by world, method by method, level by level
};

/// The level sweep of a report, if the sweep has a `method` axis and exactly one axis besides it
/// and `world`; cells only where both rows have an area.
std::optional<LevelSweep> levelSweep(const SweepResults& results, const std::vector<ReportRow>& rows);

/// The rows of one level (by its index in `s.levels`).
std::vector<ReportRow> rowsAtLevel(const SweepResults& results, const std::vector<ReportRow>& rows, const LevelSweep& s,
                                   size_t level);

/// The report's section: a table of ratios per level and one statement per method and world.
std::string levelSweepMarkdown(const LevelSweep& s);

/// ablation_levels.csv for the figure script: world, level_index, level, method, ratio, lo, hi, pairs.
std::string levelSweepCsv(const LevelSweep& s);

}  // namespace msb
