// Grid A*: clearance from occupied cells on hand-built grids, unknown_is_occupied, the closest
// reachable cell for an unreachable goal, and escaping from a blocked start.
#include <gtest/gtest.h>

#include "core/grid/grid_map_test_seam.h"

#include <cmath>

#include "core/grid/grid_path_planner.h"
#include "core/methods/grid_random/grid_explorer.h"

namespace msb {
namespace {

const Aabb kBox{Vec3(-10, -10, 0), Vec3(12, 10, 4)};

// Unknown space traversable: the hand-built maps below know only their obstacles.
GridPlannerConfig traversableUnknown() {
  GridPlannerConfig c;
  c.unknown_is_occupied = false;
  return c;
}

// A wall of occupied cells across x = 5.25, y ∈ [-4, 4], z ∈ [0, 4].
GridMap wallMap() {
  GridMap map(GridMapConfig{});
  for (double y = -3.75; y < 4.0; y += 0.5)
    for (double z = 0.25; z < 4.0; z += 0.5)
      GridMapTestSeam::tree(map).updateNode(octomap::point3d(5.25f, float(y), float(z)), true);
  GridMapTestSeam::tree(map).updateInnerOccupancy();
  return map;
}

// Smallest distance from the cells a path passes through to any occupied cell centre.
double pathClearance(const GridMap& map, const std::vector<Vec3>& pts) {
  const auto occupied = map.leaves(true);
  double best = 1e18;
  for (size_t i = 1; i < pts.size(); ++i) {
    const Vec3 a = pts[i - 1], b = pts[i];
    const int n = std::max(1, int(std::ceil((b - a).norm() / 0.05)));
    for (int s = 0; s <= n; ++s) {
      const Vec3 x = a + (double(s) / n) * (b - a);
      const Vec3 cell = ((x / 0.5).array().floor() + 0.5).matrix() * 0.5;
      for (const auto& o : occupied) best = std::min(best, (cell - o.centre).norm());
    }
  }
  return best;
}

TEST(GridPathPlanner, PathsKeepTheClearanceFromOccupiedCells) {
  const GridMap map = wallMap();
  GridPathPlanner planner(traversableUnknown(), kBox, 0.5);
  planner.rebuild(map);
  const auto path = planner.plan(Vec3(0.1, 0.1, 2.1), Vec3(10.1, 0.1, 2.1));
  ASSERT_TRUE(path);
  EXPECT_TRUE(path->reaches_goal);
  EXPECT_TRUE(path->points.back().isApprox(Vec3(10.1, 0.1, 2.1)));
  EXPECT_GT(pathClearance(map, path->points), 1.5);
  // It went around the wall's end, not over it (the box ends at 4 m).
  double max_abs_y = 0;
  for (const auto& p : path->points) max_abs_y = std::max(max_abs_y, std::abs(p.y()));
  EXPECT_GT(max_abs_y, 4.0);
}

TEST(GridPathPlanner, UnknownIsOccupiedKeepsPathsInKnownFreeSpace) {
  GridMap map(GridMapConfig{});
  // Known free space: a corridor along x at y ≈ 0, z ≈ 2 (rays from the origin).
  for (double z = 1.25; z <= 2.75; z += 0.5)
    for (double y = -1.25; y <= 1.25; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(14.0, y, z)});
  GridPlannerConfig strict;
  strict.unknown_is_occupied = true;
  strict.clearance_m = 0.0;
  GridPathPlanner planner(strict, kBox, 0.5);
  planner.rebuild(map);
  // Inside the corridor: reachable. Off it (unknown): the closest known cell instead.
  const auto along = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 0.25, 2.25));
  ASSERT_TRUE(along);
  EXPECT_TRUE(along->reaches_goal);
  const auto off = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 8.25, 2.25));
  ASSERT_TRUE(off);
  EXPECT_FALSE(off->reaches_goal);
  for (const auto& p : off->points) EXPECT_GE(map.occupancy(p), 0) << p.transpose();
  EXPECT_NEAR(off->points.back().y(), 1.25, 0.3);
  // The same goal with unknown space traversable (the reference's rule) is reached.
  GridPlannerConfig loose = strict;
  loose.unknown_is_occupied = false;
  GridPathPlanner open(loose, kBox, 0.5);
  open.rebuild(map);
  EXPECT_TRUE(open.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 8.25, 2.25))->reaches_goal);
}

