// Coverage regression against stored results (docs/regression.md). A golden file records, per
// run of a sweep, its status, A and determinism hash, and the machine fingerprint they came from.
// A sweep on the same machine (same fingerprint id) must match exactly: status, A and hash. A run
// from another machine whose hash equals the golden's is the same run, compared exactly too. Only
// a run from another machine with another hash (floating point differs with CPU features and
// libraries, and closed-loop runs diverge) is checked in band mode: status and A within a band.
// A run or golden entry without a hash or machine id is an error unless band mode is asked for:
// the mode never changes silently.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/sweep/sweep_report.h"

namespace msb {

/// The band for runs from another machine: |A - A_golden| <= max(relative * A_golden, absolute_m2).
struct RegressionTolerance {
  double relative = 0.25;
  double absolute_m2 = 100.0;
  bool band_only = false;  ///< compare every run in band mode (regress --band)
};

/// The value of "kind" in a golden file msbench wrote.
inline constexpr char kGoldenKind[] = "msbench-golden";

/// Reads and checks a golden file: a JSON object whose runs each have id, status, area_m2,
/// determinism_hash and machine_id of the right types. Throws FileConfigError naming the file
/// and the key.
nlohmann::json readGolden(const std::filesystem::path& file);

/// True if `file` holds a golden msbench wrote (its kind, or the keys of one written before the
/// kind existed): the only file regress --update replaces.
bool isGoldenFile(const std::filesystem::path& file);

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
