// The paper's qualitative findings as checks on a sweep's report (docs/sweeps.md, "Findings" and
// "Intervals and verdicts"): one table of claims — which rows are compared, how, against which
// threshold — evaluated to a three-way verdict: holds (the 95 % interval lies on the paper's side
// of the threshold), fails (on the other side), undecided (it straddles; with the seeds per row
// that would decide it at the observed spread), or "n/a" when the sweep lacks the rows. Counts
// of events are rates with Wilson intervals, compared with the paper's count by Fisher's exact
// test. The paper's figures come from the method registry (one source). A new finding is one entry
// of findingsTable().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tools/sweep/sweep_report.h"

namespace msb {

/// How a finding compares rows (a row is a world and a method name as the report names it:
/// "monospheres", "monospheres -ovde", "grid_random").
enum class FindingCheck {
  kRatioAtLeast,  ///< mean A of `methods[0]` / mean A of `methods[1]` >= threshold, in `world`
  kRatioAtMost,   ///< the same ratio <= threshold
  kOrder,  ///< mean A decreasing along `methods`; `relations[i]` between i and i+1: ">" (greater) or "≈" (within
           ///< `threshold` of each other, relative)
  kNoCollisions,    ///< no run of `methods` in `world` collided
  kCollisionKinds,  ///< every collision in `world` (all methods) was on a textureless or thin object
  kCollisionsLate,  ///< every collision of `methods` in `world` came at a box share >= threshold
};

/// One claim of the paper.
struct Finding {
  const char* id;     ///< short key (findings.csv)
  const char* claim;  ///< the claim in words
  FindingCheck check;
  const char* world;
  std::vector<std::string> methods;
  std::vector<std::string> relations;  ///< kOrder only
  double threshold;
  const char* paper_note;  ///< the paper's words where its figures are not numbers of Table I ("" none)
};

/// The findings of the MonoSpheres paper (seed 001, §V-B and Table I).
const std::vector<Finding>& findingsTable();

/// A finding evaluated on a sweep.
struct FindingResult {
  const Finding* finding = nullptr;
  std::string status;                       ///< "holds", "fails", "undecided" or "n/a" (rows missing)
  std::string measured;                     ///< the numbers behind the verdict, intervals included
  std::string paper;                        ///< the paper's figures for it (from the method registry) and its words
  std::optional<stats::Estimate> estimate;  ///< the ratio, or the rate of events, with its interval
  std::optional<double> p_value;            ///< Fisher's exact test against the paper's count
  std::optional<int> seeds_to_decide;       ///< undecided ratios: seeds per row that would decide
  int runs = 0;                             ///< runs behind the verdict
  std::string note;                         ///< pairing, saturation
  /// The same finding on verified A instead of the paper's (area findings of sweeps whose runs
  /// carry verified coverage; empty otherwise): its verdict and numbers.
  std::string verified_status, verified_measured;
};

/// Evaluates every finding of `table` on the sweep's rows and runs; the area findings also on
/// verified A when every run of the rows has it.
std::vector<FindingResult> evaluateFindings(const SweepResults& results, const std::vector<ReportRow>& rows,
                                            const std::vector<Finding>& table = findingsTable());

/// How many findings hold, fail, are undecided, and could not be evaluated.
struct FindingCounts {
  int holds = 0, fails = 0, undecided = 0, not_evaluated = 0;
};

/// The verdicts of `findings` counted.
FindingCounts countFindings(const std::vector<FindingResult>& findings);

/// The "Findings" section of report.md.
std::string findingsMarkdown(const std::vector<FindingResult>& findings);

/// findings.csv text: id, claim, verdict, measured, estimate, ci_lo, ci_hi, n, threshold, p_value,
/// seeds_to_decide, paper, note (and verified_verdict, verified_measured when evaluated).
std::string findingsCsv(const std::vector<FindingResult>& findings);

}  // namespace msb
