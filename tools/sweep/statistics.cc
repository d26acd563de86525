#include "tools/sweep/statistics.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace msb::stats {

namespace {

// An index in [0, n) from the generator (n is a handful of seeds: the modulo bias is ~n / 2^64).
size_t pick(std::mt19937_64& rng, size_t n) { return static_cast<size_t>(rng() % n); }

// The mean of one resample of x.
double resampledMean(std::mt19937_64& rng, const std::vector<double>& x) {
  double s = 0.0;
  for (size_t k = 0; k < x.size(); ++k) s += x[pick(rng, x.size())];
  return s / static_cast<double>(x.size());
}

// The percentile interval of the bootstrap values (sorted here).
Interval percentile(std::vector<double>& values, double level) {
  std::sort(values.begin(), values.end());
  const double tail = (1.0 - level) / 2.0;
  return {quantileSorted(values, tail), quantileSorted(values, 1.0 - tail)};
}

void checkResampling(const Resampling& r) {
  if (r.draws < 1) throw std::invalid_argument("bootstrap: draws must be at least 1");
  if (!(r.level > 0.0 && r.level < 1.0)) throw std::invalid_argument("bootstrap: level must be in (0, 1)");
}

// log of the binomial coefficient C(n, k).
double logChoose(int n, int k) { return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0); }

}  // namespace

double mean(const std::vector<double>& x) {
  if (x.empty()) return 0.0;
  double s = 0.0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

double quantileSorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) throw std::invalid_argument("quantile of no values");
  const double h = std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

Estimate bootstrapMean(const std::vector<double>& x, const Resampling& r) {
  if (x.empty()) throw std::invalid_argument("bootstrap of no values");
  checkResampling(r);
  Estimate e{mean(x), {}, static_cast<int>(x.size())};
  std::mt19937_64 rng(r.seed);
  std::vector<double> means(static_cast<size_t>(r.draws));
  for (double& m : means) m = resampledMean(rng, x);
  e.ci = percentile(means, r.level);
  return e;
}

Estimate bootstrapRatio(const std::vector<double>& a, const std::vector<double>& b, const Resampling& r) {
  if (a.empty() || b.empty()) throw std::invalid_argument("bootstrap ratio of no values");
  if (!(mean(b) > 0.0)) throw std::invalid_argument("bootstrap ratio: the denominator's mean is not positive");
  checkResampling(r);
  Estimate e{mean(a) / mean(b), {}, static_cast<int>(std::min(a.size(), b.size()))};
  std::mt19937_64 rng(r.seed);
  std::vector<double> ratios;
  ratios.reserve(static_cast<size_t>(r.draws));
  // A resample whose denominator is 0 (all its runs covered nothing) has no ratio: drawn again.
  for (int k = 0, tries = 0; k < r.draws && tries < 100 * r.draws; ++tries) {
    const double ma = resampledMean(rng, a), mb = resampledMean(rng, b);
    if (mb > 0.0) ratios.push_back(ma / mb), ++k;
  }
  e.ci = percentile(ratios, r.level);
  return e;
}

Estimate bootstrapPairedRatio(const std::vector<double>& a, const std::vector<double>& b, const Resampling& r) {
  if (a.size() != b.size()) throw std::invalid_argument("paired bootstrap: the two rows have different sizes");
  if (a.empty()) throw std::invalid_argument("paired bootstrap of no pairs");
  if (!(mean(b) > 0.0)) throw std::invalid_argument("paired bootstrap: the denominator's mean is not positive");
  checkResampling(r);
  Estimate e{mean(a) / mean(b), {}, static_cast<int>(a.size())};
  std::mt19937_64 rng(r.seed);
  std::vector<double> ratios;
  ratios.reserve(static_cast<size_t>(r.draws));
  for (int k = 0, tries = 0; k < r.draws && tries < 100 * r.draws; ++tries) {
    double sa = 0.0, sb = 0.0;
    for (size_t j = 0; j < a.size(); ++j) {
      const size_t i = pick(rng, a.size());
      sa += a[i], sb += b[i];
    }
    if (sb > 0.0) ratios.push_back(sa / sb), ++k;
  }
  e.ci = percentile(ratios, r.level);
  return e;
}

std::optional<double> correlation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.size() < 3) return std::nullopt;
  const double ma = mean(a), mb = mean(b);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (saa <= 0.0 || sbb <= 0.0) return std::nullopt;
  return sab / std::sqrt(saa * sbb);
}

double normalQuantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal quantile: p must be in (0, 1)");
  // Bisection on the normal CDF, 0.5 erfc(-x / sqrt 2): exact to double precision in 200 steps.
  double lo = -40.0, hi = 40.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Interval wilson(int k, int n, double level) {
  if (n <= 0) return {0.0, 1.0};
  if (k < 0 || k > n) throw std::invalid_argument("wilson: k must be in [0, n]");
  const double z = normalQuantile(1.0 - (1.0 - level) / 2.0), z2 = z * z;
  const double p = static_cast<double>(k) / n, nn = static_cast<double>(n);
  const double centre = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z / (1.0 + z2 / nn) * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  // At k = 0 and k = n the bounds are exactly 0 and 1 (the formula's rounding aside).
  return {k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

double fisherExact(int k1, int n1, int k2, int n2) {
  if (n1 < 0 || n2 < 0 || k1 < 0 || k2 < 0 || k1 > n1 || k2 > n2)
    throw std::invalid_argument("fisher: counts must satisfy 0 <= k <= n");
  const int total = n1 + n2, events = k1 + k2;
  if (total == 0) return 1.0;
  // The hypergeometric law of the first row's events with both margins fixed.
  auto logP = [&](int x) { return logChoose(events, x) + logChoose(total - events, n1 - x) - logChoose(total, n1); };
  const double observed = logP(k1);
  double p = 0.0;
  for (int x = std::max(0, n1 - (total - events)); x <= std::min(events, n1); ++x)
    if (logP(x) <= observed + 1e-7) p += std::exp(logP(x));  // R's relative tolerance
  return std::min(1.0, p);
}

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::kHolds:
      return "holds";
    case Verdict::kFails:
      return "fails";
    case Verdict::kUndecided:
      return "undecided";
  }
  return "?";
}

Verdict verdictOf(const Interval& ci, double threshold, Side side) {
  if (side == Side::kAtLeast) {
    if (ci.lo >= threshold) return Verdict::kHolds;
    if (ci.hi < threshold) return Verdict::kFails;
  } else {
    if (ci.hi <= threshold) return Verdict::kHolds;
    if (ci.lo > threshold) return Verdict::kFails;
  }
  return Verdict::kUndecided;
}

std::optional<int> seedsToDecide(const Estimate& e, double threshold, int n_a, int n_b) {
  const double distance = std::abs(e.value - threshold);
  const double half = e.value >= threshold ? e.value - e.ci.lo : e.ci.hi - e.value;
  if (!(distance > 0.0) || n_a <= 0) return std::nullopt;
  if (half < distance) return std::max(n_a, n_b);  // decided already
  const double rows = n_b > 0 ? 2.0 : 1.0;
  const double spread_now = 1.0 / n_a + (n_b > 0 ? 1.0 / n_b : 0.0);
  // half * sqrt(rows / n / spread_now) < distance  <=>  n > rows / spread_now * (half / distance)^2
  const double n = rows / spread_now * (half / distance) * (half / distance);
  return static_cast<int>(std::floor(n)) + 1;
}

}  // namespace msb::stats
