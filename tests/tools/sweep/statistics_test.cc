#include "tools/sweep/statistics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace msb::stats {
namespace {

std::vector<double> normalSample(std::mt19937_64& rng, int n, double mu, double sigma) {
  std::normal_distribution<double> d(mu, sigma);
  std::vector<double> x(static_cast<size_t>(n));
  for (double& v : x) v = d(rng);
  return x;
}

TEST(Quantile, InterpolatesBetweenOrderStatistics) {
  const std::vector<double> s = {1, 2, 3, 4};
  EXPECT_DOUBLE_EQ(quantileSorted(s, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantileSorted(s, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantileSorted(s, 0.5), 2.5);    // numpy.quantile([1,2,3,4], 0.5)
  EXPECT_DOUBLE_EQ(quantileSorted(s, 0.25), 1.75);  // numpy.quantile([1,2,3,4], 0.25)
}

TEST(BootstrapMean, IntervalOfAKnownMeanHasTheNormalWidth) {
  // 400 draws of N(10, 2): the 95 % interval of the mean is about 10 ± 1.96 * 2 / 20 = ±0.196.
  std::mt19937_64 rng(7);
  const auto x = normalSample(rng, 400, 10.0, 2.0);
  const Estimate e = bootstrapMean(x);
  EXPECT_EQ(e.n, 400);
  EXPECT_LT(e.ci.lo, e.value);
  EXPECT_GT(e.ci.hi, e.value);
  EXPECT_LT(std::abs(e.value - 10.0), 0.3);
  const double half = (e.ci.hi - e.ci.lo) / 2.0;
  EXPECT_NEAR(half, 1.96 * 2.0 / 20.0, 0.03);
}

TEST(BootstrapMean, CoversTheTrueMeanAtAboutTheLevel) {
  // 300 data sets of 30 draws of N(0, 1): the percentile interval covers 0 in about 95 % of them
  // (a little less: the percentile bootstrap is slightly narrow at small n).
  std::mt19937_64 rng(11);
  int covered = 0;
  for (int k = 0; k < 300; ++k) {
    const Estimate e = bootstrapMean(normalSample(rng, 30, 0.0, 1.0), {kResampleSeed + k, 2000, kLevel});
    covered += e.ci.lo <= 0.0 && 0.0 <= e.ci.hi;
  }
  EXPECT_GE(covered, 270);  // >= 90 %
  EXPECT_LE(covered, 294);  // <= 98 %
}

TEST(BootstrapMean, DeterministicAndDegenerateCases) {
  const std::vector<double> x = {3, 5, 9};
  const Estimate a = bootstrapMean(x), b = bootstrapMean(x);
  EXPECT_EQ(a.ci.lo, b.ci.lo);
  EXPECT_EQ(a.ci.hi, b.ci.hi);
  // Three values: a resample of three copies of the smallest has probability 1/27 > 2.5 %, so the
  // 95 % percentile interval runs from the smallest value to the largest.
  EXPECT_DOUBLE_EQ(a.ci.lo, 3.0);
  EXPECT_DOUBLE_EQ(a.ci.hi, 9.0);
  const Estimate one = bootstrapMean({4.0});
  EXPECT_EQ(one.ci.lo, 4.0);
  EXPECT_EQ(one.ci.hi, 4.0);
  EXPECT_THROW(bootstrapMean({}), std::invalid_argument);
}

TEST(BootstrapRatio, StratifiedAndPaired) {
  const std::vector<double> a = {2.0, 2.2, 1.8, 2.1, 1.9, 2.0}, b = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  const Estimate r = bootstrapRatio(a, b);
  EXPECT_DOUBLE_EQ(r.value, 2.0);
  EXPECT_LT(r.ci.lo, 2.0);
  EXPECT_GT(r.ci.hi, 2.0);
  // Pairs that move together: the paired interval is narrower than the stratified one.
  const std::vector<double> c = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, d = {0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  const Estimate paired = bootstrapPairedRatio(c, d), stratified = bootstrapRatio(c, d);
  EXPECT_DOUBLE_EQ(paired.ci.lo, 2.0);
  EXPECT_DOUBLE_EQ(paired.ci.hi, 2.0);
  EXPECT_LT(stratified.ci.lo, 1.7);
  EXPECT_NEAR(*correlation(c, d), 1.0, 1e-12);
  EXPECT_THROW(bootstrapRatio(a, {0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(bootstrapPairedRatio(a, {1.0}), std::invalid_argument);
}

TEST(Verdict, AnIntervalAcrossTheThresholdIsUndecided) {
  // Rooftops of the published Table I: MonoSpheres 7294, 7075, 7444; grid 4106, 3050, 4625.
  const Estimate r = bootstrapRatio({7294, 7075, 7444}, {4106, 3050, 4625});
  EXPECT_NEAR(r.value, 1.85, 0.01);
  EXPECT_EQ(verdictOf(r.ci, 2.0, Side::kAtLeast), Verdict::kUndecided);
  EXPECT_GT(*seedsToDecide(r, 2.0, 3, 3), 3);
  EXPECT_EQ(verdictOf({2.1, 3.0}, 2.0, Side::kAtLeast), Verdict::kHolds);
  EXPECT_EQ(verdictOf({1.1, 1.9}, 2.0, Side::kAtLeast), Verdict::kFails);
  EXPECT_EQ(verdictOf({0.1, 0.2}, 0.3, Side::kAtMost), Verdict::kHolds);
  EXPECT_EQ(verdictOf({0.4, 0.5}, 0.3, Side::kAtMost), Verdict::kFails);
  EXPECT_STREQ(verdictName(Verdict::kUndecided), "undecided");
}

TEST(Verdict, SeedsToDecideScalesWithTheSquaredRatioOfHalfWidthToDistance) {
  // Estimate 1.85 [1.58, 2.37] against 2 from 3 and 3 runs: the upper half-width 0.52 must fall
  // below 0.15: n > 2 / (2/3) * (0.52 / 0.15)^2 = 36.05.
  const Estimate e{1.85, {1.58, 2.37}, 3};
  EXPECT_EQ(*seedsToDecide(e, 2.0, 3, 3), 37);
  EXPECT_FALSE(seedsToDecide({2.0, {1.5, 2.5}, 3}, 2.0, 3, 3).has_value());
  EXPECT_EQ(*seedsToDecide({3.0, {2.5, 3.5}, 3}, 2.0, 3, 3), 3);  // decided already
}

TEST(Wilson, AgainstTabulatedIntervals) {
  EXPECT_NEAR(normalQuantile(0.975), 1.959964, 1e-6);
  const Interval a = wilson(3, 6);  // 0.1876 - 0.8124
  EXPECT_NEAR(a.lo, 0.1876, 1e-4);
  EXPECT_NEAR(a.hi, 0.8124, 1e-4);
  const Interval b = wilson(0, 6);  // 0 - 0.3903
  EXPECT_EQ(b.lo, 0.0);
  EXPECT_NEAR(b.hi, 0.3903, 1e-4);
  const Interval c = wilson(1, 10);  // 0.0179 - 0.4042
  EXPECT_NEAR(c.lo, 0.0179, 1e-4);
  EXPECT_NEAR(c.hi, 0.4042, 1e-4);
  EXPECT_EQ(wilson(6, 6).hi, 1.0);
}

TEST(FisherExact, AgainstTabulatedPValues) {
  EXPECT_NEAR(fisherExact(3, 4, 1, 4), 0.4857, 1e-4);      // Fisher's tea tasting
  EXPECT_NEAR(fisherExact(6, 6, 1, 6), 14.0 / 924, 1e-9);  // the urban grid's 6 of 6 vs the paper's 1 of 6
  EXPECT_NEAR(fisherExact(3, 6, 2, 6), 1.0, 1e-9);         // MonoSpheres' 3 of 6 vs 2 of 6
  EXPECT_NEAR(fisherExact(0, 6, 0, 3), 1.0, 1e-9);
  EXPECT_NEAR(fisherExact(5, 10, 0, 10), 0.0325, 1e-4);  // R: fisher.test(matrix(c(5,5,0,10),2))
  EXPECT_THROW(fisherExact(4, 3, 0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace msb::stats
