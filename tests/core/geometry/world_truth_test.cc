#include "core/geometry/world_truth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/rng.h"

namespace msb {
namespace {

Shape box(const Vec3& c, const Vec3& half, double yaw = 0.0, double roll = 0.0) {
  Shape s;
  s.type = ShapeType::kBox;
  s.pose = poseFromXyzYaw(c, yaw);
  s.pose.linear() = s.pose.linear() * Eigen::AngleAxisd(roll, Vec3::UnitX()).toRotationMatrix();
  s.size = half;
  return s;
}
Shape cylinder(const Vec3& c, double r, double hh, double tilt = 0.0) {
  Shape s;
  s.type = ShapeType::kCylinder;
  s.pose = poseFromXyzYaw(c, 0.3);
  s.pose.linear() = s.pose.linear() * Eigen::AngleAxisd(tilt, Vec3::UnitY()).toRotationMatrix();
  s.size = Vec3(r, r, hh);
  return s;
}
Shape sphere(const Vec3& c, double r) {
  Shape s;
  s.type = ShapeType::kSphere;
  s.pose = poseFromXyzYaw(c, 0);
  s.size = Vec3::Constant(r);
  return s;
}

// Brute-force first hit along a ray by marching with inside tests (1 mm steps near hits).
double marchHit(const Shape& s, const Vec3& o, const Vec3& d, double max_t) {
  double t = 0;
  const double step = 0.01;
  while (t < max_t && s.signedDistance(o + t * d) > 0) t += step;
  if (t >= max_t) return -1;
  double lo = std::max(0.0, t - step), hi = t;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (s.signedDistance(o + mid * d) > 0 ? lo : hi) = mid;
  }
  return hi;
}

TEST(Shapes, RaycastAgreesWithMarchingOnRandomRays) {
  RngStream rng(3, "shapes");
  const std::vector<Shape> shapes = {box({0, 0, 0}, {1, 2, 0.5}, 0.4, 0.3), cylinder({0, 0, 0}, 0.7, 1.5, 0.5),
                                     sphere({0, 0, 0}, 1.2)};
  for (const auto& s : shapes) {
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const Vec3 o(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6));
      if (s.signedDistance(o) <= 0.05) continue;
      // Aim near the shape's centre so that most rays hit, some graze and some miss.
      const Vec3 d = (Vec3(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)) - o).normalized();
      const auto t = s.raycast(o, d);
      const double ref = marchHit(s, o, d, 20.0);
      ASSERT_EQ(t.has_value(), ref >= 0) << i;
      if (t) {
        EXPECT_NEAR(*t, ref, 1e-3);
        ++hits;
      }
    }
    EXPECT_GT(hits, 100);
  }
}

TEST(Shapes, SignedDistanceIsExactOutsideAndNegativeInside) {
  const Shape b = box({1, 2, 3}, {1, 2, 0.5});
  EXPECT_NEAR(b.signedDistance({4, 2, 3}), 2.0, 1e-12);
  EXPECT_NEAR(b.signedDistance({3, 5, 3}), std::hypot(1.0, 1.0), 1e-12);
  EXPECT_NEAR(b.signedDistance({1, 2, 3}), -0.5, 1e-12);
  const Shape c = cylinder({0, 0, 0}, 1.0, 2.0);
  EXPECT_NEAR(c.signedDistance({0, 0, 3}), 1.0, 1e-12);
  EXPECT_NEAR(c.signedDistance({0, 0, 0}), -1.0, 1e-12);
  // Distance is 1-Lipschitz: |sd(p) − sd(q)| <= |p − q| (checked on random pairs).
  RngStream rng(4, "lipschitz");
  for (const Shape& s : {b, c, cylinder({1, 1, 1}, 0.5, 1.0, 0.7), sphere({0, 1, 0}, 2)})
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5));
      const Vec3 q = p + 0.1 * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      ASSERT_LE(std::abs(s.signedDistance(p) - s.signedDistance(q)), (p - q).norm() + 1e-9);
    }
}