TEST(GridPathPlanner, UnknownIsOccupiedKeepsTheClearanceFromUnknownSpace) {
  GridMap map(GridMapConfig{});
  // Known free space: a slab x ∈ [0, 14], y ∈ [-4, 4], the box's full height.
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(14.1, y, z)});
  GridPlannerConfig paper;
  paper.unknown_is_occupied = true;  // clearance 1.5 m from unknown cells too
  GridPathPlanner planner(paper, kBox, 0.5);
  planner.rebuild(map);
  const auto along = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 0.25, 2.25));
  ASSERT_TRUE(along);
  EXPECT_TRUE(along->reaches_goal);
  // Known, but within 1.5 m of the unknown side: the closest cell keeps the clearance.
  const auto edge = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 3.75, 2.25));
  ASSERT_TRUE(edge);
  EXPECT_FALSE(edge->reaches_goal);
  EXPECT_NEAR(edge->points.back().y(), 2.25, 1e-9);
}

TEST(GridPathPlanner, UnknownClearanceZeroAllowsEveryKnownFreeCellAwayFromObstacles) {
  // The slab of known free space above, with unknown_clearance_m = 0 (star discovery's rule):
  // the cell next to the unknown side is traversable, the unknown cell beyond it is not.
  GridMap map(GridMapConfig{});
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(14.1, y, z)});
  GridPlannerConfig star;
  star.unknown_is_occupied = true;
  star.unknown_clearance_m = 0.0;
  GridPathPlanner planner(star, kBox, 0.5);
  planner.rebuild(map);
  EXPECT_TRUE(planner.traversable(Vec3(8.25, 3.75, 2.25)));
  EXPECT_FALSE(planner.traversable(Vec3(8.25, 4.25, 2.25)));
  const auto edge = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 3.75, 2.25));
  ASSERT_TRUE(edge);
  EXPECT_TRUE(edge->reaches_goal);
  // The default (-1) keeps clearance_m from unknown cells, as before.
  GridPlannerConfig paper;
  GridPathPlanner planner2(paper, kBox, 0.5);
  planner2.rebuild(map);
  EXPECT_FALSE(planner2.traversable(Vec3(8.25, 3.75, 2.25)));
  EXPECT_TRUE(planner2.traversable(Vec3(8.25, 2.25, 2.25)));
}

// The published grid (mrs_octomap_planner's A*, astar_planner.cpp getNeighborhood) expands only
// known free cells: an unknown cell is never entered, and it keeps no clearance (its
// `unknown_is_occupied: False` decides only the distance field). Before issue 91 msbench's
// published grid flew through unknown space.
TEST(GridPathPlanner, ThePublishedGridNeverEntersAnUnknownCellAndKeepsNoClearanceFromOne) {
  GridMap map(GridMapConfig{});
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(14.1, y, z)});
  GridExplorerConfig published;
  published.applyPublishedSettings();
  published.planner.planning_tree_resolution_m = 0.0;  // the map's cells: the known-cell rule alone
  GridPathPlanner planner(published.planner, kBox, 0.5);
  planner.rebuild(map);
  // A known free cell beside unknown space: reached (no clearance from unknown).
  const auto edge = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 3.75, 2.25));
  ASSERT_TRUE(edge);
  EXPECT_TRUE(edge->reaches_goal);
  // A goal in unknown space: the path ends in known cells, none of it unknown.
  const auto off = planner.plan(Vec3(0.25, 0.25, 2.25), Vec3(8.25, 9.25, 2.25));
  ASSERT_TRUE(off);
  EXPECT_FALSE(off->reaches_goal);
  for (const auto& p : off->points) EXPECT_GE(map.occupancy(p), 0) << p.transpose();
  EXPECT_FALSE(planner.traversable(Vec3(8.25, 4.25, 2.25)));
}

