// A* with the safety-aware cost on hand-built sphere graphs; the containing-sphere rule.
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/rng.h"
#include "core/methods/monospheres/map/sphere_map_test_seam.h"
#include "core/methods/monospheres/planner/sphere_graph_search.h"

namespace msb {
namespace {

SphereMap emptyMap() { return SphereMap(SphereMapConfig{}, FisheyeCamera(FisheyeCameraConfig{}), 1); }

TEST(SafetyCost, PenaltyShape) {
  // The shape with the paper's r_min 1.6 m (the default is 1.4: full penalty there instead).
  EXPECT_DOUBLE_EQ(narrownessPenalty(SafetyCostConfig{}.r_min_m, SafetyCostConfig{}), 1.0);
  SafetyCostConfig cfg;
  cfg.r_min_m = 1.6;
  EXPECT_DOUBLE_EQ(narrownessPenalty(1.6, cfg), 1.0);
  EXPECT_DOUBLE_EQ(narrownessPenalty(8.0, cfg), 0.0);
  EXPECT_DOUBLE_EQ(narrownessPenalty(10.0, cfg), 0.0);
  EXPECT_NEAR(narrownessPenalty(4.8, cfg), 0.25, 1e-12);
  // Narrow spheres cost more (the reference inverted this).
  EXPECT_GT(edgeCost(1.0, 1.7, cfg), edgeCost(1.0, 5.0, cfg));
  EXPECT_DOUBLE_EQ(edgeCost(2.0, 8.0, cfg), 2.0);
}

// S and G joined by a short chain of narrow spheres and by a longer detour through wide ones.
struct TwoRoutes {
  SphereMap map = emptyMap();
  uint64_t s, n1, n2, n3, g, w1, w2;
  TwoRoutes() {
    s = SphereMapTestSeam::addSphere(map, {0, 0, 0}, 2.0);
    n1 = SphereMapTestSeam::addSphere(map, {3, 0, 0}, 1.7);
    n2 = SphereMapTestSeam::addSphere(map, {6, 0, 0}, 1.7);
    n3 = SphereMapTestSeam::addSphere(map, {9, 0, 0}, 1.7);
    g = SphereMapTestSeam::addSphere(map, {12, 0, 0}, 2.0);
    w1 = SphereMapTestSeam::addSphere(map, {0, 9, 0}, 7.5);
    w2 = SphereMapTestSeam::addSphere(map, {12, 9, 0}, 7.5);
  }
};

TEST(SphereGraphSearch, SafetyCostPrefersWideSpheres) {
  TwoRoutes t;
  ASSERT_EQ(t.map.neighbours(t.s), (std::set<uint64_t>{t.n1, t.w1}));
  ASSERT_EQ(t.map.neighbours(t.g), (std::set<uint64_t>{t.n3, t.w2}));
  SafetyCostConfig safe;  // w = 50
  const auto p = findSpherePath(t.map, t.s, t.g, safe);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->spheres, (std::vector<uint64_t>{t.s, t.w1, t.w2, t.g}));
  EXPECT_NEAR(p->length_m, 30.0, 1e-9);
  SafetyCostConfig plain;
  plain.weight = 0.0;  // pure length: the narrow chain
  const auto q = findSpherePath(t.map, t.s, t.g, plain);
  ASSERT_TRUE(q);
  EXPECT_EQ(q->spheres, (std::vector<uint64_t>{t.s, t.n1, t.n2, t.n3, t.g}));
  EXPECT_NEAR(q->cost, 12.0, 1e-9);
}

TEST(SphereGraphSearch, AStarMatchesDijkstraOnRandomGraphs) {
  RngStream rng(7, "test");
  for (int trial = 0; trial < 20; ++trial) {
    SphereMap map = emptyMap();
    std::vector<uint64_t> ids;
    for (int i = 0; i < 60; ++i)
      ids.push_back(SphereMapTestSeam::addSphere(map, {rng.uniform(0, 40), rng.uniform(0, 40), rng.uniform(0, 4)},
                                                 rng.uniform(1.6, 6)));
    const SafetyCostConfig cfg;
    const SphereCostField field = sphereCostsFrom(map, ids[0], cfg);
    for (uint64_t g : ids) {
      const auto p = findSpherePath(map, ids[0], g, cfg);
      ASSERT_EQ(bool(p), field.cost.count(g) == 1);
      if (!p) continue;
      EXPECT_NEAR(p->cost, field.cost.at(g), 1e-9);  // the heuristic is admissible: optimal
      // The reported cost is the sum of the edge costs along the path.
      double c = 0;
      for (size_t k = 1; k < p->spheres.size(); ++k) {
        const Sphere& a = map.spheres().at(p->spheres[k - 1]);
        const Sphere& b = map.spheres().at(p->spheres[k]);
        ASSERT_TRUE(map.neighbours(a.id).count(b.id));
        c += edgeCost((b.centre - a.centre).norm(), b.radius, cfg);
      }
      EXPECT_NEAR(c, p->cost, 1e-9);
    }
  }
}

TEST(SphereGraphSearch, UnreachableAndContainingSphere) {
  SphereMap map = emptyMap();
  const uint64_t a = SphereMapTestSeam::addSphere(map, {0, 0, 0}, 3.0);
  const uint64_t b = SphereMapTestSeam::addSphere(map, {2, 0, 0}, 2.0);
  const uint64_t far = SphereMapTestSeam::addSphere(map, {50, 0, 0}, 2.0);
  const SafetyCostConfig cfg;
  EXPECT_FALSE(findSpherePath(map, a, far, cfg));
  EXPECT_EQ(*containingSphere(map, {0.5, 0, 0}, 1.5, 1.6), a);  // depth 2.5 vs 0.5
  EXPECT_EQ(*containingSphere(map, {3.5, 0, 0}, 1.5, 1.6), b);  // depth 0.5 vs −0.5
  EXPECT_EQ(*containingSphere(map, {5.4, 0, 0}, 1.5, 1.6), b);  // 1.4 m outside b
  EXPECT_FALSE(containingSphere(map, {5.4, 0, 0}, 1.0, 1.6));
  EXPECT_FALSE(containingSphere(map, {0.5, 0, 0}, 1.5, 3.5));  // spheres below the minimum radius are skipped
}

TEST(SafetyCost, ThePublishedCodesCostRisesWithTheRadius) {
  // method.reference_code.safety_cost_inverted (LNM compute_safety_cost): ((r − r_min)/(r_safe −
  // r_min))², radii below r_min taken as r_min, nothing above r_safe.
  SafetyCostConfig cfg;
  cfg.r_min_m = 1.6;
  cfg.inverted = true;
  EXPECT_DOUBLE_EQ(narrownessPenalty(1.6, cfg), 0.0);
  EXPECT_DOUBLE_EQ(narrownessPenalty(1.0, cfg), 0.0);
  EXPECT_NEAR(narrownessPenalty(4.8, cfg), 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(narrownessPenalty(8.0, cfg), 1.0);
  EXPECT_DOUBLE_EQ(narrownessPenalty(8.01, cfg), 0.0);
  EXPECT_DOUBLE_EQ(edgeCost(1.0, 8.0, cfg), 51.0);  // the widest spheres below r_safe: ×51
}

TEST(SphereGraphSearch, UnderThePublishedCostTheRouteTakesTheNarrowChain) {
  // The detour's 7.5 m spheres cost ×43.7 under the inverted cost; the 1.7 m chain ×1.1.
  TwoRoutes t;
  SafetyCostConfig inverted;
  inverted.inverted = true;
  const auto p = findSpherePath(t.map, t.s, t.g, inverted);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->spheres, (std::vector<uint64_t>{t.s, t.n1, t.n2, t.n3, t.g}));
}

}  // namespace
}  // namespace msb