// A random town on a ground plane: `boxes` turned boxes and 30 tilted rods in 80 × 80 m.
std::vector<Shape> randomTown(RngStream& rng, int boxes) {
  std::vector<Shape> shapes;
  Shape ground;
  ground.type = ShapeType::kHalfSpace;
  shapes.push_back(ground);
  for (int i = 0; i < boxes; ++i)
    shapes.push_back(box({rng.uniform(-40, 40), rng.uniform(-40, 40), 2}, {rng.uniform(0.5, 3), rng.uniform(0.5, 3), 2},
                         rng.uniform(0, 3)));
  for (int i = 0; i < 30; ++i)
    shapes.push_back(cylinder({rng.uniform(-40, 40), rng.uniform(-40, 40), 3}, 0.3, 3, rng.uniform(0, 0.4)));
  return shapes;
}

TEST(WorldTruth, IndexedNearestMatchesBruteForce) {
  RngStream rng(8, "truth");
  const std::vector<Shape> shapes = randomTown(rng, 60);
  const WorldTruth truth(shapes);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(0.1, 8));
    double best = 1e9;
    bool inside = false;
    for (const auto& s : shapes) best = std::min(best, s.signedDistance(p)), inside |= s.signedDistance(p) <= 0;
    EXPECT_NEAR(truth.distance(p, 100.0), best, 1e-12);
    EXPECT_EQ(truth.inside(p), inside);
  }
}

TEST(WorldTruth, IndexedRaycastFindsTheSameFirstHit) {
  // The grid walk returns exactly what testing every shape returns (distance and shape), for
  // rays from inside and outside the grid, in every direction, short and long.
  RngStream rng(9, "rays");
  const WorldTruth truth(randomTown(rng, 80));
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 o(rng.uniform(-60, 60), rng.uniform(-60, 60), rng.uniform(0.1, 8));
    Vec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.3, 0.3));
    if (i % 50 == 0) d = Vec3(0, 0, -1);  // straight down
    if (i % 50 == 1) d = Vec3(1, 0, 0);   // along a grid axis
    const double range = i % 3 == 0 ? 10.0 : 100.0;
    const auto a = truth.raycast(o, d, range), b = truth.raycastIndexed(o, d, range);
    ASSERT_EQ(a.has_value(), b.has_value()) << i;
    if (!a) continue;
    ++hits;
    EXPECT_EQ(a->distance_m, b->distance_m) << i;
    EXPECT_EQ(a->shape, b->shape) << i;
  }
  EXPECT_GT(hits, 1000);
}

TEST(WorldTruth, ExplorableColumnsOnAHandBuiltWorld) {
  // Box 10 x 5 m (4 x 2 columns), z in [0, 4]. One column fully blocked by a 2.5 m cube-ish
  // block taller than the box; one half-blocked (still explorable); a low block (explorable).
  std::vector<Shape> shapes;
  Shape ground;
  ground.type = ShapeType::kHalfSpace;
  shapes.push_back(ground);
  shapes.push_back(box({1.25, 1.25, 3}, {1.3, 1.3, 3}));     // covers column (0, 0) fully
  shapes.push_back(box({4.375, 1.25, 3}, {0.625, 1.3, 3}));  // half of column (1, 0)
  shapes.push_back(box({8.75, 3.75, 1}, {1.3, 1.3, 1}));     // low: column (3, 1) free above
  const WorldTruth truth(shapes);
  Aabb b{Vec3(0, 0, 0), Vec3(10, 5, 4)};
  const auto cols = truth.explorableColumns(b);
  EXPECT_EQ(cols.size(), 7u);
  for (const auto& c : cols) EXPECT_FALSE(c.ix == 0 && c.iy == 0);
}

}  // namespace
}  // namespace msb