// mrs_octomap_planner's planning tree (astar_planner.cpp createPlanningTree): the 0.5 m map's
// leaves keyed by their centres into a 0.4 m tree leave one key plane in five empty (centres
// 0.25, 0.75, 1.25 m fall in 0.4 m cells 0, 1, 3: cell 2, x 0.8…1.2 m, holds none), and the A*
// enters only nodes that exist. On an unpruned map of a free slab the published planner cannot
// leave the first 0.8 m; on the map's own cells it crosses the slab (results/planning_tree/).
TEST(GridPathPlanner, ThePlanningTreeLeavesEveryFifthKeyPlaneOfAnUnprunedMapEmpty) {
  GridMap map(GridMapConfig{});
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(14.1, y, z)});
  GridExplorerConfig published;
  published.applyPublishedSettings();
  ASSERT_EQ(published.planner.planning_tree_resolution_m, 0.4);
  const Vec3 start(0.25, 0.25, 2.25), goal(8.25, 0.25, 2.25);
  GridPathPlanner tree(published.planner, kBox, 0.4);
  tree.rebuild(map, start);
  EXPECT_FALSE(tree.traversable(Vec3(1.0, 0.25, 2.25)));  // x 0.8…1.2: no leaf's centre
  EXPECT_TRUE(tree.traversable(Vec3(1.4, 0.25, 2.25)));   // x 1.2…1.6: the leaf at 1.25
  const auto confined = tree.plan(start, goal);
  ASSERT_TRUE(confined);
  EXPECT_FALSE(confined->reaches_goal);
  for (const auto& p : confined->points) EXPECT_LT(p.x(), 0.8) << p.transpose();
  // The same map on its own cells: across.
  published.planner.planning_tree_resolution_m = 0.0;
  GridPathPlanner cells(published.planner, kBox, 0.5);
  cells.rebuild(map);
  const auto across = cells.plan(start, goal);
  ASSERT_TRUE(across);
  EXPECT_TRUE(across->reaches_goal);
}

TEST(GridPathPlanner, ThePlanningTreeHoldsOnlyTheMapsLeavesNearTheStart) {
  // createPlanningTree resamples the leaves within submap_distance (20 m) of the start: from
  // 0.25 m the free cell at x 30 m is unknown to it, from 25 m it is known.
  GridMap map(GridMapConfig{});
  for (double x0 : {0.0, 8.0, 16.0, 24.0, 32.0})
    map.insertScan(Vec3(x0 + 0.25, 0.25, 2.25), {Vec3(x0 + 9.1, 0.25, 2.25)});
  GridPlannerConfig c;
  c.unknown_is_occupied = true;
  c.unknown_clearance_m = 0.0;
  c.clearance_m = 0.0;
  c.planning_tree_resolution_m = 0.5;  // the map's size: no key planes lost
  const Aabb box{Vec3(-5, -5, 0), Vec3(45, 5, 5)};
  GridPathPlanner tree(c, box, 0.5);
  tree.rebuild(map, Vec3(0.25, 0.25, 2.25));
  EXPECT_TRUE(tree.traversable(Vec3(15.25, 0.25, 2.25)));
  EXPECT_FALSE(tree.traversable(Vec3(30.25, 0.25, 2.25)));
  tree.rebuild(map, Vec3(25.25, 0.25, 2.25));
  EXPECT_TRUE(tree.traversable(Vec3(30.25, 0.25, 2.25)));
  EXPECT_FALSE(tree.traversable(Vec3(2.25, 0.25, 2.25)));
}

// mrs_octomap_planner's search (findPath): when its time runs out it flies to its best node so
// far — the lowest-f node reached, or the reached node closest to the goal when that is the
// start (reached: generated, not only expanded). With one expansion msbench's search has only
// its start; the reference's steps to the neighbour towards the goal.
TEST(GridPathPlanner, TheReferenceSearchStepsToItsBestReachedCellWhenTheBudgetEnds) {
  GridMap map(GridMapConfig{});
  for (double z = 0.25; z < 4.0; z += 0.5)
    for (double y = -3.75; y < 4.0; y += 0.5) map.insertScan(Vec3(0.25, y, z), {Vec3(11.1, y, z)});
  GridPlannerConfig c;
  c.unknown_clearance_m = 0.0;
  const Vec3 start(0.25, 0.25, 2.25), goal(8.25, 0.25, 2.25);
  GridPathPlanner ours(c, kBox, 0.5);
  ours.rebuild(map);
  c.reference_search = true;
  GridPathPlanner reference(c, kBox, 0.5);
  reference.rebuild(map);
  EXPECT_EQ(ours.plan(start, goal, 1)->points.size(), 1u);
  const auto step = reference.plan(start, goal, 1);
  ASSERT_EQ(step->points.size(), 2u);
  EXPECT_FALSE(step->reaches_goal);
  EXPECT_TRUE(step->points.back().isApprox(Vec3(0.75, 0.25, 2.25))) << step->points.back().transpose();
  // Without a budget both reach the goal.
  EXPECT_TRUE(ours.plan(start, goal)->reaches_goal);
  EXPECT_TRUE(reference.plan(start, goal)->reaches_goal);
  EXPECT_EQ(reference.plan(start, goal, 0)->points.size(), 1u);  // no expansion: nowhere to go
}

