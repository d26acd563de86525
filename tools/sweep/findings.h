// The paper's qualitative findings as checks on a sweep's report (docs/sweeps.md, "Findings"):
// one table of claims — which rows are compared, how, against which threshold, and the paper's
// own figures — evaluated to ✓ / ✗ (or "n/a" when the sweep lacks the rows) with the numbers
// behind each. A new finding is one entry of findingsTable().
#pragma once

#include <string>
#include <vector>

#include "tools/sweep/sweep_report.h"

namespace msb {

/// How a finding compares rows (a row is a world and a method name as the report names it:
/// "monospheres", "monospheres -ovde", "grid_random").
enum class FindingCheck {
  kRatioAtLeast,    ///< mean A of `methods[0]` / mean A of `methods[1]` >= threshold, in `world`
  kRatioAtMost,     ///< the same ratio <= threshold
  kOrder,           ///< mean A decreasing along `methods`; `relations[i]` between i and i+1: ">" (greater) or "≈" (within `threshold` of each other, relative)
  kNoCollisions,    ///< no run of `methods` in `world` collided
  kCollisionKinds,  ///< every collision in `world` (all methods) was on a textureless or thin object
  kCollisionsLate,  ///< every collision of `methods` in `world` came at a box share >= threshold
};

/// One claim of the paper.
struct Finding {
  const char* id;                    ///< short key (findings.csv)
  const char* claim;                 ///< the claim in words
  FindingCheck check;
  const char* world;
  std::vector<std::string> methods;
  std::vector<std::string> relations;  ///< kOrder only
  double threshold;
  const char* paper;                 ///< the paper's own figures for it
};

/// The findings of the MonoSpheres paper (seed 001, §V-B and Table I).
const std::vector<Finding>& findingsTable();

/// A finding evaluated on a sweep.
struct FindingResult {
  const Finding* finding = nullptr;
  std::string status;   ///< "pass", "fail" or "n/a" (rows missing)
  std::string measured; ///< the numbers behind the verdict
};

/// Evaluates every finding of `table` on the sweep's rows and runs.
std::vector<FindingResult> evaluateFindings(const SweepResults& results, const std::vector<ReportRow>& rows,
                                            const std::vector<Finding>& table = findingsTable());

/// The "Findings" section of report.md.
std::string findingsMarkdown(const std::vector<FindingResult>& findings);

/// findings.csv text: id, claim, status, measured, threshold, paper.
std::string findingsCsv(const std::vector<FindingResult>& findings);

}  // namespace msb
