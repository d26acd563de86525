// Mission coverage: box share over explorable columns only, and the longest stretch without gain.
#include "core/eval/mission_coverage.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

TEST(MissionCoverage, BoxShareCountsOnlyExplorableColumns) {
  // A 10 x 10 m box whose explorable columns are two nodes; free space covers the whole box
  // (and more): the numerator is the explored explorable columns, never more than the two.
  const Aabb box{Vec3(0, 0, 0), Vec3(10, 10, 5)};
  MissionCoverage cov(box, {{0, 0}, {1, 0}});
  EXPECT_EQ(cov.boxExplorableColumns(), 2);
  cov.columns().markDisk(Vec2(5, 5), 20.0);
  cov.sample(1.0, 0.0, {});
  EXPECT_GT(cov.columns().countInside(box.min.head<2>(), box.max.head<2>()), 2u);
  EXPECT_EQ(cov.exploredExplorableColumns(), 2u);
  // Only one of them explored: half.
  MissionCoverage half(box, {{0, 0}, {3, 3}});
  half.columns().markDisk(Vec2(0, 0), 1.0);
  EXPECT_EQ(half.exploredExplorableColumns(), 1u);
}

TEST(MissionCoverage, TrueFrameBoxShareUsesTheCorrectionOfFirstSight) {
  // The only explorable column is node (4, 0) at x = 10 m. An element seen at the VIO origin
  // while the estimate is 10 m off truth lies, in truth, at x = 10: the VIO-frame count misses
  // it, the true-frame count has it.
  const Aabb box{Vec3(-5, -5, 0), Vec3(15, 5, 5)};
  MissionCoverage cov(box, {{4, 0}});
  Pose T_true_est = Pose::Identity();
  T_true_est.translation() = Vec3(10, 0, 0);
  cov.setTrueFromEstimate(T_true_est);
  cov.columns().markDisk(Vec2(0, 0), 1.0);
  cov.sample(1.0, 0.0, {{7, Vec3(0, 0, 1), 1.0}});
  EXPECT_EQ(cov.exploredExplorableColumns(), 0u);
  EXPECT_EQ(cov.trueFrameExploredExplorableColumns(), 1u);
  // The drift is corrected later: the element keeps its first correction, a new element at the
  // origin is placed at the origin (not explorable), so the count stays 1.
  cov.setTrueFromEstimate(Pose::Identity());
  cov.sample(2.0, 0.0, {{7, Vec3(0, 0, 1), 1.0}, {8, Vec3(0, 0, 1), 1.0}});
  EXPECT_EQ(cov.trueFrameExploredExplorableColumns(), 1u);
  EXPECT_EQ(cov.trueFrameColumns().columns().size(), 2u);
}

TEST(MissionCoverage, LongestIntervalWithoutGain) {
  auto at = [](double t, double a) {
    CoverageSample s;
    s.t_s = t;
    s.area_m2 = a;
    return s;
  };
  // Gains at 1 and 2, flat from 2 to 6, a gain at 7, flat to the end at 9.
  const std::vector<CoverageSample> samples = {at(0, 0),  at(1, 10), at(2, 20), at(3, 20), at(4, 20),
                                               at(5, 20), at(6, 20), at(7, 30), at(8, 30), at(9, 30)};
  const NoGainInterval i = longestIntervalWithoutGain(samples);
  EXPECT_DOUBLE_EQ(i.start_s, 2.0);
  EXPECT_DOUBLE_EQ(i.end_s, 6.0);
  EXPECT_DOUBLE_EQ(i.lengthS(), 4.0);
  // A stall still open at the end counts up to the last sample.
  const std::vector<CoverageSample> stalled = {at(0, 0), at(1, 10), at(2, 10), at(3, 10), at(10, 10)};
  EXPECT_DOUBLE_EQ(longestIntervalWithoutGain(stalled).lengthS(), 9.0);
  EXPECT_DOUBLE_EQ(longestIntervalWithoutGain({}).lengthS(), 0.0);
}

TEST(MissionCoverage, ThePublishedOctomapRuleScoresACellAsADiskOfItsDepthIndex) {
  // EVAL (process_explored_volume_octomap_gridmarking, BUG-11): a free cell 2^k leaves wide
  // (leaf 0.5 m) counts as a disk of radius 0.5·(k + 1) about its centre. A leaf 0.3 m from a
  // node: disk r 0.5 takes the node, msbench's square (half side 0.25) does not. A cell of
  // 8 m (k = 4): disk r 2.5 about (5, 5) takes 5 nodes, the square [1, 9]² takes 9.
  const Aabb box{Vec3(-10, -10, 0), Vec3(20, 20, 5)};
  const std::vector<FreeSpaceElement> cells = {{1, Vec3(0.3, 0, 1), 0.25, FreeSpaceElement::Footprint::kSquare},
                                               {2, Vec3(5, 5, 1), 4.0, FreeSpaceElement::Footprint::kSquare}};
  MissionCoverage cov(box, {});
  EXPECT_EQ(cov.publishedRuleColumns(), nullptr);
  cov.enablePublishedOctomapRule(0.5);
  cov.columns().markFreeSpace(cells);
  cov.sample(1.0, 0.0, cells);
  ASSERT_NE(cov.publishedRuleColumns(), nullptr);
  const auto& rule = cov.publishedRuleColumns()->columns();
  EXPECT_EQ(rule.size(), 6u);
  EXPECT_TRUE(rule.count({0, 0}));
  EXPECT_EQ(cov.columns().count(), 9u);
  EXPECT_FALSE(cov.columns().columns().count({0, 0}));
  // Cumulative, and disks (spheres) are not OctoMap cells: they add nothing to the rule.
  cov.sample(2.0, 0.0, {{3, Vec3(20, 20, 1), 5.0}});
  EXPECT_EQ(cov.publishedRuleColumns()->count(), 6u);
}

// The rule on a pruned map's cells (the reference's mapper prunes; method.map.prune): cells of
// 1, 2, 4 and 8 m (k = 1...4) count as disks of radius 1, 1.5, 2 and 2.5 m about their centres.
// Centred on nodes, they take 1, 1, 1 and 5 nodes; their squares take 1, 1, 1 and 9.
TEST(MissionCoverage, ThePublishedOctomapRuleScoresPrunedCellsOf1To8Metres) {
  const Aabb box{Vec3(-10, -10, 0), Vec3(40, 10, 5)};
  std::vector<FreeSpaceElement> cells;
  uint64_t id = 1;
  for (const auto& [x, half] : std::vector<std::pair<double, double>>{{0, 0.5}, {10, 1.0}, {20, 2.0}, {30, 4.0}})
    cells.push_back({id++, Vec3(x, 0, 1), half, FreeSpaceElement::Footprint::kSquare});
  MissionCoverage cov(box, {});
  cov.enablePublishedOctomapRule(0.5);
  EXPECT_DOUBLE_EQ(cov.publishedRuleRadius(0.5), 1.0);
  EXPECT_DOUBLE_EQ(cov.publishedRuleRadius(1.0), 1.5);
  EXPECT_DOUBLE_EQ(cov.publishedRuleRadius(2.0), 2.0);
  EXPECT_DOUBLE_EQ(cov.publishedRuleRadius(4.0), 2.5);
  cov.columns().markFreeSpace(cells);
  cov.sample(1.0, 0.0, cells);
  EXPECT_EQ(cov.publishedRuleColumns()->count(), 8u);
  EXPECT_EQ(cov.columns().count(), 12u);
}

}  // namespace
}  // namespace msb