// The planning tree's work, which the time budget charges: its distance field spans the tree's
// box, and the tree always holds the map origin's cell, so far from the origin the field is
// large (the cave grid's session spawns 113 m from it).
TEST(GridPathPlanner, ThePlanningTreesDistanceFieldSpansFromTheMapOrigin) {
  GridMap map(GridMapConfig{});
  for (double x0 : {0.0, 40.0}) map.insertScan(Vec3(x0 + 0.25, 0.25, 2.25), {Vec3(x0 + 6.1, 0.25, 2.25)});
  GridExplorerConfig published;
  published.applyPublishedSettings();
  const Aabb box{Vec3(-5, -5, 0), Vec3(50, 5, 5)};
  GridPathPlanner tree(published.planner, box, 0.4);
  EXPECT_EQ(tree.treeWork().seconds(), 0.0);
  tree.rebuild(map, Vec3(0.25, 0.25, 2.25));
  const PlanningTreeWork near = tree.treeWork();
  EXPECT_GT(near.leaves, 0);
  EXPECT_GE(near.cells, near.leaves);
  tree.rebuild(map, Vec3(40.25, 0.25, 2.25));
  const PlanningTreeWork far = tree.treeWork();
  // The far tree's box reaches back from x 46 m to the origin's cell (x, y and z from 0).
  EXPECT_GE(far.edt_cells, (46.0 / 0.4) * (2.0 / 0.4));
  EXPECT_GT(far.edt_cells, 5 * near.edt_cells);
  EXPECT_GT(far.seconds(), near.seconds());
}

TEST(GridPathPlanner, AnUnreachableGoalGivesTheClosestReachableCell) {
  const GridMap map = wallMap();
  GridPathPlanner planner(traversableUnknown(), kBox, 0.5);
  planner.rebuild(map);
  const Vec3 goal(5.25, 0.25, 2.25);  // inside the wall
  const auto path = planner.plan(Vec3(0.1, 0.1, 2.1), goal);
  ASSERT_TRUE(path);
  EXPECT_FALSE(path->reaches_goal);
  const Vec3 end = path->points.back();
  EXPECT_TRUE(planner.traversable(end));
  // The closest cells keep just over 1.5 m from the wall's cells: 2 cells (1.5 m) from the
  // wall cell would be blocked, so the end lies 4 cells (2 m) before the wall's centre line.
  EXPECT_NEAR((end - goal).norm(), 2.0, 1e-9);
  EXPECT_GT(pathClearance(map, path->points), 1.5);
}

TEST(GridPathPlanner, AVehicleInBlockedCellsCanLeave) {
  const GridMap map = wallMap();
  GridPathPlanner planner(traversableUnknown(), kBox, 0.5);
  planner.rebuild(map);
  const Vec3 start(4.1, 0.1, 2.1);  // 1.15 m from the wall: blocked
  EXPECT_FALSE(planner.traversable(start));
  const auto path = planner.plan(start, Vec3(-5.1, 0.1, 2.1));
  ASSERT_TRUE(path);
  EXPECT_TRUE(path->reaches_goal);
  EXPECT_GT(pathClearance(map, path->points), 0.75);  // never through the escape clearance
  // Towards the wall's far side the way leads around the wall, not through it.
  const auto around = planner.plan(start, Vec3(8.1, 0.1, 2.1));
  ASSERT_TRUE(around);
  EXPECT_TRUE(around->reaches_goal);
  EXPECT_GT(pathClearance(map, around->points), 0.75);
  // A start that is not blocked never enters blocked cells, even near it.
  const auto free_start = planner.plan(Vec3(3.1, 0.1, 2.1), Vec3(-5.1, 0.1, 2.1));
  ASSERT_TRUE(free_start);
  EXPECT_GT(pathClearance(map, free_start->points), 1.5);
}

}  // namespace
}  // namespace msb
