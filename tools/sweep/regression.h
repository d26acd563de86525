// Coverage regression against stored results (docs/regression.md). A golden file records, per
// run of a sweep, its status, A and determinism hash, and the machine fingerprint they came from.
// A sweep on the same machine (same fingerprint id) must match exactly: status, A and hash. On
// another machine, floating point differs (CPU features, libraries) and closed-loop runs diverge,
// so only the status and A within a tolerance band are checked.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/sweep/sweep_report.h"

namespace msb {

/// The band for runs from another machine: |A - A_golden| <= max(relative * A_golden, absolute_m2).
struct RegressionTolerance {
  double relative = 0.25;
  double absolute_m2 = 100.0;
};

/// The outcome of comparing a sweep with a golden file.
struct RegressionOutcome {
  int compared = 0, exact = 0, banded = 0;  ///< runs compared, of them exactly / in band mode
  std::vector<std::string> regressions;     ///< one line per regression (empty = pass)
  std::vector<std::string> notes;           ///< runs not in the golden, etc. (not failures)
};

/// The golden file content of a sweep: every run must be complete (throws std::runtime_error
/// naming the runs that are not).
nlohmann::json goldenFromSweep(const SweepResults& results, const RegressionTolerance& tolerance);

/// Compares a sweep with a golden (content of golden.json).
RegressionOutcome compareWithGolden(const SweepResults& results, const nlohmann::json& golden,
                                    const RegressionTolerance& tolerance);

/// The tolerance stored in a golden file (defaults where absent).
RegressionTolerance toleranceOf(const nlohmann::json& golden);

}  // namespace msb
