// The grid baseline's map: insertion rules (free along rays, occupied at ends, the range rules)
// and the coverage of free leaves, exact on hand-built trees (also after pruning).
#include <gtest/gtest.h>

#include "core/baseline/grid_explorer.h"
#include "core/baseline/grid_map.h"

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

TEST(GridMap, CoverageFromFreeLeavesIsExactAlsoAfterPruning) {
  GridExplorerConfig cfg;
  ExplorerContext ctx;
  ctx.exploration_box = {Vec3(-50, -50, 0), Vec3(50, 50, 10)};
  GridExplorer explorer(cfg, ctx);
  octomap::OcTree& tree = explorer.mutableMap().mutableTree();
  // A 4 m block of free cells aligned to the octree, pruned into one leaf of side 4 m over
  // x, y ∈ [0, 4]: its footprint holds the nodes (0|2.5, 0|2.5).
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 8; ++k) tree.updateNode(octomap::point3d(0.25f + 0.5f * i, 0.25f + 0.5f * j, 0.25f + 0.5f * k), false);
  // One free cell [10, 10.5]² touching the node (10, 10) at its corner; an occupied cell elsewhere.
  tree.updateNode(octomap::point3d(10.25f, 10.25f, 0.25f), false);
  tree.updateNode(octomap::point3d(20.25f, 20.25f, 0.25f), true);
  tree.updateInnerOccupancy();
  tree.prune();
  const auto free = explorer.map().leaves(false);
  ASSERT_EQ(free.size(), 2u);
  EXPECT_DOUBLE_EQ(free[0].size_m + free[1].size_m, 4.5);
  ColumnCoverage cov;
  explorer.markCoverage(cov);
  const std::set<ColumnIndex> expected = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {4, 4}};
  EXPECT_EQ(cov.columns(), expected);
}

}  // namespace
}  // namespace msb
