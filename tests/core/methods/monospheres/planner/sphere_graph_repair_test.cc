// The sphere-graph repair on hand-built maps: gap links, trail links, blocked edges, the link
// being crossed.
#include "core/methods/monospheres/planner/sphere_graph_repair.h"
#include "core/methods/monospheres/map/sphere_map_test_seam.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

// Two parts of two spheres each (radius 2) along x: A at 0 and 1.5, B at `b` and b + 1.5.
struct TwoParts {
  explicit TwoParts(double b) : map(SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1) {
    a0 = SphereMapTestSeam::addSphere(map, Vec3(0, 0, 2), 2.0);
    a1 = SphereMapTestSeam::addSphere(map, Vec3(1.5, 0, 2), 2.0);
    b0 = SphereMapTestSeam::addSphere(map, Vec3(b, 0, 2), 2.0);
    b1 = SphereMapTestSeam::addSphere(map, Vec3(b + 1.5, 0, 2), 2.0);
  }
  SphereMap map;
  uint64_t a0 = 0, a1 = 0, b0 = 0, b1 = 0;
};

TEST(SphereGraphRepair, ANarrowGapIsLinkedUnlessAnObstacleSitsInIt) {
  TwoParts s(6.0);  // surfaces 0.5 m apart
  ASSERT_FALSE(s.map.neighbours(s.a1).count(s.b0));
  SphereGraphRepair repair(s.map, GraphRepairConfig{}, SafetyCostConfig{}, PathCheckConfig{}, 10.0);
  const SphereLinks& links = repair.relink();
  ASSERT_TRUE(links.count(s.a1));
  EXPECT_EQ(links.at(s.a1), std::vector<uint64_t>{s.b0});  // the closest pair of centres
  EXPECT_EQ(links.at(s.b0), std::vector<uint64_t>{s.a1});
  // An obstacle point on the segment between the centres: the link would not keep the clearance.
  SphereMapTestSeam::addObstacle(s.map, Vec3(3.75, 0, 2), 1.0);
  EXPECT_TRUE(repair.relink().empty());
  // Wider than link_gap_m: no gap link.
  TwoParts far(14.0);
  SphereGraphRepair far_repair(far.map, GraphRepairConfig{}, SafetyCostConfig{}, PathCheckConfig{}, 10.0);
  EXPECT_TRUE(far_repair.relink().empty());
}

TEST(SphereGraphRepair, TheVehiclesTrailLinksPartsItFlewBetween) {
  TwoParts s(14.0);  // 8.5 m between the surfaces: too wide for a gap link
  SphereGraphRepair repair(s.map, GraphRepairConfig{}, SafetyCostConfig{}, PathCheckConfig{}, 10.0);
  EXPECT_TRUE(repair.relink().empty());
  for (double x = 0; x <= 15.5; x += 0.5) repair.beginStep(Vec3(x, 0, 2), x);
  const SphereLinks& links = repair.relink();
  ASSERT_TRUE(links.count(s.a1)) << "no trail link";
  EXPECT_EQ(links.at(s.a1), std::vector<uint64_t>{s.b0});
  // A trail that went around elsewhere (5 m off the segment) links nothing.
  SphereGraphRepair elsewhere(s.map, GraphRepairConfig{}, SafetyCostConfig{}, PathCheckConfig{}, 10.0);
  for (double x = 0; x <= 15.5; x += 0.5) elsewhere.beginStep(Vec3(x, x > 2 && x < 13 ? 5.0 : 0.0, 2), x);
  EXPECT_TRUE(elsewhere.relink().empty());
}

TEST(SphereGraphRepair, ABlockedEdgeIsImpassableUntilItsTimeIsUp) {
  TwoParts s(6.0);
  GraphRepairConfig c;
  c.blocked_edge_timeout_s = 30.0;
  SphereGraphRepair repair(s.map, c, SafetyCostConfig{}, PathCheckConfig{}, 10.0);
  repair.blockEdge(s.a1, s.a0, 10.0);
  EXPECT_FALSE(repair.passable()(s.a0, s.a1));  // either direction
  EXPECT_FALSE(repair.passable()(s.a1, s.a0));
  EXPECT_TRUE(repair.passable()(s.b0, s.b1));
  repair.beginStep(Vec3(0, 0, 2), 39.9);
  EXPECT_FALSE(repair.passable()(s.a0, s.a1));
  repair.beginStep(Vec3(0, 0, 2), 40.0);
  EXPECT_TRUE(repair.passable()(s.a0, s.a1));
}

TEST(SphereGraphRepair, ARouteOverALinkStartsTheSearchAtItsFarSphereWhileCrossing) {
  TwoParts s(6.0);
  GraphRepairConfig c;
  SphereGraphRepair repair(s.map, c, SafetyCostConfig{}, PathCheckConfig{}, /*transit_timeout_s=*/10.0);
  EXPECT_FALSE(repair.transitStart(0.0, 0.0));
  SpherePath within;
  within.spheres = {s.a0, s.a1};
  EXPECT_FALSE(repair.noteRoute(within, 1.0));  // neighbours only: no link
  SpherePath over;
  over.spheres = {s.a0, s.a1, s.b0, s.b1};
  EXPECT_TRUE(repair.noteRoute(over, 1.0));   // a link newly used
  EXPECT_FALSE(repair.noteRoute(over, 2.0));  // the same link, still being crossed
  EXPECT_EQ(repair.transitStart(5.0, 0.0), s.b0);
  EXPECT_FALSE(repair.transitStart(12.0, 0.0));  // the crossing's time is up
  // Progress keeps a crossing alive: until at least the last progress + the timeout.
  EXPECT_TRUE(repair.noteRoute(over, 20.0));
  EXPECT_EQ(repair.transitStart(29.0, 25.0), s.b0);
  EXPECT_EQ(repair.transitStart(34.0, 25.0), s.b0);
  EXPECT_FALSE(repair.transitStart(35.0, 25.0));
}

}  // namespace
}  // namespace msb
