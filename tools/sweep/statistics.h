// The statistics of a sweep report (docs/sweeps.md, "Intervals and verdicts"): percentile
// bootstrap intervals of a mean and of a ratio of means over a row's seeds (rows resampled
// independently, or as pairs on common seeds), Wilson intervals of a rate, Fisher's exact test of
// two rates, and the three-way verdict of a finding. Every resampling draws from one generator
// seeded with a fixed seed, so a report is the same whenever it is written.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace msb::stats {

/// The resampling seed of every interval of a report (fixed: the report is deterministic).
inline constexpr uint64_t kResampleSeed = 0x6d736265'6e636831ULL;  // "msbench1"
/// Bootstrap draws per interval.
inline constexpr int kDraws = 20000;
/// Confidence level of every interval.
inline constexpr double kLevel = 0.95;

/// A closed interval.
struct Interval {
  double lo = 0.0, hi = 0.0;
};

/// A point estimate with its interval and the number of values behind it (per row for ratios:
/// the smaller of the two).
struct Estimate {
  double value = 0.0;
  Interval ci;
  int n = 0;
};

/// Resampling settings of one estimate.
struct Resampling {
  uint64_t seed = kResampleSeed;
  int draws = kDraws;
  double level = kLevel;
};

/// The arithmetic mean (0 for no values).
double mean(const std::vector<double>& x);

/// The q-quantile (0 <= q <= 1) of `sorted` (ascending, not empty), linearly interpolated
/// between order statistics (type 7 of Hyndman & Fan, numpy's and R's default).
double quantileSorted(const std::vector<double>& sorted, double q);

/// The mean of `x` with its percentile bootstrap interval. One value: the interval is the value.
/// Throws std::invalid_argument on no values.
Estimate bootstrapMean(const std::vector<double>& x, const Resampling& r = {});

/// mean(a) / mean(b) with a percentile bootstrap interval, `a` and `b` resampled independently
/// (stratified: each row keeps its own number of runs). Throws std::invalid_argument when either
/// is empty or mean(b) is not positive.
Estimate bootstrapRatio(const std::vector<double>& a, const std::vector<double>& b, const Resampling& r = {});

/// mean(a) / mean(b) over pairs (a[i], b[i]) from common seeds, the pairs resampled together.
/// Throws std::invalid_argument when the sizes differ, no pair is given or mean(b) <= 0.
Estimate bootstrapPairedRatio(const std::vector<double>& a, const std::vector<double>& b, const Resampling& r = {});

/// Pearson's correlation of the pairs (nullopt: fewer than 3 pairs or no spread).
std::optional<double> correlation(const std::vector<double>& a, const std::vector<double>& b);

/// The standard normal quantile of p (0 < p < 1).
double normalQuantile(double p);

/// Wilson's score interval of a rate of k events in n trials (n = 0: [0, 1]).
Interval wilson(int k, int n, double level = kLevel);

/// Two-sided p-value of Fisher's exact test of k1 of n1 against k2 of n2: the probability,
/// with both margins fixed, of a table no more likely than the one observed.
double fisherExact(int k1, int n1, int k2, int n2);

/// The three verdicts of a finding.
enum class Verdict {
  kHolds,      ///< the interval lies on the paper's side of the threshold
  kFails,      ///< it lies on the other side
  kUndecided,  ///< it straddles the threshold
};

/// The word of a verdict in files: "holds", "fails", "undecided".
const char* verdictName(Verdict v);

/// Which side of the threshold the paper's claim is.
enum class Side { kAtLeast, kAtMost };

/// The verdict of a claim "value >= threshold" (kAtLeast) or "value <= threshold" (kAtMost).
Verdict verdictOf(const Interval& ci, double threshold, Side side);

/// Seeds per row that would decide an undecided comparison at the observed spread: the
/// interval's half-width on the threshold's side shrinks as sqrt(1/n_a + 1/n_b) (one row: n_b
/// = 0), and the estimate stays. nullopt when the estimate sits on the threshold.
std::optional<int> seedsToDecide(const Estimate& e, double threshold, int n_a, int n_b);

}  // namespace msb::stats
