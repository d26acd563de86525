// The grid baseline's map: insertion rules (free along rays, occupied at ends, the range rules)
// and the coverage of free leaves, exact on hand-built trees (also after pruning).
#include <gtest/gtest.h>

#include <cmath>

#include "core/eval/column_coverage.h"
#include "core/grid/grid_map.h"
#include "core/methods/grid_random/grid_explorer.h"
#include "core/methods/grid_random/grid_test_seam.h"

namespace msb {
namespace {

TEST(GridMap, RaysClearFreeSpaceAndEndsAreOccupied) {
  GridMap map(GridMapConfig{});
  const Vec3 o(0.25, 0.25, 2.25);
  map.insertScan(o, {Vec3(5.25, 0.25, 2.25)});
  for (double x = 0.25; x < 5.0; x += 0.5) EXPECT_EQ(map.occupancy(Vec3(x, 0.25, 2.25)), 0) << x;
  EXPECT_EQ(map.occupancy(Vec3(5.25, 0.25, 2.25)), 1);
  EXPECT_EQ(map.occupancy(Vec3(5.75, 0.25, 2.25)), -1);  // behind the point: unknown
  EXPECT_EQ(map.occupancy(Vec3(0.25, 3.25, 2.25)), -1);  // off the ray
}

TEST(GridMap, RangeRulesFreeRayLengthAndMaxRange) {
  GridMap map(GridMapConfig{});  // max range 20 m, free rays 15 m
  const Vec3 o(0.25, 0.25, 2.25);
  // 25 m away: beyond the range, free space only, up to 15 m.
  map.insertScan(o, {Vec3(25.25, 0.25, 2.25)});
  EXPECT_EQ(map.occupancy(Vec3(10.25, 0.25, 2.25)), 0);
  EXPECT_EQ(map.occupancy(Vec3(14.75, 0.25, 2.25)), 0);
  EXPECT_EQ(map.occupancy(Vec3(16.25, 0.25, 2.25)), -1);
  EXPECT_EQ(map.occupancy(Vec3(25.25, 0.25, 2.25)), -1);
  // 18 m away: within range, so occupied, but free space still ends at 15 m.
  map.insertScan(o, {Vec3(0.25, 18.25, 2.25)});
  EXPECT_EQ(map.occupancy(Vec3(0.25, 18.25, 2.25)), 1);
  EXPECT_EQ(map.occupancy(Vec3(0.25, 14.75, 2.25)), 0);
  EXPECT_EQ(map.occupancy(Vec3(0.25, 16.75, 2.25)), -1);
}

TEST(GridMap, AHitInTheScanIsNotClearedByAnotherRay) {
  GridMap map(GridMapConfig{});
  // The second ray passes through the first ray's end cell.
  map.insertScan(Vec3(0.25, 0.25, 2.25), {Vec3(3.25, 0.25, 2.25), Vec3(8.25, 0.25, 2.25)});
  EXPECT_EQ(map.occupancy(Vec3(3.25, 0.25, 2.25)), 1);
  EXPECT_EQ(map.occupancy(Vec3(8.25, 0.25, 2.25)), 1);
}

// The mechanism of the urban grid collisions (docs/baseline.md, "Why the grid collides in urban"):
// a sparse surface is hit now and then while rays to points behind it (or farther along it, at a
// grazing angle) cross its cells far more often. One scan hits the cell, the next three cross
// it, ten times over.
GridMap hitOnceMissedThrice(const GridMapConfig& config) {
  GridMap map(config);
  const Vec3 o(0.25, 0.25, 2.25), surface(5.25, 0.25, 2.25), behind(9.25, 0.25, 2.25);
  for (int cycle = 0; cycle < 10; ++cycle) {
    map.insertScan(o, {surface});
    for (int k = 0; k < 3; ++k) map.insertScan(o, {behind});
  }
  return map;
}

TEST(GridMap, OctoMapsDefaultModelLetsMissesOutnumberingHitsClearASurface) {
  GridMapConfig octomap_defaults;  // OctoMap's own: hit 0.7, miss 0.4, clamping 0.1192 - 0.971
  octomap_defaults.prob_hit = 0.7, octomap_defaults.prob_miss = 0.4;
  octomap_defaults.clamp_min = 0.1192, octomap_defaults.clamp_max = 0.971;
  // +0.85 per hit, -0.41 per miss: the log-odds fall by 0.37 a cycle, and the cell ends free.
  EXPECT_EQ(hitOnceMissedThrice(octomap_defaults).occupancy(Vec3(5.25, 0.25, 2.25)), 0);
}

TEST(GridMap, TheReferenceSensorModelKeepsASurfaceHitEveryFourthScan) {
  GridMapConfig reference;  // mrs_octomap_server's: hit 0.95, miss 0.45, clamping 0.3 - 0.7
  reference.prob_hit = 0.95, reference.prob_miss = 0.45, reference.clamp_min = 0.3, reference.clamp_max = 0.7;
  // A hit saturates the cell (+2.94, clamped at 0.85); three misses take 0.60 of it.
  const GridMap map = hitOnceMissedThrice(reference);
  EXPECT_EQ(map.occupancy(Vec3(5.25, 0.25, 2.25)), 1);
  // Five misses in a row do clear it (0.85 - 5 x 0.20 < 0).
  GridMap cleared(reference);
  cleared.insertScan(Vec3(0.25, 0.25, 2.25), {Vec3(5.25, 0.25, 2.25)});
  for (int k = 0; k < 5; ++k) cleared.insertScan(Vec3(0.25, 0.25, 2.25), {Vec3(9.25, 0.25, 2.25)});
  EXPECT_EQ(cleared.occupancy(Vec3(5.25, 0.25, 2.25)), 0);
}

TEST(GridMap, WatchedCellsListTheRaysThatUpdatedThem) {
  GridMap map(GridMapConfig{});
  const Vec3 o(0.25, 0.25, 2.25), cell(5.25, 0.25, 2.25);
  map.watch({*map.keyOf(cell)});
  // Point 0 ends in the cell (hit), point 1 crosses it (miss: dropped, the scan hit the cell).
  map.insertScan(o, {cell, Vec3(9.25, 0.25, 2.25)});
  ASSERT_EQ(map.lastWatched().size(), 1u);
  EXPECT_TRUE(map.lastWatched()[0].hit);
  EXPECT_EQ(map.lastWatched()[0].point, 0);
  // Next scan only crosses it: one miss, by point 0 of that scan.
  map.insertScan(o, {Vec3(9.25, 0.25, 2.25)});
  ASSERT_EQ(map.lastWatched().size(), 1u);
  EXPECT_FALSE(map.lastWatched()[0].hit);
  EXPECT_LT((map.centreOf(map.lastWatched()[0].key) - cell).norm(), 1e-6);
  EXPECT_TRUE(map.probabilityOf(*map.keyOf(cell)).has_value());
  EXPECT_FALSE(map.probabilityOf(*map.keyOf(Vec3(0.25, 9.25, 2.25))).has_value());  // never seen
}

TEST(GridMap, ExtrinsicQualityRanksSidewaysMotionAboveMotionAlongTheView) {
  // Buck et al.'s ordering (their Fig. 1): aligned views moved sideways (excellent) > moved
  // partly sideways (good) > moved along the look direction (poor); views 90° apart: bad.
  const Vec3 look(0, 0, 1);
  const double sideways = extrinsicQuality(look, look, Vec3(1, 0, 0));
  const double oblique = extrinsicQuality(look, look, Vec3(1, 0, 1));
  const double along = extrinsicQuality(look, look, Vec3(0, 0, 1));
  const double apart = extrinsicQuality(look, Vec3(1, 0, 0), Vec3(1, 0, 0));
  EXPECT_DOUBLE_EQ(sideways, 1.0);
  EXPECT_NEAR(oblique, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(along, 0.0, 1e-12);
  EXPECT_NEAR(apart, 0.0, 1e-12);
  EXPECT_GT(sideways, oblique);
  EXPECT_GT(oblique, along);
  EXPECT_EQ(extrinsicQuality(look, look, Vec3::Zero()), 0.0);  // no baseline, no depth
}

// A SLAM point seen first from `anchor`, now from `now` (both looking along +x).
SlamPoint pointSeenFrom(const Vec3& p, const Vec3& anchor, double depth_std_m) {
  SlamPoint s;
  s.p_W = p;
  s.depth_std_m = depth_std_m;
  s.T_W_anchor = Pose::Identity();
  s.T_W_anchor.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // optical z along world +x
  s.T_W_anchor.translation() = anchor;
  return s;
}

TEST(GridMap, ConfidenceWeightsScaleTheLogOddsUpdates) {
  Pose now = Pose::Identity();
  now.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  now.translation() = Vec3(0.25, 1.25, 2.25);
  // Moved 1 m sideways: quality 1; a precise point keeps weight 1, an uncertain far one less.
  const SlamPoint precise = pointSeenFrom(Vec3(6.25, 0.25, 2.25), Vec3(0.25, 0.25, 2.25), 0.0);
  const SlamPoint uncertain = pointSeenFrom(Vec3(6.25, 0.25, 2.25), Vec3(0.25, 0.25, 2.25), 6.0);
  EXPECT_DOUBLE_EQ(confidenceWeight(precise, now, 5.0), 1.0);
  EXPECT_NEAR(confidenceWeight(uncertain, now, 5.0), 0.4, 1e-12);  // 1 - 5·12/100
  // Moved along the view: no weight, whatever the depth.
  Pose ahead = now;
  ahead.translation() = Vec3(1.25, 0.25, 2.25);
  EXPECT_NEAR(confidenceWeight(precise, ahead, 5.0), 0.0, 1e-12);
  // In the map: the occupied cell of a weighted point gets weight x OctoMap's hit log-odds,
  // the free cells weight x the miss log-odds; standard insertion the full values.
  // (OctoMap's own sensor model here, whose clamping leaves the scaled updates visible.)
  GridMapConfig octomap_model;
  octomap_model.prob_hit = 0.7, octomap_model.prob_miss = 0.4, octomap_model.clamp_min = 0.1192,
  octomap_model.clamp_max = 0.971;
  GridMapConfig cfg = octomap_model;
  cfg.insertion = "confidence_weighted";
  GridMap weighted(cfg), standard(octomap_model);
  SlamPointsFrame frame;
  frame.T_W_C = now;
  frame.points = {uncertain};
  weighted.insert(frame);
  standard.insert(frame);
  const float l_hit = octomap::logodds(0.7), l_miss = octomap::logodds(0.4);
  const auto* occ_w = weighted.tree().search(octomap::point3d(6.25f, 0.25f, 2.25f));
  const auto* occ_s = standard.tree().search(octomap::point3d(6.25f, 0.25f, 2.25f));
  ASSERT_TRUE(occ_w && occ_s);
  EXPECT_NEAR(occ_w->getLogOdds(), 0.4f * l_hit, 1e-5);
  EXPECT_NEAR(occ_s->getLogOdds(), l_hit, 1e-5);
  const auto* free_w = weighted.tree().search(octomap::point3d(3.25f, 0.75f, 2.25f));
  ASSERT_TRUE(free_w);
  EXPECT_NEAR(free_w->getLogOdds(), 0.4f * l_miss, 1e-5);
  // Bad settings name their key.
  GridMapConfig bad;
  bad.insertion = "fuzzy";
  EXPECT_THROW(GridMap{bad}, ConfigError);
}

TEST(GridMap, CoverageFromFreeLeavesIsExactAlsoAfterPruning) {
  GridExplorerConfig cfg;
  ExplorerContext ctx;
  ctx.exploration_box = {Vec3(-50, -50, 0), Vec3(50, 50, 10)};
  GridExplorer explorer(cfg, ctx);
  octomap::OcTree& tree = GridMapTestSeam::tree(GridExplorerTestSeam::map(explorer));
  // A 4 m block of free cells aligned to the octree, pruned into one leaf of side 4 m over
  // x, y ∈ [0, 4]: its footprint holds the nodes (0|2.5, 0|2.5).
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k)
        tree.updateNode(octomap::point3d(0.25f + 0.5f * i, 0.25f + 0.5f * j, 0.25f + 0.5f * k), false);
  // One free cell [10, 10.5]² touching the node (10, 10) at its corner; an occupied cell elsewhere.
  tree.updateNode(octomap::point3d(10.25f, 10.25f, 0.25f), false);
  tree.updateNode(octomap::point3d(20.25f, 20.25f, 0.25f), true);
  tree.updateInnerOccupancy();
  tree.prune();
  const auto free = explorer.map().leaves(false);
  ASSERT_EQ(free.size(), 2u);
  EXPECT_DOUBLE_EQ(free[0].size_m + free[1].size_m, 4.5);
  ColumnCoverage cov;
  cov.markFreeSpace(explorer.freeSpace());  // the metric scores the leaves' square footprints
  const std::set<ColumnIndex> expected = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {4, 4}};
  EXPECT_EQ(cov.columns(), expected);
}

// A fan of rays from one origin to a 6 x 6 m wall of points 12 m away, inserted `scans` times.
GridMap fannedMap(bool prune, int scans) {
  GridMapConfig c;
  c.prune = prune;
  GridMap map(c);
  std::vector<Vec3> wall;
  for (double y = -3.0; y <= 3.0; y += 0.2)
    for (double z = 0.0; z <= 6.0; z += 0.2) wall.emplace_back(12.1, y + 0.05, z + 0.05);
  for (int i = 0; i < scans; ++i) map.insertScan(Vec3(0.1, 0.05, 3.05), wall);
  return map;
}

// The reference's mapper prunes its map as it updates (method.map.prune, the published profile):
// repeated scans saturate the free cells near the origin at the clamp, eight equal siblings
// become one cell of 1 m and more; the map means the same everywhere (each point's occupancy is
// the unpruned map's), only its cells are larger.
TEST(GridMap, APrunedMapHoldsLargerCellsAndTheSameOccupancy) {
  const GridMap lazy = fannedMap(false, 8), pruned = fannedMap(true, 8);
  double largest_lazy = 0, largest_pruned = 0;
  for (const GridLeaf& l : lazy.leaves(false)) largest_lazy = std::max(largest_lazy, l.size_m);
  for (const GridLeaf& l : pruned.leaves(false)) largest_pruned = std::max(largest_pruned, l.size_m);
  EXPECT_DOUBLE_EQ(largest_lazy, 0.5);
  EXPECT_GE(largest_pruned, 1.0);
  EXPECT_LT(pruned.leaves(false).size(), lazy.leaves(false).size());
  for (double x = 0.25; x < 13; x += 0.5)
    for (double y = -3.75; y < 4; y += 0.5)
      for (double z = 0.25; z < 6.5; z += 0.5)
        ASSERT_EQ(pruned.occupancy(Vec3(x, y, z)), lazy.occupancy(Vec3(x, y, z))) << x << " " << y << " " << z;
}

}  // namespace
}  // namespace msb
