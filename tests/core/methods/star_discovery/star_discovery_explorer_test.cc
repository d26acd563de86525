// Star discovery on hand-built maps: rays stop at inflated obstacles (and unknown space), the
// interesting cells are those out of sight of every origin (a second origin behind a wall takes
// them away), the largest connected component, and the explorer's first moves.
#include <gtest/gtest.h>

#include "core/methods/star_discovery/star_discovery_explorer.h"
#include "core/methods/star_discovery/star_discovery_test_seam.h"

namespace msb {
namespace {

// Marks every 0.5 m cell of [lo, hi] free, then the cells of `occupied` boxes occupied.
void fill(GridMap& map, const Vec3& lo, const Vec3& hi, const std::vector<Aabb>& occupied = {}) {
  auto& tree = GridMapTestSeam::tree(map);
  for (double x = lo.x() + 0.25; x < hi.x(); x += 0.5)
    for (double y = lo.y() + 0.25; y < hi.y(); y += 0.5)
      for (double z = lo.z() + 0.25; z < hi.z(); z += 0.5) {
        bool occ = false;
        for (const Aabb& b : occupied)
          occ =
              occ || ((Vec3(x, y, z).array() >= b.min.array()).all() && (Vec3(x, y, z).array() <= b.max.array()).all());
        tree.updateNode(octomap::point3d(float(x), float(y), float(z)), occ);
        if (occ) tree.updateNode(octomap::point3d(float(x), float(y), float(z)), true);  // firmly occupied
      }
  tree.updateInnerOccupancy();
}

Aabb box(const Vec3& lo, const Vec3& hi) {
  Aabb b;
  b.min = lo, b.max = hi;
  return b;
}

TEST(StarDiscovery, RaysStopAtInflatedObstaclesAndUnknownSpace) {
  GridMap map(GridMapConfig{});
  // Free space 24 x 24 x 6 m, a wall at x in [6, 7].
  fill(map, Vec3(-12, -12, -1), Vec3(12, 12, 5), {box(Vec3(6, -12, -1), Vec3(7, 12, 5))});
  StarDiscoveryConfig cfg;  // clearance 1.5 m from occupied cells, 8 rays, 3 heights, rays up to 15 m
  const Aabb b = box(Vec3(-15, -15, 0), Vec3(15, 15, 4));
  GridPathPlanner planner(cfg.planner, b, 0.5);
  planner.rebuild(map);
  const Star star = planStar(planner, Vec3(0.25, 0.25, 2.25), cfg);
  ASSERT_EQ(star.ends.size(), 8u);
  // +x: stops 1.5 m (the inflation) before the wall, which starts at x = 6.
  const Vec3 east = star.ends[0] - star.origin;
  EXPECT_NEAR(east.y(), 0.0, 1e-9);
  EXPECT_LE(star.origin.x() + east.x(), 6.0 - 1.5 + 0.25);
  EXPECT_GE(star.origin.x() + east.x(), 6.0 - 1.5 - 0.75);
  // -x: free up to x = -12, unknown beyond (not inflated): ends in the last free cell.
  const Vec3 west = star.ends[4] - star.origin;
  EXPECT_LE(star.origin.x() + west.x(), -12.0 + 0.5);
  EXPECT_GE(star.origin.x() + west.x(), -12.0);
  // With the clearance kept from unknown space too (the grid baseline's rule) it ends near -10.5.
  StarDiscoveryConfig grid_rule = cfg;
  grid_rule.planner.unknown_clearance_m = -1.0;
  GridPathPlanner grid_planner(grid_rule.planner, b, 0.5);
  grid_planner.rebuild(map);
  const Star cautious = planStar(grid_planner, Vec3(0.25, 0.25, 2.25), grid_rule);
  ASSERT_EQ(cautious.ends.size(), 8u);
  EXPECT_LE(cautious.ends[4].x(), -10.5 + 0.75);
  EXPECT_GE(cautious.ends[4].x(), -10.5 - 0.25);
  EXPECT_GT(star.size_m, 60.0);
  // A free pocket of 5.5 x 5.5 m around the origin: every ray ends within it (known free
  // cells only), and rays under min_ray_m are dropped.
  GridMap tiny(GridMapConfig{});
  fill(tiny, Vec3(-2.5, -2.5, -1), Vec3(3, 3, 5));
  GridPathPlanner tiny_planner(cfg.planner, b, 0.5);
  tiny_planner.rebuild(tiny);
  const Star small = planStar(tiny_planner, Vec3(0.25, 0.25, 2.25), cfg);
  for (const Vec3& e : small.ends) {
    EXPECT_GE((e - small.origin).norm(), cfg.min_ray_m);
    EXPECT_LT(e.x(), 3.0) << e.transpose();
    EXPECT_GE(e.x(), -2.5) << e.transpose();
    EXPECT_LT(e.y(), 3.0) << e.transpose();
    EXPECT_GE(e.y(), -2.5) << e.transpose();
  }
  EXPECT_LT(small.size_m, 0.4 * star.size_m);
}

TEST(StarDiscovery, InterestingCellsAreFreeCellsOutOfSightOfEveryOrigin) {
  GridMap map(GridMapConfig{});
  // Free space with a wall at x in [0, 1] for y < 4: the east side is hidden from a west origin
  // except through the gap at y > 4.
  fill(map, Vec3(-10, -10, -1), Vec3(10, 10, 5), {box(Vec3(0, -10, -1), Vec3(1, 4, 5))});
  GridPlannerConfig pc;
  pc.clearance_m = 0.5;
  const Aabb b = box(Vec3(-10, -10, 1), Vec3(10, 10, 3));
  GridPathPlanner planner(pc, b, 0.5);
  planner.rebuild(map);
  const Vec3 west(-5.25, -5.25, 2.25), east(5.25, -5.25, 2.25);
  const std::vector<Vec3> one = interestingCells(map, planner, b, {west}, 30.0);
  ASSERT_FALSE(one.empty());
  // Behind the wall (east, low y) is interesting; the west side is not.
  int behind = 0;
  for (const Vec3& c : one) {
    EXPECT_GT(c.x(), 0.0) << c.transpose();  // nothing on the origin's side
    behind += c.x() > 2 && c.y() < -2;
  }
  EXPECT_GT(behind, 50);
  EXPECT_EQ(map.occupancy(Vec3(0.25, -5.25, 2.25)), 1);
  // A second origin east of the wall sees that side: far fewer interesting cells remain.
  const std::vector<Vec3> two = interestingCells(map, planner, b, {west, east}, 30.0);
  EXPECT_LT(two.size(), one.size() / 4) << one.size() << " -> " << two.size();
  // Unknown space is not free: cells beyond the mapped region are never interesting.
  for (const Vec3& c : two) EXPECT_EQ(map.occupancy(c), 0);
}

TEST(StarDiscovery, LargestComponentIsTheBiggest26ConnectedSet) {
  const std::vector<Vec3> cells = {{0.25, 0.25, 0.25}, {0.75, 0.25, 0.25},                      // 2 cells
                                   {5.25, 5.25, 0.25}, {5.75, 5.75, 0.75}, {6.25, 6.25, 1.25},  // 3, diagonal
                                   {9.25, 0.25, 0.25}};
  const std::vector<Vec3> big = largestComponent(cells, 0.5);
  ASSERT_EQ(big.size(), 3u);
  EXPECT_EQ(big[0], cells[2]);
  EXPECT_TRUE(largestComponent({}, 0.5).empty());
}

TEST(StarDiscovery, TakesOffLooksAroundThenFliesAStarSideways) {
  StarDiscoveryConfig cfg;
  ExplorerContext ctx;
  ctx.exploration_box = box(Vec3(-15, -15, 0), Vec3(15, 15, 6));
  StarDiscoveryExplorer ex(cfg, ctx);
  fill(StarDiscoveryTestSeam::map(ex), Vec3(-12, -12, -1), Vec3(12, 12, 7));
  VehicleState s;
  s.path_finished = true;
  // Take-off: climb, then forward.
  auto step = [&](double t) {
    s.t_s = t;
    const auto cmd = ex.plan(s);
    if (cmd && !cmd->waypoints.empty()) s.reference.position_m = cmd->waypoints.back().position_m;
    return cmd;
  };
  ASSERT_TRUE(step(0.0).has_value());
  step(0.1);
  ASSERT_TRUE(step(0.2).has_value());
  // Look-around (as soon as the take-off is done): four turns on the spot.
  const auto look = step(0.3);
  ASSERT_TRUE(look.has_value());
  ASSERT_EQ(look->waypoints.size(), 4u);
  for (const auto& w : look->waypoints) EXPECT_EQ(w.position_m, look->waypoints[0].position_m);
  // The star: out and back along each ray, heading 90° to the ray.
  const auto star = step(0.4);
  ASSERT_TRUE(star.has_value());
  ASSERT_GE(star->waypoints.size(), 3u);
  const Vec3 origin = star->waypoints[0].position_m;
  const Vec3 out = star->waypoints[1].position_m - origin;
  ASSERT_TRUE(star->waypoints[1].heading_rad.has_value());
  const double h = *star->waypoints[1].heading_rad;
  EXPECT_NEAR(out.normalized().dot(Vec3(std::cos(h), std::sin(h), 0)), 0.0, 1e-9);
  EXPECT_EQ(star->waypoints[2].position_m, origin);
  EXPECT_EQ(ex.counters().at("stars"), 1.0);
}

}  // namespace
}  // namespace msb
