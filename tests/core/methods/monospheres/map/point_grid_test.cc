// The hash grid's queries against a brute-force scan: same ids, ascending, after inserts and
// erases, for small and large query boxes (both lookup strategies).
#include "core/methods/monospheres/map/point_grid.h"

#include <gtest/gtest.h>

#include <map>

#include "core/common/rng.h"

namespace msb {
namespace {

TEST(PointGrid, QueriesMatchABruteForceScanAfterInsertsAndErases) {
  RngStream rng(7, "point_grid_test");
  PointGrid grid(2.0);
  std::map<uint64_t, Vec3> points;
  for (uint64_t id = 1; id <= 600; ++id) {
    const Vec3 p(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-5, 5));
    grid.insert(id, p);
    points[id] = p;
  }
  for (uint64_t id = 3; id <= 600; id += 3) {  // every third point leaves again
    grid.erase(id, points.at(id));
    points.erase(id);
  }
  ASSERT_EQ(grid.size(), points.size());
  for (int q = 0; q < 40; ++q) {
    const Vec3 c(rng.uniform(-22, 22), rng.uniform(-22, 22), rng.uniform(-6, 6));
    const double r = q < 20 ? rng.uniform(0.2, 3.0) : rng.uniform(10.0, 40.0);  // both strategies
    std::vector<uint64_t> ball, cube;
    for (const auto& [id, p] : points) {
      if ((p - c).norm() <= r) ball.push_back(id);
      if (((p - c).array().abs() <= r).all()) cube.push_back(id);
    }
    EXPECT_EQ(grid.select(c, r, [&](uint64_t, const Vec3& p) { return (p - c).norm() <= r; }), ball);
    EXPECT_EQ(grid.anyNear(c, r, [&](uint64_t, const Vec3& p) { return (p - c).norm() <= r; }), !ball.empty());
    // The box query returns whole cells: a superset of the cube, ascending, without duplicates.
    const std::vector<uint64_t> box = grid.near(c, r);
    EXPECT_TRUE(std::is_sorted(box.begin(), box.end()));
    EXPECT_EQ(std::adjacent_find(box.begin(), box.end()), box.end());
    EXPECT_TRUE(std::includes(box.begin(), box.end(), cube.begin(), cube.end()));
    for (uint64_t id : box) EXPECT_TRUE(points.count(id)) << "erased id " << id << " returned";
  }
}

}  // namespace
}  // namespace msb
